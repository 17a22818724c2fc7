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
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "fremond/core/types.hpp"
#include "fremond/solvers/lemke.hpp"

namespace fremond::detail::lcp {

/// The tableau's storage: on the stack for a finite MaxN (no heap, no zeroing), else on the heap.
/// Row-major with a leading dimension of 2n + 2 for the actual size n, so that the small problems
/// touch only the entries they use.
template <int MaxN>
struct TableauStorage {
  std::array<double, static_cast<std::size_t>(MaxN) * (2 * MaxN + 2)> values;
  std::array<int, MaxN> basis, w_basic;
  std::array<double, MaxN> col_max;
  void resize(int) {}
};
template <>
struct TableauStorage<Dynamic> {
  std::vector<double> values;
  std::vector<int> basis, w_basic;
  std::vector<double> col_max;
  void resize(int n) {
    values.resize(static_cast<std::size_t>(n) * (2 * n + 2));
    basis.resize(static_cast<std::size_t>(n));
    w_basic.resize(static_cast<std::size_t>(n));
    col_max.resize(static_cast<std::size_t>(n));
  }
};

/// ‖min(z, Mz + q)‖∞ (unscaled); w receives M z + q. By hand loops: on the small sizes met here
/// Eigen's dynamic-size product goes through its general GEMV kernel, whose set-up costs more than
/// the product.
template <int MaxN>
double complementarity_error(const MatT<MaxN, MaxN>& M, const VecT<MaxN>& q, const VecT<MaxN>& z,
                             VecT<MaxN>& w) {
  const Eigen::Index n = q.size();
  w = q;
  for (Eigen::Index j = 0; j < n; ++j) {
    const double zj = z(j);
    const double* col = M.data() + j * M.outerStride();
    for (Eigen::Index i = 0; i < n; ++i) w(i) += col[i] * zj;
  }
  double err = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) err = std::max(err, std::fabs(std::min(z(i), w(i))));
  return err;
}

