#include "fremond/potentials/callable_potential.hpp"

#include <limits>

#include "fremond/core/error.hpp"

namespace fremond {

CallablePotential::CallablePotential(CallablePotentialParts parts) : parts_(std::move(parts)) {
  if (parts_.name.empty()) throw InvalidArgument("name", "a potential needs a non-empty name");
  if (!parts_.value)
    throw InvalidArgument(parts_.name + ".value", "the value callable is required");
  if (!parts_.subgradient)
    throw InvalidArgument(parts_.name + ".subgradient", "the subgradient callable is required");
}

PotentialCapabilities CallablePotential::do_capabilities() const {
  PotentialCapabilities c;
  c.subdifferential = static_cast<bool>(parts_.subdifferential);
  c.prox = static_cast<bool>(parts_.prox) || c.subdifferential;
  c.prox_derivative = c.prox;
  c.conjugate = static_cast<bool>(parts_.conjugate);
  return c;
}

Interval CallablePotential::do_subdifferential(double z) const {
  return parts_.subdifferential ? parts_.subdifferential(z)
                                : Interval::point(parts_.subgradient(z));
}

double CallablePotential::do_prox(double x, double tau, double* dprox) const {
  if (parts_.prox) {
    double d = 1.0;
    const double y = parts_.prox(x, tau, &d);
    if (dprox) *dprox = d;
    return y;
  }
  return Potential::do_prox(x, tau, dprox);
}

double CallablePotential::do_conjugate(double s) const {
  return parts_.conjugate ? parts_.conjugate(s) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace fremond
