// The small LU of semismooth Newton (src/core/detail/small_lu.hpp) against Eigen's full-pivoting
// LU and the explicit inverse: solutions to rounding, the exact 1-norm condition number, and
// singular matrices reported as such.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

#include "core/detail/small_full_piv_lu.hpp"
#include "core/detail/small_lu.hpp"

namespace {

using fremond::detail::SmallLU;
using Mat = SmallLU<8>::Mat;
using Vec = SmallLU<8>::Vec;

TEST(SmallLU, SolvesRandomSystemsAndGivesTheExactConditionNumber) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 1 + trial % 8;
    Mat A(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = u(gen);
    Vec b(n);
    for (int i = 0; i < n; ++i) b(i) = u(gen);
    SmallLU<8> lu;
    lu.compute(A);
    ASSERT_FALSE(lu.singular());
    Vec x;
    lu.solve(b, x);
    const Eigen::MatrixXd Ad = A;
    const Eigen::FullPivLU<Eigen::MatrixXd> ref(Ad);
    const Eigen::VectorXd xr = ref.solve(Eigen::VectorXd(b));
    const Eigen::MatrixXd inv = ref.inverse();
    const double cond1 =
        Ad.cwiseAbs().colwise().sum().maxCoeff() * inv.cwiseAbs().colwise().sum().maxCoeff();
    // Backward-stable solves: the difference is bounded by the conditioning.
    EXPECT_LE((Eigen::VectorXd(x) - xr).norm(), 1e-13 * cond1 * (1.0 + xr.norm())) << trial;
    EXPECT_NEAR(lu.rcond() * cond1, 1.0, 1e-10 * cond1) << trial;
  }
}

TEST(SmallLU, PermutedTriangularSystemIsSolvedExactly) {
  // Pivoting swaps the rows; the answer (1, 2, 3) is exact in binary.
  Mat A(3, 3);
  A << 0, 0, 4, 2, 0, 0, 1, 1, 0;
  Vec b(3);
  b << 12, 2, 3;
  SmallLU<8> lu;
  lu.compute(A);
  Vec x = Vec::Zero(3);  // zeros only to quiet GCC 12's -Wmaybe-uninitialized: solve writes x
  lu.solve(b, x);
  EXPECT_EQ(x(0), 1.0);
  EXPECT_EQ(x(1), 2.0);
  EXPECT_EQ(x(2), 3.0);
  // ‖A‖₁ = 4, A⁻¹ = [[0, .5, 0], [0, -.5, 1], [.25, 0, 0]], ‖A⁻¹‖₁ = 1: rcond = 1/4.
  EXPECT_DOUBLE_EQ(lu.rcond(), 0.25);
}

TEST(SmallLU, SingularMatricesHaveZeroReciprocalCondition) {
  Mat A(2, 2);
  A << 1, 2, 2, 4;  // the flat bar sticking with both ends: two identical rows, up to scale
  SmallLU<8> lu;
  lu.compute(A);
  EXPECT_TRUE(lu.singular());
  EXPECT_EQ(lu.rcond(), 0.0);
  Mat Z = Mat::Zero(3, 3);
  lu.compute(Z);
  EXPECT_TRUE(lu.singular());
  EXPECT_EQ(lu.rcond(), 0.0);
  Mat N(1, 1);
  N << std::numeric_limits<double>::quiet_NaN();
  lu.compute(N);
  EXPECT_TRUE(lu.singular());
}

TEST(SmallLU, NearlySingularMatrixIsBelowNewtonsThreshold) {
  // rows differing by 1e-14: cond₁ ≈ 4e14, below semismooth Newton's rcond threshold of 1e-12.
  Mat A(2, 2);
  A << 1, 1, 1, 1 + 1e-14;
  SmallLU<8> lu;
  lu.compute(A);
  EXPECT_FALSE(lu.singular());
  EXPECT_LT(lu.rcond(), 1e-12);
  EXPECT_GT(lu.rcond(), 1e-16);
}

