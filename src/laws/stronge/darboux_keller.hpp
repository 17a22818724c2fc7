#pragma once
/// @file Stronge's energetic restitution with Coulomb friction for one planar contact, solved
/// exactly by Darboux-Keller integration in the normal impulse p_N (docs/stronge.md). Every phase
/// (slip, stick, slip in the reversed direction) is linear in p_N, so its ends are closed form.
#include <Eigen/Core>
#include <limits>
#include <string_view>

namespace fremond::detail {

/// How the tangential velocity D_T evolves during the impact (docs/stronge.md, "Regimes").
enum class StrongeRegime {
  no_impact,      ///< D_NA ≥ 0: the contact does not approach; no percussion.
  slide,          ///< slides in one direction throughout (also: starts at D_T = 0 and slides).
  slip_stick,     ///< slips until D_T = 0, then sticks (|G_NT| ≤ μ G_TT) to the end.
  slip_reversal,  ///< slips until D_T = 0, then slides the other way (|G_NT| > μ G_TT).
  stick,          ///< D_TA = 0 and |G_NT| ≤ μ G_TT: sticks throughout.
};
std::string_view to_string(StrongeRegime r);

/// The end of the impact. P_N, P_T act on the body: M(q̇_E − q̇_A) = w_N P_N + w_T P_T.
struct StrongeAnswer {
  Eigen::VectorXd qdot_E;  ///< velocity after the impact
  double P_N = 0.0;        ///< total normal percussion (the final p_N), ≥ 0
  double P_T = 0.0;        ///< total tangential percussion, |P_T| ≤ μ P_N
  double D_NA = 0.0;       ///< w_N·q̇_A
  double D_TA = 0.0;       ///< w_T·q̇_A
  double D_NE = 0.0;       ///< normal contact velocity after, ≥ 0 (from the phase formulas)
  double D_TE = 0.0;       ///< tangential contact velocity after (exactly 0 when it ends stuck)
  double p_N_compression = 0.0;  ///< p_N where D_N = 0: end of compression
  /// p_N where the contact sticks or reverses its slip (slip_stick, slip_reversal); NaN otherwise.
  double p_N_transition = std::numeric_limits<double>::quiet_NaN();
  StrongeRegime regime = StrongeRegime::no_impact;
  double work_compression = 0.0;       ///< W_N(p_Nc) = ∫ D_N dp_N over compression, ≤ 0
  double dissipated_normal = 0.0;      ///< −W_N(P_N) = (1 − e²)|W_N(p_Nc)|, ≥ 0
  double dissipated_tangential = 0.0;  ///< −∫ D_T dp_T = μ ∫ |D_T| dp_N over slip, ≥ 0
  /// T_E − T_A (T = ½ q̇ᵀMq̇) as the work of the percussions: −(dissipated_normal +
  /// dissipated_tangential), free of the cancellation of subtracting two kinetic energies.
  double energy_change = 0.0;
};

/// Stronge's law (energetic coefficient e ∈ [0, 1], Coulomb's μ ≥ 0) for one contact with normal
/// direction w_N and tangent w_T in generalised coordinates: D_N = w_N·q̇, D_T = w_T·q̇ (no obstacle
/// velocity terms). Throws InvalidArgument naming "M", "w_N", "w_T", "qdot_A", "e" or "mu" on
/// bad input: shapes, non-finite values, M not symmetric positive definite, w_N with
/// w_N·M⁻¹w_N = 0, w_T zero or parallel to w_N in the metric M⁻¹ (singular Delassus matrix).
StrongeAnswer stronge_one_contact(const Eigen::MatrixXd& M, const Eigen::VectorXd& w_N,
                                  const Eigen::VectorXd& w_T, const Eigen::VectorXd& qdot_A,
                                  double e, double mu);

/// The same law in contact space, from the contact's Delassus matrix G = [[G_NN, G_NT], [G_NT,
/// G_TT]] (G_NN > 0, det G > 1e-12 G_NN G_TT) and its velocities before the impact; qdot_E is left
/// empty. No input check: stronge_one_contact's, or the caller's.
StrongeAnswer stronge_contact(double G_NN, double G_NT, double G_TT, double D_NA, double D_TA,
                              double e, double mu);

}  // namespace fremond::detail
