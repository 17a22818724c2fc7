// The Cholesky factor of the contact space and of G (src/core/detail/cholesky.hpp): the hand loops
// of the stack sizes against Eigen's LLT (the factor to rounding, L Lᵀ = A, solves), the same
// refusal of matrices that are not positive definite, and the heap sizes going through Eigen
// itself.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <cmath>
#include <limits>
#include <random>

#include "core/detail/cholesky.hpp"
#include "core/detail/refined_solve.hpp"

namespace {

using fremond::MatT;
using fremond::VecT;
using fremond::detail::CholeskyT;
using Small = CholeskyT<6>;

// A random SPD matrix of size n with condition number about 10^decades.
Eigen::MatrixXd random_spd(int n, double decades, std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = u(gen);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
  const Eigen::MatrixXd Q = qr.householderQ();
  Eigen::VectorXd d(n);
  for (int i = 0; i < n; ++i) d(i) = std::pow(10.0, -decades * i / std::max(1, n - 1));
  const Eigen::MatrixXd S = Q * d.asDiagonal() * Q.transpose();
  return 0.5 * (S + S.transpose());  // exactly symmetric: the factor reads one triangle only
}

TEST(Cholesky, FactorAndSolvesAgreeWithEigenOnRandomSpdMatrices) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 600; ++trial) {
    const int n = 1 + trial % 6;
    const double decades = (trial / 6) % 10;  // κ from 1 to 1e9
    const Eigen::MatrixXd Ad = random_spd(n, decades, gen) * std::pow(10.0, (trial % 7) * 50 - 150);
    const MatT<6, 6> A = Ad;
    const Small chol(A);
    ASSERT_EQ(chol.info(), Eigen::Success) << trial;
    const Eigen::LLT<Eigen::MatrixXd> ref(Ad);
    const Eigen::MatrixXd L = Eigen::MatrixXd(chol.matrixLLT()).triangularView<Eigen::Lower>();
    const Eigen::MatrixXd Lr = ref.matrixL();
    const double eps = std::numeric_limits<double>::epsilon();
    // Both are backward stable: L Lᵀ = A to rounding of |L||Lᵀ|, and each factor within n·κ·ε of
    // the other (relative to ‖L‖).
    const Eigen::MatrixXd LLt_abs = L.cwiseAbs() * L.cwiseAbs().transpose();
    EXPECT_LE(((L * L.transpose() - Ad).cwiseAbs() - 8 * n * eps * LLt_abs).maxCoeff(), 0.0)
        << trial;
    const double kappa = std::pow(10.0, decades);
    EXPECT_LE((L - Lr).norm(), 64 * n * eps * kappa * Lr.norm()) << trial;
    // The upper triangle keeps A's entries, as Eigen's matrixLLT().
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) EXPECT_EQ(chol.matrixLLT()(i, j), A(i, j));
    VecT<6> b(n);
    for (int i = 0; i < n; ++i) b(i) = u(gen);
    const Eigen::VectorXd x = chol.solve(b), xr = ref.solve(Eigen::VectorXd(b));
    EXPECT_LE((x - xr).norm(), 64 * n * eps * kappa * xr.norm()) << trial;
    // The two triangular halves compose to the solve.
    VecT<6> y = b;
    chol.solve_lower_in_place(y);
    chol.solve_upper_in_place(y);
    EXPECT_EQ((Eigen::VectorXd(y) - x).cwiseAbs().maxCoeff(), 0.0) << trial;
  }
}

