#pragma once
/// @file φ = f + g, e.g. a power law plus a dead-zone term of a user's design.
#include "fremond/potentials/potential.hpp"

namespace fremond {

/// f + g. ∂(f + g) = ∂f + ∂g (one of them finite everywhere, which every built-in potential but the
/// indicators is). The prox is computed by bisection on the monotone inclusion (exact to the last
/// bit); the conjugate (an infimal convolution) is not known in general.
class SumPotential final : public Potential {
 public:
  SumPotential(const Potential& f, const Potential& g);
  SumPotential(PotentialPtr f, PotentialPtr g);
  const Potential& first() const { return *f_; }
  const Potential& second() const { return *g_; }

 protected:
  std::string_view do_name() const override { return "sum"; }
  PotentialPtr do_clone() const override { return std::make_unique<SumPotential>(*f_, *g_); }
  PotentialCapabilities do_capabilities() const override;
  double do_value(double z) const override { return f_->value(z) + g_->value(z); }
  double do_subgradient(double z) const override;
  Interval do_subdifferential(double z) const override;
  std::string do_describe() const override;

 private:
  PotentialPtr f_, g_;
};

/// α f with α > 0: prox_{τ α f} = prox_{(τα) f}, ∂(αf) = α∂f, (αf)*(s) = α f*(s/α).
class ScaledPotential final : public Potential {
 public:
  ScaledPotential(double alpha, const Potential& f);
  double alpha() const { return alpha_; }
  const Potential& inner() const { return *f_; }

 protected:
  std::string_view do_name() const override { return "scaled"; }
  PotentialPtr do_clone() const override { return std::make_unique<ScaledPotential>(alpha_, *f_); }
  PotentialCapabilities do_capabilities() const override { return f_->capabilities(); }
  double do_value(double z) const override;
  double do_subgradient(double z) const override { return alpha_ * f_->subgradient(z); }
  Interval do_subdifferential(double z) const override;
  double do_prox(double x, double tau, double* dprox) const override {
    return f_->prox(x, tau * alpha_, dprox);
  }
  double do_conjugate(double s) const override { return alpha_ * f_->conjugate(s / alpha_); }
  std::string do_describe() const override;

 private:
  double alpha_;
  PotentialPtr f_;
};

/// f + g as a new potential.
PotentialPtr operator+(const Potential& f, const Potential& g);
/// α f as a new potential (α > 0).
PotentialPtr operator*(double alpha, const Potential& f);

}  // namespace fremond
