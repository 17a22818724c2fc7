#pragma once
// What the generic driver (solve_impact, law_residual, the independent groups) calls for Frémond's
// laws: their solver chain (solvers/fremond.cpp) and their residual (laws/fremond/residual.cpp).
// docs/architecture.md lists the hooks every law gives.
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "admissibility/detail/admissibility.hpp"
#include "fremond/potentials/registry.hpp"
#include "laws/detail/residuals.hpp"
#include "laws/fremond/certificate.hpp"
#include "solvers/detail/fremond.hpp"

namespace fremond::detail {

struct ChainWorkspace;  // solvers/detail/chain_workspace.hpp

/// The law from the problem file's `law` object (docs/problem-file.md), `name` one of its names;
/// InvalidArgument naming the file's key (under `where`) for a bad one (laws/fremond/schema.cpp).
ImpactLaw read_law(std::type_identity<FremondLaw>, std::string_view name, const nlohmann::json& j,
                   int contacts, const PotentialRegistry& registry, const std::string& where);

template <int N, int C>
double residual_of(const ImpactProblemT<N, C>& pb, const FremondLaw& law,
                   const ImpactResultT<N, C>& r) {
  return fremond_residual(pb, law, r);
}

template <int N, int C>
void solve_chain(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                 const FremondLaw& law, const SolverOptions& options, ImpactResultT<N, C>& out,
                 ChainWorkspace& /*ws*/) {
  solve_fremond(pb, cs, law, options, out);
}

template <int N, int C>
std::vector<ImpactResultT<N, C>> solve_every_answer(const ImpactProblemT<N, C>& pb,
                                                    const FremondLaw& law,
                                                    const SolverOptions& options,
                                                    HeldContacts held) {
  return solve_fremond_all(pb, law, options, held);
}

/// The answer of independent groups solved apart: the velocities from the gathered percussions,
/// as Frémond's methods write their own.
template <int N, int C>
void write_merged_answer(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                         const FremondLaw& /*law*/, const typename ContactSpaceT<N, C>::Rows& P,
                         const typename ContactSpaceT<N, C>::Rows& /*P_C*/, const VecT<C>& reaction,
                         const VecT<N>& /*dq*/, const VecT<N>& /*dq_C*/, ImpactResultT<N, C>& out) {
  scatter_solution(pb, cs, P, out);
  out.P_N_reaction = reaction;
}

/// No lane of one contact (solve_impact.cpp): its chain starts from the closed forms of its
/// modes, with their own checks.
template <int N, int C>
bool solve_one_contact_lane(const ImpactProblemT<N, C>& /*pb*/, const ContactSpaceT<N, C>& /*cs*/,
                            const FremondLaw& /*law*/, const SolverOptions& /*options*/,
                            ImpactResultT<N, C>& /*out*/) {
  return false;
}

/// An answer its certificate refuses: where a potential of an impacting contact is not a
/// pseudo-potential at the answer (not convex, negative, or not zero at 0), the law is outside its
/// domain, which is the finding (status unsupported, the contact named). False otherwise.
template <int N, int C>
bool refuse_outside_domain(const FremondLaw& law, ImpactResultT<N, C>& out) {
  for (Eigen::Index i = 0; i < out.D_NA.size(); ++i) {
    if (out.D_NA(i) > 0.0) continue;
    const int k = static_cast<int>(i);
    const bool defect =
        not_a_pseudo_potential(law.normal[k], 0.5 * (out.D_NA(i) + out.D_NE(i))) ||
        (law.has_tangential_potential() &&
         not_a_pseudo_potential(law.tangential_potential[k], 0.5 * (out.D_TA(i) + out.D_TE(i))));
    if (!defect) continue;
    out.solver.status = SolverStatus::unsupported;
    out.solver.message =
        "a potential of the contact admissibility.failed_contact names is not a pseudo-potential "
        "at the answer (not convex, negative, or not zero at 0): Frémond's law is defined for "
        "pseudo-potentials only (check_potential tests one)";
    out.admissibility.failed_contact = k;
    return true;
  }
  return false;
}

}  // namespace fremond::detail
