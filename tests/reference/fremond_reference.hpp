#pragma once
/// @file An independent high-precision reference for the impact laws, in `__float128` (libquadmath:
/// link with `-lquadmath`). It shares no code with the library: its own linear algebra, its own
/// root finders, its own reading of docs/concepts.md and docs/laws.md. Use it to check the
/// library's solvers, never inside them.
///
/// What it solves (docs/concepts.md: D = Wᵀ q̇ + w, G = Wᵀ M⁻¹ W, D_E = D_A + G P, z = (D_A +
/// D_E)/2; P ≥ 0 pushes apart; only contacts with D_NA ≤ 0 take part, the others get no
/// percussion):
///
///  - fremond_one_contact(): Frémond's law on ONE contact, any M, with the normal law
///    −P_N ∈ k z_N|z_N|^(p−2) + N_R+(D_NE) (docs/laws.md) and the tangential law none, the
///    viscous dead zone −P_T = k_T sign(z_T) max(0, |z_T| − r)^(q−1) (eq. 25 in our scaling), or
///    Coulomb on (P_T, z_T) with the bound μ|P_N|. Returns EVERY solution (several or none are
///    possible with Coulomb when μ|G_NT| > G_NN). Method: the reaction is the normal cone of z_N ≥
///    D_NA/2 (that is D_NE ≥ 0), so for a fixed tangential mode the normal law is one scalar
///    inclusion z_N + (α/2)(f_N(z_N) + N(z_N)) ∋ b; for α > 0 it has one root (a monotone equation,
///    then a clamp at D_NA/2), for α < 0 (Painlevé) every root is found on the ≤ 3 intervals where
///    it is monotone. Coulomb: modes stick (z_T = 0) and slide σ = ±1 with each sign of P_N. Dead
///    zone: the tangential equation P_T + f_T(z_T(P_T)) = 0, with z_T(P_T) from the normal solve,
///    is strictly increasing in P_T (a partial minimisation of the dual problem), so one bracketed
///    root (its mode, in the zone or out on a side, is read off the answer). Every scalar root is
///    found by bisection safeguarding Newton's method, to the last bit of quad precision.
///  - fremond_several(): Frémond's law on several contacts, normal law with the tangential law none
///    or dead zone (not Coulomb): the strongly convex problem of docs/laws.md, solved in contact
///    space (no G⁻¹) through its optimality system z = D_A + G P/2 with each row's law written with
///    its resolvent z_j = J_j(s_j), P_j = c_j (z_j − s_j) (the reaction is the clamp of J_N at
///    D_NA/2): non-smooth Gauss-Seidel sweeps (each row solved exactly by the scalar root finder;
///    the block coordinate descent of the dual problem, which converges), then Levenberg-Marquardt
///    on F(s) = z(s) − D_A − G P(s)/2, whose Jacobian stays bounded for p or q near 1 and for large
///    p.
///  - fremond_coulomb_near(): Frémond + Coulomb on several contacts, not as a reference (the law is
///    quasi-variational there, and no method here lists every solution) but as a check of a given
///    answer: the exact solution nearest to it, each contact mode the answer lies near solved by
///    damped Newton in quad precision and its inequalities and residual checked.
///  - newton_frictionless(): Newton's law, LCP 0 ≤ P_N ⊥ G_NN P_N + (1 + e) D_NA ≥ 0 (eq. 6 for one
///    contact), by enumeration of the active sets; every distinct solution of a regular active
///    set (a singular one is skipped: where G_NN is singular the list may be empty although the
///    law has a solution; classical_modes says so).
///  - classical_modes(): Newton's or Poisson's law, with or without Coulomb friction (docs/laws.md
///    table; Poisson + Coulomb in the compression/expansion form), on up to 4 contacts taking part,
///    by enumeration of every contact mode of each phase (normal open or closed; tangential stick,
///    slide forwards or backwards, or held at zero where the bound is zero): each mode's linear
///    equations solved, its inequalities checked. Every solution; `complete` is false when some
///    mode's equations are singular to 1e-12 (G singular: a continuum of percussions may solve
///    it, which the enumeration does not list; or so nearly singular that double-precision data
///    cannot resolve the answer). The law's residual (classical_residual(), from the velocities
///    the percussions make) comes with each solution.
///
/// Ranges: checked (tests/unit/reference_selftest.cpp) for p ∈ [1.01, 50], q ∈ [1.01, 3], r from 0
/// to above every velocity, |D_A| from 1e-10 to 1e6, k from 1e-6 to 1e6, mass ratios up to 1e6.
/// The law's residual (fremond_residual(), a backward error, reported with each solution) is then
/// about 1e-33, and up to cond(M)·1e-34 for ill-conditioned M. Cost: a few ms for one contact, up
/// to about a second for several contacts with stiff masses.
/// Not handled: α = 0 exactly in a Coulomb slide mode (μ G_NT = ±G_NN: a continuum of solutions or
/// none; that mode is skipped), stick with W_T parallel to W_N (G singular on one contact) and
/// D_NE = 0 exactly (the reaction free: a continuum),
/// every solution of Frémond + Coulomb on several contacts (fremond_coulomb_near checks one
/// answer), more than 12 contacts taking part in newton_frictionless (2^c active sets), more than 4
/// in classical_modes (6^c modes a phase), and whether a classical law has a solution where a mode
/// is singular (classical_modes says `complete` = false). Observed, not proved: on one contact with
/// Coulomb the number of solutions found was always odd (1 or 3) over 20000 random draws up to μ =
/// 400, never 0.
#include <quadmath.h>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fremond_reference {

using quad = __float128;
using QVec = std::vector<quad>;

// ---------------------------------------------------------------------------------------------
// Data

/// One impact problem in quad precision (docs/concepts.md). W_N[i] and W_T[i] are the columns of
/// contact i (length n each); W_T empty: frictionless. w_N, w_T empty: zero.
struct Problem {
  std::vector<QVec> M;  ///< n rows of n, symmetric positive definite.
  std::vector<QVec> W_N, W_T;
  QVec w_N, w_T;
  QVec qdot_A;
  /// Every contact takes part, also those with D_NA > 0 (the caller gives those their law with
  /// the restitution on min(D_NA, 0) = 0: e = 0, φ_N = 0, no tangential potential); false: the
  /// contacts with D_NA > 0 are left out and get no percussion.
  bool every_contact_takes_part = false;
  int dofs() const { return static_cast<int>(qdot_A.size()); }
  int contacts() const { return static_cast<int>(W_N.size()); }
  bool has_tangential() const { return !W_T.empty(); }
};

