// Frémond's law (docs/laws.md; paper §5): the method chain, the exact methods for one or decoupled
// contacts, the split of the normal percussion into reaction and dissipative parts, and uniqueness.
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include "core/detail/small_lu.hpp"
#include "fremond/admissibility/admissibility.hpp"
#include "fremond/potentials/power.hpp"
#include "laws/detail/as_power.hpp"
#include "laws/detail/residuals.hpp"
#include "laws/detail/separating_contacts.hpp"
#include "solvers/detail/chain.hpp"
#include "solvers/detail/classical_law.hpp"
#include "solvers/detail/fremond.hpp"

namespace fremond::detail {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

template <int N, int C>
using Rows = typename FremondRowsT<N, C>::Rows;

/// True when no row is coupled to another (G diagonal): each row is then one prox.
template <int N, int C>
bool decoupled(const ContactSpaceT<N, C>& cs) {
  const int r = cs.rows();
  const double scale = cs.G.cwiseAbs().maxCoeff();
  for (int j = 0; j < r; ++j)
    for (int k = 0; k < r; ++k)
      if (j != k && std::fabs(cs.G(j, k)) > 4 * kEps * scale) return false;
  return true;
}

/// The normal rows decoupled from the tangential ones: G_NT = 0 to the same threshold as
/// decoupled().
template <int N, int C>
bool normal_rows_decoupled(const ContactSpaceT<N, C>& cs) {
  const int a = cs.active, r = cs.rows();
  const double scale = cs.G.cwiseAbs().maxCoeff();
  for (int j = 0; j < a; ++j)
    for (int k = a; k < r; ++k)
      if (std::fabs(cs.G(j, k)) > 4 * kEps * scale) return false;
  return true;
}

/// Decoupled rows: P_j = 2(z_j − D_A,j)/G_jj with z_j = prox_{τ_j ψ_j}(D_A,j), τ_j = G_jj/2 (the
/// equation z = D_A + G_jj P/2, −P ∈ ∂ψ(z) is z = prox_{(G_jj/2)ψ}(D_A)). Normal rows first: the
/// Coulomb bound of a tangential row needs its P_N. A row with G_jj = 0 cannot change its velocity:
/// P_j = −(least subgradient of ψ at D_A), and a normal row with D_NA < 0 has no solution.
template <int N, int C>
MethodOutcome solve_decoupled(const FremondRowsT<N, C>& rows, Rows<N, C>& P) {
  const auto& cs = *rows.cs;
  const int r = cs.rows();
  MethodOutcome o;
  P.setZero(r);
  const double gmax = cs.G.diagonal().maxCoeff();
  for (int j = 0; j < r; ++j) {
    const double g = cs.G(j, j);
    const double D = cs.D_A(j);
    if (g > 1e-14 * gmax) {
      const double z = rows.prox(j, D, rows.bound(j, P));
      P(j) = 2.0 * (z - D) / g;
    } else if (rows.is_normal(j)) {
      if (D < 0.0) {
        o.status = SolverStatus::no_solution;
        o.message = "a contact that takes part has no normal direction (W_N column is zero)";
        return o;
      }
      P(j) = -rows.law->normal[rows.contact(j)].subgradient(D);
    } else if (rows.coulomb) {
      P(j) = D == 0.0 ? 0.0 : -std::copysign(rows.bound(j, P), D);
    } else {
      P(j) = -rows.law->tangential_potential[rows.contact(j)].subgradient(D);
    }
  }
  o.status = SolverStatus::converged;
  o.criterion = StopCriterion::exact;
  o.message = "decoupled rows: one exact prox per row";
  return o;  // the residual is check_exact's (or, for a guess, nobody's)
}

/// The start of Newton: the decoupled rows' answer from `P`, zero where it is not finite.
template <int N, int C>
Rows<N, C> decoupled_guess(const FremondRowsT<N, C>& rows, Rows<N, C> P) {
  solve_decoupled(rows, P);
  if (!P.allFinite()) P.setZero();
  return P;
}

// ---------------------------------------------------------------------------------------------
// One contact with Coulomb friction: every mode (stick, slide ±, with P_N of either sign) reduces
// to one scalar normal problem  z = D̃ + g P/2,  −P ∈ ∂ψ(z),  ψ = φ_N + I_{[D_NA/2, ∞)}.
// With g > 0 it has exactly one solution, z = prox_{(g/2)ψ}(D̃). With g ≤ 0 (μ|G_NT| > G_NN, the
// Painlevé-type case of docs/laws.md) it may have none or several: for a power law f(z) = φ'(z) −
// a(z − D̃), a = 2/|g|, is monotone between the points where φ''(z) = a, so all roots are found
// by bisection on at most three monotone pieces.

struct ScalarRoots {
  std::array<double, 4> z{};
  int count = 0;
  bool exhaustive = true;  ///< false when a degenerate case leaves a continuum of solutions
  void add(double v) {
    for (int i = 0; i < count; ++i)
      if (std::fabs(z[i] - v) <= 8 * kEps * (std::fabs(v) + std::fabs(z[i]))) return;
    if (count < 4) z[count++] = v;
  }
};

double bisect_root(const PowerPotential& phi, double a, double Dt, double lo, double hi) {
  auto f = [&](double z) { return phi.subgradient(z) - a * (z - Dt); };
  double flo = f(lo);
  for (int i = 0; i < 2000; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    const double fm = f(mid);
    if (fm == 0.0) return mid;
    if ((fm < 0.0) == (flo < 0.0)) {
      lo = mid;
      flo = fm;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

/// Solutions z of the scalar normal problem; `phi` may be null (then only g > 0 is handled).
ScalarRoots scalar_normal(const Potential& normal, const PowerPotential* phi, double Dt, double g,
                          double lb, double gscale) {
  ScalarRoots out;
  if (g > 1e-14 * gscale) {
    const double y = normal.prox(Dt, 0.5 * g);
    out.add(std::max(y, lb));
    return out;
  }
  if (std::fabs(g) <= 1e-14 * gscale) {  // z = D̃ cannot move
    if (Dt > lb) out.add(Dt);
    if (Dt == lb) {
      out.add(Dt);
      out.exhaustive = false;  // any reaction ≥ 0 will do
    }
    return out;
  }
  if (!phi) {
    out.exhaustive = false;
    return out;
  }
  const double a = 2.0 / std::fabs(g);
  auto f = [&](double z) { return phi->subgradient(z) - a * (z - Dt); };
  // Root at the bound (reaction active): a(lb − D̃) ∈ ∂ψ(lb) = (−∞, φ'(lb)].
  if (a * (lb - Dt) <= phi->subgradient(lb)) out.add(lb);
  // Interior roots z > lb, piece by piece.
  std::array<double, 4> cuts{};
  int nc = 0;
  cuts[nc++] = lb;
  const double k = phi->k(), p = phi->p();
  if (k > 0.0 && p != 2.0) {
    const double zs = std::pow(a / (k * (p - 1.0)), 1.0 / (p - 2.0));
    if (std::isfinite(zs)) {
      if (-zs > lb) cuts[nc++] = -zs;
      if (zs > lb) cuts[nc++] = zs;
    }
  }
  std::sort(cuts.begin(), cuts.begin() + nc);
  // The unbounded last piece: walk out until f has its limiting sign.
  double limit_sign;
  if (k == 0.0 || p < 2.0)
    limit_sign = -1.0;
  else if (p > 2.0)
    limit_sign = 1.0;
  else
    limit_sign = (k > a) ? 1.0 : (k < a ? -1.0 : (a * Dt > 0 ? 1.0 : -1.0));
  double hi = std::max({1.0, std::fabs(lb), std::fabs(Dt), cuts[nc - 1] + 1.0});
  for (int i = 0; i < 2100 && (f(hi) > 0.0 ? 1.0 : -1.0) != limit_sign; ++i) hi *= 2.0;
  for (int i = 0; i < nc; ++i) {
    const double lo = cuts[i];
    const double up = (i + 1 < nc) ? cuts[i + 1] : hi;
    const double flo = f(lo), fup = f(up);
    if (flo == 0.0 && lo > lb) out.add(lo);
    if (fup == 0.0) out.add(up);
    if ((flo < 0.0 && fup > 0.0) || (flo > 0.0 && fup < 0.0))
      out.add(bisect_root(*phi, a, Dt, lo, up));
  }
  return out;
}

struct ContactSolution {
  double PN, PT;
  /// The shared stopping test's residual at (PN, PT), where keep_resolved found it met as it was
  /// (check_exact's first branch): the answer's test need not run again. NaN otherwise.
  double accepted_residual = std::numeric_limits<double>::quiet_NaN();
};

/// All solutions of Frémond + Coulomb for one active contact (rows N, T).
template <int N, int C>
int one_contact_coulomb_modes(const FremondRowsT<N, C>& rows, std::array<ContactSolution, 16>& sols,
                              bool* exhaustive) {
  const auto& cs = *rows.cs;
  const int i = rows.contact(0);
  const Potential& normal = rows.law->normal[i];
  const auto* phi = as_power(normal);
  const double mu = rows.law->mu[i];
  const double gN = cs.G(0, 0), gNT = cs.G(0, 1), gT = cs.G(1, 1);
  const double DN = cs.D_A(0), DT = cs.D_A(1);
  const double lb = 0.5 * DN;
  const double gscale = std::max(gN, gT);
  int n = 0;
  *exhaustive = true;
  auto push = [&](double PN, double PT) {
    const double scale = std::fabs(PN) + std::fabs(PT) + 1e-300;
    for (int s = 0; s < n; ++s)
      if (std::fabs(sols[s].PN - PN) + std::fabs(sols[s].PT - PT) <= 1e-12 * scale) return;
    if (n < 16) sols[n++] = {PN, PT};
  };
  const double tol = 1e-12;
  // Stick: z_T = 0 ⇒ P_T = −(2 D_T + G_NT P_N)/G_TT; Schur complement on the normal row.
  if (gT > 1e-14 * gscale) {
    const double Dt = DN - gNT * DT / gT;
    const double g = gN - gNT * gNT / gT;
    const ScalarRoots roots = scalar_normal(normal, phi, Dt, g, lb, gscale);
    *exhaustive = *exhaustive && roots.exhaustive;
    for (int r = 0; r < roots.count; ++r) {
      const double PN = std::fabs(g) > 1e-14 * gscale ? 2.0 * (roots.z[r] - Dt) / g
                                                      : -normal.subgradient(roots.z[r]);
      const double PT = -(2.0 * DT + gNT * PN) / gT;
      if (std::fabs(PT) <= mu * std::fabs(PN) * (1.0 + tol)) push(PN, PT);
    }
  } else if (DT == 0.0) {
    *exhaustive = false;
  }
  // Slide with sign s of z_T, and σ the sign of P_N: P_T = −s μ|P_N| = c P_N, c = −sσμ.
  for (double s : {1.0, -1.0}) {
    for (double sigma : {1.0, -1.0}) {
      const double c = -s * sigma * mu;
      const double g = gN + gNT * c;
      const ScalarRoots roots = scalar_normal(normal, phi, DN, g, lb, gscale);
      *exhaustive = *exhaustive && roots.exhaustive;
      for (int r = 0; r < roots.count; ++r) {
        const double PN = std::fabs(g) > 1e-14 * gscale ? 2.0 * (roots.z[r] - DN) / g
                                                        : -normal.subgradient(roots.z[r]);
        if (PN * sigma < 0.0) continue;
        const double PT = c * PN;
        const double zT = DT + 0.5 * (gNT * PN + gT * PT);
        if (zT * s > 0.0) push(PN, PT);
      }
    }
  }
  return n;
}

/// Splits the normal percussion: P_reac = max(0, P_N + φ_N'(z_N)) on a contact whose reaction acts,
/// else 0 (eq. 16). The reaction acts where the natural map is on its bound branch,
/// prox_{τφ_N}(z_N − τP_N) < D_NA/2: the same test the residual uses, so the split agrees with
/// the solver's own convergence, whatever rounding left in D_NE.
/// `z` is the mean velocity of P (rows.mean_velocity).
template <int N, int C>
void split_reaction(const FremondRowsT<N, C>& rows, const Rows<N, C>& P, const Rows<N, C>& z,
                    ImpactResultT<N, C>& out) {
  const auto& cs = *rows.cs;
  out.P_N_reaction.setZero(cs.contacts);
  for (int k = 0; k < cs.active; ++k) {
    const Potential& phi = rows.law->normal[rows.contact(k)];
    const double lb = rows.lower_bound(k);
    const bool bound_branch = (!(rows.all_prox || rows.row_has_prox(k)) || !std::isfinite(z(k)))
                                  ? z(k) <= lb + 64 * kEps * (std::fabs(lb) + std::fabs(z(k)))
                                  : rows.normal_prox(k, z(k) - rows.tau(k) * P(k)) < lb;
    if (bound_branch) out.P_N_reaction(cs.index(k)) = std::max(0.0, P(k) + phi.subgradient(z(k)));
  }
}

/// The rank of A's columns, at a relative threshold of 1e-10 (0 without a column).
template <class Mat>
int column_rank(const Mat& A) {
  if (A.cols() == 0) return 0;
  Eigen::ColPivHouseholderQR<Mat> qr(A);
  qr.setThreshold(1e-10);
  return static_cast<int>(qr.rank());
}

/// The percussion is determined by the velocities except on rows whose ∂ψ is set-valued (an
/// active reaction, a sticking Coulomb contact, a kink of a potential); P is unique iff the
/// columns of W for those rows are independent.
/// `z` is the mean velocity of P (rows.mean_velocity).
template <int N, int C>
bool percussion_unique(const FremondRowsT<N, C>& rows, const Rows<N, C>& P, const Rows<N, C>& z,
                       const ImpactResultT<N, C>& out) {
  const auto& cs = *rows.cs;
  const int r = cs.rows();
  MatT<N, ContactSpaceT<N, C>::kMaxRows> Ws(cs.dofs, r);
  int m = 0;
  for (int j = 0; j < r; ++j) {
    bool set_valued;
    const double zs = 64 * kEps * cs.v_scale;
    if (rows.is_normal(j)) {
      set_valued = out.P_N_reaction(rows.contact(j)) > 0.0;
      if (!set_valued) {
        const Interval sd = rows.law->normal[rows.contact(j)].subdifferential(z(j));
        set_valued = sd.hi - sd.lo > 0.0;
      }
    } else if (rows.coulomb) {
      set_valued = std::fabs(z(j)) <= zs && rows.bound(j, P) > 0.0;
    } else {
      const Interval sd = rows.law->tangential_potential[rows.contact(j)].subdifferential(z(j));
      set_valued = sd.hi - sd.lo > 0.0;
    }
    if (set_valued) Ws.col(m++) = cs.W.col(j);
  }
  if (m <= 1) return m == 0 || Ws.col(0).squaredNorm() > 0.0;
  Ws.conservativeResize(cs.dofs, m);
  return column_rank(Ws) == m;
}

/// The free normal rows of coulomb_bounds_undetermined (see there): their columns of W go to Wf
/// (m of them); `bound_sensitive` says whether a contact among them slides or sticks near enough
/// to its bound that their freedom reaches it.
template <int N, int C>
void free_rows_moving_bounds(const FremondRowsT<N, C>& rows, const Rows<N, C>& P,
                             const Rows<N, C>& z, const ImpactResultT<N, C>& out, double limit,
                             MatT<N, C>& Wf, int& m, bool& bound_sensitive) {
  const auto& cs = *rows.cs;
  const int a = cs.active;
  Wf.resize(cs.dofs, a);
  m = 0;
  bound_sensitive = false;
  for (int j = 0; j < a; ++j) {
    const int i = rows.contact(j);
    if (out.P_N_reaction(i) > 0.0) continue;
    const double f = rows.rounding_floor(j, P);
    const Potential& phi = rows.law->normal[i];
    const Interval sd = phi.subdifferential(z(j));
    if (sd.hi - sd.lo > 0.0) continue;  // set-valued: P_N is free in exact arithmetic too
    const double s0 = phi.subgradient(z(j));
    // The freedom both ways: a null direction of W moves some rows up and others down.
    const double u = std::min(std::fabs(phi.subgradient(z(j) + f) - s0),
                              std::fabs(s0 - phi.subgradient(z(j) - f)));
    const double mu = rows.law->mu[i], tau_t = rows.tau(a + j);
    if (!(2.0 * tau_t * mu * u > limit) || !std::isfinite(u)) continue;
    Wf.col(m++) = cs.W.col(j);
    // Sliding, or sticking near enough to the bound that the bound's freedom reaches it.
    bound_sensitive =
        bound_sensitive || std::fabs(P(a + j)) >= mu * (std::fabs(P(j)) - u) - 64 * kEps * mu * u;
  }
  Wf.conservativeResize(cs.dofs, m);
}

/// Whether Coulomb's bounds μ|P_N| of an answer rest on normal percussions that double precision
/// does not determine. A normal law steep at z_N = 0 (p near 1: P_N = −k|z|^(p−1) sign z, so
/// p = 1.2 and k = 1e6 give P_N = 1 at |z| = 1e-30) leaves P_N free over the range its
/// subgradient spans across the row's rounding floor f (z_N ± f), and where the rows so left free
/// have dependent columns of W (more contacts than their normals span: the plate on four
/// contacts) the percussions can move along W's null space without moving any velocity or failing
/// the stopping test. Without friction that changes no velocity; under Coulomb it moves the bounds
/// and, where a contact slides or could, the tangential answer: on that plate (p = 1.2, k = 1e6,
/// μ = 0.3) an answer with P_N of mixed signs passes the law's test and slides 50 % off the exact
/// one, whose P_N are all positive. True when such a row's freedom moves its contact's
/// tangential velocity (2τ_T μ u) by more than the limit (free_rows_moving_bounds, whose output
/// this takes) and the free rows' normals are dependent. A reaction that acts, or a normal law
/// set-valued at z_N (P_N free in exact arithmetic too), is the law's own non-uniqueness and is
/// not counted here.
template <int N, int C>
bool coulomb_bounds_undetermined(const MatT<N, C>& Wf, int m, bool bound_sensitive) {
  return m >= 2 && bound_sensitive && column_rank(Wf) < m;
}

enum class Parallel { no, to_rounding, exactly };

/// Whether two columns are parallel: every 2×2 minor x_i y_j − x_j y_i within `relative` of
/// |x||y|, and exactly when every minor is exactly zero (from the exact products, p + e = x_i y_j
/// and q + f = x_j y_i).
template <class X, class Y>
Parallel parallelism(const X& x, const Y& y, double relative) {
  // Lagrange's identity: the minors' squares sum to |x|²|y|² − (x·y)². Where that exceeds, beyond
  // its rounding (1e-12 of |x|²|y|²), what minors each within `relative` of |x||y| can sum to,
  // one minor is not: an O(n) answer for the pairs of a pile's contacts, most of them far from
  // parallel. Overflow or underflow (NaN, 0) leave the answer to the minors.
  const double xx = x.squaredNorm(), yy = y.squaredNorm(), xy = x.dot(y);
  const double pairs = 0.5 * static_cast<double>(x.size()) * static_cast<double>(x.size() - 1);
  if (xx * yy - xy * xy > (pairs * relative * relative + 1e-12) * (xx * yy)) return Parallel::no;
  const double size = std::sqrt(xx) * std::sqrt(yy);  // x.norm() y.norm()
  bool exactly = true;
  for (Eigen::Index i = 0; i < x.size(); ++i)
    for (Eigen::Index j = i + 1; j < x.size(); ++j) {
      const double p = x(i) * y(j), e = std::fma(x(i), y(j), -p);
      const double q = x(j) * y(i), f = std::fma(x(j), y(i), -q);
      if (!(std::fabs((p - q) + (e - f)) <= relative * size)) return Parallel::no;
      exactly = exactly && p == q && e == f;
    }
  return exactly ? Parallel::exactly : Parallel::to_rounding;
}

/// The largest normal entry of a unit null vector of the sticking mode's columns for which
/// sticking_tied_below_rounding looks at the tie: nearly parallel tangents, whose lever arms
/// differ by up to about that much. Ties of order one are the steep normal laws'
/// (coulomb_mode_undetermined). A bar tilted by 6.7e-7 rad (normal entries 4.8e-7) at speeds of
/// 1.3e6 can pass with both ends sticking where the exact answer slides one, so the bar must lie
/// well above such entries; whether the tie is below rounding is then the test on its own terms.
constexpr double kTieLeverArm = 1e-3;

/// Sticking contacts tied to the normal rows through a dependence of their columns whose normal
/// entries are real (above ε) but small (at most kTieLeverArm), so that its exact condition lies
/// below rounding. For the mode's
/// columns W_E (every normal row and the sticking tangents) a null vector n gives Σ n_t z_t = 0
/// exactly (z = W_Eᵀq̄), so with the tangents' z_T = 0, Σ_normal n_t z_N,t = 0: on the bar nearly
/// flat on both ends (tangents ±δ = ±1.2e-11 apart), both contacts stick exactly only where
/// 2δ(z_N2 − z_N1) = 0. Where those terms are within 1e3 times the rows' rounding floors, the
/// stopping test cannot see that condition fail (speeds of 1e7 round z_T to 1e-8, while
/// 2δ q̄_θ = 3e-13), and the answer can stick where the exact one slides.
template <int N, int C>
bool sticking_tied_below_rounding(const FremondRowsT<N, C>& rows, const Rows<N, C>& P,
                                  const Rows<N, C>& z) {
  const auto& cs = *rows.cs;
  const int a = cs.active, n = cs.dofs;
  if (!rows.coulomb || a < 2) return false;
  Eigen::Matrix<int, Eigen::Dynamic, 1, Eigen::ColMajor, times2(C), 1> E(2 * a);
  int u = 0;
  for (int j = 0; j < a; ++j) E(u++) = j;
  for (int j = 0; j < a; ++j) {
    const double b = rows.law->mu[rows.contact(j)] * std::fabs(P(j));
    if (b > 0.0 && std::fabs(P(a + j)) < b * (1.0 - 1e-9)) E(u++) = a + j;
  }
  if (u == a) return false;  // nothing sticks
  // Such a tie needs the sticking tangents nearly dependent among themselves (W_S n_S = −W_N n_N
  // with |n_N| ≤ kTieLeverArm): two of them parallel to that but not exactly (the flat bar's
  // exactly parallel tangents are the law's continuum), or three or more of rank below their count.
  const int sticking = u - a;
  if (sticking == 1) return false;
  if (sticking == 2 &&
      parallelism(cs.W.col(E(a)), cs.W.col(E(a + 1)), kTieLeverArm) != Parallel::to_rounding)
    return false;
  MatT<N, times2(C)> WE(n, u);
  for (int t = 0; t < u; ++t) WE.col(t) = cs.W.col(E(t));
  if (u <= n && column_rank(WE) == u) return false;  // independent columns: no condition
  const Eigen::JacobiSVD<MatT<N, times2(C)>> svd(WE, Eigen::ComputeFullV);
  const auto& sv = svd.singularValues();
  int rank = 0;
  for (int t = 0; t < sv.size(); ++t)
    if (sv(t) > 1e-10 * sv(0)) ++rank;
  const auto& V = svd.matrixV();
  const double known = 64 * kEps * u;  // a null vector's entries are known to that
  for (int c = rank; c < u; ++c) {
    double normal = 0.0, terms = 0.0, floor = 0.0;
    for (int t = 0; t < u; ++t) {
      const double w = std::fabs(V(t, c));
      if (E(t) < a) {
        normal = std::max(normal, w);
        terms += w * std::fabs(z(E(t)));
      }
      floor += w * rows.rounding_floor(E(t), P);
    }
    if (normal > known && normal <= kTieLeverArm && terms <= 1e3 * floor) return true;
  }
  return false;
}

/// A contact sliding at its bound whose mean tangential velocity z_T is within its row's rounding
/// floor: the sign of z_T, which decides the friction's direction, is then rounding's, and the
/// answer passes the law's test whichever way the contact slides. `min_change`: a contact whose
/// reversal would move its own velocity by no more (2 μ|P_N| G_TT) is not counted: either
/// direction is then the answer to that accuracy.
template <int N, int C>
bool sliding_at_rounding(const FremondRowsT<N, C>& rows, const Rows<N, C>& P, const Rows<N, C>& z,
                         double min_change = 0.0) {
  const int a = rows.cs->active;
  for (int j = 0; j < a; ++j) {
    const double b = rows.law->mu[rows.contact(j)] * std::fabs(P(j));
    if (b > 0.0 && 2.0 * b * rows.cs->G(a + j, a + j) > min_change &&
        std::fabs(P(a + j)) >= b * (1.0 - 1e-9) &&
        std::fabs(z(a + j)) <= rows.rounding_floor(a + j, P))
      return true;
  }
  return false;
}

/// The same freedom reaching the answer through the other contacts: free rows (as in
/// coulomb_bounds_undetermined) whose columns are independent, but
///  - not together with the tangents of the contacts that stick (two contacts on three dofs, both
///    sticking, p = 1.5, k = 1e6, speeds 5e-6: four columns in R^3): along such a null direction
///    the free rows' percussions move with the sticking ones' and no velocity changes until a
///    bound is reached, so any sticking contact may be concerned, far from its bound included
///    (one that bears no P_N has bound 0 and cannot move);
///  - or that fix the mean velocities so near zero that a sliding contact's z_T is at its
///    rounding (two contacts on two dofs, both sliding, p = 1.5 at speeds of 1e-10): the sign
///    of z_T, which decides whether the contact slides against its velocity, is then rounding's.
/// True when rank[W_F W_S] < m + rank W_S (S the sticking tangential rows), or a sliding row's
/// |z_T| is within its rounding floor; W_F (m columns) from free_rows_moving_bounds.
template <int N, int C>
bool coulomb_mode_undetermined(const FremondRowsT<N, C>& rows, const Rows<N, C>& P,
                               const Rows<N, C>& z, const MatT<N, C>& Wf, int m) {
  const auto& cs = *rows.cs;
  const int a = cs.active;
  if (!rows.coulomb || a < 2 || m < 1) return false;
  if (sliding_at_rounding(rows, P, z)) return true;
  MatT<N, times2(C)> WS(cs.dofs, a), WFS(cs.dofs, m + a);
  WFS.leftCols(m) = Wf;
  int s = 0;
  for (int j = 0; j < a; ++j) {
    const double b = rows.law->mu[rows.contact(j)] * std::fabs(P(j));
    if (!(b > 0.0) || std::fabs(P(a + j)) >= b * (1.0 - 1e-9)) continue;  // no bound, or slides
    WS.col(s) = cs.W.col(a + j);
    WFS.col(m + s) = cs.W.col(a + j);
    ++s;
  }
  if (s == 0) return false;
  WS.conservativeResize(cs.dofs, s);
  WFS.conservativeResize(cs.dofs, m + s);
  return column_rank(WFS) < m + column_rank(WS);
}

/// Two contacts held by their reactions whose normals are parallel to rounding (every 2×2 minor
/// below 1e-10 of |n_k||n_l|) but not exactly (some minor not exactly zero: the bar upright on both
/// ends, θ = π/2 in double, normals 6e-17 apart). The exact data then fix how the two reactions
/// share their percussion through terms 1e-33 of G's entries, which double precision rounds to
/// parallel normals, whose law has a continuum of answers; under Coulomb the bounds μ|P_N|, so
/// whether each contact sticks or slides and the tangential answer, depend on that share (by up to
/// the order of the velocity scale). Exactly parallel normals are the law's own continuum, answered
/// as converged and not unique.
template <int N, int C>
bool reactions_on_normals_parallel_to_rounding(const FremondRowsT<N, C>& rows,
                                               const ImpactResultT<N, C>& out) {
  const auto& cs = *rows.cs;
  const int a = cs.active;
  for (int k = 0; k < a; ++k) {
    if (!(out.P_N_reaction(rows.contact(k)) > 0.0)) continue;
    for (int l = k + 1; l < a; ++l) {
      if (!(out.P_N_reaction(rows.contact(l)) > 0.0)) continue;
      if (parallelism(cs.W.col(k), cs.W.col(l), 1e-10) == Parallel::to_rounding) return true;
    }
  }
  return false;
}

/// The split of the normal percussions that coulomb_bounds_undetermined finds double precision
/// cannot make, made from its exact condition. For any n with W_F n = 0 (F the free normal rows),
/// nᵀz_F = nᵀD_A,F = nᵀw_F: zero for fixed obstacles, a condition on the mean normal velocities
/// z_F, which are far below their rounding as D_A + GP/2 but exact as functions of the percussions:
/// for the power law, z_j = −sign(P_j) (|P_j|/k_j)^(q_j − 1), q_j = p_j/(p_j − 1). That condition
/// is the stationarity, over P_F + N α (N a basis of null(W_F)), of the convex Σ_j k_j^(1−q_j)
/// |P_j|^q_j / q_j (the conjugates of the normal potentials), which Newton minimises in α with
/// every term scaled by the largest, in logarithms (p = 1.01, k = 1e6 puts z near 1e-600). Moving
/// along N changes no velocity; the tangential rows, whose bounds moved, are then solved again with
/// the normal percussions held (Gauss–Seidel sweeps), which settles the plate, whose tangential
/// rows do not move its normal ones; where they do, semismooth Newton on the whole law follows,
/// alternating with the split until its answer keeps the condition. Only power laws, fixed
/// obstacles (nᵀw_F = 0) and an answer that passes the law's test again: true then, with P
/// replaced; else false and P untouched. On the plate on four points (p = 1.2, k = 1e6) the split
/// answer is within 1e-10 of the exact one where the plain answer is 50 % off.
template <int N, int C>
bool split_normal_percussions(const FremondRowsT<N, C>& rows, Rows<N, C>& P,
                              const ImpactResultT<N, C>& out, const SolverOptions& opt) {
  const auto& cs = *rows.cs;
  const int a = cs.active, n = cs.dofs;
  Eigen::Matrix<int, Eigen::Dynamic, 1, 0, C, 1> F(a);
  VecT<C> k(a), q(a);
  int m = 0;
  for (int j = 0; j < a; ++j) {
    const int i = rows.contact(j);
    if (out.P_N_reaction(i) > 0.0) continue;
    const Potential& phi = rows.law->normal[i];
    const auto* power = as_power(phi);
    if (!power || !(power->p() > 1.0) || !(power->k() > 0.0)) return false;
    F(m) = j;
    k(m) = power->k();
    q(m) = power->p() / (power->p() - 1.0);
    ++m;
  }
  if (m < 2) return false;
  MatT<N, C> WF(n, m);
  for (int t = 0; t < m; ++t) WF.col(t) = cs.W.col(F(t));
  const Eigen::FullPivLU<MatT<N, C>> lu(WF);
  const MatT<C, C> kernel = lu.kernel();
  if (kernel.cols() == 0 || kernel.isZero(0.0)) return false;
  const MatT<C, C> Nb = Eigen::HouseholderQR<MatT<C, C>>(kernel).householderQ() *
                        MatT<C, C>::Identity(m, kernel.cols());
  const int d = static_cast<int>(Nb.cols());
  // Fixed obstacles only: nᵀD_A,F must be rounding.
  for (int c = 0; c < d; ++c) {
    double s = 0.0, size = 0.0;
    for (int t = 0; t < m; ++t) {
      s += Nb(t, c) * cs.D_A(F(t));
      size += std::fabs(Nb(t, c) * cs.D_A(F(t)));
    }
    if (!(std::fabs(s) <= 64 * kEps * size)) return false;
  }
  // ŝ_t = −z_t scaled by the largest |z|, ĥ_t = ∂ŝ_t/∂P_t likewise (log|z_t| = (q−1) log(|P|/k)),
  // and ŝ_t's rounding: P_t's last bit and the logarithm's, both times q − 1 (p = 1.01: 100).
  VecT<C> s_hat(m), h_hat(m), s_err(m);
  auto scaled_terms = [&](const Rows<N, C>& Q, double& log_max) {
    log_max = -std::numeric_limits<double>::infinity();
    for (int t = 0; t < m; ++t) {
      const double x = std::fabs(Q(F(t))), l = x > 0.0 ? std::log(x / k(t)) : 0.0;
      s_err(t) = 8 * kEps * (1.0 + (q(t) - 1.0) * (1.0 + std::fabs(l)));
      s_hat(t) = x > 0.0 ? (q(t) - 1.0) * l : -std::numeric_limits<double>::infinity();
      log_max = std::max(log_max, s_hat(t));
    }
    for (int t = 0; t < m; ++t) {
      const double x = Q(F(t)), e = std::exp(s_hat(t) - log_max);
      s_hat(t) = std::copysign(e, x);
      h_hat(t) = x != 0.0 ? (q(t) - 1.0) * e / std::fabs(x) : 0.0;
      s_err(t) *= e;
    }
  };
  // Nᵀŝ, by hand: Eigen's product of these bounded sizes draws a false "maybe uninitialised" from
  // GCC 12.
  auto gradient = [&]() {
    VecT<C> g = VecT<C>::Zero(d);
    for (int c = 0; c < d; ++c)
      for (int t = 0; t < m; ++t) g(c) += Nb(t, c) * s_hat(t);
    return g;
  };
  auto length = [&](const VecT<C>& v) {  // ‖v‖, by hand for the same reason
    double sum = 0.0;
    for (int c = 0; c < d; ++c) sum += v(c) * v(c);
    return std::sqrt(sum);
  };
  // Nᵀŝ = 0 to the rounding of its terms.
  auto gradient_at_rounding = [&](const VecT<C>& g) {
    for (int c = 0; c < d; ++c) {
      double floor = 0.0;
      for (int t = 0; t < m; ++t) floor += std::fabs(Nb(t, c)) * s_err(t);
      if (!(std::fabs(g(c)) <= floor)) return false;
    }
    return true;
  };
  // Ψ at Q scaled by exp(log_ref): Σ_t |ŝ_t| |P_t| / q_t.
  auto psi = [&](const Rows<N, C>& Q, double log_ref) {
    double sum = 0.0;
    for (int t = 0; t < m; ++t) {
      const double x = std::fabs(Q(F(t)));
      if (x > 0.0) sum += std::exp((q(t) - 1.0) * std::log(x / k(t)) - log_ref) * x / q(t);
    }
    return sum;
  };
  // Newton's step in α (from scaled_terms' last point) and whether it is negligible: it moves no
  // percussion by more than would move a tangential velocity through the bounds by 1e-9 of the
  // velocity scale, 1/1000 of what coulomb_bounds_undetermined allows (with q = 101 the gradient
  // itself is only known to 1e-12 of its terms, and Ψ's decrease is below Ψ's rounding long
  // before).
  double mu_max = 0.0, tau_max = 0.0;
  for (int t = 0; t < m; ++t) {
    mu_max = std::max(mu_max, rows.law->mu[rows.contact(F(t))]);
    tau_max = std::max(tau_max, rows.tau(a + F(t)));
  }
  auto newton_step = [&](const VecT<C>& g, VecT<C>& step) {
    MatT<C, C> H = Nb.transpose() * h_hat.asDiagonal() * Nb;
    H.diagonal().array() += 1e-14 * H.diagonal().cwiseAbs().maxCoeff() + 1e-300;
    step = -H.ldlt().solve(g);
    if (!step.allFinite()) return false;
    const double moved_P = (Nb * step).cwiseAbs().maxCoeff();
    return 2.0 * tau_max * mu_max * moved_P <= 1e-9 * cs.v_scale;
  };
  auto stationary = [&](const Rows<N, C>& Q) {
    double log_max = 0.0;
    scaled_terms(Q, log_max);
    const VecT<C> g = gradient();
    VecT<C> step;
    return gradient_at_rounding(g) || newton_step(g, step);
  };
  // Newton with a line search on Ψ; near the minimum Ψ's decrease is below its own rounding, and a
  // step is taken there when it shrinks the gradient instead.
  auto make_stationary = [&](Rows<N, C>& Q) {
    for (int it = 0; it < 100; ++it) {
      double log_max = 0.0;
      scaled_terms(Q, log_max);
      const VecT<C> g = gradient();
      if (gradient_at_rounding(g)) return true;
      VecT<C> step;
      if (newton_step(g, step)) {
        for (int u = 0; u < m; ++u) Q(F(u)) += Nb.row(u).dot(step);
        return true;
      }
      if (!step.allFinite()) return false;
      const double f0 = psi(Q, log_max), g0 = length(g);
      double t = 1.0;
      bool moved = false;
      for (int ls = 0; ls < 60 && !moved; ++ls, t *= 0.5) {
        Rows<N, C> trial = Q;
        for (int u = 0; u < m; ++u) trial(F(u)) += t * Nb.row(u).dot(step);
        const double f1 = psi(trial, log_max);
        if (f1 < f0 + 1e-4 * t * g.dot(step)) {
          moved = true;
        } else if (f1 <= f0 * (1.0 + 64 * kEps)) {
          double log_trial = 0.0;
          scaled_terms(trial, log_trial);
          moved = std::exp(log_trial - log_max) * length(gradient()) < g0;
        }
        if (moved) {
          // A full step accepted: Newton on |P|^q with q large (p = 1.01: q = 101) shrinks P by
          // only 1/(q − 1) a step, so longer steps are tried while Ψ keeps decreasing.
          double best = f1;
          for (double longer = 2.0 * t; ls == 0 && longer <= 256.0; longer *= 2.0) {
            Rows<N, C> further = Q;
            for (int u = 0; u < m; ++u) further(F(u)) += longer * Nb.row(u).dot(step);
            const double f2 = psi(further, log_max);
            if (!(f2 < best)) break;
            best = f2;
            trial = further;
          }
          Q = trial;
        }
      }
      if (!moved) return stationary(Q);
    }
    return stationary(Q);
  };
  Rows<N, C> Q = P, z, R;
  const double target = opt.tolerance * cs.v_scale;
  // The tangential rows alone, by Gauss–Seidel sweeps with the normal percussions held: where they
  // do not move the normal rows (G_NT = 0, the plate), the split above still holds after them.
  auto tangential_sweeps = [&](Rows<N, C>& X) {
    const int r = cs.rows();
    rows.mean_velocity(X, z);
    for (int sweep = 0; sweep < 1000; ++sweep) {
      double change = 0.0;
      for (int j = a; j < r; ++j) {
        const double g = cs.G(j, j);
        if (!(g > 0.0)) continue;
        change = std::max(change, std::fabs(rows.gauss_seidel_step(j, X, z)) * g);
      }
      if (!(change > 0.25 * target)) break;
    }
  };
  for (int round = 0; round < 6; ++round) {
    if (!make_stationary(Q)) return false;
    tangential_sweeps(Q);
    if (std::isfinite(rows.residual(Q, z, R)) && rows.converged(Q, R, target)) {
      P = Q;
      return true;
    }
    // The bounds moved: the tangential rows again, from here.
    if (semismooth_newton(rows, Q, opt).status != SolverStatus::converged) return false;
    if (stationary(Q)) {
      P = Q;
      return true;
    }
  }
  return false;
}

/// One Gauss–Seidel sweep after convergence: each row then satisfies its own law exactly given the
/// others (a row in a dead zone or a stick zone gets exactly zero, not Newton's last rounding).
/// Every row, smooth ones included: with μ = 1e8 and M of entries 1e11, skipping those (0 <
/// ∂prox/∂x < 1) moves velocities by 3e-7 that must stay at q̇_A to 1e-13
/// (RegressionFremond.CoulombConeIsChecked…). Kept only if the answer still passes the stopping
/// test; then `o` gets its plain residual, so that the driver need not evaluate the law once more.
template <int N, int C>
void final_row_sweep(const FremondRowsT<N, C>& rows, Rows<N, C>& P, double target,
                     MethodOutcome& o) {
  const auto& cs = *rows.cs;
  const int r = cs.rows();
  if (r < 2) return;
  Rows<N, C> Q = P, z, R;
  rows.mean_velocity(P, z);
  const double gmax = cs.G.diagonal().maxCoeff();
  bool moved = false;
  for (int j = 0; j < r; ++j) {
    const double g = cs.G(j, j);
    if (!(g > 1e-14 * gmax)) continue;
    if (rows.gauss_seidel_step(j, Q, z) != 0.0) moved = true;
  }
  if (!moved) return;
  if (std::isfinite(rows.residual(Q, z, R)) && rows.converged(Q, R, target)) {
    P = Q;
    o.residual = R.cwiseAbs().maxCoeff();  // what plain_residual(P) would compute again
    o.residual_is_plain = true;
  }
}

/// R(P) with the mean velocity taken from the velocities themselves: q̇_E = q̇_A + M⁻¹WP from a
/// twice-precise force (velocity_after, accurate), D_E = Wᵀq̇_E + w by accurate dot products and
/// z = (D_A + D_E)/2 (paper eq. 21). The contact-space form z = D_A + GP/2 is rounded to
/// ε Σ_k |G_jk P_k|, which is far above ε|z| where the percussions' terms cancel: a light rotor
/// (mass ratio 1e6) has G of condition 3e6, percussions of 1e6 and terms G_jk P_k of 1e12 that
/// cancel to velocities of 1e6. Returns the weighted norm, as FremondRowsT::residual.
template <int N, int C>
double velocity_space_residual(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows,
                               const Rows<N, C>& P, Rows<N, C>& z, Rows<N, C>& R) {
  const auto& cs = *rows.cs;
  const int r = cs.rows(), a = cs.active;
  VecT<N> q;
  velocity_after(pb, cs, P, q, /*accurate=*/true);
  z.resize(r);
  for (int j = 0; j < r; ++j) {
    const bool normal = j < a;
    const int i = cs.index(normal ? j : j - a);
    const auto& w = normal ? pb.w_N : pb.w_T;
    z(j) = 0.5 * (cs.D_A(j) + contact_velocity(cs.W.col(j), q, w.size() ? w(i) : 0.0));
  }
  return rows.residual_at(P, z, R);
}

/// Iterative refinement of an answer that the stopping test accepted at the contact space's
/// rounding floor (criterion `rounding`): Newton steps J ΔP = −R with R from the velocities
/// themselves (velocity_space_residual) and J the law's generalized Jacobian in contact space,
/// while that residual decreases (at most 4). Where the terms of GP cancel, the floor is ε|G||P| ≫
/// ε|z|, and an answer there is off by up to that floor (a light rotor, mass ratio 1e6: D_NE =
/// −6e-3 where the reaction holds it at 0); the refined one is at the rounding of the velocities.
/// Kept only when the law's own stopping test still accepts it. Returns true when P was changed.
template <int N, int C>
bool refine_in_velocity_space(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows,
                              Rows<N, C>& P, double target) {
  using RowMat = typename ContactSpaceT<N, C>::RowMat;
  const int r = rows.cs->rows();
  Rows<N, C> z, R, Q, zq, Rq, dP(r);
  double nr = velocity_space_residual(pb, rows, P, z, R);
  if (!std::isfinite(nr) || nr == 0.0) return false;
  RowMat J(r, r);
  Q = P;
  bool moved = false;
  for (int it = 0; it < 4; ++it) {
    rows.jacobian(z, Q, J);
    if constexpr (N != Dynamic) {
      SmallLU<ContactSpaceT<N, C>::kMaxRows> lu;
      lu.compute(J);
      if (!lu.well_conditioned(1e-14)) break;
      lu.solve(-R, dP);
    } else {
      Eigen::PartialPivLU<RowMat> lu(J);
      if (!(lu.rcond() > 1e-14)) break;
      dP = lu.solve(-R);
    }
    if (!dP.allFinite()) break;
    const Rows<N, C> trial = Q + dP;
    const double nt = velocity_space_residual(pb, rows, trial, zq, Rq);
    if (!(nt < nr)) break;
    Q = trial;
    z = zq;
    R = Rq;
    nr = nt;
    moved = true;
  }
  if (!moved) return false;
  Rows<N, C> zc, Rc;
  if (!(std::isfinite(rows.residual(Q, zc, Rc)) && rows.converged(Q, Rc, target))) return false;
  P = Q;
  return true;
}

/// Frémond + Coulomb on two to four contacts: Coulomb's tangential modes enumerated. Each mode
/// (stick, sliding forwards, backwards per contact) makes the tangential rows smooth, and Newton on
/// them converges where Newton on Coulomb's law itself stalls at a kink of ‖R‖²: a block landing
/// flat on both corners, one sticking, the other sliding at 2e-7 of the velocity scale. The kinks a
/// mode leaves are held fixed too: each normal row's branch (the law's own row first, then free or
/// with its reaction active, FremondRowsT::fixed_normal) and the sign σ of P_N in a sliding
/// contact's bound μσP_N (FremondRowsT::fixed_signs): Newton stops at them short of answers that
/// exist (a contact sliding with its reaction active, or pulling with P_N < 0). The modes and signs
/// of `start` (its mean tangential velocities, stick where |z_T| ≤ 1e-8 v_scale; the signs of its
/// P_N) come first, then the other modes by the number of contacts changed, then the flipped signs;
/// Newton on a mode starts from `start`, then from zero, which reaches answers the start misses. A
/// mode's answer is taken when it passes the stopping test of the law itself (with |P_N|: an answer
/// whose P_N has the other sign is no answer). Returns false, P untouched, when no mode does
/// (ill-posed splits included: two stick rows with the same W_T give Newton one split of many).
template <int N, int C>
bool enumerate_coulomb_modes(const FremondRowsT<N, C>& rows, const Rows<N, C>& start, Rows<N, C>& P,
                             const SolverOptions& opt, MethodOutcome& out) {
  const auto& cs = *rows.cs;
  const int a = cs.active;
  if (!rows.coulomb || a < 2 || a > 4) return false;
  Rows<N, C> z, R;
  rows.mean_velocity(start, z);
  std::array<signed char, 4> guess{}, mode{}, sign_guess{}, sign{}, normal{};
  for (int k = 0; k < a; ++k) {
    const double zt = z(a + k);
    guess[k] = std::fabs(zt) <= 1e-8 * cs.v_scale ? 0 : (zt > 0.0 ? 1 : -1);
    sign_guess[k] = start(k) < 0.0 ? -1 : 1;
  }
  constexpr signed char kNext[3] = {1, -1, 0};  // the other two modes of each, in turn
  const auto other = [&](signed char m, int step) {
    for (int i = 0; i < step; ++i) m = kNext[m + 1];
    return m;
  };
  FremondRowsT<N, C> fixed = rows;
  fixed.fixed_modes = mode.data();
  fixed.fixed_signs = sign.data();
  fixed.fixed_normal = normal.data();
  const double target = opt.tolerance * cs.v_scale;
  int total = 1;
  for (int k = 0; k < a; ++k) total *= 3;
  int sweeps = 0;
  // Normal branches: the law's own rows first (code −1), then each contact free or with its
  // reaction active (bit k of the code set: contact k's reaction active).
  // On four contacts the signs of P_N stay the start's: 81 modes × 17 branches already, and the
  // flips would multiply the cost by five without reaching more answers.
  const int max_flipped = a == 4 ? 0 : a;
  for (int branches = -1; branches < (1 << a); ++branches) {
    for (int k = 0; k < a; ++k)
      normal[k] = static_cast<signed char>(branches < 0 ? 0 : ((branches >> k) & 1 ? 2 : 1));
    for (int flipped = 0; flipped <= max_flipped; ++flipped)
      for (int flips = 0; flips < (1 << a); ++flips) {
        if (std::popcount(static_cast<unsigned>(flips)) != flipped) continue;
        for (int changed = 0; changed <= a; ++changed)
          for (int code = 0; code < total; ++code) {
            // code's base-3 digits: 0 keeps the guess's mode of that contact, 1 and 2 the others.
            int c = code, n_changed = 0;
            bool repeated = false;
            for (int k = 0; k < a; ++k, c /= 3) {
              const int digit = c % 3;
              n_changed += digit != 0;
              mode[k] = other(guess[k], digit);
              const bool flip = (flips >> k) & 1;
              sign[k] = static_cast<signed char>(flip ? -sign_guess[k] : sign_guess[k]);
              repeated = repeated || (flip && mode[k] == 0);  // a sticking row has no bound
            }
            if (n_changed != changed || repeated) continue;
            Rows<N, C> Q = start;
            MethodOutcome o = semismooth_newton(fixed, Q, opt);
            sweeps += o.iterations;
            if (o.status != SolverStatus::converged && !start.isZero(0.0)) {
              Q.setZero();
              o = semismooth_newton(fixed, Q, opt);
              sweeps += o.iterations;
            }
            if (o.status != SolverStatus::converged) continue;
            const double r = rows.residual(Q, z, R);
            if (!(std::isfinite(r) && rows.converged(Q, R, target))) continue;
            P = Q;
            out.status = SolverStatus::converged;
            out.criterion = StopCriterion::residual;
            out.iterations = sweeps;
            out.residual = r;
            out.message =
                "Coulomb's tangential modes enumerated: semismooth Newton on the first mode whose "
                "answer satisfies the law";
            return true;
          }
      }
  }
  return false;
}

/// An exact method (one prox per row, mode enumeration) is exact in exact arithmetic; on
/// ill-conditioned data (cond(M) ~ 1e13 with μ = 1e8) its answer can miss the tolerance. Its
/// answer P is checked by the shared stopping test and, if it misses, polished by semismooth
/// Newton from there; if that fails too, the outcome says `stalled` (never a silent "converged").
/// The outcome `o` is updated in place, here and in the chain's `finish`: a copy of a
/// MethodOutcome whose fields were just stored one by one is reloaded in 16-byte pieces, a
/// store-forwarding stall that cost a quarter of this function on the bar.
/// True when P met the test as it was (`o` then holds its plain residual).
template <int N, int C>
bool check_exact(const FremondRowsT<N, C>& rows, Rows<N, C>& P, const SolverOptions& opt,
                 MethodOutcome& o) {
  if (o.status != SolverStatus::converged || rows.cs->rows() == 0) return false;
  Rows<N, C> z, R;
  const double target = opt.tolerance * rows.cs->v_scale;
  if (std::isfinite(rows.residual(P, z, R)) && rows.converged(P, R, target)) {
    o.residual = R.cwiseAbs().maxCoeff();  // what plain_residual(P) would compute again
    o.residual_is_plain = true;
    return true;
  }
  Rows<N, C> Q = P;
  if (rows.all_prox) {
    MethodOutcome n = semismooth_newton(rows, Q, opt);
    if (n.status == SolverStatus::converged) {
      P = Q;
      n.message =
          "the exact answer missed the tolerance (ill-conditioned data): polished by "
          "semismooth Newton";
      o = n;
      return false;
    }
  }
  o.status = SolverStatus::stalled;
  o.message =
      "the exact answer misses the tolerance (ill-conditioned data) and semismooth Newton "
      "could not polish it";
  return false;
}

/// Keeps the candidates of the mode enumeration that satisfy the law to the shared stopping test
/// (after check_exact's polish): a degenerate mode (W_T = W_N, g ≈ 0) can produce percussions of
/// 1e23 that cancel in exact arithmetic only. A dropped candidate makes the list non-exhaustive.
template <int N, int C>
int keep_resolved(const FremondRowsT<N, C>& rows, std::array<ContactSolution, 16>& sols, int n,
                  const SolverOptions& opt, bool* exhaustive) {
  int kept = 0;
  for (int s = 0; s < n; ++s) {
    Rows<N, C> P(2);
    P << sols[s].PN, sols[s].PT;
    MethodOutcome o;
    o.status = SolverStatus::converged;
    o.criterion = StopCriterion::exact;
    const bool as_it_was = check_exact(rows, P, opt, o);
    if (o.status == SolverStatus::converged)
      sols[kept++] = ContactSolution{
          P(0), P(1), as_it_was ? o.residual : std::numeric_limits<double>::quiet_NaN()};
  }
  if (kept < n) *exhaustive = false;
  return kept;
}

/// The outcome `o` of method `m` into the result's report, with `residual` (unscaled) in place of
/// o.residual.
template <int N, int C>
void write_outcome(const MethodOutcome& o, double residual, SolverMethod m, double v_scale,
                   const SolverOptions& opt, ImpactResultT<N, C>& out) {
  out.solver.method = m;
  out.solver.status = o.status;
  out.solver.criterion = o.criterion;
  out.solver.iterations = o.iterations;
  out.solver.message = o.message;
  out.solver.native_code = o.native_code;
  out.solver.residual = residual / v_scale;
  // A method that stopped on FremondRows::converged's rounding floors has a residual above the
  // tolerance: say so by the criterion (SolverStatus::converged's second clause), so "converged"
  // never hides a residual above tolerance.
  const double promised = m == SolverMethod::nlopt ? opt.nlopt_accepts() : opt.tolerance;
  if (o.status == SolverStatus::converged && !(out.solver.residual <= promised))
    out.solver.criterion = StopCriterion::rounding;
}

template <int N, int C>
void write_outcome(const MethodOutcome& o, SolverMethod m, double v_scale, const SolverOptions& opt,
                   ImpactResultT<N, C>& out) {
  write_outcome(o, o.residual, m, v_scale, opt, out);
}

/// True when no velocity after the impact keeps every contact that takes part from penetrating:
/// D_NE = D_NA + G_N P ≥ 0 holds for no percussions P. Frémond's reaction asks D_NE ≥ 0 of every
/// contact that takes part whatever the potentials (docs/laws.md), so the law then has no solution.
/// By Farkas's lemma that is y ≥ 0 with W_N y = 0 and y·w_N < 0: obstacles that close in on the
/// body from opposite sides faster than it can move. The same inequalities make Newton's law with e
/// = 0 on the normal rows, a positive semidefinite LCP, solvable exactly when they are feasible;
/// its solver decides, with a Lemke ray checked to be a proof beyond rounding (classical_law.hpp).
template <int N, int C>
bool normal_rows_infeasible(const ImpactProblemT<N, C>& pb, HeldContacts held) {
  ContactSpaceT<N, C> cs;
  build_contact_space(pb, false, cs, held);
  classical::LawOutcome<C> lo;
  classical::solve_law(pb, cs, RestitutionLaw{}, 0, lo);  // Newton, e = 0
  return lo.solutions.size == 0 && lo.exhaustive && !lo.beyond_precision && !lo.unsupported;
}

/// Frémond's chain (docs/solvers.md): the stages of run()'s table, in order; the first that
/// answers ends it. A stage applies to some laws, problems and requested methods; it runs one or
/// more methods, each recorded in the result's attempt log, and answers or hands on what it
/// learned (its end point, as the next stages' start).
template <int N, int C>
struct FremondChain {
  FremondChain(const ImpactProblemT<N, C>& pb_, const ContactSpaceT<N, C>& cs_,
               const FremondLaw& law_, const SolverOptions& opt_, ImpactResultT<N, C>& out_)
      : pb(pb_),
        cs(cs_),
        law(law_),
        opt(opt_),
        out(out_),
        want(opt_.method),
        automatic(opt_.method == SolverMethod::automatic) {
    rows.init(cs, law);
    P = Rows<N, C>::Zero(cs.rows());
    has_prox = rows.all_prox;  // else only NLopt applies
    velocity_space = has_prox && !rows.coulomb;
  }

  void run() {
    using F = FremondChain;
    run_stages<
        // Exact stages.
        Stage<&F::no_contact, &F::trivial>,  // no contact takes part: no percussion
        Stage<&F::forced_without_prox, &F::unsupported_without_prox>,  // forced, no prox
        Stage<&F::decoupled_rows, &F::solve_decoupled_rows>,           // one prox per row
        Stage<&F::one_contact_coulomb, &F::one_contact_modes>,         // every mode
        Stage<&F::one_contact_dead_zone, &F::dead_zone_prox>,          // one prox, P_T = 0
        Stage<&F::forced_coulomb_modes, &F::coulomb_modes_by_name>,    // 2-4 contacts, by name
        Stage<&F::forced_exact_inapplicable, &F::unsupported_exact>,
        Stage<&F::forced_other_law, &F::unsupported_other_law>,
        // Iterative stages: Newton, the splitting, NLopt, and restarts from each one's end.
        Stage<&F::newton_allowed, &F::velocity_newton_first>,  // rows > 2 dofs, no Coulomb
        Stage<&F::newton_allowed, &F::contact_newton>,         // from the decoupled guess
        Stage<&F::coulomb_newton_from_zero, &F::newton_from_zero>,
        Stage<&F::coulomb_modes_after_newton, &F::coulomb_modes>,  // Newton per mode, 2-4
        Stage<&F::splitting_allowed, &F::splitting>,  // from Newton's end or the guess, then 0
        Stage<&F::after_failed_splitting, &F::newton_from_splitting>, Stage<&F::always, &F::nlopt>,
        Stage<&F::after_nlopt_with_prox, &F::newton_from_nlopt>,
        Stage<&F::late_velocity_newton_applies, &F::velocity_newton>,
        Stage<&F::after_velocity_newton, &F::newton_from_velocity_newton>,
        Stage<&F::normal_rows_apart, &F::normal_rows_first>,         // G_NT = 0: normal rows alone
        Stage<&F::splitting_and_nlopt_failed, &F::nearest_failure>,  // the nearest failure
        Stage<&F::always, &F::nlopt_answer>>(*this);
  }

  // ---- shared state --------------------------------------------------------------------------

  const ImpactProblemT<N, C>& pb;
  const ContactSpaceT<N, C>& cs;
  const FremondLaw& law;
  const SolverOptions& opt;
  ImpactResultT<N, C>& out;
  const SolverMethod want;
  const bool automatic;
  FremondRowsT<N, C> rows;
  bool has_prox = false, velocity_space = false;
  Rows<N, C> P;   // the percussions the stages work on
  Rows<N, C> z;   // the mean velocity of the answer, shared by the split and the uniqueness test
  Rows<N, C> P0;  // the decoupled guess, once Newton's stages made it
  Rows<N, C> PV;  // where velocity-space Newton stopped
  Rows<N, C> P_split;  // where NLopt started: the splitting's end, if it ran
  AttemptStart split_start = AttemptStart::zero;
  MethodOutcome split_end, nlopt_end;
  bool have_split_end = false, velocity_ran = false, have_velocity_end = false;

  void record(SolverMethod m, AttemptStart from, const MethodOutcome& o) {
    out.solver.record(m, from, o.status, o.residual / cs.v_scale);
  }

  // ---- when each stage applies ----------------------------------------------------------------

  bool always() const { return true; }
  bool no_contact() const { return cs.active == 0; }
  bool forced_without_prox() const {
    return !has_prox && !automatic && want != SolverMethod::nlopt;
  }
  bool decoupled_rows() const {
    return has_prox && decoupled(cs) &&
           (automatic || want == SolverMethod::closed_form || want == SolverMethod::scalar_newton);
  }
  bool one_contact_coulomb() const {
    return has_prox && cs.active == 1 && rows.coulomb &&
           (automatic || want == SolverMethod::mode_enumeration);
  }
  bool one_contact_dead_zone() const {
    return has_prox && cs.active == 1 && cs.tangential && law.has_tangential_potential() &&
           (automatic || want == SolverMethod::scalar_newton ||
            want == SolverMethod::closed_form) &&
           cs.G(0, 0) > 0.0;
  }
  bool forced_coulomb_modes() const {
    return want == SolverMethod::mode_enumeration && has_prox && rows.coulomb && cs.active >= 2 &&
           cs.active <= 4;
  }
  bool forced_exact_inapplicable() const {
    return !automatic &&
           (want == SolverMethod::closed_form || want == SolverMethod::scalar_newton ||
            want == SolverMethod::mode_enumeration);
  }
  // A method that is not Frémond's (the classical laws' Lemke and sweeps, Stronge's
  // integration), or trivial where contacts take part: forced, it is refused rather than answered
  // by NLopt under its name.
  bool forced_other_law() const {
    switch (want) {
      case SolverMethod::automatic:
      case SolverMethod::closed_form:
      case SolverMethod::scalar_newton:
      case SolverMethod::mode_enumeration:
      case SolverMethod::semismooth_newton:
      case SolverMethod::proximal:
      case SolverMethod::nlopt:
        return false;
      default:
        return true;
    }
  }
  bool newton_allowed() const {
    return has_prox && (automatic || want == SolverMethod::semismooth_newton);
  }
  bool coulomb_newton_from_zero() const {
    return automatic && newton_allowed() && law.uses_coulomb() && !P0.isZero(0.0);
  }
  bool coulomb_modes_after_newton() const { return automatic && newton_allowed() && rows.coulomb; }
  bool splitting_allowed() const {
    return has_prox && (automatic || want == SolverMethod::proximal);
  }
  bool after_failed_splitting() const { return automatic && have_split_end; }
  bool after_nlopt_with_prox() const { return automatic && has_prox && P.allFinite(); }
  bool nlopt_failed_in_velocity_space() const {
    return automatic && velocity_space && nlopt_end.status != SolverStatus::converged &&
           P0.size() == cs.rows();
  }
  // Without Coulomb the velocity-space problem is strongly convex, and its Newton reaches the
  // minimiser where contact space's methods stall on a badly scaled G; only where every other
  // method failed, since answers accepted at the law's rounding floor are not all equally near
  // the exact one.
  bool late_velocity_newton_applies() const {
    return nlopt_failed_in_velocity_space() && !velocity_ran;
  }
  bool after_velocity_newton() const {
    return nlopt_failed_in_velocity_space() && have_velocity_end;
  }
  bool normal_rows_apart() const {
    return nlopt_failed_in_velocity_space() && cs.tangential && normal_rows_decoupled(cs);
  }
  bool splitting_and_nlopt_failed() const {
    return have_split_end && nlopt_end.status != SolverStatus::converged;
  }

  // ---- the stages ---------------------------------------------------------------------------

  bool trivial() {
    MethodOutcome o;
    o.status = SolverStatus::converged;
    o.criterion = StopCriterion::exact;
    o.message = "no contact takes part (every D_NA > 0): no percussion";
    record(SolverMethod::trivial, AttemptStart::none, o);
    finish(o, SolverMethod::trivial);
    return true;
  }

  bool unsupported(const char* why) {
    MethodOutcome o;
    o.status = SolverStatus::unsupported;
    o.message = why;
    finish(o, want);
    return true;
  }
  bool unsupported_without_prox() {
    return unsupported("a potential of the law has no prox: only the NLopt method applies");
  }
  bool unsupported_exact() {
    return unsupported("the requested exact method does not apply to this problem");
  }
  bool unsupported_other_law() {
    return unsupported("the requested method is not one of Frémond's law");
  }

  bool solve_decoupled_rows() {
    MethodOutcome o = solve_decoupled(rows, P);
    return exact_prox_answers(o);
  }

  // An answer of exact proxes: checked, recorded and written (closed_form when every potential is
  // piecewise quadratic).
  bool exact_prox_answers(MethodOutcome& o) {
    check_exact(rows, P, opt, o);
    const SolverMethod m =
        rows.all_quadratic ? SolverMethod::closed_form : SolverMethod::scalar_newton;
    record(m, AttemptStart::none, o);
    finish(o, m);
    return true;
  }

  bool one_contact_modes() {
    std::array<ContactSolution, 16> sols;
    bool exhaustive = true;
    const int n = keep_resolved(rows, sols, one_contact_coulomb_modes(rows, sols, &exhaustive), opt,
                                &exhaustive);
    if (n == 0 && !exhaustive) return false;
    MethodOutcome o;
    o.criterion = StopCriterion::exact;
    if (n == 0) {
      // Every mode was tried in double precision, but a mode's scalar normal root can lie below
      // the smallest double (p within 0.01 of 1: |z| ~ (a D/k)^(1/(p-1)) = 1e-1000) and be
      // missed, while z = 0 to rounding is an answer double precision can hold: semismooth Newton
      // and then the splitting get one try each before "no solution" is said.
      o.status = SolverStatus::no_solution;
      record(SolverMethod::mode_enumeration, AttemptStart::none, o);
      if (automatic) {
        auto take = [&](const Rows<N, C>& found, MethodOutcome o_found, SolverMethod m,
                        const char* message) {
          P = found;
          o_found.message = message;
          finish(o_found, m);
          out.unique = false;
          return true;
        };
        Rows<N, C> PN = decoupled_guess(rows, P);
        auto newton = semismooth_newton(rows, PN, opt);
        if (newton.status == SolverStatus::converged)
          final_row_sweep(rows, PN, opt.tolerance * cs.v_scale, newton);
        record(SolverMethod::semismooth_newton, AttemptStart::decoupled_guess, newton);
        if (newton.status == SolverStatus::converged)
          return take(PN, newton, SolverMethod::semismooth_newton,
                      "one contact with Coulomb: no mode resolved in double precision (a root "
                      "below its range), semismooth Newton converged");
        Rows<N, C> PS = Rows<N, C>::Zero(cs.rows());
        const auto split = proximal_iterations(rows, PS, opt);
        record(SolverMethod::proximal, AttemptStart::zero, split);
        if (split.status == SolverStatus::converged)
          return take(PS, split, SolverMethod::proximal,
                      "one contact with Coulomb: no mode resolved in double precision (a root "
                      "below its range), the proximal splitting converged");
      }
      o.message = "Frémond + Coulomb has no solution for these data (mu|G_NT| > G_NN)";
      finish(o, SolverMethod::mode_enumeration);
      out.unique = false;
      return true;
    }
    // Several solutions: the one that dissipates most (the least T_E). T_E − T_A = P·z (eq. 9) is
    // known only to |P| times the rounding of z = D_A + GP/2, so energies that overlap within
    // their rounding are a tie, and a tie goes to the better resolved answer.
    int best = 0;
    double best_e = std::numeric_limits<double>::infinity(), best_u = 0.0;
    for (int s = 0; s < n; ++s) {
      const double PN = sols[s].PN, PT = sols[s].PT;
      const double zN = cs.D_A(0) + 0.5 * (cs.G(0, 0) * PN + cs.G(0, 1) * PT);
      const double zT = cs.D_A(1) + 0.5 * (cs.G(1, 0) * PN + cs.G(1, 1) * PT);
      const double e = PN * zN + PT * zT;  // T_E − T_A, eq. 9
      const double dz = std::fabs(cs.D_A(0)) + std::fabs(cs.D_A(1)) +
                        0.5 * (std::fabs(cs.G(0, 0) * PN) +
                               2 * std::fabs(cs.G(0, 1)) * (std::fabs(PN) + std::fabs(PT)) +
                               std::fabs(cs.G(1, 1) * PT));
      const double u = 8 * kEps * (std::fabs(PN) + std::fabs(PT)) * dz;
      const bool clearly_better = e + u < best_e - best_u;
      const bool tie = !clearly_better && !(e - u > best_e + best_u);
      if (s == 0 || clearly_better || (tie && u < best_u)) {
        best_e = e;
        best_u = u;
        best = s;
      }
    }
    P(0) = sols[best].PN;
    P(1) = sols[best].PT;
    o.status = SolverStatus::converged;
    o.message = n == 1 ? "one contact with Coulomb: every mode tried, one solution"
                       : "one contact with Coulomb: several solutions; the most dissipative one";
    out.solutions_found = n;
    out.unique = (n == 1) && exhaustive;
    if (!std::isnan(sols[best].accepted_residual)) {
      o.residual = sols[best].accepted_residual;  // keep_resolved's test, on the same P
      o.residual_is_plain = true;
    } else {
      Rows<N, C> zb, R;
      o.residual = rows.residual(P, zb, R);
      check_exact(rows, P, opt, o);
    }
    record(SolverMethod::mode_enumeration, AttemptStart::none, o);
    finish(o, SolverMethod::mode_enumeration);
    if (n == 1 && exhaustive) out.unique = percussion_unique(rows, P, z, out);
    return true;
  }

  // With P_T = 0 the normal row alone is one prox; it is the answer when 0 ∈ ∂φ_T(z_T).
  bool dead_zone_prox() {
    const double zN = rows.prox(0, cs.D_A(0), 0.0);
    const double PN = 2.0 * (zN - cs.D_A(0)) / cs.G(0, 0);
    const double zT = cs.D_A(1) + 0.5 * cs.G(1, 0) * PN;
    if (!law.tangential_potential[rows.contact(1)].subdifferential(zT).contains(0.0)) return false;
    P(0) = PN;
    P(1) = 0.0;
    MethodOutcome o;
    o.status = SolverStatus::converged;
    o.criterion = StopCriterion::exact;
    o.message = "one contact inside the tangential dead zone: one exact prox";
    return exact_prox_answers(o);
  }

  bool coulomb_modes_by_name() {
    const Rows<N, C> start = decoupled_guess(rows, P);
    MethodOutcome om;
    if (enumerate_coulomb_modes(rows, start, P, opt, om)) {
      final_row_sweep(rows, P, opt.tolerance * cs.v_scale, om);
    } else {
      P = start;
      om.status = SolverStatus::stalled;
      om.criterion = StopCriterion::step;
      om.message =
          "Coulomb's tangential modes enumerated: no mode's answer satisfies the law (the "
          "decoupled guess is returned)";
    }
    record(SolverMethod::mode_enumeration, AttemptStart::decoupled_guess, om);
    finish(om, SolverMethod::mode_enumeration);
    return true;
  }

  // Newton from `start`: true, with the answer written, when it converges.
  bool newton_answers(Rows<N, C> start, AttemptStart from, const char* message = nullptr) {
    auto on = semismooth_newton(rows, start, opt);
    if (on.status == SolverStatus::converged) {
      P = start;
      final_row_sweep(rows, P, opt.tolerance * cs.v_scale, on);
    }
    record(SolverMethod::semismooth_newton, from, on);
    if (on.status != SolverStatus::converged) return false;
    finish(on, SolverMethod::semismooth_newton);
    if (message) out.solver.message = message;
    return true;
  }

  // Newton in velocity space (fremond_velocity_newton.cpp) from the decoupled guess; its end,
  // where it ran and failed, is kept as a start for contact space's Newton.
  bool velocity_newton() {
    PV = P0;
    velocity_ran = true;
    auto ov = velocity_space_newton(pb, rows, PV, opt);
    if (ov.status == SolverStatus::converged)
      final_row_sweep(rows, PV, opt.tolerance * cs.v_scale, ov);
    record(SolverMethod::semismooth_newton, AttemptStart::decoupled_guess, ov);
    if (ov.status == SolverStatus::converged) {
      P = PV;
      finish(ov, SolverMethod::semismooth_newton);
      return true;
    }
    have_velocity_end = PV.allFinite();
    return false;
  }

  // More than twice as many rows as degrees of freedom (and no Coulomb): velocity space's
  // Hessian stays positive definite where contact space's J is singular up to a small diagonal
  // (the plate flat on 16 and 32 contacts under p = 3: 68 µs and 5.1 ms → 12 µs and 21 µs). With
  // fewer rows contact space's Newton is the faster. It also makes the decoupled guess.
  bool velocity_newton_first() {
    P0 = decoupled_guess(rows, P);  // each row as if alone
    return velocity_space && cs.rows() > 2 * cs.dofs && velocity_newton();
  }

  bool contact_newton() {
    P = P0;
    auto o = semismooth_newton(rows, P, opt);
    if (o.status == SolverStatus::converged)
      final_row_sweep(rows, P, opt.tolerance * cs.v_scale, o);
    record(SolverMethod::semismooth_newton, AttemptStart::decoupled_guess, o);
    if (o.status != SolverStatus::converged && automatic) return false;
    finish(o, SolverMethod::semismooth_newton);
    return true;
  }

  // The law is quasi-variational with Coulomb: ‖R‖² has stationary points that are no solution,
  // which Newton from the decoupled guess can end at while Newton from zero converges.
  bool newton_from_zero() {
    return newton_answers(Rows<N, C>::Zero(cs.rows()), AttemptStart::zero);
  }

  bool coulomb_modes() {
    MethodOutcome om;
    const bool found = enumerate_coulomb_modes(rows, P0, P, opt, om);
    if (found) final_row_sweep(rows, P, opt.tolerance * cs.v_scale, om);
    if (om.status != SolverStatus::not_run)
      record(SolverMethod::mode_enumeration, AttemptStart::decoupled_guess, om);
    if (!found) return false;
    finish(om, SolverMethod::mode_enumeration);
    return true;
  }

  bool splitting() {
    // After Newton's stages, the splitting goes on from Newton's last iterate where its weighted
    // residual is below the guess's: every order of magnitude Newton gained is sweeps saved.
    if (P0.size() == cs.rows()) {
      Rows<N, C> zn, R;
      const double from_newton = rows.residual(P, zn, R);
      const bool newton_nearer =
          std::isfinite(from_newton) && from_newton < rows.residual(P0, zn, R);
      if (!newton_nearer) P = P0;
      split_start = newton_nearer ? AttemptStart::newton_end : AttemptStart::decoupled_guess;
    }
    const bool from_zero = P.isZero(0.0);
    if (from_zero) split_start = AttemptStart::zero;
    auto o = proximal_iterations(rows, P, opt);
    record(SolverMethod::proximal, split_start, o);
    // Where the splitting ends depends on where it starts (with Coulomb the law is
    // quasi-variational; without, it can stop on stagnation): once more from zero, on failure.
    if (automatic && o.status != SolverStatus::converged && !from_zero) {
      const Rows<N, C> first_end = P;
      P.setZero();
      const auto again = proximal_iterations(rows, P, opt);
      record(SolverMethod::proximal, AttemptStart::zero, again);
      if (again.status == SolverStatus::converged)
        o = again;
      else
        P = first_end;
    }
    if (o.status == SolverStatus::converged || !automatic) {
      finish(o, SolverMethod::proximal);
      return true;
    }
    split_end = o;
    have_split_end = true;
    return false;
  }

  // The splitting stops on stagnation near answers that Newton from the guess or from zero does
  // not reach; Newton from there converges in a few steps.
  bool newton_from_splitting() { return newton_answers(P, AttemptStart::splitting_end); }

  bool nlopt() {
    P_split = P;
    const AttemptStart from = have_split_end ? AttemptStart::splitting_end : AttemptStart::zero;
    nlopt_end = nlopt_velocity_space(pb, rows, P, opt);
    record(SolverMethod::nlopt, from, nlopt_end);
    return false;
  }

  // NLopt stops at its own tolerance (nlopt_tolerance), far above the law's; Newton from its end
  // polishes it.
  bool newton_from_nlopt() {
    return newton_answers(P, AttemptStart::nlopt_end,
                          "semismooth Newton converged from NLopt's answer");
  }

  bool newton_from_velocity_newton() {
    return newton_answers(PV, AttemptStart::velocity_newton_end,
                          "semismooth Newton converged from velocity-space Newton's answer");
  }

  // Normal rows that the tangential ones do not move (G_NT = 0) are a problem of their own, and
  // ‖R‖² over both mixes their scales: solved alone by the whole chain, then Newton on all rows
  // from their answer with the tangential rows' decoupled guess.
  bool normal_rows_first() {
    ContactSpaceT<N, C> normal_space;
    build_contact_space(pb, false, normal_space, held_by(cs));
    ImpactResultT<N, C> normal_answer;
    FremondChain<N, C>(pb, normal_space, law, opt, normal_answer).run();
    out.solver.record(normal_answer.solver.method, AttemptStart::none, normal_answer.solver.status,
                      normal_answer.solver.residual);
    if (normal_answer.solver.status != SolverStatus::converged) return false;
    Rows<N, C> start = P0;
    for (int k = 0; k < cs.active; ++k) start(k) = normal_answer.P_N(cs.index(k));
    return newton_answers(start, AttemptStart::normal_rows,
                          "semismooth Newton converged from the normal rows' own answer (G_NT = "
                          "0: the tangential rows do not move them)");
  }

  // Every method failed: the answer is the nearest to the law, not the last (NLopt, stopped by
  // its budget, can end far from where the splitting left off).
  bool nearest_failure() {
    const double r_nlopt = P.allFinite() ? rows.plain_residual(P) : 0.0;
    const double r_split = rows.plain_residual(P_split);
    if (r_nlopt <= r_split || !std::isfinite(r_split)) return false;
    P = P_split;
    split_end.message =
        "every method failed; the proximal splitting's end is returned, nearer to the law than "
        "NLopt's";
    finish(split_end, SolverMethod::proximal);
    return true;
  }

  bool nlopt_answer() {
    finish(nlopt_end, SolverMethod::nlopt);
    return true;
  }

  // ---- writing the answer ---------------------------------------------------------------------

  // The outcome `o` of method `m` into the result, then the repairs an answer may need, each
  // named: refine_at_rounding, none_if_overflow, claim_uniqueness, settle_coulomb_mode. `o` by
  // reference and not copied (see check_exact).
  void finish(const MethodOutcome& o, SolverMethod m) {
    out.solver.fallbacks = std::max(0, out.solver.attempt_count - 1);
    write_outcome(
        o, cs.rows() && P.allFinite() && !o.residual_is_plain ? rows.plain_residual(P) : o.residual,
        m, cs.v_scale, opt, out);  // the law's residual
    refine_at_rounding(o, m);
    write_velocities();
    none_if_overflow();
    claim_uniqueness();
    settle_coulomb_mode(o, m);
  }

  // An answer accepted at its rows' rounding floors, refined in velocity space where every row has
  // a prox: the floors then cost nothing.
  void refine_at_rounding(const MethodOutcome& o, SolverMethod m) {
    if (out.solver.status == SolverStatus::converged &&
        out.solver.criterion == StopCriterion::rounding && rows.all_prox &&
        refine_in_velocity_space(pb, rows, P, opt.tolerance * cs.v_scale))
      write_outcome(o, rows.plain_residual(P), m, cs.v_scale, opt, out);
  }

  void write_velocities() {
    scatter_solution(pb, cs, P, out);
    rows.mean_velocity(P, z);
    split_reaction(rows, P, z, out);
  }

  // No NaN or infinity leaves the library, whatever the status: percussions so large that the
  // velocities, the energy or the reaction (φ_N' of a far iterate) overflow are no answer; none
  // is returned (q̇_E = q̇_A), and the message says so.
  void none_if_overflow() {
    if (out.qdot_E.allFinite() && std::isfinite(out.energy_change) && P.allFinite() &&
        out.P_N_reaction.allFinite())
      return;
    P.setZero();
    write_velocities();
    if (out.solver.status == SolverStatus::converged) out.solver.status = SolverStatus::failed;
    out.solver.message =
        "the method's answer overflows (velocities, energy or reaction not finite): no "
        "percussion is returned";
    if (cs.rows()) out.solver.residual = rows.plain_residual(P) / cs.v_scale;
  }

  // With Coulomb on several contacts the law is quasi-variational: other velocities may solve it
  // too, and nothing here looks for them, so uniqueness is not claimed (as for a classical law
  // whose modes were not enumerated).
  void claim_uniqueness() {
    if (out.solver.status == SolverStatus::converged && out.solutions_found == 0)
      out.unique = !(rows.coulomb && cs.active >= 2) && percussion_unique(rows, P, z, out);
  }

  // Frémond + Coulomb on several contacts: where rounding, not the law, would fix how dependent
  // contacts share their percussions or which way a contact slides, the contact mode is solved
  // with its exact conditions; where no mode gives an answer, the answer is kept and called
  // stalled. The limit, 1e-6 of the velocity scale, is the cap of every row's rounding floor
  // (row_rounding_floor): an answer not resolved to that is none in double precision.
  void settle_coulomb_mode(const MethodOutcome& o, SolverMethod m) {
    if (out.solver.status != SolverStatus::converged || !rows.coulomb || cs.active < 2) return;
    auto stall = [&](const char* message) {  // the answer is kept, and said to be no more
      out.solver.status = SolverStatus::stalled;
      out.solver.criterion = StopCriterion::rounding;
      out.solver.message = message;
      out.unique = false;
    };
    if (reactions_on_normals_parallel_to_rounding(rows, out)) {
      stall(
          "Frémond + Coulomb: two contacts held by their reactions have normals parallel to "
          "rounding but not exactly; how they share their percussion is fixed by terms of G below "
          "double precision, and Coulomb's bounds, so the tangential answer, depend on it; the "
          "answer passes the law's test but may be far from the exact one");
      return;
    }
    const double limit = 1e-6 * cs.v_scale;
    MatT<N, C> Wf;
    int free_rows = 0;
    bool bound_sensitive = false;
    free_rows_moving_bounds(rows, P, z, out, limit, Wf, free_rows, bound_sensitive);
    // Whatever the normal rows, the tangential mode may be rounding's: a sliding contact's z_T
    // below the rounding of tangential percussions that cancel, or both contacts sticking where
    // the exact answer slides one. A reversal that moves velocities by less than 1e-9 of their
    // scale is not looked for: the answer holds to that either way.
    const bool sliding_undetermined = sliding_at_rounding(rows, P, z, 1e-9 * cs.v_scale) ||
                                      sticking_tied_below_rounding(rows, P, z);
    if (free_rows == 0 && !sliding_undetermined) return;
    const bool normals_dependent =
        free_rows > 0 && coulomb_bounds_undetermined<N, C>(Wf, free_rows, bound_sensitive);
    if (!normals_dependent && !sliding_undetermined &&
        !coulomb_mode_undetermined(rows, P, z, Wf, free_rows))
      return;
    auto take_exact = [&](const char* message) {
      write_outcome(o, rows.plain_residual(P), m, cs.v_scale, opt, out);
      out.solver.message = message;
      write_velocities();
      out.unique = false;
    };
    // The split first (normals alone dependent); its answer may still leave the mode to rounding,
    // through sticking tangents or a sliding z_T, and is checked for that.
    if (normals_dependent && split_normal_percussions(rows, P, out, opt)) {
      take_exact(
          "converged, with the normal percussions of contacts whose normals are dependent, which "
          "their rounded velocities do not determine, split by their exact condition");
      free_rows_moving_bounds(rows, P, z, out, limit, Wf, free_rows, bound_sensitive);
      if (!coulomb_mode_undetermined(rows, P, z, Wf, free_rows)) return;
    }
    if (solve_in_coulomb_mode(pb, rows, P, out.P_N_reaction, opt)) {
      take_exact(
          sliding_undetermined && free_rows == 0
              ? "converged, with the contact mode (which contacts stick, which way the others "
                "slide) fixed by its exact conditions: tangents dependent on the other rows "
                "leave mean tangential velocities below the rounding of the percussions"
              : "converged, with the percussions of contacts that are free in double "
                "precision (normal laws steep at z_N = 0) solved in their contact mode, "
                "with the exact conditions their dependent columns and their velocities "
                "below rounding leave");
      return;
    }
    stall(sliding_undetermined && free_rows == 0
              ? "Frémond + Coulomb: tangents dependent on the other rows leave mean tangential "
                "velocities below the rounding of the percussions, so which contacts stick and "
                "which way the others slide is rounding's, and no contact mode solved with its "
                "exact conditions gave an answer; the answer passes the law's test but may be far "
                "from the exact one"
              : "Frémond + Coulomb: a normal law steep at z_N = 0 holds mean normal velocities at "
                "rounding level, which leaves the percussions of contacts with dependent columns "
                "of W (with each other or with sticking contacts' tangents), or the direction of a "
                "contact sliding at rounding speed, to rounding, and no contact mode solved with "
                "their exact conditions gave an answer; the answer passes the law's test but may "
                "be far from the exact one");
  }
};

template <int N, int C>
void solve_fremond_chain(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                         const FremondLaw& law, const SolverOptions& opt,
                         ImpactResultT<N, C>& out) {
  FremondChain<N, C>(pb, cs, law, opt, out).run();
}

}  // namespace

namespace {
/// Where every method failed on one degree of freedom without Coulomb, the exact scalar solve of
/// the velocity-space problem (solve_one_dof) replaces the failed answer: its velocities are exact
/// to rounding by construction. Its status is the law's own test on its percussions, as for every
/// method: converged where they pass it; else still stalled, with exact velocities, where
/// percussions many orders above the velocities do not reproduce them in double precision
/// (z = D_A + GP/2 rounded to ε|G||P|).
template <int N, int C>
void solve_one_dof_instead(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                           const FremondLaw& law, const SolverOptions& opt,
                           ImpactResultT<N, C>& out) {
  if (cs.dofs != 1 || cs.rows() == 0) return;
  FremondRowsT<N, C> rows;
  rows.init(cs, law);
  Rows<N, C> P, z(cs.rows()), R;
  double u = 0.0;
  if (!solve_one_dof(pb, rows, P, u)) return;
  out.qdot_E.resize(1);
  out.qdot_E(0) = pb.qdot_A(0) + 2.0 * u;
  scatter_at_velocities(pb, cs, P, out);
  for (int j = 0; j < cs.rows(); ++j) z(j) = cs.D_A(j) + cs.W(0, j) * u;  // from the velocity
  split_reaction(rows, P, z, out);
  MethodOutcome o;
  Rows<N, C> zp;
  const double target = opt.tolerance * cs.v_scale;
  const bool passes = std::isfinite(rows.residual(P, zp, R)) && rows.converged(P, R, target);
  o.status = passes ? SolverStatus::converged : SolverStatus::stalled;
  o.criterion = passes ? StopCriterion::exact : StopCriterion::rounding;
  o.residual = rows.plain_residual(P);
  o.message =
      passes ? "every contact-space method failed; one degree of freedom: the velocity-space "
               "problem (docs/laws.md) solved exactly by bisection on its subdifferential"
             : "one degree of freedom: the velocity is exact (the velocity-space problem solved "
               "by bisection on its subdifferential), but its percussions, far above the "
               "velocities, do not reproduce it in double precision within the law's test";
  write_outcome(o, SolverMethod::scalar_newton, cs.v_scale, opt, out);
  out.solver.record(SolverMethod::scalar_newton, AttemptStart::none, o.status, out.solver.residual);
  out.solver.fallbacks = out.solver.attempt_count - 1;
  out.solutions_found = 0;
  out.unique = passes && percussion_unique(rows, P, z, out);
}
}  // namespace

namespace {
/// Where the normal rows alone have no solution (their obstacles close in on the body), no method
/// could have found one: the state before the impact, as the classical laws report it, with the
/// proof's verdict.
template <int N, int C>
void report_no_solution(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                        const FremondLaw& law, ImpactResultT<N, C>& out) {
  typename ContactSpaceT<N, C>::Rows none = ContactSpaceT<N, C>::Rows::Zero(cs.rows());
  scatter_solution(pb, cs, none, out);
  out.P_N_reaction.setZero(cs.contacts);
  out.unique = false;
  out.solutions_found = 0;
  out.solver.status = SolverStatus::no_solution;
  out.solver.method = SolverMethod::lemke;  // what decided it
  out.solver.criterion = StopCriterion::exact;
  out.solver.residual = fremond_residual(pb, law, out);  // of the state returned
  out.solver.record(SolverMethod::lemke, AttemptStart::none, SolverStatus::no_solution,
                    out.solver.residual);
  out.solver.fallbacks = out.solver.attempt_count - 1;
  out.solver.message =
      "no solution: no velocity after the impact keeps every contact that takes part from "
      "penetrating (D_NE >= 0 on all of them is infeasible: their obstacles close in on the "
      "body); the state before the impact (no percussion) is returned";
}
}  // namespace

template <int N, int C>
void solve_fremond(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                   const FremondLaw& law, const SolverOptions& opt, ImpactResultT<N, C>& out) {
  solve_fremond_chain(pb, cs, law, opt, out);
  // The repairs where every method failed, only on that path, so that a solve that converges pays
  // nothing for them: no answer exists (proved on the normal rows), or one degree of freedom
  // solved exactly in velocity space.
  const SolverStatus s = out.solver.status;
  if (s != SolverStatus::stalled && s != SolverStatus::failed && s != SolverStatus::max_iterations)
    return;
  if (normal_rows_infeasible(pb, held_by(cs)))
    report_no_solution(pb, cs, law, out);
  else
    solve_one_dof_instead(pb, cs, law, opt, out);
}

template <int N, int C>
std::vector<ImpactResultT<N, C>> solve_fremond_all(const ImpactProblemT<N, C>& pb,
                                                   const FremondLaw& law, const SolverOptions& opt,
                                                   HeldContacts held) {
  ContactSpaceT<N, C> cs;
  build_contact_space(pb, law.has_friction(), cs, held);
  FremondRowsT<N, C> rows;
  rows.init(cs, law);
  std::vector<ImpactResultT<N, C>> all;
  if (cs.active == 1 && rows.coulomb && rows.all_prox && !decoupled(cs)) {
    std::array<ContactSolution, 16> sols;
    bool exhaustive = true;
    const int n = keep_resolved(rows, sols, one_contact_coulomb_modes(rows, sols, &exhaustive), opt,
                                &exhaustive);
    for (int s = 0; s < n; ++s) {
      ImpactResultT<N, C> r;
      Rows<N, C> P(2), z, R;
      P << sols[s].PN, sols[s].PT;
      MethodOutcome o;
      o.status = SolverStatus::converged;
      o.criterion = StopCriterion::exact;
      o.message = "one contact with Coulomb: every mode tried";
      o.residual = rows.residual(P, z, R);
      check_exact(rows, P, opt, o);
      o.residual = rows.plain_residual(P);
      write_outcome(o, SolverMethod::mode_enumeration, cs.v_scale, opt, r);
      scatter_solution(pb, cs, P, r);
      rows.mean_velocity(P, z);
      split_reaction(rows, P, z, r);
      r.unique = n == 1 && exhaustive;
      r.solutions_found = n;
      all.push_back(std::move(r));
    }
    if (n > 0) return all;
    // None found: solve_fremond decides between "no solution" and what semismooth Newton finds.
  }
  ImpactResultT<N, C> r;
  solve_fremond(pb, cs, law, opt, r);
  if (r.solver.status == SolverStatus::no_solution) return {};
  r.solutions_found = 1;
  all.push_back(std::move(r));
  return all;
}

#define FREMOND_INSTANTIATE(N, C)                                                             \
  template void solve_fremond(const ImpactProblemT<N, C>&, const ContactSpaceT<N, C>&,        \
                              const FremondLaw&, const SolverOptions&, ImpactResultT<N, C>&); \
  template std::vector<ImpactResultT<N, C>> solve_fremond_all(                                \
      const ImpactProblemT<N, C>&, const FremondLaw&, const SolverOptions&, HeldContacts);
FREMOND_INSTANTIATE(Dynamic, Dynamic)
FREMOND_INSTANTIATE(kSmallDofs, kSmallContacts)
#undef FREMOND_INSTANTIATE

}  // namespace fremond::detail
