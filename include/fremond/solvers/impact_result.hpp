#pragma once
/// @file The result of one impact: velocities, percussions, the admissibility certificate, and how
/// the solver got there.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>

#include "fremond/admissibility/admissibility_report.hpp"
#include "fremond/solvers/solver_status.hpp"

namespace fremond {

/// Where a method of the chain started from (docs/solvers.md).
enum class AttemptStart : std::uint8_t {
  none,                 ///< an exact method: no starting point.
  decoupled_guess,      ///< each row's percussion as if its contact were alone.
  zero,                 ///< no percussion.
  newton_end,           ///< where semismooth Newton stopped.
  splitting_end,        ///< where the proximal splitting stopped.
  nlopt_end,            ///< where NLopt stopped.
  velocity_newton_end,  ///< where Newton in velocity space stopped.
  normal_rows,          ///< the normal rows' own answer, solved alone (G_NT = 0).
  sweeps_end,           ///< where nonsmooth Gauss–Seidel's sweeps stood (sparse.md).
};
std::string_view to_string(AttemptStart s);
AttemptStart attempt_start_from_string(std::string_view s);

/// One method the chain ran, in the order run: what it ran, from where, and how it ended (its own
/// status and scaled residual, before any later stage). Eight bytes, no allocation: the residual
/// is a log's figure, kept in single precision.
struct Attempt {
  SolverMethod method = SolverMethod::automatic;
  AttemptStart start = AttemptStart::none;
  SolverStatus status = SolverStatus::not_run;
  float residual = 0.0f;
};

/// How the solver ended, separate from the answer.
struct SolverReport {
  static constexpr int kMaxAttempts = 16;

  SolverMethod method = SolverMethod::automatic;  ///< the method that produced the answer.
  SolverStatus status = SolverStatus::not_run;
  StopCriterion criterion = StopCriterion::none;
  std::string_view message = "not run";  ///< a static explanation (no allocation).
  int iterations = 0;  ///< summed over independent groups of contacts (solve_impact.hpp).
  double residual = std::numeric_limits<double>::quiet_NaN();  ///< the law's scaled residual.
  int native_code = 0;  ///< the fallback's own return code (NLopt's nlopt_result), else 0.
  int fallbacks = 0;    ///< how many methods were tried before this one.
  /// Frémond's chain: every method it ran, the first kMaxAttempts of them, in order; the answer's
  /// is the last that converged, or the one the chain kept. attempt_count counts them all.
  std::array<Attempt, kMaxAttempts> attempts{};
  int attempt_count = 0;

  /// Appends an attempt (counted always, kept while there is room).
  void record(SolverMethod m, AttemptStart from, SolverStatus s, double scaled_residual) {
    if (attempt_count < kMaxAttempts) {
      // Beyond float's range a residual is infinite (a conversion out of range is undefined).
      const float r = !(std::fabs(scaled_residual) <= std::numeric_limits<float>::max())
                          ? (std::isnan(scaled_residual) ? std::numeric_limits<float>::quiet_NaN()
                                                         : std::numeric_limits<float>::infinity())
                          : static_cast<float>(scaled_residual);
      attempts[static_cast<std::size_t>(attempt_count)] = {m, from, s, r};
    }
    ++attempt_count;
  }
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