/// Copies matrices with .rows(), .cols() and (i, j) (e.g. Eigen's, in double) into a Problem.
/// W_N and W_T are n×c, one column a contact; a W_T with no column gives a frictionless problem.
template <class MatM, class MatW, class VecQ>
Problem problem_from(const MatM& M, const MatW& W_N, const MatW& W_T, const VecQ& qdot_A) {
  Problem p;
  const int n = static_cast<int>(M.rows());
  p.M.assign(n, QVec(n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) p.M[i][j] = static_cast<quad>(M(i, j));
  for (int c = 0; c < static_cast<int>(W_N.cols()); ++c) {
    QVec col(n);
    for (int i = 0; i < n; ++i) col[i] = static_cast<quad>(W_N(i, c));
    p.W_N.push_back(col);
  }
  for (int c = 0; c < static_cast<int>(W_T.cols()); ++c) {
    QVec col(n);
    for (int i = 0; i < n; ++i) col[i] = static_cast<quad>(W_T(i, c));
    p.W_T.push_back(col);
  }
  p.qdot_A.resize(n);
  for (int i = 0; i < n; ++i) p.qdot_A[i] = static_cast<quad>(qdot_A(i));
  return p;
}

/// Normal law φ_N(z) = k|z|^p/p, p > 1, k ≥ 0: −P_N = f_N(z) = k z|z|^(p−2) (plus the reaction).
struct PowerLaw {
  quad k = 0;
  quad p = 2;
};

enum class TangentialKind {
  none,      ///< P_T = 0.
  deadzone,  ///< −P_T = f_T(z_T) = k sign(z_T) max(0, |z_T| − r)^(q−1), q > 1, r ≥ 0.
  coulomb,   ///< Coulomb on (P_T, z_T) with the bound μ|P_N| (one contact only).
};

struct TangentialLaw {
  TangentialKind kind = TangentialKind::none;
  quad k = 0, q = 2, r = 0;  ///< dead zone.
  quad mu = 0;               ///< Coulomb.
  static TangentialLaw none() { return {}; }
  static TangentialLaw dead_zone(quad k, quad q, quad r) {
    TangentialLaw t;
    t.kind = TangentialKind::deadzone;
    t.k = k;
    t.q = q;
    t.r = r;
    return t;
  }
  static TangentialLaw coulomb(quad mu) {
    TangentialLaw t;
    t.kind = TangentialKind::coulomb;
    t.mu = mu;
    return t;
  }
};

/// One solution. Per-contact vectors have one entry a contact (zero for those that do not take
/// part, and P_T, D_T*, z_T zero without W_T).
struct Solution {
  QVec qdot_E;
  QVec P_N, P_T;    ///< total percussions on the body.
  QVec P_reaction;  ///< the reaction part of P_N (≥ 0; −I_reac of docs/laws.md).
  QVec D_NA, D_TA, D_NE, D_TE;
  QVec z_N, z_T;  ///< mean velocities.
  /// Poisson's compression phase (classical_modes with ClassicalLaw::poisson; empty otherwise).
  QVec P_NC, P_TC, D_NC, D_TC;
  /// classical_modes: the smallest relative pivot of the equations of its modes, about the
  /// inverse of their condition. The answer in double precision can be no closer than
  /// ε/mode_pivot relative, however exact the method (1 for the other laws).
  quad mode_pivot = 1;
  std::vector<int> takes_part;  ///< 1 when D_NA ≤ 0.
  std::string mode;   ///< e.g. "c0:free/slide+" (normal: free or reaction; tangential mode).
  quad residual = 0;  ///< the law's scaled residual at this solution (fremond/newton_residual).
  bool ok = true;     ///< false when an iterative part did not meet its tolerance.
};

// ---------------------------------------------------------------------------------------------
// Helpers

namespace detail {

inline quad eps() {
  return ldexpq(1, -112);
}
inline quad huge() {
  return ldexpq(1, 16000);
}
inline bool finite(quad x) {
  return finiteq(x) != 0;
}
inline quad sgn(quad x) {
  return x > 0 ? 1 : (x < 0 ? -1 : 0);
}

/// |x|^a for x ≠ 0 (0 at 0 for a > 0, +∞ for a < 0).
inline quad pow_abs(quad x, quad a) {
  const quad ax = fabsq(x);
  if (ax == 0) return a > 0 ? quad(0) : (a == 0 ? quad(1) : huge() * huge());
  return powq(ax, a);
}

inline quad dot(const QVec& a, const QVec& b) {
  quad s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

/// A dense row-major matrix.
struct Mat {
  int rows = 0, cols = 0;
  QVec a;
  Mat() = default;
  Mat(int r, int c) : rows(r), cols(c), a(static_cast<std::size_t>(r) * c, quad(0)) {}
  quad& operator()(int i, int j) { return a[static_cast<std::size_t>(i) * cols + j]; }
  quad operator()(int i, int j) const { return a[static_cast<std::size_t>(i) * cols + j]; }
};

/// Solves A x = b by Gaussian elimination with partial pivoting; false when a pivot is below
/// rel_tol × the largest entry of A (singular to that tolerance). `smallest_pivot`, if given,
/// receives the smallest pivot over that largest entry (about 1/cond(A)).
inline bool solve_linear(Mat A, QVec& b, quad rel_tol = ldexpq(1, -100),
                         quad* smallest_pivot = nullptr) {
  const int n = A.rows;
  quad scale = 0;
  for (quad v : A.a) scale = fmaxq(scale, fabsq(v));
  if (scale == 0) return n == 0;
  for (int k = 0; k < n; ++k) {
    int piv = k;
    for (int i = k + 1; i < n; ++i)
      if (fabsq(A(i, k)) > fabsq(A(piv, k))) piv = i;
    if (fabsq(A(piv, k)) <= rel_tol * scale) return false;
    if (smallest_pivot) *smallest_pivot = fminq(*smallest_pivot, fabsq(A(piv, k)) / scale);
    if (piv != k) {
      for (int j = 0; j < n; ++j) std::swap(A(k, j), A(piv, j));
      std::swap(b[k], b[piv]);
    }
    for (int i = k + 1; i < n; ++i) {
      const quad f = A(i, k) / A(k, k);
      if (f == 0) continue;
      for (int j = k; j < n; ++j) A(i, j) -= f * A(k, j);
      b[i] -= f * b[k];
    }
  }
  for (int k = n - 1; k >= 0; --k) {
    quad s = b[k];
    for (int j = k + 1; j < n; ++j) s -= A(k, j) * b[j];
    b[k] = s / A(k, k);
  }
  return true;
}

/// Levenberg-Marquardt's normal equations of J δ = −F (J square, m × m): A = JᵀJ, g = −JᵀF.
inline void normal_equations(const Mat& J, const QVec& F, Mat& A, QVec& g) {
  const int m = J.rows;
  A = Mat(m, m);
  g.assign(m, 0);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      quad v = 0;
      for (int l = 0; l < m; ++l) v += J(l, i) * J(l, j);
      A(i, j) = v;
    }
    for (int l = 0; l < m; ++l) g[i] -= J(l, i) * F[l];
  }
}

/// Is the polyhedron {u : A u = b, C u ≥ h} non-empty? Phase one of the simplex method on
/// u = u⁺ − u⁻ (u⁺, u⁻ ≥ 0), with an artificial variable per row and Bland's rule (no cycling on
/// degenerate vertices), in quad precision. Each row is scaled to a largest coefficient of 1; the
/// polyhedron counts as non-empty when the artificials' least sum is below `rel_tol` times the
/// largest scaled right-hand side (each constraint then holds to that, relative). The default
/// 2^-50 (9e-16) is loose for quad precision on purpose: a mode regular to 3e-12 with μ = 1e8
/// left 1e-20 of it at its exact answer (stress newton_coulomb #37224 of seed 23); a point the
/// program accepts is then checked against the law by the caller. A or C may have
/// no row. `point`, if given, receives a point of it. Used where a mode's equations are singular
/// (a continuum of percussions, or none): Gaussian elimination cannot say which.
inline bool polyhedron_nonempty(const Mat& A, const QVec& b, const Mat& C, const QVec& h,
                                QVec* point = nullptr, quad rel_tol = ldexpq(1, -50)) {
  const int n = A.rows ? A.cols : C.cols, me = A.rows, mi = C.rows, m = me + mi;
  // Columns: u⁺ (n), u⁻ (n), surplus of each inequality (mi), artificial of each row (m), rhs.
  const int ca = 2 * n + mi, cols = ca + m + 1, rhs = cols - 1;
  Mat T(m + 1, cols);  // row m: the reduced costs of Σ artificials
  std::vector<int> basis(m);
  quad rhs_max = 0;
  for (int i = 0; i < m; ++i) {
    const bool eq = i < me;
    quad scale = 0;
    for (int j = 0; j < n; ++j) scale = fmaxq(scale, fabsq(eq ? A(i, j) : C(i - me, j)));
    const quad r = eq ? b[i] : h[i - me];
    if (scale == 0) {  // 0 = r or 0 ≥ r: no variable helps
      if (eq ? r != 0 : r > 0) return false;
      scale = 1;
    }
    const quad sign = r < 0 ? -1 : 1;
    for (int j = 0; j < n; ++j) {
      const quad v = sign * (eq ? A(i, j) : C(i - me, j)) / scale;
      T(i, j) = v;
      T(i, n + j) = -v;
    }
    if (!eq) T(i, 2 * n + (i - me)) = -sign;
    T(i, ca + i) = 1;
    T(i, rhs) = sign * r / scale;
    rhs_max = fmaxq(rhs_max, T(i, rhs));
    basis[i] = ca + i;
  }
  for (int j = 0; j < cols; ++j) {
    if (j >= ca && j < rhs) continue;
    quad s = 0;
    for (int i = 0; i < m; ++i) s += T(i, j);
    T(m, j) = -s;
  }
  // Reduced costs below 2^-100 of the largest are zero; a pivot must be 2^-60 of its column's
  // largest entry: pivots down to 2^-100 were taken, and their growth left the tableau off by
  // 1e-7 (μ = 1e8 beside entries of 1e-3: an answer with slack 42 in every inequality was called
  // infeasible, stress newton_coulomb #71778 of seed 23).
  const quad tiny = ldexpq(1, -100), pivot_tol = ldexpq(1, -60);
  for (int it = 0; it < 5000; ++it) {
    quad cost_scale = 1;
    for (int j = 0; j < ca + m; ++j) cost_scale = fmaxq(cost_scale, fabsq(T(m, j)));
    int enter = -1;
    for (int j = 0; j < ca + m && enter < 0; ++j)
      if (T(m, j) < -tiny * cost_scale) enter = j;
    if (enter < 0) break;
    quad col_scale = 0;
    for (int i = 0; i < m; ++i) col_scale = fmaxq(col_scale, fabsq(T(i, enter)));
    int leave = -1;
    quad best = 0;
    for (int i = 0; i < m; ++i) {
      if (!(T(i, enter) > pivot_tol * col_scale)) continue;
      const quad ratio = T(i, rhs) / T(i, enter);
      if (leave < 0 || ratio < best || (ratio == best && basis[i] < basis[leave])) {
        leave = i;
        best = ratio;
      }
    }
    if (leave < 0) break;  // unbounded below: impossible for a sum of non-negative artificials
    const quad pv = T(leave, enter);
    for (int j = 0; j < cols; ++j) T(leave, j) /= pv;
    for (int i = 0; i <= m; ++i) {
      if (i == leave || T(i, enter) == 0) continue;
      const quad f = T(i, enter);
      for (int j = 0; j < cols; ++j) T(i, j) -= f * T(leave, j);
      T(i, enter) = 0;
    }
    basis[leave] = enter;
  }
  if (!(-T(m, rhs) <= rel_tol * rhs_max)) return false;
  if (point) {
    point->assign(n, 0);
    for (int i = 0; i < m; ++i) {
      if (basis[i] < n)
        (*point)[basis[i]] += T(i, rhs);
      else if (basis[i] < 2 * n)
        (*point)[basis[i] - n] -= T(i, rhs);
    }
  }
  return true;
}

/// Cholesky factor L (M = L Lᵀ) of the symmetric positive definite M; throws otherwise.
struct Cholesky {
  int n = 0;
  Mat L;
  explicit Cholesky(const std::vector<QVec>& M) : n(static_cast<int>(M.size())), L(n, n) {
    for (int j = 0; j < n; ++j) {
      quad d = M[j][j];
      for (int k = 0; k < j; ++k) d -= L(j, k) * L(j, k);
      if (!(d > 0)) throw std::invalid_argument("fremond_reference: M is not positive definite");
      L(j, j) = sqrtq(d);
      for (int i = j + 1; i < n; ++i) {
        quad s = M[i][j];
        for (int k = 0; k < j; ++k) s -= L(i, k) * L(j, k);
        L(i, j) = s / L(j, j);
      }
    }
  }
  QVec solve(QVec b) const {
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < i; ++k) b[i] -= L(i, k) * b[k];
      b[i] /= L(i, i);
    }
    for (int i = n - 1; i >= 0; --i) {
      for (int k = i + 1; k < n; ++k) b[i] -= L(k, i) * b[k];
      b[i] /= L(i, i);
    }
    return b;
  }
};

/// The contact-space data of a problem (docs/concepts.md).
struct ContactData {
  int n = 0, c = 0;
  bool has_T = false;
  std::vector<QVec> MinvWN, MinvWT;  ///< M⁻¹ W columns.
  Mat GNN, GNT, GTT;                 ///< G blocks, c×c (GNT(i, j) = W_N,iᵀ M⁻¹ W_T,j).
  QVec DNA, DTA;
  std::vector<int> part;  ///< 1 when D_NA ≤ 0.
};

inline ContactData contact_data(const Problem& p) {
  const int n = p.dofs(), c = p.contacts();
  if (static_cast<int>(p.M.size()) != n) throw std::invalid_argument("fremond_reference: M size");
  if (p.has_tangential() && static_cast<int>(p.W_T.size()) != c)
    throw std::invalid_argument("fremond_reference: W_T must have as many columns as W_N");
  const Cholesky chol(p.M);
  ContactData d;
  d.n = n;
  d.c = c;
  d.has_T = p.has_tangential();
  d.GNN = Mat(c, c);
  d.GNT = Mat(c, c);
  d.GTT = Mat(c, c);
  d.DNA.assign(c, 0);
  d.DTA.assign(c, 0);
  d.part.assign(c, 0);
  for (int i = 0; i < c; ++i) {
    d.MinvWN.push_back(chol.solve(p.W_N[i]));
    if (d.has_T) d.MinvWT.push_back(chol.solve(p.W_T[i]));
  }
  for (int i = 0; i < c; ++i) {
    d.DNA[i] = dot(p.W_N[i], p.qdot_A) + (p.w_N.empty() ? quad(0) : p.w_N[i]);
    if (d.has_T) d.DTA[i] = dot(p.W_T[i], p.qdot_A) + (p.w_T.empty() ? quad(0) : p.w_T[i]);
    d.part[i] = p.every_contact_takes_part || d.DNA[i] <= 0 ? 1 : 0;
    for (int j = 0; j < c; ++j) {
      d.GNN(i, j) = dot(p.W_N[i], d.MinvWN[j]);
      if (d.has_T) {
        d.GNT(i, j) = dot(p.W_N[i], d.MinvWT[j]);
        d.GTT(i, j) = dot(p.W_T[i], d.MinvWT[j]);
      }
    }
  }
  return d;
}

/// f_N(z) = k z|z|^(p−2) and its derivative k(p−1)|z|^(p−2).
inline quad f_normal(const PowerLaw& law, quad z) {
  return law.k * sgn(z) * pow_abs(z, law.p - 1);
}
inline quad df_normal(const PowerLaw& law, quad z) {
  if (law.k == 0) return 0;
  return law.k * (law.p - 1) * pow_abs(z, law.p - 2);
}
/// f_T(y) = k sign(y) max(0, |y| − r)^(q−1) and its derivative (0 inside the zone).
inline quad f_tangent(const TangentialLaw& law, quad y) {
  if (law.kind != TangentialKind::deadzone) return 0;
  const quad out = fabsq(y) - law.r;
  return out > 0 ? law.k * sgn(y) * powq(out, law.q - 1) : quad(0);
}
inline quad df_tangent(const TangentialLaw& law, quad y) {
  if (law.kind != TangentialKind::deadzone || law.k == 0) return 0;
  const quad out = fabsq(y) - law.r;
  return out > 0 ? law.k * (law.q - 1) * pow_abs(out, law.q - 2) : quad(0);
}

/// A value and a slope.
struct ValueSlope {
  quad value, slope;
};

