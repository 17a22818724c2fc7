#pragma once
// Lexicographic Lemke (Cottle, Pang & Stone, "The Linear Complementarity Problem", Algorithm 4.4.5
// with the lexicographic rule of §4.9), templated on the largest problem size so that the small
// impact problems pivot on a stack-stored tableau.
//
// The tableau holds B⁻¹ [I | −M | −e | q] for the basis B of the system I w − M z − e z₀ = q, one
// row per basic variable; its first n columns are B⁻¹ itself, which is what the lexicographic ratio
// test compares. Because B⁻¹ is invertible no two rows are lexicographically equal, so each pivot
// row is unique and the method cannot cycle, whatever the degeneracy of q.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "fremond/core/types.hpp"
#include "fremond/solvers/lemke.hpp"

namespace fremond::detail::lcp {

constexpr int tableau_cols(int max_n) {
  return max_n == Dynamic ? Dynamic : 2 * max_n + 2;
}

template <int MaxN>
using Tableau = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor, MaxN,
                              tableau_cols(MaxN)>;

/// ‖min(z, Mz + q)‖∞ (unscaled); w receives M z + q.
template <int MaxN>
double complementarity_error(const MatT<MaxN, MaxN>& M, const VecT<MaxN>& q, const VecT<MaxN>& z,
                             VecT<MaxN>& w) {
  w = q;
  w.noalias() += M * z;
  double err = 0.0;
  for (Eigen::Index i = 0; i < q.size(); ++i) err = std::max(err, std::fabs(std::min(z(i), w(i))));
  return err;
}

/// Solves w = Mz + q ≥ 0, z ≥ 0, zᵀw = 0. Writes z and w (= Mz + q recomputed) and the number of
/// pivots. No heap allocation for a finite MaxN.
template <int MaxN>
LcpStatus lemke(const MatT<MaxN, MaxN>& M, const VecT<MaxN>& q, const LemkeOptions& opt,
                VecT<MaxN>& z, VecT<MaxN>& w, int& pivots) {
  const int n = static_cast<int>(q.size());
  const int c_z0 = 2 * n, c_rhs = 2 * n + 1;
  pivots = 0;
  z.setZero(n);
  w = q;
  if (n == 0 || q.minCoeff() >= 0.0) return LcpStatus::solved;  // z = 0 already solves it

  Tableau<MaxN> T(n, 2 * n + 2);
  T.leftCols(n).setIdentity();
  T.middleCols(n, n) = -M;
  T.col(c_z0).setConstant(-1.0);
  T.col(c_rhs) = q;
  Eigen::Matrix<int, Eigen::Dynamic, 1, Eigen::ColMajor, MaxN, 1> basis(n);
  for (int i = 0; i < n; ++i) basis(i) = i;  // w basic: B = I

  const double eps = std::numeric_limits<double>::epsilon();
  // Rounding scales of the right-hand side and of the B⁻¹ block, refreshed once per ratio test
  // (only when two candidates have to be compared).
  double rhs_scale = 0.0, binv_scale = 0.0;
  bool scales_fresh = false;
  auto refresh_scales = [&] {
    rhs_scale = T.col(c_rhs).cwiseAbs().maxCoeff();
    binv_scale = T.leftCols(n).cwiseAbs().maxCoeff();
    scales_fresh = true;
  };
  // Is row i / d_i lexicographically smaller than row k / d_k, comparing (rhs, B⁻¹ row)? Two
  // entries are tied when they differ by less than the tie tolerance or than the rounding of their
  // column; then the next component decides. The B⁻¹ rows are independent, so some component does.
  auto lex_less = [&](int i, int k, double di, double dk) {
    if (!scales_fresh) refresh_scales();
    const double inv_min = 1.0 / std::min(di, dk);
    for (int c = -1; c < n; ++c) {
      const int col = c < 0 ? c_rhs : c;
      const double a = T(i, col) / di, b = T(k, col) / dk;
      const double rounding = 64 * eps * (c < 0 ? rhs_scale : binv_scale) * inv_min;
      if (std::fabs(a - b) > opt.tie_tolerance * std::max(std::fabs(a), std::fabs(b)) + rounding)
        return a < b;
    }
    return i > k;  // unreachable for an invertible basis; keeps the order total
  };
  auto pivot = [&](int r, int j) {
    T.row(r) /= T(r, j);
    for (int i = 0; i < n; ++i) {
      if (i == r) continue;
      const double f = T(i, j);
      if (f != 0.0) T.row(i) -= f * T.row(r);
      T(i, j) = 0.0;
    }
    T(r, j) = 1.0;
    scales_fresh = false;
  };

  // First pivot: z₀ enters at the level that makes every w_i ≥ 0; with the column −e every row
  // qualifies and the leaving row is the lexicographic minimum of (q_i, e_iᵀ).
  int r = 0;
  for (int i = 1; i < n; ++i)
    if (lex_less(i, r, 1.0, 1.0)) r = i;
  pivot(r, c_z0);
  int leaving = basis(r);
  basis(r) = c_z0;
  pivots = 1;

  while (leaving != c_z0) {
    // Complementary pivoting: the complement of the variable that just left enters.
    const int entering = leaving < n ? leaving + n : leaving - n;
    if (pivots >= opt.max_pivots) return LcpStatus::max_pivots;
    const double d_max = T.col(entering).cwiseAbs().maxCoeff();
    const double original = entering >= n ? M.col(entering - n).cwiseAbs().maxCoeff() : 1.0;
    const double threshold = opt.pivot_tolerance * std::max(d_max, original);
    r = -1;
    for (int i = 0; i < n; ++i) {
      const double d = T(i, entering);
      if (d > threshold && (r < 0 || lex_less(i, r, d, T(r, entering)))) r = i;
    }
    if (r < 0) return LcpStatus::secondary_ray;
    pivot(r, entering);
    leaving = basis(r);
    basis(r) = entering;
    ++pivots;
    if (!std::isfinite(T(r, c_rhs))) return LcpStatus::failed;
  }

  // z₀ has left: the basic values are the answer (clamped: rounding can leave −1e-17).
  for (int i = 0; i < n; ++i)
    if (basis(i) >= n && basis(i) < 2 * n) z(basis(i) - n) = std::max(0.0, T(i, c_rhs));
  const double scale = q.cwiseAbs().maxCoeff() + M.cwiseAbs().maxCoeff() * z.cwiseAbs().maxCoeff();
  double err = complementarity_error(M, q, z, w);
  if (!std::isfinite(err)) return LcpStatus::failed;
  if (opt.refine && err > 64 * eps * scale) {
    // Accumulated pivoting error: solve the final basis, B x_B = q, from the original data.
    MatT<MaxN, MaxN> B(n, n);
    for (int i = 0; i < n; ++i) {
      if (basis(i) < n)
        B.col(i) = VecT<MaxN>::Unit(n, basis(i));
      else
        B.col(i) = -M.col(basis(i) - n);
    }
    const VecT<MaxN> x = B.fullPivLu().solve(q);
    VecT<MaxN> z2 = VecT<MaxN>::Zero(n), w2;
    bool usable = x.allFinite();
    for (int i = 0; i < n && usable; ++i) {
      if (x(i) < -1e3 * eps * (x.cwiseAbs().maxCoeff() + scale)) usable = false;
      if (basis(i) >= n) z2(basis(i) - n) = std::max(0.0, x(i));
    }
    if (usable) {
      const double err2 = complementarity_error(M, q, z2, w2);
      if (err2 < err) {
        z = z2;
        w = w2;
      }
    }
  }
  return LcpStatus::solved;
}

}  // namespace fremond::detail::lcp
