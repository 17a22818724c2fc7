#pragma once
/// @file The thermodynamic admissibility certificate of one impact (docs/concepts.md; paper eqs. 9,
/// 15-19).
#include <string_view>

#include "fremond/core/types.hpp"

namespace fremond {

/// The first inequality found violated, in the order they are checked.
enum class Inequality {
  none,                ///< every check holds.
  total_15,            ///< (15) in sum: −P·z ≥ 0, i.e. T_E ≤ T_A (eq. 9).
  per_contact_15,      ///< (15) for one contact: −P_i·z_i ≥ 0.
  reaction_17,         ///< (17): I_reac·z ≥ 0.
  dissipation_19,      ///< (19): I_d·z ≥ 0.
  complementarity_16,  ///< (16): I_reac ≤ 0, D_NE ≥ 0, I_reac·D_NE = 0.
  fenchel_young,       ///< the Fenchel–Young gap of a potential is not zero: the answer is not
                       ///< a solution of the law (−P_d ∉ ∂φ(z)).
  non_penetration,     ///< D_NE < 0 for a contact that takes part.
};
std::string_view to_string(Inequality i);
Inequality inequality_from_string(std::string_view s);

template <int MaxContacts>
struct AdmissibilityReportT {
  using CVec = VecT<MaxContacts>;
  double kinetic_energy_A = 0.0;  ///< T_A = ½ q̇_Aᵀ M q̇_A.
  double energy_change = 0.0;     ///< T_E − T_A, computed from the velocities.
  double total = 0.0;             ///< (15) −P·z over the contacts (= −(T_E − T_A), eq. 9).
  CVec per_contact;               ///< (15) −(P_N,i z_N,i + P_T,i z_T,i) per contact.
  double reaction = 0.0;          ///< (17) I_reac·z = −P_reac·z_N (Frémond; 0 for other laws).
  double dissipation = 0.0;       ///< (19) I_d·z = −P_d·z (Frémond; equals `total` otherwise).
  double complementarity = 0.0;   ///< (16) max violation of the reaction's complementarity, scaled.
  double penetration = 0.0;       ///< max(0, −D_NE,i), scaled by the velocity scale.
  double fenchel_young_gap = 0.0;  ///< max scaled FY gap over potentials with a known conjugate.
  double tolerance = 0.0;  ///< absolute energy tolerance used: admissibility_tolerance·T_A, or the
                           ///< rounding of the energies P·z when that is larger.
  bool admissible = false;               ///< no inequality violated beyond the tolerance.
  Inequality failed = Inequality::none;  ///< the first violated inequality.
  int failed_contact = -1;               ///< the contact of a per-contact failure, else −1.
  double violation = 0.0;  ///< by how much it fails (energy units, or scaled for gaps).
};

}  // namespace fremond
