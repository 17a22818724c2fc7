// The classical impact laws of docs/laws.md: Newton (eqs. 5-6) and Poisson, each with or without
// Coulomb friction in the compression/expansion form of Pfeiffer & Glocker (1996), on any number of
// contacts.
//
// Each law is one phase (Newton) or two (Poisson's compression, then expansion) of the form solved
// in detail/classical_phase.hpp. Per phase the cheapest exact method comes first: the closed form
// for one contact, the all-closed guess u = −G⁻¹q for several (eq. 6 when it holds), then
// lexicographic Lemke on the phase's LCP. With friction the enumeration of contact modes lists
// every solution when asked (options.check_uniqueness: up to 3 contacts; solve_impact_all: up to
// 4), and on up to 4 contacts settles existence when Lemke's method ends on a ray (its LCP is
// copositive, not copositive-plus: a ray proves nothing), or re-solves the law when Lemke's
// answer misses the tolerance by rounding. Where G is singular the percussions that
// give the same velocities form a polyhedron; the minimum-norm one is returned and `unique` says
// so. An answer that still misses the tolerance beyond rounding is refined in its mode, solved in
// velocities in its mode (classical_velocity_mode.hpp), and last, on up to 4 contacts, replaced by
// the answer of every mode solved in velocities where that converges.
#include "solvers/detail/classical.hpp"

#include <algorithm>
#include <limits>
#include <utility>

#include "laws/detail/residuals.hpp"
#include "laws/detail/separating_contacts.hpp"
#include "solvers/detail/chain.hpp"
#include "solvers/detail/chain_workspace.hpp"
#include "solvers/detail/classical_law.hpp"
#include "solvers/detail/classical_one_contact.hpp"
#include "solvers/detail/classical_refine.hpp"
#include "solvers/detail/classical_velocity_mode.hpp"
#include "solvers/nsgs/sweeps.hpp"

