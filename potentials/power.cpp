#include "fremond/potentials/power.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "core/detail/validate.hpp"
#include "detail/power_root.hpp"
#include "fremond/core/error.hpp"

namespace fremond {

PowerPotential::PowerPotential(double k, double p) : k_(k), p_(p) {
  detail::require_finite_at_least("k", k, 0.0);
  detail::require_finite_above("p", p, 1.0);
}

PotentialCapabilities PowerPotential::do_capabilities() const {
  PotentialCapabilities c;
  c.prox = c.prox_derivative = c.subdifferential = c.conjugate = true;
  c.quadratic = (p_ == 2.0);
  return c;
}

// p = 2 (the linear law) and φ' for p = 3 without pow: |z|² and |z|¹ are exact or correctly
// rounded either way, so these are the same numbers at a fraction of the cost. φ for p = 3 (the
// paper's law) as |z|·|z|·|z|: two roundings instead of pow's one, within 2 ulp, far inside the
// allowance the certificate makes for the rounding of z itself (admissibility.cpp).
double PowerPotential::do_value(double z) const {
  if (p_ == 2.0) return k_ * (z * z) / 2.0;
  if (p_ == 3.0) {
    const double a = std::fabs(z);
    return k_ * (a * a * a) / 3.0;
  }
  return k_ * std::pow(std::fabs(z), p_) / p_;
}

double PowerPotential::do_subgradient(double z) const {
  if (p_ == 2.0) return k_ * z;
  if (p_ == 3.0) return k_ * std::copysign(z * z, z);
  return k_ * std::copysign(std::pow(std::fabs(z), p_ - 1.0), z);
}

double PowerPotential::do_prox(double x, double tau, double* dprox) const {
  // y + τk y|y|^{p−2} = x: y has the sign of x and |y| is the root of t + τk t^{p−1} = |x|.
  // x = ±∞ gives ±∞, the limit of the prox of a potential finite on the whole line (power_root).
  const double t = detail::power_root(tau * k_, p_ - 1.0, std::fabs(x), dprox);
  return std::copysign(t, x);
}

double PowerPotential::do_conjugate(double s) const {
  if (k_ == 0.0) return s == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  if (s == 0.0) return 0.0;
  if (p_ == 2.0) return s * s / (2.0 * k_);
  if (p_ == 3.0) {  // p' = 3/2
    const double a = std::fabs(s);
    return a * std::sqrt(a / k_) / 1.5;
  }
  // |s|^{p'}/(p' k^{p'−1}) in logarithms: for p near 1 the exponent p' is large and each factor
  // alone over- or underflows although their ratio (≈ (1 − 1/p) k|z|^p at s = φ'(z)) is moderate.
  const double pc = p_ / (p_ - 1.0);  // conjugate exponent p'
  return std::exp(pc * std::log(std::fabs(s)) - (pc - 1.0) * std::log(k_) - std::log(pc));
}

std::string PowerPotential::do_describe() const {
  std::ostringstream os;
  os.precision(10);
  os << "power(k=" << k_ << ", p=" << p_ << ")";
  return os.str();
}

}  // namespace fremond