/// A root of a function monotone on the bracket [a, b] whose ends have values of opposite signs
/// (fa, fb, either may be 0): Newton's method safeguarded by bisection (rtsafe), to the last bit
/// (or until |f| ≤ ftol or the bracket is narrower than xtol·|x|). Slopes may be infinite or zero:
/// the step then bisects.
template <class F>
quad find_root(F&& f, quad a, quad b, quad fa, quad fb, quad ftol = 0, quad xtol = 0) {
  if (fa == 0) return a;
  if (fb == 0) return b;
  if ((fa > 0) == (fb > 0)) throw std::logic_error("fremond_reference: root not bracketed");
  // Orient so that f(lo) < 0 < f(hi) (lo may be above hi).
  quad lo = fa < 0 ? a : b, hi = fa < 0 ? b : a;
  quad x = (lo + hi) / 2;
  quad dx_old = fabsq(hi - lo), dx = dx_old;
  const quad tiny = ldexpq(1, -16300);
  for (int it = 0; it < 20000; ++it) {
    const ValueSlope v = f(x);
    if (v.value == 0 || fabsq(v.value) <= ftol) return x;
    if (v.value < 0)
      lo = x;
    else
      hi = x;
    const quad width = fabsq(hi - lo);
    if (width <= fmaxq(xtol, 2 * eps()) * fabsq(x) || width <= tiny) break;
    quad next = x;
    bool newton = finite(v.slope) && v.slope != 0;
    if (newton) {
      next = x - v.value / v.slope;
      // Inside the bracket and at least halving the step.
      newton = finite(next) && (next - lo) * (next - hi) < 0 &&
               fabsq(2 * v.value) <= fabsq(dx_old * v.slope);
    }
    dx_old = dx;
    if (!newton) next = (lo + hi) / 2;
    dx = fabsq(next - x);
    if (next == x) next = (lo + hi) / 2;
    if (next == lo || next == hi) break;  // the bracket holds two neighbouring numbers
    x = next;
  }
  const quad flo = f(lo).value, fhi = f(hi).value;
  return fabsq(flo) <= fabsq(fhi) ? lo : hi;
}

/// Every root of g(z) = z + a f_N(z) − b on [lower, ∞), a ≠ 0. g' = 1 + a k (p−1)|z|^(p−2) is even
/// and monotone in |z|, so g is monotone on (−∞, −z_c], [−z_c, z_c], [z_c, ∞) with z_c where g' = 0
/// (no z_c when a > 0 or p = 2: one interval).
inline std::vector<quad> roots_of_normal(const PowerLaw& law, quad a, quad b, quad lower) {
  auto g = [&](quad z) {
    return ValueSlope{z + a * f_normal(law, z) - b, 1 + a * df_normal(law, z)};
  };
  std::vector<quad> cuts;  // interval ends inside (lower, ∞)
  if (a * law.k < 0 && law.p != 2) {
    const quad zc = powq(-1 / (a * law.k * (law.p - 1)), 1 / (law.p - 2));
    if (finite(zc) && zc > 0) {
      if (-zc > lower) cuts.push_back(-zc);
      if (zc > lower) cuts.push_back(zc);
    }
  } else if (a * law.k < 0 && law.p == 2 && 1 + a * law.k == 0) {
    return {};  // g constant: a continuum or nothing (not handled)
  }
  std::vector<quad> ends{lower};
  ends.insert(ends.end(), cuts.begin(), cuts.end());
  std::vector<quad> roots;
  for (std::size_t s = 0; s < ends.size(); ++s) {
    const quad lo = ends[s];
    const quad glo = g(lo).value;
    quad hi, ghi;
    if (s + 1 < ends.size()) {
      hi = ends[s + 1];
      ghi = g(hi).value;
    } else {
      // Last interval, [lo, ∞): step out until the sign changes or g stops moving towards 0.
      quad step = fmaxq(fmaxq(fabsq(b), fabsq(lo)), ldexpq(1, -200));
      hi = lo + step;
      ghi = g(hi).value;
      for (int k = 0; k < 40000 && (ghi > 0) == (glo > 0) && ghi != 0; ++k) {
        step *= 2;
        hi = lo + step;
        if (!finite(hi)) break;
        ghi = g(hi).value;
        if (!finite(ghi)) break;
      }
      if (!finite(hi) || !finite(ghi)) continue;
    }
    if (glo == 0) {
      roots.push_back(lo);
      continue;
    }
    if ((glo > 0) == (ghi > 0)) continue;
    if (ghi == 0 && s + 1 < ends.size()) continue;  // found as the next interval's lower end
    roots.push_back(find_root(g, lo, hi, glo, ghi));
  }
  return roots;
}

/// The normal inclusion z + (α/2)(f_N(z) + N_[lower,∞)(z)) ∋ b. Each candidate is (z, P_N,
/// reaction) with P_N = 2(z − b)/α; for α > 0 there is exactly one (the monotone case), for α < 0
/// the free roots above `lower` and the clamped z = lower when its reaction is ≥ 0.
struct NormalCandidate {
  quad z, P_N, reaction;
  bool clamped;
};

inline std::vector<NormalCandidate> normal_candidates(const PowerLaw& law, quad alpha, quad b,
                                                      quad lower) {
  std::vector<NormalCandidate> out;
  if (alpha == 0) return out;  // not handled (see the file comment)
  const quad a = alpha / 2;
  // P_N of a free root: −f_N(z), or (z − b)/a (the same at the root) when z is within the last
  // bracket width of 0. With p near 1, f_N climbs from 0 to most of k below quad's smallest
  // numbers (p = 1 + 2.7e-6: f_N = 0.6 k at |z| = 1e-82000), so a root there is found only as
  // the bracket [−2^-16300, 2^-16300], where −f_N(z) is anything in (−k, k) but (z − b)/a is P_N
  // to the last bit.
  auto free_P = [&](quad z) {
    return fabsq(z) <= ldexpq(1, -16000) ? (z - b) / a : -f_normal(law, z);
  };
  auto g = [&](quad z) {
    return ValueSlope{z + a * f_normal(law, z) - b, 1 + a * df_normal(law, z)};
  };
  if (alpha > 0) {
    // Monotone: clamp when the free root lies below `lower`.
    const quad glow = g(lower).value;
    if (glow >= 0) {
      out.push_back({lower, (lower - b) / a, (lower - b) / a + f_normal(law, lower), true});
      return out;
    }
    // Root above lower: bracket [max(lower, min(b, 0)), max(b, 0)].
    const quad lo = fmaxq(lower, fminq(b, quad(0))), hi = fmaxq(b, quad(0));
    const quad z = find_root(g, lo, hi, g(lo).value, g(hi).value);
    out.push_back({z, free_P(z), 0, false});
    return out;
  }
  for (quad z : roots_of_normal(law, a, b, lower)) out.push_back({z, free_P(z), 0, false});
  const quad P = (lower - b) / a, R = P + f_normal(law, lower);
  if (R >= 0) out.push_back({lower, P, R, true});
  return out;
}

inline const PowerLaw& pick(const std::vector<PowerLaw>& v, int i) {
  return v.size() == 1 ? v[0] : v.at(i);
}
inline const TangentialLaw& pick(const std::vector<TangentialLaw>& v, int i) {
  return v.size() == 1 ? v[0] : v.at(i);
}

/// Fills velocities and the mean velocities of `s` from its percussions.
/// q̇ = q̇_A + M⁻¹(W_N P_N + W_T P_T) and the velocities W q̇ + w it gives each contact.
inline void velocities_after(const Problem& p, const ContactData& d, const QVec& PN, const QVec& PT,
                             QVec& q, QVec& DN, QVec& DT) {
  q = p.qdot_A;
  for (int i = 0; i < d.c; ++i)
    for (int k = 0; k < d.n; ++k) {
      q[k] += d.MinvWN[i][k] * PN[i];
      if (d.has_T) q[k] += d.MinvWT[i][k] * PT[i];
    }
  DN.assign(d.c, 0);
  DT.assign(d.c, 0);
  for (int i = 0; i < d.c; ++i) {
    DN[i] = dot(p.W_N[i], q) + (p.w_N.empty() ? quad(0) : p.w_N[i]);
    if (d.has_T) DT[i] = dot(p.W_T[i], q) + (p.w_T.empty() ? quad(0) : p.w_T[i]);
  }
}

inline void complete(const Problem& p, const ContactData& d, Solution& s) {
  const int c = d.c;
  velocities_after(p, d, s.P_N, s.P_T, s.qdot_E, s.D_NE, s.D_TE);
  s.D_NA = d.DNA;
  s.D_TA = d.DTA;
  s.z_N.assign(c, 0);
  s.z_T.assign(c, 0);
  s.takes_part = d.part;
  for (int i = 0; i < c; ++i) {
    s.z_N[i] = (s.D_NA[i] + s.D_NE[i]) / 2;
    if (d.has_T) s.z_T[i] = (s.D_TA[i] + s.D_TE[i]) / 2;
  }
}

/// Coulomb's natural map on (t, v) with bound β, scaled: |t − proj_[−β, β](t − v P_s/v_s)| / P_s.
inline quad coulomb_error(quad t, quad v, quad beta, quad Ps, quad vs) {
  const quad proj = fminq(beta, fmaxq(-beta, t - v * Ps / vs));
  return fabsq(t - proj) / Ps;
}

inline Solution empty_solution(int c) {
  Solution s;
  s.P_N.assign(c, 0);
  s.P_T.assign(c, 0);
  s.P_reaction.assign(c, 0);
  return s;
}

/// The scales of the residuals: the largest |D_A| over the contacts that take part, and the
/// percussion scale max(max|P|, v_scale / max G_ii).
inline std::pair<quad, quad> scales(const ContactData& d, const Solution& s) {
  quad v = 0, g = 0, P = 0;
  for (int i = 0; i < d.c; ++i) {
    if (!d.part[i]) continue;
    v = fmaxq(v, fabsq(d.DNA[i]));
    g = fmaxq(g, d.GNN(i, i));
    if (d.has_T) {
      v = fmaxq(v, fabsq(d.DTA[i]));
      g = fmaxq(g, d.GTT(i, i));
    }
    P = fmaxq(P, fmaxq(fabsq(s.P_N[i]), fabsq(s.P_T[i])));
  }
  if (v == 0) v = 1;
  if (g == 0) g = 1;
  return {v, fmaxq(P, v / g)};
}

/// |D_E − (D_A + G P)| / v_scale over the contacts: q̇_E and P agree.
inline quad consistency(const ContactData& d, const Solution& s, quad vs) {
  quad r = 0;
  for (int i = 0; i < d.c; ++i) {
    quad dn = d.DNA[i], dt = d.DTA[i];
    for (int j = 0; j < d.c; ++j) {
      dn += d.GNN(i, j) * s.P_N[j];
      if (d.has_T) {
        dn += d.GNT(i, j) * s.P_T[j];
        dt += d.GNT(j, i) * s.P_N[j] + d.GTT(i, j) * s.P_T[j];
      }
    }
    r = fmaxq(r, fabsq(dn - s.D_NE[i]) / vs);
    if (d.has_T) r = fmaxq(r, fabsq(dt - s.D_TE[i]) / vs);
  }
  return r;
}

}  // namespace detail

// ---------------------------------------------------------------------------------------------
// Residuals