namespace fremond::detail {

// Writes the percussions P (and Poisson's compression P_C) of the rows that take part into `out`:
// velocities, percussions, phases.
template <int N, int C>
void write_classical_answer(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                            const RestitutionLaw& law, const typename ContactSpaceT<N, C>::Rows& P,
                            const typename ContactSpaceT<N, C>::Rows& P_C, ImpactResultT<N, C>& out,
                            const VecT<N>* velocities, const VecT<N>* compression_velocities) {
  const bool poisson = law.has_phases();
  if (velocities) {
    out.qdot_E = *velocities;
    scatter_at_velocities(pb, cs, P, out);
  } else {
    scatter_solution(pb, cs, P, out);
  }
  out.has_phases = poisson;
  if (!poisson) out.qdot_C.resize(0);
  if (poisson) {
    const int c = cs.contacts, a = cs.active;
    out.P_NC.setZero(c);
    out.P_TC.setZero(c);
    for (int k = 0; k < a; ++k) {
      out.P_NC(cs.index(k)) = P_C(k);
      if (cs.tangential) out.P_TC(cs.index(k)) = P_C(a + k);
    }
    auto& qdot_C = out.qdot_C;
    if (compression_velocities)
      qdot_C = *compression_velocities;
    else
      velocity_after(pb, cs, P_C, qdot_C);
    out.D_NC.resize(c);
    out.D_TC.setZero(c);
    for (int i = 0; i < c; ++i) {
      out.D_NC(i) = contact_velocity(pb.W_N.col(i), qdot_C, pb.w_N.size() ? pb.w_N(i) : 0.0);
      if (pb.has_tangential())
        out.D_TC(i) = contact_velocity(pb.W_T.col(i), qdot_C, pb.w_T.size() ? pb.w_T(i) : 0.0);
    }
  }
}

namespace {

using classical::LawOutcome;
using classical::LawSolution;
using classical::Phase;
using classical::solve_law;

/// The largest part of the velocities that the rounding of a refined answer's percussions may
/// account for (classical_residual's percussion_cap, for the answer's acceptance only).
constexpr double kRoundedPercussionCap = 1e-8;

bool is_poisson(const RestitutionLaw& law) {
  return law.has_phases();
}

// The mode offsets of Newton's laws: no fixed part, target e D_NA (eq. 5).
template <int N, int C>
classical::ModeOffsets<N, C> newton_offsets(const ContactSpaceT<N, C>& cs,
                                            const RestitutionLaw& law) {
  using Rows = typename ContactSpaceT<N, C>::Rows;
  const int a = cs.active;
  classical::ModeOffsets<N, C> off;
  off.cN = off.cT = off.cB = Rows::Zero(a);
  off.target.resize(a);
  for (int k = 0; k < a; ++k) off.target(k) = law.e[cs.index(k)] * cs.D_A(k);
  return off;
}

// Refines the answer's percussions P (and Poisson's compression P_C) in its contact mode
// (classical_refine.hpp): compression first, then the expansion with the compression held.
template <int N, int C>
classical::Refinement refine_answer(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                                    const RestitutionLaw& law,
                                    typename ContactSpaceT<N, C>::Rows& P,
                                    typename ContactSpaceT<N, C>::Rows& P_C) {
  using classical::Refinement;
  classical::ModeOffsets<N, C> off = newton_offsets(cs, law);
  Refinement compression = Refinement::converged;
  if (is_poisson(law)) {
    off.target.setZero();  // both phases hold D = 0 on closed rows, from a fixed part
    compression = classical::refine_mode(pb, cs, law, off, P_C);  // D_NC = 0 where closed
    if (compression == Refinement::singular) return compression;
    classical::hold_compression(cs, law, P_C, off);
  }
  const Refinement expansion = classical::refine_mode(pb, cs, law, off, P);
  return expansion == Refinement::converged ? compression : expansion;
}

// The answer's mode solved for its velocities and percussions together
// (classical_velocity_mode.hpp); Poisson's compression first, then its expansion around the
// compression so solved. P, P_C, q (q̇_E) and qC (Poisson's q̇_C) are the new answer when true;
// `continuum` then says whether a phase's percussions form a continuum about it (more rows hold
// than they have independent directions, solve_mode_with_velocities).
template <int N, int C>
bool solve_in_velocities(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                         const RestitutionLaw& law, typename ContactSpaceT<N, C>::Rows& P,
                         typename ContactSpaceT<N, C>::Rows& P_C, VecT<N>& q, VecT<N>& qC,
                         bool& continuum) {
  classical::ModeOffsets<N, C> off = newton_offsets(cs, law);
  const VecT<N>* from_A = nullptr;  // from q̇_A and no percussion
  const typename ContactSpaceT<N, C>::Rows* from_zero = nullptr;
  if (!is_poisson(law))
    return classical::solve_mode_in_velocities(pb, cs, law, off, P, q, from_A, from_zero,
                                               &continuum);
  off.target.setZero();
  typename ContactSpaceT<N, C>::Rows PC = P_C, PE = P;
  VecT<N> qc;
  bool compression = false, expansion = false;
  if (!classical::solve_mode_in_velocities(pb, cs, law, off, PC, qc, from_A, from_zero,
                                           &compression))
    return false;
  // The expansion's increments (x = P_N − (1 + e) P_NC, t = P_T − P_TC) carried over to the
  // compression just solved, whose P_NC moved by its cond(M) ε: read around the new compression,
  // an expansion at x = 0 exactly (open, P_NE = e P_NC) would read as closed, and its mode have
  // no answer (cond(M) near 1e11).
  classical::ModeOffsets<N, C> found_around = off;
  classical::hold_compression(cs, law, P_C, found_around);
  classical::hold_compression(cs, law, PC, off);
  for (int k = 0; k < cs.active; ++k) {
    PE(k) = off.cN(k) + (P(k) - found_around.cN(k));
    if (cs.tangential) PE(cs.active + k) = off.cT(k) + (P(cs.active + k) - found_around.cT(k));
  }
  if (!classical::solve_mode_in_velocities(pb, cs, law, off, PE, q, &qc, &PC, &expansion))
    return false;
  P = PE;
  P_C = PC;
  qC = qc;
  continuum = compression || expansion;
  return true;
}

// One solution of the law as it is settled into an answer: its residual, how far that is beyond
// the rounding of its terms, the percussions kept, and whether they form a continuum.
template <int N, int C>
struct Settling {
  double residual = 0.0;
  double beyond_rounding = 0.0;
  typename ContactSpaceT<N, C>::Rows P, P_C;
  bool continuum = false;
};

// Repair 1, beyond rounding: the percussions may carry cond(G)·ε (W_T nearly parallel to W_N).
// Refined in their mode (classical_refine.hpp), the better answer by the law's residual is kept;
// a refinement that solves its mode to rounding is also allowed the rounding of the percussions
// themselves, since a mode misread at a stick-slip boundary stays beyond that allowance.
template <int N, int C>
void refine_in_mode(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                    const RestitutionLaw& law, const SolverOptions& options, Settling<N, C>& st,
                    ImpactResultT<N, C>& out) {
  typename ContactSpaceT<N, C>::Rows P = st.P, P_C = st.P_C;
  const auto refined = refine_answer(pb, cs, law, P, P_C);
  if (refined == classical::Refinement::singular) return;
  const bool rounded = refined == classical::Refinement::converged;
  ImpactResultT<N, C> trial;
  write_classical_answer(pb, cs, law, P, P_C, trial);
  double trial_beyond = 0.0;
  const double trial_residual = classical_residual(pb, cs, law, trial, &trial_beyond, rounded);
  bool keep = trial_residual < st.residual || (rounded && trial_beyond <= options.tolerance);
  // On a diagonal M (a body in its principal axes) each component is solved to its last bit, so
  // the percussions' rounding is all that is left: it is allowed up to kRoundedPercussionCap of
  // the velocities. With M not diagonal such answers can be 1e-8 from the exact one, and
  // `stalled` is the honest word.
  if (!(trial_beyond <= options.tolerance) && is_diagonal(pb.M)) {
    double loose = 0.0;
    classical_residual(pb, cs, law, trial, &loose, true, kRoundedPercussionCap);
    if (loose <= options.tolerance) {
      keep = true;
      trial_beyond = loose;
    }
  }
  if (!keep) return;
  write_classical_answer(pb, cs, law, P, P_C, out);
  st.residual = trial_residual;
  st.beyond_rounding = trial_beyond;
  st.P = P;
  st.P_C = P_C;
}

// Repair 2, still above the tolerance: the answer's mode solved for the velocities and the
// percussions together, M only multiplied (Poisson's: each phase), kept when the law's residual
// then reads smaller and within rounding. G = WᵀM⁻¹W carries cond(M)·ε that this solve avoids.
template <int N, int C>
void mode_in_velocities(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                        const RestitutionLaw& law, const SolverOptions& options, Settling<N, C>& st,
                        ImpactResultT<N, C>& out) {
  VecT<N> q, qC;
  typename ContactSpaceT<N, C>::Rows P = st.P, P_C = st.P_C;
  bool dependent = false;
  if (!solve_in_velocities(pb, cs, law, P, P_C, q, qC, dependent)) return;
  ImpactResultT<N, C> trial;
  write_classical_answer(pb, cs, law, P, P_C, trial, &q, &qC);
  double trial_beyond = 0.0;
  const double trial_residual = classical_residual(pb, cs, law, trial, &trial_beyond, true);
  if (!(trial_beyond <= options.tolerance) ||
      (st.beyond_rounding <= options.tolerance && !(trial_residual < st.residual)))
    return;
  write_classical_answer(pb, cs, law, P, P_C, out, &q, &qC);
  st.residual = trial_residual;
  st.beyond_rounding = trial_beyond;
  st.continuum = dependent;
}

// The report of a settled solution: method, uniqueness, message and status.
template <int N, int C>
void report_solution(const SolverOptions& options, const LawOutcome<C>& lo, const LawSolution<C>& s,
                     const Settling<N, C>& st, ImpactResultT<N, C>& out) {
  const int found = lo.solutions.size;
  out.unique = lo.exhaustive && found == 1 && !lo.continuum && !st.continuum &&
               lo.percussion_unique && lo.compression_unique;
  out.solutions_found = lo.exhaustive ? found : 0;
  out.solver.method = s.method;
  out.solver.criterion = lo.sweeps ? StopCriterion::residual : StopCriterion::exact;
  out.solver.iterations = lo.pivots;
  out.solver.fallbacks = lo.fallbacks;
  out.solver.residual = st.residual;
  if (lo.sweeps)
    out.solver.message =
        "solved by nonsmooth Gauss-Seidel and semismooth Newton on the contact modes; other "
        "solutions not looked for";
  else if (lo.continuum)
    out.solver.message = "a continuum of solutions (singular contact modes)";
  else if (st.continuum)
    out.solver.message =
        "the percussions are not unique: more contact rows hold than they have independent "
        "directions; the velocities are, and the mode was solved for them and the percussions "
        "together, M only multiplied";
  else if (lo.exhaustive && found > 1)
    out.solver.message =
        "several solutions; the most dissipative that satisfies the law is returned";
  else if (lo.in_velocities)
    out.solver.message =
        "no contact mode solves the law with G = W^T M^-1 W (G carries cond(M) below rounding); "
        "a mode solved for the velocities and percussions together, M only multiplied, does; "
        "other solutions not looked for";
  else if (lo.extended)
    out.solver.message =
        lo.percussion_unique
            ? "no contact mode solves the law in double precision (a mode's small singular values "
              "lie below its rounding); solved by the modes with G = W^T M^-1 W in extended "
              "precision"
            : "no contact mode solves the law in double precision (a mode's small singular values "
              "lie below its rounding); solved by the modes with G = W^T M^-1 W in extended "
              "precision; the percussions are not unique (G singular)";
  else if (!lo.compression_unique)
    out.solver.message =
        "Poisson: the compression percussion is not unique; the minimum-norm one is used";
  else if (!lo.percussion_unique)
    out.solver.message = "the percussions are not unique (G singular); the minimum-norm one";
  else if (!lo.exhaustive)
    out.solver.message = "one solution; uniqueness not checked";
  else
    out.solver.message = "the unique solution";
  if (st.residual <= options.tolerance || st.beyond_rounding <= options.tolerance) {
    out.solver.status = SolverStatus::converged;
    if (!(st.residual <= options.tolerance)) out.solver.criterion = StopCriterion::rounding;
  } else {
    out.solver.status = SolverStatus::stalled;
    out.solver.message = "exact method, but rounding leaves the law's residual above tolerance";
  }
}

// True when `r` drives a contact that cs does not hold (a separating one) into its obstacle
// beyond the rounding that G = WᵀM⁻¹W carries (16ε cond(M), as velocity_rounding allows): the
// repairs and the later stages of the chain, which solve cs's rows again more accurately, leave
// it there wherever cs's answer is unique, and the impact is solved again on every contact
// (solve_impact.cpp).
template <int N, int C>
bool drives_unheld_contact(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                           const ImpactResultT<N, C>& r, const SolverOptions& options) {
  if (cs.active == cs.contacts) return false;
  return drives_a_separating_contact(pb, r, options, cs.delassus_rounding());
}

// One solution of the law written into `out` and settled: within the tolerance, or within the
// rounding of the contact velocities' own terms (criterion `rounding`: a grazing contact of a
// spinning body cannot be resolved below the rounding of the terms its D_NA is summed from); else
// repaired in its mode, then in velocities. `velocities` (and Poisson's `compression_velocities`),
// where given, are the solution's q̇_E (q̇_C) solved with its percussions
// (classical_velocity_mode.hpp): kept as they are, the percussions allowed their rounding.
template <int N, int C>
void settle_solution(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                     const RestitutionLaw& law, const SolverOptions& options,
                     const LawOutcome<C>& lo, int pick, ImpactResultT<N, C>& out,
                     const VecT<N>* velocities = nullptr,
                     const VecT<N>* compression_velocities = nullptr) {
  const LawSolution<C>& s = lo.solutions[pick];
  write_classical_answer(pb, cs, law, s.P, s.P_C, out, velocities, compression_velocities);
  Settling<N, C> st;
  // On a diagonal M the answer is judged at its own velocities where they settle it
  // (residual_at_own_velocities): the same verdict as from the data, without solving with M again.
  if (velocities ||
      !residual_at_own_velocities(pb, cs, law, s.P, s.P_C, out, options.tolerance, &st.residual))
    st.residual = classical_residual(pb, cs, law, out);
  st.P = s.P;
  st.P_C = s.P_C;
  // An answer that drives a contact cs does not hold is beyond rounding and beyond repair.
  const bool driven = !velocities && !(st.residual <= options.tolerance) &&
                      drives_unheld_contact(pb, cs, out, options);
  if (driven)
    st.beyond_rounding = st.residual;
  else if (!(st.residual <= options.tolerance))  // the floors, on this failure path only
    classical_residual(pb, cs, law, out, &st.beyond_rounding, velocities != nullptr);
  if (!velocities && !driven && !(st.residual <= options.tolerance)) {
    if (!(st.beyond_rounding <= options.tolerance)) refine_in_mode(pb, cs, law, options, st, out);
    if (!(st.residual <= options.tolerance)) mode_in_velocities(pb, cs, law, options, st, out);
  }
  report_solution(options, lo, s, st, out);
}

template <int N, int C>
void fill_trivial(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                  const RestitutionLaw& law, ImpactResultT<N, C>& out) {
  typename ContactSpaceT<N, C>::Rows P(0);
  scatter_solution(pb, cs, P, out);
  out.has_phases = is_poisson(law);
  if (out.has_phases) {
    out.P_NC.setZero(cs.contacts);
    out.P_TC.setZero(cs.contacts);
    out.D_NC = out.D_NA;
    out.D_TC = out.D_TA;
    out.qdot_C = pb.qdot_A;
  }
  out.unique = true;
  out.solutions_found = 1;
  out.solver.method = SolverMethod::trivial;
  out.solver.status = SolverStatus::converged;
  out.solver.criterion = StopCriterion::exact;
  out.solver.message = "no contact takes part (every D_NA > 0): no percussion";
  // No contact takes part, so the law has no row: its residual is zero exactly (computing it would
  // only add the rounding, or the overflow, of the separating contacts' data).
  out.solver.residual = 0.0;
}

// `overflow`: the law has an answer, but its percussions, velocities or energy do not fit in
// double precision; it is not returned.
template <int N, int C>
void fill_failure(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                  const RestitutionLaw& law, const LawOutcome<C>& lo, ImpactResultT<N, C>& out,
                  bool overflow = false) {
  // No answer: report the state before the impact (no percussion) so every field is defined.
  typename ContactSpaceT<N, C>::Rows P = ContactSpaceT<N, C>::Rows::Zero(cs.rows());
  scatter_solution(pb, cs, P, out);
  out.has_phases = is_poisson(law);
  if (out.has_phases) {
    out.P_NC.setZero(cs.contacts);
    out.P_TC.setZero(cs.contacts);
    out.D_NC = out.D_NA;
    out.D_TC = out.D_TA;
    out.qdot_C = pb.qdot_A;
  }
  out.unique = false;
  out.solutions_found = 0;
  out.solver.method = lo.method;
  out.solver.criterion = StopCriterion::exact;
  out.solver.iterations = lo.pivots;
  out.solver.fallbacks = lo.fallbacks;
  // The residual of the state reported, as for any other result: no NaN leaves the library, and
  // a failure's residual says how far "no percussion" is from the law.
  out.solver.residual = classical_residual(pb, cs, law, out);
  if (overflow) {
    out.solver.status = SolverStatus::failed;
    out.solver.message =
        "the law's answer overflows double precision (percussions, velocities or energy not "
        "finite): no percussion is returned";
  } else if (lo.beyond_precision) {
    out.solver.status = SolverStatus::failed;
    out.solver.message =
        "a solution exists (the same LCP with the contact normals' Gram matrix in place of "
        "G = W^T M^-1 W, which has the same solvability, is solved), but Lemke's method on G "
        "ended on a ray: M is too ill-conditioned for double precision to find it. The state "
        "before the impact (no percussion) is returned, with its residual";
  } else if (lo.exhaustive) {
    out.solver.status = SolverStatus::no_solution;
    out.solver.message = "no solution: no contact mode satisfies the law";
  } else {
    out.solver.status = SolverStatus::failed;
    out.solver.message =
        "Lemke's method stopped without a solution (a secondary ray, or its pivot budget), and "
        "no enumeration of contact modes settled whether one exists (friction on more than 4 "
        "contacts, or method lemke forced). The state before the impact (no percussion) is "
        "returned, with its residual";
  }
}

// The classical laws are LCPs, solved by closed forms, Lemke's method and the enumeration of
// contact modes, which `automatic` chooses per phase (a Poisson law has two). Naming one of them
// forces it, where it applies; an iterative method of Frémond's law (scalar or semismooth Newton,
// proximal, NLopt) does not, and saying so beats answering by another method under its name.
bool method_applies(SolverMethod m) {
  switch (m) {
    case SolverMethod::automatic:
    case SolverMethod::trivial:
    case SolverMethod::closed_form:
    case SolverMethod::lemke:
    case SolverMethod::mode_enumeration:
    case SolverMethod::nsgs:
      return true;
    default:
      return false;
  }
}

template <int N, int C>
void fill_unsupported(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                      const RestitutionLaw& law, const SolverOptions& options,
                      ImpactResultT<N, C>& out) {
  LawOutcome<C> none;
  none.exhaustive = false;
  fill_failure(pb, cs, law, none, out);
  out.solver.method = options.method;
  out.solver.status = SolverStatus::unsupported;
  out.solver.message =
      !method_applies(options.method)
          ? "the requested method is not one of the classical laws' (closed_form, lemke, "
            "mode_enumeration, nsgs; automatic chooses among them)"
      : options.method == SolverMethod::trivial
          ? "the requested method applies only when no contact takes part"
      : options.method == SolverMethod::nsgs
          ? "nsgs solves Newton's law (Poisson's phases need closed_form, lemke or "
            "mode_enumeration)"
          : "the requested method does not apply to this problem (closed_form: one contact with "
            "a regular Delassus matrix, or every contact closed and sticking; mode_enumeration: "
            "up to 4 contacts)";
}

// Nothing but finite numbers leaves the library.
template <int N, int C>
bool all_finite(const ImpactResultT<N, C>& r) {
  const bool phases = !r.has_phases || (r.P_NC.allFinite() && r.P_TC.allFinite() &&
                                        r.D_NC.allFinite() && r.D_TC.allFinite());
  return phases && r.qdot_E.allFinite() && r.P_N.allFinite() && r.P_T.allFinite() &&
         r.D_NE.allFinite() && r.D_TE.allFinite() && std::isfinite(r.energy_change) &&
         std::isfinite(r.solver.residual);
}

// The most dissipative solution (smallest T_E − T_A) among those not tried yet; -1 when none is
// left. Energies within 1e-12 count as equal, and then the one found first wins.
template <int C>
int most_dissipative(const LawOutcome<C>& lo, const bool* tried) {
  int best = -1;
  for (int k = 0; k < lo.solutions.size; ++k) {
    if (tried[k]) continue;
    if (best < 0 ||
        lo.solutions[k].energy_change <
            lo.solutions[best].energy_change - 1e-12 * std::fabs(lo.solutions[best].energy_change))
      best = k;
  }
  return best;
}

// Where there are several solutions the most dissipative is returned — among those that satisfy
// the law to the tolerance. The enumeration accepts a contact mode within its own tolerance (1e-9
// of the velocity scale), so on a degenerate continuum (a zero column of W_N: any ΔP ≥ 0 satisfies
// Poisson's expansion) its vertex can sit 1e-9 outside Coulomb's cone while Lemke's answer is
// exact; "stalled" would then be reported for a law that has an exact answer. Only when no solution
// meets the tolerance is the most dissipative returned as it is (stalled).
template <int N, int C>
void fill_best(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
               const RestitutionLaw& law, const SolverOptions& options, const LawOutcome<C>& lo,
               ImpactResultT<N, C>& out) {
  bool tried[classical::kMaxSolutions] = {};
  const int first = most_dissipative(lo, tried);
  int settled = -1;
  for (int k = first; k >= 0; k = most_dissipative(lo, tried)) {
    tried[k] = true;
    settle_solution(pb, cs, law, options, lo, k, out);
    settled = k;
    if (out.solver.status == SolverStatus::converged && all_finite(out)) return;
  }
  if (settled != first) settle_solution(pb, cs, law, options, lo, first, out);
  if (!all_finite(out)) fill_failure(pb, cs, law, lo, out, true);
}

// Where the law's modes in contact space gave no solution (`lo` empty), G carrying cond(M), or
// only answers that stall beyond rounding (solve_classical): every mode solved for the velocities
// and percussions together (classical_velocity_mode.hpp;
// Poisson's in both phases), the velocities kept as solved. True, with the answer in `out`, only
// when the law's residual then converges.
template <int N, int C>
bool solve_in_velocity_modes(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                             const RestitutionLaw& law, const SolverOptions& options,
                             const LawOutcome<C>& lo, ImpactResultT<N, C>& out) {
  if (options.method != SolverMethod::automatic && options.method != SolverMethod::mode_enumeration)
    return false;
  typename ContactSpaceT<N, C>::Rows P, P_C;
  VecT<N> q, qC;
  if (classical::solve_modes_in_velocities(pb, cs, law, is_poisson(law), newton_offsets(cs, law), P,
                                           P_C, q, qC) == 0)
    return false;
  LawOutcome<C> lv;
  lv.method = SolverMethod::mode_enumeration;
  lv.pivots = lo.pivots;
  lv.fallbacks = lo.fallbacks + 1;
  lv.exhaustive = false;
  lv.in_velocities = true;
  LawSolution<C>* s = lv.solutions.emplace();
  s->P = P;
  if (is_poisson(law)) s->P_C = P_C;
  s->method = SolverMethod::mode_enumeration;
  ImpactResultT<N, C> r;
  settle_solution(pb, cs, law, options, lv, 0, r, &q, &qC);
  if (r.solver.status != SolverStatus::converged || !all_finite(r)) return false;
  out = std::move(r);
  return true;
}

// An answer that stalls beyond rounding, solved again by every mode in velocities
// (solve_in_velocity_modes). Two rows nearly parallel (the flat bar tilted by 1e-11 rad: its
// tangential rows differ by 1e-11 in the rotation) make G singular to rounding, and contact space
// answers in a mode the exact problem does not have: both ends sticking, which needs the rotation
// to stop, while Newton's normal law keeps it turning, so the rows' velocities differ by 2e-12 of
// the scale, far above their rounding. The exact answer slides at one end, with the velocities the
// same to 2e-12 and the percussions 10 times larger, opposed. True, with the answer in `alt`, only
// when that converges.
template <int N, int C>
bool stalled_in_velocity_modes(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                               const RestitutionLaw& law, const SolverOptions& options,
                               const LawOutcome<C>& lo, const ImpactResultT<N, C>& stalled,
                               ImpactResultT<N, C>& alt) {
  if (stalled.solver.status != SolverStatus::stalled || options.method != SolverMethod::automatic ||
      !solve_in_velocity_modes(pb, cs, law, options, lo, alt))
    return false;
  alt.solver.fallbacks = stalled.solver.fallbacks + 1;
  alt.solver.message =
      "contact space's answer missed the tolerance beyond rounding; every contact mode solved in "
      "velocities, the most dissipative that meets the law is returned (not proven unique)";
  return true;
}

// Newton's law on the contact space by the sweeps and the mode Newton (solvers/nsgs), on the
// rows regrouped by contact as they take them, in the workspace's storage: the answer in `s`
// (cs's rows) where they converge, or whatever their end where `keep` asks; their runs recorded
// in `log`.
template <int N, int C>
bool sweep_contact_space(const ContactSpaceT<N, C>& cs, const RestitutionLaw& law,
                         const SolverOptions& options, bool keep, ChainWorkspace::Sweeps& ws,
                         SolverReport& log, LawSolution<C>& s, int& iterations) {
  const int a = cs.active, rows = cs.rows();
  const bool t = cs.tangential;
  auto grouped = [&](int j) { return !t ? j : (j < a ? 2 * j : 2 * (j - a) + 1); };
  auto of_grouped = [&](int g) { return !t ? g : (g % 2 == 0 ? g / 2 : a + g / 2); };
  Eigen::VectorXd& D_A = ws.D_A;
  D_A.resize(rows);
  for (int j = 0; j < rows; ++j) D_A(grouped(j)) = cs.D_A(j);
  // G's non-zeros row by row in the grouped order, each row's columns ascending: the compressed
  // row-major storage the sweeps read, written in place (a triplet list sorted into it cost a
  // tenth of a plate's solve on 8 contacts).
  Layout& L = ws.layout;
  RowMajorMatrix& G = L.G;
  G.resize(rows, rows);
  G.reserve(static_cast<Eigen::Index>(rows) * rows);
  for (int gj = 0; gj < rows; ++gj) {
    const int j = of_grouped(gj);
    G.startVec(gj);
    for (int gk = 0; gk < rows; ++gk) {
      const double v = cs.G(j, of_grouped(gk));
      if (v != 0.0) G.insertBack(gj, gk) = v;
    }
  }
  G.finalize();
  ws.e.resize(static_cast<std::size_t>(a));
  ws.mu.resize(static_cast<std::size_t>(a));
  for (int k = 0; k < a; ++k) {
    ws.e[static_cast<std::size_t>(k)] = law.e[cs.index(k)];
    ws.mu[static_cast<std::size_t>(k)] = law.has_friction() ? law.mu[cs.index(k)] : 0.0;
  }
  lay_out(L, D_A, t, law.has_friction(), ws.e, ws.mu);
  // A body of few degrees of freedom on many rows: the sweeps and the Newton steps work on its
  // velocities (contact_rows.hpp), G = Wᵀ M⁻¹ W being of rank n at most.
  if (velocity_factors_pay(cs.dofs, rows)) {
    L.W.resize(cs.dofs, rows);
    L.X.resize(cs.dofs, rows);
    for (int g = 0; g < rows; ++g) {
      L.W.col(g) = cs.W.col(of_grouped(g));
      L.X.col(g) = cs.MinvW.col(of_grouped(g));
    }
  } else {
    L.W.resize(0, 0);
    L.X.resize(0, 0);
  }
  Eigen::VectorXd& P = ws.P;
  P.setZero(rows);
  const SweepOutcome o =
      solve_by_sweeps(L, D_A, P,
                      {.tolerance = options.tolerance,
                       .max_sweeps = keep ? SweepOptions{}.max_sweeps : classical::kChainSweeps,
                       .newton_polish = true},
                      AttemptStart::zero, log, ws.run);
  if (o.status != SolverStatus::converged && !keep) return false;
  s.P.resize(rows);
  for (int j = 0; j < rows; ++j) s.P(j) = P(grouped(j));
  // T_E − T_A = P·D_A + ½ PᵀG P (eq. 9), the figure the most-dissipative choice reads.
  s.energy_change = s.P.dot(cs.D_A) + 0.5 * s.P.dot(cs.G * s.P);
  s.method = o.method;
  iterations = o.iterations;
  return true;
}

/// The classical laws' chain (docs/solvers.md): the stages of run()'s table, in order; the first
/// that answers ends it, and each records what it ran in the result's attempt log.
template <int N, int C>
struct ClassicalChain {
  const ImpactProblemT<N, C>& pb;
  const ContactSpaceT<N, C>& cs;
  const RestitutionLaw& law;
  const SolverOptions& opt;
  ImpactResultT<N, C>& out;
  ChainWorkspace& ws;
  LawOutcome<C> lo;

