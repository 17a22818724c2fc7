#pragma once
// The law level of the classical impact laws: each law as one phase (Newton) or two (Poisson's
// compression, then expansion) of detail/classical_phase.hpp, each phase by its cheapest exact
// method, with every solution listed where the enumeration can list them. Header-only so that the
// benchmarks time exactly what solve_impact runs; the results are filled in classical.cpp.
#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_space/contact_space.hpp"
#include "core/detail/accurate_dot.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/solver_status.hpp"
#include "solvers/detail/classical_phase.hpp"

namespace fremond::detail::classical {

// The costlier of two methods, for a law whose phases were solved by different ones.
inline SolverMethod costlier(SolverMethod a, SolverMethod b) {
  auto rank = [](SolverMethod m) {
    switch (m) {
      case SolverMethod::closed_form:
        return 1;
      case SolverMethod::lemke:
        return 2;
      case SolverMethod::mode_enumeration:
        return 3;
      default:
        return 0;
    }
  };
  return rank(a) >= rank(b) ? a : b;
}

/// What solving one phase found.
template <int C>
struct PhaseOutcome {
  using Rows = typename Phase<C>::Rows;
  FixedList<Rows, kMaxSolutions> u;  ///< the first one is the primary method's answer
  SolverMethod primary = SolverMethod::closed_form;  ///< the method of u[0]
  SolverMethod others = SolverMethod::closed_form;   ///< the method of the rest of the list
  int pivots = 0;
  int fallbacks = 0;
  bool exhaustive = false;        ///< u holds every solution (up to equal velocities)
  bool percussion_unique = true;  ///< false when a minimum-norm choice was made
  bool continuum = false;         ///< a singular mode may hold a continuum of velocities
  bool unsupported = false;       ///< the method forced does not apply to this phase
  bool extended = false;          ///< u was found by the modes in extended precision (see below)
};

/// G once per law: its factor (the eq. 6 guess) and, when it is singular, null(G) (the
/// minimum-norm choice), computed on first use: the semidefinite guess's answer needs none
/// (GuessNorm), and null(G) was half the law's work on the flat bar.
///
/// Two rows (two frictionless contacts: the flat bar) are factored as L D Lᵀ with the pivots'
/// reciprocals, two divisions in all; the Cholesky factor there took two square roots and five
/// divisions in one dependency chain, 17.6 ns of the flat bar's 2×2 guess against 106 ns for
/// Siconos's Lemke on it. Both are backward stable on a symmetric positive definite G; the
/// regularity test is the same (pivots within 1e-14 of each other: the Cholesky diagonal's
/// 1e-7, squared).
template <int C>
struct Factored {
  using RowMat = typename Phase<C>::RowMat;
  using Rows = typename Phase<C>::Rows;
  CholeskyT<RowMat::MaxRowsAtCompileTime> llt;
  bool regular = false;

  /// `dofs`: the number of degrees of freedom, a bound on G's rank (G = Wᵀ M⁻¹ W).
  void compute(const RowMat& G, int dofs) {
    regular = false;
    null_known = false;
    null_.resize(G.rows(), 0);
    two_ = false;
    if (G.rows() > dofs) return;  // singular for sure: skip the factor, whose pivots are rounding
    if (G.rows() == 2) {
      two_ = true;
      const double d1 = G(0, 0);
      if (!(d1 > 0.0)) return;  // also NaN: the Cholesky factor's refusal
      inv_d1_ = 1.0 / d1;
      l_ = G(1, 0) * inv_d1_;
      const double d2 = G(1, 1) - l_ * G(1, 0);
      if (!(d2 > 0.0)) return;
      inv_d2_ = 1.0 / d2;
      regular = d2 > 1e-14 * d1 && d1 > 1e-14 * d2;
      return;
    }
    llt.compute(G);
    if (llt.info() == Eigen::Success && G.rows() > 0) {
      const auto d = llt.matrixLLT().diagonal();
      regular = d.minCoeff() > 1e-7 * d.maxCoeff();
    }
  }

