// Parameters at the edges of their ranges and problems beyond the enumeration's reach: the
// classical laws never crash, and whatever they report as converged satisfies the law.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "unit/classical_support.hpp"

namespace fremond {
namespace {

ImpactProblem random_problem(std::mt19937& rng, int n, int c) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatrixX A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = u(rng);
  ImpactProblem p;
  p.M = A * A.transpose() / n + 0.5 * MatrixX::Identity(n, n);
  p.W_N.resize(n, c);
  p.W_T.resize(n, c);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < c; ++j) {
      p.W_N(i, j) = u(rng);
      p.W_T(i, j) = u(rng);
    }
  p.qdot_A.resize(n);
  for (int i = 0; i < n; ++i) p.qdot_A(i) = u(rng);
  return p;
}

// Every status is one of the documented ends, and a converged answer solves the law.
void expect_sound(const ImpactProblem& p, const ImpactLaw& law, const ImpactResult& r,
                  const char* what) {
  EXPECT_NE(r.solver.status, SolverStatus::not_run) << what;
  EXPECT_NE(r.solver.status, SolverStatus::unsupported) << what;
  EXPECT_FALSE(r.solver.message.empty()) << what;
  if (r.ok()) {
    EXPECT_LE(law_residual(p, law, r), 1e-11) << what << ": " << r.solver.message;
    EXPECT_TRUE(r.qdot_E.allFinite()) << what;
  }
}

TEST(ClassicalRobustness, ExtremeParametersNeverCrash) {
  const ImpactProblem cases[] = {test::bar_first_impact(),     test::flat_bar({2, -3, 1}),
                                 test::flat_bar({0, 0, 0}),    test::bar(0.0, {1, -1, 0}),
                                 test::point_mass(0, -1e-300), test::point_mass(1e150, -1e150)};
  for (const ImpactProblem& p : cases)
    for (const double e : {0.0, 1.0})
      for (const double mu : {0.0, 1e-300, 1e3, 1e300})
        for (const ImpactLaw& law :
             {ImpactLaw::newton_coulomb(e, mu), ImpactLaw::poisson_coulomb(e, mu),
              ImpactLaw::newton(e), ImpactLaw::poisson(e)}) {
          const ImpactResult r = solve_impact(p, law);
          expect_sound(p, law, r, law.describe().c_str());
          for (const auto& s : solve_impact_all(p, law)) expect_sound(p, law, s, "all");
        }
}

TEST(ClassicalRobustness, MoreThanThreeContactsUseLemkeAlone) {
  // Beyond 3 contacts with friction there is no enumeration: the answer is Lemke's, uniqueness is
  // not checked (solutions_found = 0), and a ray is reported as `failed`, not as `no_solution`.
  std::mt19937 rng(17);
  int solved = 0, beyond = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const ImpactProblem p = random_problem(rng, 8, 4 + trial % 3);
    const ImpactLaw law = ImpactLaw::newton_coulomb(0.5, 0.3);
    const ImpactResult r = solve_impact(p, law);
    expect_sound(p, law, r, "newton_coulomb");
    // The contacts solved for: the approaching ones, or every one where a separating contact is
    // stopped by its reaction (docs/concepts.md).
    int held = r.takes_part.sum();
    for (int i = 0; i < r.P_N.size(); ++i)
      if (!r.takes_part(i) && (r.P_N(i) != 0.0 || r.P_T(i) != 0.0))
        held = static_cast<int>(r.P_N.size());
    beyond += held > 3;
    if (r.ok()) {
      ++solved;
      if (held > 3)
        EXPECT_EQ(r.solutions_found, 0) << r.solver.message;
      else
        EXPECT_GE(r.solutions_found, 1);
    } else {
      EXPECT_EQ(r.solver.status, SolverStatus::failed) << r.solver.message;
    }
    const ImpactLaw frictionless = ImpactLaw::poisson(0.7);
    const ImpactResult q = solve_impact(p, frictionless);
    ASSERT_TRUE(q.ok()) << q.solver.message;  // positive semidefinite: Lemke always answers
    expect_sound(p, frictionless, q, "poisson");
  }
  EXPECT_GT(solved, 50);
  EXPECT_GT(beyond, 10);  // the sample does go beyond the enumeration's reach
}

// Two point masses, each on its own obstacle; the second obstacle moves away at 1e308 (near the
// largest double), so that contact's velocities before and after are both 1e308: their mean is
// finite, their sum is not. The report must stay finite (a separating contact adds no energy, not
// 0·∞ = NaN), under every law, with an answer or without one.
TEST(ClassicalRobustness, VelocitiesNearTheLargestDoubleGiveAFiniteReport) {
  ImpactProblem p;
  p.M = MatrixX::Identity(4, 4);
  p.W_N = MatrixX::Zero(4, 2);
  p.W_T = MatrixX::Zero(4, 2);
  p.W_N(0, 0) = p.W_T(1, 0) = p.W_N(2, 1) = p.W_T(3, 1) = 1.0;
  p.qdot_A = VectorX{{-1.0, 0.5, -1.0, 0.0}};
  p.w_T = VectorX::Zero(2);
  for (const double w : {1e308, -1e308}) {
    // w = −1e308: the second mass meets an obstacle approaching at 1e308; its percussion is
    // beyond double precision, which must be reported as a failure with a finite report.
    p.w_N = VectorX{{0.0, w}};
    for (const ImpactLaw& law :
         {ImpactLaw::newton(0.5), ImpactLaw::poisson(0.5), ImpactLaw::newton_coulomb(0.5, 0.3),
          ImpactLaw::poisson_coulomb(0.5, 0.3)}) {
      const ImpactResult r = solve_impact(p, law);
      const std::string what = law.describe() + " w = " + std::to_string(w);
      const auto& a = r.admissibility;
      EXPECT_TRUE(std::isfinite(a.total)) << what;
      EXPECT_TRUE(a.per_contact.allFinite()) << what;
      EXPECT_TRUE(std::isfinite(a.dissipation)) << what;
      EXPECT_TRUE(std::isfinite(a.reaction)) << what;
      if (w > 0) {
        ASSERT_TRUE(r.ok()) << what << ": " << r.solver.message;
        // The first mass alone: P_N = (1 + e)·1, and P_T = −μP_N slides (|D_TA| = 0.5 > μ P_N).
        EXPECT_NEAR(r.P_N(0), 1.5, 1e-15) << what;
        EXPECT_EQ(r.P_N(1), 0.0) << what;
        EXPECT_TRUE(a.admissible) << what;
        EXPECT_DOUBLE_EQ(a.per_contact(1), 0.0) << what;
      } else {
        EXPECT_FALSE(r.ok()) << what;
      }
    }
  }
}

}  // namespace
}  // namespace fremond