  void run() {
    using F = ClassicalChain;
    run_stages<
        Stage<&F::forced_other_law, &F::unsupported>,  // an iterative method of Frémond's law
        Stage<&F::no_contact, &F::trivial>,            // no contact takes part: no percussion
        Stage<&F::forced_trivial, &F::unsupported>,    // trivial forced, yet contacts take part
        Stage<&F::forced_sweeps_on_phases, &F::unsupported>,  // nsgs is Newton's only
        Stage<&F::many_contacts, &F::sweeps>,                 // Newton on many contacts: the sweeps
        Stage<&F::one_contact, &F::one_contact_closed_form>,  // one contact, M diagonal: scalars
        Stage<&F::always, &F::contact_modes>,  // per phase: closed form, Lemke, enumeration
        Stage<&F::no_mode_found, &F::modes_in_velocities_or_none>,
        Stage<&F::stalled_after_lemke, &F::enumeration_again>,  // Lemke's pivots' rounding
        Stage<&F::drives_unheld_contact, &F::as_it_is>,         // solved again on every contact
        Stage<&F::stalled, &F::modes_in_velocities_after_stall>>(*this);
  }

  // ---- where each stage applies ---------------------------------------------------------------

  bool always() const { return true; }
  bool forced_other_law() const { return !method_applies(opt.method); }
  bool no_contact() const { return cs.active == 0; }  // whichever exact method was asked for
  bool forced_trivial() const { return opt.method == SolverMethod::trivial; }
  bool forced_sweeps_on_phases() const {
    return opt.method == SolverMethod::nsgs && is_poisson(law);
  }
  // Newton + Coulomb on kSweepsFromContacts contacts or more whose rows outnumber the degrees of
  // freedom (G singular), on kSweepsRegularFromContacts or more otherwise, or nsgs asked for: a
  // sweep costs G's entries (rows times the dofs on a body of few dofs, through its velocities),
  // where Lemke's pivots on the friction LCP grow with their cube (a plate on 32 contacts: 390 µs
  // by Lemke, 48 µs by the sweeps). Without friction (the LCP is G itself) Lemke's pivots are few
  // and it is about as fast. So many contacts are beyond the enumeration (kMaxEnumerated):
  // checking uniqueness changes nothing here.
  bool many_contacts() const {
    static_assert(classical::kSweepsFromContacts > classical::kMaxEnumerated &&
                  classical::kSweepsRegularFromContacts > classical::kMaxEnumerated);
    if (is_poisson(law)) return false;
    if (opt.method == SolverMethod::nsgs) return true;
    return opt.method == SolverMethod::automatic && cs.tangential &&
           cs.active >= (cs.rows() > cs.dofs ? classical::kSweepsFromContacts
                                             : classical::kSweepsRegularFromContacts);
  }
  bool one_contact() const { return classical::one_approaching_contact(cs, opt); }
  bool drives_unheld_contact() const { return drives_unheld(out); }
  bool drives_unheld(const ImpactResultT<N, C>& r) const {
    return detail::drives_unheld_contact(pb, cs, r, opt);
  }
  bool no_mode_found() const { return lo.solutions.size == 0; }
  bool stalled() const { return out.solver.status == SolverStatus::stalled; }
  // Lemke's pivots accumulate rounding: where the enumeration applies, the same contact mode solved
  // directly can meet the tolerance that Lemke's answer (in either of Poisson's phases) misses.
  bool stalled_after_lemke() const {
    return stalled() && opt.method == SolverMethod::automatic &&
           (lo.method == SolverMethod::lemke || lo.pivots > 0) &&
           cs.active <= classical::kMaxEnumerated;
  }

