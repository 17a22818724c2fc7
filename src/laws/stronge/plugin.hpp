#pragma once
// What the generic driver (solve_impact, law_residual, the independent groups) calls for
// Stronge's law (docs/stronge.md): the closed-form Darboux-Keller integration of one contact
// (darboux_keller.hpp), and on coupled contacts its integration in impulse space with the
// distributing law of Liu, Zhao and Brogliato (lzb.hpp). docs/architecture.md lists the hooks
// every law gives.
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
#include "laws/stronge/lzb.hpp"

namespace fremond::detail {

struct ChainWorkspace;  // solvers/detail/chain_workspace.hpp

/// The law from the problem file's `law` object (laws/stronge/schema.cpp).
ImpactLaw read_law(std::type_identity<StrongeLaw>, std::string_view name, const nlohmann::json& j,
                   int contacts, const PotentialRegistry& registry, const std::string& where);

namespace stronge {

/// Below this sin² of the angle between the normal and tangential rows in the metric M⁻¹ (det G /
/// (G_NN G_TT)), G is singular: the stick slope would be rounding (docs/stronge.md).
inline constexpr double kSingularDelassus = 1e-12;

/// Whether active contact k's rows are coupled to another active contact's (G_kj ≠ 0:
/// simultaneous impacts, for the distributing law).
template <int N, int C>
bool coupled(const ContactSpaceT<N, C>& cs, int k) {
  const int a = cs.active, rows = cs.rows();
  for (int j = 0; j < rows; ++j) {
    const bool own = j == k || (cs.tangential && j == a + k);
    if (own) continue;
    if (cs.G(k, j) != 0.0 || (cs.tangential && cs.G(a + k, j) != 0.0)) return true;
  }
  return false;
}

/// Whether active contact k has friction and a singular Delassus matrix of its own (its tangent
/// parallel to its normal in the metric M⁻¹): it has no stick, and no law is solved for it.
template <int N, int C>
bool singular_with_friction(const ContactSpaceT<N, C>& cs, const StrongeLaw& law, int k) {
  const int a = cs.active;
  if (!(law.coulomb && cs.tangential && law.mu[cs.index(k)] > 0.0)) return false;
  const double G_NN = cs.G(k, k), G_NT = cs.G(k, a + k), G_TT = cs.G(a + k, a + k);
  return !(1.0 - (G_NT / G_NN) * (G_NT / G_TT) > kSingularDelassus);
}

/// The integration's relative tolerance for the solve's: no tighter than 1e-13, where the
/// Dormand-Prince steps would multiply for rounding's sake.
inline double integration_tolerance(double tolerance) {
  return std::max(tolerance, 1e-13);
}
/// An answer of the distributing law is converged when its error estimate is within this factor
/// of the integration's tolerance (the estimate is a global one; the tolerance a local one).
inline constexpr double kEstimateAllowance = 100.0;

/// Every active contact of cs integrated together by the distributing law (lzb.hpp).
template <int N, int C>
LzbAnswer distributed(const ContactSpaceT<N, C>& cs, const StrongeLaw& law, double tolerance) {
  const int a = cs.active, rows = cs.rows();
  std::vector<LzbContact> contacts(static_cast<std::size_t>(a));
  for (int k = 0; k < a; ++k) {
    const int i = cs.index(k);
    contacts[static_cast<std::size_t>(k)] = {law.e[i], law.coulomb ? law.mu[i] : 0.0, law.eta[i],
                                             law.stiffness[i]};
  }
  const Eigen::MatrixXd G = cs.G.topLeftCorner(rows, rows);
  const Eigen::VectorXd D_A = cs.D_A.head(rows);
  LzbOptions options;
  options.tolerance = integration_tolerance(tolerance);
  return lzb_impact(G, D_A, contacts, options);
}

/// The exact percussions (P_N, P_T) of active contact k of `cs`, alone; false where its rows are
/// coupled to another active contact's or where its Delassus matrix is singular with friction.
template <int N, int C>
bool exact_percussions(const ContactSpaceT<N, C>& cs, const StrongeLaw& law, int k, double& P_N,
                       double& P_T) {
  const int a = cs.active;
  if (coupled(cs, k)) return false;
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
/// percussions, in velocity units (|ΔP| G_ii / v_scale); +∞ where the law is not solved. On
/// coupled contacts the distributing law's answer stands for the exact one: the distance to it,
/// or its own error estimate where that is larger.
template <int N, int C>
double residual_at(const ContactSpaceT<N, C>& cs, const StrongeLaw& law, const VecT<C>& P_N_of,
                   const VecT<C>& P_T_of) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  bool any_coupled = false;
  for (int k = 0; k < cs.active; ++k) any_coupled = any_coupled || coupled(cs, k);
  double worst = 0.0, floor = 0.0;
  LzbAnswer lzb;
  if (any_coupled) {
    for (int k = 0; k < cs.active; ++k)
      if (singular_with_friction(cs, law, k)) return kInf;
    lzb = distributed(cs, law, SolverOptions{}.tolerance);
    if (!lzb.converged) return kInf;
    floor = lzb.error_estimate;
  }
  for (int k = 0; k < cs.active; ++k) {
    double P_N = 0.0, P_T = 0.0;
    if (any_coupled) {
      P_N = lzb.P_N(k);
      P_T = lzb.P_T(k);
    } else if (!exact_percussions(cs, law, k, P_N, P_T)) {
      return kInf;
    }
    const int i = cs.index(k);
    worst = std::max(worst, std::fabs(P_N_of(i) - P_N) * cs.G(k, k));
    if (cs.tangential)
      worst = std::max(worst, std::fabs(P_T_of(i) - P_T) * cs.G(cs.active + k, cs.active + k));
  }
  return std::max(worst / cs.v_scale, floor);
}

/// Every contact apart at the end (D_NE ≥ 0): the largest −D_NE, in units of v_scale.
template <int N, int C>
double penetration(const ContactSpaceT<N, C>& cs, const VecT<C>& D_NE) {
  double worst = 0.0;
  for (int k = 0; k < cs.active; ++k) worst = std::max(worst, -D_NE(cs.index(k)));
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
  double held = stronge::residual_at(cs, law, r.P_N, r.P_T);
  if (r.D_NE.size() == cs.contacts) held = std::max(held, stronge::penetration(cs, r.D_NE));
  double g = 0.0;
  for (int k = 0; k < cs.active; ++k) g = std::max(g, cs.G(k, k));
  return std::max(held, off * g / cs.v_scale);
}

namespace stronge {

/// Coupled contacts by the distributing law (lzb.hpp): the percussions, the velocities they give,
/// and as residual the integration's error estimate or the end's penetration, the larger.
template <int N, int C>
void solve_distributed(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                       const StrongeLaw& law, const SolverOptions& options,
                       ImpactResultT<N, C>& out) {
  const LzbAnswer s = distributed(cs, law, options.tolerance);
  out.solver.method = SolverMethod::impulse_integration;
  out.solver.iterations = s.steps;
  if (!s.converged) {
    out.solver.status = SolverStatus::failed;
    out.solver.message = s.message;
    return;
  }
  typename ContactSpaceT<N, C>::Rows P = ContactSpaceT<N, C>::Rows::Zero(cs.rows());
  for (int k = 0; k < cs.active; ++k) {
    P(k) = s.P_N(k);
    if (cs.tangential) P(cs.active + k) = s.P_T(k);
  }
  scatter_solution(pb, cs, P, out);
  out.unique = true;
  out.solutions_found = 1;
  out.solver.criterion = StopCriterion::residual;
  if (!(out.qdot_E.allFinite() && std::isfinite(out.energy_change))) {
    out.solver.status = SolverStatus::failed;
    out.solver.message = "the answer's velocities or energy do not fit in double precision";
    return;
  }
  out.solver.residual = std::max(s.error_estimate, penetration(cs, out.D_NE));
  if (out.solver.residual <= kEstimateAllowance * integration_tolerance(options.tolerance)) {
    out.solver.status = SolverStatus::converged;
    out.solver.message =
        "Stronge's law on coupled contacts, integrated in impulse space with the distributing "
        "law of Liu, Zhao and Brogliato (docs/stronge.md)";
  } else {
    out.solver.status = SolverStatus::stalled;
    out.solver.message =
        "the distributing law's integration ended with an error estimate above its tolerance";
  }
}

}  // namespace stronge

/// One closed form per contact (docs/stronge.md), or, where contacts are coupled (simultaneous
/// impacts) or the method is impulse_integration, the distributing law on all of them.
template <int N, int C>
void solve_stronge(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                   const StrongeLaw& law, const SolverOptions& options, ImpactResultT<N, C>& out) {
  const SolverMethod m = options.method;
  if (m != SolverMethod::automatic && m != SolverMethod::closed_form &&
      m != SolverMethod::impulse_integration && !(m == SolverMethod::trivial && cs.active == 0)) {
    out.solver.method = m;
    out.solver.status = SolverStatus::unsupported;
    out.solver.message =
        "Stronge's law is solved in closed form, or on coupled contacts by impulse integration "
        "(method automatic, closed_form or impulse_integration)";
    return;
  }
  auto refuse_singular = [&] {
    out.solver.method = SolverMethod::closed_form;
    out.solver.status = SolverStatus::unsupported;
    out.solver.message =
        "a contact whose tangent is parallel to its normal in the metric M^-1 has no stick: "
        "Stronge's law with friction is not solved for it (docs/stronge.md)";
  };
  bool any_coupled = false;
  for (int k = 0; k < cs.active; ++k) any_coupled = any_coupled || stronge::coupled(cs, k);
  if (cs.active > 0 && (any_coupled || m == SolverMethod::impulse_integration)) {
    for (int k = 0; k < cs.active; ++k)
      if (stronge::singular_with_friction(cs, law, k)) return refuse_singular();
    if (m == SolverMethod::closed_form) {
      out.solver.method = m;
      out.solver.status = SolverStatus::unsupported;
      out.solver.message =
          "coupled contacts (G_ij != 0) have no closed form under Stronge's law: method automatic "
          "or impulse_integration solves them with the distributing law (docs/stronge.md)";
      return;
    }
    stronge::solve_distributed(pb, cs, law, options, out);
    return;
  }
  typename ContactSpaceT<N, C>::Rows P = ContactSpaceT<N, C>::Rows::Zero(cs.rows());
  for (int k = 0; k < cs.active; ++k) {
    double P_N = 0.0, P_T = 0.0;
    if (!stronge::exact_percussions(cs, law, k, P_N, P_T)) return refuse_singular();
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

/// Its chain keeps no storage between solves.
template <int N, int C>
void solve_chain(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                 const StrongeLaw& law, const SolverOptions& options, ImpactResultT<N, C>& out,
                 ChainWorkspace& /*ws*/) {
  solve_stronge(pb, cs, law, options, out);
}

template <int N, int C>
std::vector<ImpactResultT<N, C>> solve_every_answer(const ImpactProblemT<N, C>& pb,
                                                    const StrongeLaw& law,
                                                    const SolverOptions& options,
                                                    HeldContacts held) {
  ContactSpaceT<N, C> cs;
  build_contact_space(pb, law.has_friction(), cs, held);
  std::vector<ImpactResultT<N, C>> all(1);
  solve_stronge(pb, cs, law, options, all.front());
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

/// No lane of one contact (solve_impact.cpp): its chain is the integration of the impact.
template <int N, int C>
bool solve_one_contact_lane(const ImpactProblemT<N, C>& /*pb*/, const ContactSpaceT<N, C>& /*cs*/,
                            const StrongeLaw& /*law*/, const SolverOptions& /*options*/,
                            ImpactResultT<N, C>& /*out*/) {
  return false;
}

/// Dissipative by construction, with no data outside its domain: a refused answer is unresolved.
template <int N, int C>
bool refuse_outside_domain(const StrongeLaw& /*law*/, ImpactResultT<N, C>& /*out*/) {
  return false;
}

/// No terms of its own: the certificate holds it to (15) in total and non-penetration (the
/// distributing law passes energy from one contact to another: StrongeLaw::
/// shares_energy_between_contacts).
inline bool has_certificate_terms(const StrongeLaw& /*law*/) {
  return false;
}
inline void certificate_terms(const StrongeLaw& /*law*/, int /*i*/, const CertificateContact& /*k*/,
                              CertificateTerms& /*out*/) {}

}  // namespace fremond::detail