/// The scaled residual of Frémond's law at `s` (0 exactly at a solution), the largest of:
///  - q̇_E and P agree: |D_E − D_A − G P| / v_s;
///  - the normal law with its reaction R = P_N + f_N(z_N): |min(D_NE / v_s, R_b)|, R_b the smaller
///    of |R|/P_s and |z_N − f_N⁻¹(−P_N)|/v_s, with the sign of R;
///  - tangential: none |P_T|/P_s; dead zone the smaller of |P_T + f_T(z_T)|/P_s and the distance
///    of z_T to f_T⁻¹(−P_T) over v_s; Coulomb the natural map
///    |P_T − proj_[−μ|P_N|, μ|P_N|](P_T − z_T P_s/v_s)| / P_s;
///  - contacts that do not take part: |P| / P_s;
/// with v_s the largest |D_A| of the contacts that take part and P_s = max(max|P|, v_s / max G_ii).
/// Taking the smaller of the two makes each term a backward error (the relative change of P or of z
/// that would make the equation exact), so a stiff law (large k, q or p near 1 at the edge of the
/// zone) is not penalised for the rounding of z.
/// Laws: one entry for every contact or one each.
inline quad fremond_residual(const Problem& p, const std::vector<PowerLaw>& normal,
                             const std::vector<TangentialLaw>& tangential, const Solution& s) {
  const detail::ContactData d = detail::contact_data(p);
  const std::pair<quad, quad> scale_pair = detail::scales(d, s);
  const quad vs = scale_pair.first, Ps = scale_pair.second;
  quad r = detail::consistency(d, s, vs);
  for (int i = 0; i < d.c; ++i) {
    if (!d.part[i]) {
      r = fmaxq(r, fmaxq(fabsq(s.P_N[i]), fabsq(s.P_T[i])) / Ps);
      continue;
    }
    const PowerLaw& nl = detail::pick(normal, i);
    const TangentialLaw& tl = detail::pick(tangential, i);
    const quad z_N = (s.D_NA[i] + s.D_NE[i]) / 2;
    const quad R = s.P_N[i] + detail::f_normal(nl, z_N);
    // R measured as a backward error: the smaller of its relative size and the relative change of
    // z_N that would make P_N − R = −f_N(z_N) hold with R = 0.
    quad Rb = R / Ps;
    if (nl.k > 0) {
      const quad s_N = -s.P_N[i];
      const quad z_inv = detail::sgn(s_N) * powq(fabsq(s_N) / nl.k, 1 / (nl.p - 1));
      Rb = detail::sgn(R) * fminq(fabsq(R) / Ps, fabsq(z_N - z_inv) / vs);
    }
    r = fmaxq(r, fabsq(fminq(s.D_NE[i] / vs, Rb)));
    if (!d.has_T) continue;
    const quad z_T = (s.D_TA[i] + s.D_TE[i]) / 2;
    switch (tl.kind) {
      case TangentialKind::none:
        r = fmaxq(r, fabsq(s.P_T[i]) / Ps);
        break;
      case TangentialKind::deadzone: {
        // The same backward error: −P_T = f_T(z_T) up to a relative change of P_T or of z_T;
        // f_T⁻¹(s) is r + (|s|/k)^(1/(q−1)) with the sign of s, or the zone [−r, r] for s = 0.
        const quad s_T = -s.P_T[i];
        quad dz = 0;
        if (s_T == 0)
          dz = fmaxq(quad(0), fabsq(z_T) - tl.r);
        else if (tl.k > 0)
          dz = fabsq(z_T - detail::sgn(s_T) * (tl.r + powq(fabsq(s_T) / tl.k, 1 / (tl.q - 1))));
        else
          dz = detail::huge();
        r = fmaxq(r, fminq(fabsq(s.P_T[i] + detail::f_tangent(tl, z_T)) / Ps, dz / vs));
        break;
      }
      case TangentialKind::coulomb:
        r = fmaxq(r, detail::coulomb_error(s.P_T[i], z_T, tl.mu * fabsq(s.P_N[i]), Ps, vs));
        break;
    }
  }
  return r;
}

/// The scaled residual of Newton's frictionless law: |min(P_N/P_s, (D_NE + e D_NA)/v_s)| over the
/// contacts that take part, |P|/P_s over the others, and the agreement of q̇_E with P.
inline quad newton_residual(const Problem& p, const QVec& e, const Solution& s) {
  const detail::ContactData d = detail::contact_data(p);
  const std::pair<quad, quad> scale_pair = detail::scales(d, s);
  const quad vs = scale_pair.first, Ps = scale_pair.second;
  quad r = detail::consistency(d, s, vs);
  for (int i = 0; i < d.c; ++i) {
    if (!d.part[i]) {
      r = fmaxq(r, fabsq(s.P_N[i]) / Ps);
      continue;
    }
    const quad ei = e.size() == 1 ? e[0] : e.at(i);
    r = fmaxq(r, fabsq(fminq(s.P_N[i] / Ps, (s.D_NE[i] + ei * s.D_NA[i]) / vs)));
    if (d.has_T) r = fmaxq(r, fabsq(s.P_T[i]) / Ps);
  }
  return r;
}

// ---------------------------------------------------------------------------------------------
// Frémond's law, one contact

/// Every solution of Frémond's law on the one contact of `p` (see the file comment). For the
/// tangential laws none and dead zone there is exactly one; with Coulomb the list may hold several
/// or be empty (no solution). A contact with D_NA > 0 gives the one solution P = 0.
inline std::vector<Solution> fremond_one_contact(const Problem& p, const PowerLaw& normal,
                                                 const TangentialLaw& tangential) {
  using namespace detail;
  if (p.contacts() != 1) throw std::invalid_argument("fremond_one_contact: needs one contact");
  if (!(normal.p > 1) || normal.k < 0) throw std::invalid_argument("fremond_one_contact: p, k");
  const ContactData d = contact_data(p);
  const std::vector<PowerLaw> nv{normal};
  const std::vector<TangentialLaw> tv{tangential};
  auto finish = [&](quad PN, quad PT, quad R, std::string mode) {
    Solution s = empty_solution(1);
    s.P_N[0] = PN;
    s.P_T[0] = d.has_T ? PT : quad(0);
    s.P_reaction[0] = R;
    s.mode = "c0:" + mode;
    complete(p, d, s);
    s.residual = fremond_residual(p, nv, tv, s);
    return s;
  };
  if (!d.part[0]) return {finish(0, 0, 0, "separating")};

  const quad DNA = d.DNA[0], DTA = d.DTA[0], lower = DNA / 2;
  const quad GNN = d.GNN(0, 0);
  const quad GNT = d.has_T ? d.GNT(0, 0) : quad(0), GTT = d.has_T ? d.GTT(0, 0) : quad(0);
  const TangentialKind kind = d.has_T ? tangential.kind : TangentialKind::none;

  if (kind == TangentialKind::none) {
    const NormalCandidate nc = normal_candidates(normal, GNN, DNA, lower).at(0);
    return {finish(nc.P_N, 0, nc.reaction, nc.clamped ? "reaction/none" : "free/none")};
  }

  if (kind == TangentialKind::deadzone) {
    // The normal solve for a given P_T: b = D_NA + G_NT P_T/2, α = G_NN.
    struct Inner {
      NormalCandidate nc;
      quad z_T, dzT;  // z_T and dz_T/dP_T
    };
    auto inner = [&](quad PT) {
      const quad b = DNA + GNT * PT / 2;
      const NormalCandidate nc = normal_candidates(normal, GNN, b, lower).at(0);
      quad dPN;
      if (nc.clamped) {
        dPN = -GNT / GNN;
      } else {
        const quad fp = df_normal(normal, nc.z);
        dPN = finite(fp) ? -GNT * fp / (2 + GNN * fp) : -GNT / GNN;
      }
      const quad zT = DTA + (GNT * nc.P_N + GTT * PT) / 2;
      return Inner{nc, zT, (GNT * dPN + GTT) / 2};
    };
    auto e = [&](quad PT) {
      const Inner in = inner(PT);
      const quad fp = df_tangent(tangential, in.z_T);
      return ValueSlope{PT + f_tangent(tangential, in.z_T), 1 + fp * in.dzT};
    };
    // e(0) = A = f_T(z_T(0)); z_T is nondecreasing in P_T, so e(−A) ≤ 0 ≤ e(0) when A > 0 (and
    // the other way round when A < 0): the root lies between −A and 0.
    const quad A = e(0).value;
    quad PT = 0;
    if (A != 0) {
      const quad eA = e(-A).value;
      PT = (eA != 0 && (eA > 0) == (A > 0)) ? -A : find_root(e, -A, quad(0), eA, A);
    }
    const Inner in = inner(PT);
    // The mode from the percussion: near the edge of the zone with q near 1, z_T may be out of the
    // zone by less than its rounding.
    const std::string tmode = PT == 0 ? "zone" : (PT < 0 ? "out+" : "out-");
    return {finish(in.nc.P_N, PT, in.nc.reaction,
                   std::string(in.nc.clamped ? "reaction/" : "free/") + tmode)};
  }

  // Coulomb on (P_T, z_T) with the bound μ|P_N|.
  const quad mu = tangential.mu;
  std::vector<Solution> found;
  auto add = [&](const Solution& s) {
    for (const Solution& f : found) {
      const quad sc = fmaxq(fmaxq(fabsq(f.P_N[0]), fabsq(f.P_T[0])), ldexpq(1, -16000));
      if (fabsq(f.P_N[0] - s.P_N[0]) <= ldexpq(1, -90) * sc &&
          fabsq(f.P_T[0] - s.P_T[0]) <= ldexpq(1, -90) * sc)
        return;
    }
    found.push_back(s);
  };
  const quad tol = ldexpq(1, -100);
  // Stick: z_T = 0, P_T = −(2 D_TA + G_NT P_N)/G_TT; z_N = b' + (S/2) P_N with the Schur
  // complement S = G_NN − G_NT²/G_TT.
  if (GTT > 0) {
    const quad S = GNN - GNT * GNT / GTT, b = DNA - GNT * DTA / GTT;
    if (S > ldexpq(1, -66) * GNN) {
      for (const NormalCandidate& nc : normal_candidates(normal, S, b, lower)) {
        const quad PT = -(2 * DTA + GNT * nc.P_N) / GTT;
        if (fabsq(PT) <= mu * fabsq(nc.P_N) * (1 + tol) + tol * fabsq(DTA) / GTT)
          add(finish(nc.P_N, PT, nc.reaction,
                     std::string(nc.clamped ? "reaction" : "free") + "/stick"));
      }
    } else if (GNT != 0) {
      // G singular on the contact (W_T ∥ W_N in the metric of M⁻¹; one degree of freedom, say):
      // the velocity changes are tied, ΔD_T = (G_NT/G_NN) ΔD_N, so z_T = 0 fixes
      // ΔD_N = −2 D_TA G_NN/G_NT, hence z_N and D_NE. With D_NE > 0 the normal law gives P_N and
      // G_NN P_N + G_NT P_T = ΔD_N gives P_T. (D_NE < 0 is no solution; D_NE = 0 exactly leaves the
      // reaction free, a continuum, left out.) Each solution's own residual checks it.
      const quad dDN = -2 * DTA * GNN / GNT, zN = DNA + dDN / 2;
      if (DNA + dDN > 0) {
        const quad PN = -f_normal(normal, zN), PT = (dDN - GNN * PN) / GNT;
        if (fabsq(PT) <= mu * fabsq(PN) * (1 + tol) + tol * fabsq(DTA) / GTT)
          add(finish(PN, PT, 0, "free/stick (G singular)"));
      }
    }
  }
  // Slide σ with P_N of sign s: P_T = c P_N, c = −σ μ s; z_N = D_NA + (α/2) P_N, α = G_NN + c G_NT.
  for (int sigma : {1, -1})
    for (int sP : {1, -1}) {
      const quad c = -sigma * mu * sP, alpha = GNN + c * GNT;
      for (const NormalCandidate& nc : normal_candidates(normal, alpha, DNA, lower)) {
        if (sP * nc.P_N < 0) continue;
        const quad PT = c * nc.P_N;
        const quad zT = DTA + (GNT * nc.P_N + GTT * PT) / 2;
        if (sigma * zT < -tol * fmaxq(fabsq(DTA), fabsq(DNA))) continue;
        add(finish(
            nc.P_N, PT, nc.reaction,
            std::string(nc.clamped ? "reaction" : "free") + (sigma > 0 ? "/slide+" : "/slide-")));
      }
    }
  return found;
}

// ---------------------------------------------------------------------------------------------
// Frémond's law, several contacts (normal law; tangential none or dead zone)

