#pragma once
/// @file The contact impulse of one time step against smooth forces: the persistent-contact part
/// of the Moreau–Jean step, and the closing step of an accumulation of impacts.
///
/// Over a step the contacts that stay closed carry the impulse that keeps them closed: Signorini's
/// condition V_N ≥ 0 ⊥ P_N ≥ 0 (the reaction of docs/laws.md) and Coulomb's law with bound μP_N on
/// a tangential velocity V_T, where each of V_N, V_T is either
///  - the velocity at the end of the step, D_E (a plastic contact; sticking stops the slip), or
///  - the mean z = (D_before + D_E)/2 (Frémond's variable, docs/concepts.md).
/// The velocities obey M (v⁺ − v_free) = W_N P_N + W_T P_T with v_free = v_before + h M⁻¹ f, and
/// with midpoint positions the step changes the energy by exactly P·z, z = W(v_before + v⁺)/2
/// (paper eq. 9 with the work of gravity). Hence:
///  - on the mean, P_N z_N = 0 and P_T z_T ≤ 0: the step never creates energy, and no contact
///    moves into its obstacle at first order (z_N ≥ 0);
///  - on the end velocities with no gravity (h = 0), P·z = P·D_E − ½PᵀGP ≤ 0;
///  - Coulomb on D_TE with gravity may give P_T z_T > 0 for a slip slower than about h g/2 that the
///    normal–tangential coupling reverses; step_energy() tells.
///
/// The solve enumerates contact modes (open, stick, slide ±) — exact, allocation-free, and fast for
/// the few contacts of a planar body — trying the previous step's mode first.
#include <Eigen/Core>
#include <array>
#include <string_view>

#include "fremond/core/types.hpp"

namespace fremond {

/// A contact mode of the persistent-contact step.
enum class ContactMode {
  open,           ///< P = 0, V_N ≥ 0.
  stick,          ///< V_N = 0, V_T = 0, |P_T| ≤ μP_N.
  slide_forward,  ///< V_N = 0, V_T ≥ 0, P_T = −μP_N.
  slide_back,     ///< V_N = 0, V_T ≤ 0, P_T = +μP_N.
};
std::string_view to_string(ContactMode m);
ContactMode contact_mode_from_string(std::string_view s);

/// The velocity a contact condition acts on.
enum class StepVelocity {
  end,   ///< D_E, the velocity after the step.
  mean,  ///< z = (D_before + D_E)/2.
};
std::string_view to_string(StepVelocity v);
StepVelocity step_velocity_from_string(std::string_view s);

/// The data of one persistent-contact solve (M = diag(m, m, J) of a planar body).
struct PersistentContactProblem {
  static constexpr int kMax = kSmallContacts;
  Eigen::Vector3d minv = Eigen::Vector3d::Ones();  ///< diagonal of M⁻¹.
  int contacts = 0;                                ///< ≤ kMax.
  std::array<Eigen::Vector3d, kMax> W_N{}, W_T{};
  std::array<double, kMax> mu{};                       ///< μ ≥ 0 per contact (0: frictionless).
  Eigen::Vector3d v_before = Eigen::Vector3d::Zero();  ///< velocity at the start of the step.
  Eigen::Vector3d v_free = Eigen::Vector3d::Zero();    ///< v_before + h M⁻¹ f.
  StepVelocity normal = StepVelocity::end;             ///< V_N of Signorini's condition.
  StepVelocity friction = StepVelocity::end;           ///< V_T of Coulomb's law.
};

struct PersistentContactResult {
  bool solved = false;                          ///< a mode satisfying every condition was found.
  Eigen::Vector3d v = Eigen::Vector3d::Zero();  ///< v⁺.
  std::array<double, PersistentContactProblem::kMax> P_N{}, P_T{};
  std::array<ContactMode, PersistentContactProblem::kMax> mode{};
  int modes_tried = 0;
};

/// P·z = Σ P_N,i z_N,i + P_T,i z_T,i with z = W(v_before + v⁺)/2: the change of energy of the step
/// with midpoint positions (J). `rounding`, when not null, receives a bound of the rounding of
/// that sum (a sticking contact gives zero up to it).
double step_energy(const PersistentContactProblem& problem, const PersistentContactResult& result,
                   double* rounding = nullptr);

/// Solves the step. `warm` (may be null) is the mode of each contact to try first. When no mode
/// passes the checks (a Painlevé-type case, docs/laws.md), `solved` is false and v = v_free.
PersistentContactResult solve_persistent_contact(const PersistentContactProblem& problem,
                                                 const ContactMode* warm = nullptr);

/// The persistent-contact step over a step with gravity, as Moreau–Jean takes it: Signorini on the
/// mean normal velocity, so that no contact sinks through the midpoint rule and P_N z_N = 0;
/// Coulomb on the end velocity (sticking stops the slip), or, in a step where that would create
/// energy (step_energy above its rounding), on the mean. Never creates energy. Sets
/// problem.normal and problem.friction to the velocities of the answer's solve. The same answer,
/// bit for bit, as the two solve_persistent_contact calls it stands for; it only forms once what
/// they share.
PersistentContactResult solve_dissipative_step(PersistentContactProblem& problem,
                                               const ContactMode* warm = nullptr);

}  // namespace fremond
