// Every public enum of the library, by the names its to_string gives (one helper, bind_enum).
#include "fremond/admissibility/admissibility_report.hpp"
#include "fremond/curves/curves.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/scenes/presets.hpp"
#include "fremond/simulation/simulate.hpp"
#include "fremond/simulation/simulation_options.hpp"
#include "fremond/solvers/solver_status.hpp"
#include "python/bind_helpers.hpp"
#include "python/docstrings.hpp"

namespace fremond::python {

void bind_enums(py::module_& m) {
  using T = TangentialLaw;
  bind_enum<T>(m, "TangentialLaw", doc::kTangentialLaw, {T::none, T::potential, T::coulomb},
               &tangential_law_from_string);
  using S = SolverStatus;
  bind_enum<S>(m, "SolverStatus", doc::kSolverStatus,
               {S::not_run, S::converged, S::max_iterations, S::stalled, S::no_solution, S::failed,
                S::unsupported},
               &solver_status_from_string);
  using M = SolverMethod;
  bind_enum<M>(
      m, "SolverMethod", doc::kSolverMethod,
      {M::automatic, M::trivial, M::closed_form, M::scalar_newton, M::mode_enumeration, M::lemke,
       M::semismooth_newton, M::proximal, M::nlopt, M::impulse_integration, M::nsgs},
      &solver_method_from_string);
  using A = AttemptStart;
  bind_enum<A>(m, "AttemptStart", "Where a method of the chain started from.",
               {A::none, A::decoupled_guess, A::zero, A::newton_end, A::splitting_end, A::nlopt_end,
                A::velocity_newton_end, A::normal_rows, A::sweeps_end},
               &attempt_start_from_string);
  using C = StopCriterion;
  bind_enum<C>(
      m, "StopCriterion", doc::kStopCriterion,
      {C::none, C::exact, C::residual, C::step, C::iterations, C::nlopt, C::rounding, C::data},
      &stop_criterion_from_string);
  using I = Inequality;
  bind_enum<I>(m, "Inequality", doc::kInequality,
               {I::none, I::total_15, I::per_contact_15, I::reaction_17, I::dissipation_19,
                I::complementarity_16, I::fenchel_young, I::non_penetration},
               &inequality_from_string);
  bind_enum<Scaling>(m, "Scaling", doc::kScaling, {Scaling::library, Scaling::paper},
                     &scaling_from_string);
  using P = PaperLaw;
  bind_enum<P>(m, "PaperLaw", doc::kPaperLaw,
               {P::newton, P::newton_coulomb, P::poisson_coulomb, P::fremond_coulomb,
                P::fremond_viscous, P::stronge_coulomb},
               &paper_law_from_string);
  bind_enum<Integrator>(m, "Integrator", doc::kIntegrator,
                        {Integrator::event_driven, Integrator::moreau_jean},
                        &integrator_from_string);
  bind_enum<Phase>(m, "Phase", doc::kPhase, {Phase::event_driven, Phase::moreau_jean},
                   &phase_from_string);
  using R = SimulationStatus;
  bind_enum<R>(m, "SimulationStatus", doc::kSimulationStatus,
               {R::not_run, R::completed, R::max_impacts, R::impact_failed, R::contact_failed,
                R::event_search_failed, R::interrupted},
               &simulation_status_from_string);
  using K = ImpactKind;
  bind_enum<K>(m, "ImpactKind", doc::kImpactKind, {K::event, K::time_step, K::accumulation},
               &impact_kind_from_string);
}

}  // namespace fremond::python
