// The kernel of the classical laws' G (src/core/detail/small_null_space.hpp: pivoted Cholesky,
// then the orthogonal complement of its range) against Eigen's FullPivLU with the same 1e-10
// threshold: the same rank and the same subspace (compared through orthogonal projectors, since the
// two bases differ), on symmetric semidefinite matrices of every rank, zero and identity, exact
// ties, entries spread over many orders of magnitude, and the tall ranks of many contacts on a
// few degrees of freedom.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/QR>
#include <cmath>
#include <random>

#include "core/detail/small_null_space.hpp"
#include "solvers/detail/classical_phase.hpp"

namespace {

using fremond::detail::psd_null_space;
using Mat = fremond::detail::SmallSquare<8>;

/// Rank and kernel projector against FullPivLU; orthonormality and G N ≈ 0 on their own.
template <int Max>
void check_against_eigen(const fremond::detail::SmallSquare<Max>& A, const char* what, int trial) {
  const int n = static_cast<int>(A.rows());
  fremond::detail::SmallSquare<Max> N;
  const int rank = psd_null_space<Max>(A, 1e-10, N);
  const Eigen::MatrixXd Ad = A;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(Ad);
  lu.setThreshold(1e-10);
  ASSERT_EQ(rank, lu.rank()) << what << " " << trial;
  ASSERT_EQ(N.rows(), n);
  ASSERT_EQ(N.cols(), n - rank);
  if (rank == n) return;
  const Eigen::MatrixXd Nd = N;
  const Eigen::MatrixXd gram = Nd.transpose() * Nd;
  EXPECT_LE((gram - Eigen::MatrixXd::Identity(n - rank, n - rank)).cwiseAbs().maxCoeff(), 1e-14)
      << what << " " << trial;
  // LU's kernel made orthonormal by a QR: the same subspace when both projectors agree.
  const Eigen::MatrixXd K = lu.kernel();
  const Eigen::MatrixXd QK = Eigen::HouseholderQR<Eigen::MatrixXd>(K).householderQ() *
                             Eigen::MatrixXd::Identity(n, n - rank);
  const double a = std::max(Ad.cwiseAbs().maxCoeff(), 1e-300);
  EXPECT_LE((Nd * Nd.transpose() - QK * QK.transpose()).cwiseAbs().maxCoeff(), 1e-10)
      << what << " " << trial;
  EXPECT_LE((Ad * Nd).cwiseAbs().maxCoeff(), 1e-9 * a * n) << what << " " << trial;
}

TEST(ClassicalNullSpace, PsdNullSpaceMatchesEigenOnSemidefiniteMatrices) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, 7);
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 1 + trial % 8;
    const int kind = (trial / 8) % 4;
    Mat B = Mat::Zero(n, n);
    const int k = kind == 0 ? n : pick(gen) % (n + 1);
    if (kind == 2) {  // small integer entries: exact ties among the pivot candidates
      std::uniform_int_distribution<int> small(-1, 1);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < k; ++j) B(i, j) = small(gen);
    } else if (kind == 3) {  // rows scaled over many orders of magnitude (kept above 1e-5 of the
                             // largest, so that the rank is not a matter of rounding)
      std::uniform_real_distribution<double> e(-2.5, 0.0);
      for (int i = 0; i < n; ++i) {
        const double s = std::pow(10.0, e(gen));
        for (int j = 0; j < k; ++j) B(i, j) = s * u(gen);
      }
    } else {  // random, regular (kind 0) or of rank k (kind 1)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < k; ++j) B(i, j) = u(gen);
    }
    if (n > 1 && kind == 1) B.row(pick(gen) % n) = B.row(pick(gen) % n);  // exact repeats
    const Mat A = B * B.transpose();
    check_against_eigen<8>(A, "plain", trial);
    check_against_eigen<8>(Mat(A * 1e100), "x1e100", trial);
    check_against_eigen<8>(Mat(A * 1e-100), "x1e-100", trial);
  }
  check_against_eigen<8>(Mat(Mat::Zero(3, 3)), "zero", 0);
  check_against_eigen<8>(Mat(Mat::Identity(5, 5)), "identity", 0);
}

// Many contacts on a few degrees of freedom: G of 64 rows and rank 3, the plate's shape,
// heap-stored.
TEST(ClassicalNullSpace, TallRankDeficientHeapStoredMatrices) {
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const int r = 8 + 8 * (trial % 8), dofs = 1 + trial % 6;
    Eigen::MatrixXd W(dofs, r);
    for (int i = 0; i < dofs; ++i)
      for (int j = 0; j < r; ++j) W(i, j) = u(gen);
    if (trial % 2) W.col(1) = W.col(0);  // two equal contacts, as on the flat plate
    const Eigen::MatrixXd G = W.transpose() * W;
    check_against_eigen<Eigen::Dynamic>(G, "tall", trial);
  }
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