TEST(SmallLU, TwoRowsGiveTheGeneralLoopsBits) {
  // Two rows run the loops of length 2, three rows those of length 3: embedded as [A 0; 0 1], the
  // same A goes through the 3-row loops (the third row and column add exact zeros), and both
  // solutions agree to the bit, row swaps included. Its rcond is the exact one
  // (checked against the explicit inverse above for n = 2 too).
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> expo(-30, 30);
  int swaps = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Mat A(2, 2), B = Mat::Zero(3, 3);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) A(i, j) = B(i, j) = std::ldexp(u(gen), expo(gen));
    B(2, 2) = 1.0;
    swaps += std::fabs(A(1, 0)) > std::fabs(A(0, 0));
    Vec b(2), b3 = Vec::Zero(3);
    b(0) = b3(0) = u(gen);
    b(1) = b3(1) = u(gen);
    SmallLU<8> lu2, lu3;
    lu2.compute(A);
    lu3.compute(B);
    ASSERT_EQ(lu2.singular(), lu3.singular()) << trial;
    if (lu2.singular()) continue;
    Vec x2, x3;
    lu2.solve(b, x2);
    lu3.solve(b3, x3);
    ASSERT_EQ(x2.size(), 2);
    EXPECT_EQ(x2(0), x3(0)) << trial;
    EXPECT_EQ(x2(1), x3(1)) << trial;
    EXPECT_EQ(x3(2), 0.0);
  }
  EXPECT_GT(swaps, 500);  // both pivot orders were exercised
}

