#pragma once
/// @file The admissibility check with the contact velocities' rounding supplied by the caller, who
/// already has the Delassus matrix (solve_impact); the public check_admissibility computes it.
#include "contact_space/contact_space.hpp"
#include "fremond/admissibility/admissibility_report.hpp"
#include "fremond/core/impact_problem.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/potentials/potential.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond::detail {

/// True where φ is seen not to be a pseudo-potential (convex, ≥ 0, φ(0) = 0: docs/laws.md) near
/// an answer's mean velocity z: φ(0) ≠ 0, φ(z) < 0, or φ above a chord between two of the points
/// 0, ±z, z/2, 3z/2, 2z at its midpoint (beyond rounding). Independent of how well the answer is
/// solved: built on φ's values alone.
bool not_a_pseudo_potential(const Potential& phi, double z);

/// Fenchel–Young gap of φ at (z, s) beyond what the rounding of z (dz) and s (ds) explains, scaled
/// by the size of its terms and by `energy`, the impact's energy scale (admissibility.cpp).
double scaled_gap(const Potential& phi, double z, double s, double energy, double dz, double ds);

/// One contact of an answer as a law's own certificate terms see it (its certificate_terms).
struct CertificateContact {
  bool separating = false;    ///< D_NA > 0: held by the reaction alone (docs/concepts.md)
  double zN = 0.0, zT = 0.0;  ///< mean velocities (D_A + D_E)/2
  double P_N = 0.0, P_T = 0.0, D_NE = 0.0, D_TE = 0.0;
  double P_N_reaction = 0.0;            ///< the reaction part of P_N the result reports (0 if none)
  double rounding = 0.0;                ///< how well D_E is known from rounding (velocity_rounding)
  double percussion_floor = 0.0;        ///< how well the stopping test pins P down (0 if unknown)
  double solved_to = 0.0;               ///< the solver's stopping tolerance
  double v_scale = 0.0, p_scale = 0.0;  ///< the impact's velocity and percussion scales
  double g_max = 0.0;                   ///< delassus_max
  double energy = 0.0;                  ///< p_scale · v_scale
};

/// What a law adds to the certificate for one contact: the reaction part of P_N (checked by (16)
/// and (17); the rest of P_N by (19)), the complementarity (16) and Fenchel–Young violations.
struct CertificateTerms {
  double reaction = 0.0;
  double complementarity = 0.0;
  double fenchel_young = 0.0;
};

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

/// An answer to a problem of one contact as its certificate reads it: its scalars, and q̇_E (the
/// problem's dofs entries).
struct OneContactFacts {
  const double* qdot_E = nullptr;
  bool takes_part = true;
  double P_N = 0.0, P_T = 0.0, D_NA = 0.0, D_TA = 0.0, D_NE = 0.0, D_TE = 0.0;
  double P_N_reaction = 0.0;  ///< the reaction part of P_N (0 where the law has none)
  double energy_change = 0.0;
  SolverMethod method = SolverMethod::automatic;  ///< the method that answered
};

/// The facts of a filled one-contact result (check_one_contact's reading of it).
template <int MaxDofs, int MaxContacts>
OneContactFacts one_contact_facts(const ImpactResultT<MaxDofs, MaxContacts>& r) {
  return {.qdot_E = r.qdot_E.data(),
          .takes_part = r.takes_part(0) != 0,
          .P_N = r.P_N(0),
          .P_T = r.P_T(0),
          .D_NA = r.D_NA(0),
          .D_TA = r.D_TA(0),
          .D_NE = r.D_NE(0),
          .D_TE = r.D_TE(0),
          .P_N_reaction = r.P_N_reaction.size() == 1 ? r.P_N_reaction(0) : 0.0,
          .energy_change = r.energy_change,
          .method = r.solver.method};
}

/// check_one_contact on an answer's scalars (a filled one), to the same bits: what a caller that
/// keeps no result certifies with (solve_batch's columns).
template <int MaxDofs, int MaxContacts>
AdmissibilityReportT<MaxContacts> certify_one_contact(
    const ImpactProblemT<MaxDofs, MaxContacts>& problem, const ImpactLaw& law,
    const OneContactFacts& facts, const SolverOptions& options,
    const ContactSpaceT<MaxDofs, MaxContacts>& cs);

/// check_admissibility of an answer to a problem of one contact, computed as velocity_rounding and
/// check_admissibility compute it, to the same bits, from its scalars (the law's own terms
/// included), with `cs` the contact space it was solved on.
template <int MaxDofs, int MaxContacts>
AdmissibilityReportT<MaxContacts> check_one_contact(
    const ImpactProblemT<MaxDofs, MaxContacts>& problem, const ImpactLaw& law,
    const ImpactResultT<MaxDofs, MaxContacts>& result, const SolverOptions& options,
    const ContactSpaceT<MaxDofs, MaxContacts>& cs);

}  // namespace fremond::detail
