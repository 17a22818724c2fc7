#pragma once
/// @file Indicators of R+ and R− (paper eq. 16): the reaction that forbids interpenetration.
#include "fremond/potentials/potential.hpp"

namespace fremond {

/// I_{R+}(z) = 0 for z ≥ 0, +∞ otherwise; ∂I(0) = (−∞, 0] (the normal cone); φ* = I_{R−}.
/// With `nonpositive = true`, the mirror image I_{R−}.
class IndicatorPotential final : public Potential {
 public:
  explicit IndicatorPotential(bool nonpositive = false) : nonpositive_(nonpositive) {}
  bool nonpositive() const { return nonpositive_; }

 protected:
  std::string_view do_name() const override {
    return nonpositive_ ? "indicator_nonpositive" : "indicator_nonnegative";
  }
  PotentialPtr do_clone() const override {
    return std::make_unique<IndicatorPotential>(nonpositive_);
  }
  PotentialCapabilities do_capabilities() const override;
  double do_value(double z) const override;
  double do_subgradient(double z) const override;
  Interval do_subdifferential(double z) const override;
  double do_prox(double x, double tau, double* dprox) const override;
  double do_conjugate(double s) const override;

 private:
  bool nonpositive_;
};

}  // namespace fremond
