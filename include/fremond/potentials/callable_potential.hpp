#pragma once
/// @file A potential from callables: the quickest way for a user to plug in a law of their own.
#include <functional>

#include "fremond/potentials/potential.hpp"

namespace fremond {

/// The parts of a user's potential. `value` and `subgradient` are required; each further part a
/// user gives lets the driver use a faster exact method:
///  - `subdifferential` (the whole interval): prox by bisection, hence semismooth Newton;
///  - `prox` (with its derivative): semismooth Newton directly;
///  - `conjugate`: the Fenchel–Young certificate.
/// With only value and subgradient the impact is solved through the NLopt fallback.
struct CallablePotentialParts {
  std::string name = "callable";
  std::function<double(double)> value;
  std::function<double(double)> subgradient;
  std::function<Interval(double)> subdifferential;
  /// prox(x, τ, dprox*): prox_{τφ}(x); writes the derivative when dprox is not null.
  std::function<double(double, double, double*)> prox;
  std::function<double(double)> conjugate;
};

class CallablePotential final : public Potential {
 public:
  /// Throws InvalidArgument when value or subgradient is missing.
  explicit CallablePotential(CallablePotentialParts parts);

 protected:
  std::string_view do_name() const override { return parts_.name; }
  PotentialPtr do_clone() const override { return std::make_unique<CallablePotential>(parts_); }
  PotentialCapabilities do_capabilities() const override;
  double do_value(double z) const override { return parts_.value(z); }
  double do_subgradient(double z) const override { return parts_.subgradient(z); }
  Interval do_subdifferential(double z) const override;
  double do_prox(double x, double tau, double* dprox) const override;
  double do_conjugate(double s) const override;

 private:
  CallablePotentialParts parts_;
};

}  // namespace fremond
