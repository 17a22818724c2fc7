#pragma once
/// @file Simulating a scene: exact flights, every impact, accumulations, Moreau–Jean.
///
/// The run starts in the integrator's phase. In the event-driven phase the body flies exactly
/// (free_flight.hpp) until the first contact event (event_detection.hpp); every contact that closes
/// then (within options.simultaneity_tolerance) or touches enters one impact, solved with the
/// scene's law by solve_impact. Two things end the phase:
///  - an accumulation of impacts (bouncing with e < 1 has infinitely many impacts in finite time):
///    options.accumulation_impacts intervals between impacts, each shorter than the previous one
///    and than options.accumulation_interval. The geometric tail of the intervals gives the
///    accumulation time t∞ = t_k + Δ_k r/(1 − r), r = Δ_k/Δ_{k−1} (exact for a bouncing ball),
///    which the log and the result report. The touching contacts lose the small normal velocity
///    of their last bounce (an M-orthogonal projection, which only lowers the kinetic energy) and
///    Moreau–Jean integrates on from t_k with them closed: the tail's remaining bounces are below
///    the resolution of a step, while the rest of the body (a rotation, another contact coming
///    down, friction) goes on being integrated;
///  - a persistent contact: a contact touching at rest (|D_N| ≤ velocity_tolerance) that free
///    flight would push into its obstacle. Moreau–Jean handles the resting, sliding or rocking.
/// The Moreau–Jean phase hands back to event-driven once options.return_after_free_steps steps in
/// a row had no contact. Time-stepping rather than a smooth persistent-contact phase, because after
/// an accumulation the contacts of a bar stick, slip, rock, lift off and come down again in any
/// order: a time-stepping scheme takes every such change in its stride, where a smooth phase would
/// need an event search for each contact-mode switch and a Painlevé-safe force law.
///
/// Moreau–Jean step (θ = 1/2, Jean 1999; Acary & Brogliato 2008), from (q_k, v_k), step h:
///  1. active contacts: those that free flight would close within the step (g + hg' + h²g''/2 ≤ 0);
///  2. impact: the active contacts approaching faster than twice what gravity and rotation add to
///     D_N in one step (D_N < −2h(g + ω²|r|)), and not hit in the previous step, get the scene's
///     law at the velocity level, v_k → v_E (logged as an impact of kind time_step). Slower
///     approaches are persistent contact: restitution below the resolution of a step would only
///     chatter;
///  3. contacts still approaching close plastically at once (persistent_contact.hpp with h = 0);
///  4. the active contacts carry the persistent-contact impulse against gravity over the step:
///     Signorini on the mean normal velocity, Coulomb on the end velocity (or on the mean in a
///     step where that would create energy), v_E → v_{k+1} (persistent_contact.hpp);
///  5. q_{k+1} = q_k + h (v_E + v_{k+1})/2.
/// Free steps are exact ballistic steps, so the energy is constant between contacts; steps 3-5
/// never create energy (the change of energy of a step is exactly P·z), so a step with contact
/// creates energy only through the law's own impact (step 2), which the log flags.
///
/// Runs are reproducible to the last bit: no threads, no clocks, no state outside the call.
/// With no observer (or one that stores nothing) a run of a scene with at most 4 contacts in any
/// impact performs no heap allocation after its set-up, except inside solve_impact for potentials
/// that need the NLopt fallback. The library prints nothing; progress goes to the observer.
#include <array>
#include <limits>
#include <string_view>

#include "fremond/admissibility/admissibility_report.hpp"
#include "fremond/scenes/scene.hpp"
#include "fremond/simulation/simulation_options.hpp"
#include "fremond/solvers/impact_result.hpp"

