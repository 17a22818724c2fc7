#pragma once
/// @file The admissibility check with the contact velocities' rounding supplied by the caller, who
/// already has the Delassus matrix (solve_impact); the public check_admissibility computes it.
#include "contact_space/contact_space.hpp"
#include "fremond/admissibility/admissibility_report.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/laws/impact_problem.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond::detail {

/// True where φ is seen not to be a pseudo-potential (convex, ≥ 0, φ(0) = 0: docs/laws.md) near
/// an answer's mean velocity z: φ(0) ≠ 0, φ(z) < 0, or φ above a chord between two of the points
/// 0, ±z, z/2, 3z/2, 2z at its midpoint (beyond rounding). Independent of how well the answer is
/// solved: built on φ's values alone.
bool not_a_pseudo_potential(const Potential& phi, double z);

/// Per contact of the problem, how well its velocities D_E (hence z = (D_A + D_E)/2) are known
/// from rounding alone: 16ε (|D_A,j| + κ(M) Σ_k |G_jk||P_k|) over its rows (G is formed by a
/// solve with M, accurate to ε κ(M)). With an ill-conditioned G
/// the terms G_jk P_k cancel to a D_E much smaller than themselves (a mass ratio of 1e6), so z
/// carries their rounding, not ε|D_E|. Contacts that do not take part get 0.
///
/// With `percussion`, also per contact how well Frémond's stopping test pins its percussions
/// down: a row j passes at its rounding floor f_j = min(16ε (|D_A,j| + ½Σ_k|G_jk P_k| +
/// τ_j|P_j|), 1e-6 v_scale) (fremond_rows.hpp), and R_j = τ_j·(percussion error), so the error
/// may reach f_j/τ_j, τ_j = G_jj/2: on a row that barely moves any velocity (G_jj = 1e-7 beside
/// 1e-2) that is far above the tolerance-based bound.
template <int MaxDofs, int MaxContacts>
VecT<MaxContacts> velocity_rounding(const ContactSpaceT<MaxDofs, MaxContacts>& cs,
                                    const ImpactResultT<MaxDofs, MaxContacts>& result,
                                    VecT<MaxContacts>* percussion = nullptr);

/// The largest diagonal entry of the Delassus matrix G over the rows that take part (0 without
/// any): Frémond's stopping test bounds a row's percussion error by tolerance · v_scale / (G_max/2)
/// (fremond_rows.hpp, the weighted residual), which the certificate must allow for.
template <int MaxDofs, int MaxContacts>
double delassus_max(const ContactSpaceT<MaxDofs, MaxContacts>& cs) {
  return cs.rows() ? cs.G.diagonal().maxCoeff() : 0.0;
}

/// check_admissibility with `rounding` (and `percussion`, when given) from velocity_rounding and
/// `g_max` from delassus_max.
template <int MaxDofs, int MaxContacts>
AdmissibilityReportT<MaxContacts> check_admissibility(
    const ImpactProblemT<MaxDofs, MaxContacts>& problem, const ImpactLaw& law,
    const ImpactResultT<MaxDofs, MaxContacts>& result, const SolverOptions& options,
    const VecT<MaxContacts>& rounding, double g_max, const VecT<MaxContacts>* percussion = nullptr);

}  // namespace fremond::detail