// Sizes 1-4 factor and substitute with their trip counts fixed at compile time: the same
// operations in the same order as the runtime-size loops, so the same bits. Checked against the
// unblocked loop written out here and against small_dense's runtime-size substitutions, on
// matrices of every size the stack storage takes (5 and 6 take the runtime path).
TEST(Cholesky, FixedSizePathsGiveTheBitsOfTheRuntimeLoops) {
  std::mt19937 gen(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 1200; ++trial) {
    const int n = 1 + trial % 6;
    const Eigen::MatrixXd Ad = random_spd(n, (trial / 6) % 10, gen);
    Eigen::MatrixXd L = Ad;  // Eigen's llt_inplace<Lower>::unblocked, summed in index order
    for (int k = 0; k < n; ++k) {
      double x = L(k, k);
      for (int j = 0; j < k; ++j) x -= L(k, j) * L(k, j);
      x = std::sqrt(x);
      L(k, k) = x;
      for (int i = k + 1; i < n; ++i) {
        double s = L(i, k);
        for (int j = 0; j < k; ++j) s -= L(i, j) * L(k, j);
        L(i, k) = s / x;
      }
    }
    const MatT<6, 6> A = Ad;
    const Small chol(A);
    ASSERT_EQ(chol.info(), Eigen::Success) << trial;
    for (int j = 0; j < n; ++j)
      for (int i = j; i < n; ++i) ASSERT_EQ(chol.matrixLLT()(i, j), L(i, j)) << trial;
    MatT<6, 6> B(n, 3), X(n, 3);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) B(i, k) = u(gen);
    X = B;
    chol.solve_lower_in_place(X);
    MatT<6, 6> Y = B;
    fremond::detail::small_dense::forward_substitute(chol.matrixLLT(), Y);
    EXPECT_EQ((X - Y).cwiseAbs().maxCoeff(), 0.0) << trial;
    chol.solve_upper_in_place(X);
    fremond::detail::small_dense::backward_substitute_transposed(chol.matrixLLT(), Y);
    EXPECT_EQ((X - Y).cwiseAbs().maxCoeff(), 0.0) << trial;
  }
}

TEST(Cholesky, RefusesWhatIsNotPositiveDefiniteAsEigenDoes) {
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int refused = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 1 + trial % 6;
    Eigen::MatrixXd Ad = random_spd(n, 3, gen);
    switch (trial % 4) {
      case 0:  // an indefinite diagonal
        Ad(n - 1, n - 1) = -Ad(n - 1, n - 1);
        break;
      case 1:  // negative definite
        Ad = -Ad;
        break;
      case 2:  // zero: the first pivot is 0
        Ad.setZero(n, n);
        break;
      default:  // eigenvalues in [1e-3, 1], shifted by −2e-3: indefinite
        Ad -= 2e-3 * Eigen::MatrixXd::Identity(n, n);
        break;
    }
    const MatT<6, 6> A = Ad;
    const Small chol(A);
    const Eigen::LLT<Eigen::MatrixXd> ref(Ad);
    EXPECT_EQ(chol.info(), ref.info()) << trial;
    refused += chol.info() != Eigen::Success;
  }
  EXPECT_GT(refused, 390);  // every case but an occasional shift that stays positive definite
}