/// Solves w = Mz + q ≥ 0, z ≥ 0, zᵀw = 0. Writes z and w (= Mz + q recomputed) and the number of
/// pivots. No heap allocation for a finite MaxN.
///
/// The tableau is a plain row-major array worked by hand loops: the problems of the impact laws
/// have 2 to 16 unknowns, where Eigen's dynamic-size block expressions cost more in set-up than in
/// arithmetic (a pivot of the 8-unknown flat-bar LCP is 144 multiply-adds).
template <int MaxN>
LcpStatus lemke(const MatT<MaxN, MaxN>& M, const VecT<MaxN>& q, const LemkeOptions& opt,
                VecT<MaxN>& z, VecT<MaxN>& w, int& pivots) {
  const int n = static_cast<int>(q.size());
  const int ld = 2 * n + 2, c_z0 = 2 * n, c_rhs = 2 * n + 1;
  pivots = 0;
  z.setZero(n);
  w = q;
  if (n == 0 || q.minCoeff() >= 0.0) return LcpStatus::solved;  // z = 0 already solves it

  TableauStorage<MaxN> storage;
  storage.resize(n);
  double* const T = storage.values.data();
  int* const basis = storage.basis.data();
  int* const w_basic = storage.w_basic.data();
  double* const col_max = storage.col_max.data();
  auto at = [&](int i, int c) -> double& { return T[i * ld + c]; };
  const double* const Md = M.data();
  const Eigen::Index ldm = M.outerStride();
  for (int i = 0; i < n; ++i) {
    double* row = T + i * ld;
    for (int c = 0; c < n; ++c) row[c] = 0.0;
    row[i] = 1.0;
    for (int c = 0; c < n; ++c) row[n + c] = -Md[c * ldm + i];
    row[c_z0] = -1.0;
    row[c_rhs] = q(i);
    basis[i] = i;  // w basic: B = I
    w_basic[i] = 1;
  }
  // Largest |M_ij| per column (the pivot threshold's scale) and overall (the final residual's).
  for (int c = 0; c < n; ++c) {
    double m = 0.0;
    for (int i = 0; i < n; ++i) m = std::max(m, std::fabs(Md[c * ldm + i]));
    col_max[c] = m;
  }

  const double eps = std::numeric_limits<double>::epsilon();
  // Rounding scales of the right-hand side and of the B⁻¹ block, computed when a comparison first
  // needs them after a pivot (negative: stale). The B⁻¹ scale (n² entries) is only needed when the
  // right-hand sides tie, i.e. on degenerate steps.
  double rhs_scale = -1.0, binv_scale = -1.0;
  auto scale_of = [&](int col) {
    if (col == c_rhs) {
      if (rhs_scale < 0.0) {
        rhs_scale = 0.0;
        for (int i = 0; i < n; ++i) rhs_scale = std::max(rhs_scale, std::fabs(at(i, c_rhs)));
      }
      return rhs_scale;
    }
    if (binv_scale < 0.0) {
      // The column of a basic w_k is a unit vector (pivoting leaves it exactly so): its largest
      // entry is 1 and needs no scan.
      binv_scale = 0.0;
      for (int i = 0; i < n; ++i)
        if (basis[i] < n) binv_scale = 1.0;
      for (int c = 0; c < n; ++c) {
        if (w_basic[c]) continue;
        for (int i = 0; i < n; ++i) binv_scale = std::max(binv_scale, std::fabs(at(i, c)));
      }
    }
    return binv_scale;
  };
  // Is row i / d_i lexicographically smaller than row k / d_k, comparing (rhs, B⁻¹ row)? Two
  // entries are tied when they differ by less than the tie tolerance or than the rounding of their
  // column; then the next component decides. The B⁻¹ rows are independent, so some component does.
  auto lex_less = [&](int i, int k, double di, double dk) {
    const double inv_min = 1.0 / std::min(di, dk);
    for (int c = -1; c < n; ++c) {
      const int col = c < 0 ? c_rhs : c;
      const double a = at(i, col) / di, b = at(k, col) / dk;
      const double rounding = 64 * eps * scale_of(col) * inv_min;
      if (std::fabs(a - b) > opt.tie_tolerance * std::max(std::fabs(a), std::fabs(b)) + rounding)
        return a < b;
    }
    return i > k;  // unreachable for an invertible basis; keeps the order total
  };
  auto pivot = [&](int r, int j) {
    double* const pr = T + r * ld;
    const double p = pr[j];
    for (int c = 0; c < ld; ++c) pr[c] /= p;
    for (int i = 0; i < n; ++i) {
      if (i == r) continue;
      double* const pi = T + i * ld;
      const double f = pi[j];
      if (f != 0.0)
        for (int c = 0; c < ld; ++c) pi[c] -= f * pr[c];
      pi[j] = 0.0;
    }
    pr[j] = 1.0;
    rhs_scale = binv_scale = -1.0;
  };

  // First pivot: z₀ enters at the level that makes every w_i ≥ 0; with the column −e every row
  // qualifies and the leaving row is the lexicographic minimum of (q_i, e_iᵀ).
  int r = 0;
  for (int i = 1; i < n; ++i)
    if (lex_less(i, r, 1.0, 1.0)) r = i;
  pivot(r, c_z0);
  int leaving = basis[r];
  basis[r] = c_z0;
  w_basic[leaving] = 0;
  pivots = 1;

  while (leaving != c_z0) {
    // Complementary pivoting: the complement of the variable that just left enters.
    const int entering = leaving < n ? leaving + n : leaving - n;
    if (pivots >= opt.max_pivots) return LcpStatus::max_pivots;
    double d_max = 0.0;
    for (int i = 0; i < n; ++i) d_max = std::max(d_max, std::fabs(at(i, entering)));
    const double original = entering >= n ? col_max[entering - n] : 1.0;
    const double threshold = opt.pivot_tolerance * std::max(d_max, original);
    r = -1;
    for (int i = 0; i < n; ++i) {
      const double d = at(i, entering);
      if (d > threshold && (r < 0 || lex_less(i, r, d, at(r, entering)))) r = i;
    }
    if (r < 0) return LcpStatus::secondary_ray;
    pivot(r, entering);
    leaving = basis[r];
    basis[r] = entering;
    if (leaving < n) w_basic[leaving] = 0;
    if (entering < n) w_basic[entering] = 1;
    ++pivots;
    if (!std::isfinite(at(r, c_rhs))) return LcpStatus::failed;
  }

  // z₀ has left: the basic values are the answer (clamped: rounding can leave −1e-17).
  for (int i = 0; i < n; ++i)
    if (basis[i] >= n && basis[i] < 2 * n) z(basis[i] - n) = std::max(0.0, at(i, c_rhs));
  double q_max = 0.0, m_max = 0.0, z_max = 0.0;
  for (int i = 0; i < n; ++i) {
    q_max = std::max(q_max, std::fabs(q(i)));
    z_max = std::max(z_max, std::fabs(z(i)));
    m_max = std::max(m_max, col_max[i]);
  }
  const double scale = q_max + m_max * z_max;
  double err = complementarity_error(M, q, z, w);
  if (!std::isfinite(err)) return LcpStatus::failed;
  if (opt.refine && err > 64 * eps * scale) {
    // Accumulated pivoting error: solve the final basis, B x_B = q, from the original data.
    MatT<MaxN, MaxN> B(n, n);
    for (int i = 0; i < n; ++i) {
      if (basis[i] < n)
        B.col(i) = VecT<MaxN>::Unit(n, basis[i]);
      else
        B.col(i) = -M.col(basis[i] - n);
    }
    const VecT<MaxN> x = B.fullPivLu().solve(q);
    VecT<MaxN> z2 = VecT<MaxN>::Zero(n), w2;
    bool usable = x.allFinite();
    for (int i = 0; i < n && usable; ++i) {
      if (x(i) < -1e3 * eps * (x.cwiseAbs().maxCoeff() + scale)) usable = false;
      if (basis[i] >= n) z2(basis[i] - n) = std::max(0.0, x(i));
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
