// The non-virtual interface of Potential: argument checks, and the generic prox by bisection.
#include "fremond/potentials/potential.hpp"

#include <cmath>
#include <limits>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"

namespace fremond {

namespace {

// prox_{τφ} is nondecreasing and 1-Lipschitz, and its limit at ±∞ is the end of dom φ on that side
// (the quadratic term pulls y outwards without bound): ±∞ when φ is finite out to the largest
// double, else the boundary of the domain, found by bisection between a point of the domain and the
// largest double. Potential::do_prox's bracket expansion cannot start from an infinite x (it would
// form ∞ − ∞ and answer NaN or a point outside the domain).
double prox_at_infinity(const Potential& phi, double x, double tau, double* dprox) {
  auto in_domain = [&](double y) { return !phi.subdifferential(y).is_empty(); };
  const double far = std::copysign(std::numeric_limits<double>::max(), x);
  if (in_domain(far)) {
    if (dprox) *dprox = 1.0;  // conservative element, as where the bisection lands on the root
    return x;
  }
  double in = phi.prox(0.0, tau), out = far;  // a prox lies in the domain
  for (int i = 0; i < 2200; ++i) {
    const double mid = 0.5 * in + 0.5 * out;  // no overflow, unlike 0.5 * (in + out)
    if (mid == in || mid == out) break;
    (in_domain(mid) ? in : out) = mid;
  }
  if (dprox) *dprox = 0.0;  // the prox is constant (the domain's end) near ±∞
  return in;
}

}  // namespace

Interval Potential::subdifferential(double z) const {
  return do_subdifferential(z);
}

double Potential::prox(double x, double tau, double* dprox) const {
  if (!(tau > 0.0) || !std::isfinite(tau))
    throw InvalidArgument(
        "tau", "the prox step must be positive and finite, got " + detail::format_number(tau));
  // ±∞ is accepted: every do_prox answers the limit of the prox there, which is well defined (the
  // prox is monotone), so a solver's diverging iterate gives a number and not an exception.
  if (std::isnan(x)) throw InvalidArgument("x", "the prox argument is NaN");
  // A potential with its own prox answers here; the capability test is in the generic do_prox
  // below, the only one that needs the subdifferential (the solvers call prox in their inner
  // loops).
  return do_prox(x, tau, dprox);
}

double Potential::conjugate(double s) const {
  if (!do_capabilities().conjugate)
    throw InvalidArgument(std::string(name()), "the conjugate of this potential is not known");
  return do_conjugate(s);
}

double Potential::fenchel_young_gap(double z, double s) const {
  if (!do_capabilities().conjugate) return std::numeric_limits<double>::quiet_NaN();
  const double fz = do_value(z);
  const double fs = do_conjugate(s);
  if (std::isinf(fz) || std::isinf(fs)) return std::numeric_limits<double>::infinity();
  return fz + fs - s * z;
}

double Potential::do_conjugate(double) const {
  return std::numeric_limits<double>::quiet_NaN();
}

// prox_{τφ}(x) is the unique y with 0 ∈ y − x + τ∂φ(y). The map y ↦ y − x + τ∂φ(y) is strictly
// increasing (set-valued), so bisection on the sign of its interval finds y to the last bit. The
// bracket grows geometrically from x: the root lies between x and the point where the subgradient
// changes sign, i.e. inside [x − τ|g(x)| − 1, x + τ|g(x)| + 1] widened until it brackets.
double Potential::do_prox(double x, double tau, double* dprox) const {
  if (!do_capabilities().subdifferential)
    throw InvalidArgument(std::string(name()),
                          "this potential gives neither a prox nor its subdifferential");
  if (std::isinf(x)) return prox_at_infinity(*this, x, tau, dprox);
  auto sign_at = [&](double y) {  // −1: y below the root, +1: above, 0: y is the root
    const Interval sd = do_subdifferential(y);
    if (sd.is_empty()) {
      // Outside the domain: the root lies on the side where φ is finite.
      const double d = 1.0 + std::fabs(y);
      return std::isfinite(do_value(y + d)) ? -1 : 1;
    }
    const double lo = y - x + tau * sd.lo;
    const double hi = y - x + tau * sd.hi;
    if (hi < 0.0) return -1;
    if (lo > 0.0) return 1;
    return 0;
  };
  double step = 1.0 + std::fabs(x);
  double a = x, b = x;
  int sa = sign_at(a);
  if (sa == 0) {
    if (dprox) *dprox = 1.0;  // conservative element of the derivative
    return x;
  }
  // Expand in the direction of the root.
  for (int i = 0; i < 2100; ++i) {
    b = (sa < 0) ? a + step : a - step;
    const int sb = sign_at(b);
    if (sb == 0) {
      if (dprox) *dprox = 1.0;
      return b;
    }
    if (sb != sa) break;
    a = b;
    step *= 2.0;
    if (!std::isfinite(step)) break;
  }
  double lo = std::fmin(a, b), hi = std::fmax(a, b);
  // The map has slope ≥ 1 in y, and x carries its own rounding, so the root is known to no better
  // than ε|x|: stop there. Bisecting on to adjacent doubles costs ~1,100 steps when the root is at
  // or near 0 (the denormals), e.g. a touching contact's prox, and buys nothing.
  const double enough = 2.0 * std::numeric_limits<double>::epsilon() * std::fabs(x);
  for (int i = 0; i < 2200 && hi - lo > enough; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    const int sm = sign_at(mid);
    if (sm == 0) {
      lo = hi = mid;
      break;
    }
    if (sm < 0)
      lo = mid;
    else
      hi = mid;
  }
  const double y = 0.5 * (lo + hi);
  if (dprox) {
    // dprox = 1/(1 + τφ''(y)) where φ is twice differentiable; 0 at a kink (a set-valued ∂φ(y)).
    const Interval sd = do_subdifferential(y);
    const double scale = 1e-12 * (1.0 + std::fabs(sd.hi) + std::fabs(sd.lo));
    if (sd.is_empty() || sd.hi - sd.lo > scale) {
      *dprox = 0.0;
    } else {
      const double h = 1e-6 * (1.0 + std::fabs(y));
      const double curv = (do_subgradient(y + h) - do_subgradient(y - h)) / (2.0 * h);
      *dprox = (std::isfinite(curv) && curv >= 0.0) ? 1.0 / (1.0 + tau * curv) : 0.0;
    }
  }
  return y;
}

}  // namespace fremond
