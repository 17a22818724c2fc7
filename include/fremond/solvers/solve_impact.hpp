#pragma once
/// @file The one entry point for every law: validate, the law's own solver chain
/// (docs/solvers.md), then the admissibility certificate (docs/concepts.md) on the answer.
#include <vector>

#include "fremond/core/impact_problem.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond {

/// Solves one impact. Throws InvalidArgument for an invalid problem, law or options; a solver that
/// does not converge says so in result.solver.status (never an exception). For small problems
/// (SmallImpactProblem) the solve allocates nothing on the heap, except for potentials whose prox
/// is computed through the NLopt fallback. A heap-stored problem (ImpactProblem) that fits the
/// small form (fits_small) is solved in it: the only allocations are then the result's vectors.
///
/// Contacts that G = WᵀM⁻¹W does not couple (two bodies in one problem) form independent groups,
/// each solved as a problem of its own, to its own velocity scale (docs/concepts.md and
/// docs/laws.md: the laws separate). The report is then the hardest group's (the first not
/// converged, else the one that worked most): its method, status and message; `iterations` is
/// summed over the groups, `residual` is the largest group residual, each relative to its group's
/// velocities.
template <int MaxDofs, int MaxContacts>
ImpactResultT<MaxDofs, MaxContacts> solve_impact(
    const ImpactProblemT<MaxDofs, MaxContacts>& problem, const ImpactLaw& law,
    const SolverOptions& options = {});

/// Every solution found: for laws with friction on up to 4 contacts (and Frémond + Coulomb on one
/// contact, exactly) by enumerating contact modes; otherwise the single answer of solve_impact.
/// Each result has `unique` and `solutions_found` set. An empty list means no solution exists.
/// Independent groups of contacts (see solve_impact) give the product of the groups' lists.
/// Solved in the storage solve_impact uses, so a unique answer is solve_impact's to the last bit.
std::vector<ImpactResult> solve_impact_all(const ImpactProblem& problem, const ImpactLaw& law,
                                           const SolverOptions& options = {});

namespace detail {
/// solve_impact in the problem's own storage, without moving a heap-stored problem that fits into
/// the small form. For tests that exercise the heap-stored code on small problems.
template <int MaxDofs, int MaxContacts>
ImpactResultT<MaxDofs, MaxContacts> solve_impact_in_own_storage(
    const ImpactProblemT<MaxDofs, MaxContacts>& problem, const ImpactLaw& law,
    const SolverOptions& options = {});
}  // namespace detail

}  // namespace fremond
