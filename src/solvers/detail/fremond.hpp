#pragma once
// Private interface of Frémond's law solvers (docs/laws.md): the driver calls solve_fremond; every
// method works on the same rows (fremond_rows.hpp) and ends in finish_fremond.
#include <vector>

#include "contact_space/contact_space.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/solver_options.hpp"
#include "laws/fremond/rows.hpp"

namespace fremond::detail {

/// How one iterative method ended, before the answer is written into a result.
struct MethodOutcome {
  SolverStatus status = SolverStatus::not_run;
  StopCriterion criterion = StopCriterion::none;
  int iterations = 0;
  double residual = 0.0;  ///< ‖R‖∞ (unscaled)
  /// True when `residual` is already the law's plain residual ‖R(P)‖∞ of the returned P (then
  /// the driver need not evaluate it again).
  bool residual_is_plain = false;
  const char* message = "not run";
  int native_code = 0;
};

template <int N, int C>
void solve_fremond(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                   const FremondLaw& law, const SolverOptions& options, ImpactResultT<N, C>& out);

/// Every solution found: exact for one contact with Coulomb (mode enumeration), else one;
/// `held`: the contacts solved for (separating_contacts.hpp).
template <int N, int C>
std::vector<ImpactResultT<N, C>> solve_fremond_all(const ImpactProblemT<N, C>& pb,
                                                   const FremondLaw& law,
                                                   const SolverOptions& options,
                                                   HeldContacts held = HeldContacts::approaching);

/// Semismooth Newton on R(P) = z − prox(z − τP) from the P given; P is overwritten.
template <int N, int C>
MethodOutcome semismooth_newton(const FremondRowsT<N, C>& rows,
                                typename FremondRowsT<N, C>::Rows& P, const SolverOptions& options);

/// Newton on the velocity-space problem of docs/laws.md (n unknowns instead of one per row), for a
/// law without Coulomb whose potentials all have a prox; P (the start, then the answer) in contact
/// space. Converged only when the answer passes the law's own stopping test: an answer that needs
/// a reaction does not (fremond_velocity_newton.cpp).
template <int N, int C>
MethodOutcome velocity_space_newton(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows,
                                    typename FremondRowsT<N, C>::Rows& P,
                                    const SolverOptions& options);

/// Frémond's law without Coulomb on one degree of freedom: docs/laws.md's velocity-space problem is
/// scalar and strongly convex, and bisection on the sign of its subdifferential finds u = v − q̇_A
/// to the last bit (q̇_E = q̇_A + 2u), whatever the percussions' scale; P gets each row's
/// percussion in −∂ψ_j(z_j) with Σ W_j P_j = 2Mu, the least-norm choice where rows are
/// set-valued (fremond_one_dof.cpp). False, P and u untouched, where it does not apply (several
/// dofs, Coulomb, a potential without its subdifferential, an empty domain).
template <int N, int C>
bool solve_one_dof(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows,
                   typename FremondRowsT<N, C>::Rows& P, double& u);

/// Accelerated proximal gradient (FISTA with restart) on the dual in contact space.
template <int N, int C>
MethodOutcome proximal_iterations(const FremondRowsT<N, C>& rows,
                                  typename FremondRowsT<N, C>::Rows& P,
                                  const SolverOptions& options);

/// NLopt (SLSQP) on the velocity-space minimisation of docs/laws.md; uses value and one
/// subgradient.
template <int N, int C>
MethodOutcome nlopt_velocity_space(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows,
                                   typename FremondRowsT<N, C>::Rows& P,
                                   const SolverOptions& options);

/// Frémond + Coulomb (power normal laws) solved in the contact mode of the answer P: each normal
/// row free or held by its reaction (P_N_reaction > 0), each tangential row sticking or sliding,
/// by Newton on the mode's equations z_E = t_E(P) for the rows E whose velocity the mode fixes
/// (free normals: z_N = −sign(P_N)(|P_N|/k)^(1/(p−1)); reactions: D_NE = 0; sticking: z_T = 0),
/// sliding percussions σμ|P_N|. Where the columns W_E are dependent, the equations along their
/// null space N read Nᵀt_E(P) = Nᵀw_E exactly (Nᵀz_E = (W_E N)ᵀq̄ + Nᵀw_E), in place of
/// D_A + G P/2, which cancels to its rounding where a normal law is steep at z_N = 0 (p ≤ 1.5 at
/// small speeds): the rows so left free in double precision, with the sticking contacts' tangents,
/// then get the split of their percussions that the law's exact conditions make, not one the
/// rounding allows. Rows that break the mode's inequalities change mode and Newton runs again;
/// where that ends in no root or cycles, every mode of up to 4 contacts (6^a) is solved from the
/// answer and the feasible root nearest to it is taken. True, P replaced, when the answer passes
/// the law's stopping test; false, P untouched, when no mode gives one (Newton stalls, a mode
/// leaves a percussion undetermined, or a null direction mixes a free row with a reaction: a z_N
/// far below the rounding of that reaction's D_NA).
template <int N, int C>
bool solve_in_coulomb_mode(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows,
                           typename FremondRowsT<N, C>::Rows& P,
                           const typename ImpactResultT<N, C>::CVec& P_N_reaction,
                           const SolverOptions& options);

}  // namespace fremond::detail
