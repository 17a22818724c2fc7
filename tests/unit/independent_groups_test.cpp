// Independent groups of contacts (src/solvers/detail/independent_groups.hpp): a problem made of
// two bodies that do not touch each other separates, and each body must get the answer of its own
// problem, to its own velocity scale, whatever the other body's (docs/concepts.md and docs/laws.md:
// the laws read D_E = D_A + G P row by row, and G has no entry between the bodies).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "fremond/fremond.hpp"

namespace fremond {
namespace {

/// A point mass on the ground y = 0 in the plane, q = (x, y): D_NA = ẏ, D_TA = ẋ.
struct Body {
  double m, xdot, ydot;
};

ImpactProblem one_body(const Body& b) {
  ImpactProblem p;
  p.M = Eigen::Matrix2d::Identity() * b.m;
  p.W_N = Eigen::Vector2d(0.0, 1.0);
  p.W_T = Eigen::Vector2d(1.0, 0.0);
  p.qdot_A = Eigen::Vector2d(b.xdot, b.ydot);
  return p;
}

/// Both bodies in one problem, q = (x₁, y₁, x₂, y₂): M block-diagonal, one contact each.
ImpactProblem two_bodies(const Body& a, const Body& b) {
  ImpactProblem p;
  p.M = Eigen::Vector4d(a.m, a.m, b.m, b.m).asDiagonal();
  p.W_N = Eigen::MatrixXd::Zero(4, 2);
  p.W_T = Eigen::MatrixXd::Zero(4, 2);
  p.W_N(1, 0) = p.W_N(3, 1) = 1.0;
  p.W_T(0, 0) = p.W_T(2, 1) = 1.0;
  p.qdot_A = Eigen::Vector4d(a.xdot, a.ydot, b.xdot, b.ydot);
  return p;
}

// A body approaching at 1.5e5 m/s beside one at 3.7e-10 m/s, and the slow one sliding.
const Body kFast{2.0, 4.0e4, -1.5e5};
const Body kSlow{0.3, 2.0e-9, -3.7e-10};

struct NamedLaw {
  std::string name;
  ImpactLaw law;
};

std::vector<NamedLaw> laws() {
  std::vector<NamedLaw> v;
  v.push_back({"newton", ImpactLaw::newton(0.6)});
  v.push_back({"poisson", ImpactLaw::poisson(0.6)});
  v.push_back({"newton_coulomb", ImpactLaw::newton_coulomb(0.6, 0.4)});
  v.push_back({"poisson_coulomb", ImpactLaw::poisson_coulomb(0.6, 0.4)});
  v.push_back({"fremond", ImpactLaw::fremond(PowerPotential(3.0, 2.0))});
  // The dead zone's radius at the slow body's scale: the fast one slides far beyond it.
  v.push_back({"fremond_viscous", ImpactLaw::fremond(PowerPotential(3.0, 2.0),
                                                     DeadZonePowerPotential(0.5, 2.0, 1e-10))});
  v.push_back({"fremond_coulomb", ImpactLaw::fremond_coulomb(PowerPotential(3.0, 2.0), 0.4)});
  return v;
}

TEST(IndependentGroups, EachBodyGetsTheAnswerOfItsOwnProblem) {
  for (const auto& [name, law] : laws()) {
    SCOPED_TRACE(name);
    const ImpactResult both = solve_impact(two_bodies(kFast, kSlow), law);
    const ImpactResult fast = solve_impact(one_body(kFast), law);
    const ImpactResult slow = solve_impact(one_body(kSlow), law);
    ASSERT_TRUE(fast.ok() && slow.ok()) << fast.solver.message << " / " << slow.solver.message;
    ASSERT_TRUE(both.ok()) << both.solver.message;
    EXPECT_TRUE(both.admissibility.admissible);
    for (int i = 0; i < 2; ++i) {
      const double s_fast = std::fabs(kFast.ydot), s_slow = std::fabs(kSlow.ydot);
      EXPECT_NEAR(both.qdot_E(i), fast.qdot_E(i), 1e-13 * s_fast) << i;
      EXPECT_NEAR(both.qdot_E(2 + i), slow.qdot_E(i), 1e-13 * s_slow) << i;
    }
    EXPECT_NEAR(both.P_N(1), slow.P_N(0), 1e-13 * std::fabs(slow.P_N(0)));
    EXPECT_NEAR(both.P_T(1), slow.P_T(0), 1e-13 * std::fabs(slow.P_N(0)));
    // The slow body does not go on approaching at its own scale.
    EXPECT_GE(both.D_NE(1), -1e-13 * std::fabs(kSlow.ydot));
    EXPECT_EQ(both.unique, fast.unique && slow.unique);
    EXPECT_EQ(both.has_phases, fast.has_phases);
  }
}

TEST(IndependentGroups, SlowBodyBesideAFastOneByHand) {
  // Newton + Coulomb, G = I/m per contact: P_N = −(1 + e) m D_NA. The slow body slides
  // (m|D_TA| = 6e-10 > μ P_N = 0.4 · 1.6 · 0.3 · 3.7e-10 = 7.1e-11): P_T = −μ P_N and
  // D_TE = D_TA + P_T/m. The fast one sticks (m|D_TA| = 8e4 ≤ μ P_N = 1.92e5): P_T = −m D_TA.
  const double e = 0.6, mu = 0.4;
  const ImpactResult r = solve_impact(two_bodies(kFast, kSlow), ImpactLaw::newton_coulomb(e, mu));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  const double PN_slow = -(1 + e) * kSlow.m * kSlow.ydot;
  ASSERT_GT(kSlow.m * std::fabs(kSlow.xdot), mu * PN_slow);
  EXPECT_NEAR(r.P_N(1), PN_slow, 1e-14 * PN_slow);
  EXPECT_NEAR(r.P_T(1), -mu * PN_slow, 1e-14 * PN_slow);
  EXPECT_NEAR(r.D_NE(1), -e * kSlow.ydot, 1e-14 * std::fabs(kSlow.ydot));
  EXPECT_NEAR(r.D_TE(1), kSlow.xdot - mu * PN_slow / kSlow.m, 1e-14 * std::fabs(kSlow.xdot));
  const double PN_fast = -(1 + e) * kFast.m * kFast.ydot;
  EXPECT_NEAR(r.P_N(0), PN_fast, 1e-14 * PN_fast);
  EXPECT_NEAR(r.P_T(0), -kFast.m * kFast.xdot, 1e-14 * PN_fast);
  EXPECT_TRUE(r.unique);
}

TEST(IndependentGroups, AFrictionlessCornerSeparatesItsTwoWalls) {
  // One point mass against the floor (normal y) and a wall (normal x): G = I/m is diagonal, so
  // each wall is its own group though both act on the same body. Floor approached at 1e-9, wall
  // at 1e3: Newton's law gives D_NE = −e D_NA on each, each to its own scale.
  ImpactProblem p;
  p.M = Eigen::Matrix2d::Identity() * 0.7;
  p.W_N.resize(2, 2);
  p.W_N << 1.0, 0.0, 0.0, 1.0;
  p.W_T.resize(2, 0);
  p.qdot_A = Eigen::Vector2d(-1e3, -1e-9);
  for (const double e : {0.0, 0.5, 1.0}) {
    const ImpactResult r = solve_impact(p, ImpactLaw::newton(e));
    ASSERT_TRUE(r.ok()) << r.solver.message;
    EXPECT_NEAR(r.qdot_E(0), e * 1e3, 1e-15 * 1e3) << e;
    EXPECT_NEAR(r.qdot_E(1), e * 1e-9, 1e-15 * 1e-9) << e;
    EXPECT_NEAR(r.P_N(1), (1 + e) * 0.7e-9, 1e-15 * 0.7e-9) << e;
    EXPECT_TRUE(r.unique);
    EXPECT_TRUE(r.admissibility.admissible);
  }
}

TEST(IndependentGroups, EverySolutionIsOneOfEachBodysSolutions) {
  // Two bars (m = 1, l = 0.5, J = 1/12) touching at their lower end at θ = π/4 with D_NA = 0 and
  // sliding back, q̇_A = (−v, 0, 0): under Newton + Coulomb with μ = 2 each has two solutions, the
  // open contact and sticking with P = v (1.5, 2.5)/4 (ClassicalCoulomb.GrazingBar…), which loses
  // ½ P_T D_TA = 0.3125 v² (docs/concepts.md, eq. 9). At v = 1 and v = 1e-9 the problem has the
  // four pairs, most dissipative first, and solve_impact returns the first.
  const double l = 0.5, c = l * std::cos(std::numbers::pi / 4), v[2] = {1.0, 1e-9};
  ImpactProblem p;
  p.M =
      Eigen::VectorXd((Eigen::VectorXd(6) << 1.0, 1.0, 1.0 / 12.0, 1.0, 1.0, 1.0 / 12.0).finished())
          .asDiagonal();
  p.W_N = Eigen::MatrixXd::Zero(6, 2);
  p.W_T = Eigen::MatrixXd::Zero(6, 2);
  p.qdot_A = Eigen::VectorXd::Zero(6);
  for (int b = 0; b < 2; ++b) {
    p.W_N.col(b).segment(3 * b, 3) << 0.0, 1.0, -c;
    p.W_T.col(b).segment(3 * b, 3) << 1.0, 0.0, c;
    p.qdot_A(3 * b) = -v[b];
  }
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.5, 2.0);
  const std::vector<ImpactResult> all = solve_impact_all(p, law);
  ASSERT_EQ(all.size(), 4u);
  // (stick, stick), (stick, open), (open, stick), (open, open).
  const bool sticks[4][2] = {{true, true}, {true, false}, {false, true}, {false, false}};
  for (int s = 0; s < 4; ++s) {
    SCOPED_TRACE(s);
    const ImpactResult& r = all[s];
    EXPECT_TRUE(r.ok()) << r.solver.message;
    EXPECT_FALSE(r.unique);
    EXPECT_EQ(r.solutions_found, 4);
    double energy = 0.0;
    for (int b = 0; b < 2; ++b) {
      const double PN = sticks[s][b] ? 0.375 * v[b] : 0.0, PT = sticks[s][b] ? 0.625 * v[b] : 0.0;
      EXPECT_NEAR(r.P_N(b), PN, 1e-15 * v[b]) << b;
      EXPECT_NEAR(r.P_T(b), PT, 1e-15 * v[b]) << b;
      energy -= sticks[s][b] ? 0.3125 * v[b] * v[b] : 0.0;
    }
    EXPECT_NEAR(r.energy_change, energy, 1e-15);
  }
  const ImpactResult one = solve_impact(p, law);
  ASSERT_TRUE(one.ok());
  EXPECT_FALSE(one.unique);
  for (int b = 0; b < 2; ++b) EXPECT_NEAR(one.P_T(b), 0.625 * v[b], 1e-15 * v[b]) << b;
}

// A body whose answer's mode fixes its velocities (two contacts closed on two dofs, cond(M) = 2e9;
// classical_velocity_mode.hpp) beside a point mass: the whole answer keeps that body's velocities,
// which meet Newton's law to rounding, where the velocities made again from the gathered
// percussions miss it by 6e-7 of that body's velocity scale.
TEST(IndependentGroups, AGroupsVelocitiesSolvedForFirstAreKept) {
  ImpactProblem pb;
  pb.M = Eigen::Matrix3d::Zero();
  pb.M.topLeftCorner(2, 2) << 20020865.219324283, 12189185.166647436, 12189185.166647436,
      7421069.6412495691;
  pb.M(2, 2) = 1.0;
  pb.W_N = Eigen::MatrixXd::Zero(3, 3);
  pb.W_N.topLeftCorner(2, 2) << -0.82138343776774914, 0.67160663654018937, 0.71750379326275238,
      -0.15782769523263629;
  pb.W_N(2, 2) = 1.0;
  pb.qdot_A = Eigen::Vector3d(-4.5863067036418446e-12, -8.0835310028874393e-12, -1.0);
  const ImpactLaw law =
      ImpactLaw::newton(PerContact({0.20025873288569646, 0.21829989042951392, 0.5}));
  const ImpactResult r = solve_impact(pb, law);
  ASSERT_EQ(r.solver.status, SolverStatus::converged) << r.solver.message;
  const double slow = std::max(std::fabs(r.D_NA(0)), std::fabs(r.D_NA(1)));
  for (int i = 0; i < 2; ++i) {
    ASSERT_GT(r.P_N(i), 0.0);
    EXPECT_NEAR(r.D_NE(i), -law.get<RestitutionLaw>().e[i] * r.D_NA(i), 1e-15 * slow) << i;
  }
  EXPECT_DOUBLE_EQ(r.qdot_E(2), 0.5);
  EXPECT_DOUBLE_EQ(r.P_N(2), 1.5);
  EXPECT_LE(law_residual(pb, law, r), 1e-14);
}

/// A point mass in a wedge: the ground y = 0 (contact 0) and a ceiling of normal (0.8, −0.6)
/// (contact 1), which it leaves at first (D_NA = 0.8 ẋ − 0.6 ẏ > 0); `scale` multiplies the
/// velocities. Two such bodies side by side where `pair`, q = (x₁, y₁, x₂, y₂), the second at 1e-9
/// of the first's velocities.
ImpactProblem wedge(double m, bool pair, double scale = 1.0) {
  const int n = pair ? 4 : 2, c = pair ? 4 : 2;
  ImpactProblem p;
  p.M = Eigen::MatrixXd::Identity(n, n) * m;
  p.W_N = Eigen::MatrixXd::Zero(n, c);
  p.W_T = Eigen::MatrixXd::Zero(n, c);
  p.qdot_A.resize(n);
  for (int b = 0; b < (pair ? 2 : 1); ++b) {
    p.W_N(2 * b + 1, 2 * b) = 1.0;
    p.W_T(2 * b, 2 * b) = 1.0;
    p.W_N(2 * b, 2 * b + 1) = 0.8;
    p.W_N(2 * b + 1, 2 * b + 1) = -0.6;
    p.W_T(2 * b, 2 * b + 1) = 0.6;
    p.W_T(2 * b + 1, 2 * b + 1) = 0.8;
    const double s = scale * (b == 0 ? 1.0 : 1e-9);
    p.qdot_A.segment(2 * b, 2) = s * Eigen::Vector2d(0.1, -1.0);
  }
  return p;
}

TEST(IndependentGroups, SolvedAgainOnEveryContactEachBodyKeepsItsOwnScale) {
  // Bouncing off the ground, each body is driven into the ceiling it was leaving (ẏ_E > 0 with ẋ
  // small), so the impact is solved again on every contact; there too the two bodies are
  // independent, and the slow one must get its own problem's answer to its own scale.
  for (const auto& [name, law] : laws()) {
    SCOPED_TRACE(name);
    const ImpactResult fast = solve_impact(wedge(0.3, false), law);
    const ImpactResult slow = solve_impact(wedge(0.3, false, 1e-9), law);
    ASSERT_TRUE(fast.ok() && slow.ok()) << fast.solver.message << " / " << slow.solver.message;
    // The case is the one it means to be: the ceiling stops each body alone.
    ASSERT_GT(fast.P_N(1), 0.0);
    ASSERT_GT(slow.P_N(1), 0.0);
    const ImpactResult both = solve_impact(wedge(0.3, true), law);
    ASSERT_TRUE(both.ok()) << both.solver.message;
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(both.qdot_E(i), fast.qdot_E(i), 1e-12) << i;
      EXPECT_NEAR(both.qdot_E(2 + i), slow.qdot_E(i), 1e-12 * 1e-9) << i;
      EXPECT_NEAR(both.P_N(2 + i), slow.P_N(i), 1e-12 * std::fabs(slow.P_N(0))) << i;
    }
    // Neither body ends in its ceiling, each to its own scale.
    EXPECT_GE(both.D_NE(1), -1e-13);
    EXPECT_GE(both.D_NE(3), -1e-13 * 1e-9);
  }
}

