// Newton's law on one contact of a body with a diagonal M (docs/solvers.md: the chain's first stage
// there works on scalars). Its answers against a second method: the same impact written in rotated
// coordinates q = Q y, where M becomes Qᵀ M Q (no longer diagonal) and the contact modes solve it.
// Percussions and contact velocities do not depend on the coordinates; velocities map by Q.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <random>

#include "fremond/solvers/solve_impact.hpp"

namespace fremond {
namespace {

struct Pair {
  ImpactProblem diagonal, rotated;
  Eigen::MatrixXd Q;
};

// A random impact of one approaching contact on n dofs with a diagonal M, and the same impact in
// rotated coordinates. `tangent`: W_T given; `moving`: the obstacle's velocity terms w given.
Pair random_pair(std::mt19937& rng, int n, bool tangent, bool moving) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> decade(-2.0, 2.0);
  Pair p;
  ImpactProblem& pb = p.diagonal;
  pb.M = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) pb.M(i, i) = std::pow(10.0, decade(rng));
  pb.W_N = Eigen::MatrixXd(n, 1);
  for (int i = 0; i < n; ++i) pb.W_N(i, 0) = normal(rng);
  if (tangent) {
    pb.W_T = Eigen::MatrixXd(n, 1);
    for (int i = 0; i < n; ++i) pb.W_T(i, 0) = normal(rng);
  } else {
    pb.W_T = Eigen::MatrixXd(n, 0);
  }
  if (moving) {
    pb.w_N = Eigen::VectorXd::Constant(1, 0.3 * normal(rng));
    if (tangent) pb.w_T = Eigen::VectorXd::Constant(1, 0.3 * normal(rng));
  }
  pb.qdot_A = Eigen::VectorXd(n);
  for (int i = 0; i < n; ++i) pb.qdot_A(i) = normal(rng);
  // Approaching: D_NA = W_Nᵀq̇_A + w_N < 0, by moving q̇_A along M⁻¹W_N where it is not.
  const double w = moving ? pb.w_N(0) : 0.0;
  const double dna = pb.W_N.col(0).dot(pb.qdot_A) + w;
  if (dna >= 0.0) {
    const Eigen::VectorXd dir = pb.M.diagonal().cwiseInverse().cwiseProduct(pb.W_N.col(0));
    pb.qdot_A -= (dna + 0.5 + std::fabs(normal(rng))) / pb.W_N.col(0).dot(dir) * dir;
  }
  p.Q = Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd::NullaryExpr(n, n, [&] {
          return normal(rng);
        })).householderQ();
  ImpactProblem& r = p.rotated;
  r = pb;
  r.M = p.Q.transpose() * pb.M * p.Q;
  r.M = 0.5 * (r.M + r.M.transpose()).eval();
  r.W_N = p.Q.transpose() * pb.W_N;
  if (tangent) r.W_T = p.Q.transpose() * pb.W_T;
  r.qdot_A = p.Q.transpose() * pb.qdot_A;
  return p;
}

TEST(ClassicalOneContact, DiagonalMassAgreesWithTheContactModesInRotatedCoordinates) {
  std::mt19937 rng(20261205);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int compared = 0, sliding = 0, sticking = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const int n = 1 + trial % 6;
    const bool tangent = n > 1 && trial % 5 != 0, moving = trial % 7 == 0;
    const Pair p = random_pair(rng, n, tangent, moving);
    const double e = unit(rng), mu = 1.5 * unit(rng);
    const bool friction = tangent && trial % 3 != 0, poisson = trial % 2 == 1;
    const ImpactLaw law =
        poisson ? (friction ? ImpactLaw::poisson_coulomb(e, mu) : ImpactLaw::poisson(e))
                : (friction ? ImpactLaw::newton_coulomb(e, mu) : ImpactLaw::newton(e));
    const ImpactResult a = solve_impact(p.diagonal, law), b = solve_impact(p.rotated, law);
    ASSERT_TRUE(a.ok()) << "trial " << trial << ": " << a.solver.message;
    ASSERT_TRUE(b.ok()) << "trial " << trial << ": " << b.solver.message;
    const double v = std::max(std::fabs(a.D_NA(0)), std::fabs(a.D_TA(0)));
    const double pscale = std::max(std::fabs(b.P_N(0)), std::fabs(b.P_T(0)));
    const double q =
        std::max(p.diagonal.qdot_A.cwiseAbs().maxCoeff(), a.qdot_E.cwiseAbs().maxCoeff());
    // The rotation costs a few ε cond(M) ≤ 1e4·ε of the velocities.
    EXPECT_NEAR(a.P_N(0), b.P_N(0), 1e-10 * pscale) << "trial " << trial;
    EXPECT_NEAR(a.P_T(0), b.P_T(0), 1e-10 * pscale) << "trial " << trial;
    EXPECT_NEAR(a.D_NE(0), b.D_NE(0), 1e-10 * v) << "trial " << trial;
    EXPECT_NEAR(a.D_TE(0), b.D_TE(0), 1e-10 * v) << "trial " << trial;
    EXPECT_LE((a.qdot_E - p.Q * b.qdot_E).cwiseAbs().maxCoeff(), 1e-10 * q) << "trial " << trial;
    EXPECT_NEAR(a.energy_change, b.energy_change,
                1e-10 * std::max(a.admissibility.kinetic_energy_A, 1e-300))
        << "trial " << trial;
    if (poisson) {
      // Both phases, and the compression's end: D_NC = 0 on the closed normal row.
      EXPECT_NEAR(a.P_NC(0), b.P_NC(0), 1e-10 * pscale) << "trial " << trial;
      EXPECT_NEAR(a.P_TC(0), b.P_TC(0), 1e-10 * pscale) << "trial " << trial;
      EXPECT_NEAR(a.D_NC(0), 0.0, 1e-12 * v) << "trial " << trial;
      EXPECT_LE((a.qdot_C - p.Q * b.qdot_C).cwiseAbs().maxCoeff(), 1e-10 * q) << "trial " << trial;
    } else {
      EXPECT_NEAR(a.D_NE(0), -e * a.D_NA(0), 1e-12 * v) << "trial " << trial;  // eq. 5
    }
    EXPECT_LE(a.solver.residual, 1e-12);
    EXPECT_EQ(a.unique, b.unique) << "trial " << trial;
    EXPECT_EQ(a.admissibility.admissible, b.admissibility.admissible) << "trial " << trial;
    EXPECT_EQ(a.admissibility.failed, b.admissibility.failed) << "trial " << trial;
    if (law.has_friction()) {
      const bool slides = std::fabs(a.D_TE(0)) > 1e-9 * v;
      sliding += slides;
      sticking += !slides;
    }
    ++compared;
  }
  EXPECT_EQ(compared, 600);
  // Both regimes of Coulomb's law were met.
  EXPECT_GT(sliding, 50);
  EXPECT_GT(sticking, 50);
}

}  // namespace
}  // namespace fremond