TEST(SmallLU, UnrolledSizesGiveTheRunTimeLoopsBits) {
  // Sizes 3 … 8 of the stack-stored form run loops of compile-time length; the dynamic form runs
  // the same loops with run-time bounds. Same operations in the same order: the same bits for the
  // solution and the condition number, also on badly scaled matrices that pivot.
  std::mt19937 gen(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> expo(-20, 20);
  for (int trial = 0; trial < 600; ++trial) {
    const int n = 3 + trial % 6;
    Mat A(n, n);
    Eigen::MatrixXd D(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = D(i, j) = std::ldexp(u(gen), expo(gen));
    Vec b(n);
    for (int i = 0; i < n; ++i) b(i) = u(gen);
    SmallLU<8> fixed;
    SmallLU<Eigen::Dynamic> dynamic;
    fixed.compute(A);
    dynamic.compute(D);
    ASSERT_EQ(fixed.singular(), dynamic.singular()) << trial;
    if (fixed.singular()) continue;
    Vec x;
    Eigen::VectorXd y;
    fixed.solve(b, x);
    dynamic.solve(Eigen::VectorXd(b), y);
    for (int i = 0; i < n; ++i) ASSERT_EQ(x(i), y(i)) << trial << " row " << i;
    EXPECT_EQ(fixed.rcond(), dynamic.rcond()) << trial;
  }
}

TEST(SmallFullPivLU, GivesFullPivLUsRankAndSolutionOnSingularConsistentSystems) {
  // Semismooth Newton's singular steps (src/solvers/fremond_iterative.cpp): rank-deficient
  // matrices with repeated rows (two contacts sticking with one tangent), repeated columns and
  // ties of the largest entry, and right-hand sides in the range. Eigen's FullPivLU is the
  // reference: the same rank, and the same particular solution (the same pivots, so the same free
  // unknowns set to zero) to rounding; A x = b to rounding.
  std::mt19937 gen(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int deficient = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    const int n = 1 + trial % 8;
    const int rank = 1 + static_cast<int>(gen() % n);
    Eigen::MatrixXd B(n, rank), C(rank, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < rank; ++j) B(i, j) = u(gen);
    for (int i = 0; i < rank; ++i)
      for (int j = 0; j < n; ++j) C(i, j) = u(gen);
    Eigen::MatrixXd A = B * C;
    if (trial % 3 == 0 && n > 1) A.row(n - 1) = A.row(0);  // an exact repeat of a row
    if (trial % 5 == 0 && n > 1) A.col(n - 1) = A.col(0);  // an exact repeat of a column
    if (trial % 7 == 0) A.setConstant(0.5);                // every entry ties
    const Eigen::VectorXd x0 = Eigen::VectorXd::NullaryExpr(n, [&] { return u(gen); });
    const Eigen::VectorXd b = A * x0;  // consistent
    const Eigen::FullPivLU<Eigen::MatrixXd> ref(A);
    const Eigen::VectorXd xr = ref.solve(b);
    fremond::detail::SmallFullPivLU<8> lu;
    lu.compute(Mat(A));
    Vec x;
    lu.solve(Vec(b), x);
    ASSERT_EQ(lu.rank(), ref.rank()) << trial;
    deficient += ref.rank() < n;
    const double scale = 1.0 + xr.cwiseAbs().maxCoeff();
    EXPECT_LE((Eigen::VectorXd(x) - xr).cwiseAbs().maxCoeff(), 1e-9 * scale) << trial;
    EXPECT_LE((A * Eigen::VectorXd(x) - b).cwiseAbs().maxCoeff(),
              1e-12 * (1.0 + A.cwiseAbs().maxCoeff() * x.cwiseAbs().maxCoeff()))
        << trial;
  }
  EXPECT_GT(deficient, 800);
  fremond::detail::SmallFullPivLU<8> zero;
  zero.compute(Mat::Zero(3, 3));
  Vec x;
  zero.solve(Vec::Ones(3), x);
  EXPECT_EQ(zero.rank(), 0);
  EXPECT_EQ(x.cwiseAbs().maxCoeff(), 0.0);
}

TEST(SmallLU, WellConditionedIsRcondAboveTheThreshold) {
  // The pivots' screen decides only where rcond is at most half the threshold: on random matrices
  // made nearly singular by a row close to another (distance 10^-k), the answer is rcond()'s for
  // every threshold semismooth Newton and the classical refinement use, on both sides of it.
  std::mt19937 gen(19);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int below = 0, above = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = 2 + trial % 7;
    Mat A(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = u(gen);
    const double delta = std::pow(10.0, -static_cast<double>(trial % 17));
    for (int j = 0; j < n; ++j) A(n - 1, j) = A(0, j) + delta * u(gen);
    SmallLU<8> lu;
    lu.compute(A);
    for (double t : {1e-12, 1e-14, 64 * std::numeric_limits<double>::epsilon()}) {
      const bool expected = !lu.singular() && lu.rcond() > t;
      ASSERT_EQ(lu.well_conditioned(t), expected) << trial << " threshold " << t;
      (expected ? above : below) += 1;
    }
  }
  EXPECT_GT(below, 1000);
  EXPECT_GT(above, 1000);
}

TEST(SmallLU, WellConditionedDecidesAsRcondJustAboveAndBelowIt) {
  // Thresholds at 0.3, 0.9, 1.1 and 3 times each matrix's own rcond: the bounds that skip A⁻¹
  // (pivots below, comparison matrices above) must leave every one of these to rcond(), so a bound
  // on ‖A⁻¹‖₁ that fell short of it by a factor 2.2 would answer "yes" at 1.1 here.
  std::mt19937 gen(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 4000; ++trial) {
    const int n = 1 + trial % 8;
    Mat A(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = u(gen) * std::pow(10.0, 3 * u(gen));
    if (n > 1 && trial % 3 == 0) {
      const double delta = std::pow(10.0, -static_cast<double>(trial % 13));
      for (int j = 0; j < n; ++j) A(n - 1, j) = A(0, j) + delta * u(gen);
    }
    SmallLU<8> lu;
    lu.compute(A);
    if (lu.singular()) continue;
    const double rc = lu.rcond();
    ASSERT_GT(rc, 0.0) << trial;
    for (const double f : {0.3, 0.9, 1.1, 3.0})
      ASSERT_EQ(lu.well_conditioned(f * rc), rc > f * rc) << trial << " factor " << f;
  }
}

}  // namespace
