#pragma once
/// @file The data of the paper's Figs. 8 and 9: one point mass hitting a fixed ground under
/// Frémond's law, swept over the velocity before the impact.
///
///  - Fig. 8 (normal law alone, paper §5.3): D_NE against |D_NA| for φ_N = k|z|^p/p. For p = 2 the
///    curve is the straight line D_NE = ε|D_NA| of eq. (24), ε = (k − 2m)/(k + 2m) in the library's
///    scaling, while ε ≥ 0; for k < 2m the reaction stops the mass (D_NE = 0). For p > 2 the
///    restitution grows with the speed, for p < 2 it falls.
///  - Fig. 9 (viscous dead zone, paper §5.4, eq. 25): D_TE against D_TA for
///    φ_T = (k_T/q) max(0, |z_T| − r)^q, the normal law fixed. Inside the dead zone |D_TA| ≤ r the
///    tangential percussion is zero and D_TE = D_TA.
///
/// Every point is one call of solve_impact on the point-mass problem (M = m I, W_N = (0, 1),
/// W_T = (1, 0)), so the curves are the library's answers, with their admissibility certificates.
///
/// Parameters may be given in the library's scaling (potentials of the mean velocity z,
/// docs/laws.md) or in the paper's (eqs. 23 and 25 applied to D_E + D_A): k_paper = k·2^(1−p),
/// k_T,paper = k_T·2^(1−q), r_paper = 2r. A curve always records which scaling its parameters were
/// given in.
#include <span>
#include <string_view>
#include <vector>

#include "fremond/admissibility/admissibility_report.hpp"
#include "fremond/core/impact_problem.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/solver_options.hpp"
#include "fremond/solvers/solver_status.hpp"

namespace fremond {

/// Which constants a curve's parameters are written in (docs/laws.md).
enum class Scaling {
  library,  ///< the library's: φ_N = k|z|^p/p, φ_T = (k_T/q) max(0, |z| − r)^q of the mean velocity
            ///< z.
  paper,  ///< the paper's: k_paper = k·2^(1−p), k_T,paper = k_T·2^(1−q), r_paper = 2r.
};
std::string_view to_string(Scaling s);
/// Throws InvalidArgument("scaling", ...) naming the accepted values.
Scaling scaling_from_string(std::string_view s);

/// Fig. 8: a point mass m under Frémond's normal power law alone.
struct NormalCurveParameters {
  double mass = 1.0;  ///< m > 0 (kg).
  /// Stiffness ≥ 0 in `scaling` (units N s^p m^(1−p)). The paper does not give the k of its Fig. 8;
  /// the default 4 (the library's scaling) spreads the curves over a few m/s: for p = 2,
  /// ε = (4 − 2)/(4 + 2) = 1/3 (eq. 24); for p > 2 the mass stops below |D_NA| = (2^(p−1)
  /// m/k)^(1/(p−2)) (1 m/s for p = 3); for p < 2 the restitution falls with the speed.
  double k = 4.0;
  double p = 2.0;  ///< exponent > 1.
  Scaling scaling = Scaling::library;

  /// The same law with k in the library's scaling (k = k_paper·2^(p−1)).
  NormalCurveParameters in_library_scaling() const;
  /// The same law with k in the paper's scaling (k_paper = k·2^(1−p)).
  NormalCurveParameters in_paper_scaling() const;
  /// Throws InvalidArgument naming `mass`, `k` or `p`.
  void validate() const;
};

/// Fig. 9: a point mass m under Frémond's law with the viscous dead zone (eq. 25), the normal law
/// fixed. The defaults are the paper's Fig. 9 (r_paper = 0.4, k_T,paper = 0.75, q = 2) in the
/// library's scaling; the normal law (k_N, p) and D_NA do not change D_TE for a point mass (G is
/// diagonal), they only fix the normal percussion.
struct TangentialCurveParameters {
  double mass = 1.0;   ///< m > 0 (kg).
  double k_N = 4.0;    ///< normal stiffness ≥ 0 in `scaling` (Fig. 8's default law).
  double p = 2.0;      ///< normal exponent > 1.
  double D_NA = -1.0;  ///< normal velocity before the impact, ≤ 0 (m/s): the mass hits the ground.
  double k_T = 1.5;    ///< tangential stiffness ≥ 0 in `scaling` (paper: 0.75).
  double q = 2.0;      ///< tangential exponent > 1.
  double r = 0.2;      ///< dead-zone half-width ≥ 0 in `scaling` (m/s; paper: 0.4).
  Scaling scaling = Scaling::library;

