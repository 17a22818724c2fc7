#pragma once
// An orthonormal basis of the kernel of a symmetric positive semidefinite matrix, for the classical
// laws' G = Wᵀ M⁻¹ W (classical_phase.hpp, null_space). By hand loops, one code
// for the stack-stored sizes and the heap-stored ones, so that both storages get the same basis to
// the last bit.
//
// Why not a full-pivoting LU and Gram-Schmidt on its kernel: G has r = 2 × contacts rows but rank
// at most the number of degrees of freedom n (a plate on 32 points: r = 64, rank 3). The LU
// eliminates the whole r × r corner, O(r³), though every pivot after the third is rounding, and
// orthonormalising its r − rank kernel vectors costs O(r (r − rank)²) again. Here:
//  1. pivoted Cholesky (diagonal pivoting: for a semidefinite matrix the largest entry of every
//  Schur
//     complement is on its diagonal, so these are full pivoting's pivots) stops at the first pivot
//     d_k ≤ threshold · d_0: O(r² rank). The rank is the one FullPivLU::rank() gives with the same
//     relative threshold, since both count the pivots above threshold × the largest;
//  2. null(G) is the orthogonal complement of range(L) (G ≈ L Lᵀ with L r × rank): the last
//     r − rank columns of the Householder QR's Q of L, orthonormal by construction:
//     O(r (r − rank) rank).
#include <Eigen/Core>
#include <cmath>

namespace fremond::detail {

template <int Max>
using SmallSquare =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, Max, Max>;

/// Rank of the symmetric positive semidefinite G with the relative pivot threshold `threshold`;
/// N receives an orthonormal basis of its kernel (r × (r − rank); no columns when G is regular).
/// Only G's lower triangle is read. A zero matrix has rank 0 and N = I.
template <int Max>
int psd_null_space(const SmallSquare<Max>& G, double threshold, SmallSquare<Max>& N) {
  const int r = static_cast<int>(G.rows());
  SmallSquare<Max> S(r, r);  // the Schur complement; its lower triangle, then L's columns
  for (int j = 0; j < r; ++j)
    for (int i = j; i < r; ++i) S(i, j) = G(i, j);
  // Pivoted Cholesky in place: column k of L is stored in column k of S after the rows and columns
  // are permuted so that the k-th pivot sits at (k, k). perm[k]: the original index of row k.
  Eigen::Matrix<int, Eigen::Dynamic, 1, 0, Max, 1> perm(r);
  for (int i = 0; i < r; ++i) perm(i) = i;
  double d0 = 0.0;
  for (int i = 0; i < r; ++i) d0 = std::max(d0, S(i, i));
  const double cut = threshold * d0;
  int rank = 0;
  for (; rank < r; ++rank) {
    const int k = rank;
    int p = k;
    for (int i = k + 1; i < r; ++i)
      if (S(i, i) > S(p, p)) p = i;
    const double d = S(p, p);
    if (!(d > cut) || !(d > 0.0)) break;
    if (p != k) {  // symmetric swap of rows/columns k and p in the lower triangle
      for (int j = 0; j < k; ++j) std::swap(S(k, j), S(p, j));
      std::swap(S(k, k), S(p, p));
      for (int i = k + 1; i < p; ++i) std::swap(S(i, k), S(p, i));
      for (int i = p + 1; i < r; ++i) std::swap(S(i, k), S(i, p));
      std::swap(perm(k), perm(p));
    }
    const double s = std::sqrt(d);
    S(k, k) = s;
    for (int i = k + 1; i < r; ++i) S(i, k) /= s;
    for (int j = k + 1; j < r; ++j) {
      const double lj = S(j, k);
      for (int i = j; i < r; ++i) S(i, j) -= S(i, k) * lj;
    }
  }
  const int dim = r - rank;
  N.resize(r, dim);
  if (dim == 0) return rank;
  // Householder QR of L = S(:, 0..rank) (rows in pivot order, zero above the diagonal): reflector
  // j is I − β_j v_j v_jᵀ with v_j(j) = 1 and its tail stored below the diagonal of column j.
  for (int c = 1; c < rank; ++c)
    for (int i = 0; i < c; ++i) S(i, c) = 0.0;  // L's upper triangle (never written so far)
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, Max, 1> beta(rank);
  for (int j = 0; j < rank; ++j) {
    double tail = 0.0;
    for (int i = j + 1; i < r; ++i) tail += S(i, j) * S(i, j);
    const double x0 = S(j, j);
    if (tail == 0.0) {
      beta(j) = 0.0;
      continue;
    }
    const double norm = std::sqrt(x0 * x0 + tail);
    const double alpha = x0 <= 0.0 ? norm : -norm;  // R(j, j); the sign that avoids cancellation
    const double v0 = x0 - alpha;
    for (int i = j + 1; i < r; ++i) S(i, j) /= v0;
    beta(j) = -v0 / alpha;
    S(j, j) = alpha;
    for (int c = j + 1; c < rank; ++c) {
      double w = S(j, c);
      for (int i = j + 1; i < r; ++i) w += S(i, j) * S(i, c);
      w *= beta(j);
      S(j, c) -= w;
      for (int i = j + 1; i < r; ++i) S(i, c) -= w * S(i, j);
    }
  }
  // Q's last r − rank columns: H_0 ⋯ H_{rank−1} applied to the unit vectors e_rank..e_{r−1},
  // innermost reflector first; then the rows back to the original order.
  SmallSquare<Max> Q = SmallSquare<Max>::Zero(r, dim);
  for (int c = 0; c < dim; ++c) Q(rank + c, c) = 1.0;
  for (int j = rank - 1; j >= 0; --j) {
    if (beta(j) == 0.0) continue;
    for (int c = 0; c < dim; ++c) {
      double w = Q(j, c);
      for (int i = j + 1; i < r; ++i) w += S(i, j) * Q(i, c);
      w *= beta(j);
      Q(j, c) -= w;
      for (int i = j + 1; i < r; ++i) Q(i, c) -= w * S(i, j);
    }
  }
  for (int i = 0; i < r; ++i)
    for (int c = 0; c < dim; ++c) N(perm(i), c) = Q(i, c);
  return rank;
}

}  // namespace fremond::detail
