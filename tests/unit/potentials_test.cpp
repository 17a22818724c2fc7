#include <gtest/gtest.h>

#include <cmath>

#include "fremond/fremond.hpp"

namespace fremond {
namespace {

TEST(PowerPotential, ProxClosedFormsP2P3) {
  PowerPotential p2(3.0, 2.0), p3(2.0, 3.0);
  // p = 2: y(1 + τk) = x.
  EXPECT_NEAR(p2.prox(4.0, 0.5), 4.0 / 2.5, 1e-15);
  // p = 3: y + τk y|y| = x; check the equation itself.
  const double y = p3.prox(-7.0, 0.25);
  EXPECT_NEAR(y + 0.25 * 2.0 * y * std::fabs(y), -7.0, 1e-14);
}

TEST(PowerPotential, GeneralExponentsSolveTheProxEquation) {
  for (double p : {1.01, 1.1, 1.5, 2.5, 4.0, 10.0, 50.0}) {
    for (double k : {1e-6, 1.0, 1e6}) {
      PowerPotential f(k, p);
      for (double x : {-1e6, -3.0, -1e-10, 1e-10, 0.5, 1e6}) {
        double d = -1;
        const double y = f.prox(x, 0.7, &d);
        const double lhs = y + 0.7 * f.subgradient(y);
        if (std::fabs(y) > 1e-300) {
          EXPECT_NEAR(lhs, x, 1e-13 * std::fabs(x)) << "p=" << p << " k=" << k << " x=" << x;
        } else {  // the root is below the smallest double: the equation overshoots just above it
          EXPECT_GT(std::fabs(1e-300 + 0.7 * f.subgradient(1e-300)), std::fabs(x) * (1 - 1e-12));
        }
        EXPECT_GE(d, 0.0);
        EXPECT_LE(d, 1.0);
      }
    }
  }
}

TEST(Conformance, BuiltinsConform) {
  PowerPotential a(2.0, 3.0), b(0.5, 1.3);
  DeadZonePowerPotential c(1.5, 2.0, 0.2), d(3.0, 1.5, 0.0);
  AbsoluteValuePotential e(0.7);
  IndicatorPotential f;
  for (const Potential* pot : std::initializer_list<const Potential*>{&a, &b, &c, &d, &e, &f}) {
    const auto rep = check_potential(*pot);
    EXPECT_TRUE(rep.ok) << pot->describe() << ": " << rep.summary();
  }
}

TEST(Conformance, KinkedSumsConform) {
  // k|z|^p/p + c|z| has a kink at 0, where ∂φ(0) = [−c, c]: its prox by bisection returns 2e-29
  // or −3.9e-21 for the exact 0, and the optimality test must read ∂φ within that rounding.
  const SumPotential kinked(PowerPotential(10.0, 2.5), AbsoluteValuePotential(0.3));
  const auto rep = check_potential(kinked);
  EXPECT_TRUE(rep.ok) << rep.summary();
  EXPECT_LE(rep.max_prox_optimality, 1e-12);
  const SumPotential dead(DeadZonePowerPotential(1.5, 2.0, 0.2), AbsoluteValuePotential(0.1));
  EXPECT_TRUE(check_potential(dead).ok) << check_potential(dead).summary();
}

TEST(Conformance, CatchesAWrongProx) {
  CallablePotentialParts parts;
  parts.name = "broken";
  parts.value = [](double z) { return z * z; };
  parts.subgradient = [](double z) { return 2 * z; };
  parts.subdifferential = [](double z) { return Interval::point(2 * z); };
  parts.prox = [](double x, double tau,
                  double* d) {  // wrong: the prox of z², not of 2z²/2... off by 2
    if (d) *d = 1.0 / (1.0 + tau);
    return x / (1.0 + tau);
  };
  parts.conjugate = [](double s) { return s * s / 4.0; };
  CallablePotential f(parts);
  EXPECT_FALSE(check_potential(f).ok);
}

}  // namespace
}  // namespace fremond
