// The Cholesky factor of the contact space and of G (src/core/detail/cholesky.hpp): the hand loops
// of the stack sizes against Eigen's LLT (the factor to rounding, L Lᵀ = A, solves), the same
// refusal of matrices that are not positive definite, and the heap sizes going through Eigen
// itself.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <cmath>
#include <limits>
#include <random>

#include "core/detail/cholesky.hpp"

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