  /// G⁻¹ b, where compute() found G regular.
  template <class B>
  Rows solve(const B& b) const {
    if (!two_) return llt.solve(b);
    Rows x(2);
    x(1) = (b(1) - l_ * b(0)) * inv_d2_;
    x(0) = b(0) * inv_d1_ - l_ * x(1);
    return x;
  }

  /// An orthonormal basis of null(G) (the G given to compute), no columns when G is regular. A
  /// small pivot of the factor is only a hint: the eigenvalues decide what null(G) is.
  const RowMat& kernel(const RowMat& G) {
    if (!null_known && !regular) null_ = null_space<C>(G);
    null_known = true;
    return null_;
  }

 private:
  bool null_known = false;
  RowMat null_;
  bool two_ = false;  // two rows: the L D Lᵀ scalars below, not llt
  double inv_d1_ = 0.0, l_ = 0.0, inv_d2_ = 0.0;
};

/// The eq. 6 guess on several contacts, every contact closed (and sticking): with G's factor where
/// G is regular, else in its semidefinite form (a line of solutions); on two frictionless contacts
/// with a regular G, every other mode too (one_of_two_closed). True when it solves the phase.
/// `norm`, when given: see GuessNorm (a regular G has no choice to make: its default).
template <int C>
bool closed_guess(const Phase<C>& ph, const Tolerances& tol, const Factored<C>& fg,
                  typename Phase<C>::Rows& u, GuessNorm* norm = nullptr) {
  if (norm) *norm = GuessNorm{};
  if (fg.regular) return all_closed_guess(ph, tol, fg, true, u) || one_of_two_closed(ph, u);
  // On a singular G only with friction and without a fixed bound b0 (Newton's phase, Poisson's
  // compression). Without friction Lemke's LCP is symmetric semidefinite and cheap; from Poisson's
  // expansion (b0 = μ e P_NC) on an ill-conditioned M the guess's answer, within its own test, can
  // leave the law stalled where Lemke's and the enumeration's converge.
  return !frictionless(ph) && ph.b0.isZero(0.0) && closed_sticking_semidefinite(ph, tol, u, norm);
}

/// The exact method of a phase on several contacts that finds one solution: the eq. 6 guess, then
/// Lemke, the order solve_phase's automatic choice takes before any listing of solutions (there
/// written out, beside the methods forced by name); the benchmarks time this as the kernel.
/// Returns the method that answered (Lemke also when it found none: `solved` false).
template <int C>
SolverMethod exact_phase(const Phase<C>& ph, const Tolerances& tol, const Factored<C>& fg,
                         typename Phase<C>::Rows& u, int& pivots, bool& solved) {
  if (closed_guess(ph, tol, fg, u)) {
    solved = true;
    return SolverMethod::closed_form;
  }
  solved = lemke_phase(ph, LemkeOptions{}, u, pivots) == LcpStatus::solved;
  return SolverMethod::lemke;
}

/// `force`: automatic takes the cheapest exact method, with the enumeration as fallback (where
/// Lemke finds no answer, up to kMaxEnumerated contacts) and to list every solution (up to
/// `list_up_to` contacts); closed_form, lemke or mode_enumeration use that method alone
/// (unsupported where it does not apply: no closed form, or more contacts than the enumeration
/// takes).
template <int C>
void solve_phase(const Phase<C>& ph, const Tolerances& tol, int list_up_to, Factored<C>& fg,
                 const typename Phase<C>::Rows& shift, PhaseOutcome<C>& out,
                 SolverMethod force = SolverMethod::automatic) {
  using Rows = typename Phase<C>::Rows;
  const int r = ph.rows();
  Rows u(r);
  GuessNorm guess_norm;  // of the eq. 6 guess's answer, u[0] where it answered
  bool enumerate = false;
  const bool automatic = force == SolverMethod::automatic;
  if (force == SolverMethod::mode_enumeration) {
    if (ph.a > kMaxEnumerated) {
      out.unsupported = true;
      return;
    }
    enumerate = true;
    out.primary = out.others = SolverMethod::mode_enumeration;
  } else if (ph.a == 1 && force != SolverMethod::lemke) {
    const bool f = ph.friction;
    const OneContact oc =
        one_contact(ph.G(0, 0), f ? ph.G(0, 1) : 0.0, f ? ph.G(1, 1) : 0.0, ph.q(0),
                    f ? ph.q(1) : 0.0, f ? ph.mu(0) : 0.0, f ? ph.b0(0) : 0.0, f, tol);
    // No answer by the closed forms is checked by the enumeration where automatic chooses (see
    // solve_law_one_contact: rounding can refuse every closed form of an ill-conditioned G).
    if (!oc.degenerate && (oc.count > 0 || !automatic)) {
      // count ≤ 4 by construction; said here too, or GCC 12 warns of a read past x[3].
      for (int k = 0; k < std::min(oc.count, 4); ++k) {
        u(0) = oc.x[k];
        if (f) u(1) = oc.t[k];
        out.u.push(u);
      }
      out.primary = out.others = SolverMethod::closed_form;
      out.exhaustive = true;
      return;  // one contact with a regular 2×2 G: the percussion is fixed by the velocity
    }
    if (!automatic) {  // closed_form: a singular 2×2 G has none
      out.unsupported = true;
      return;
    }
    enumerate = true;  // singular 2×2 G, or no closed form held: only the enumeration is sure
    out.primary = out.others = SolverMethod::mode_enumeration;
  } else {
    const bool friction = !frictionless(ph);
    bool have = false;
    if (force != SolverMethod::lemke && closed_guess(ph, tol, fg, u, &guess_norm)) {
      have = true;
      out.primary = SolverMethod::closed_form;
    } else if (force == SolverMethod::closed_form) {
      out.unsupported = true;
      return;
    } else {
      int pivots = 0;
      have = lemke_phase(ph, LemkeOptions{}, u, pivots) == LcpStatus::solved;
      out.pivots += pivots;
      out.primary = SolverMethod::lemke;
      if (have)
        for (int i = 0; i < ph.a; ++i) u(i) = std::max(0.0, u(i));
    }
    if (!friction) {
      // Symmetric positive semidefinite LCP: the velocities are unique, and a ray proves that
      // there is no solution in exact arithmetic (solve_law checks that rounding agrees:
      // ray_is_proof). Where rounding made the ray (cond(G) = 7e10: Lemke stopped after two
      // pivots where both contacts close), the modes still have the answer, to rounding.
      if (have) out.u.push(u);
      out.exhaustive = true;
      if (!have && automatic && ph.a <= kMaxEnumerated) {
        enumerate = true;
        out.primary = out.others = SolverMethod::mode_enumeration;
        out.fallbacks = 1;
      }
    } else if (automatic && (ph.a <= list_up_to || (!have && ph.a <= kMaxEnumerated))) {
      enumerate = true;
      out.others = SolverMethod::mode_enumeration;
      if (have) {
        out.u.push(u);
      } else {
        out.primary = SolverMethod::mode_enumeration;
        out.fallbacks = 1;
      }
    } else if (have) {
      out.u.push(u);
    }
  }
  if (enumerate) {
    FixedList<Rows, kMaxSolutions> found;
    enumerate_modes(ph, tol, found, out.continuum);
    for (int k = 0; k < found.size; ++k) {
      const Rows v = ph.velocity(found[k]);
      bool seen = false;
      for (int j = 0; j < out.u.size && !seen; ++j)
        seen = (ph.velocity(out.u[j]) - v).cwiseAbs().maxCoeff() <= 16 * tol.v;
      if (!seen) out.u.push(found[k]);
    }
    out.exhaustive = !found.overflow && !out.u.overflow;
  }
  if (fg.regular) return;
  // The guess's answer is its own minimum-norm choice where GuessNorm says so; the shift (of
  // Poisson's expansion) must be zero for that, as the guess minimises ‖u‖.
  const bool guessed = out.primary == SolverMethod::closed_form && guess_norm.minimum &&
                       shift.isZero(0.0) && out.u.size > 0;
  for (int k = 0; k < out.u.size; ++k) {
    const bool unique = k == 0 && guessed
                            ? guess_norm.unique
                            : minimum_norm<C>(ph, tol, fg.kernel(ph.G), shift, out.u[k]);
    out.percussion_unique = unique && out.percussion_unique;
  }
}

template <int C>
struct LawSolution {
  using Rows = typename Phase<C>::Rows;
  Rows P;    ///< total percussion, active rows
  Rows P_C;  ///< Poisson: compression percussion
  double energy_change = 0.0;
  SolverMethod method = SolverMethod::closed_form;
};

/// Every solution found for a law, and how.
template <int C>
struct LawOutcome {
  // User-provided: a value-initialised aggregate (a chain's `{}`) is zeroed whole first, 24
  // solutions' rows, 540 instructions of a one-contact solve's 5,000.
  LawOutcome() {}  // NOLINT(modernize-use-equals-default)
  FixedList<LawSolution<C>, kMaxSolutions> solutions;
  SolverMethod method = SolverMethod::closed_form;  ///< the method of solutions[0]
  int pivots = 0;
  int fallbacks = 0;
  bool exhaustive = true;
  bool percussion_unique = true;
  bool compression_unique = true;  ///< Poisson: the compression percussion
  bool continuum = false;
  /// Frictionless: Lemke's method ended on a ray of G's LCP, yet a solution exists (see
  /// ray_is_proof): G lost its small eigenvalues to rounding. Then exhaustive is false.
  bool beyond_precision = false;
  bool unsupported = false;  ///< the method forced does not apply to a phase
  bool extended = false;     ///< a phase was decided in extended precision
  /// Newton's laws: the answer is a mode solved for its velocities, no mode in contact space having
  /// one (classical_velocity_mode.hpp, solve_modes_in_velocities).
  bool in_velocities = false;
  bool sweeps = false;  ///< found by the sweeps and the mode Newton (solvers/nsgs)

