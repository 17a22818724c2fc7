#pragma once
/// @file The residual of each law family (laws/residual.hpp dispatches to them); the solvers report
/// and stop on the same functions.
#include "contact_space/contact_space.hpp"
#include "fremond/core/impact_problem.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/impact_result.hpp"

namespace fremond::detail {

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
double classical_residual(const ImpactProblemT<MaxDofs, MaxContacts>& problem,
                          const RestitutionLaw& law,
                          const ImpactResultT<MaxDofs, MaxContacts>& result,
                          double* beyond_rounding = nullptr, bool percussions_rounded = false,
                          double percussion_cap = 1e-10);

/// classical_residual of an answer on the problem `cs` was built from, through cs's factor of M
/// and its self_delassus() scales, computed once a build: the same number, to the last bit.
template <int MaxDofs, int MaxContacts>
double classical_residual(const ImpactProblemT<MaxDofs, MaxContacts>& problem,
                          const ContactSpaceT<MaxDofs, MaxContacts>& cs, const RestitutionLaw& law,
                          const ImpactResultT<MaxDofs, MaxContacts>& result,
                          double* beyond_rounding = nullptr, bool percussions_rounded = false,
                          double percussion_cap = 1e-10);

/// classical_residual at the answer's own velocities (its D_NE, D_TE from q̇_E; Poisson's D_NC,
/// D_TC from q̇_C), where that is the same number to within the tolerance: M diagonal in cs (each
/// velocity q̇_A + M⁻¹W P with one rounding an entry, as the residual's own velocities are) and the
/// velocities' rounding, 2(rows + 2)ε Σ|W||M⁻¹W||P| over every contact (P and Poisson's P_C, the
/// active rows' percussions), at most 45 % of the tolerance times the velocity scale. True, with
/// the residual in *value, when those hold and the residual is at most 45 % of the tolerance too:
/// the law's residual from the data is then within the tolerance, and the answer converged as the
/// data would say. False otherwise: the caller measures from the data.
template <int MaxDofs, int MaxContacts>
bool residual_at_own_velocities(const ImpactProblemT<MaxDofs, MaxContacts>& problem,
                                const ContactSpaceT<MaxDofs, MaxContacts>& cs,
                                const RestitutionLaw& law,
                                const typename ContactSpaceT<MaxDofs, MaxContacts>::Rows& P,
                                const typename ContactSpaceT<MaxDofs, MaxContacts>::Rows& P_C,
                                const ImpactResultT<MaxDofs, MaxContacts>& result, double tolerance,
                                double* value);

/// Scaled Frémond residual of an answer (law_residual for Frémond's law).
template <int N, int C>
double fremond_residual(const ImpactProblemT<N, C>& pb, const FremondLaw& law,
                        const ImpactResultT<N, C>& result);

}  // namespace fremond::detail
