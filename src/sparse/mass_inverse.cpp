// M⁻¹ X through M's diagonal blocks (sparse/detail/mass_inverse.hpp).
#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "fremond/core/error.hpp"
#include "sparse/detail/mass_inverse.hpp"

namespace fremond::detail {

namespace {

constexpr int kLargestDenseBlock = 64;

[[noreturn]] void not_positive_definite(const std::string& name, int row) {
  throw InvalidArgument(name,
                        "must be positive definite (the Cholesky factorisation of the block "
                        "holding row " +
                            std::to_string(row) + " failed)");
}

// Rows of each connected block of M's graph, ascending; blocks in order of their first row.
std::vector<std::vector<int>> diagonal_blocks(const SparseMatrix& M) {
  const int n = static_cast<int>(M.rows());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int i) {
    while (parent[static_cast<std::size_t>(i)] != i)
      i = parent[static_cast<std::size_t>(i)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    return i;
  };
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(M, j); it; ++it) {
      const int a = root(static_cast<int>(it.row())), b = root(j);
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  std::vector<int> block_of(static_cast<std::size_t>(n), -1);
  std::vector<std::vector<int>> blocks;
  for (int i = 0; i < n; ++i) {
    int& b = block_of[static_cast<std::size_t>(root(i))];
    if (b < 0) {
      b = static_cast<int>(blocks.size());
      blocks.emplace_back();
    }
    blocks[static_cast<std::size_t>(b)].push_back(i);
  }
  return blocks;
}

}  // namespace

SparseMatrix interleaved_jacobian(const SparseMatrix& W_N, const SparseMatrix& W_T) {
  const bool tangential = W_T.cols() > 0;
  const int c = static_cast<int>(W_N.cols());
  SparseMatrix W(W_N.rows(), tangential ? 2 * c : c);
  W.reserve(W_N.nonZeros() + W_T.nonZeros());
  auto append = [&W](const SparseMatrix& from, int column, int to) {
    W.startVec(to);
    for (SparseMatrix::InnerIterator it(from, column); it; ++it)
      W.insertBack(it.row(), to) = it.value();
  };
  for (int i = 0; i < c; ++i) {
    append(W_N, i, tangential ? 2 * i : i);
    if (tangential) append(W_T, i, 2 * i + 1);
  }
  W.finalize();
  return W;
}

SparseMatrix solve_mass(const SparseMatrix& M, const SparseMatrix& X, const std::string& name) {
  const int n = static_cast<int>(M.rows());
  double scale = 0.0;
  for (int k = 0; k < M.nonZeros(); ++k) scale = std::max(scale, std::fabs(M.valuePtr()[k]));
  const double pivot_floor = 1e-12 * std::sqrt(scale);
  const auto blocks = diagonal_blocks(M);
  std::size_t largest = 0;
  for (const auto& b : blocks) largest = std::max(largest, b.size());

  if (largest > static_cast<std::size_t>(kLargestDenseBlock)) {
    const Eigen::SimplicialLLT<SparseMatrix> llt(M);
    if (llt.info() != Eigen::Success) not_positive_definite(name, 0);
    const SparseMatrix L = llt.matrixL();
    for (int j = 0; j < n; ++j)
      if (!(L.coeff(j, j) > pivot_floor))
        not_positive_definite(name, llt.permutationPinv().indices()(j));
    return llt.solve(X);
  }

  std::vector<Eigen::Triplet<double>> inverse;
  Eigen::MatrixXd block;
  for (const auto& rows : blocks) {
    const int b = static_cast<int>(rows.size());
    block.setZero(b, b);
    for (int jj = 0; jj < b; ++jj)
      for (SparseMatrix::InnerIterator it(M, rows[static_cast<std::size_t>(jj)]); it; ++it) {
        const auto at = std::lower_bound(rows.begin(), rows.end(), static_cast<int>(it.row()));
        block(static_cast<int>(at - rows.begin()), jj) = it.value();
      }
    const Eigen::LLT<Eigen::MatrixXd> llt(block);
    if (llt.info() != Eigen::Success || !(llt.matrixLLT().diagonal().minCoeff() > pivot_floor))
      not_positive_definite(name, rows.front());
    const Eigen::MatrixXd inv = llt.solve(Eigen::MatrixXd::Identity(b, b));
    for (int jj = 0; jj < b; ++jj)
      for (int ii = 0; ii < b; ++ii)
        inverse.emplace_back(rows[static_cast<std::size_t>(ii)], rows[static_cast<std::size_t>(jj)],
                             inv(ii, jj));
  }
  SparseMatrix Minv(n, n);
  Minv.setFromTriplets(inverse.begin(), inverse.end());
  return Minv * X;
}

}  // namespace fremond::detail
