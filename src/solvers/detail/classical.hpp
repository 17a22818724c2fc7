#pragma once
/// @file Internal interface of the classical laws (Newton, Poisson, with or without Coulomb),
/// called by the driver in solve_impact.
#include <vector>

#include "contact_space/contact_space.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond::detail {

struct ChainWorkspace;  // chain_workspace.hpp

/// Solves a classical law on the active contacts of `cs`; fills percussions, velocities, phases,
/// `unique`, `solutions_found` and `out.solver` (not the admissibility, which the driver adds).
/// The stages' storage is taken from `ws`.
template <int MaxDofs, int MaxContacts>
void solve_classical(const ImpactProblemT<MaxDofs, MaxContacts>& problem,
                     const ContactSpaceT<MaxDofs, MaxContacts>& cs, const RestitutionLaw& law,
                     const SolverOptions& options, ImpactResultT<MaxDofs, MaxContacts>& out,
                     ChainWorkspace& ws);

/// Writes the percussions P (and Poisson's compression P_C) of the rows that take part (`cs`'s
/// row order) into `out`: velocities, percussions, contact velocities and, for Poisson, the phases.
/// The velocities are made from P (and P_C), or are `velocities` (and `compression_velocities`)
/// where given (a mode solved for its velocities and percussions together,
/// classical_velocity_mode.hpp).
template <int MaxDofs, int MaxContacts>
void write_classical_answer(const ImpactProblemT<MaxDofs, MaxContacts>& problem,
                            const ContactSpaceT<MaxDofs, MaxContacts>& cs,
                            const RestitutionLaw& law,
                            const typename ContactSpaceT<MaxDofs, MaxContacts>::Rows& P,
                            const typename ContactSpaceT<MaxDofs, MaxContacts>::Rows& P_C,
                            ImpactResultT<MaxDofs, MaxContacts>& out,
                            const VecT<MaxDofs>* velocities = nullptr,
                            const VecT<MaxDofs>* compression_velocities = nullptr);

/// Every solution found by mode enumeration (friction, up to 4 active contacts), else the one;
/// `held`: the contacts solved for.
template <int MaxDofs, int MaxContacts>
std::vector<ImpactResultT<MaxDofs, MaxContacts>> solve_classical_all(
    const ImpactProblemT<MaxDofs, MaxContacts>& problem, const RestitutionLaw& law,
    const SolverOptions& options, HeldContacts held = HeldContacts::approaching);

}  // namespace fremond::detail
