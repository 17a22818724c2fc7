#pragma once
// What the generic driver (solve_impact, law_residual, the independent groups) calls for Newton's
// and Poisson's laws: their solver chain (solvers/classical.cpp) and their residual
// (laws/restitution/residual.cpp). docs/architecture.md lists the hooks every law gives.
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "admissibility/detail/admissibility.hpp"
#include "fremond/potentials/registry.hpp"
#include "laws/detail/residuals.hpp"
#include "solvers/detail/classical.hpp"
#include "solvers/detail/classical_one_contact.hpp"

namespace fremond::detail {

/// The law from the problem file's `law` object (docs/problem-file.md), `name` one of its names;
/// InvalidArgument naming the file's key (under `where`) for a bad one
/// (laws/restitution/schema.cpp).
ImpactLaw read_law(std::type_identity<RestitutionLaw>, std::string_view name,
                   const nlohmann::json& j, int contacts, const PotentialRegistry& registry,
                   const std::string& where);

template <int N, int C>
double residual_of(const ImpactProblemT<N, C>& pb, const RestitutionLaw& law,
                   const ImpactResultT<N, C>& r) {
  return classical_residual(pb, law, r);
}

template <int N, int C>
void solve_chain(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                 const RestitutionLaw& law, const SolverOptions& options, ImpactResultT<N, C>& out,
                 ChainWorkspace& ws) {
  solve_classical(pb, cs, law, options, out, ws);
}

/// The lane of one contact (solve_impact.cpp): one approaching contact on a diagonal M, answered
/// by the chain's first stage, its closed form on scalars (classical_one_contact.hpp), without
/// the chain around it. False, `out` untouched, where the chain would start otherwise or the
/// closed form does not settle.
template <int N, int C>
bool solve_one_contact_lane(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                            const RestitutionLaw& law, const SolverOptions& options,
                            ImpactResultT<N, C>& out) {
  return classical::one_approaching_contact(cs, options) &&
         classical::settle_one_contact(pb, cs, law, options, out);
}

template <int N, int C>
std::vector<ImpactResultT<N, C>> solve_every_answer(const ImpactProblemT<N, C>& pb,
                                                    const RestitutionLaw& law,
                                                    const SolverOptions& options,
                                                    HeldContacts held) {
  return solve_classical_all(pb, law, options, held);
}

/// The answer of independent groups solved apart: q̇_A plus each group's velocity change (dq,
/// dq_C: Poisson's compression), since a group whose mode was solved for its velocities has them
/// more accurately than its percussions make them (classical_velocity_mode.hpp).
template <int N, int C>
void write_merged_answer(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                         const RestitutionLaw& law, const typename ContactSpaceT<N, C>::Rows& P,
                         const typename ContactSpaceT<N, C>::Rows& P_C, const VecT<C>& /*reaction*/,
                         const VecT<N>& dq, const VecT<N>& dq_C, ImpactResultT<N, C>& out) {
  const VecT<N> q = pb.qdot_A + dq, qC = pb.qdot_A + dq_C;
  write_classical_answer(pb, cs, law, P, P_C, out, &q, &qC);
}

/// Not dissipative by construction: its certificate's refusal is the finding (solve_impact.cpp).
template <int N, int C>
bool refuse_outside_domain(const RestitutionLaw& /*law*/, ImpactResultT<N, C>& /*out*/) {
  return false;
}

/// No terms of its own: the certificate holds it to (15) and non-penetration.
inline bool has_certificate_terms(const RestitutionLaw& /*law*/) {
  return false;
}
inline void certificate_terms(const RestitutionLaw& /*law*/, int /*i*/,
                              const CertificateContact& /*k*/, CertificateTerms& /*out*/) {}

}  // namespace fremond::detail
