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

/// Writes the percussions P (and Poisson's compression P_C) of the rows that take part (`cs`'s
/// row order) into `out`: velocities, percussions, contact velocities and, for Poisson, the phases.
/// The velocities are made from P (and P_C), or are `velocities` (and `compression_velocities`)
/// where given (a mode solved for its velocities and percussions together,
/// classical_velocity_mode.hpp).
template <int MaxDofs, int MaxContacts>
void write_classical_answer(const ImpactProblemT<MaxDofs, MaxContacts>& problem,
                            const ContactSpaceT<MaxDofs, MaxContacts>& cs, const ImpactLaw& law,
                            const typename ContactSpaceT<MaxDofs, MaxContacts>::Rows& P,
                            const typename ContactSpaceT<MaxDofs, MaxContacts>::Rows& P_C,
                            ImpactResultT<MaxDofs, MaxContacts>& out,
                            const VecT<MaxDofs>* velocities = nullptr,
                            const VecT<MaxDofs>* compression_velocities = nullptr);

/// Every solution found by mode enumeration (friction, up to 4 active contacts), else the one;
/// `held`: the contacts solved for.
template <int MaxDofs, int MaxContacts>
std::vector<ImpactResultT<MaxDofs, MaxContacts>> solve_classical_all(
    const ImpactProblemT<MaxDofs, MaxContacts>& problem, const ImpactLaw& law,
    const SolverOptions& options, HeldContacts held = HeldContacts::approaching);

/// The scaled natural-map residual of a classical law at `result` (see laws/residual.hpp).
/// `beyond_rounding`, if given, receives the same residual without the contacts whose every term
/// is within its rounding floor, min(16ε (|w| + |W_N,i|ᵀq + |W_T,i|ᵀq), 1e-6 v_scale) with
/// q = |q̇_A| + |q̇_E| (+ |q̇_C|): the solvers' stopping test, as Frémond's row_rounding_floor.
/// `percussions_rounded`: the percussions are the exact solution of their contact mode rounded to
/// double (refined, classical_refine.hpp); the floor then also holds the terms 16ε Σ_k |G_ik||P_k|
/// that this rounding moves the velocities by, up to `percussion_cap` v_scale. Never for an
/// unrefined answer: Lemke's pivots on cond(M) = 1e9 leave errors of 1e-5 that such a floor would
/// hide.
template <int MaxDofs, int MaxContacts>
double classical_residual(const ImpactProblemT<MaxDofs, MaxContacts>& problem, const ImpactLaw& law,
                          const ImpactResultT<MaxDofs, MaxContacts>& result,
                          double* beyond_rounding = nullptr, bool percussions_rounded = false,
                          double percussion_cap = 1e-10);

}  // namespace fremond::detail
