#include "fremond/potentials/absolute_value.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "core/detail/validate.hpp"

namespace fremond {

AbsoluteValuePotential::AbsoluteValuePotential(double b) : b_(b) {
  detail::require_finite_at_least("b", b, 0.0);
}

PotentialCapabilities AbsoluteValuePotential::do_capabilities() const {
  PotentialCapabilities c;
  c.prox = c.prox_derivative = c.subdifferential = c.conjugate = c.quadratic = true;
  return c;
}

double AbsoluteValuePotential::do_subgradient(double y) const {
  return y > 0.0 ? b_ : (y < 0.0 ? -b_ : 0.0);
}

Interval AbsoluteValuePotential::do_subdifferential(double y) const {
  if (y > 0.0) return Interval::point(b_);
  if (y < 0.0) return Interval::point(-b_);
  return {-b_, b_};
}

double AbsoluteValuePotential::do_prox(double x, double tau, double* dprox) const {
  const double t = tau * b_;  // soft thresholding
  if (std::fabs(x) <= t) {
    if (dprox) *dprox = 0.0;
    return 0.0;
  }
  if (dprox) *dprox = 1.0;
  return x - std::copysign(t, x);
}

double AbsoluteValuePotential::do_conjugate(double s) const {
  return std::fabs(s) <= b_ ? 0.0 : std::numeric_limits<double>::infinity();
}

std::string AbsoluteValuePotential::do_describe() const {
  std::ostringstream os;
  os.precision(10);
  os << "absolute_value(b=" << b_ << ")";
  return os.str();
}

}  // namespace fremond
