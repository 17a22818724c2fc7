#include "fremond/potentials/indicator.hpp"

#include <cmath>
#include <limits>

namespace fremond {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

PotentialCapabilities IndicatorPotential::do_capabilities() const {
  PotentialCapabilities c;
  c.prox = c.prox_derivative = c.subdifferential = c.conjugate = c.quadratic = true;
  return c;
}

// Work on the mirrored variable so that one code path serves both R+ and R−.
double IndicatorPotential::do_value(double z) const {
  const double u = nonpositive_ ? -z : z;
  return u >= 0.0 ? 0.0 : kInf;
}

double IndicatorPotential::do_subgradient(double z) const {
  const double u = nonpositive_ ? -z : z;
  return u >= 0.0 ? 0.0 : std::numeric_limits<double>::quiet_NaN();
}

Interval IndicatorPotential::do_subdifferential(double z) const {
  const double u = nonpositive_ ? -z : z;
  if (u > 0.0) return Interval::point(0.0);
  if (u < 0.0) return Interval::empty();
  return nonpositive_ ? Interval{0.0, kInf} : Interval{-kInf, 0.0};  // the normal cone at 0
}

double IndicatorPotential::do_prox(double x, double, double* dprox) const {
  const double u = nonpositive_ ? -x : x;
  if (dprox) *dprox = u > 0.0 ? 1.0 : 0.0;
  return u > 0.0 ? x : 0.0;
}

double IndicatorPotential::do_conjugate(double s) const {
  const double u = nonpositive_ ? -s : s;  // the conjugate is the indicator of the polar cone
  return u <= 0.0 ? 0.0 : kInf;
}

}  // namespace fremond
