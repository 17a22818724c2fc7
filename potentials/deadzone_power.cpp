#include "fremond/potentials/deadzone_power.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "core/detail/validate.hpp"
#include "detail/power_root.hpp"

namespace fremond {

DeadZonePowerPotential::DeadZonePowerPotential(double k, double q, double r) : k_(k), q_(q), r_(r) {
  detail::require_finite_at_least("k", k, 0.0);
  detail::require_finite_above("q", q, 1.0);
  detail::require_finite_at_least("r", r, 0.0);
}

PotentialCapabilities DeadZonePowerPotential::do_capabilities() const {
  PotentialCapabilities c;
  c.prox = c.prox_derivative = c.subdifferential = c.conjugate = true;
  c.quadratic = (q_ == 2.0);
  return c;
}

// q = 2 (the viscous law) without pow: e² and e¹ are correctly rounded either way, the same
// numbers at a fraction of the cost.
double DeadZonePowerPotential::do_value(double y) const {
  const double e = std::fabs(y) - r_;
  if (!(e > 0.0)) return 0.0;
  return k_ * (q_ == 2.0 ? e * e : std::pow(e, q_)) / q_;
}

double DeadZonePowerPotential::do_subgradient(double y) const {
  const double e = std::fabs(y) - r_;
  if (!(e > 0.0)) return 0.0;
  return std::copysign(k_ * (q_ == 2.0 ? e : std::pow(e, q_ - 1.0)), y);
}

double DeadZonePowerPotential::do_prox(double x, double tau, double* dprox) const {
  // Inside the dead zone φ = 0 near x, so prox(x) = x. Outside, y = sign(x)(r + t) with
  // t + τk t^{q−1} = |x| − r.
  const double e = std::fabs(x) - r_;
  if (e <= 0.0) {
    if (dprox) *dprox = 1.0;
    return x;
  }
  const double t = detail::power_root(tau * k_, q_ - 1.0, e, dprox);
  return std::copysign(r_ + t, x);
}

double DeadZonePowerPotential::do_conjugate(double s) const {
  if (k_ == 0.0) return s == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  if (s == 0.0) return 0.0;
  if (q_ == 2.0) return r_ * std::fabs(s) + s * s / (2.0 * k_);
  const double qc = q_ / (q_ - 1.0);  // in logarithms, as for the power law
  return r_ * std::fabs(s) +
         std::exp(qc * std::log(std::fabs(s)) - (qc - 1.0) * std::log(k_) - std::log(qc));
}

std::string DeadZonePowerPotential::do_describe() const {
  std::ostringstream os;
  os.precision(10);
  os << "deadzone_power(k=" << k_ << ", q=" << q_ << ", r=" << r_ << ")";
  return os.str();
}

}  // namespace fremond