  // ---- what each stage runs --------------------------------------------------------------------

  bool unsupported() {
    fill_unsupported(pb, cs, law, opt, out);
    return logged();
  }
  bool as_it_is() { return true; }
  bool trivial() {
    fill_trivial(pb, cs, law, out);
    return logged();
  }
  // The contact modes' answer on scalars where they would give it unchanged
  // (classical_one_contact.hpp); else the contact modes run.
  bool one_contact_closed_form() {
    return classical::settle_one_contact(pb, cs, law, opt, out) && logged();
  }
  // The law's modes in contact space; with several solutions the most dissipative that meets the
  // law. Hands on a stalled answer, or none.
  bool contact_modes() {
    solve_law(pb, cs, law, opt.check_uniqueness ? classical::kMaxEnumeratedAlways : 0, lo,
              opt.method);
    if (lo.unsupported) return unsupported();
    if (lo.solutions.size == 0) {
      out.solver.record(lo.method, AttemptStart::none,
                        lo.exhaustive ? SolverStatus::no_solution : SolverStatus::failed,
                        std::numeric_limits<double>::infinity());
      return false;
    }
    fill_best(pb, cs, law, opt, lo, out);
    logged();
    return !stalled();
  }
  // The sweeps and the mode Newton (solvers/nsgs/sweeps.hpp) on the contact space, their answer
  // settled as any classical answer is; unless it converges, the contact modes come next (nsgs
  // asked for: its answer stands).
  bool sweeps() {
    const bool forced = opt.method == SolverMethod::nsgs;
    LawOutcome<C> ls;
    LawSolution<C>& s = *ls.solutions.emplace();
    ChainWorkspace::Sweeps& room = ws.sweeps ? *ws.sweeps : ws.sweeps.emplace();
    const bool swept = sweep_contact_space(cs, law, opt, forced, room, out.solver, s, ls.pivots);
    if (!ws.persistent) ws.sweeps.reset();
    if (!swept) return false;
    ls.method = s.method;
    ls.exhaustive = false;
    ls.sweeps = true;
    ImpactResultT<N, C> alt;
    fill_best(pb, cs, law, opt, ls, alt);
    if (alt.solver.status != SolverStatus::converged && !forced && !drives_unheld(alt)) {
      out.solver.record(alt.solver.method, AttemptStart::none, alt.solver.status,
                        alt.solver.residual);
      return false;
    }
    alt.solver.attempts = out.solver.attempts;
    alt.solver.attempt_count = out.solver.attempt_count;
    out = std::move(alt);
    return true;
  }
  // No mode in contact space (G carrying cond(M)): every mode solved in velocities, else the
  // failure is reported.
  bool modes_in_velocities_or_none() {
    ImpactResultT<N, C> alt;
    if (solve_in_velocity_modes(pb, cs, law, opt, lo, alt)) return adopt(alt);
    fill_failure(pb, cs, law, lo, out);
    return logged();
  }
  bool enumeration_again() {
    LawOutcome<C> le;
    solve_law(pb, cs, law, classical::kMaxEnumerated, le, SolverMethod::mode_enumeration);
    if (le.solutions.size == 0) {
      out.solver.record(SolverMethod::mode_enumeration, AttemptStart::none,
                        SolverStatus::no_solution, std::numeric_limits<double>::infinity());
      return false;
    }
    ImpactResultT<N, C> alt;
    fill_best(pb, cs, law, opt, le, alt);
    if (alt.solver.status != SolverStatus::converged) {
      out.solver.record(alt.solver.method, AttemptStart::none, alt.solver.status,
                        alt.solver.residual);
      return false;
    }
    alt.solver.fallbacks = out.solver.fallbacks + 1;
    alt.solver.message =
        "Lemke's answer missed the tolerance by rounding; the enumeration of contact modes "
        "meets it (unique says whether it is the only solution)";
    return adopt(alt);
  }
  // Still stalled: every mode solved in velocities, as where contact space finds none; the
  // stalled answer stays where that does not converge.
  bool modes_in_velocities_after_stall() {
    ImpactResultT<N, C> alt;
    if (stalled_in_velocity_modes(pb, cs, law, opt, lo, out, alt)) return adopt(alt);
    return true;
  }

