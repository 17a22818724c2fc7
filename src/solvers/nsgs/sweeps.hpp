#pragma once
/// @file Nonsmooth Gauss–Seidel with the mode Newton after it (docs/sparse.md): Newton's law, with
/// or without Coulomb friction, on contact rows, for the sparse path and for the classical chain's
/// large contact sets alike.
#include <Eigen/Core>
#include <string_view>

#include "fremond/solvers/impact_result.hpp"
#include "solvers/nsgs/anderson.hpp"
#include "solvers/nsgs/contact_rows.hpp"
#include "solvers/nsgs/mode_newton.hpp"

namespace fremond::detail {

struct SweepOptions {
  double tolerance = 1e-10;  ///< relative to the layout's v_scale
  int max_sweeps = 100000;
  bool newton_polish = true;  ///< the mode Newton from the second residual measure on
  bool acceleration = true;   ///< Anderson mixing of the sweeps on more than 64 contacts
};

/// How the sweeps ended, and the law's residual at the percussions they leave.
struct SweepOutcome {
  SolverStatus status = SolverStatus::max_iterations;
  StopCriterion criterion = StopCriterion::iterations;
  std::string_view message;
  SolverMethod method = SolverMethod::nsgs;  ///< semismooth_newton where its run converged
  int iterations = 0;                        ///< sweeps and Newton steps
};

/// The storage of solve_by_sweeps and of its Newton runs, reused by the next solve of the same size
/// (a caller that solves again keeps it: no allocation then). `measure` holds the law's residual
/// at the percussions the last solve left.
struct SweepWorkspace {
  Measure measure, trial_measure;
  Eigen::VectorXd velocities;  // the sweeps' room for the body's velocities
  Eigen::VectorXd trial;       // a Newton run's start
  ModeNewtonWorkspace newton;
  AndersonMixing mixing;
  Eigen::VectorXd start, input;  // the sweeps' start; the input of the pair of sweeps under way
};

/// Sweeps from P (in place) until the residual meets the tolerance, stalls (8,192 sweeps without a
/// 1 % gain) or the budget ends; the mode Newton tries to finish at the 2nd, 4th, 8th, ...
/// measure. With `acceleration`, on more than 64 contacts, each forward and backward pair of sweeps
/// starts from the Anderson mix of the pairs before; where 128 sweeps so do not halve the residual,
/// the sweeps start again from P's first value without it. Each stretch of sweeps and each Newton
/// run is recorded in `log`, the first stretch as starting from `first`. The residual at the P left
/// is in ws.measure.
SweepOutcome solve_by_sweeps(const Layout& L, const Eigen::VectorXd& D_A, Eigen::VectorXd& P,
                             const SweepOptions& options, AttemptStart first, SolverReport& log,
                             SweepWorkspace& ws);

}  // namespace fremond::detail