namespace fremond {

/// How a run ended.
enum class SimulationStatus {
  not_run,         ///< the default.
  completed,       ///< reached options.t_end.
  max_impacts,     ///< stopped after options.max_impacts impacts.
  impact_failed,   ///< the impact solver did not converge (its report is in the last impact), or
                   ///< a state the run reached overflows what an impact computes (the message
                   ///< says which value; no impact is logged for it).
  contact_failed,  ///< no persistent-contact mode satisfies the law (Painlevé-type), or more than
                   ///< four contacts closed at once in a Moreau–Jean step.
  event_search_failed,  ///< a free flight's event search spent options.max_gap_evaluations
                        ///< without deciding where the next event is (the body turns too fast);
                        ///< the run stops at the start of that flight.
  interrupted,          ///< the observer asked the run to stop (stop_requested()); the state and
                        ///< everything observed are those of the time it stopped at.
};
std::string_view to_string(SimulationStatus s);
SimulationStatus simulation_status_from_string(std::string_view s);

/// What produced an entry of the impact log.
enum class ImpactKind {
  event,         ///< an impact of the event-driven phase, with the scene's law.
  time_step,     ///< the impact part of a Moreau–Jean step, with the scene's law.
  accumulation,  ///< the persistent-contact step closing an accumulation of impacts.
};
std::string_view to_string(ImpactKind k);
ImpactKind impact_kind_from_string(std::string_view s);

/// One point of the trajectory.
struct TrajectorySample {
  double t = 0.0;
  PlanarState state;
  double energy = 0.0;  ///< ½ q̇ᵀMq̇ + m g y.
  Phase phase = Phase::event_driven;
};

/// One entry of the impact log. Per-contact arrays hold the contacts of the impact, in the order
/// of `contacts` (scene contact indices).
struct ImpactRecord {
  using CVec = VecT<kMaxSceneContacts>;
  long index = 0;  ///< 0, 1, ... over the log.
  double t = 0.0;
  ImpactKind kind = ImpactKind::event;
  int contact_count = 0;
  std::array<int, kMaxSceneContacts> contacts{};
  Eigen::Vector3d q = Eigen::Vector3d::Zero();
  Eigen::Vector3d qdot_A = Eigen::Vector3d::Zero(), qdot_E = Eigen::Vector3d::Zero();
  CVec P_N, P_T, D_NA, D_NE, D_TA, D_TE;
  double energy_A = 0.0, energy_E = 0.0;  ///< total energy just before and just after.
  bool admissible = true;                 ///< docs/concepts.md certificate of the law's answer.
  Inequality failed = Inequality::none;   ///< the first inequality that failed.
  int failed_contact = -1;                ///< scene contact index of a per-contact failure.
  double violation = 0.0;
  bool unique = true;
  SolverReport
      solver;  ///< the impact solver's report (method `closed_form` for kind accumulation).
  /// kind accumulation: the accumulation time t∞ the run continues from (t is the last impact).
  double accumulation_limit = std::numeric_limits<double>::quiet_NaN();
};

/// Receives the run as it goes. Every hook has an empty default.
class SimulationObserver {
 public:
  virtual ~SimulationObserver() = default;
  /// Samples on the grid of options.sample_interval, at t = 0 and t_end, and around every impact.
  virtual void on_sample(const TrajectorySample& /*sample*/) {}
  virtual void on_impact(const ImpactRecord& /*impact*/) {}
  /// A change of phase at time t.
  virtual void on_phase(double /*t*/, Phase /*from*/, Phase /*to*/, std::string_view /*why*/) {}
  /// Called at most about a hundred times per run as time advances, and once at the end, for a
  /// progress bar.
  virtual void on_progress(double /*t*/, double /*t_end*/) {}
  /// Asked before every flight and every Moreau–Jean step: true stops the run there, with status
  /// interrupted (a user's Ctrl-C, a deadline).
  virtual bool stop_requested() { return false; }
};

/// The summary of a run.
struct SimulationResult {
  SimulationStatus status = SimulationStatus::not_run;
  std::string_view message = "not run";  ///< a static explanation.
  double t = 0.0;                        ///< where the run stopped.
  PlanarState state;                     ///< the state there.
  Phase phase = Phase::event_driven;     ///< the phase there.
  double energy_initial = 0.0, energy_final = 0.0;
  long impacts = 0;               ///< impacts with the scene's law (kinds event and time_step).
  long event_impacts = 0;         ///< of which in the event-driven phase.
  long inadmissible_impacts = 0;  ///< impacts whose docs/concepts.md certificate failed.
  double first_inadmissible_time = std::numeric_limits<double>::quiet_NaN();
  int accumulations = 0;  ///< accumulations of impacts closed.
  double first_accumulation_time = std::numeric_limits<double>::quiet_NaN();  ///< its t∞.
  long steps = 0;  ///< Moreau–Jean steps.
  int phase_switches = 0;
  /// The largest energy increase over any flight, step, accumulation or admissible impact (J):
  /// rounding only. Inadmissible impacts are left out: their gain is the law's, and they are
  /// counted in inadmissible_impacts.
  double max_energy_rise = 0.0;
  long gap_evaluations = 0;  ///< work of the event search.

  bool ok() const {
    return status == SimulationStatus::completed || status == SimulationStatus::max_impacts;
  }
};

/// Throws InvalidArgument("initial", ...) when the scene's initial state puts a contact point
/// inside an obstacle, deeper than options.gap_tolerance: no impact would push it out. simulate()
/// and the scene-file reader both call it.
void validate_start(const Scene& scene, const SimulationOptions& options);

/// Runs `scene` (validated on a copy; throws InvalidArgument for an invalid scene or options).
SimulationResult simulate(const Scene& scene, const SimulationOptions& options,
                          SimulationObserver* observer = nullptr);

}  // namespace fremond
