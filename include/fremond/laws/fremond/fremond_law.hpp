#pragma once
/// @file Frémond's laws: pseudo-potentials of the mean velocity (paper §5, docs/laws.md).
#include <array>
#include <span>
#include <string>
#include <string_view>

#include "fremond/laws/per_contact.hpp"

namespace fremond {

/// Frémond's tangential law.
enum class TangentialLaw {
  none,       ///< no tangential percussion.
  potential,  ///< −P_T ∈ ∂φ_T(z_T), e.g. the viscous dead zone (eq. 25).
  coulomb,    ///< Coulomb on (P_T, z_T) with bound μ|P_N| (quasi-variational, docs/laws.md).
};
std::string_view to_string(TangentialLaw t);
TangentialLaw tangential_law_from_string(std::string_view s);

/// −P ∈ ∂φ(z) + reaction, z = (D_A + D_E)/2 the mean velocity (paper eq. 23): dissipative by
/// construction for pseudo-potentials (convex, non-negative, zero at 0).
struct FremondLaw {
  PerContactPotential normal;  ///< φ_N (the reaction is added by the law).
  TangentialLaw tangential = TangentialLaw::none;
  PerContactPotential tangential_potential;  ///< φ_T, read with TangentialLaw::potential.
  PerContact mu{0.0};  ///< friction coefficient, read with TangentialLaw::coulomb.

  static constexpr std::array<std::string_view, 1> names{"fremond"};
  std::string_view name() const { return names[0]; }

  bool has_phases() const { return false; }
  /// Tangential rows: any tangential law.
  bool has_friction() const { return tangential != TangentialLaw::none; }
  bool uses_coulomb() const { return tangential == TangentialLaw::coulomb; }
  bool has_tangential_potential() const { return tangential == TangentialLaw::potential; }
  /// Dissipative by construction: an answer its certificate refuses is not resolved.
  /// No tangential percussion on a lasting slide of contact k at D_T (its mean velocity is D_T):
  /// 0 ∈ ∂φ_T(D_T) for a tangential potential, μ = 0 for Coulomb's, always without friction.
  bool leaves_slide_free(int k, double D_T) const;
  static constexpr bool dissipative = true;

  /// Throws InvalidArgument naming `law.normal`, `law.tangential` or `law.mu`: potentials present,
  /// μ ≥ 0 and finite, one value or one per contact.
  void validate(int contacts) const;
  /// True when validate(contacts) would not throw (no message is built).
  bool quick_valid(int contacts) const;
  /// The longest of the per-contact lists (1 where every value is shared).
  std::size_t longest_list() const;
  /// E.g. "fremond(normal=power(k=85.36, p=3), tangential=coulomb(mu=1))".
  std::string describe() const;
  /// The law of the contacts idx[0..n).
  FremondLaw restricted(const int* idx, int n) const;
  /// The law as every contact obeys it (docs/laws.md), D_N their velocities before the impact:
  /// the separating contacts without potentials (the reaction alone).
  FremondLaw of_every_contact(std::span<const double> D_N) const;
};

}  // namespace fremond