  // ---- the attempt log -------------------------------------------------------------------------

  // The answer in `out` is this stage's attempt.
  bool logged() {
    out.solver.record(out.solver.method, AttemptStart::none, out.solver.status,
                      out.solver.residual);
    return true;
  }
  // `alt` becomes the answer, with the attempts so far and its own.
  bool adopt(ImpactResultT<N, C>& alt) {
    alt.solver.attempts = out.solver.attempts;
    alt.solver.attempt_count = out.solver.attempt_count;
    out = std::move(alt);
    return logged();
  }
};

}  // namespace

template <int N, int C>
void solve_classical(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                     const RestitutionLaw& law, const SolverOptions& options,
                     ImpactResultT<N, C>& out, ChainWorkspace& ws) {
  ClassicalChain<N, C>{pb, cs, law, options, out, ws, {}}.run();
}

template <int N, int C>
std::vector<ImpactResultT<N, C>> solve_classical_all(const ImpactProblemT<N, C>& pb,
                                                     const RestitutionLaw& law,
                                                     const SolverOptions& options,
                                                     HeldContacts held) {
  ContactSpaceT<N, C> cs;
  build_contact_space(pb, law.has_friction(), cs, held);
  std::vector<ImpactResultT<N, C>> all;
  if (!method_applies(options.method)) {
    fill_unsupported(pb, cs, law, options, all.emplace_back());
    return all;
  }
  if (cs.active == 0) {
    fill_trivial(pb, cs, law, all.emplace_back());
    return all;
  }
  LawOutcome<C> lo;
  if (options.method != SolverMethod::trivial)
    solve_law(pb, cs, law, classical::kMaxEnumerated, lo, options.method);
  if (options.method == SolverMethod::trivial || lo.unsupported) {
    fill_unsupported(pb, cs, law, options, all.emplace_back());
    return all;
  }
  if (lo.solutions.size == 0) {
    // The answer solve_impact finds in the velocities, where it finds one (not unique: other
    // solutions not looked for).
    ImpactResultT<N, C> r;
    if (solve_in_velocity_modes(pb, cs, law, options, lo, r)) {
      all.push_back(std::move(r));
      return all;
    }
    // An empty list means "no solution"; when that is not proven, say so in one failed result.
    if (!lo.exhaustive) fill_failure(pb, cs, law, lo, all.emplace_back());
    return all;
  }
  std::vector<int> order(lo.solutions.size);
  for (int k = 0; k < lo.solutions.size; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](int i, int j) {
    return lo.solutions[i].energy_change < lo.solutions[j].energy_change;
  });
  for (int k : order) {
    ImpactResultT<N, C>& r = all.emplace_back();
    settle_solution(pb, cs, law, options, lo, k, r);
    if (!all_finite(r)) fill_failure(pb, cs, law, lo, r, true);
  }
  // A stalled solution that solve_impact would find converged by every mode in velocities is
  // listed so in place of the first stalled one whose velocities (Poisson's: both phases') agree
  // with it to 1e-9 of the scale: the same solution, found to the law's tolerance.
  auto stalled = [](const ImpactResultT<N, C>& r) {
    return r.solver.status == SolverStatus::stalled;
  };
  const auto first = std::find_if(all.begin(), all.end(), stalled);
  ImpactResultT<N, C> alt;
  if (first == all.end() || !stalled_in_velocity_modes(pb, cs, law, options, lo, *first, alt))
    return all;
  const double scale = std::max(pb.qdot_A.cwiseAbs().maxCoeff(), alt.qdot_E.cwiseAbs().maxCoeff());
  auto near = [&](const VecT<N>& a, const VecT<N>& b) {
    return (a - b).cwiseAbs().maxCoeff() <= 1e-9 * scale;
  };
  for (ImpactResultT<N, C>& r : all) {
    if (!stalled(r) || !near(r.qdot_E, alt.qdot_E) ||
        (is_poisson(law) && !near(r.qdot_C, alt.qdot_C)))
      continue;
    alt.solutions_found = r.solutions_found;
    r = std::move(alt);
    break;  // one solution: a second stalled one near it is another
  }
  return all;
}

#define FREMOND_INSTANTIATE(N, C)                                                                  \
  template void solve_classical(const ImpactProblemT<N, C>&, const ContactSpaceT<N, C>&,           \
                                const RestitutionLaw&, const SolverOptions&, ImpactResultT<N, C>&, \
                                ChainWorkspace&);                                                  \
  template void write_classical_answer(                                                            \
      const ImpactProblemT<N, C>&, const ContactSpaceT<N, C>&, const RestitutionLaw&,              \
      const typename ContactSpaceT<N, C>::Rows&, const typename ContactSpaceT<N, C>::Rows&,        \
      ImpactResultT<N, C>&, const VecT<N>*, const VecT<N>*);                                       \
  template std::vector<ImpactResultT<N, C>> solve_classical_all(                                   \
      const ImpactProblemT<N, C>&, const RestitutionLaw&, const SolverOptions&, HeldContacts);
FREMOND_INSTANTIATE(Dynamic, Dynamic)
FREMOND_INSTANTIATE(kSmallDofs, kSmallContacts)
#undef FREMOND_INSTANTIATE

}  // namespace fremond::detail
