#pragma once
/// @file The scalar kernel behind every power-type prox: the root t ≥ 0 of t + a t^m = b.
#include <cmath>
#include <limits>

namespace fremond::detail {

/// Root t ≥ 0 of t + a·t^m = b for b ≥ 0, a ≥ 0, m > 0, with dt/db in `*dtdb` when not null.
///
/// This is prox_{τφ} of φ(y) = k|y|^p/p on y ≥ 0 (a = τk, m = p − 1, b = |x|). Closed forms for m =
/// 1 and m = 2 (p = 2, 3). Otherwise Newton in u = ln t: g(u) = e^u + a e^{mu} − b is increasing
/// and convex, so Newton started to the right of the root (at an upper bound) decreases
/// monotonically to it, with no overshoot and no bracketing; the start is within a factor 2^{1/m}
/// of the root, so a few steps suffice for every m. Overflow is impossible: every iterate satisfies
/// a t^m ≤ b. The derivative uses a t^m = b − t: dt/db = 1/(1 + a m t^{m−1}) = t/(t + m(b − t)). b
/// = +∞ gives the limit t = +∞ (the root grows without bound with b), with dt/db its limit: the
/// closed forms and the Newton steps would form ∞ − ∞ there.
inline double power_root(double a, double m, double b, double* dtdb = nullptr) {
  if (std::isinf(b) && b > 0.0) {
    // 1/(1 + a m t^{m−1}) as t → ∞: 1 without the power term or for m < 1, 1/(1 + a) for m = 1.
    if (dtdb) *dtdb = (a == 0.0 || m < 1.0) ? 1.0 : (m == 1.0 ? 1.0 / (1.0 + a) : 0.0);
    return b;
  }
  if (b <= 0.0) {
    if (dtdb) *dtdb = (a == 0.0) ? 1.0 : (m < 1.0 ? 0.0 : (m == 1.0 ? 1.0 / (1.0 + a) : 1.0));
    return 0.0;
  }
  if (a == 0.0) {
    if (dtdb) *dtdb = 1.0;
    return b;
  }
  double t;
  if (m == 1.0) {
    t = b / (1.0 + a);
  } else if (m == 2.0) {
    t = 2.0 * b / (1.0 + std::sqrt(1.0 + 4.0 * a * b));
  } else {
    // Upper bounds from each term alone: t ≤ b and a t^m ≤ b.
    const double t_hi = std::fmin(b, std::pow(b / a, 1.0 / m));
    if (!(t_hi > 0.0)) {  // (b/a)^{1/m} underflows: the root is below the smallest double.
      if (dtdb) *dtdb = (m < 1.0) ? 0.0 : 1.0;
      return 0.0;
    }
    double u = std::log(t_hi);
    t = t_hi;
    for (int it = 0; it < 200; ++it) {
      const double e1 = std::exp(u);
      const double e2 = a * std::exp(m * u);
      const double g = e1 + e2 - b;
      if (g <= 0.0) break;  // at (or, by rounding, just left of) the root
      const double du = g / (e1 + m * e2);
      const double u_new = u - du;
      if (!(u_new < u)) break;  // no further decrease in floating point
      u = u_new;
      t = std::exp(u);
      if (du <= 4.0 * std::numeric_limits<double>::epsilon() * std::fmax(1.0, std::fabs(u))) break;
    }
  }
  if (dtdb) *dtdb = t / (t + m * (b - t));
  return t;
}

}  // namespace fremond::detail
