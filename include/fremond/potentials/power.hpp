#pragma once
/// @file φ_N(z) = k|z|^p / p, the normal power law of Frémond's model (paper eq. 22, docs/laws.md).
#include "fremond/potentials/potential.hpp"

namespace fremond {

/// k|z|^p/p with k ≥ 0, p > 1. ∂φ(z) = k z|z|^{p−2}; φ*(s) = |s|^{p'}/(p' k^{p'−1}), 1/p + 1/p'
/// = 1. For p = 2 the impact of one point mass m is Newton's law with ε = (k − 2m)/(k + 2m) (eq. 24
/// in the library's scaling).
class PowerPotential final : public Potential {
 public:
  /// Throws InvalidArgument unless k ≥ 0 and p > 1, both finite.
  PowerPotential(double k, double p);
  double k() const { return k_; }
  double p() const { return p_; }

 protected:
  std::string_view do_name() const override { return "power"; }
  PotentialPtr do_clone() const override { return std::make_unique<PowerPotential>(k_, p_); }
  PotentialCapabilities do_capabilities() const override;
  double do_value(double z) const override;
  double do_subgradient(double z) const override;
  double do_prox(double x, double tau, double* dprox) const override;
  double do_conjugate(double s) const override;
  std::string do_describe() const override;

 private:
  double k_, p_;
};

}  // namespace fremond
