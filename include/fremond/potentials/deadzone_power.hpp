#pragma once
/// @file φ_T(y) = (k/q) max(0, |y| − r)^q, the viscous tangential law with a dead zone (paper eq.
/// 25).
#include "fremond/potentials/potential.hpp"

namespace fremond {

/// (k/q) max(0, |y| − r)^q with k ≥ 0, q > 1, r ≥ 0. Inside the dead zone |y| ≤ r there is no
/// percussion. φ*(s) = r|s| + |s|^{q'}/(q' k^{q'−1}).
class DeadZonePowerPotential final : public Potential {
 public:
  /// Throws InvalidArgument unless k ≥ 0, q > 1, r ≥ 0, all finite.
  DeadZonePowerPotential(double k, double q, double r);
  double k() const { return k_; }
  double q() const { return q_; }
  double r() const { return r_; }

 protected:
  std::string_view do_name() const override { return "deadzone_power"; }
  PotentialPtr do_clone() const override {
    return std::make_unique<DeadZonePowerPotential>(k_, q_, r_);
  }
  PotentialCapabilities do_capabilities() const override;
  double do_value(double y) const override;
  double do_subgradient(double y) const override;
  double do_prox(double x, double tau, double* dprox) const override;
  double do_conjugate(double s) const override;
  std::string do_describe() const override;

 private:
  double k_, q_, r_;
};

}  // namespace fremond
