#pragma once
/// @file The result of one impact: velocities, percussions, the admissibility certificate, and how
/// the solver got there.
#include <limits>
#include <string_view>

#include "fremond/admissibility/admissibility_report.hpp"
#include "fremond/solvers/solver_status.hpp"

namespace fremond {

/// How the solver ended, separate from the answer.
struct SolverReport {
  SolverMethod method = SolverMethod::automatic;  ///< the method that produced the answer.
  SolverStatus status = SolverStatus::not_run;
  StopCriterion criterion = StopCriterion::none;
  std::string_view message = "not run";  ///< a static explanation (no allocation).
  int iterations = 0;  ///< summed over independent groups of contacts (solve_impact.hpp).
  double residual = std::numeric_limits<double>::quiet_NaN();  ///< the law's scaled residual.
  int native_code = 0;  ///< the fallback's own return code (NLopt's nlopt_result), else 0.
  int fallbacks = 0;    ///< how many methods were tried before this one.
};

template <int MaxDofs, int MaxContacts>
struct ImpactResultT {
  using Vec = VecT<MaxDofs>;
  using CVec = VecT<MaxContacts>;
  Vec qdot_E;                   ///< velocity after the impact.
  CVec P_N, P_T;                ///< percussions on the body (P_N ≥ 0 pushes apart).
  CVec D_NA, D_TA, D_NE, D_TE;  ///< contact velocities before and after.
  CVec P_N_reaction;            ///< Frémond: the reaction part of P_N (−I_reac ≥ 0); else 0.
  /// Poisson's phases (has_phases): compression percussions and the velocities at its end, of
  /// the body (qdot_C) and of the contacts.
  bool has_phases = false;
  CVec P_NC, P_TC, D_NC, D_TC;
  Vec qdot_C;
  Eigen::Matrix<int, Eigen::Dynamic, 1, Eigen::ColMajor, MaxContacts, 1>
      takes_part;              ///< 1 if D_NA ≤ 0
  double energy_change = 0.0;  ///< T_E − T_A.
  /// False when the law has several solutions for these data (this is one of them).
  bool unique = true;
  /// Number of distinct solutions found when uniqueness was checked (0: not checked).
  int solutions_found = 0;
  AdmissibilityReportT<MaxContacts> admissibility;
  SolverReport solver;

  /// True when the answer is usable: the solver converged (or was exact).
  bool ok() const { return solver.status == SolverStatus::converged; }
};

using ImpactResult = ImpactResultT<Dynamic, Dynamic>;
using SmallImpactResult = ImpactResultT<kSmallDofs, kSmallContacts>;

/// Copies a stack-stored result into the heap-stored form: every member, the same values.
ImpactResult to_dynamic(const SmallImpactResult& result);
/// The same for the certificate alone.
AdmissibilityReportT<Dynamic> to_dynamic(const AdmissibilityReportT<kSmallContacts>& report);
/// True when every vector of the result fits the small form (kSmallDofs, kSmallContacts).
bool fits_small(const ImpactResult& result);
/// Copies a result into the stack-stored form; throws InvalidArgument if it does not fit.
SmallImpactResult to_small(const ImpactResult& result);

}  // namespace fremond
