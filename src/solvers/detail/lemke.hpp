#pragma once
// Lexicographic Lemke (Cottle, Pang & Stone, "The Linear Complementarity Problem", Algorithm 4.4.5
// with the lexicographic rule of §4.9), templated on the largest problem size so that the small
// impact problems pivot on a stack-stored tableau.
//
// The method works on B⁻¹ [I | −M | −e | q] for the basis B of the system I w − M z − e z₀ = q,
// one row per basic variable; its w columns are B⁻¹ itself, which is what the lexicographic ratio
// test compares. Because B⁻¹ is invertible no two rows are lexicographically equal, so each pivot
// row is unique and the method cannot cycle, whatever the degeneracy of q.
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>

#include "fremond/core/types.hpp"
#include "fremond/solvers/lemke.hpp"

namespace fremond::detail::lcp {

/// y_c −= f x_c for c < len: a pivot's update of one tableau row, most of Lemke's cost. Four
/// entries at a time on a processor with AVX2, with the same bits (a product, then a difference,
/// never fused).
void subtract_multiple(double* y, const double* x, double f, int len);

/// The tableau's storage: on the stack for a finite MaxN (no heap, no zeroing), else on the heap.
/// Row-major with a leading dimension of n + 2 for the actual size n, so that the small problems
/// touch only the entries they use.
template <int MaxN>
struct TableauStorage {
  std::array<double, static_cast<std::size_t>(MaxN) * (MaxN + 2)> values_;
  std::array<double, 2 * MaxN> reals_;
  std::array<int, 6 * MaxN + 4> ints_;
  void resize(int) {}
  double* values() { return values_.data(); }
  double* reals() { return reals_.data(); }
  int* ints() { return ints_.data(); }
};
/// Heap-stored: left uninitialised like the stack arrays (every entry read is written first). A
/// zero-filled vector of the n(n + 2) tableau entries costs as much as a third of the pivots on the
/// many-contact problems (n = 128 for 32 contacts with friction).
template <>
struct TableauStorage<Dynamic> {
  std::unique_ptr<double[]> values_, reals_;
  std::unique_ptr<int[]> ints_;
  void resize(int n) {
    const auto m = static_cast<std::size_t>(n);
    values_.reset(new double[m * (m + 2)]);
    reals_.reset(new double[2 * m]);
    ints_.reset(new int[6 * m + 4]);
  }
  double* values() { return values_.get(); }
  double* reals() { return reals_.get(); }
  int* ints() { return ints_.get(); }
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
/// The tableau is condensed: of B⁻¹ [I | −M | −e | q] it keeps only the n + 1 columns of the
/// non-basic variables and the right-hand side, since a basic variable's column is a unit vector.
/// That halves the work of a pivot against the full tableau. The lexicographic test still reads
/// B⁻¹ = the columns of w: a basic w_k's column is the unit vector of its row, a non-basic one's is
/// stored. A plain row-major array worked by hand loops: the problems of the impact laws have 2 to
/// 16 unknowns, where Eigen's dynamic-size block expressions cost more in set-up than in
/// arithmetic.
template <int MaxN>
LcpStatus lemke(const MatT<MaxN, MaxN>& M, const VecT<MaxN>& q, const LemkeOptions& opt,
                VecT<MaxN>& z, VecT<MaxN>& w, int& pivots) {
  const int n = static_cast<int>(q.size());
  // Variables: w_k = k, z_k = n + k, the artificial z₀ = 2n. Columns: n + 1 non-basic, then rhs.
  const int ld = n + 2, c_rhs = n + 1, z0 = 2 * n;
  pivots = 0;
  z.setZero(n);
  w = q;
  if (n == 0 || q.minCoeff() >= 0.0) return LcpStatus::solved;  // z = 0 already solves it

  TableauStorage<MaxN> storage;
  storage.resize(n);
  double* const T = storage.values();
  int* const basis = storage.ints();         // row → basic variable (n)
  int* const nonbasic = basis + n;           // column → non-basic variable (n + 1)
  int* const position = nonbasic + n + 1;    // variable → its row or column (2n + 1)
  int* const w_free = position + 2 * n + 1;  // the non-basic w's, ascending (n at most)
  int* const pivot_nz = w_free + n;          // the pivot row's non-zero columns (n + 2 at most)
  double* const col_max = storage.reals();   // n
  double* const ratio = col_max + n;         // n
  auto at = [&](int i, int c) -> double& { return T[i * ld + c]; };
  auto is_basic = [&](int v) {
    const int p = position[v];
    return p < n && basis[p] == v;
  };
  const double* const Md = M.data();
  const Eigen::Index ldm = M.outerStride();
  // B = I: w basic, the z and z₀ columns are −M and −e.
  for (int i = 0; i < n; ++i) {
    double* row = T + i * ld;
    for (int c = 0; c < n; ++c) row[c] = -Md[c * ldm + i];
    row[n] = -1.0;
    row[c_rhs] = q(i);
    basis[i] = i;
    position[i] = i;
  }
  for (int c = 0; c < n; ++c) {
    nonbasic[c] = n + c;
    position[n + c] = c;
  }
  nonbasic[n] = z0;
  position[z0] = n;
  // Largest |M_ij| per column (the pivot threshold's scale) and overall (the final residual's).
  for (int c = 0; c < n; ++c) {
    double m = 0.0;
    for (int i = 0; i < n; ++i) m = std::max(m, std::fabs(Md[c * ldm + i]));
    col_max[c] = m;
  }

  const double eps = std::numeric_limits<double>::epsilon();
  // Rounding scales of the right-hand side and of the B⁻¹ block, computed when a comparison first
  // needs them after a pivot (negative: stale). The B⁻¹ scale is only needed when the right-hand
  // sides tie, i.e. on degenerate steps.
  double rhs_scale = -1.0, binv_scale = -1.0;
  auto scale_of = [&](int k) {
    if (k < 0) {
      if (rhs_scale < 0.0) {
        rhs_scale = 0.0;
        for (int i = 0; i < n; ++i) rhs_scale = std::max(rhs_scale, std::fabs(at(i, c_rhs)));
      }
      return rhs_scale;
    }
    if (binv_scale < 0.0) {
      binv_scale = 0.0;
      for (int v = 0; v < n; ++v) {
        if (is_basic(v)) {
          binv_scale = std::max(binv_scale, 1.0);
          continue;
        }
        for (int i = 0; i < n; ++i)
          binv_scale = std::max(binv_scale, std::fabs(at(i, position[v])));
      }
    }
    return binv_scale;
  };
  // Two ratios of component k (−1: the right-hand side) are tied when they differ by less than the
  // tie tolerance or than the rounding of their column.
  auto tied = [&](double a, double b, int k, double d_min) {
    const double rounding = 64 * eps * scale_of(k) / d_min;
    return std::fabs(a - b) <= opt.tie_tolerance * std::max(std::fabs(a), std::fabs(b)) + rounding;
  };
  // The non-basic w's in ascending order, listed when a comparison first needs them after a pivot
  // (−1: stale). Of B⁻¹'s columns only theirs are stored; a basic w_k's column is the unit vector
  // of its row, zero in both rows compared unless one of them is that row.
  int w_free_count = -1;
  auto list_w_free = [&] {
    if (w_free_count >= 0) return;
    w_free_count = 0;
    for (int v = 0; v < n; ++v)
      if (!is_basic(v)) w_free[w_free_count++] = v;
  };
  // Is row i / d_i lexicographically smaller than row k / d_k, comparing (rhs, B⁻¹ row)? On a tie
  // the next component decides. The B⁻¹ rows are independent, so some component does. The test of
  // `tied` multiplied through by d_i d_k > 0, without divisions. On degenerate problems (many equal
  // contacts) the comparisons are many and long, so they visit only the components that can be
  // non-zero: the non-basic w's, and the basic w's of rows i and k, merged in ascending order.
  auto lex_less = [&](int i, int k, double di, double dk) {
    const double d_max = std::max(di, dk);
    bool less = false;
    auto decides = [&](double a, double b, int c) {
      if (a == 0.0 && b == 0.0) return false;
      const double x = a * dk, y = b * di;
      const double tie =
          opt.tie_tolerance * std::max(std::fabs(x), std::fabs(y)) + 64 * eps * scale_of(c) * d_max;
      if (std::fabs(x - y) <= tie) return false;
      less = x < y;
      return true;
    };
    if (decides(at(i, c_rhs), at(k, c_rhs), -1)) return less;
    list_w_free();
    const int wi = basis[i] < n ? basis[i] : n, wk = basis[k] < n ? basis[k] : n;
    int unit = std::min(wi, wk);  // the next basic w to visit, then the other one
    const int unit_last = std::max(wi, wk);
    for (int f = 0;;) {
      const int free_c = f < w_free_count ? w_free[f] : n;
      if (free_c < unit) {
        const int p = position[free_c];
        if (decides(at(i, p), at(k, p), free_c)) return less;
        ++f;
      } else if (unit < n) {
        if (decides(unit == wi ? 1.0 : 0.0, unit == wk ? 1.0 : 0.0, unit)) return less;
        unit = unit == unit_last ? n : unit_last;
      } else {
        break;
      }
    }
    return i > k;  // unreachable for an invertible basis; keeps the order total
  };
  // Exchanges the basic variable of row r with the non-basic one of column j.
  auto pivot = [&](int r, int j) {
    // Divisions, not a product by 1/p: one rounding per entry, as the full tableau had.
    double* const pr = T + r * ld;
    const double p = pr[j];
    for (int c = 0; c < ld; ++c) pr[c] /= p;
    pr[j] = 1.0 / p;  // the leaving variable's column: 1/p in its row, −d_i/p elsewhere
    // With friction on many contacts the pivot row is mostly zeros (36 of its 130 entries, on
    // average, for 32 contacts): the other rows are then updated on its non-zero columns only.
    // A zero column would change no entry (x − f·0 = x for a finite f; at most a −0 becomes +0, and
    // the answer is read through max(0, ·)), so both loops give the same tableau.
    int nnz = 0;
    for (int c = 0; c < ld; ++c)
      if (pr[c] != 0.0 && c != j) pivot_nz[nnz++] = c;
    const bool sparse = 2 * nnz < ld;
    for (int i = 0; i < n; ++i) {
      if (i == r) continue;
      double* const pi = T + i * ld;
      const double f = pi[j];
      if (f == 0.0) continue;
      if (sparse) {
        for (int k = 0; k < nnz; ++k) pi[pivot_nz[k]] -= f * pr[pivot_nz[k]];
      } else {
        subtract_multiple(pi, pr, f, ld);
      }
      pi[j] = -f / p;
    }
    const int leaving = basis[r], entering = nonbasic[j];
    basis[r] = entering;
    position[entering] = r;
    nonbasic[j] = leaving;
    position[leaving] = j;
    rhs_scale = binv_scale = -1.0;
    w_free_count = -1;
    return leaving;
  };
  // The ratio test on column j: among rows with d_i > threshold, the lexicographic minimum of
  // (rhs_i, B⁻¹ row i) / d_i. The ratios rhs_i / d_i decide unless they tie, so the lexicographic
  // comparison runs only among the rows tied with the smallest. −1 when no row qualifies.
  auto leaving_row = [&](int j, double threshold) {
    int r = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
      const double d = at(i, j);
      if (!(d > threshold)) continue;
      ratio[i] = at(i, c_rhs) / d;
      if (r < 0 || ratio[i] < best) {
        best = ratio[i];
        r = i;
      }
    }
    if (r < 0) return r;
    const int first = r;
    for (int i = 0; i < n; ++i) {
      if (i == first) continue;
      const double d = at(i, j);
      if (!(d > threshold) || !tied(ratio[i], best, -1, std::min(d, at(first, j)))) continue;
      if (lex_less(i, r, d, at(r, j))) r = i;
    }
    return r;
  };

  // First pivot: z₀ enters at the level that makes every w_i ≥ 0. With its column −e every row
  // qualifies and the leaving row is the lexicographic minimum of (q_i, e_iᵀ): the most negative
  // q_i, ties broken by B⁻¹ = I.
  int r = 0;
  for (int i = 1; i < n; ++i)
    if (lex_less(i, r, 1.0, 1.0)) r = i;
  int leaving = pivot(r, n);
  pivots = 1;

  while (leaving != z0) {
    // Complementary pivoting: the complement of the variable that just left enters.
    const int entering = leaving < n ? leaving + n : leaving - n;
    if (pivots >= opt.max_pivots) return LcpStatus::max_pivots;
    const int j = position[entering];
    double d_max = 0.0;
    for (int i = 0; i < n; ++i) d_max = std::max(d_max, std::fabs(at(i, j)));
    const double original = entering >= n ? col_max[entering - n] : 1.0;
    r = leaving_row(j, opt.pivot_tolerance * std::max(d_max, original));
    if (r < 0) return LcpStatus::secondary_ray;
    leaving = pivot(r, j);
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
