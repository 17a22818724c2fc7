#include "fremond/potentials/sum.hpp"

#include <cmath>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"

namespace fremond {

SumPotential::SumPotential(const Potential& f, const Potential& g) : f_(f.clone()), g_(g.clone()) {}

SumPotential::SumPotential(PotentialPtr f, PotentialPtr g) : f_(std::move(f)), g_(std::move(g)) {
  if (!f_ || !g_) throw InvalidArgument("sum", "both terms must be potentials, got a null pointer");
}

PotentialCapabilities SumPotential::do_capabilities() const {
  const auto a = f_->capabilities(), b = g_->capabilities();
  PotentialCapabilities c;
  // The prox of a sum comes from the subdifferential (bisection), so it needs both intervals.
  c.subdifferential = a.subdifferential && b.subdifferential;
  c.prox = c.prox_derivative = c.subdifferential;
  c.conjugate = false;
  c.quadratic = false;
  return c;
}

double SumPotential::do_subgradient(double z) const {
  return f_->subgradient(z) + g_->subgradient(z);
}

Interval SumPotential::do_subdifferential(double z) const {
  return f_->subdifferential(z) + g_->subdifferential(z);
}

std::string SumPotential::do_describe() const {
  return "sum(" + f_->describe() + ", " + g_->describe() + ")";
}

ScaledPotential::ScaledPotential(double alpha, const Potential& f) : alpha_(alpha), f_(f.clone()) {
  detail::require_finite_above("alpha", alpha, 0.0);
}

double ScaledPotential::do_value(double z) const {
  const double v = f_->value(z);
  return std::isinf(v) ? v : alpha_ * v;
}

Interval ScaledPotential::do_subdifferential(double z) const {
  const Interval i = f_->subdifferential(z);
  if (i.is_empty()) return i;
  return {alpha_ * i.lo, alpha_ * i.hi};
}

std::string ScaledPotential::do_describe() const {
  return detail::format_number(alpha_) + " * " + f_->describe();
}

PotentialPtr operator+(const Potential& f, const Potential& g) {
  return std::make_unique<SumPotential>(f, g);
}

PotentialPtr operator*(double alpha, const Potential& f) {
  return std::make_unique<ScaledPotential>(alpha, f);
}

}  // namespace fremond
