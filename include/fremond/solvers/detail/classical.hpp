#pragma once
/// @file Internal interface of the classical laws (Newton, Poisson, with or without Coulomb),
/// called by the driver in solve_impact.
#include <vector>

#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/detail/contact_space.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond::detail {

/// Solves a classical law on the active contacts of `cs`; fills percussions, velocities, phases,
/// `unique`, `solutions_found` and `out.solver` (not the admissibility, which the driver adds).
template <int MaxDofs, int MaxContacts>
void solve_classical(const ImpactProblemT<MaxDofs, MaxContacts>& problem,
                     const ContactSpaceT<MaxDofs, MaxContacts>& cs, const ImpactLaw& law,
                     const SolverOptions& options, ImpactResultT<MaxDofs, MaxContacts>& out);

/// Every solution found by mode enumeration (friction, up to 3 active contacts), else the one.
std::vector<ImpactResult> solve_classical_all(const ImpactProblem& problem, const ImpactLaw& law,
                                              const SolverOptions& options);

/// The scaled natural-map residual of a classical law at `result` (see laws/residual.hpp).
template <int MaxDofs, int MaxContacts>
double classical_residual(const ImpactProblemT<MaxDofs, MaxContacts>& problem, const ImpactLaw& law,
                          const ImpactResultT<MaxDofs, MaxContacts>& result);

}  // namespace fremond::detail