TEST(IndependentGroups, CoupledContactsAreSolvedTogether) {
  // The flat bar on both ends: G couples the ends, one group, Newton's frictionless law on two
  // contacts. With e = 0 both ends come to rest: the bar's ẏ and θ̇ after are 0.
  ImpactProblem p;
  p.M = Eigen::Vector3d(1.0, 1.0, 1.0 / 12.0).asDiagonal();
  p.W_N.resize(3, 2);
  p.W_N << 0.0, 0.0, 1.0, 1.0, 0.5, -0.5;
  p.W_T.resize(3, 0);
  p.qdot_A = Eigen::Vector3d(2.0, -3.0, 1.0);
  const ImpactResult r = solve_impact(p, ImpactLaw::newton(0.0));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_NEAR(r.qdot_E(1), 0.0, 1e-14);
  EXPECT_NEAR(r.qdot_E(2), 0.0, 1e-14);
  EXPECT_NEAR(r.qdot_E(0), 2.0, 0.0);
  // ΣP_N = m·3 and the torque balance 0.5 (P₀ − P₁) = J θ̇_A = 1/12.
  EXPECT_NEAR(r.P_N(0) + r.P_N(1), 3.0, 1e-14);
  EXPECT_NEAR(0.5 * (r.P_N(0) - r.P_N(1)), -1.0 / 12.0, 1e-14);
}

}  // namespace
}  // namespace fremond