namespace detail {

/// One contact row (normal or tangential) of the contact-space system, with its resolvent
/// z = J(s): the solution of z + (1/c)(f(z) + N(z)) ∋ s, c = 2/G_jj, N the normal cone of
/// [D_NA/2, ∞) on a normal row (the reaction) and nothing on a tangential row. Then P = c(z − s).
struct Row {
  int contact = 0;
  bool normal = true;
  PowerLaw nl;
  TangentialLaw tl;
  quad lower = 0;  // D_NA/2 on a normal row
  quad c = 1;
};

struct Resolvent {
  quad z, slope;  // J(s) and J'(s) ∈ [0, 1]
  bool clamped;   // the reaction acts
};

inline Resolvent resolvent(const Row& row, quad s) {
  const quad alpha = 2 / row.c;  // = G_jj
  if (row.normal) {
    const NormalCandidate nc = normal_candidates(row.nl, alpha, s, row.lower).at(0);
    if (nc.clamped) return {nc.z, 0, true};
    const quad fp = df_normal(row.nl, nc.z);
    return {nc.z, finite(fp) ? 1 / (1 + fp / row.c) : quad(0), false};
  }
  // Dead zone: z = s inside the zone, else the root of z + f_T(z)/c = s beyond the edge.
  if (fabsq(s) <= row.tl.r || row.tl.k == 0) return {s, 1, false};
  auto g = [&](quad z) {
    return ValueSlope{z + f_tangent(row.tl, z) / row.c - s, 1 + df_tangent(row.tl, z) / row.c};
  };
  const quad edge = sgn(s) * row.tl.r;
  const quad z = find_root(g, edge, s, g(edge).value, g(s).value);
  // f_T' on the branch beyond the edge, also where the root rounds onto the edge itself (q near
  // 1: |z| − r far below quad's ulp of r), whose limit there is ∞ for q < 2: J' = 0, not 1.
  const quad out = fmaxq(fabsq(z) - row.tl.r, quad(0));
  const quad fp = row.tl.k * (row.tl.q - 1) * pow_abs(out, row.tl.q - 2);
  return {z, finite(fp) ? 1 / (1 + fp / row.c) : quad(0), false};
}

}  // namespace detail

/// Frémond's law on several contacts with the normal power law and the tangential law none or
/// dead zone (see the file comment): the unique solution. Method, in contact space (it needs no
/// G⁻¹): with one variable s_j a row and the resolvents above, z_j = J_j(s_j), P_j = c_j(z_j −
/// s_j), solve F(s) = z − D_A − G P/2 = 0 (docs/concepts.md: z = D_A + G P/2). First non-smooth
/// Gauss-Seidel sweeps (each row exactly: s_j = D_A,j + ½ Σ_{k≠j} G_jk P_k; the block coordinate
/// descent of the dual problem, which converges), then Levenberg-Marquardt on F with the Jacobian
/// diag(J') − ½ G C (diag(J') − I), alternating until ‖F‖ is at rounding level. `ok` is false when
/// the law's residual stays above 1e-27. Laws: one for every contact or one each. Where the normals
/// are dependent (a plate on three points) and the law holds z_N far below the velocities (p = 1.2,
/// k = 1e6: z_N near 1e-29), the split of P_N between those contacts, which only z_N sees, is as
/// good as that residual: 30 % off on the plate, whose velocities do not depend on it.
inline Solution fremond_several(const Problem& p, const std::vector<PowerLaw>& normal,
                                const std::vector<TangentialLaw>& tangential) {
  using namespace detail;
  const ContactData d = contact_data(p);
  const int c = d.c;
  for (const TangentialLaw& t : tangential)
    if (t.kind == TangentialKind::coulomb)
      throw std::invalid_argument("fremond_several: Coulomb is for fremond_one_contact");
  for (const PowerLaw& l : normal)
    if (!(l.p > 1) || l.k < 0) throw std::invalid_argument("fremond_several: p, k");

  // The rows of the contacts that take part: N, and T when there is a dead zone.
  std::vector<Row> rows;
  QVec DA;
  for (int i = 0; i < c; ++i) {
    if (!d.part[i]) continue;
    Row rn;
    rn.contact = i;
    rn.normal = true;
    rn.nl = pick(normal, i);
    rn.lower = d.DNA[i] / 2;
    rn.c = 2 / d.GNN(i, i);
    rows.push_back(rn);
    DA.push_back(d.DNA[i]);
    const TangentialLaw& tl = pick(tangential, i);
    if (d.has_T && tl.kind == TangentialKind::deadzone) {
      Row rt;
      rt.contact = i;
      rt.normal = false;
      rt.tl = tl;
      rt.c = 2 / d.GTT(i, i);
      rows.push_back(rt);
      DA.push_back(d.DTA[i]);
    }
  }
  const int m = static_cast<int>(rows.size());
  Mat G(m, m);
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) {
      const int i = rows[a].contact, j = rows[b].contact;
      if (rows[a].normal && rows[b].normal) G(a, b) = d.GNN(i, j);
      if (rows[a].normal && !rows[b].normal) G(a, b) = d.GNT(i, j);
      if (!rows[a].normal && rows[b].normal) G(a, b) = d.GNT(j, i);
      if (!rows[a].normal && !rows[b].normal) G(a, b) = d.GTT(i, j);
    }
  quad vs = 0;
  for (quad x : DA) vs = fmaxq(vs, fabsq(x));
  if (vs == 0) vs = 1;

  QVec s = DA, z(m), P(m, 0), slope(m, 0);
  std::vector<int> clamped(m, 0);
  auto evaluate = [&](const QVec& sv, QVec& zv, QVec& Pv, QVec& sl, std::vector<int>& cl) {
    for (int a = 0; a < m; ++a) {
      const Resolvent r = resolvent(rows[a], sv[a]);
      zv[a] = r.z;
      sl[a] = r.slope;
      cl[a] = r.clamped;
      Pv[a] = rows[a].c * (r.z - sv[a]);
    }
  };
  // max_a |F_a| relative to the size of its terms, so that the floor is rounding, however large
  // G's entries (mass ratios) are.
  auto residual_of = [&](const QVec& zv, const QVec& Pv, QVec& F) {
    quad worst = 0;
    for (int a = 0; a < m; ++a) {
      quad GP = 0, size = fabsq(zv[a]) + fabsq(DA[a]) + ldexpq(1, -200) * vs;
      for (int b = 0; b < m; ++b) {
        GP += G(a, b) * Pv[b];
        size += fabsq(G(a, b) * Pv[b]) / 2;
      }
      F[a] = zv[a] - DA[a] - GP / 2;
      worst = fmaxq(worst, fabsq(F[a]) / size);
    }
    return worst;
  };
  auto sweeps = [&](int count) {
    for (int sweep = 0; sweep < count; ++sweep) {
      quad change = 0;
      for (int a = 0; a < m; ++a) {
        quad rest = 0;
        for (int b = 0; b < m; ++b)
          if (b != a) rest += G(a, b) * P[b];
        s[a] = DA[a] + rest / 2;
        const Resolvent r = resolvent(rows[a], s[a]);
        const quad Pn = rows[a].c * (r.z - s[a]);
        change = fmaxq(change, fabsq(r.z - z[a]));
        z[a] = r.z;
        slope[a] = r.slope;
        clamped[a] = r.clamped;
        P[a] = Pn;
      }
      if (change <= ldexpq(1, -40) * vs) break;
    }
  };

  const quad target = ldexpq(1, -108);
  QVec F(m);
  bool converged = m == 0;
  // Few sweeps first (LM converges from far once the reactions and zones are about right), more
  // when LM stalls.
  const int sweep_counts[] = {30, 300, 3000, 10000};
  for (int round = 0; round < 4 && !converged; ++round) {
    sweeps(sweep_counts[round]);
    evaluate(s, z, P, slope, clamped);
    quad norm = residual_of(z, P, F);
    quad lambda = ldexpq(1, -60);
    for (int it = 0; it < 400 && norm > target; ++it) {
      // Jacobian of F: δz = J' δs, δP = c (J' − 1) δs.
      Mat Jf(m, m);
      for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b)
          Jf(a, b) = (a == b ? slope[a] : quad(0)) - G(a, b) * rows[b].c * (slope[b] - 1) / 2;
      Mat A;
      QVec g;
      normal_equations(Jf, F, A, g);
      quad diag = 0;
      for (int a = 0; a < m; ++a) diag = fmaxq(diag, A(a, a));
      bool improved = false;
      for (int tries = 0; tries < 40 && !improved; ++tries) {
        Mat Al = A;
        for (int a = 0; a < m; ++a) Al(a, a) += lambda * diag;
        QVec step = g;
        if (!solve_linear(Al, step, ldexpq(1, -112))) {
          lambda *= 16;
          continue;
        }
        QVec s2(m), z2(m), P2(m), sl2(m), F2(m);
        std::vector<int> cl2(m);
        for (int a = 0; a < m; ++a) s2[a] = s[a] + step[a];
        evaluate(s2, z2, P2, sl2, cl2);
        const quad norm2 = residual_of(z2, P2, F2);
        if (norm2 < norm) {
          s = s2, z = z2, P = P2, slope = sl2, clamped = cl2, F = F2;
          norm = norm2;
          lambda = fmaxq(lambda / 16, ldexpq(1, -100));
          improved = true;
        } else {
          lambda *= 16;
        }
      }
      if (!improved) break;
    }
    converged = norm <= ldexpq(1, -100);  // LM stopped: at rounding level, or sweep more
  }

  Solution sol = empty_solution(c);
  for (int a = 0; a < m; ++a) {
    const int i = rows[a].contact;
    if (rows[a].normal) {
      sol.P_N[i] = P[a];
      sol.P_reaction[i] = clamped[a] ? P[a] + f_normal(rows[a].nl, z[a]) : quad(0);
    } else {
      sol.P_T[i] = P[a];
    }
  }
  complete(p, d, sol);
  sol.residual = fremond_residual(p, normal, tangential, sol);
  for (int i = 0; i < c; ++i) {
    if (!sol.mode.empty()) sol.mode += " ";
    std::string t;
    for (int a = 0; a < m; ++a)
      if (rows[a].contact == i && !rows[a].normal)
        t = sol.P_T[i] == 0 ? "/zone" : (sol.P_T[i] < 0 ? "/out+" : "/out-");
    sol.mode += "c" + std::to_string(i) + ":" +
                (!d.part[i] ? std::string("separating")
                            : (sol.P_reaction[i] != 0 ? std::string("reaction") : "free") + t);
  }
  sol.ok = sol.residual <= ldexpq(1, -90);
  return sol;
}

// ---------------------------------------------------------------------------------------------
// Frémond + Coulomb, several contacts: the exact solution near a given answer

namespace detail {

/// A contact mode of Frémond + Coulomb on one contact that takes part: the normal row free (the
/// power law alone) or held by its reaction (D_NE = 0); the tangential row sticking (z_T = 0) or
/// sliding against σ = sign(z_T) at the bound, P_T = −σ μ s P_N, with s the sign of P_N.
struct CoulombMode {
  bool reaction = false;
  int slide = 0;  ///< 0: stick; ±1: σ
  int sign = 1;   ///< s = sign(P_N) in a slide
};

}  // namespace detail

