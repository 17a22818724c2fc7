// Balls in a line (ball_chain.hpp), where laws of simultaneous impacts differ: Newton's cradle
// struck at one end, and a ball dropped on one resting on the ground. Newton's and Poisson's laws
// at e = 1 against the answers derived by hand from G = WᵀM⁻¹W (the discrete Laplacian, whose
// inverse is min(i,j)(m+1−max(i,j))/(m+1)); Stronge's law on coupled contacts (Liu, Zhao and
// Brogliato's distributing law, Hertz's η = 3/2) against what a cradle does: the struck ball
// stops and the last one leaves with nearly all the momentum.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fremond/fremond.hpp"
#include "support/why.hpp"

namespace fremond {
namespace {

double kinetic(const ImpactProblem& pb, const Eigen::VectorXd& v) {
  return 0.5 * v.dot(pb.M * v);
}

ImpactLaw stronge_hertz() {
  StrongeLaw s;
  s.e = 1.0;
  s.eta = 1.5;
  return ImpactLaw(s);
}

// Three equal balls, the first at 1 m/s: Newton (e = 1) gives G P = (2, 0), P = (4/3, 2/3) and
// (−1/3, 2/3, 2/3); Poisson (e = 1) doubles the compression percussion G⁻¹(1, 0) = (2/3, 1/3):
// the same answer.
TEST(BallChain, NewtonsCradleOfThreeUnderNewtonAndPoisson) {
  const std::vector<double> m(3, 1.0), v{1.0, 0.0, 0.0};
  const ImpactProblem pb = ball_chain(m, v);
  for (const ImpactLaw& law : {ImpactLaw::newton(1.0), ImpactLaw::poisson(1.0)}) {
    const ImpactResult r = solve_impact(pb, law);
    ASSERT_TRUE(r.ok()) << law.name();
    EXPECT_NEAR(r.qdot_E(0), -1.0 / 3, 1e-15) << law.name();
    EXPECT_NEAR(r.qdot_E(1), 2.0 / 3, 1e-15) << law.name();
    EXPECT_NEAR(r.qdot_E(2), 2.0 / 3, 1e-15) << law.name();
    EXPECT_NEAR(r.P_N(0), 4.0 / 3, 1e-15) << law.name();
    EXPECT_NEAR(r.P_N(1), 2.0 / 3, 1e-15) << law.name();
    EXPECT_NEAR(kinetic(pb, r.qdot_E), kinetic(pb, pb.qdot_A), 1e-15);
  }
}

// Five equal balls: P = 2 G⁻¹e₁ = (8, 6, 4, 2)/5 and (−3, 2, 2, 2, 2)/5 under Newton at e = 1.
TEST(BallChain, NewtonsCradleOfFiveUnderNewton) {
  const std::vector<double> m(5, 1.0), v{1.0, 0.0, 0.0, 0.0, 0.0};
  const ImpactResult r = solve_impact(ball_chain(m, v), ImpactLaw::newton(1.0));
  ASSERT_TRUE(r.ok());
  const double expected[5] = {-0.6, 0.4, 0.4, 0.4, 0.4};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(r.qdot_E(i), expected[i], 1e-15) << i;
}

// What a cradle does, which only the distributing law gives: the struck ball nearly stops, the
// last leaves with nearly all the speed; momentum and (e = 1) energy kept.
TEST(BallChain, NewtonsCradleUnderStrongesDistributingLaw) {
  for (const int n : {3, 5}) {
    std::vector<double> m(static_cast<std::size_t>(n), 1.0), v(static_cast<std::size_t>(n), 0.0);
    v[0] = 1.0;
    const ImpactProblem pb = ball_chain(m, v);
    const ImpactResult r = solve_impact(pb, stronge_hertz());
    ASSERT_TRUE(r.ok()) << n << ": " << r.solver.message;
    EXPECT_GT(r.qdot_E(n - 1), 0.9) << n;
    EXPECT_LT(std::abs(r.qdot_E(0)), 0.1) << n;
    EXPECT_NEAR(r.qdot_E.sum(), 1.0, 1e-12) << n;
    EXPECT_NEAR(kinetic(pb, r.qdot_E), kinetic(pb, pb.qdot_A), 1e-8) << n;
    for (int k = 0; k + 1 < n; ++k) EXPECT_GE(r.D_NE(k), -1e-12) << n << " contact " << k;
  }
}

// A ball dropped at 1 m/s on an equal ball resting on the ground. Contacts: between the balls (D_NA
// = −1), the ground (D_NA = 0). G = [[2, −1], [−1, 1]]; Newton at e = 1: G P = (2, 0), P = (2, 2):
// the bottom ball stays, the top one rebounds at 1 m/s.
TEST(BallChain, BallDroppedOnARestingBall) {
  const std::vector<double> m{1.0, 1.0}, v{0.0, -1.0};
  const ImpactProblem pb = ball_chain(m, v, true);
  const ImpactResult r = solve_impact(pb, ImpactLaw::newton(1.0));
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.qdot_E(0), 0.0, 1e-15);
  EXPECT_NEAR(r.qdot_E(1), 1.0, 1e-15);
  EXPECT_NEAR(r.P_N(0), 2.0, 1e-15);
  EXPECT_NEAR(r.P_N(1), 2.0, 1e-15);
  // Every law: a momentum balance with the ground's percussion, no penetration, and no energy
  // created where the law dissipates by construction.
  for (const ImpactLaw& law : {ImpactLaw::newton(0.8), ImpactLaw::poisson(0.8),
                               ImpactLaw::fremond(PowerPotential(4.0, 3.0)), stronge_hertz()}) {
    const ImpactResult s = solve_impact(pb, law);
    ASSERT_TRUE(s.ok()) << law.name() << ": " << s.solver.message;
    const Eigen::VectorXd balance = pb.M * (s.qdot_E - pb.qdot_A) - pb.W_N * s.P_N;
    EXPECT_LE(balance.lpNorm<Eigen::Infinity>(), 1e-12) << law.name();
    EXPECT_GE(s.D_NE.minCoeff(), -1e-12) << law.name();
    EXPECT_LE(kinetic(pb, s.qdot_E), kinetic(pb, pb.qdot_A) * (1 + 1e-9)) << law.name();
  }
}

TEST(BallChain, RefusesBadBallsNamingThem) {
  const std::vector<double> one{1.0}, two{1.0, 1.0}, bad{1.0, -2.0};
  auto name = [](auto&& f) { return testing::refused_name(f); };
  EXPECT_EQ(name([&] { ball_chain(one, one); }), "masses");
  EXPECT_EQ(name([&] { ball_chain(bad, two); }), "masses[1]");
  EXPECT_EQ(name([&] { ball_chain(two, one); }), "velocity");
  EXPECT_EQ(name([&] { ball_chain(one, one, true); }), "accepted");
}

}  // namespace
}  // namespace fremond
