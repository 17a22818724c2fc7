#pragma once
/// @file The natural maps of one contact's rows under the classical laws (docs/solvers.md):
/// the complementarity of the normal row and Coulomb's law on the tangential one, in velocity
/// units. The law's residual (residual.cpp) and the one-contact stage of its chain read the same
/// functions, so that they agree to the last bit.
#include <algorithm>
#include <cmath>

namespace fremond::detail {

/// g·x with 0 exactly where x is: g = W_iᵀM⁻¹W_i overflows for |W| near 1e308, and 0·∞ would
/// make an exact zero a NaN residual.
inline double scaled(double g, double x) {
  return x == 0.0 ? 0.0 : g * x;
}

/// min(w, g·x): zero exactly when 0 ≤ x ⊥ w ≥ 0 (g converts a percussion to a velocity).
inline double complementarity(double w, double x, double g) {
  return std::min(w, scaled(g, x));
}

/// Coulomb's natural map on (t, v) with bound b: g·(t − clamp(t − v/g, −b, b)); zero exactly when
/// |t| ≤ b, v = 0 where |t| < b, t = −b sign(v) where v ≠ 0. A negative bound is clipped (the
/// normal residual reports the negative percussion).
inline double coulomb(double t, double v, double b, double g) {
  b = std::max(0.0, b);
  return scaled(g, t - std::clamp(t - v / g, -b, b));
}

/// The share of the tolerance that the residual at an answer's own velocities, and those
/// velocities' rounding, may each take for the law's residual from the data to stay within it
/// (both maps are 1-Lipschitz in the velocities): residual_at_own_velocities.
inline constexpr double kOwnVelocityShare = 0.45;

}  // namespace fremond::detail