/// Frémond + Coulomb on several contacts: the exact solution nearest to an answer (P_N, P_T, one
/// entry a contact). NOT a reference of the law: with Coulomb's bound μ|P_N| the law is
/// quasi-variational and each contact mode is a nonlinear system with no bracket, so no method
/// here lists every solution. It checks an answer instead: is it within rounding of an exact
/// solution? Each mode the answer lies near (per contact: free, or held by its reaction where
/// D_NE ≈ 0; stick where z_T ≈ 0, slide where |P_T| ≈ μ|P_N|, with both signs of P_N where
/// P_N ≈ 0; "near" is 1e-3 of the scales) is solved by damped Newton in quad precision from the
/// answer, its equations written in the form that stays smooth (P_N + f_N(z_N) = 0 for p ≥ 2,
/// z_N = f_N⁻¹(−P_N) for p < 2, where f_N⁻¹ is (|s|/k)^(1/(p−1)) and resolves z_N near 0 to
/// full relative precision). A mode's root is a solution when its inequalities hold (D_NE ≥ 0
/// free; reaction ≥ 0 held; |P_T| ≤ μ|P_N| stick; σ z_T ≥ 0 and s P_N ≥ 0 slide) and its
/// fremond_residual is at quad level. Returns the solution nearest to the answer (in P, relative
/// to the percussion scale), `ok` false when no mode gives one: the answer is then not near any
/// solution this check can find (or, with `mode` "too many modes", more than 1024 modes lie near
/// it and none was tried). `mode_pivot` is the smallest relative pivot of the mode's
/// Jacobian at the root: near 0 where the root is not determined by the data (dependent normals
/// under a law that holds z_N below quad rounding: only the power law's inverse splits P_N there).
inline Solution fremond_coulomb_near(const Problem& p, const std::vector<PowerLaw>& normal,
                                     const QVec& mu, const QVec& PN0, const QVec& PT0) {
  using namespace detail;
  const ContactData d = contact_data(p);
  const int c = d.c;
  if (!d.has_T || static_cast<int>(PN0.size()) != c || static_cast<int>(PT0.size()) != c ||
      (mu.size() != 1 && static_cast<int>(mu.size()) != c))
    throw std::invalid_argument("fremond_coulomb_near: sizes");
  auto mu_of = [&](int i) { return mu.size() == 1 ? mu[0] : mu[i]; };
  std::vector<int> act;
  for (int i = 0; i < c; ++i)
    if (d.part[i]) act.push_back(i);
  const int a = static_cast<int>(act.size());
  Solution start = empty_solution(c);
  for (int i : act) {
    start.P_N[i] = PN0[i];
    start.P_T[i] = PT0[i];
  }
  complete(p, d, start);
  const std::pair<quad, quad> scale_pair = scales(d, start);
  const quad vs = scale_pair.first, Ps = scale_pair.second;
  const std::vector<TangentialLaw> tangential = [&] {
    std::vector<TangentialLaw> t;
    for (int i = 0; i < c; ++i) t.push_back(TangentialLaw::coulomb(mu_of(i)));
    return t;
  }();
  // "Near": within 1e-3 of the scales, for answers computed in double precision from data whose
  // M has a condition up to 1e12 (a velocity 1e-6 of the scale off where the exact one is 0).
  const quad near = ldexpq(1, -10);
  // The candidate modes of each contact that takes part.
  std::vector<std::vector<CoulombMode>> cand(a);
  for (int k = 0; k < a; ++k) {
    const int i = act[k];
    const quad PN = start.P_N[i], PT = start.P_T[i], zT = start.z_T[i];
    const quad m = mu_of(i);
    std::vector<bool> reactions{false};
    if (fabsq(start.D_NE[i]) <= near * vs) reactions.push_back(true);
    std::vector<int> signs;
    if (PN >= -near * Ps) signs.push_back(1);
    if (PN <= near * Ps) signs.push_back(-1);
    for (bool r : reactions) {
      if (fabsq(zT) <= near * vs) cand[k].push_back({r, 0, 1});
      if (fabsq(fabsq(PT) - m * fabsq(PN)) <= near * Ps || fabsq(zT) > near * vs) {
        std::vector<int> sigmas;
        if (zT >= -near * vs && PT <= near * Ps) sigmas.push_back(1);
        if (zT <= near * vs && PT >= -near * Ps) sigmas.push_back(-1);
        for (int sg : sigmas)
          for (int sn : signs) cand[k].push_back({r, sg, sn});
      }
    }
    if (cand[k].empty()) {
      Solution none = start;
      none.ok = false;
      return none;
    }
  }
  // Every contact ambiguous in every way (four contacts: up to 10^4 modes, seconds): not checked.
  std::size_t modes = 1;
  for (const auto& cs : cand) modes *= cs.size();
  if (modes > 1024) {
    Solution none = start;
    none.ok = false;
    none.mode = "too many modes";
    return none;
  }
  // z = D_A + G P/2 on the contacts that take part (the others carry no percussion).
  auto mean_velocities = [&](const QVec& x, QVec& zN, QVec& zT) {
    zN.assign(a, 0);
    zT.assign(a, 0);
    for (int k = 0; k < a; ++k) {
      const int i = act[k];
      quad n = d.DNA[i], t = d.DTA[i];
      for (int l = 0; l < a; ++l) {
        const int j = act[l];
        n += (d.GNN(i, j) * x[l] + d.GNT(i, j) * x[a + l]) / 2;
        t += (d.GNT(j, i) * x[l] + d.GTT(i, j) * x[a + l]) / 2;
      }
      zN[k] = n;
      zT[k] = t;
    }
  };
  // The mode's equations F(x) (x = (P_N, P_T) over the contacts that take part; each equation over
  // its own scale, v_s or P_s) and, if asked, their Jacobian.
  auto equations = [&](const std::vector<CoulombMode>& mode, const QVec& x, QVec& F, Mat* J) {
    QVec zN, zT;
    mean_velocities(x, zN, zT);
    F.assign(2 * a, 0);
    if (J) *J = Mat(2 * a, 2 * a);
    for (int k = 0; k < a; ++k) {
      const int i = act[k];
      const PowerLaw& nl = pick(normal, i);
      const quad PN = x[k], PT = x[a + k];
      // ∂z_N,k/∂x_l and ∂z_T,k/∂x_l: entries of G/2.
      auto dzN = [&](int l) {
        const int j = act[l % a];
        return (l < a ? d.GNN(i, j) : d.GNT(i, j)) / 2;
      };
      auto dzT = [&](int l) {
        const int j = act[l % a];
        return (l < a ? d.GNT(j, i) : d.GTT(i, j)) / 2;
      };
      if (mode[k].reaction) {  // D_NE = 2 z_N − D_NA = 0
        F[k] = (2 * zN[k] - d.DNA[i]) / vs;
        if (J)
          for (int l = 0; l < 2 * a; ++l) (*J)(k, l) = 2 * dzN(l) / vs;
      } else if (nl.k == 0) {
        F[k] = PN / Ps;
        if (J) (*J)(k, k) = 1 / Ps;
      } else if (nl.p >= 2) {  // P_N + f_N(z_N) = 0
        F[k] = (PN + f_normal(nl, zN[k])) / Ps;
        if (J) {
          const quad fp = df_normal(nl, zN[k]);
          for (int l = 0; l < 2 * a; ++l) (*J)(k, l) = fp * dzN(l) / Ps;
          (*J)(k, k) += 1 / Ps;
        }
      } else {  // z_N − f_N⁻¹(−P_N) = 0, f_N⁻¹(s) = sign(s)(|s|/k)^(1/(p−1))
        const quad e = 1 / (nl.p - 1);
        F[k] = (zN[k] + sgn(PN) * powq(fabsq(PN) / nl.k, e)) / vs;
        if (J) {
          for (int l = 0; l < 2 * a; ++l) (*J)(k, l) = dzN(l) / vs;
          (*J)(k, k) += e / nl.k * pow_abs(PN / nl.k, e - 1) / vs;
        }
      }
      if (mode[k].slide == 0) {  // z_T = 0
        F[a + k] = zT[k] / vs;
        if (J)
          for (int l = 0; l < 2 * a; ++l) (*J)(a + k, l) = dzT(l) / vs;
      } else {  // P_T + σ μ s P_N = 0
        const quad g = mode[k].slide * mu_of(i) * mode[k].sign;
        F[a + k] = (PT + g * PN) / Ps;
        if (J) {
          (*J)(a + k, a + k) = 1 / Ps;
          (*J)(a + k, k) = g / Ps;
        }
      }
    }
  };
  auto norm = [](const QVec& F) {
    quad m = 0;
    for (quad f : F) m = fmaxq(m, fabsq(f));
    return m;
  };
  // Damped Newton on one mode from the answer, until ‖F‖ stops decreasing (quad rounding: a stop
  // at a fixed tolerance would leave z_N near 1e-30 unresolved, and with it the split of P_N
  // between dependent normals); true at a root. `pivot`: the smallest relative pivot of the
  // Jacobian there, about the inverse of its condition.
  auto solve_mode = [&](const std::vector<CoulombMode>& mode, QVec& x, quad& pivot) {
    QVec F, Fn, dx;
    Mat J;
    equations(mode, x, F, &J);
    for (int it = 0; it < 300; ++it) {
      const quad f = norm(F);
      if (!finite(f)) return false;
      if (f == 0) break;
      dx = F;
      for (quad& v : dx) v = -v;
      if (!solve_linear(J, dx, ldexpq(1, -110))) {
        // A singular mode (contacts sharing a tangent that sticks: only the sum of their P_T is
        // determined; the velocities are): a Levenberg-Marquardt step, (JᵀJ + λI) dx = −JᵀF with
        // λ at 2^-100 of JᵀJ's largest diagonal entry, which keeps the root nearest the answer.
        Mat A;
        QVec g;
        normal_equations(J, F, A, g);
        quad top = 0;
        for (int i = 0; i < A.rows; ++i) top = fmaxq(top, A(i, i));
        for (int i = 0; i < A.rows; ++i) A(i, i) += ldexpq(top, -100);
        dx = g;
        if (!solve_linear(A, dx, ldexpq(1, -125))) return false;
      }
      quad t = 1;
      bool moved = false;
      for (int ls = 0; ls < 60; ++ls, t /= 2) {
        QVec xn = x;
        for (int l = 0; l < 2 * a; ++l) xn[l] += t * dx[l];
        equations(mode, xn, Fn, nullptr);
        if (norm(Fn) < (1 - t / 4) * f) {
          x = xn;
          moved = true;
          break;
        }
      }
      if (!moved) break;
      equations(mode, x, F, &J);
    }
    // Where Newton stops, F is at its rounding, which an ill-conditioned M (1e12) or mode (contacts
    // whose tangents are 1e-11 apart, both sticking) lifts far above quad's ε: the root is judged
    // by the law's residual below, as every reference answer is.
    if (!(norm(F) <= ldexpq(1, -40))) return false;
    pivot = 1;
    QVec b(2 * a, 0);
    if (!solve_linear(J, b, 0, &pivot)) pivot = 0;
    return true;
  };
  Solution best = start;
  best.ok = false;
  quad best_d = 0;
  std::vector<int> pick_of(a, 0);
  const quad slack = ldexpq(1, -80);  // the mode's inequalities, relative to the scales
  for (;;) {
    std::vector<CoulombMode> mode(a);
    for (int k = 0; k < a; ++k) mode[k] = cand[k][pick_of[k]];
    QVec x(2 * a);
    for (int k = 0; k < a; ++k) {
      x[k] = start.P_N[act[k]];
      x[a + k] = start.P_T[act[k]];
    }
    quad pivot = 1;
    if (solve_mode(mode, x, pivot)) {
      Solution s = empty_solution(c);
      s.mode_pivot = pivot;
      for (int k = 0; k < a; ++k) {
        s.P_N[act[k]] = x[k];
        s.P_T[act[k]] = x[a + k];
      }
      complete(p, d, s);
      bool holds = true;
      for (int k = 0; k < a && holds; ++k) {
        const int i = act[k];
        const quad R = s.P_N[i] + f_normal(pick(normal, i), s.z_N[i]);
        if (mode[k].reaction) {
          holds = R >= -slack * Ps;
          s.P_reaction[i] = fmaxq(R, quad(0));
        } else {
          holds = s.D_NE[i] >= -slack * vs;
        }
        if (mode[k].slide == 0)
          holds = holds && fabsq(s.P_T[i]) <= mu_of(i) * fabsq(s.P_N[i]) + slack * Ps;
        else
          holds = holds && mode[k].slide * s.z_T[i] >= -slack * vs &&
                  mode[k].sign * s.P_N[i] >= -slack * Ps;
      }
      if (holds) {
        s.residual = fremond_residual(p, normal, tangential, s);
        quad dist = 0;
        for (int i : act)
          dist = fmaxq(dist, fmaxq(fabsq(s.P_N[i] - start.P_N[i]), fabsq(s.P_T[i] - start.P_T[i])));
        dist /= Ps;
        s.ok = s.residual <= ldexpq(1, -67);  // below 1e-20
        if (s.ok && (!best.ok || dist < best_d)) {
          std::string m;
          for (int k = 0; k < a; ++k)
            m += "c" + std::to_string(act[k]) + ":" + (mode[k].reaction ? "reaction" : "free") +
                 (mode[k].slide == 0 ? "/stick" : (mode[k].slide > 0 ? "/slide+" : "/slide-")) +
                 " ";
          s.mode = m;
          best = s;
          best_d = dist;
        }
      }
    }
    int k = 0;
    while (k < a && ++pick_of[k] == static_cast<int>(cand[k].size())) pick_of[k++] = 0;
    if (k == a) break;
  }
  return best;
}

