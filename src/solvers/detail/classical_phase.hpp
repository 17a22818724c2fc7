#pragma once
// One phase of a classical impact law in contact space (docs/laws.md), and the exact methods that
// solve it: the closed form for one contact, the LCP by lexicographic Lemke, the enumeration of
// contact modes, and the choice of the minimum-norm percussion when G is singular.
//
// Every classical law is one or two phases of the same form. Unknowns: normal percussions x ≥ 0
// and tangential percussions t on the a contacts that take part; velocities
//
//     w = G_NN x + G_NT t + q_N,     0 ≤ x ⊥ w ≥ 0,
//     v = G_TN x + G_TT t + q_T,     Coulomb on (t, v) with bound β = μ∘x + b0,
//
// i.e. |t_i| ≤ β_i, v_i = 0 where |t_i| < β_i, t_i = −β_i sign(v_i) where v_i ≠ 0.
//  - Newton (eq. 5):   q = ((1 + e)∘D_NA, D_TA), b0 = 0; then P = (x, t), w = D_NE + e D_NA.
//  - Poisson, compression: q = D_A, b0 = 0; then P_C = (x, t), D_C = D_A + G P_C.
//  - Poisson, expansion: x = ΔP, q = D_C + G (e∘P_NC, 0), b0 = μ∘e∘P_NC; then
//    P_E = (e∘P_NC + ΔP, t) (docs/laws.md: P_NE = e P_NC + ΔP, bound μ P_NE).
// Without friction rows (or with zero bounds everywhere) t = 0 and the phase is LCP(G_NN, q_N).
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <new>

#include "core/detail/fixed_size.hpp"
#include "core/detail/small_dense.hpp"
#include "core/detail/small_null_space.hpp"
#include "fremond/core/types.hpp"
#include "fremond/solvers/lemke.hpp"
#include "laws/detail/residuals.hpp"
#include "solvers/detail/lemke.hpp"

namespace fremond::detail::classical {

constexpr int times(int m, int k) {
  return m == Dynamic ? Dynamic : k * m;
}

/// A fixed-capacity list (no heap) whose items are constructed only when pushed, so that an empty
/// list costs nothing to create: the solutions of one phase or one law.
template <class T, int Capacity>
struct FixedList {
  int size = 0;
  bool overflow = false;  ///< more were found than fit (the list is then not exhaustive)

  FixedList() = default;
  FixedList(const FixedList&) = delete;
  FixedList& operator=(const FixedList&) = delete;
  ~FixedList() { clear(); }
  void clear() {
    for (int i = 0; i < size; ++i) at(i)->~T();
    size = 0;
    overflow = false;
  }
  /// A new default-constructed item at the end, or nullptr (and `overflow`) when full.
  T* emplace() {
    if (size == Capacity) {
      overflow = true;
      return nullptr;
    }
    return new (at(size++)) T();
  }
  void push(const T& x) {
    if (T* p = emplace()) *p = x;
  }
  const T& operator[](int i) const { return *at(i); }
  T& operator[](int i) { return *at(i); }

 private:
  T* at(int i) { return std::launder(reinterpret_cast<T*>(storage_)) + i; }
  const T* at(int i) const { return std::launder(reinterpret_cast<const T*>(storage_)) + i; }
  alignas(T) unsigned char storage_[sizeof(T) * Capacity];
};

/// How many solutions one phase or one law keeps. Enough for every case met in practice: one
/// contact has at most 4 per phase; more contacts are only enumerated up to 4 (an overflow says
/// the list is not exhaustive).
inline constexpr int kMaxSolutions = 24;

using small_dense::add_product;

/// Vectors and matrices of a given scalar: double everywhere but in the extended-precision
/// decision of a phase's singular modes (decide_in_extended_precision).
template <int Max, class S>
using VecS = Eigen::Matrix<S, Eigen::Dynamic, 1, Eigen::ColMajor, Max, 1>;
template <int MaxR, int MaxC, class S>
using MatS = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, MaxR, MaxC>;

template <int MaxC, class S = double>
struct Phase {
  using Scalar = S;
  static constexpr int kMaxRows = times(MaxC, 2);
  using Rows = VecS<kMaxRows, S>;
  using RowMat = MatS<kMaxRows, kMaxRows, S>;
  using CVec = VecS<MaxC, S>;

  int a = 0;              ///< contacts that take part
  bool friction = false;  ///< tangential rows present (rows = 2a), else rows = a and t = 0
  RowMat G;               ///< rows × rows: [G_NN G_NT; G_TN G_TT] or G_NN
  Rows q;                 ///< rows: (q_N, q_T)
  CVec mu, b0;            ///< a (friction only)

