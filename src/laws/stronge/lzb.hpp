#pragma once
/// @file Stronge's energetic restitution with Coulomb friction on several simultaneous contacts:
/// Darboux-Keller integration in impulse space, the percussion shared among the contacts by the
/// distributing law of Liu, Zhao and Brogliato (docs/stronge.md, "Several contacts").
///
/// Each contact is a compliant element of force F = K δ^η that stores the potential energy
/// E = K δ^(η+1)/(η+1): dE = −D_N dP_N while it is compressed, dE = −D_N dP_N / e*² while it
/// expands (restitution gives back e*² of the work of compression). The contact with the largest
/// energy (the primary) drives the integration in its own percussion; the others follow at
/// dP_i/dP_p = F_i/F_p, each F = K^(1/(η+1)) ((η+1)E)^(η/(η+1)). The answer does not depend on a
/// common scale of the stiffnesses: only their ratios and the exponents matter.
#include <Eigen/Core>
#include <span>

namespace fremond::detail {

/// One contact's data for the distributing law.
struct LzbContact {
  double e = 0.0;          ///< Stronge's energetic coefficient e* ∈ [0, 1]
  double mu = 0.0;         ///< Coulomb's coefficient ≥ 0, read where G has tangential rows
  double eta = 1.0;        ///< compliance exponent η > 0 (1: linear spring, 3/2: Hertz)
  double stiffness = 1.0;  ///< relative stiffness K > 0
};

struct LzbOptions {
  /// Relative tolerance of the integration (Dormand-Prince 5(4) on the problem scaled to unit
  /// velocities and percussions), and of the events' location. At least 1e-14.
  double tolerance = 1e-12;
  /// Accepted integration steps before the run gives up (not converged). A chain of three balls
  /// takes a few hundred; contacts that stick and keep compressing (more rows than the bodies can
  /// answer) may never end.
  int max_steps = 50000;
};

/// The end of the impact. Rows as G's: n contacts' normal rows, then their tangential rows.
struct LzbAnswer {
  Eigen::VectorXd P_N, P_T;  ///< percussions (P_T zero without tangential rows)
  Eigen::VectorXd D_E;       ///< contact velocities after, every row: D_A + G P
  /// Per contact: ∫ D_N dP_N over its compression phases (≤ 0), the normal work lost
  /// (1 − e*²)·|compression work| (≥ 0) and the friction work lost −∫ D_T dP_T (≥ 0).
  Eigen::VectorXd work_compression, dissipated_normal, dissipated_tangential;
  /// T_E − T_A as the percussions' work: −Σ (dissipated_normal + dissipated_tangential).
  double energy_change = 0.0;
  /// Relative error of the run, in units of the largest |D_A|: the integration's tolerance, or
  /// the drift of two invariants if larger (each contact's energy at its end against the works
  /// integrated beside it; the percussions' work against D_Aᵀ P + ½ PᵀGP).
  double error_estimate = 0.0;
  int steps = 0;           ///< accepted integration steps
  int events = 0;          ///< phase changes located (compression end, stick, slip, separation)
  bool converged = false;  ///< every contact ended: compressed, then its energy back to 0
  const char* message = "not run";  ///< why it failed, or how it ended
};

/// Integrates the impact from the Delassus matrix G of the contacts' rows (n normal rows, then n
/// tangential rows when friction is on: G is n×n or 2n×2n) and the velocities before, D_A. One
/// LzbContact per contact (size n). No input check beyond the sizes: the caller's (StrongeLaw::
/// validate, the contact space). Never throws on numerical trouble: converged is then false.
LzbAnswer lzb_impact(const Eigen::Ref<const Eigen::MatrixXd>& G,
                     const Eigen::Ref<const Eigen::VectorXd>& D_A,
                     std::span<const LzbContact> contacts, const LzbOptions& options = {});

}  // namespace fremond::detail
