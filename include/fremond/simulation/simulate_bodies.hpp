#pragma once
/// @file Simulating a scene of several bodies (scenes/multibody.hpp), event-driven.
///
/// Each body flies exactly under gravity (free_flight.hpp) until the first contact event; every
/// contact that closes then (within options.simultaneity_tolerance) or touches enters one impact,
/// solved with the scene's law on the problem of multibody.hpp. Events of a body against a
/// half-plane are found as for one body (event_detection.hpp); those of two disks from the
/// squared distance of their centres, a polynomial of degree ≤ 4 in time (gravity cancels between
/// two flying bodies), all of whose real roots are computed, so none is missed.
///
/// Lasting contact. A body at rest on what holds it (a ball on the ground, a ball resting on it)
/// is held where it is while the others fly: it is held when one contact step against gravity
/// (plastic, Coulomb with the law's μ; options.step long) leaves it at rest. A moving body in
/// lasting contact (rolling, sliding, resting on a moving body) is not simulated: the run stops
/// with status contact_failed. An accumulation of impacts (options.accumulation_impacts
/// shrinking intervals, simulate.hpp) is closed by a plastic impact of the touching contacts
/// (Newton, e = 0, frictionless: it only lowers the energy), after which the bodies at rest are
/// held.
///
/// Disks that touch another body's disk must be at their body's centre of mass (r = 0) for the
/// event search; simulate() refuses the others naming `bodies[i].points[j].r`. Only the
/// event-driven integrator (options.integrator) is offered.
#include <Eigen/Core>
#include <limits>
#include <string_view>
#include <vector>

#include "fremond/scenes/multibody.hpp"
#include "fremond/simulation/simulate.hpp"
#include "fremond/solvers/impact_result.hpp"

namespace fremond {

/// One point of the trajectory.
struct MultiBodySample {
  double t = 0.0;
  MultiBodyState state;
  double energy = 0.0;  ///< Σ ½ q̇ᵢᵀMᵢq̇ᵢ + mᵢ g yᵢ.
};

/// One entry of the impact log; per-contact vectors in the order of `contacts` (indices into
/// MultiBodyScene::contacts()).
struct MultiBodyImpact {
  long index = 0;
  double t = 0.0;
  /// event: with the scene's law; accumulation: the plastic impact closing an accumulation.
  ImpactKind kind = ImpactKind::event;
  std::vector<int> contacts;
  Eigen::VectorXd q, qdot_A, qdot_E;
  Eigen::VectorXd P_N, P_T, D_NA, D_NE;
  double energy_A = 0.0, energy_E = 0.0;
  bool admissible = true;  ///< docs/concepts.md certificate of the law's answer.
  SolverReport solver;
};

/// Receives the run as it goes; every hook has an empty default.
class MultiBodyObserver {
 public:
  virtual ~MultiBodyObserver() = default;
  /// On the grid of options.sample_interval, at t = 0 and at the end, and around every impact.
  virtual void on_sample(const MultiBodySample& /*sample*/) {}
  virtual void on_impact(const MultiBodyImpact& /*impact*/) {}
  /// Asked before every flight: true stops the run with status interrupted.
  virtual bool stop_requested() { return false; }
};

/// The summary of a run.
struct MultiBodyResult {
  SimulationStatus status = SimulationStatus::not_run;
  std::string_view message = "not run";  ///< a static explanation.
  double t = 0.0;
  MultiBodyState state;
  double energy_initial = 0.0, energy_final = 0.0;
  long impacts = 0;  ///< impacts with the scene's law.
  long inadmissible_impacts = 0;
  int accumulations = 0;
  /// The largest energy increase over a flight or an admissible impact (J): rounding only.
  double max_energy_rise = 0.0;

  bool ok() const {
    return status == SimulationStatus::completed || status == SimulationStatus::max_impacts;
  }
};

/// Throws InvalidArgument("initial", ...) when a contact starts deeper than options.gap_tolerance.
void validate_start(const MultiBodyScene& scene, const SimulationOptions& options);

/// Runs `scene` (validated on a copy; throws InvalidArgument for an invalid scene or options, or a
/// disk off its body's centre that touches another body, or options.integrator moreau_jean).
MultiBodyResult simulate(const MultiBodyScene& scene, const SimulationOptions& options,
                         MultiBodyObserver* observer = nullptr);

}  // namespace fremond
