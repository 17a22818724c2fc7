// Tutorial: a pseudo-potential of your own, from definition to a solved and certified impact.
//
// The law: a viscous tangential law whose dead zone is not symmetric,
//     φ(y) = (k/2) max(0, y − a)² + (k/2) max(0, −b − y)²,     a, b ≥ 0, k > 0,
// e.g. a surface that lets the body slip freely up to a forward and b backward. It is convex,
// non-negative and zero at the origin (paper §5.2), so Frémond's law built on it is admissible.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fremond/fremond.hpp"
#include "fremond/io/problem_file.hpp"
#include "support/test_problems.hpp"

namespace {

using namespace fremond;

// Step 1: the potential. Override the protected hooks; the public interface (value, prox, ...)
// checks arguments and calls them. Each optional capability you provide lets the solver use a
// faster exact method: prox → semismooth Newton; conjugate → the Fenchel–Young certificate.
class AsymmetricDeadZone final : public Potential {
 public:
  AsymmetricDeadZone(double k, double a, double b) : k_(k), a_(a), b_(b) {
    if (!(k > 0.0) || !std::isfinite(k)) throw InvalidArgument("k", "must be > 0");
    if (!(a >= 0.0) || !std::isfinite(a)) throw InvalidArgument("a", "must be >= 0");
    if (!(b >= 0.0) || !std::isfinite(b)) throw InvalidArgument("b", "must be >= 0");
  }

 protected:
  std::string_view do_name() const override { return "asymmetric_deadzone"; }
  PotentialPtr do_clone() const override {
    return std::make_unique<AsymmetricDeadZone>(k_, a_, b_);
  }
  PotentialCapabilities do_capabilities() const override {
    PotentialCapabilities c;
    c.prox = c.prox_derivative = c.subdifferential = c.conjugate = c.quadratic = true;
    return c;
  }
  double do_value(double y) const override {
    const double e = excess(y);
    return 0.5 * k_ * e * e;
  }
  double do_subgradient(double y) const override { return k_ * excess(y); }
  // prox_{τφ}(x): inside [−b, a] nothing acts; outside, y − x + τk(y − a) = 0 (or with −b).
  double do_prox(double x, double tau, double* d) const override {
    if (x > a_) {
      if (d) *d = 1.0 / (1.0 + tau * k_);
      return (x + tau * k_ * a_) / (1.0 + tau * k_);
    }
    if (x < -b_) {
      if (d) *d = 1.0 / (1.0 + tau * k_);
      return (x - tau * k_ * b_) / (1.0 + tau * k_);
    }
    if (d) *d = 1.0;
    return x;
  }
  // φ*(s) = sup_y s y − φ(y) = max(a s, −b s) + s²/(2k).
  double do_conjugate(double s) const override {
    return std::max(a_ * s, -b_ * s) + s * s / (2.0 * k_);
  }

