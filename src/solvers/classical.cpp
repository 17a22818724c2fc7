// The classical impact laws of SPEC §2: Newton (eqs. 5-6) and Poisson, each with or without Coulomb
// friction in the compression/expansion form of Pfeiffer & Glocker (1996), on any number of contacts.
//
// Each law is one phase (Newton) or two (Poisson's compression, then expansion) of the form solved
// in detail/classical_phase.hpp. Per phase the cheapest exact method comes first: the closed form
// for one contact, the all-closed guess u = −G⁻¹q for several (eq. 6 when it holds), then
// lexicographic Lemke on the phase's LCP. With friction on up to 3 contacts the enumeration of
// contact modes lists every solution when asked (options.check_uniqueness, solve_impact_all), and
// settles existence when Lemke's method ends on a ray. Where G is singular the percussions that give
// the same velocities form a polyhedron; the minimum-norm one is returned and `unique` says so.
#include "fremond/solvers/detail/classical.hpp"

#include <algorithm>
#include <limits>

#include "detail/classical_phase.hpp"

namespace fremond::detail {

namespace {

using classical::FixedList;
using classical::kMaxSolutions;
using classical::Phase;
using classical::Tolerances;

// The costlier of two methods, for a law whose phases were solved by different ones.
SolverMethod costlier(SolverMethod a, SolverMethod b) {
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

template <int C>
struct PhaseOutcome {
  using Rows = typename Phase<C>::Rows;
  FixedList<Rows, kMaxSolutions> u;  ///< the first one is the primary method's answer
  SolverMethod primary = SolverMethod::closed_form;  ///< the method of u[0]
  SolverMethod others = SolverMethod::closed_form;   ///< the method of the rest of the list
  int pivots = 0;
  int fallbacks = 0;
  bool exhaustive = false;         ///< u holds every solution (up to equal velocities)
  bool percussion_unique = true;   ///< false when a minimum-norm choice was made
  bool continuum = false;          ///< a singular mode may hold a continuum of velocities
};

// Conservative test of a singular G (then minimum_norm decides exactly, by SVD).
template <class Mat>
bool maybe_singular(const Mat& G) {
  if (G.rows() == 0) return false;
  Eigen::LLT<Mat> llt(G);
  if (llt.info() != Eigen::Success) return true;
  const auto d = llt.matrixLLT().diagonal();
  return !(d.minCoeff() > 1e-7 * d.maxCoeff());
}

template <int C>
void solve_phase(const Phase<C>& ph, const Tolerances& tol, bool all, bool singular,
                 const typename Phase<C>::Rows& shift, PhaseOutcome<C>& out) {
  using Rows = typename Phase<C>::Rows;
  const int r = ph.rows();
  Rows u(r);
  bool enumerate = false;
  if (ph.a == 1) {
    const bool f = ph.friction;
    const classical::OneContact oc =
        classical::one_contact(ph.G(0, 0), f ? ph.G(0, 1) : 0.0, f ? ph.G(1, 1) : 0.0, ph.q(0),
                               f ? ph.q(1) : 0.0, f ? ph.mu(0) : 0.0, f ? ph.b0(0) : 0.0, f, tol);
    if (!oc.degenerate) {
      for (int k = 0; k < oc.count; ++k) {
        u(0) = oc.x[k];
        if (f) u(1) = oc.t[k];
        out.u.push(u);
      }
      out.primary = out.others = SolverMethod::closed_form;
      out.exhaustive = true;
      return;  // one contact with a regular 2×2 G: the percussion is fixed by the velocity
    }
    enumerate = true;  // singular 2×2 G: only the enumeration is sure
    out.primary = out.others = SolverMethod::mode_enumeration;
  } else {
    const bool friction = !classical::frictionless(ph);
    bool have = false;
    if (classical::all_closed_guess(ph, tol, u)) {
      have = true;
      out.primary = SolverMethod::closed_form;
    } else {
      int pivots = 0;
      have = classical::lemke_phase(ph, LemkeOptions{}, u, pivots) == LcpStatus::solved;
      out.pivots += pivots;
      out.primary = SolverMethod::lemke;
      if (have) {
        for (int i = 0; i < ph.a; ++i) u(i) = std::max(0.0, u(i));
      }
    }
    if (!friction) {
      // Symmetric positive semidefinite LCP: the velocities are unique, and a ray proves that
      // there is no solution.
      if (have) out.u.push(u);
      out.exhaustive = true;
    } else if (ph.a <= 3 && (all || !have)) {
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
    classical::enumerate_modes(ph, tol, found, out.continuum);
    for (int k = 0; k < found.size; ++k) {
      const Rows v = ph.velocity(found[k]);
      bool seen = false;
      for (int j = 0; j < out.u.size && !seen; ++j)
        seen = (ph.velocity(out.u[j]) - v).cwiseAbs().maxCoeff() <= 16 * tol.v;
      if (!seen) out.u.push(found[k]);
    }
    out.exhaustive = !found.overflow && !out.u.overflow;
  }
  if (singular)
    for (int k = 0; k < out.u.size; ++k)
      out.percussion_unique = classical::minimum_norm(ph, tol, shift, out.u[k]) &&
                              out.percussion_unique;
}

template <int C>
struct LawSolution {
  using Rows = typename Phase<C>::Rows;
  Rows P;    ///< total percussion, active rows
  Rows P_C;  ///< Poisson: compression percussion
  double energy_change = 0.0;
  SolverMethod method = SolverMethod::closed_form;
};

template <int C>
struct LawOutcome {
  FixedList<LawSolution<C>, kMaxSolutions> solutions;
  SolverMethod method = SolverMethod::closed_form;  ///< the method of solutions[0]
  int pivots = 0;
  int fallbacks = 0;
  bool exhaustive = true;
  bool percussion_unique = true;
  bool compression_unique = true;  ///< Poisson: the compression percussion
  bool continuum = false;
};

template <int N, int C>
void solve_law(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs, const ImpactLaw& law,
               bool all, LawOutcome<C>& out) {
  using Rows = typename Phase<C>::Rows;
  const int a = cs.active;
  const bool poisson = law.type == LawType::poisson || law.type == LawType::poisson_coulomb;
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
  const Tolerances tol = classical::tolerances(ph, cs.v_scale);
  const bool singular = maybe_singular(ph.G);
  // T_E − T_A = Pᵀ Wᵀq̇_A + ½ PᵀGP (eq. 9 with the obstacle terms w taken out of D_A).
  const Rows Wq = cs.W.leftCols(r).transpose() * pb.qdot_A;
  auto energy = [&](const Rows& P) { return P.dot(Wq) + 0.5 * P.dot(ph.G * P); };
  const Rows zero = Rows::Zero(r);

  // Newton (eq. 5): q = ((1 + e) D_NA, D_TA). Poisson's compression: q = D_A.
  ph.q = cs.D_A.head(r);
  if (!poisson) ph.q.head(a) = ph.q.head(a).cwiseProduct((e.array() + 1.0).matrix());
  PhaseOutcome<C> first;
  solve_phase(ph, tol, all, singular, zero, first);
  out.pivots = first.pivots;
  out.fallbacks = first.fallbacks;
  out.exhaustive = first.exhaustive;
  out.continuum = first.continuum;
  if (poisson) out.compression_unique = first.percussion_unique;
  else out.percussion_unique = first.percussion_unique;

  for (int k = 0; k < first.u.size; ++k) {
    const SolverMethod mk = k == 0 ? first.primary : first.others;
    if (!poisson) {
      LawSolution<C> s;
      s.P = first.u[k];
      s.energy_change = energy(s.P);
      s.method = mk;
      out.solutions.push(s);
      continue;
    }
    // Poisson's expansion from the end of compression: P_NE = e P_NC + ΔP with 0 ≤ ΔP ⊥ D_NE ≥ 0,
    // Coulomb on (P_TE, D_TE) with bound μ P_NE = μ ΔP + μ e P_NC.
    const Rows& uc = first.u[k];
    Phase<C> ex = ph;
    Rows shift = Rows::Zero(r);
    shift.head(a) = e.cwiseProduct(uc.head(a));
    ex.q = ph.velocity(uc);
    ex.q.noalias() += ph.G * shift;
    if (ph.friction) ex.b0 = ph.mu.cwiseProduct(shift.head(a));
    PhaseOutcome<C> second;
    solve_phase(ex, tol, all, singular, shift, second);
    out.pivots += second.pivots;
    out.fallbacks += second.fallbacks;
    out.exhaustive = out.exhaustive && second.exhaustive;
    out.continuum = out.continuum || second.continuum;
    out.percussion_unique = out.percussion_unique && second.percussion_unique;
    for (int j = 0; j < second.u.size; ++j) {
      LawSolution<C> s;
      s.P_C = uc;
      s.P = uc + shift + second.u[j];
      s.energy_change = energy(s.P);
      s.method = costlier(mk, j == 0 ? second.primary : second.others);
      out.solutions.push(s);
    }
  }
  if (out.solutions.overflow) out.exhaustive = false;
  out.method = out.solutions.size ? out.solutions[0].method : first.primary;
}

// Writes one solution of the law into `out` (velocities, percussions, phases, solver report).
template <int N, int C>
void fill_result(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs, const ImpactLaw& law,
                 const SolverOptions& options, const LawOutcome<C>& lo, int pick,
                 ImpactResultT<N, C>& out) {
  const bool poisson = law.type == LawType::poisson || law.type == LawType::poisson_coulomb;
  const LawSolution<C>& s = lo.solutions[pick];
  scatter_solution(pb, cs, s.P, out);
  out.has_phases = poisson;
  if (poisson) {
    const int c = cs.contacts, a = cs.active;
    out.P_NC.setZero(c);
    out.P_TC.setZero(c);
    for (int k = 0; k < a; ++k) {
      out.P_NC(cs.index(k)) = s.P_C(k);
      if (cs.tangential) out.P_TC(cs.index(k)) = s.P_C(a + k);
    }
    typename ImpactResultT<N, C>::Vec qdot_C = pb.qdot_A;
    qdot_C.noalias() += cs.MinvW * s.P_C;
    out.D_NC.resize(c);
    out.D_TC.setZero(c);
    for (int i = 0; i < c; ++i) {
      out.D_NC(i) = pb.W_N.col(i).dot(qdot_C) + (pb.w_N.size() ? pb.w_N(i) : 0.0);
      if (pb.has_tangential())
        out.D_TC(i) = pb.W_T.col(i).dot(qdot_C) + (pb.w_T.size() ? pb.w_T(i) : 0.0);
    }
  }
  const int found = lo.solutions.size;
  out.unique = lo.exhaustive && found == 1 && !lo.continuum && lo.percussion_unique &&
               lo.compression_unique;
  out.solutions_found = lo.exhaustive ? found : 0;
  out.solver.method = s.method;
  out.solver.criterion = StopCriterion::exact;
  out.solver.iterations = lo.pivots;
  out.solver.fallbacks = lo.fallbacks;
  out.solver.residual = classical_residual(pb, law, out);
  if (lo.continuum) out.solver.message = "a continuum of solutions (singular contact modes)";
  else if (lo.exhaustive && found > 1)
    out.solver.message = "several solutions; the most dissipative is returned";
  else if (!lo.compression_unique)
    out.solver.message =
        "Poisson: the compression percussion is not unique; the minimum-norm one is used";
  else if (!lo.percussion_unique)
    out.solver.message = "the percussions are not unique (G singular); the minimum-norm one";
  else if (!lo.exhaustive)
    out.solver.message = "one solution; uniqueness not checked";
  else
    out.solver.message = "the unique solution";
  if (out.solver.residual <= options.tolerance) {
    out.solver.status = SolverStatus::converged;
  } else {
    out.solver.status = SolverStatus::stalled;
    out.solver.message = "exact method, but rounding leaves the law's residual above tolerance";
  }
}

template <int N, int C>
void fill_trivial(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                  const ImpactLaw& law, ImpactResultT<N, C>& out) {
  typename ContactSpaceT<N, C>::Rows P(0);
  scatter_solution(pb, cs, P, out);
  out.has_phases = law.type == LawType::poisson || law.type == LawType::poisson_coulomb;
  if (out.has_phases) {
    out.P_NC.setZero(cs.contacts);
    out.P_TC.setZero(cs.contacts);
    out.D_NC = out.D_NA;
    out.D_TC = out.D_TA;
  }
  out.unique = true;
  out.solutions_found = 1;
  out.solver.method = SolverMethod::trivial;
  out.solver.status = SolverStatus::converged;
  out.solver.criterion = StopCriterion::exact;
  out.solver.message = "no contact takes part (every D_NA > 0): no percussion";
  out.solver.residual = classical_residual(pb, law, out);
}

template <int N, int C>
void fill_failure(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                  const ImpactLaw& law, const LawOutcome<C>& lo, ImpactResultT<N, C>& out) {
  // No answer: report the state before the impact (no percussion) so every field is defined.
  typename ContactSpaceT<N, C>::Rows P = ContactSpaceT<N, C>::Rows::Zero(cs.rows());
  scatter_solution(pb, cs, P, out);
  out.has_phases = law.type == LawType::poisson || law.type == LawType::poisson_coulomb;
  if (out.has_phases) {
    out.P_NC.setZero(cs.contacts);
    out.P_TC.setZero(cs.contacts);
    out.D_NC = out.D_NA;
    out.D_TC = out.D_TA;
  }
  out.unique = false;
  out.solutions_found = 0;
  out.solver.method = lo.method;
  out.solver.criterion = StopCriterion::exact;
  out.solver.iterations = lo.pivots;
  out.solver.fallbacks = lo.fallbacks;
  if (lo.exhaustive) {
    out.solver.status = SolverStatus::no_solution;
    out.solver.message = "no solution: no contact mode satisfies the law";
  } else {
    out.solver.status = SolverStatus::failed;
    out.solver.message =
        "Lemke's method ended on a secondary ray; with friction on more than 3 contacts no "
        "enumeration settles whether a solution exists";
  }
}

// The most dissipative solution (smallest T_E − T_A): the one returned when there are several.
template <int C>
int most_dissipative(const LawOutcome<C>& lo) {
  int best = 0;
  for (int k = 1; k < lo.solutions.size; ++k)
    if (lo.solutions[k].energy_change < lo.solutions[best].energy_change - 1e-12 *
                                            std::fabs(lo.solutions[best].energy_change))
      best = k;
  return best;
}

}  // namespace

template <int N, int C>
void solve_classical(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                     const ImpactLaw& law, const SolverOptions& options, ImpactResultT<N, C>& out) {
  if (cs.active == 0) {
    fill_trivial(pb, cs, law, out);
    return;
  }
  LawOutcome<C> lo;
  solve_law(pb, cs, law, options.check_uniqueness, lo);
  if (lo.solutions.size == 0) {
    fill_failure(pb, cs, law, lo, out);
    return;
  }
  fill_result(pb, cs, law, options, lo, most_dissipative(lo), out);
}

std::vector<ImpactResult> solve_classical_all(const ImpactProblem& pb, const ImpactLaw& law,
                                              const SolverOptions& options) {
  ContactSpaceT<Dynamic, Dynamic> cs;
  build_contact_space(pb, law.has_friction(), cs);
  std::vector<ImpactResult> all;
  if (cs.active == 0) {
    fill_trivial(pb, cs, law, all.emplace_back());
    return all;
  }
  LawOutcome<Dynamic> lo;
  solve_law(pb, cs, law, true, lo);
  if (lo.solutions.size == 0) {
    // An empty list means "no solution"; when that is not proven, say so in one failed result.
    if (!lo.exhaustive) fill_failure(pb, cs, law, lo, all.emplace_back());
    return all;
  }
  std::vector<int> order(lo.solutions.size);
  for (int k = 0; k < lo.solutions.size; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](int i, int j) {
    return lo.solutions[i].energy_change < lo.solutions[j].energy_change;
  });
  for (int k : order) fill_result(pb, cs, law, options, lo, k, all.emplace_back());
  return all;
}

#define FREMOND_INSTANTIATE(N, C)                                                                \
  template void solve_classical(const ImpactProblemT<N, C>&, const ContactSpaceT<N, C>&,        \
                                const ImpactLaw&, const SolverOptions&, ImpactResultT<N, C>&);
FREMOND_INSTANTIATE(Dynamic, Dynamic)
FREMOND_INSTANTIATE(kSmallDofs, kSmallContacts)
#undef FREMOND_INSTANTIATE

}  // namespace fremond::detail
