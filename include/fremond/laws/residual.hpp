#pragma once
/// @file One residual per law, shared by every solver and by the tests (scaled by the velocity
/// scale).
#include "fremond/core/impact_problem.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/impact_result.hpp"

namespace fremond {

/// ‖R‖∞ / v_scale of the law's natural-map residual at the answer in `result`, with v_scale the
/// largest |D_A| over the contacts that take part. Zero exactly when `result` satisfies the law.
///  - Frémond: R = z − prox_{τψ}(z − τP) per row (ψ = φ_N + I_{[D_NA/2, ∞)} normal; φ_T or
///    μ|P_N||·| tangential), with τ = G_ii/2 (a natural scale of the row).
///  - Newton: min(D_NE + e D_NA, P_N·g) with Coulomb's natural map on (P_T, D_TE).
///  - Poisson: the same per phase (needs the phases in `result`).
/// Classical laws: the law at the velocities the percussions make; where that is above 64ε, the
/// smaller of it and the law at the result's own q̇_E, if q̇_E balances the percussions,
/// M(q̇_E − q̇_A) = W_N P_N + W_T P_T, to the rounding of that equation's terms. A result whose
/// q̇_E and P disagree is judged by its P.
/// Frémond's law: velocities are recomputed from the percussions.
/// A result whose P_N or P_T is not of the problem's contact count is refused with
/// InvalidArgument("result") naming the sizes, for every law.
template <int MaxDofs, int MaxContacts>
double law_residual(const ImpactProblemT<MaxDofs, MaxContacts>& problem, const ImpactLaw& law,
                    const ImpactResultT<MaxDofs, MaxContacts>& result);

}  // namespace fremond
