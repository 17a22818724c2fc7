#pragma once
/// @file Enumerations of the solver report, each with to_string / from_string (CLI, bindings).
#include <cstdint>
#include <string_view>

namespace fremond {

/// How a solve ended. Every value is documented by the test that sets it.
enum class SolverStatus : std::uint8_t {
  not_run,         ///< the default: nothing was solved.
  converged,       ///< the law's residual (laws/residual.hpp) ≤ tolerance × velocity scale, or
                   ///< (criterion `rounding`) each row above it is at its own rounding floor.
  max_iterations,  ///< the iteration budget ran out with the residual above tolerance.
  stalled,         ///< no further decrease of the residual was possible in floating point and
                   ///< the residual is above tolerance.
  no_solution,     ///< the law has no solution for these data (e.g. Painlevé-type Coulomb cases).
  failed,          ///< numerical breakdown (non-finite values); the answer is not usable.
  unsupported,     ///< the chosen method cannot solve this law with these potentials, or a
                   ///< potential is not a pseudo-potential (not convex, negative, or φ(0) ≠ 0),
                   ///< as the certificate finds it at the answer.
};

/// Which method produced the answer.
enum class SolverMethod : std::uint8_t {
  automatic,  ///< options only: let the driver choose (closed form → Newton → prox → NLopt).
  trivial,    ///< no contact takes part (all D_NA > 0): no percussion.
  closed_form,          ///< piecewise-linear law on one contact, or a single exact prox.
  scalar_newton,        ///< one decoupled contact: one scalar root per mode; or, Frémond's law
                        ///< without Coulomb on one degree of freedom where every other method
                        ///< failed, the velocity-space problem's root by bisection on ∂F.
  mode_enumeration,     ///< contact modes tried: every one (small problems; finds all solutions),
                        ///< or, Frémond + Coulomb on 2-4 contacts, until one satisfies the law.
  lemke,                ///< lexicographic Lemke on the law's LCP (classical laws).
  semismooth_newton,    ///< Newton on the prox-based (natural-map) residual, with a line search.
  proximal,             ///< accelerated proximal-gradient iteration in contact space.
  nlopt,                ///< NLopt on the velocity-space minimisation (value and subgradient only).
  impulse_integration,  ///< Stronge's law on coupled contacts: the impact integrated in impulse
                        ///< space with Liu, Zhao and Brogliato's distributing law.
  nsgs,  ///< nonsmooth Gauss–Seidel over the contacts of a sparse problem, each contact's law
         ///< solved exactly given the others (sparse/sparse_solver.hpp).
};

/// Which stopping criterion fired.
enum class StopCriterion {
  none,        ///< not stopped (not run).
  exact,       ///< a closed form or a finite enumeration: no iteration to stop.
  residual,    ///< ‖R‖∞ ≤ tolerance × velocity scale.
  step,        ///< the step became smaller than rounding; residual checked after.
  iterations,  ///< the iteration budget.
  nlopt,       ///< NLopt's own criterion (its code is kept in the report).
  rounding,    ///< converged, but the tolerance asked for is below what floating point can
             ///< resolve: each row above it is within 16ε (|D_A,j| + ½Σ_k|G_jk P_k| + τ_j|P_j|),
             ///< the rounding of forming it, and within 1e-6 of the velocity scale (the
             ///< classical laws: each contact's terms within 16ε (|w| + |W_i|ᵀ(|q̇_A| +
             ///< |q̇_E|)), classical_residual); the reported residual is then above tolerance.
  data,  ///< converged as far as the problem's numbers are known (sparse problems read from
         ///< files, ContactProblem::G_rounding): the sweeps stalled with each contact's
         ///< residual within what the data's digits leave undetermined of its velocities.
};

std::string_view to_string(SolverStatus s);
std::string_view to_string(SolverMethod m);
std::string_view to_string(StopCriterion c);
/// Each throws InvalidArgument naming the text and the accepted values.
SolverStatus solver_status_from_string(std::string_view s);
SolverMethod solver_method_from_string(std::string_view s);
StopCriterion stop_criterion_from_string(std::string_view s);

}  // namespace fremond
