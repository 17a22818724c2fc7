// The hand-written kernel of the classical laws' stack sizes
// (src/solvers/detail/small_null_space.hpp) against Eigen's FullPivLU with the same 1e-10
// threshold: the same rank, the same basis up to rounding (it is the same elimination), and the
// invariants null_space's callers rely on — G N ≈ 0 and N orthonormal — on random, rank-deficient,
// zero-column, symmetric semidefinite and widely scaled matrices.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "../../src/solvers/detail/classical_phase.hpp"
#include "../../src/solvers/detail/small_null_space.hpp"

namespace {

using fremond::detail::small_kernel;
using Mat = fremond::detail::SmallSquare<8>;

void check_against_eigen(const Mat& A, const char* what, int trial) {
  const int n = static_cast<int>(A.rows());
  Mat K;
  const int rank = small_kernel<8>(A, 1e-10, K);
  Eigen::FullPivLU<Mat> lu(A);
  lu.setThreshold(1e-10);
  ASSERT_EQ(rank, lu.rank()) << what << " " << trial;
  ASSERT_EQ(K.rows(), n);
  ASSERT_EQ(K.cols(), n - rank);
  if (rank == n) return;
  const Mat ref = lu.kernel();
  // Same pivots, same arithmetic up to the order of a few sums: the same basis to rounding.
  const double scale = std::max(1.0, ref.cwiseAbs().maxCoeff());
  EXPECT_LE((K - ref).cwiseAbs().maxCoeff(), 1e-12 * scale) << what << " " << trial;
  // A basis of the kernel: A K ≈ 0 relative to |A| |K|, and of full column rank (K has an identity
  // block in the rows of the free columns).
  const double a = A.cwiseAbs().maxCoeff();
  EXPECT_LE((A * K).cwiseAbs().maxCoeff(), 1e-9 * std::max(a, 1e-300) * n * scale)
      << what << " " << trial;
  Eigen::FullPivLU<Mat> kr(K);
  EXPECT_EQ(kr.rank(), n - rank) << what << " " << trial;
}

TEST(ClassicalNullSpace, SmallKernelMatchesEigenOnRandomAndDegenerateMatrices) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, 7);
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 1 + trial % 8;
    const int kind = (trial / 8) % 6;
    Mat A(n, n);
    if (kind == 0) {  // random, regular
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) A(i, j) = u(gen);
    } else if (kind == 1 || kind == 2) {  // rank k < n as a product; kind 2: symmetric W Wᵀ
      const int k = pick(gen) % n;
      Mat B = Mat::Zero(n, n), C = Mat::Zero(n, n);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < k; ++j) B(i, j) = u(gen), C(j, i) = u(gen);
      A = kind == 1 ? Mat(B * C) : Mat(B * B.transpose());
    } else if (kind == 3) {  // zero columns and rows, exact repeats
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) A(i, j) = u(gen);
      A.col(pick(gen) % n).setZero();
      if (n > 1) A.row(pick(gen) % n) = A.row(pick(gen) % n);
    } else if (kind == 4) {  // small integer entries: exact ties among the pivot candidates
      std::uniform_int_distribution<int> small(-1, 1);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) A(i, j) = small(gen);
    } else {  // entries spread over many orders of magnitude
      std::uniform_real_distribution<double> e(-12.0, 12.0);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) A(i, j) = u(gen) * std::pow(10.0, e(gen));
    }
    check_against_eigen(A, "plain", trial);
    check_against_eigen(Mat(A * 1e100), "x1e100", trial);
    check_against_eigen(Mat(A * 1e-100), "x1e-100", trial);
  }
  check_against_eigen(Mat::Zero(3, 3), "zero", 0);
  check_against_eigen(Mat::Identity(5, 5), "identity", 0);
}

// What the classical laws use: an orthonormal basis of null(G) for G = Wᵀ M⁻¹ W, the flat bar's
// singular 4 × 4 among them.
TEST(ClassicalNullSpace, NullSpaceIsAnOrthonormalBasisOfTheKernel) {
  using fremond::detail::classical::null_space;
  using Small = fremond::detail::classical::Phase<4>::RowMat;
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    const int r = 1 + trial % 8;
    const int dofs = 1 + (trial / 8) % 6;
    Eigen::MatrixXd W(dofs, r);
    for (int i = 0; i < dofs; ++i)
      for (int j = 0; j < r; ++j) W(i, j) = u(gen);
    const Small G = W.transpose() * W;
    const Small N = null_space<4>(G);
    const Eigen::MatrixXd Gd = G;
    const auto ref = null_space<fremond::Dynamic>(Gd);
    ASSERT_EQ(N.cols(), ref.cols()) << trial;
    if (N.cols() == 0) continue;
    EXPECT_LE((Eigen::MatrixXd(N) - ref).cwiseAbs().maxCoeff(), 1e-12) << trial;
    EXPECT_LE((G * N).cwiseAbs().maxCoeff(), 1e-12) << trial;
    const Eigen::MatrixXd Nd = N;
    const Eigen::MatrixXd gram = Nd.transpose() * Nd;
    EXPECT_LE((gram - Eigen::MatrixXd::Identity(Nd.cols(), Nd.cols())).cwiseAbs().maxCoeff(), 1e-14)
        << trial;
  }
}

}  // namespace
