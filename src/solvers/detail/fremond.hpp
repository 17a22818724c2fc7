#pragma once
// Private interface of Frémond's law solvers (SPEC §2): the driver calls solve_fremond; every
// method works on the same rows (fremond_rows.hpp) and ends in finish_fremond.
#include <vector>

#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/detail/contact_space.hpp"
#include "fremond/solvers/solver_options.hpp"
#include "fremond_rows.hpp"

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
                   const ImpactLaw& law, const SolverOptions& options, ImpactResultT<N, C>& out);

/// Every solution found: exact for one contact with Coulomb (mode enumeration), else one.
template <int N, int C>
std::vector<ImpactResultT<N, C>> solve_fremond_all(const ImpactProblemT<N, C>& pb,
                                                   const ImpactLaw& law,
                                                   const SolverOptions& options);

/// Semismooth Newton on R(P) = z − prox(z − τP) from the P given; P is overwritten.
template <int N, int C>
MethodOutcome semismooth_newton(const FremondRowsT<N, C>& rows,
                                typename FremondRowsT<N, C>::Rows& P, const SolverOptions& options);

/// Newton on the velocity-space problem of SPEC §2 (n unknowns instead of one per row), for a law
/// without Coulomb whose potentials all have a prox; P (the start, then the answer) in contact
/// space. Converged only when the answer passes the law's own stopping test: an answer that needs
/// a reaction does not (fremond_velocity_newton.cpp).
template <int N, int C>
MethodOutcome velocity_space_newton(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows,
                                    typename FremondRowsT<N, C>::Rows& P,
                                    const SolverOptions& options);

/// Accelerated proximal gradient (FISTA with restart) on the dual in contact space.
template <int N, int C>
MethodOutcome proximal_iterations(const FremondRowsT<N, C>& rows,
                                  typename FremondRowsT<N, C>::Rows& P,
                                  const SolverOptions& options);

/// NLopt (SLSQP) on the velocity-space minimisation of SPEC §2; uses value and one subgradient.
template <int N, int C>
MethodOutcome nlopt_velocity_space(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows,
                                   typename FremondRowsT<N, C>::Rows& P,
                                   const SolverOptions& options);

/// Scaled Frémond residual of an answer (law_residual for Frémond's law).
template <int N, int C>
double fremond_residual(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                        const ImpactResultT<N, C>& result);

}  // namespace fremond::detail