TEST(Cholesky, HeapSizesAreEigensOwnFactor) {
  std::mt19937 gen(3);
  const Eigen::MatrixXd A = random_spd(9, 4, gen);
  const CholeskyT<fremond::Dynamic> chol(A);
  const Eigen::LLT<Eigen::MatrixXd> ref(A);
  ASSERT_EQ(chol.info(), Eigen::Success);
  EXPECT_EQ((chol.matrixLLT() - ref.matrixLLT()).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(9, -1.0, 1.0);
  EXPECT_EQ((chol.solve(b) - ref.solve(b)).cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace

// matrix_is_diagonal() stands in for is_diagonal(M) in the contact space (whether M⁻¹W is
// refined): both triangles, so a mass matrix symmetric only to its validation's 1e-12 with a
// diagonal lower triangle is not diagonal. Stack and heap storage alike.
TEST(Cholesky, MatrixIsDiagonalReadsBothTriangles) {
  for (int n = 1; n <= 6; ++n)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        Eigen::MatrixXd A = Eigen::MatrixXd::Identity(n, n) * 2.0;
        if (i != j) A(i, j) = 1e-13;  // one entry off the diagonal, in either triangle
        const Small small(A);
        const CholeskyT<fremond::Dynamic> heap(A);
        const bool diagonal = i == j;
        EXPECT_EQ(small.matrix_is_diagonal(), diagonal) << "n = " << n << " at " << i << "," << j;
        EXPECT_EQ(heap.matrix_is_diagonal(), diagonal) << "n = " << n << " at " << i << "," << j;
        EXPECT_EQ(small.info(), Eigen::Success);
      }
}

// condition_bound() decides where M⁻¹B is refined (refined_solve.hpp): it must never fall below
// cond₂(A), which the eigenvalues give here, and its looseness is at most ‖A‖₁/‖A‖₂ ≤ √n times
// ‖L⁻¹‖_F²/‖L⁻¹‖₂² ≤ n. Stack and heap storage, κ from 1 to 1e9, scales from 1e-150 to 1e150.
TEST(Cholesky, ConditionBoundHoldsTheConditionNumberWithinTheSize) {
  std::mt19937 gen(29);
  for (int trial = 0; trial < 420; ++trial) {
    const int n = 2 + trial % 30;  // n = 1 is diagonal
    const double decades = (trial / 30) % 10;
    const Eigen::MatrixXd A = random_spd(n, decades, gen) * std::pow(10.0, (trial % 7) * 50 - 150);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
    const double kappa = eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
    const CholeskyT<fremond::Dynamic> heap(A);
    ASSERT_EQ(heap.info(), Eigen::Success) << trial;
    if (heap.matrix_is_diagonal()) continue;  // κ = 1 can round to exactly diagonal
    const double bound = heap.condition_bound();
    EXPECT_GE(bound, kappa * (1 - 1e-6)) << trial;
    EXPECT_LE(bound, n * std::sqrt(double(n)) * kappa * (1 + 1e-6)) << trial;
    if (n <= 6) {
      // The two factors' inverses agree to about κε.
      EXPECT_NEAR(Small(MatT<6, 6>(A)).condition_bound(), bound, 1e-14 * kappa * bound) << trial;
    }
  }
  // A diagonal matrix's solves are divisions and need no bound; a failed factor has none.
  EXPECT_EQ(Small(MatT<6, 6>(Eigen::MatrixXd::Identity(3, 3))).condition_bound(),
            std::numeric_limits<double>::infinity());
  Eigen::MatrixXd indefinite = Eigen::MatrixXd::Identity(3, 3);
  indefinite(0, 1) = indefinite(1, 0) = 2.0;
  EXPECT_EQ(CholeskyT<fremond::Dynamic>(indefinite).condition_bound(),
            std::numeric_limits<double>::infinity());
}

// Where the bound is at most kPlainSolveCondition, refine_solve leaves the plain solve: that is
// sound only if the plain solve is then within kPlainSolveCondition·ε of M⁻¹B, relative to each
// column. Checked against a solve in extended precision on matrices at the threshold.
TEST(Cholesky, PlainSolvesUnderTheConditionThresholdAreAccurate) {
  using Long = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  std::mt19937 gen(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double eps = std::numeric_limits<double>::epsilon();
  int plain = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 600; ++trial) {
    const int n = 2 + trial % 24;
    // κ up to the threshold over n, where the bound reaches the threshold.
    const double decades = std::log10(fremond::detail::kPlainSolveCondition / n) * (trial % 5) / 4;
    const Eigen::MatrixXd M = random_spd(n, decades, gen);
    const CholeskyT<fremond::Dynamic> llt(M);
    Eigen::MatrixXd B(n, 4);
    for (double& x : B.reshaped()) x = u(gen);
    Eigen::MatrixXd X(n, 4);
    for (int j = 0; j < 4; ++j) X.col(j) = llt.solve(B.col(j));
    const Eigen::MatrixXd plain_X = X;
    const bool refined = fremond::detail::refine_solve(M, llt, B, X);
    if (llt.condition_bound() > fremond::detail::kPlainSolveCondition) continue;
    ++plain;
    EXPECT_FALSE(refined) << trial;
    EXPECT_EQ((X - plain_X).cwiseAbs().maxCoeff(), 0.0) << trial;
    const Long exact = M.cast<long double>().llt().solve(B.cast<long double>());
    for (int j = 0; j < 4; ++j) {
      const long double error = (X.col(j).cast<long double>() - exact.col(j)).cwiseAbs().maxCoeff();
      const double relative = double(error / exact.col(j).cwiseAbs().maxCoeff());
      worst = std::max(worst, relative);
      EXPECT_LE(relative, fremond::detail::kPlainSolveCondition * eps) << trial;
    }
  }
  EXPECT_GT(plain, 400);
  EXPECT_GT(worst, 0.0);  // the check reads real rounding
}