 private:
  double excess(double y) const { return y > a_ ? y - a_ : (y < -b_ ? y + b_ : 0.0); }
  double k_, a_, b_;
};

// Step 2: check it before trusting it: convexity, the subgradient inequality, prox optimality,
// firm non-expansiveness, Fenchel–Young and the Moreau identity.
TEST(TutorialCustomPotential, PassesTheConformanceChecks) {
  const auto report = check_potential(AsymmetricDeadZone(3.0, 0.2, 0.5));
  EXPECT_TRUE(report.ok) << report.summary();
  EXPECT_LE(report.max_fenchel_young_gap_at_prox, 1e-12);
  EXPECT_LE(report.max_moreau_error, 1e-6);
}

// Step 3: use it in C++ as the tangential law of the paper's bar. With a = b it is the built-in
// dead-zone power law with q = 2, r = a: both must give the same impact, to rounding.
TEST(TutorialCustomPotential, SymmetricCaseEqualsTheBuiltinDeadZone) {
  const ImpactProblem bar = fremond::testing::paper_bar_first_impact();
  const PowerPotential normal(85.36, 3.0);
  for (double r : {0.0, 0.01, 0.2, 5.0}) {
    const auto mine = solve_impact(bar, ImpactLaw::fremond(normal, AsymmetricDeadZone(1.5, r, r)));
    const auto builtin =
        solve_impact(bar, ImpactLaw::fremond(normal, DeadZonePowerPotential(1.5, 2.0, r)));
    ASSERT_TRUE(mine.ok()) << mine.solver.message;
    ASSERT_TRUE(builtin.ok());
    EXPECT_LE((mine.qdot_E - builtin.qdot_E).cwiseAbs().maxCoeff(), 1e-13) << "r=" << r;
    EXPECT_TRUE(mine.admissibility.admissible);
  }
}

// Step 4: register it by name and use it from a problem file (docs/problem-file.md). The registry
// is an object you pass: nothing global changes.
TEST(TutorialCustomPotential, FromAProblemFileByName) {
  PotentialRegistry registry = PotentialRegistry::with_builtins();
  registry.add("asymmetric_deadzone", {{"k", "a", "b"},
                                       {},
                                       [](const PotentialParameters& p) {
                                         return std::make_unique<AsymmetricDeadZone>(
                                             p.at("k"), p.at("a"), p.at("b"));
                                       },
                                       "(k/2)(max(0,y-a)^2 + max(0,-b-y)^2)"});
  const char* text = R"({
    "M": [[1, 0], [0, 1]], "W_N": [[0], [1]], "W_T": [[1], [0]], "qdot_A": [0.3, -2.0],
    "law": {"type": "fremond", "normal": {"potential": "power", "k": 8, "p": 2},
            "tangential": {"potential": "asymmetric_deadzone", "k": 2, "a": 0.1, "b": 0.05}}})";
  const auto file = io::parse_problem_file(text, registry);
  const auto r = solve_impact(file.problem, file.law);
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_TRUE(r.admissibility.admissible);
  // A point mass, decoupled rows (G = I): each row is one prox with τ = 1/2 (docs/laws.md).
  // Normal, p = 2: z = D/(1 + k/2), D_NE = 2z − D; eq. (24): ε = (k − 2m)/(k + 2m) = 0.6.
  EXPECT_NEAR(r.D_NE(0), 0.6 * 2.0, 1e-14);
  // Tangential: x = 0.3 > a, z = (x + τka)/(1 + τk) = (0.3 + 0.1)/2 = 0.2, D_TE = 2z − x = 0.1.
  EXPECT_NEAR(r.D_TE(0), 0.1, 1e-14);
  EXPECT_NEAR(r.P_T(0), -2.0 * (0.2 - 0.1), 1e-14);  // −P_T = k(z − a)
  // The built-in registry does not know it.
  EXPECT_THROW(io::parse_problem_file(text, PotentialRegistry::with_builtins()), InvalidArgument);
}

// Step 5: a potential given only by value and one subgradient still works, through the NLopt
// fallback; the answer matches the full potential's.
TEST(TutorialCustomPotential, ValueAndSubgradientOnlyGoesThroughNlopt) {
  CallablePotentialParts parts;
  parts.name = "asymmetric_deadzone_lite";
  const AsymmetricDeadZone full(1.5, 0.05, 0.3);
  parts.value = [&full](double y) { return full.value(y); };
  parts.subgradient = [&full](double y) { return full.subgradient(y); };
  const CallablePotential lite(parts);
  const ImpactProblem bar = fremond::fixtures::bar(0.3, Eigen::Vector3d(1.0, -3.0, 2.0));
  const PowerPotential normal(20.0, 3.0);
  const auto r_lite = solve_impact(bar, ImpactLaw::fremond(normal, lite));
  const auto r_full = solve_impact(bar, ImpactLaw::fremond(normal, full));
  ASSERT_TRUE(r_full.ok());
  ASSERT_TRUE(r_lite.ok()) << r_lite.solver.message;
  EXPECT_EQ(r_lite.solver.method, SolverMethod::nlopt);
  EXPECT_LE((r_lite.qdot_E - r_full.qdot_E).cwiseAbs().maxCoeff(), 1e-8 * r_full.qdot_E.norm());
  EXPECT_TRUE(r_lite.admissibility.admissible);
}

}  // namespace