  /// The paper's Fig. 9 (r_paper = 0.4, k_T,paper = 0.75, q = 2; normal law k = 4, p = 2 in the
  /// library's scaling), written in `scaling`.
  static TangentialCurveParameters paper_figure(Scaling scaling);
  TangentialCurveParameters in_library_scaling() const;
  TangentialCurveParameters in_paper_scaling() const;
  /// Throws InvalidArgument naming `mass`, `k_N`, `p`, `D_NA`, `k_T`, `q` or `r`.
  void validate() const;
};

/// One point of a curve: one impact of the point mass.
struct CurvePoint {
  double D_NA = 0.0, D_NE = 0.0;  ///< normal velocity before and after (m/s).
  double D_TA = 0.0, D_TE = 0.0;  ///< tangential velocity before and after (m/s; 0 for Fig. 8).
  double P_N = 0.0;               ///< normal percussion on the mass (N s), reaction included.
  double P_N_reaction = 0.0;      ///< its reaction part −I_reac ≥ 0 (eq. 16).
  double P_T = 0.0;               ///< tangential percussion (N s).
  double energy_change = 0.0;     ///< T_E − T_A (J), ≤ 0 for an admissible impact (eq. 9).
  /// Fig. 9: |D_TA| ≤ r (the library's scaling), so the law gives no tangential percussion and
  /// D_TE = D_TA. Always false for Fig. 8.
  bool in_dead_zone = false;
  bool admissible = false;               ///< the docs/concepts.md certificate holds.
  Inequality failed = Inequality::none;  ///< the first inequality that failed.
  SolverStatus status = SolverStatus::not_run;
};

/// The one-contact problem of a point mass of mass m on fixed ground, normal direction only:
/// q = (y), M = (m), W_N = (1), q̇_A = (D_NA). Throws InvalidArgument naming `mass` unless m > 0
/// and finite, or a velocity that is not finite.
ImpactProblem point_mass_problem(double mass, double D_NA);
/// The same with the tangential direction: q = (x, y), M = m I, W_N = (0, 1), W_T = (1, 0),
/// q̇_A = (D_TA, D_NA).
ImpactProblem point_mass_problem(double mass, double D_NA, double D_TA);

/// Frémond's normal law of Fig. 8, φ_N = k|z|^p/p with k in the library's scaling.
ImpactLaw normal_curve_law(const NormalCurveParameters& parameters);
/// Frémond's law of Fig. 9: φ_N = k_N|z|^p/p and φ_T = (k_T/q) max(0, |z| − r)^q, the library's
/// scaling.
ImpactLaw tangential_curve_law(const TangentialCurveParameters& parameters);

/// Fig. 8: one impact per approach speed |D_NA| ≥ 0 (D_NA = −speed). Throws InvalidArgument naming
/// the parameter, or `speeds[i]` for a negative or non-finite speed.
std::vector<CurvePoint> normal_restitution_curve(const NormalCurveParameters& parameters,
                                                 std::span<const double> speeds,
                                                 const SolverOptions& options = {});

/// Fig. 9: one impact per tangential velocity D_TA. Throws InvalidArgument naming the parameter, or
/// `D_TA[i]` for a non-finite value.
std::vector<CurvePoint> tangential_curve(const TangentialCurveParameters& parameters,
                                         std::span<const double> D_TA,
                                         const SolverOptions& options = {});

/// Eq. (24): for p = 2 Frémond's normal law on a point mass is Newton's law with
/// ε = (k − 2m)/(k + 2m) (the library's scaling; the paper's (k_paper − m)/(k_paper + m)), where ε
/// ≥ 0. Returns ε, negative when k < 2m (then the reaction stops the mass and D_NE = 0). Throws
/// InvalidArgument("p", ...) unless p = 2.
double equivalent_restitution(const NormalCurveParameters& parameters);

}  // namespace fremond