// ---------------------------------------------------------------------------------------------
// Newton's law, frictionless

/// Every solution of Newton's frictionless law (e: one for every contact or one each) by
/// enumeration of the active sets S of the LCP 0 ≤ P_N ⊥ G_NN P_N + (1 + e) D_NA ≥ 0 over the
/// contacts that take part: P_S = −G_SS⁻¹ (1 + e_S) D_NA,S where G_SS is regular, kept when
/// P_S ≥ 0 and the others' D_NE + e D_NA ≥ 0. Distinct solutions (in P_N) only; for one contact
/// this is eq. (6): P_N = −(1 + e) D_NA / G_NN.
inline std::vector<Solution> newton_frictionless(const Problem& p, const QVec& e) {
  using namespace detail;
  const ContactData d = contact_data(p);
  const int c = d.c;
  auto ecoef = [&](int i) { return e.size() == 1 ? e[0] : e.at(i); };
  std::vector<int> J;
  for (int i = 0; i < c; ++i)
    if (d.part[i]) J.push_back(i);
  if (J.size() > 12)
    throw std::invalid_argument("newton_frictionless: at most 12 contacts take part");
  const int m = static_cast<int>(J.size());
  quad vs = 0;
  for (int i : J) vs = fmaxq(vs, fabsq(d.DNA[i]));
  if (vs == 0) vs = 1;
  std::vector<Solution> found;
  for (int S = 0; S < (1 << m); ++S) {
    std::vector<int> act;
    for (int k = 0; k < m; ++k)
      if (S & (1 << k)) act.push_back(J[k]);
    const int s = static_cast<int>(act.size());
    Mat Gs(s, s);
    QVec x(s);
    for (int a = 0; a < s; ++a) {
      x[a] = -(1 + ecoef(act[a])) * d.DNA[act[a]];
      for (int b = 0; b < s; ++b) Gs(a, b) = d.GNN(act[a], act[b]);
    }
    if (s > 0 && !solve_linear(Gs, x)) continue;
    Solution sol = empty_solution(c);
    for (int a = 0; a < s; ++a) sol.P_N[act[a]] = x[a];
    quad gmax = 0;
    for (int i : J) gmax = fmaxq(gmax, d.GNN(i, i));
    const quad Ps = vs / gmax, tol = ldexpq(1, -95);
    bool ok = true;
    for (int a = 0; a < s; ++a) ok = ok && x[a] >= -tol * Ps;
    for (int i : J) {
      if (std::find(act.begin(), act.end(), i) != act.end()) continue;
      quad w = (1 + ecoef(i)) * d.DNA[i];
      for (int j : act) w += d.GNN(i, j) * sol.P_N[j];
      ok = ok && w >= -tol * vs;
    }
    if (!ok) continue;
    bool known = false;
    for (const Solution& f : found) {
      quad diff = 0;
      for (int i = 0; i < c; ++i) diff = fmaxq(diff, fabsq(f.P_N[i] - sol.P_N[i]));
      known = known || diff <= ldexpq(1, -90) * Ps;
    }
    if (known) continue;
    complete(p, d, sol);
    sol.mode.clear();
    for (int i = 0; i < c; ++i) {
      if (!sol.mode.empty()) sol.mode += " ";
      const bool active = std::find(act.begin(), act.end(), i) != act.end();
      // Appended piece by piece: "c" + std::to_string(i) trips GCC 12's -Wrestrict (a false
      // positive of its string inlining) in some of the files that include this one.
      sol.mode += "c";
      sol.mode += std::to_string(i);
      sol.mode += ":";
      sol.mode += !d.part[i] ? "separating" : (active ? "active" : "open");
    }
    sol.residual = newton_residual(p, e, sol);
    found.push_back(sol);
  }
  return found;
}

// ---------------------------------------------------------------------------------------------
// The classical laws with Coulomb friction, several contacts

enum class ClassicalLaw { newton, poisson };

/// What classical_modes() finds.
struct ClassicalSolutions {
  std::vector<Solution> solutions;
  /// False when some contact mode's equations were singular: a continuum of percussions may solve
  /// that mode, and the list may then miss solutions (or hold only some of a continuum's).
  bool complete = true;
  /// Whether the law has a solution at all, where that is known: a singular mode's polyhedron
  /// (its equations with its inequalities) is tested for a point by a linear program. Known where
  /// every singular polyhedron is empty, or a solution is listed, or (Newton's laws) a singular
  /// mode's vertex solves the law; open otherwise (Poisson's singular modes, whose points are not
  /// carried through both phases, and vertices the program's rounding put off the law).
  bool exists = false;
  bool existence_known = true;
  /// Some singular mode has answers (not listed in `solutions`); `singular_example` is one of
  /// them (Newton's laws: a vertex of the first such mode's polyhedron, with its residual).
  bool singular_answers = false;
  std::vector<Solution> singular_example;
};

namespace detail {

/// One phase of a classical law over the contacts J that take part: unknowns x_j (the phase's
/// normal percussion, ≥ 0) and t_j (its tangential percussion), velocities
///   v_N = bN + G_NN x + G_NT t,   v_T = bT + G_TN x + G_TT t,
/// with 0 ≤ x ⊥ v_N ≥ 0 and Coulomb on (t, v_T) with the bound β = μ (cB + x).
struct Phase {
  std::vector<int> J;
  QVec bN, bT, cB;  ///< one entry a contact
  bool friction = false;
};

struct PhaseAnswer {
  QVec x, t;       ///< one entry a contact (zero off J)
  quad pivot = 1;  ///< the smallest relative pivot of its mode's equations (about 1/cond)
};

/// Every answer of one phase, by its modes; false when a mode's equations were singular, to the
/// relative pivot `singular` (see classical_modes).
inline bool phase_answers(const ContactData& d, const Phase& ph, const QVec& mu, quad vs,
                          quad singular, std::vector<PhaseAnswer>& out,
                          bool* singular_answers = nullptr,
                          std::vector<PhaseAnswer>* singular_points = nullptr) {
  const int m = static_cast<int>(ph.J.size()), c = d.c;
  bool complete = true;
  quad gmax = 0;
  for (int j : ph.J) gmax = fmaxq(gmax, fmaxq(d.GNN(j, j), d.has_T ? d.GTT(j, j) : quad(0)));
  if (gmax == 0) gmax = 1;
  auto gtn = [&](int i, int k) { return d.GNT(k, i); };  // W_T,iᵀ M⁻¹ W_N,k
  // Each contact's modes: normal 0 open, 1 closed; tangential 0 stick, 1 slide with v_T > 0
  // (t = −β), 2 slide with v_T < 0 (t = β), 3 t = 0 (no friction, or a bound that is zero).
  std::vector<std::vector<std::pair<int, int>>> modes(m);
  for (int a = 0; a < m; ++a) {
    const int j = ph.J[a];
    const bool coulomb = ph.friction && d.has_T && mu[j] > 0;
    for (int nm = 0; nm < 2; ++nm) {
      if (!coulomb || (nm == 0 && ph.cB[j] == 0)) {
        modes[a].push_back({nm, 3});
        continue;
      }
      for (int tm = 0; tm < 3; ++tm) modes[a].push_back({nm, tm});
    }
  }
  std::vector<int> pick(m, 0);
  const quad tol = ldexpq(1, -95);
  for (;;) {
    // Unknowns u = (x_J, t_J); one equation per unknown.
    Mat A(2 * m, 2 * m);
    QVec b(2 * m, 0);
    for (int a = 0; a < m; ++a) {
      const int j = ph.J[a];
      const auto [nm, tm] = modes[a][pick[a]];
      if (nm == 1) {  // closed: v_N = 0
        for (int k = 0; k < m; ++k) {
          A(a, k) = d.GNN(j, ph.J[k]);
          A(a, m + k) = d.has_T ? d.GNT(j, ph.J[k]) : quad(0);
        }
        b[a] = -ph.bN[j];
      } else {  // open: x = 0
        A(a, a) = 1;
      }
      if (tm == 0) {  // stick: v_T = 0
        for (int k = 0; k < m; ++k) {
          A(m + a, k) = gtn(j, ph.J[k]);
          A(m + a, m + k) = d.GTT(j, ph.J[k]);
        }
        b[m + a] = -ph.bT[j];
      } else if (tm == 3) {  // t = 0
        A(m + a, m + a) = 1;
      } else {  // slide: t = −s μ (cB + x)
        const quad sgn_v = tm == 1 ? 1 : -1;
        A(m + a, m + a) = 1;
        A(m + a, a) = sgn_v * mu[j];
        b[m + a] = -sgn_v * mu[j] * ph.cB[j];
      }
    }
    QVec u = b;
    quad pivot = 1;
    if (!solve_linear(A, u, singular, &pivot)) {
      complete = false;
      // Singular: the mode's equations with its inequalities, as a linear program.
      // (Where points are kept, up to 8 of them: a vertex can miss the law by the program's own
      // rounding, and another mode's may not.)
      if (singular_answers &&
          (singular_points ? singular_points->size() < 8 : !*singular_answers)) {
        Mat C(0, 2 * m);
        QVec h;
        auto add_row = [&](const QVec& row, quad rhs) {
          Mat D(C.rows + 1, 2 * m);
          std::copy(C.a.begin(), C.a.end(), D.a.begin());
          for (int k = 0; k < 2 * m; ++k) D(C.rows, k) = row[k];
          C = D;
          h.push_back(rhs);
        };
        for (int a = 0; a < m; ++a) {
          const int j = ph.J[a];
          const auto [nm, tm] = modes[a][pick[a]];
          QVec row(2 * m, 0);
          if (nm == 1) {  // x ≥ 0
            row[a] = 1;
            add_row(row, 0);
          } else {  // v_N ≥ 0
            for (int k = 0; k < m; ++k) {
              row[k] = d.GNN(j, ph.J[k]);
              row[m + k] = d.has_T ? d.GNT(j, ph.J[k]) : quad(0);
            }
            add_row(row, -ph.bN[j]);
          }
          if (tm == 0) {  // |t| ≤ μ (cB + x)
            for (const quad side : {quad(1), quad(-1)}) {
              QVec r2(2 * m, 0);
              r2[a] = mu[j];
              r2[m + a] = side;
              add_row(r2, -mu[j] * ph.cB[j]);
            }
          } else if (tm == 1 || tm == 2) {  // v_T ≥ 0 (1) or ≤ 0 (2)
            const quad side = tm == 1 ? 1 : -1;
            QVec r2(2 * m, 0);
            for (int k = 0; k < m; ++k) {
              r2[k] = side * gtn(j, ph.J[k]);
              r2[m + k] = side * d.GTT(j, ph.J[k]);
            }
            add_row(r2, -side * ph.bT[j]);
          }
        }
        QVec point;
        if (polyhedron_nonempty(A, b, C, h, &point)) {
          *singular_answers = true;
          if (singular_points) {
            PhaseAnswer ans{QVec(c, 0), QVec(c, 0), 0};
            for (int a = 0; a < m; ++a) {
              ans.x[ph.J[a]] = point[a];
              ans.t[ph.J[a]] = point[m + a];
            }
            singular_points->push_back(ans);
          }
        }
      }
    } else {
      PhaseAnswer ans{QVec(c, 0), QVec(c, 0), pivot};
      quad Pscale = vs / gmax;
      for (int a = 0; a < m; ++a) {
        ans.x[ph.J[a]] = u[a];
        ans.t[ph.J[a]] = u[m + a];
        Pscale = fmaxq(Pscale, fmaxq(fabsq(u[a]), fabsq(u[m + a])));
        Pscale = fmaxq(Pscale, ph.cB[ph.J[a]]);
      }
      const quad vscale = fmaxq(vs, gmax * Pscale);  // the size of the terms each v is summed from
      bool ok = true;
      for (int a = 0; a < m && ok; ++a) {
        const int j = ph.J[a];
        const auto [nm, tm] = modes[a][pick[a]];
        quad vN = ph.bN[j], vT = d.has_T ? ph.bT[j] : quad(0);
        for (int k : ph.J) {
          vN += d.GNN(j, k) * ans.x[k];
          if (d.has_T) {
            vN += d.GNT(j, k) * ans.t[k];
            vT += gtn(j, k) * ans.x[k] + d.GTT(j, k) * ans.t[k];
          }
        }
        if (nm == 1) ok = ans.x[j] >= -tol * Pscale;
        if (nm == 0) ok = vN >= -tol * vscale;
        const quad beta = ph.friction && d.has_T ? mu[j] * (ph.cB[j] + ans.x[j]) : quad(0);
        if (ok && tm == 0) ok = fabsq(ans.t[j]) <= beta + tol * Pscale;
        if (ok && tm == 1) ok = vT >= -tol * vscale;
        if (ok && tm == 2) ok = vT <= tol * vscale;
      }
      if (ok) {
        bool known = false;
        for (const PhaseAnswer& f : out) {
          quad diff = 0;
          for (int i = 0; i < c; ++i)
            diff = fmaxq(diff, fmaxq(fabsq(f.x[i] - ans.x[i]), fabsq(f.t[i] - ans.t[i])));
          known = known || diff <= ldexpq(1, -80) * Pscale;
        }
        if (!known) out.push_back(ans);
      }
    }
    int a = 0;  // the next combination of modes
    while (a < m && ++pick[a] == static_cast<int>(modes[a].size())) pick[a++] = 0;
    if (a == m) break;
  }
  return complete;
}

}  // namespace detail

