#pragma once
/// @file A dot product as accurate as if computed in twice the working precision (Ogita, Rump and
/// Oishi, "Accurate sum and dot product", SIAM J. Sci. Comput. 26, 2005: algorithm Dot2).
///
/// What it is for: the contacts that take part are those with D_NA = W_Nᵀ q̇_A + w_N ≤ 0 (SPEC §1),
/// and a contact that touches (D_NA = 0 up to the data's last bits) is decided by the sign of a sum
/// that cancels. The plain dot product is off by up to n ε Σ|W_i q̇_i| and can give that sign
/// wrongly (+8.5e-22 for an exact −8.9e-23 beside velocities of 3e-5): the contact then takes no
/// part and the answer lets it penetrate at a quarter of the velocity scale. Dot2's error is at
/// most ε|x·y| + γ_n² Σ|x_i y_i| (γ_n = nε/(1 − nε)), so its sign is the sign of the exact dot
/// product of the stored doubles unless that is below about n² ε² Σ|x_i y_i| (1e-31 relative).
#include <Eigen/Core>
#include <cmath>

namespace fremond::detail {

/// x·y + extra, with the products and the sum error-free transformed (TwoProduct by fma, TwoSum).
/// Both vectors are Eigen expressions of the same size.
template <class X, class Y>
double accurate_dot(const X& x, const Y& y, double extra = 0.0) {
  double s = extra, c = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double p = x(i) * y(i);
    const double ep = std::fma(x(i), y(i), -p);  // p + ep = x_i y_i exactly
    const double t = s + p;
    const double z = t - s;
    const double es = (s - (t - z)) + (p - z);  // t + es = s + p exactly (TwoSum)
    s = t;
    c += ep + es;
  }
  // Overflow (|W| near 1e308): the error terms are ∞ − ∞; the plain sum says what overflowed.
  const double r = s + c;
  return std::isfinite(r) ? r : s;
}

}  // namespace fremond::detail
