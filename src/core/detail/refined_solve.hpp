#pragma once
/// @file X = M⁻¹B by Cholesky with iterative refinement, the residual B − MX summed in twice the
/// working precision (accurate_dot.hpp; Higham, "Accuracy and Stability of Numerical Algorithms",
/// §12.1: mixed-precision refinement).
///
/// What it is for: the factor of an ill-conditioned M is exact only for a nearby M + ΔM,
/// |ΔM| ≈ ε|M|, so M⁻¹W, G = WᵀM⁻¹W and every velocity after an impact are off by about
/// cond(M)·ε relative. With cond(M) = 3e10 a classical law's answer, exact for that nearby G, left
/// the law's complementarities 1e-6 of the velocities away in exact arithmetic, while the residual
/// recomputed through the same factor reported 1e-14. Each refinement step multiplies the error by
/// about cond(M)·ε, and the residual in twice the precision lets it reach the working precision.
///
/// A diagonal M needs none: its factor's solves are divisions, exact to an ulp per entry (the
/// preset bodies, point masses), and that fast path costs a test of n² entries. Nor does a
/// well-conditioned one: where the factor bounds cond(M) by kPlainSolveCondition, the plain solve
/// is already within about cond(M)·ε ≤ 6e-14 (relative) of M⁻¹B, and refinement would change its
/// last bits at the price of n² twice-precise products per column and step.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/detail/accurate_dot.hpp"
#include "core/detail/cholesky.hpp"

namespace fremond::detail {

/// The largest bound of cond(M) (CholeskyT::condition_bound) at which M⁻¹B is not refined.
inline constexpr double kPlainSolveCondition = 256.0;

template <class Mat>
bool is_diagonal(const Mat& M) {
  for (Eigen::Index j = 0; j < M.cols(); ++j)
    for (Eigen::Index i = 0; i < M.rows(); ++i)
      if (i != j && M(i, j) != 0.0) return false;
  return true;
}

/// Refines X ≈ M⁻¹B in place (`llt` is M's factor, X its plain solve). Stops when a correction is
/// within 4ε of X, or stops shrinking (by half), or after `max_steps`; a step that would leave a
/// non-finite X is not taken. Returns whether X changed by more than rounding, i.e. whether the
/// plain solve was off by more than a few ulps; false, X untouched, where the factor bounds cond(M)
/// by kPlainSolveCondition.
template <int MaxN, class MatM, class MatB, class MatX>
bool refine_solve(const MatM& M, const CholeskyT<MaxN>& llt, const MatB& B, MatX& X,
                  int max_steps = 6) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const Eigen::Index n = M.rows(), k = B.cols();
  if (n == 0 || k == 0 || llt.condition_bound() <= kPlainSolveCondition) return false;
  MatX D = X;  // same storage as X: fixed capacity for the stack-stored sizes
  double previous = std::numeric_limits<double>::infinity();
  bool changed = false;
  for (int step = 0; step < max_steps; ++step) {
    accurate_residual(M, X, B, D);  // B − M X, in twice the precision
    llt.solve_lower_in_place(D);
    llt.solve_upper_in_place(D);
    const double size = X.cwiseAbs().maxCoeff(), correction = D.cwiseAbs().maxCoeff();
    if (!std::isfinite(correction) || !(correction < 0.5 * previous)) break;
    X += D;
    if (correction <= 4 * eps * size) break;
    changed = true;
    previous = correction;
  }
  return changed;
}

}  // namespace fremond::detail
