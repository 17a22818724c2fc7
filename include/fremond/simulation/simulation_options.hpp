#pragma once
/// @file Options of a simulation run, and the names of its enumerations.
#include <string>
#include <string_view>

#include "fremond/simulation/event_detection.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond {

/// How the run integrates.
enum class Integrator {
  /// Exact free flights between impacts found by an exhaustive event search; an accumulation of
  /// impacts or a persistent contact hands over to Moreau–Jean until the body flies freely again.
  event_driven,
  /// Moreau–Jean time-stepping for the whole run.
  moreau_jean,
};
std::string_view to_string(Integrator i);
Integrator integrator_from_string(std::string_view s);

/// The phase a run is in.
enum class Phase {
  event_driven,  ///< exact flights and impacts.
  moreau_jean,   ///< time-stepping.
};
std::string_view to_string(Phase p);
Phase phase_from_string(std::string_view s);

/// Options of simulate(). Units are SI; every value is checked by is_valid().
struct SimulationOptions {
  Integrator integrator = Integrator::event_driven;
  /// End time (s), > 0. The run starts at t = 0.
  double t_end = 3.0;
  /// Moreau–Jean step h (s), in (0, t_end]. First-order accurate: errors scale with h.
  double step = 1e-3;
  /// Impacts (with the scene's law) after which the run stops with status max_impacts; ≥ 1.
  long max_impacts = 1000000;
  /// Contacts whose events fall within this time of the first one enter the same impact (s),
  /// ≥ 0. Contacts with a gap below gap_tolerance at the impact also enter it.
  double simultaneity_tolerance = 1e-12;
  /// Evaluations of the gap one free flight's event search may spend, per contact, ≥ 100. A
  /// flight that needs more (a body spinning too fast for its events to be resolved) stops the
  /// run with status event_search_failed.
  long max_gap_evaluations = kDefaultEventSearchBudget;
  /// A contact with |gap| ≤ gap_tolerance is touching (m), ≥ 0.
  double gap_tolerance = 1e-10;
  /// A touching contact with |D_N| ≤ velocity_tolerance is at rest on its obstacle (m/s), ≥ 0:
  /// if free flight would push it in (g'' < 0), the contact is persistent and Moreau–Jean takes
  /// over.
  double velocity_tolerance = 1e-9;
  /// Accumulation test: accumulation_impacts successive intervals between impacts, each shorter
  /// than the one before and than accumulation_interval (s), > 0.
  double accumulation_interval = 1e-3;
  /// In [2, 32].
  int accumulation_impacts = 4;
  /// After an accumulation or a persistent contact, the event-driven integrator resumes once this
  /// many successive Moreau–Jean steps had no contact; ≥ 1.
  int return_after_free_steps = 10;
  /// Interval of the trajectory samples handed to the observer (s), > 0. Impacts add the samples
  /// just before and just after them.
  double sample_interval = 1e-3;
  /// Options of every impact solve. Uniqueness is not checked by default: it costs extra solves at
  /// every impact and does not change the answer.
  SolverOptions solver = [] {
    SolverOptions o;
    o.check_uniqueness = false;
    return o;
  }();

  /// True when every option is within its range; otherwise false with the reason in *why.
  bool is_valid(std::string* why = nullptr) const;
  /// Throws InvalidArgument naming the option (as in the scene file, e.g. `integrator.step`).
  void validate() const;
};

}  // namespace fremond
