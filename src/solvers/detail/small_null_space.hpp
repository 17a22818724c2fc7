#pragma once
// The kernel of a small square matrix by full-pivoting elimination, for the stack-stored sizes of
// the classical laws (G is at most 8 × 8: 4 contacts with friction). Eigen's FullPivLU and its
// kernel() on a bounded dynamic-size matrix go through the blocked product and triangular-solve
// kernels, whose set-up costs several times the arithmetic at 2×2..8×8.
//
// This is the same algorithm as Eigen's FullPivLU + kernel(), step for step, so that callers get
// the same rank and the same basis up to the last bits:
//  - the pivot is the entry of largest modulus in the remaining corner, the first one met in
//    column-major order on ties (Eigen's maxCoeff visitor); elimination stops at an exactly zero
//    corner;
//  - a pivot counts toward the rank when |pivot| > threshold · (largest |pivot| met), as
//    FullPivLU::setThreshold / rank() do;
//  - the kernel basis is Q (−U₁⁻¹U₂; I) from the counted pivots, as kernel_retval<FullPivLU>.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <utility>

namespace fremond::detail {

template <int Max>
using SmallSquare =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, Max, Max>;

/// Rank of the square A with the relative pivot threshold `threshold`; K receives a basis of the
/// kernel (n × (n − rank), not orthonormal; no columns when A is regular).
template <int Max>
int small_kernel(const SmallSquare<Max>& A, double threshold, SmallSquare<Max>& K) {
  static_assert(Max != Eigen::Dynamic, "for the stack-stored sizes only");
  const int n = static_cast<int>(A.rows());
  std::array<std::array<double, Max>, Max> lu;  // lu[j][i]: column j, row i
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) lu[j][i] = A(i, j);
  std::array<int, Max> q{};  // column permutation: column k of LU is column q[k] of A
  for (int k = 0; k < n; ++k) q[k] = k;
  int nonzero = n;
  double max_pivot = 0.0;
  for (int k = 0; k < n; ++k) {
    int pr = k, pc = k;
    double big = std::fabs(lu[k][k]);
    for (int j = k; j < n; ++j)
      for (int i = (j == k ? k + 1 : k); i < n; ++i)
        if (const double s = std::fabs(lu[j][i]); s > big) {
          big = s;
          pr = i;
          pc = j;
        }
    if (big == 0.0) {
      nonzero = k;
      break;
    }
    if (big > max_pivot) max_pivot = big;
    // The row swap permutes only the equations: the kernel does not depend on it, but the later
    // pivots do, so it is applied in full as Eigen does.
    if (pr != k)
      for (int j = 0; j < n; ++j) std::swap(lu[j][k], lu[j][pr]);
    if (pc != k) {
      std::swap(lu[k], lu[pc]);
      std::swap(q[k], q[pc]);
    }
    const double p = lu[k][k];
    for (int i = k + 1; i < n; ++i) lu[k][i] /= p;
    for (int j = k + 1; j < n; ++j) {
      const double u = lu[j][k];
      for (int i = k + 1; i < n; ++i) lu[j][i] -= lu[k][i] * u;
    }
  }
  const double cut = max_pivot * threshold;
  std::array<int, Max> piv{};
  int rank = 0;
  for (int i = 0; i < nonzero; ++i)
    if (std::fabs(lu[i][i]) > cut) piv[rank++] = i;
  const int dim = n - rank;
  K.resize(n, dim);
  if (dim == 0) return rank;
  // The trapezoid m (rank × n): rows piv[i] of U from column i on, with the counted pivots brought
  // to the diagonal by column swaps (m[j][i]: column j, row i).
  std::array<std::array<double, Max>, Max> m{};
  for (int i = 0; i < rank; ++i)
    for (int j = i; j < n; ++j) m[j][i] = lu[j][piv[i]];
  for (int i = 0; i < rank; ++i)
    for (int j = i + 1; j < rank; ++j) m[i][j] = 0.0;  // strictly lower part of the square block
  for (int i = 0; i < rank; ++i) std::swap(m[i], m[piv[i]]);
  // U₁ X = U₂ by back substitution in place on the right block, column-oriented and by the
  // reciprocal of the pivot, in the order of Eigen's triangular solver.
  for (int i = rank - 1; i >= 0; --i) {
    const double inv = 1.0 / m[i][i];
    for (int c = rank; c < n; ++c) {
      const double x = (m[c][i] *= inv);
      for (int l = 0; l < i; ++l) m[c][l] -= x * m[i][l];
    }
  }
  for (int i = rank - 1; i >= 0; --i) std::swap(m[i], m[piv[i]]);
  for (int i = 0; i < rank; ++i)
    for (int c = 0; c < dim; ++c) K(q[i], c) = -m[rank + c][i];
  for (int i = rank; i < n; ++i)
    for (int c = 0; c < dim; ++c) K(q[i], c) = 0.0;
  for (int c = 0; c < dim; ++c) K(q[rank + c], c) = 1.0;
  return rank;
}

}  // namespace fremond::detail
