#pragma once
// What the generic driver (solve_impact, law_residual, the independent groups) calls for
// Stronge's law (docs/stronge.md): the closed-form Darboux-Keller integration of one contact
// (darboux_keller.hpp). docs/architecture.md lists the hooks every law gives.
#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "admissibility/detail/admissibility.hpp"
#include "contact_space/contact_space.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/potentials/registry.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/solver_options.hpp"
#include "laws/stronge/darboux_keller.hpp"

namespace fremond::detail {

/// The law from the problem file's `law` object (laws/stronge/schema.cpp).
ImpactLaw read_law(std::type_identity<StrongeLaw>, std::string_view name, const nlohmann::json& j,
                   int contacts, const PotentialRegistry& registry, const std::string& where);

namespace stronge {

/// Below this sin² of the angle between the normal and tangential rows in the metric M⁻¹ (det G /
/// (G_NN G_TT)), G is singular: the stick slope would be rounding (docs/stronge.md).
inline constexpr double kSingularDelassus = 1e-12;

/// The exact percussions (P_N, P_T) of active contact k of `cs`, alone; false where its rows are
/// coupled to another active contact's (G_kj ≠ 0: simultaneous impacts, not solved here) or where
/// its Delassus matrix is singular with friction.
template <int N, int C>
bool exact_percussions(const ContactSpaceT<N, C>& cs, const StrongeLaw& law, int k, double& P_N,
                       double& P_T) {
  const int a = cs.active, rows = cs.rows();
  for (int j = 0; j < rows; ++j) {
    const bool own = j == k || (cs.tangential && j == a + k);
    if (own) continue;
    if (cs.G(k, j) != 0.0 || (cs.tangential && cs.G(a + k, j) != 0.0)) return false;
  }
  const int i = cs.index(k);
  const double G_NN = cs.G(k, k), D_NA = cs.D_A(k);
  const double mu = law.coulomb && cs.tangential ? law.mu[i] : 0.0;
  P_T = 0.0;
  if (!(D_NA < 0.0)) {  // held without approaching (every contact held): no percussion
    P_N = 0.0;
    return true;
  }
  if (mu == 0.0) {  // frictionless: Stronge's answer is Newton's, D_NE = −e D_NA (docs/stronge.md)
    P_N = -(1.0 + law.e[i]) * D_NA / G_NN;
    return true;
  }
  const double G_NT = cs.G(k, a + k), G_TT = cs.G(a + k, a + k);
  if (!(1.0 - (G_NT / G_NN) * (G_NT / G_TT) > kSingularDelassus)) return false;
  const StrongeAnswer s = stronge_contact(G_NN, G_NT, G_TT, D_NA, cs.D_A(a + k), law.e[i], mu);
  P_N = s.P_N;
  P_T = s.P_T;
  return true;
}

/// The law's residual at percussions P (rows of cs): the largest distance to the exact
/// percussions, in velocity units (|ΔP| G_ii / v_scale); +∞ where the law is not solved.
template <int N, int C>
double residual_at(const ContactSpaceT<N, C>& cs, const StrongeLaw& law, const VecT<C>& P_N_of,
                   const VecT<C>& P_T_of) {
  double worst = 0.0;
  for (int k = 0; k < cs.active; ++k) {
    double P_N = 0.0, P_T = 0.0;
    if (!exact_percussions(cs, law, k, P_N, P_T)) return std::numeric_limits<double>::infinity();
    const int i = cs.index(k);
    worst = std::max(worst, std::fabs(P_N_of(i) - P_N) * cs.G(k, k));
    if (cs.tangential)
      worst = std::max(worst, std::fabs(P_T_of(i) - P_T) * cs.G(cs.active + k, cs.active + k));
  }
  return worst / cs.v_scale;
}

}  // namespace stronge

template <int N, int C>
double residual_of(const ImpactProblemT<N, C>& pb, const StrongeLaw& law,
                   const ImpactResultT<N, C>& r) {
  ContactSpaceT<N, C> cs;
  build_contact_space(pb, law.has_friction(), cs);
  double off = 0.0;  // a separating contact carries nothing, to the percussions' own scale
  for (int i = 0; i < cs.contacts; ++i)
    if (cs.D_N(i) > 0.0) off = std::max({off, std::fabs(r.P_N(i)), std::fabs(r.P_T(i))});
  if (cs.active == 0) return off;
  const double held = stronge::residual_at(cs, law, r.P_N, r.P_T);
  double g = 0.0;
  for (int k = 0; k < cs.active; ++k) g = std::max(g, cs.G(k, k));
  return std::max(held, off * g / cs.v_scale);
}

/// One closed form per contact (docs/stronge.md); contacts whose rows are coupled (simultaneous
/// impacts) are refused as unsupported, naming what is missing.
template <int N, int C>
void solve_chain(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                 const StrongeLaw& law, const SolverOptions& options, ImpactResultT<N, C>& out) {
  const SolverMethod m = options.method;
  if (m != SolverMethod::automatic && m != SolverMethod::closed_form &&
      !(m == SolverMethod::trivial && cs.active == 0)) {
    out.solver.method = m;
    out.solver.status = SolverStatus::unsupported;
    out.solver.message = "Stronge's law is solved in closed form (method automatic or closed_form)";
    return;
  }
  typename ContactSpaceT<N, C>::Rows P = ContactSpaceT<N, C>::Rows::Zero(cs.rows());
  for (int k = 0; k < cs.active; ++k) {
    double P_N = 0.0, P_T = 0.0;
    if (!stronge::exact_percussions(cs, law, k, P_N, P_T)) {
      out.solver.method = SolverMethod::closed_form;
      out.solver.status = SolverStatus::unsupported;
      out.solver.message =
          "Stronge's law is solved for one contact, or for contacts that do not interact "
          "(G_ij = 0); simultaneous impacts need a distributing law (docs/stronge.md), and a "
          "contact whose tangent is parallel to its normal in the metric M^-1 has no stick";
      return;
    }
    P(k) = P_N;
    if (cs.tangential) P(cs.active + k) = P_T;
  }
  scatter_solution(pb, cs, P, out);
  out.unique = true;
  out.solutions_found = 1;
  out.solver.method = cs.active == 0 ? SolverMethod::trivial : SolverMethod::closed_form;
  out.solver.criterion = StopCriterion::exact;
  out.solver.iterations = cs.active;
  if (!(out.qdot_E.allFinite() && std::isfinite(out.energy_change))) {
    out.solver.status = SolverStatus::failed;
    out.solver.message = "the answer's velocities or energy do not fit in double precision";
    return;
  }
  // The percussions are the closed form's, written as they are: their distance to it is 0.
  out.solver.residual = 0.0;
  out.solver.status = SolverStatus::converged;
  out.solver.message = cs.active == 0 ? "no contact takes part (every D_NA > 0): no percussion"
                                      : "Stronge's law in closed form (docs/stronge.md)";
}

template <int N, int C>
std::vector<ImpactResultT<N, C>> solve_every_answer(const ImpactProblemT<N, C>& pb,
                                                    const StrongeLaw& law,
                                                    const SolverOptions& options,
                                                    HeldContacts held) {
  ContactSpaceT<N, C> cs;
  build_contact_space(pb, law.has_friction(), cs, held);
  std::vector<ImpactResultT<N, C>> all(1);
  solve_chain(pb, cs, law, options, all.front());
  return all;
}

/// Independent groups solved apart: the velocities from the gathered percussions.
template <int N, int C>
void write_merged_answer(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                         const StrongeLaw& /*law*/, const typename ContactSpaceT<N, C>::Rows& P,
                         const typename ContactSpaceT<N, C>::Rows& /*P_C*/,
                         const VecT<C>& /*reaction*/, const VecT<N>& /*dq*/,
                         const VecT<N>& /*dq_C*/, ImpactResultT<N, C>& out) {
  scatter_solution(pb, cs, P, out);
}

/// Dissipative by construction, with no data outside its domain: a refused answer is unresolved.
template <int N, int C>
bool refuse_outside_domain(const StrongeLaw& /*law*/, ImpactResultT<N, C>& /*out*/) {
  return false;
}

/// No terms of its own: the certificate holds it to (15) and non-penetration.
inline bool has_certificate_terms(const StrongeLaw& /*law*/) {
  return false;
}
inline void certificate_terms(const StrongeLaw& /*law*/, int /*i*/, const CertificateContact& /*k*/,
                              CertificateTerms& /*out*/) {}

}  // namespace fremond::detail
