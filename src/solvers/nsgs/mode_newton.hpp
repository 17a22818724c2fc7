#pragma once
/// @file Semismooth Newton on the contacts' modes (docs/sparse.md#mode-newton): the polish after
/// the sweeps, whose number of steps does not grow with the pile.
#include <Eigen/Core>

#include "solvers/nsgs/contact_rows.hpp"

namespace fremond::detail {

/// What one run of mode_newton did.
struct ModeNewtonOutcome {
  int steps = 0;          ///< Newton steps (one factorisation each)
  bool improved = false;  ///< P moved to a point of smaller residual
  bool converged = false;
};

/// From P and its measure m: each step reads every contact's mode from the natural map at P
/// (apart: P = 0; stick: D_E = 0; slide either way: D_NE = 0, P_T = ∓μ P_N), solves that mode's
/// equations for P, and measures the law there. A singular G (more contact rows than degrees of
/// freedom) makes those equations singular but consistent; they are solved with a small
/// proximal term and refined, which converges to a solution of the unregularised equations.
/// Stops when m meets `target` (its residual or its excess over rounding), when the modes come
/// back unchanged, after three steps without a better point, or after `max_steps`. P and m hold
/// the best point met.
ModeNewtonOutcome mode_newton(const Layout& L, const Eigen::VectorXd& D_A, Eigen::VectorXd& P,
                              Measure& m, double target, int max_steps);

}  // namespace fremond::detail
