// Anderson mixing (solvers/nsgs/anderson.hpp) on affine maps, whose fixed point has a closed form.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "solvers/nsgs/anderson.hpp"

namespace fremond::detail {
namespace {

// x ↦ A x + b with A symmetric, its eigenvalues spread over [0, 0.999]: the plain iteration gains
// a factor 0.999 a step (about 27,600 steps from 1 to 1e-12). Mixed, it is restarted GMRES on
// (I − A) x = b and reaches the fixed point (I − A)⁻¹ b to 1e-10 in a few hundred.
TEST(AndersonMixing, SlowAffineContractionReachesItsFixedPoint) {
  const int n = 40;
  const Eigen::MatrixXd Q =
      Eigen::HouseholderQR<Eigen::MatrixXd>(
          Eigen::MatrixXd::NullaryExpr(
              n, n,
              [](Eigen::Index i, Eigen::Index j) { return std::sin(1.0 + 3.0 * i + 7.0 * j * j); }))
          .householderQ();
  Eigen::VectorXd lambda(n);
  for (int k = 0; k < n; ++k) lambda(k) = 0.999 * k / (n - 1);
  const Eigen::MatrixXd A = Q * lambda.asDiagonal() * Q.transpose();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const Eigen::VectorXd fixed = (Eigen::MatrixXd::Identity(n, n) - A).lu().solve(b);

  AndersonMixing mixing(5);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n), g(n);
  int steps = 0;
  for (; steps < 2000 && (x - fixed).lpNorm<Eigen::Infinity>() > 1e-10; ++steps) {
    g = A * x + b;
    mixing.mix(x, g);
    x = g;
  }
  EXPECT_LE((x - fixed).lpNorm<Eigen::Infinity>(), 1e-10) << "after " << steps << " steps";
  // The plain iteration after as many steps is still far: what the mixing is for.
  Eigen::VectorXd plain = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < steps; ++k) plain = A * plain + b;
  EXPECT_GT((plain - fixed).lpNorm<Eigen::Infinity>(), 1e-3);
}

// The first call after reset() has no history: the next input is the map's output itself; and a
// non-finite residual leaves the output as it is and forgets the history.
TEST(AndersonMixing, WithoutHistoryTheOutputIsTheNextInput) {
  AndersonMixing mixing(3);
  const Eigen::VectorXd x = Eigen::VectorXd::Constant(4, 1.0);
  Eigen::VectorXd g = Eigen::VectorXd::LinSpaced(4, 0.0, 3.0);
  const Eigen::VectorXd out = g;
  mixing.mix(x, g);
  EXPECT_EQ(g, out);
  Eigen::VectorXd h = 0.5 * out;
  mixing.mix(out, h);  // now a difference is known: the mix moves the output
  EXPECT_NE(h, 0.5 * out);
  mixing.reset();
  Eigen::VectorXd k = out;
  mixing.mix(x, k);
  EXPECT_EQ(k, out);
  Eigen::VectorXd bad = out;
  bad(2) = std::numeric_limits<double>::quiet_NaN();
  const Eigen::VectorXd kept = bad;
  mixing.mix(x, bad);
  EXPECT_TRUE(std::isnan(bad(2)));
  EXPECT_EQ(bad(0), kept(0));
  EXPECT_EQ(bad(3), kept(3));
  Eigen::VectorXd after = out;
  mixing.mix(x, after);  // the history was forgotten: no mix
  EXPECT_EQ(after, out);
}

// On x ↦ x/2 + 1 (n = 1) two outputs determine the map: the third input is its fixed point 2.
TEST(AndersonMixing, ScalarAffineMapIsSolvedByOneMix) {
  AndersonMixing mixing(2);
  Eigen::VectorXd x(1), g(1);
  x << 0.0;
  g << 0.5 * x(0) + 1.0;  // 1
  mixing.mix(x, g);       // no history: next input 1
  x = g;
  g << 0.5 * x(0) + 1.0;  // 1.5
  mixing.mix(x, g);
  EXPECT_NEAR(g(0), 2.0, 1e-12);
}

}  // namespace
}  // namespace fremond::detail
