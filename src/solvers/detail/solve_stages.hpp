#pragma once
/// @file The driver's stages after validation (solve_impact.cpp), shared by the one-shot
/// solve_impact and the prepared ImpactSolver.
#include "contact_space/contact_space.hpp"
#include "fremond/core/impact_problem.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond::detail {

struct ChainWorkspace;  // chain_workspace.hpp

/// Solves a validated problem whose contact space `cs` was built on the approaching contacts: the
/// law's chain (by independent groups), again on every contact where the answer drives a
/// separating one into its obstacle (cs is then rebuilt), and the certificate, into `out`, which
/// must be a result as default-constructed (the chain reads its attempt log and flags). The
/// chain's storage is taken from `ws` (kept by a caller that solves again).
template <int N, int C>
void solve_on_contact_space(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                            const SolverOptions& options, ContactSpaceT<N, C>& cs,
                            ImpactResultT<N, C>& out, ChainWorkspace& ws);

/// solve_impact_in_own_storage's work with the answer written into `out`, a result of earlier
/// solves (cleared first): the batch solves into the results it is given. Throws before
/// touching `out` where the problem, the law or the options are refused.
template <int N, int C>
void solve_impact_into(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                       const SolverOptions& options, ImpactResultT<N, C>& out);

}  // namespace fremond::detail
