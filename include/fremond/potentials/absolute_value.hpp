#pragma once
/// @file b|y|, the support function of [−b, b]: Coulomb's dissipation with a fixed bound b = μP_N.
#include "fremond/potentials/potential.hpp"

namespace fremond {

/// b|y| with b ≥ 0. ∂φ(0) = [−b, b]; prox is soft thresholding; φ* is the indicator of [−b, b].
class AbsoluteValuePotential final : public Potential {
 public:
  explicit AbsoluteValuePotential(double b);
  double bound() const { return b_; }

 protected:
  std::string_view do_name() const override { return "absolute_value"; }
  PotentialPtr do_clone() const override { return std::make_unique<AbsoluteValuePotential>(b_); }
  PotentialCapabilities do_capabilities() const override;
  double do_value(double y) const override { return b_ * std::fabs(y); }
  double do_subgradient(double y) const override;
  Interval do_subdifferential(double y) const override;
  double do_prox(double x, double tau, double* dprox) const override;
  double do_conjugate(double s) const override;
  std::string do_describe() const override;

 private:
  double b_;
};

}  // namespace fremond