  void reset() {
    solutions.clear();
    method = SolverMethod::closed_form;
    pivots = fallbacks = 0;
    exhaustive = percussion_unique = compression_unique = true;
    continuum = beyond_precision = unsupported = extended = in_velocities = sweeps = false;
  }
};

/// Whether a ray of Lemke's method on a frictionless phase (q, G = WᵀM⁻¹W) proves that the phase
/// has no solution. In exact arithmetic it does: G is positive semidefinite, so the LCP has a
/// solution exactly when it is feasible, and by Farkas it is not exactly when some y ≥ 0 has
/// Gy = 0 and qᵀy < 0. As M⁻¹ is positive definite, Gy = 0 ⟺ Wy = 0: solvability depends on W
/// and q alone, and LCP(Dq, D WᵀW D), D = diag(1/|W_i|), has a solution exactly when the phase
/// has one. That LCP does not see M. When M is so ill-conditioned that G's small eigenvalues are
/// lost to rounding, G's LCP ends on a ray where this one is solved: a solution exists, out of
/// double precision's reach, and "no solution" would be a false claim.
/// A proof must also hold for every q within q's rounding `raise`: this LCP is solved with each
/// q_i raised by it (Poisson's expansion starts from the compression's velocities, known only to
/// about ε κ(M) Σ|G||P_C|: a body closed in on every side by fixed obstacles has qᵀy = 0 exactly,
/// and that rounding alone would make a ray of it).
template <int N, int C>
bool ray_is_proof(const ContactSpaceT<N, C>& cs, const Phase<C>& ph, double raise = 0.0) {
  const int a = ph.a;
  Phase<C> wp;
  wp.a = a;
  wp.friction = false;
  wp.G.resize(a, a);
  wp.q.resize(a);
  wp.mu.setZero(a);
  wp.b0.setZero(a);
  VecT<C> d(a);
  for (int i = 0; i < a; ++i) {
    const double norm = cs.W.col(i).norm();
    if (!std::isfinite(norm)) return true;  // G's LCP decides
    // A zero column is its own certificate when q_i < 0 (y = e_i), and no constraint otherwise:
    // left as it is, Lemke sees exactly that.
    d(i) = norm > 0.0 ? std::min(1.0 / norm, 0x1p1000) : 1.0;  // a subnormal norm: 1/norm = ∞
  }
  for (int i = 0; i < a; ++i) {
    wp.q(i) = d(i) * (ph.q(i) + raise);
    for (int j = 0; j <= i; ++j)
      wp.G(i, j) = wp.G(j, i) = d(i) * d(j) * cs.W.col(i).dot(cs.W.col(j));
  }
  typename Phase<C>::Rows u(a);
  int pivots = 0;
  return lemke_phase(wp, LemkeOptions{}, u, pivots) != LcpStatus::solved;
}

/// The extended precision of decide_in_extended_precision: the x87 format's 64-bit significand
/// where the platform has it (ε = 1.1e-19), else double-double would be needed and the decision
/// stays double's.
using Extended = long double;
inline constexpr bool kHaveExtended =
    std::numeric_limits<Extended>::digits > std::numeric_limits<double>::digits;

/// G = Wᵀ M⁻¹ W of the first r rows of `cs` in extended precision. M⁻¹W is solved by M's Cholesky
/// factor in extended precision and refined against residuals W − M X summed in twice double
/// precision (X split into two doubles, the first part by accurate_dot), which leaves X accurate
/// to the extended format whatever cond(M) below 1/ε_extended; G is then summed in that format.
/// (A Cholesky solve alone is accurate only to cond(M)·ε: with cond(M) = 1e12 that is 1e-7, far
/// above the small singular values of the modes it is for.) False when M's factor or G is not
/// usable.
template <int N, int C>
bool extended_delassus(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs, int r,
                       MatS<times(C, 2), times(C, 2), Extended>& G) {
  using X =
      Eigen::Matrix<Extended, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, N, times(C, 2)>;
  using Split = MatT<N, times(C, 2)>;
  const int n = static_cast<int>(pb.M.rows());
  const auto W = cs.W.leftCols(r);
  const Eigen::Matrix<Extended, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, N, N> Me =
      pb.M.template cast<Extended>();
  const Eigen::LLT<std::remove_const_t<decltype(Me)>> llt(Me);
  if (llt.info() != Eigen::Success) return false;
  X x = llt.solve(W.template cast<Extended>());
  X residual(n, r);
  Split hi(n, r), lo(n, r);
  constexpr Extended kEps = std::numeric_limits<Extended>::epsilon();
  for (int sweep = 0; sweep < 6 && x.allFinite(); ++sweep) {
    hi = x.template cast<double>();
    lo = (x - hi.template cast<Extended>()).template cast<double>();  // x = hi + lo exactly
    for (int c = 0; c < r; ++c)
      for (int i = 0; i < n; ++i)
        residual(i, c) =
            -(Extended(accurate_dot(pb.M.row(i), hi.col(c), -W(i, c))) +
              pb.M.row(i).template cast<Extended>().dot(lo.col(c).template cast<Extended>()));
    const X delta = llt.solve(residual);
    x += delta;
    if (!(delta.cwiseAbs().maxCoeff() > 4 * kEps * x.cwiseAbs().maxCoeff())) break;
  }
  G.resize(r, r);
  for (int j = 0; j < r; ++j)
    for (int k = 0; k <= j; ++k)
      G(j, k) = G(k, j) = Extended(0.5) * (W.col(j).template cast<Extended>().dot(x.col(k)) +
                                           W.col(k).template cast<Extended>().dot(x.col(j)));
  return G.allFinite();
}

/// A phase with friction whose contact modes, every one solved in double precision, gave no
/// answer, solved again by its modes with G in extended precision. Where M is ill-conditioned
/// (cond(M) from 4e8 to 1e12) a mode's equations can have singular values from 1e-15 to 1e-14 of
/// their largest: in double, below what rounding resolves (G is accurate to ε of its entries), so
/// the mode would be refused as singular and inconsistent, and the law say `no_solution` where the
/// exact modes have an answer (with percussions 1e13 times the velocities they make). In extended
/// precision those singular values stand 1e4 above rounding and the mode is decided. An answer
/// found so is known only to the precision of the data's double rounding, and is judged by the
/// law's residual like any other.
template <int N, int C>
void decide_in_extended_precision(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                                  const Phase<C>& ph, const Tolerances& tol, PhaseOutcome<C>& out) {
  if constexpr (kHaveExtended) {
    if (frictionless(ph) || out.u.size > 0 || !out.exhaustive || ph.a > kMaxEnumerated) return;
    Phase<C, Extended> ext;
    ext.a = ph.a;
    ext.friction = ph.friction;
    if (!extended_delassus(pb, cs, ph.rows(), ext.G)) return;
    ext.q = ph.q.template cast<Extended>();
    ext.mu = ph.mu.template cast<Extended>();
    ext.b0 = ph.b0.template cast<Extended>();
    FixedList<typename Phase<C, Extended>::Rows, kMaxSolutions> found;
    bool continuum = false;
    enumerate_modes(ext, tol, found, continuum);
    if (found.size == 0) return;
    for (int k = 0; k < found.size; ++k) out.u.push(found[k].template cast<double>());
    out.continuum = out.continuum || continuum;
    out.exhaustive = !found.overflow;
    out.extended = true;
    out.fallbacks += 1;
    out.primary = out.others = SolverMethod::mode_enumeration;
  }
}

/// One contact: the whole law on scalars with the closed forms of one_contact (eqs. 7-8 with eq. 5
/// or Poisson's phases), no matrix work. False when its 2×2 G is degenerate (then the general path
/// enumerates); `out` is then left empty.
template <int N, int C>
bool solve_law_one_contact(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                           const RestitutionLaw& law, LawOutcome<C>& out) {
  const bool poisson = law.has_phases();
  const bool f = cs.tangential;
  const int r = f ? 2 : 1, i = cs.index(0);
  const double gnn = cs.G(0, 0), gnt = f ? cs.G(0, 1) : 0.0, gtt = f ? cs.G(1, 1) : 0.0;
  const double dna = cs.D_A(0), dta = f ? cs.D_A(1) : 0.0;
  const double e = law.e[i], mu = f ? law.mu[i] : 0.0;
  Tolerances tol;
  tol.v = 1e-9 * cs.v_scale;
  tol.p = tol.v / std::max({gnn, gtt, std::numeric_limits<double>::min()});
  // Answers with the same velocities (and, for Poisson, the same velocities after compression)
  // are one, as in the enumeration (enumerate_modes): on a light rotor (mass ratio 1e6) Poisson's
  // expansion from a sticking compression with e = 0 is both "open" (ΔP = 0) and "stick" with
  // increments of rounding that G maps onto the same velocities, and the two identical answers
  // were reported as two solutions (unique false).
  auto same_velocities = [&](double dx, double dt) {
    return std::fabs(gnn * dx + gnt * dt) <= 16 * tol.v &&
           std::fabs(gnt * dx + gtt * dt) <= 16 * tol.v;
  };
  auto push = [&](double xc, double tc, double x, double t) {
    for (int k = 0; k < out.solutions.size; ++k) {
      const LawSolution<C>& o = out.solutions[k];
      const double ot = f ? o.P(1) : 0.0;
      const bool same_after = same_velocities(x - o.P(0), t - ot);
      const bool same_compression =
          !poisson || same_velocities(xc - o.P_C(0), tc - (f ? o.P_C(1) : 0.0));
      if (same_after && same_compression) return;
    }
    LawSolution<C>* s = out.solutions.emplace();
    if (!s) return;
    s->P.resize(r);
    s->P(0) = x;
    if (f) s->P(1) = t;
    if (poisson) {
      s->P_C.resize(r);
      s->P_C(0) = xc;
      if (f) s->P_C(1) = tc;
    }
  };
  const OneContact first =
      one_contact(gnn, gnt, gtt, poisson ? dna : (1 + e) * dna, dta, mu, 0.0, f, tol);
  if (first.degenerate) return false;
  for (int k = 0; k < first.count; ++k) {
    const double xc = first.x[k], tc = first.t[k];
    if (!poisson) {
      push(0.0, 0.0, xc, tc);
      continue;
    }
    // Expansion from the end of compression with P_NE = e P_NC + ΔP, bound μ P_NE.
    const double s = e * xc;
    const double dnc = dna + gnn * xc + gnt * tc, dtc = dta + gnt * xc + gtt * tc;
    const OneContact second =
        one_contact(gnn, gnt, gtt, dnc + gnn * s, dtc + gnt * s, mu, mu * s, f, tol);
    if (second.degenerate) {
      out.solutions.clear();
      return false;
    }
    for (int j = 0; j < second.count; ++j) push(xc, tc, xc + s + second.x[j], tc + second.t[j]);
  }
  // No solution by the closed forms: the general path decides (Lemke, the enumeration, the
  // checks of a ray), since rounding can refuse every closed form of an ill-conditioned G.
  // Poisson + Coulomb with cond(M) = 8e9: the compression sticks (P_NC = 874), and its D_NC,
  // zero exactly, came out −4e-11, below the expansion's tolerance, so no expansion mode held
  // and the law said `no_solution`.
  if (out.solutions.size == 0) return false;
  if (out.solutions.size > 1) {
    // T_E − T_A = P·(Wᵀq̇_A) + ½ PᵀGP (eq. 9), to choose between several solutions.
    const double wn = pb.W_N.col(i).dot(pb.qdot_A);
    const double wt = f ? pb.W_T.col(i).dot(pb.qdot_A) : 0.0;
    for (int k = 0; k < out.solutions.size; ++k) {
      LawSolution<C>& s = out.solutions[k];
      const double x = s.P(0), t = f ? s.P(1) : 0.0;
      s.energy_change = x * wn + t * wt + 0.5 * (gnn * x * x + 2 * gnt * x * t + gtt * t * t);
    }
  }
  out.exhaustive = !out.solutions.overflow;
  return true;
}

/// Solves the law on the active contacts of `cs`. `list_up_to`: on up to that many contacts (at
/// most kMaxEnumerated) with friction, list every solution the enumeration finds; otherwise one,
/// by the cheapest exact method (0: always one). `force`: see solve_phase.
template <int N, int C>
void solve_law(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
               const RestitutionLaw& law, int list_up_to, LawOutcome<C>& out,
               SolverMethod force = SolverMethod::automatic) {
  using Rows = typename Phase<C>::Rows;
  out.reset();
  const int a = cs.active;
  if (a == 1 && (force == SolverMethod::automatic || force == SolverMethod::closed_form) &&
      solve_law_one_contact(pb, cs, law, out))
    return;
  const bool poisson = law.has_phases();
  Phase<C> ph;
  ph.a = a;
  ph.friction = cs.tangential;
  const int r = ph.rows();
  ph.G = cs.G.topLeftCorner(r, r);
  ph.mu.resize(a);
  ph.b0.setZero(a);
  VecT<C> e(a);
  for (int k = 0; k < a; ++k) {
    e(k) = law.e[cs.index(k)];
    ph.mu(k) = ph.friction ? law.mu[cs.index(k)] : 0.0;
  }
  const Tolerances tol = tolerances(ph, cs.v_scale);
  Factored<C> fg;
  fg.compute(ph.G, pb.dofs());  // null(G) only where a minimum-norm choice asks for it
  // T_E − T_A = Pᵀ Wᵀq̇_A + ½ PᵀGP (eq. 9 with the obstacle terms w taken out of D_A).
  // By hand loops: Eigen's dynamic-size products on these few rows go through its GEMV kernel.
  Rows Wq(r);
  for (int j = 0; j < r; ++j) Wq(j) = cs.W.col(j).dot(pb.qdot_A);
  auto energy = [&](const Rows& P) {
    Rows GP = Rows::Zero(r);
    add_product(ph.G, P, GP);
    return P.dot(Wq) + 0.5 * P.dot(GP);
  };
  const Rows zero = Rows::Zero(r);

  // Newton (eq. 5): q = ((1 + e) D_NA, D_TA). Poisson's compression: q = D_A.
  ph.q = cs.D_A.head(r);
  if (!poisson) ph.q.head(a) = ph.q.head(a).cwiseProduct((e.array() + 1.0).matrix());
  PhaseOutcome<C> first;
  solve_phase(ph, tol, list_up_to, fg, zero, first, force);
  // The minimum-norm choice among percussions of equal velocities (solve_phase) needs G's null
  // space in double and is not made for answers found in extended precision.
  auto in_extended_precision = [&](const Phase<C>& phase, PhaseOutcome<C>& o) {
    if (force != SolverMethod::automatic && force != SolverMethod::mode_enumeration) return;
    decide_in_extended_precision(pb, cs, phase, tol, o);
    if (o.extended && fg.kernel(ph.G).cols() > 0) o.percussion_unique = false;
  };
  in_extended_precision(ph, first);
  if (first.unsupported) {
    out.unsupported = true;
    out.exhaustive = false;
    return;
  }
  out.pivots = first.pivots;
  out.fallbacks = first.fallbacks;
  out.exhaustive = first.exhaustive;
  out.extended = first.extended;
  out.continuum = first.continuum;
  if (poisson)
    out.compression_unique = first.percussion_unique;
  else
    out.percussion_unique = first.percussion_unique;

  if (frictionless(ph) && first.u.size == 0 && !ray_is_proof(cs, ph)) {
    out.exhaustive = false;
    out.beyond_precision = true;
  }

  // How well the expansion's q = D_C + G e P_C is known from the compression's percussions uc:
  // G is formed by a solve with M, to ε κ(M) relative (velocity_rounding's term).
  auto start_rounding = [&](const Rows& uc) {
    double worst = 0.0;
    for (int i = 0; i < r; ++i) {
      double GP = 0.0;
      for (int k = 0; k < r; ++k) GP += std::fabs(ph.G(i, k)) * std::fabs(uc(k));
      worst = std::max(worst, GP);
    }
    return cs.delassus_rounding() * worst;
  };
  for (int k = 0; k < first.u.size; ++k) {
    const SolverMethod mk = k == 0 ? first.primary : first.others;
    if (!poisson) {
      LawSolution<C>* s = out.solutions.emplace();
      if (!s) break;
      s->P = first.u[k];
      s->energy_change = energy(s->P);
      s->method = mk;
      continue;
    }
    // Poisson's expansion from the end of compression: P_NE = e P_NC + ΔP with 0 ≤ ΔP ⊥ D_NE ≥ 0,
    // Coulomb on (P_TE, D_TE) with bound μ P_NE = μ ΔP + μ e P_NC.
    const Rows& uc = first.u[k];
    Phase<C> ex = ph;
    Rows shift = Rows::Zero(r);
    shift.head(a) = e.cwiseProduct(uc.head(a));
    ex.q = ph.velocity(uc);
    add_product(ph.G, shift, ex.q);
    if (ph.friction) ex.b0 = ph.mu.cwiseProduct(shift.head(a));
    PhaseOutcome<C> second;
    solve_phase(ex, tol, list_up_to, fg, shift, second, force);
    in_extended_precision(ex, second);
    if (second.unsupported) {
      out.solutions.clear();
      out.unsupported = true;
      out.exhaustive = false;
      return;
    }
    out.pivots += second.pivots;
    out.fallbacks += second.fallbacks;
    out.extended = out.extended || second.extended;
    out.exhaustive = out.exhaustive && second.exhaustive;
    if (frictionless(ex) && second.u.size == 0 && !ray_is_proof(cs, ex, start_rounding(uc))) {
      out.exhaustive = false;
      out.beyond_precision = true;
    }
    out.continuum = out.continuum || second.continuum;
    out.percussion_unique = out.percussion_unique && second.percussion_unique;
    for (int j = 0; j < second.u.size; ++j) {
      LawSolution<C>* s = out.solutions.emplace();
      if (!s) break;
      s->P_C = uc;
      s->P = uc + shift + second.u[j];
      s->energy_change = energy(s->P);
      s->method = costlier(mk, j == 0 ? second.primary : second.others);
    }
  }
  if (out.solutions.overflow) out.exhaustive = false;
  out.method = out.solutions.size ? out.solutions[0].method : first.primary;
}

}  // namespace fremond::detail::classical