/// The scaled residual of a classical law at `s`, from its velocities (recomputed from its
/// percussions): each complementarity |min(P/P_s, v/v_s)| and each Coulomb natural map, per phase.
inline quad classical_residual(const Problem& p, ClassicalLaw law, const QVec& e, const QVec& mu,
                               const Solution& s) {
  using namespace detail;
  const ContactData d = contact_data(p);
  const std::pair<quad, quad> scale_pair = scales(d, s);
  const quad vs = scale_pair.first, Ps = scale_pair.second;
  auto pick_e = [&](int i) { return e.size() == 1 ? e[0] : e.at(i); };
  auto pick_mu = [&](int i) { return mu.empty() ? quad(0) : (mu.size() == 1 ? mu[0] : mu.at(i)); };
  QVec q, DN, DT, DNC, DTC;
  velocities_after(p, d, s.P_N, s.P_T, q, DN, DT);
  const bool poisson = law == ClassicalLaw::poisson;
  if (poisson) velocities_after(p, d, s.P_NC, s.P_TC, q, DNC, DTC);
  quad r = 0;
  for (int i = 0; i < d.c; ++i) {
    if (!d.part[i]) {
      r = fmaxq(r, fmaxq(fabsq(s.P_N[i]), fabsq(s.P_T[i])) / Ps);
      continue;
    }
    const quad ei = pick_e(i), mi = pick_mu(i);
    if (!poisson) {
      r = fmaxq(r, fabsq(fminq(s.P_N[i] / Ps, (DN[i] + ei * d.DNA[i]) / vs)));
      if (d.has_T) r = fmaxq(r, coulomb_error(s.P_T[i], DT[i], mi * s.P_N[i], Ps, vs));
      continue;
    }
    r = fmaxq(r, fabsq(fminq(s.P_NC[i] / Ps, DNC[i] / vs)));
    const quad pne = s.P_N[i] - s.P_NC[i];  // e P_NC + ΔP
    r = fmaxq(r, fabsq(fminq((pne - ei * s.P_NC[i]) / Ps, DN[i] / vs)));
    if (d.has_T) {
      r = fmaxq(r, coulomb_error(s.P_TC[i], DTC[i], mi * s.P_NC[i], Ps, vs));
      r = fmaxq(r, coulomb_error(s.P_T[i] - s.P_TC[i], DT[i], mi * pne, Ps, vs));
    }
  }
  return r;
}

/// Every solution of Newton's or Poisson's law (docs/laws.md table), with Coulomb friction when
/// `mu` is not empty (one entry for every contact or one each; frictionless otherwise, P_T = 0), on
/// up to 4 contacts taking part. Newton: one phase, 0 ≤ P_N ⊥ D_NE + e D_NA ≥ 0, Coulomb on (P_T,
/// D_TE) with the bound μ P_N. Poisson: the compression 0 ≤ P_NC ⊥ D_NC ≥ 0 with Coulomb on (P_TC,
/// D_TC), bound μ P_NC; then for each compression answer the expansion P_NE = e P_NC + ΔP, 0 ≤ ΔP ⊥
/// D_NE ≥ 0, Coulomb on (P_TE, D_TE) with the bound μ P_NE; P = P_C + P_E. `singular`: a mode's
/// equations whose Gaussian elimination meets a pivot below `singular` times their largest entry
/// count as singular (the list is then not complete). The default 2^-40 (9e-13) leaves out what
/// double-precision data cannot resolve: the bar upright on both ends, whose normals differ by
/// 6e-17 (cos(π/2) in double), has an exact solution for its exact data, but one that any rounding
/// of them moves by 30 % of the velocities.
inline ClassicalSolutions classical_modes(const Problem& p, ClassicalLaw law, const QVec& e,
                                          const QVec& mu, quad singular = ldexpq(1, -40)) {
  using namespace detail;
  const ContactData d = contact_data(p);
  const int c = d.c;
  auto pick_e = [&](int i) { return e.size() == 1 ? e[0] : e.at(i); };
  QVec mus(c, 0);
  for (int i = 0; i < c && !mu.empty(); ++i) mus[i] = mu.size() == 1 ? mu[0] : mu.at(i);
  Phase ph;
  for (int i = 0; i < c; ++i)
    if (d.part[i]) ph.J.push_back(i);
  if (ph.J.size() > 4) throw std::invalid_argument("classical_modes: at most 4 contacts take part");
  ph.friction = !mu.empty() && d.has_T;
  quad vs = 0;
  for (int i : ph.J) vs = fmaxq(vs, fmaxq(fabsq(d.DNA[i]), fabsq(d.DTA[i])));
  if (vs == 0) vs = 1;
  const bool poisson = law == ClassicalLaw::poisson;
  ph.bN = d.DNA;
  ph.bT = d.DTA;
  ph.cB.assign(c, 0);
  if (!poisson)
    for (int i = 0; i < c; ++i) ph.bN[i] = (1 + pick_e(i)) * d.DNA[i];
  ClassicalSolutions res;
  std::vector<PhaseAnswer> first;
  bool first_singular = false, second_singular = false;
  std::vector<PhaseAnswer> first_points;
  res.complete = phase_answers(d, ph, mus, vs, singular, first, &first_singular, &first_points);
  if (!poisson)
    for (const PhaseAnswer& a : first_points) {
      Solution sol = empty_solution(c);
      sol.P_N = a.x;
      sol.P_T = a.t;
      complete(p, d, sol);
      sol.mode = "newton (singular mode)";
      sol.mode_pivot = 0;
      sol.residual = classical_residual(p, law, e, mu, sol);
      res.singular_example.push_back(sol);
    }
  for (const PhaseAnswer& a : first) {
    std::vector<PhaseAnswer> second;
    Phase ex = ph;
    if (poisson) {  // the expansion, from the compression's end
      for (int i = 0; i < c; ++i) {
        ex.bN[i] = d.DNA[i];
        ex.bT[i] = d.DTA[i];
        for (int k = 0; k < c; ++k) {
          const quad pn = (1 + pick_e(k)) * a.x[k];
          ex.bN[i] += d.GNN(i, k) * pn + (d.has_T ? d.GNT(i, k) * a.t[k] : quad(0));
          if (d.has_T) ex.bT[i] += d.GNT(k, i) * pn + d.GTT(i, k) * a.t[k];
        }
        ex.cB[i] = pick_e(i) * a.x[i];
      }
      res.complete =
          phase_answers(d, ex, mus, vs, singular, second, &second_singular) && res.complete;
    } else {
      second.push_back(a);
    }
    for (const PhaseAnswer& b : second) {
      Solution sol = empty_solution(c);
      for (int i = 0; i < c; ++i) {
        sol.P_N[i] = poisson ? (1 + pick_e(i)) * a.x[i] + b.x[i] : a.x[i];
        sol.P_T[i] = poisson ? a.t[i] + b.t[i] : a.t[i];
      }
      if (poisson) {
        sol.P_NC = a.x;
        sol.P_TC = a.t;
        QVec q_C;
        velocities_after(p, d, sol.P_NC, sol.P_TC, q_C, sol.D_NC, sol.D_TC);
      }
      complete(p, d, sol);
      sol.mode = poisson ? "poisson" : "newton";
      sol.mode_pivot = poisson ? fminq(a.pivot, b.pivot) : a.pivot;
      sol.residual = classical_residual(p, law, e, mu, sol);
      // One answer reached through two compression answers equal to rounding (or two expansion
      // modes) is one solution.
      quad size = 0, diff = ldexpq(1, 16000);
      for (int i = 0; i < c; ++i) size = fmaxq(size, fmaxq(fabsq(sol.P_N[i]), fabsq(sol.P_T[i])));
      for (const Solution& f : res.solutions) {
        quad di = 0;
        for (int i = 0; i < c; ++i) {
          di = fmaxq(di, fmaxq(fabsq(f.P_N[i] - sol.P_N[i]), fabsq(f.P_T[i] - sol.P_T[i])));
          if (poisson)
            di = fmaxq(di, fmaxq(fabsq(f.P_NC[i] - sol.P_NC[i]), fabsq(f.P_TC[i] - sol.P_TC[i])));
        }
        diff = fminq(diff, di);
      }
      if (!res.solutions.empty() && diff <= ldexpq(1, -80) * size) continue;
      res.solutions.push_back(sol);
    }
  }
  // Every singular mode is decided by its linear program. An empty polyhedron everywhere leaves
  // the regular list complete as to existence. A non-empty one is an answer where its vertex,
  // taken as percussions, solves the law (Newton: its residual below 1e-15; with percussions 1e19
  // times the velocities, μ = 1e8, the program's own rounding made a point 0.9 off the law look
  // feasible); else, and for Poisson's two phases, existence is left open unless a solution is
  // known anyway.
  res.singular_answers = first_singular || second_singular;
  bool verified = false;
  for (const Solution& s : res.singular_example) verified = verified || s.residual <= 1e-15;
  res.exists = !res.solutions.empty() || verified;
  res.existence_known = !res.singular_answers || res.exists;
  return res;
}

// ---------------------------------------------------------------------------------------------
// Output

inline double to_double(quad x) {
  return static_cast<double>(x);
}

/// x with `digits` significant digits (quadmath_snprintf "%.*Qg").
inline std::string to_string(quad x, int digits = 36) {
  char buf[128];
  quadmath_snprintf(buf, sizeof buf, "%.*Qg", digits, x);
  return buf;
}

}  // namespace fremond_reference