  int rows() const { return friction ? 2 * a : a; }
  /// The velocities (w, v) = G u + q at percussions u = (x, t).
  Rows velocity(const Rows& u) const {
    Rows v = q;
    add_product(G, u, v);
    return v;
  }
};

/// Absolute tolerances of the phase: velocities, and percussions (velocity over the largest G_ii).
struct Tolerances {
  double v = 0.0;
  double p = 0.0;
};

template <int MaxC>
Tolerances tolerances(const Phase<MaxC>& ph, double v_scale, double relative = 1e-9) {
  Tolerances tol;
  tol.v = relative * v_scale;
  const double g = ph.rows() ? ph.G.diagonal().cwiseAbs().maxCoeff() : 1.0;
  tol.p = tol.v / std::max(g, std::numeric_limits<double>::min());
  return tol;
}

// ---------------------------------------------------------------------------------------------
// One contact, closed form.

/// Every solution of a one-contact phase: the open contact (x = 0), sticking (v = 0), and sliding
/// either way (t = −σβ), each a 2×2 closed form (paper eqs. 7-8 with eq. 5 or the Poisson phases).
struct OneContact {
  int count = 0;
  double x[4] = {0, 0, 0, 0}, t[4] = {0, 0, 0, 0};
  bool degenerate = false;  ///< G singular or a continuum of sliding solutions: use the enumeration
};

inline void one_contact_push(OneContact& s, double x, double t, const Tolerances& tol) {
  x = std::max(0.0, x);
  for (int k = 0; k < s.count; ++k)
    if (std::fabs(s.x[k] - x) <= 8 * tol.p && std::fabs(s.t[k] - t) <= 8 * tol.p) return;
  s.x[s.count] = x;
  s.t[s.count] = t;
  ++s.count;
}

/// gnn, gnt, gtt: the contact's Delassus entries; qn, qt: the phase offsets; bound μx + b0.
inline OneContact one_contact(double gnn, double gnt, double gtt, double qn, double qt, double mu,
                              double b0, bool friction, const Tolerances& tol) {
  OneContact s;
  if (!friction || (mu == 0.0 && b0 == 0.0)) {
    // Frictionless (eq. 6 for one contact): x = max(0, −q_N/G_NN).
    if (qn >= 0.0)
      one_contact_push(s, 0.0, 0.0, tol);
    else if (gnn > 0.0)
      one_contact_push(s, -qn / gnn, 0.0, tol);
    else if (qn >= -tol.v)
      one_contact_push(s, 0.0, 0.0, tol);
    return s;
  }
  const double det = gnn * gtt - gnt * gnt;
  if (!(gtt > 0.0) || !(det > 1e-12 * gnn * gtt)) {
    s.degenerate = true;
    return s;
  }
  // Open: x = 0, the tangential percussion alone with the fixed bound b0 (unique as G_TT > 0).
  {
    const double t = b0 > 0.0 ? std::clamp(-qt / gtt, -b0, b0) : 0.0;
    if (qn + gnt * t >= -tol.v) one_contact_push(s, 0.0, t, tol);
  }
  // Stick: w = 0, v = 0.
  {
    const double x = (gnt * qt - gtt * qn) / det, t = (gnt * qn - gnn * qt) / det;
    if (x >= -tol.p && std::fabs(t) <= mu * std::max(0.0, x) + b0 + tol.p)
      one_contact_push(s, x, t, tol);
  }
  // Slide with σ = sign(v): t = −σ(μx + b0), w = 0 gives (G_NN − σμG_NT) x = −q_N + σG_NT b0.
  // A slide with v = 0 is the stick above, so σv must be clearly positive.
  for (const double sigma : {1.0, -1.0}) {
    const double den = gnn - sigma * mu * gnt, num = -qn + sigma * gnt * b0;
    if (std::fabs(den) <= 1e-12 * (gnn + mu * std::fabs(gnt))) {
      if (std::fabs(num) <= tol.v) s.degenerate = true;  // a continuum: let the enumeration decide
      continue;
    }
    const double x = num / den;
    if (x < -tol.p) continue;
    const double t = -sigma * (mu * std::max(0.0, x) + b0);
    const double v = gnt * std::max(0.0, x) + gtt * t + qt;
    if (sigma * v > tol.v) one_contact_push(s, x, t, tol);
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// Several contacts.

/// The cheapest exact guess for several contacts (eq. 6 generalised): every contact closed and,
/// with friction, sticking, u = −G⁻¹q. True when G is regular (`factor` is its factor, anything
/// whose solve(b) gives G⁻¹b; `regular` says it is usable) and u satisfies the phase's
/// inequalities.
template <int MaxC, class Factor>
bool all_closed_guess(const Phase<MaxC>& ph, const Tolerances& tol, const Factor& factor,
                      bool regular, typename Phase<MaxC>::Rows& u) {
  if (!regular) return false;
  const int a = ph.a;
  u = factor.solve(-ph.q);
  for (int i = 0; i < a; ++i) {
    if (u(i) < -tol.p) return false;
    u(i) = std::max(0.0, u(i));
    if (ph.friction && std::fabs(u(a + i)) > ph.mu(i) * u(i) + ph.b0(i) + tol.p) return false;
  }
  return true;
}

/// Two frictionless contacts where the all-closed guess fails (one of them would pull): the modes
/// with one contact closed, u_k = −q_k / G_kk, and the other open, w_o = q_o + G_ok u_k ≥ 0, or
/// both open (q ≥ 0). On a regular G (positive definite, so a P-matrix) the LCP has exactly one
/// solution, so the mode that holds is the one Lemke's pivots would reach (its first pivot on
/// the 2×2 cost more than this whole test). The sign tests are exact: a mode on its border (a
/// percussion or velocity zero only to rounding) is the all-closed guess's, within tol.p, or
/// failing both, Lemke's.
template <int MaxC>
bool one_of_two_closed(const Phase<MaxC>& ph, typename Phase<MaxC>::Rows& u) {
  if (ph.friction || ph.a != 2) return false;
  u.setZero(2);
  if (ph.q(0) >= 0.0 && ph.q(1) >= 0.0) return true;
  for (int k = 0; k < 2; ++k) {
    const int o = 1 - k;
    const double x = -ph.q(k) / ph.G(k, k);
    if (x >= 0.0 && ph.q(o) + ph.G(o, k) * x >= 0.0) {
      u(k) = x;
      return true;
    }
  }
  return false;
}

/// What the semidefinite guess (closed_sticking_semidefinite) knows of the minimum-norm choice
/// among the percussions with its answer's velocities (minimum_norm). With every contact closed and
/// sticking, all velocities are zero, and where null(G) is the line's direction d those
/// percussions are the points u0 + s d inside Coulomb's cone: an interval of s, whose point
/// nearest the line's minimum-norm point is the one the guess returns. Where G's rank is decided
/// clearly, that is minimum_norm's answer, and null(G) need not be computed for it.
struct GuessNorm {
  bool minimum = false;  ///< the answer is the minimum-norm one (G's rank decided clearly)
  bool unique = true;    ///< and no other percussion has its velocities (the interval is a point)
};

namespace semidefinite {

// The body for r = R rows, R known to the compiler: on these few rows the loops unroll, and with a
// runtime bound the loop bookkeeping is most of the work. The factorisation is the pivoted one of
// psd_null_space (small_null_space.hpp: same diagonal pivoting, same 1e-10 threshold), written
// again on purpose: that one works on Eigen storage of runtime size, up to 64 rows, which puts
// this guess above the kernel's target of 100 ns on the flat bar (about 120 ns against 88 ns).
template <int R, int MaxC>
bool closed_sticking(const Phase<MaxC>& ph, const Tolerances& tol, typename Phase<MaxC>::Rows& u,
                     GuessNorm* norm) {
  const int a = ph.a;
  // S: the Schur complement still to factor (kept whole, both triangles); L: the unit lower
  // factor's columns so far; D: the pivots' reciprocals. P G Pᵀ = L D Lᵀ on the first `rank`
  // pivots. Uninitialised on purpose: every entry is written before it is read (L's columns as
  // their pivots are taken, y and dir by the solves).
  double S[R][R], L[R][R], D[R], y[R], dir[R], u0[R], d[R];
  int perm[R];
  double dmax = 0.0;
  for (int i = 0; i < R; ++i) {
    perm[i] = i;
    for (int j = 0; j < R; ++j) S[i][j] = ph.G(i, j);
    dmax = std::max(dmax, S[i][i]);
  }
  if (!(dmax > 0.0) || !std::isfinite(dmax)) return false;
  int rank = 0;
  // The smallest pivot taken (relative to dmax) and the first refused, for GuessNorm::minimum.
  double kept = 1.0, refused = 0.0;
  for (int k = 0; k < R; ++k) {
    int m = k;
    for (int i = k + 1; i < R; ++i)
      if (S[i][i] > S[m][m]) m = i;
    if (!(S[m][m] > 1e-10 * dmax)) {
      refused = S[m][m];
      break;
    }
    kept = std::min(kept, S[m][m] / dmax);
    if (m != k) {  // symmetric swap of rows and columns k, m
      for (int j = 0; j < R; ++j) std::swap(S[k][j], S[m][j]);
      for (int i = 0; i < R; ++i) std::swap(S[i][k], S[i][m]);
      for (int j = 0; j < k; ++j) std::swap(L[k][j], L[m][j]);
      std::swap(perm[k], perm[m]);
    }
    // One division per pivot (its reciprocal, kept in D).
    const double inv = 1.0 / S[k][k];
    D[k] = inv;
    for (int i = k + 1; i < R; ++i) L[i][k] = S[i][k] * inv;
    for (int i = k + 1; i < R; ++i)
      for (int j = k + 1; j < R; ++j) S[i][j] -= L[i][k] * S[k][j];
    rank = k + 1;
  }
  if (rank < R - 1) return false;
  // L11 D L11ᵀ y = −P q on the first `rank` pivots, the free coordinate (if any) 0.
  for (int i = 0; i < rank; ++i) {
    double t = -ph.q(perm[i]);
    for (int k = 0; k < i; ++k) t -= L[i][k] * y[k];
    y[i] = t;
  }
  for (int i = 0; i < rank; ++i) y[i] *= D[i];
  for (int i = rank - 1; i >= 0; --i)
    for (int k = i + 1; k < rank; ++k) y[i] -= L[k][i] * y[k];
  if (rank < R) y[R - 1] = 0.0;
  for (int i = 0; i < R; ++i) u0[perm[i]] = y[i];
  const bool line = rank == R - 1;
  // The inequalities x ≥ 0 and μx + b0 ∓ t ≥ 0 on the line u0 + s d, each as α + β s ≥ 0. (With
  // friction a phase has 2a ≥ 2 rows; said to the compiler, which otherwise warns of u0[a + i]
  // past the end of a single row.)
  auto each_inequality = [&](auto&& f) {
    for (int i = 0; i < a; ++i) {
      f(u0[i], d[i]);
      if constexpr (R >= 2) {
        if (!ph.friction) continue;
        const double cap = ph.mu(i) * u0[i] + ph.b0(i), dcap = ph.mu(i) * d[i];
        f(cap - u0[a + i], dcap - d[a + i]);
        f(cap + u0[a + i], dcap + d[a + i]);
      }
    }
  };
  double s = 0.0;
  if (line) {
    // d = Pᵀ [−L11⁻ᵀ l; 1] with l the free row of L: G d = 0 to rounding.
    dir[R - 1] = 1.0;
    for (int i = rank - 1; i >= 0; --i) {
      double t = -L[R - 1][i];
      for (int k = i + 1; k < rank; ++k) t -= L[k][i] * dir[k];
      dir[i] = t;
    }
    for (int i = 0; i < R; ++i) d[perm[i]] = dir[i];
    // Each inequality α + β s ≥ 0 bounds s on one side; an empty interval: no sticking answer
    // (Lemke decides). The exact inequalities, not relaxed by tol.p: an answer up to tol.p outside
    // Coulomb's cone would pass this guess and then fail the law's own, tighter, test (stalled).
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool feasible = true;
    auto bound = [&](double alpha, double beta) {
      if (beta > 0.0)
        lo = std::max(lo, -alpha / beta);
      else if (beta < 0.0)
        hi = std::min(hi, -alpha / beta);
      else if (alpha < 0.0)
        feasible = false;
    };
    each_inequality(bound);
    if (!feasible || !(lo <= hi)) return false;
    double ud = 0.0, dd = 0.0;
    for (int i = 0; i < R; ++i) {
      ud += u0[i] * d[i];
      dd += d[i] * d[i];
    }
    s = std::clamp(dd > 0.0 ? -ud / dd : 0.0, lo, hi);
    if (!std::isfinite(s)) return false;
  } else {
    for (int i = 0; i < R; ++i) d[i] = 0.0;
  }
  u.resize(R);
  for (int i = 0; i < R; ++i) u(i) = u0[i] + s * d[i];
  for (int i = 0; i < a; ++i) {
    if (u(i) < -tol.p) return false;
    u(i) = std::max(0.0, u(i));
    if (ph.friction && std::fabs(u(a + i)) > ph.mu(i) * u(i) + ph.b0(i) + tol.p) return false;
  }
  // The mode holds only where −q is in G's range: every velocity of the phase vanishes, to the
  // rounding of its own terms (and never beyond tol.v; a NaN fails the test). tol.v alone would
  // let through answers of an ill-conditioned G that the law's residual then refuses, where
  // Lemke's would converge.
  // Column by column (G is column-major), every row's sum still in the order j = 0, 1, …: the
  // same bits as row by row, with the rows side by side in vector registers.
  constexpr double kRounding = 64 * std::numeric_limits<double>::epsilon();
  double v[R], size[R];
  for (int i = 0; i < R; ++i) {
    v[i] = ph.q(i);
    size[i] = std::fabs(ph.q(i));
  }
  for (int j = 0; j < R; ++j) {
    const double uj = u(j);
    for (int i = 0; i < R; ++i) {
      const double t = ph.G(i, j) * uj;
      v[i] += t;
      size[i] += std::fabs(t);
    }
  }
  bool holds = true;
  for (int i = 0; i < R; ++i)
    holds = holds && std::fabs(v[i]) <= std::min(tol.v, kRounding * size[i]);
  if (!holds) return false;
  if (norm) {
    // The rank decided with a margin of 10 on both sides of psd_null_space's threshold (the same
    // pivots, up to rounding): null(G) is then {0} or the line's direction, and u is the point
    // minimum_norm would choose. Unique when the inequalities active at u (within tol.p, as
    // minimum_norm reads them) bound s from both sides.
    norm->minimum = kept > 1e-9 && (!line || refused < 1e-11 * dmax);
    norm->unique = true;
    if (norm->minimum && line) {
      bool below = false, above = false;
      auto active = [&](double alpha, double beta) {
        if (!(alpha + beta * s <= tol.p)) return;
        below = below || beta > 0.0;
        above = above || beta < 0.0;
      };
      each_inequality(active);
      norm->unique = below && above;
    }
  }
  return true;
}

}  // namespace semidefinite

/// The same guess where G is singular (more rows than the body has degrees of freedom: the flat
/// bar on both ends with friction, 4 rows on 3), where every contact closed and sticking,
/// G u = −q, has a line of solutions or none. A symmetric-pivoted LDLᵀ (rank-revealing on a
/// semidefinite G; a pivot below 1e-10 of G's largest diagonal entry ends it) gives one solution
/// u0 and, where G's rank is one short, the line's direction d. The points u0 + s d that satisfy
/// the inequalities (x ≥ 0, |t| ≤ μx + b0) are an interval of s; the one nearest the minimum-norm
/// point of the line is taken. True when that interval is not empty and the mode holds: G u + q
/// vanishes to rounding (q in G's range). Null spaces of two or more dimensions, and
/// phases of more than 8 rows, are left to Lemke (false). No allocation: stack arrays only.
///
/// `norm`, when given, says whether u is also the answer of minimum_norm (and then whether it is
/// unique), so that the law need not compute null(G) for it (see GuessNorm).
template <int MaxC>
bool closed_sticking_semidefinite(const Phase<MaxC>& ph, const Tolerances& tol,
                                  typename Phase<MaxC>::Rows& u, GuessNorm* norm = nullptr) {
  if (norm) *norm = GuessNorm{};
  return with_fixed_size<8>(ph.rows(), [&](auto rows) {
    if constexpr (decltype(rows)::value == 0)
      return false;
    else
      return semidefinite::closed_sticking<decltype(rows)::value>(ph, tol, u, norm);
  });
}

/// True when the phase has no tangential percussion at all (no rows, or every bound identically 0).
template <int MaxC>
bool frictionless(const Phase<MaxC>& ph) {
  if (!ph.friction) return true;
  for (int i = 0; i < ph.a; ++i)
    if (ph.mu(i) != 0.0 || ph.b0(i) != 0.0) return false;
  return true;
}

/// The scales of the phase's rows where they differ: s_i, the size of row i's velocity (its own
/// data q_i, or what the others' percussions make of it), and P_i = s_i / G_ii, the size of its
/// percussion. Lemke's tolerances are relative to the largest right-hand side, and its artificial
/// variable z₀ adds that size to every row: a contact approaching at 1e-10 beside one sliding at
/// 1e6 loses its velocity to that rounding (P_N = 0, D_NE = −1e-10 left in the answer), and so does
/// a contact's normal row beside its own tangential row sliding at 1e6. Each row divided by its
/// own, give the same LCP with data of size 1 (w' = D w, z = S z'); the answer is scaled back.
/// False (nothing to do) when the scales are within a factor 16: the problem is solved as it is,
/// its pivots bit for bit.
///
/// The percussions' sizes from the data: P_N,j ≈ |q_N,j| / G_jj, and P_T,j ≈ |q_T,j| / G_jj, but
/// no more than the cone allows, μ_j P_N,j + b0_j. A row's velocity is at least its terms' size
/// Σ_k |G_ik| P_k, so that a row without data of its own (closed, its velocity made by the others)
/// is not blown up to the size of its rounding.
template <int MaxC>
bool row_scales(const Phase<MaxC>& ph, typename Phase<MaxC>::Rows& s,
                typename Phase<MaxC>::Rows& P) {
  const int a = ph.a, r = ph.rows();
  if (r < 2) return false;
  s.resize(r);
  P.resize(r);
  auto compliance = [&](int i) {
    const double g = ph.G(i, i);
    return g > 0.0 && std::isfinite(g) ? g : 1.0;
  };
  for (int i = 0; i < a; ++i) P(i) = std::fabs(ph.q(i)) / compliance(i);
  for (int i = a; i < r; ++i)
    P(i) = std::min(std::fabs(ph.q(i)) / compliance(i),
                    ph.mu(i - a) * P(i - a) + std::fabs(ph.b0(i - a)));
  double largest = 0.0;
  for (int i = 0; i < r; ++i) {
    double terms = 0.0;
    for (int k = 0; k < r; ++k) terms += std::fabs(ph.G(i, k)) * P(k);
    s(i) = std::max(std::fabs(ph.q(i)), terms);
    largest = std::max(largest, s(i));
  }
  if (!(largest > 0.0) || !std::isfinite(largest)) return false;
  double smallest = largest;
  for (int i = 0; i < r; ++i) {
    if (!(s(i) > 0.0)) s(i) = largest;  // no data and no coupling: any scale is as good
    smallest = std::min(smallest, s(i));
  }
  if (smallest * 16.0 >= largest) return false;
  // A tangential percussion is also bounded by its cone: a contact sliding at 1e6 has P_T = μP_N
  // (0.225), not 1e6 / G_TT, and in units of the latter its last bits would be 1e-10 of P_T.
  for (int i = 0; i < r; ++i) {
    P(i) = s(i) / compliance(i);
    if (i >= a) {
      const double cone = ph.mu(i - a) * P(i - a) + std::fabs(ph.b0(i - a));
      if (cone > 0.0) P(i) = std::min(P(i), cone);
    }
  }
  return true;
}

/// The phase as an LCP solved by lexicographic Lemke. Without friction: LCP(G_NN, q_N), symmetric
/// positive semidefinite, so a secondary ray proves there is no solution. With friction, the
/// 4a-variable form with t = β⁺ − β⁻ (Anitescu & Potra 1997, planar case):
///     D_T + λ ≥ 0 ⊥ β⁺ ≥ 0,   −D_T + λ ≥ 0 ⊥ β⁻ ≥ 0,   μx + b0 − β⁺ − β⁻ ≥ 0 ⊥ λ ≥ 0,
/// whose matrix is copositive (zᵀMz = PᵀGP + λᵀμx) but not copositive-plus: a ray there is not a
/// proof. Where the rows' scales differ (row_scales), each row and unknown is in its own units: a
/// positive diagonal scaling, which keeps the LCP and its matrix's class.
template <int MaxC>
LcpStatus lemke_phase_in(const Phase<MaxC>& ph, const LemkeOptions& opt, bool scaled,
                         const typename Phase<MaxC>::Rows& s, const typename Phase<MaxC>::Rows& P,
                         typename Phase<MaxC>::Rows& u, int& pivots) {
  constexpr int kMaxN = times(MaxC, 4);
  using Mat = MatT<kMaxN, kMaxN>;
  using Vec = VecT<kMaxN>;
  const int a = ph.a;
  Vec z, w;
  u.setZero(ph.rows());
  if (frictionless(ph)) {
    Mat M(a, a);
    Vec q(a);
    for (int j = 0; j < a; ++j)
      for (int i = 0; i < a; ++i) M(i, j) = scaled ? ph.G(i, j) * (P(j) / s(i)) : ph.G(i, j);
    for (int i = 0; i < a; ++i) q(i) = scaled ? ph.q(i) / s(i) : ph.q(i);
    const LcpStatus st = lcp::lemke<kMaxN>(M, q, opt, z, w, pivots);
    if (st == LcpStatus::solved)
      for (int i = 0; i < a; ++i) u(i) = scaled ? P(i) * z(i) : z(i);
    return st;
  }
  // Assembled entry by entry: Eigen's dynamic-size block copies cost more than the 64 entries.
  // Scaled (row_scales): x_j by P_j and β±_j by P_{a+j} (percussions), λ_j by s_{a+j} (the
  // tangential velocity it bounds); the rows of contact i by s_i (normal), s_{a+i} (tangential),
  // and the bound's row μx + b0 − β⁺ − β⁻ by P_{a+i} (a percussion).
  const int n = 4 * a;
  Mat M(n, n);
  Vec q(n);
  M.setZero();
  for (int j = 0; j < a; ++j)
    for (int i = 0; i < a; ++i) {
      const double fnn = scaled ? P(j) / s(i) : 1.0, fnt = scaled ? P(a + j) / s(i) : 1.0;
      const double ftn = scaled ? P(j) / s(a + i) : 1.0;
      const double ftt = scaled ? P(a + j) / s(a + i) : 1.0;
      const double gnn = ph.G(i, j) * fnn, gnt = ph.G(i, a + j) * fnt;
      const double gtn = ph.G(a + i, j) * ftn, gtt = ph.G(a + i, a + j) * ftt;
      M(i, j) = gnn;
      M(i, a + j) = gnt;
      M(i, 2 * a + j) = -gnt;
      M(a + i, j) = gtn;
      M(a + i, a + j) = gtt;
      M(a + i, 2 * a + j) = -gtt;
      M(2 * a + i, j) = -gtn;
      M(2 * a + i, a + j) = -gtt;
      M(2 * a + i, 2 * a + j) = gtt;
    }
  for (int i = 0; i < a; ++i) {
    M(a + i, 3 * a + i) = 1.0;
    M(2 * a + i, 3 * a + i) = 1.0;
    M(3 * a + i, i) = scaled ? ph.mu(i) * (P(i) / P(a + i)) : ph.mu(i);
    M(3 * a + i, a + i) = -1.0;
    M(3 * a + i, 2 * a + i) = -1.0;
    q(i) = scaled ? ph.q(i) / s(i) : ph.q(i);
    q(a + i) = scaled ? ph.q(a + i) / s(a + i) : ph.q(a + i);
    q(2 * a + i) = -q(a + i);
    q(3 * a + i) = scaled ? ph.b0(i) / P(a + i) : ph.b0(i);
  }
  const LcpStatus st = lcp::lemke<kMaxN>(M, q, opt, z, w, pivots);
  if (st == LcpStatus::solved)
    for (int i = 0; i < a; ++i) {
      u(i) = scaled ? P(i) * z(i) : z(i);
      u(a + i) = scaled ? P(a + i) * (z(a + i) - z(2 * a + i)) : z(a + i) - z(2 * a + i);
    }
  return st;
}

/// lemke_phase_in, in the rows' own units where their scales differ (row_scales). With friction the
/// LCP is not copositive-plus and whether Lemke's path ends on a ray depends on the units: a ray in
/// the scaled units is tried again in the problem's. Scaling ends on rays less often; where the
/// phase has several answers (μ = 1e8 or G singular) its path may reach a farther one, which the
/// law's test can refuse; the enumeration's retry (classical.cpp) covers those.
template <int MaxC>
LcpStatus lemke_phase(const Phase<MaxC>& ph, const LemkeOptions& opt, typename Phase<MaxC>::Rows& u,
                      int& pivots) {
  typename Phase<MaxC>::Rows s, P;
  const bool scaled = row_scales(ph, s, P);
  LcpStatus st = lemke_phase_in(ph, opt, scaled, s, P, u, pivots);
  if (scaled && st != LcpStatus::solved) {
    int more = 0;
    st = lemke_phase_in(ph, opt, false, s, P, u, more);
    pivots += more;
  }
  return st;
}

/// Projects 0 onto {y : B y ≥ d} shifted by y0, i.e. min ‖y − y0‖ s.t. B y ≥ d, through its dual
/// LCP(BBᵀ, B y0 − d) (symmetric positive semidefinite: Lemke finds the answer or proves the set
/// empty). Returns false when the set is empty.
template <int MaxC, class BMat, class Vec1, class Vec2>
bool project_polyhedron(const BMat& B, const Vec1& d, const Vec2& y0, VecT<times(MaxC, 2)>& y) {
  constexpr int kMaxN = times(MaxC, 4);
  const int m = static_cast<int>(B.rows());
  y = y0;
  if (m == 0) return true;
  if ((B * y0 - d).minCoeff() >= 0.0) return true;  // the unconstrained minimiser is feasible
  MatT<kMaxN, kMaxN> BBt(m, m);
  BBt.noalias() = B * B.transpose();
  VecT<kMaxN> q(m), lambda, w;
  q.noalias() = B * y0;
  q -= d;
  int pivots = 0;
  if (lcp::lemke<kMaxN>(BBt, q, LemkeOptions{}, lambda, w, pivots) != LcpStatus::solved)
    return false;
  y.noalias() += B.transpose() * lambda;
  return true;
}

/// The linear description of the percussions u that solve the phase with a given mode: equalities
/// K u = rhs, inequalities C u ≥ g. Modes per contact: normal open (x = 0, w ≥ 0) or closed
/// (w = 0, x ≥ 0); tangential zero (t = 0, bound identically 0), stick (v = 0, |t| ≤ β) or slide
/// σ = ±1 (t = −σβ, σv ≥ 0).
enum class Tangential { zero, stick, slide_positive, slide_negative };

template <int MaxC, class S = double>
struct ModeSystem {
  static constexpr int kMaxRows = times(MaxC, 2);
  static constexpr int kMaxIneq = times(MaxC, 3);
  MatS<kMaxRows, kMaxRows, S> K;
  VecS<kMaxRows, S> rhs;
  MatS<kMaxIneq, kMaxRows, S> C;
  VecS<kMaxIneq, S> g;
  int m = 0;  ///< inequality rows used
};

template <int MaxC, class S>
void build_mode(const Phase<MaxC, S>& ph, const int* normal_closed, const Tangential* tang,
                ModeSystem<MaxC, S>& s) {
  using Row = VecS<times(MaxC, 2), S>;
  const int a = ph.a, r = ph.rows();
  s.K.setZero(r, r);
  s.rhs.setZero(r);
  s.C.setZero(3 * a, r);
  s.g.setZero(3 * a);
  s.m = 0;
  auto ineq = [&](auto row, S g) {
    s.C.row(s.m) = row;
    s.g(s.m++) = g;
  };
  for (int i = 0; i < a; ++i) {
    if (normal_closed[i]) {
      s.K.row(i) = ph.G.row(i);
      s.rhs(i) = -ph.q(i);
      ineq(Row::Unit(r, i).transpose(), S(0));
    } else {
      s.K(i, i) = 1.0;
      ineq(ph.G.row(i), -ph.q(i));
    }
    if (!ph.friction) continue;
    const int k = a + i;
    switch (tang[i]) {
      case Tangential::zero:
        s.K(k, k) = 1.0;
        break;
      case Tangential::stick: {
        s.K.row(k) = ph.G.row(k);
        s.rhs(k) = -ph.q(k);
        Row up = Row::Zero(r), lo = up;
        up(i) = ph.mu(i);
        up(k) = -1.0;  // μx + b0 − t ≥ 0
        lo(i) = ph.mu(i);
        lo(k) = 1.0;  // μx + b0 + t ≥ 0
        ineq(up.transpose(), -ph.b0(i));
        ineq(lo.transpose(), -ph.b0(i));
        break;
      }
      case Tangential::slide_positive:
      case Tangential::slide_negative: {
        const double sigma = tang[i] == Tangential::slide_positive ? 1.0 : -1.0;
        s.K(k, k) = 1.0;  // t + σμx = −σ b0
        s.K(k, i) = sigma * ph.mu(i);
        s.rhs(k) = -sigma * ph.b0(i);
        ineq(sigma * ph.G.row(k), -sigma * ph.q(k));
        break;
      }
    }
  }
}

/// Solves one mode: a point u of {K u = rhs, C u ≥ g − tolerance} if there is one. `moves` is set
/// when K is singular and a direction of its null space changes the velocities (a possible
/// continuum of solutions); `near_singular` when u is the regular solution of a K singular to the
/// rank test but not to rounding (a last resort: see enumerate_modes).
template <int MaxC, class S>
bool solve_mode(const Phase<MaxC, S>& ph, const ModeSystem<MaxC, S>& s, const Tolerances& tol,
                typename Phase<MaxC, S>::Rows& u, bool& moves, bool& near_singular) {
  constexpr int kMaxRows = times(MaxC, 2);
  using Rows = typename Phase<MaxC, S>::Rows;
  constexpr S kEps = std::numeric_limits<S>::epsilon();
  // The finer rank test below: 1e-14 of the largest singular value in double, as many times the
  // unit roundoff in a wider type.
  constexpr S kFine = S(1e-14) * (kEps / std::numeric_limits<double>::epsilon());
  const int r = ph.rows();
  moves = false;
  near_singular = false;
  // A row's tolerance scales with the row: tol.p · ‖row‖∞ is about tol.v for velocity rows (G rows)
  // and tol.p for percussion rows (entries 1 and μ).
  auto row_tol = [&](int j) -> S { return tol.p * s.C.row(j).cwiseAbs().maxCoeff(); };
  // The mode's inequalities at u, each to its tolerance and to the rounding of its own product:
  // percussions 1e10 times the velocities they make (cond(M) = 1e11, μ = 1e8) leave ε|C_j||u| in
  // C_j u, far above the tolerance (a contact open at D_NE = 0 to rounding would be refused).
  auto meets_inequalities = [&](const Rows& x) {
    for (int j = 0; j < s.m; ++j) {
      const S noise = 64 * kEps * (s.C.row(j).cwiseAbs().dot(x.cwiseAbs()) + std::fabs(s.g(j)));
      if (s.C.row(j).dot(x) - s.g(j) < -(row_tol(j) + noise)) return false;
    }
    return true;
  };
  // The rank tests on K with each row scaled to a largest entry of 1: its rows are in different
  // units (velocity rows of G, percussion rows of 1 and μ), and a relative threshold on K as formed
  // took G's own small directions (cond(M) = 1e11: G's singular values 1e-13 of a row's 1) for
  // rounding beside a percussion row, or a row (1, μ = 1e8) hid the pivots of every other. The
  // scale is capped at 2^1000: a row whose largest entry is subnormal (G = W²/M = 3e-309 with M =
  // 7.7e307) has no finite reciprocal, and a row of ∞ would send the SVD below reading out of
  // bounds.
  VecS<kMaxRows, S> row_scale(r);
  for (int j = 0; j < r; ++j) {
    const S m = s.K.row(j).cwiseAbs().maxCoeff();
    row_scale(j) = m > 0 ? std::min<S>(S(1) / m, S(0x1p1000)) : S(1);
  }
  const MatS<kMaxRows, kMaxRows, S> Ks = row_scale.asDiagonal() * s.K;
  const VecS<kMaxRows, S> rhs_s = row_scale.cwiseProduct(s.rhs);
  if (!Ks.allFinite() || !rhs_s.allFinite()) return false;  // no factorisation of ∞ or NaN
  Eigen::FullPivLU<MatS<kMaxRows, kMaxRows, S>> lu(Ks);
  lu.setThreshold(1e-10);
  if (lu.rank() == r) {
    u = lu.solve(rhs_s);
    return meets_inequalities(u);
  }
  // Singular mode (e.g. the flat bar's equal tangents): u = u0 + N y, feasibility by projection.
  Eigen::JacobiSVD<MatS<kMaxRows, kMaxRows, S>> svd(Ks, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const auto& sv = svd.singularValues();
  const S smax = sv.size() ? sv(0) : S(0);
  int rank = 0;
  while (rank < sv.size() && sv(rank) > 1e-10 * smax) ++rank;
  // Consistent to the tolerance; on the last-resort path below also to the rounding of the
  // product K u0 itself: where a consistent singular mode needs percussions 1e10 times the
  // velocities they make (cond(M) = 1e11), ε|K||u0| is far above the tolerance. (Not on the first
  // test: with μ = 1e8 in a sliding row, ε|K||u0| lets a truncated u0 that solves nothing through,
  // and its answer would displace the exact ones of the near-singular modes.)
  auto consistent = [&](const Rows& x, bool rounding) {
    const S allowed = std::max<S>(tol.v, tol.p * s.K.cwiseAbs().maxCoeff());
    const Rows Kx = s.K * x;
    for (int j = 0; j < r; ++j) {
      const S noise =
          rounding ? 64 * kEps * (s.K.row(j).cwiseAbs().dot(x.cwiseAbs()) + std::fabs(s.rhs(j)))
                   : S(0);
      if (!(std::fabs(Kx(j) - s.rhs(j)) <= allowed + noise)) return false;
    }
    return true;
  };
  svd.setThreshold(1e-10);
  Rows u0 = svd.solve(rhs_s);
  if (!consistent(u0, false)) {
    // Inconsistent to the rank test, but the singular values from 1e-14 to 1e-10 of the largest may
    // be the data's own: cond(M) = 1e11 spreads G over eleven decades, and the mode's answer (every
    // contact closed by q̇_E = −e q̇_A, percussions 1e10) lies along them. Refusing it takes a mode
    // with an answer for one without, and the law would say `no_solution`. K regular to that finer
    // test (cond(K) from 1e10 to 1e14: two contacts closed, one sticking, cond(G) = 3e11) has the
    // regular solution of K as formed. Either is the answer of data that near, taken where it meets
    // the mode's inequalities and only as a last resort (enumerate_modes); the law's residual
    // judges it as any other.
    int fine = rank;
    while (fine < sv.size() && sv(fine) > kFine * smax) ++fine;
    if (fine == rank) return false;
    svd.setThreshold(kFine);
    u0 = svd.solve(rhs_s);
    if (!u0.allFinite()) return false;
    near_singular = true;
    if (fine == r) {  // regular: its solve leaves cond(K)·ε, not ε, in K u0 − rhs
      u = u0;
      return meets_inequalities(u);
    }
    if (!consistent(u0, true)) return false;
    rank = fine;
  }
  const MatS<kMaxRows, kMaxRows, S> N = svd.matrixV().rightCols(r - rank);
  // The projection in double whatever S: its data, the mode's inequalities on the null space,
  // are not where the precision is needed (K's small singular values are).
  const MatT<times(MaxC, 3), kMaxRows> B = (s.C.topRows(s.m) * N).template cast<double>();
  VecT<times(MaxC, 3)> d = (s.g.head(s.m) - s.C.topRows(s.m) * u0).template cast<double>();
  VecT<kMaxRows> y;
  const VecT<kMaxRows> y0 = VecT<kMaxRows>::Zero(r - rank);
  // The inequalities exactly first: relaxed by their tolerance from the start, the projection
  // stops on the relaxed boundary (a wedged corner's neighbour then sat 2e-10 outside Coulomb's
  // cone where a point of the null space meets it exactly). The relaxed set only when the exact
  // one is empty (rounding of u0).
  if (!project_polyhedron<MaxC>(B, d, y0, y)) {
    for (int j = 0; j < s.m; ++j) d(j) -= static_cast<double>(row_tol(j));
    if (!project_polyhedron<MaxC>(B, d, y0, y)) return false;
  }
  u = u0 + N * y.template cast<S>();
  // G N entry by entry: a temporary G N of long doubles drew a false maybe-uninitialized warning.
  S moved = 0;
  for (int c = 0; c < N.cols(); ++c)
    for (int j = 0; j < r; ++j) moved = std::max<S>(moved, std::fabs(ph.G.row(j).dot(N.col(c))));
  moves = moved > 1e-9 * std::max<S>(1, ph.G.cwiseAbs().maxCoeff());
  return true;
}

/// The phase's own residual at u, in velocity units: the natural map of each complementarity
/// (min(w_i, G_ii x_i)) and of Coulomb's law (G_kk (t − clamp(t − v/G_kk, −β, β))), as the law's
/// residual (classical_residual) takes them. Zero exactly at a solution; rounding otherwise.
template <int MaxC, class S>
double phase_residual(const Phase<MaxC, S>& ph, const typename Phase<MaxC, S>::Rows& u) {
  const int a = ph.a;
  const typename Phase<MaxC, S>::Rows v = ph.velocity(u);
  auto diag = [&](int j) -> S { return ph.G(j, j) > 0 ? ph.G(j, j) : S(1); };
  S worst = 0;
  for (int i = 0; i < a; ++i) {
    worst = std::max(worst, std::fabs(std::min<S>(v(i), u(i) == 0 ? S(0) : diag(i) * u(i))));
    if (!ph.friction) continue;
    const int k = a + i;
    const S g = diag(k), t = u(k), b = std::max<S>(0, ph.mu(i) * u(i) + ph.b0(i));
    worst = std::max(worst, std::fabs(g * (t - std::clamp(t - v(k) / g, -b, b))));
  }
  return static_cast<double>(worst);
}

/// Whether `candidate` solves the phase clearly more exactly than `kept`: its residual is below
/// half of `kept`'s, and `kept`'s is beyond rounding (1e-3 of the velocity tolerance), so that
/// two exact answers keep the first.
inline bool clearly_more_exact(double candidate, double kept, const Tolerances& tol) {
  return kept > 1e-3 * tol.v && candidate < 0.5 * kept;
}

/// The contacts from which Newton + Coulomb goes to the sweeps first (classical.cpp) where G is
/// singular (more rows than degrees of freedom): Lemke's pivots on the friction LCP grow as their
/// cube, a sweep's cost as G's rows or the body's velocities.
inline constexpr int kSweepsFromContacts = 8;
/// The same where G is regular: the sweeps and the mode Newton end the random bodies' solves in
/// 8 % less time than Lemke on 12 contacts, 25 % on 15, 34 % on 18; on 9 they cost the same.
inline constexpr int kSweepsRegularFromContacts = 12;
/// Their budget there before Lemke takes over: four runs of the mode Newton (measures 2, 4, 8, 16).
inline constexpr int kChainSweeps = 256;
inline constexpr int kMaxEnumerated = 4;  ///< the most contacts enumerate_modes takes (4⁴ modes)
/// The most contacts on which automatic lists every solution (to say whether the answer is
/// unique) even after Lemke found one: 64 modes cost tens of microseconds, 256 a few hundred. On 4
/// contacts the enumeration runs only where Lemke finds no answer.
inline constexpr int kMaxEnumeratedAlways = 3;

/// Every solution of a phase with friction, by trying every contact mode (up to 6 per contact).
/// Solutions with the same velocities are one (their percussions differ only where G is singular;
/// `minimum_norm` then picks one). Of two modes that give the same velocities the one that solves
/// the phase more exactly (phase_residual) is kept: two corners of a resting block whose W_T differ
/// by 3e-11 cannot both stick after a rotating expansion (their tangential velocities differ by
/// 4e-15), and the singular stick-stick mode, accepted within its tolerance, would hide the exact
/// stick-slide answer. `continuum` is set when a singular mode may hold a continuum of velocities.
template <int MaxC, class S>
void enumerate_modes(const Phase<MaxC, S>& ph, const Tolerances& tol,
                     FixedList<typename Phase<MaxC, S>::Rows, kMaxSolutions>& out,
                     bool& continuum) {
  using Rows = typename Phase<MaxC, S>::Rows;
  const int a = ph.a;
  continuum = false;
  constexpr int kMaxEnum = kMaxEnumerated;
  if (a > kMaxEnum) return;
  // Per contact, the list of (closed, tangential) modes that make sense.
  std::array<std::array<std::pair<int, Tangential>, 6>, kMaxEnum> modes{};
  std::array<int, kMaxEnum> count{}, pick{};
  for (int i = 0; i < a; ++i) {
    int c = 0;
    const bool zero_bound = !ph.friction || (ph.mu(i) == 0.0 && ph.b0(i) == 0.0);
    for (int closed = 0; closed < 2; ++closed) {
      if (zero_bound || (!closed && ph.b0(i) == 0.0)) {
        modes[i][c++] = {closed, Tangential::zero};
      } else {
        for (Tangential t :
             {Tangential::stick, Tangential::slide_positive, Tangential::slide_negative})
          modes[i][c++] = {closed, t};
      }
    }
    count[i] = c;
  }
  ModeSystem<MaxC, S> sys;
  Rows u;
  std::array<double, kMaxSolutions> residual{}, fallback_residual{};  // of out[k], fallback[k]
  FixedList<Rows, kMaxSolutions> fallback;  // the answers of near-singular modes
  // Adds u to `list` unless an answer with the same velocities is there (then the more exact of
  // the two is kept).
  auto keep = [&](FixedList<Rows, kMaxSolutions>& list, std::array<double, kMaxSolutions>& res,
                  const Rows& x) {
    const double rx = phase_residual(ph, x);
    const Rows v = ph.velocity(x);
    int seen = -1;
    for (int k = 0; k < list.size && seen < 0; ++k)
      if ((ph.velocity(list[k]) - v).cwiseAbs().maxCoeff() <= 16 * tol.v) seen = k;
    if (seen < 0) {
      if (list.size < kMaxSolutions) res[list.size] = rx;
      list.push(x);
    } else if (clearly_more_exact(rx, res[seen], tol)) {
      list[seen] = x;
      res[seen] = rx;
    }
  };
  int normal_closed[kMaxEnum];
  Tangential tang[kMaxEnum];
  while (true) {
    for (int i = 0; i < a; ++i) {
      normal_closed[i] = modes[i][pick[i]].first;
      tang[i] = modes[i][pick[i]].second;
    }
    build_mode(ph, normal_closed, tang, sys);
    bool moves = false, near_singular = false;
    if (solve_mode(ph, sys, tol, u, moves, near_singular)) {
      for (int i = 0; i < a; ++i) u(i) = std::max<S>(0, u(i));
      // A mode singular to the rank test but not to rounding is a last resort, taken only where
      // no mode has an answer by the rank test: on 4 contacts of 2 dofs with cond(M) = 1e10 such
      // a mode's answer, 1e-6 off, would take the place of the enumeration's exact one.
      if (near_singular) {
        keep(fallback, fallback_residual, u);
      } else {
        continuum = continuum || moves;
        keep(out, residual, u);
      }
    }
    int i = 0;
    while (i < a && ++pick[i] == count[i]) pick[i++] = 0;
    if (i == a) break;
  }
  if (out.size == 0)
    for (int k = 0; k < fallback.size; ++k) out.push(fallback[k]);
}

/// An orthonormal basis of null(G) (= null(W)): the directions along which the percussions of a
/// phase can change without changing any velocity. Empty when G is regular. Pivots below 1e-10 of
/// the largest count as zero (small_null_space.hpp).
template <int MaxC>
MatT<times(MaxC, 2), times(MaxC, 2)> null_space(const typename Phase<MaxC>::RowMat& G) {
  typename Phase<MaxC>::RowMat N;
  psd_null_space<times(MaxC, 2)>(G, 1e-10, N);
  return N;
}

/// out = the first `count` rows of A times X, for rows with a few non-zero entries (minimum_norm's
/// equalities and inequalities have one or two): only those entries' products, where a dense
/// product multiplies every zero too (on 32 contacts with friction, 64 × 64 × 61 for E·NG).
/// The non-zero products are summed in column order from zero, as the dense product sums its
/// terms (its zero ones add nothing): the same terms in the same order.
template <class MatA, class MatX, class MatOut>
void few_nonzero_rows_times(const MatA& A, int count, const MatX& X, MatOut& out) {
  out.setZero(count, X.cols());
  for (int e = 0; e < count; ++e)
    for (Eigen::Index k = 0; k < A.cols(); ++k)
      if (const double a = A(e, k); a != 0.0) out.row(e) += a * X.row(k);
}

/// Among the percussions that solve the phase with the same velocities as u (a polyhedron when G is
/// singular: the velocities fix G u, and each contact's sign pattern fixes linear conditions), the
/// one that minimises ‖u + shift‖ (`shift` turns the phase unknowns into the physical percussion:
/// Poisson's expansion adds e∘P_NC). NG is null_space(G). Replaces u; returns true when that set
/// is a single point.
template <int MaxC>
bool minimum_norm(const Phase<MaxC>& ph, const Tolerances& tol,
                  const MatT<times(MaxC, 2), times(MaxC, 2)>& NG,
                  const typename Phase<MaxC>::Rows& shift, typename Phase<MaxC>::Rows& u) {
  constexpr int kMaxRows = times(MaxC, 2);
  constexpr int kMaxIneq = times(MaxC, 3);
  using Rows = typename Phase<MaxC>::Rows;
  using RowMat = MatT<kMaxRows, kMaxRows>;
  const int a = ph.a, r = ph.rows();
  if (NG.cols() == 0) return true;
  const Rows u_in = u;
  const double residual_in = phase_residual(ph, u);
  const Rows v = ph.velocity(u);
  RowMat E(r, r);  // equalities E δ = 0 beside G δ = 0: at most one per row
  E.setZero();
  int ne = 0;
  MatT<kMaxIneq, kMaxRows> C(3 * a, r);
  C.setZero();
  VecT<kMaxIneq> g(3 * a);
  int m = 0;
  for (int i = 0; i < a; ++i) {
    if (v(i) > tol.v) {
      E(ne++, i) = 1.0;  // separating: x_i = 0
    } else {
      C(m, i) = 1.0;  // x_i ≥ 0
      g(m++) = 0.0;
    }
    if (!ph.friction) continue;
    const int k = a + i;
    if (ph.mu(i) == 0.0 && ph.b0(i) == 0.0) {
      E(ne++, k) = 1.0;
    } else if (std::fabs(v(k)) > tol.v) {
      const double sigma = v(k) > 0 ? 1.0 : -1.0;  // sliding: t + σμx = −σb0
      E(ne, k) = 1.0;
      E(ne++, i) = sigma * ph.mu(i);
    } else {
      C(m, i) = ph.mu(i);  // sticking: μx + b0 ∓ t ≥ 0
      C(m, k) = -1.0;
      g(m++) = -ph.b0(i);
      C(m, i) = ph.mu(i);
      C(m, k) = 1.0;
      g(m++) = -ph.b0(i);
    }
  }
  // null([G; E]) = NG · null(E NG): a small SVD of E NG only.
  RowMat N = NG;
  if (ne > 0) {
    RowMat ENG;
    few_nonzero_rows_times(E, ne, NG, ENG);
    Eigen::JacobiSVD<RowMat> svd(ENG, Eigen::ComputeFullV);
    const auto& sv = svd.singularValues();
    const double scale = std::max(1.0, E.topRows(ne).cwiseAbs().maxCoeff());
    int rank = 0;
    while (rank < sv.size() && sv(rank) > 1e-10 * scale) ++rank;
    if (rank == NG.cols()) return true;
    N = NG * svd.matrixV().rightCols(NG.cols() - rank);
  }
  MatT<kMaxIneq, kMaxRows> B;
  few_nonzero_rows_times(C, m, N, B);
  // u itself satisfies the inequalities up to rounding; clip that rounding so that y = 0 is exactly
  // feasible and the answer violates nothing by more than it.
  VecT<kMaxIneq> d = (g.head(m) - C.topRows(m) * u).cwiseMin(0.0);
  const VecT<kMaxRows> y0 = -N.transpose() * (u + shift);
  VecT<kMaxRows> y;
  if (!project_polyhedron<MaxC>(B, d, y0, y)) return false;
  u += N * y;
  for (int i = 0; i < a; ++i) u(i) = std::max(0.0, u(i));
  // The modes above are read from the velocities within tol.v: where G is singular only up to
  // rounding (two corners whose W_T differ by 3e-11), a contact that slides at 4e-15 is read as
  // sticking, and the set reached from u is a continuum within the tolerance only. Its
  // minimum-norm point then misses the law that u meets exactly; u is the answer, and whether it
  // is a single point is asked at u (y = 0), not taken for granted: such a u can lie on a
  // one-sided continuum.
  if (clearly_more_exact(residual_in, phase_residual(ph, u), tol)) {
    u = u_in;
    y.setZero();
  }
  // Single point? Only if no direction of the null space is feasible at y: project ±e_j onto the
  // cone {δ : B_A δ ≥ 0} of the active rows; a non-zero projection is a feasible direction.
  const int dim = static_cast<int>(N.cols());
  MatT<kMaxIneq, kMaxRows> BA(m, dim);
  int na = 0;
  for (int j = 0; j < m; ++j)
    if (B.row(j).dot(y) - d(j) <= tol.p) BA.row(na++) = B.row(j);
  if (na == 0) return false;
  const VecT<kMaxIneq> zero = VecT<kMaxIneq>::Zero(na);
  for (int j = 0; j < dim; ++j)
    for (const double s : {1.0, -1.0}) {
      const VecT<kMaxRows> e = s * VecT<kMaxRows>::Unit(dim, j);
      VecT<kMaxRows> delta;
      if (!project_polyhedron<MaxC>(BA.topRows(na), zero, e, delta)) continue;
      if (delta.norm() > 1e-6) return false;
    }
  return true;
}

}  // namespace fremond::detail::classical
