#pragma once
/// @file Semismooth Newton on the contacts' modes (docs/sparse.md#mode-newton): the finish after
/// the sweeps, a few factorisations where the modes read are right.
#include <Eigen/Core>
#include <memory>

#include "solvers/nsgs/contact_rows.hpp"

namespace fremond::detail {

/// What one run of mode_newton did.
struct ModeNewtonOutcome {
  int steps = 0;  ///< Newton steps (one factorisation each)
  bool converged = false;
};

/// The storage of mode_newton's runs (the modes' systems, their factors, the trial points), sized
/// by a run and reused by the next of the same size: the sweeps keep one for all their runs, and
/// a caller that solves again (the prepared solver) keeps it from one solve to the next. A copy
/// starts empty: it is room, not state.
struct ModeNewtonWorkspace {
  struct Work;  // mode_newton.cpp
  std::unique_ptr<Work> work;

  ModeNewtonWorkspace();
  ~ModeNewtonWorkspace();
  ModeNewtonWorkspace(const ModeNewtonWorkspace&);
  ModeNewtonWorkspace& operator=(const ModeNewtonWorkspace&);
  ModeNewtonWorkspace(ModeNewtonWorkspace&&) noexcept;
  ModeNewtonWorkspace& operator=(ModeNewtonWorkspace&&) noexcept;
};

/// From P and its measure m: each step reads every contact's mode from the natural map at P
/// (apart: P = 0; stick: D_E = 0; slide either way: D_NE = 0, P_T = ∓μ P_N), solves that mode's
/// equations for P, backtracks on ½ Σ R², and measures the law there. A singular G (more contact
/// rows than degrees of freedom) makes those equations singular; they are solved with a proximal
/// term δ (refined), which picks the solution nearest P, δ growing as Levenberg–Marquardt's where
/// a step is refused. Stops when m meets `target` (its residual or its excess over rounding),
/// after two steps that do not halve the residual, four refused steps, or `max_steps`. P and m
/// hold the best point met.
ModeNewtonOutcome mode_newton(const Layout& L, const Eigen::VectorXd& D_A, Eigen::VectorXd& P,
                              Measure& m, double target, int max_steps, ModeNewtonWorkspace& ws);

}  // namespace fremond::detail
