#pragma once
/// @file The first impact of a scene, and the calibration of Frémond's normal stiffness the paper
/// leaves out (docs/concepts.md): k_N such that at the bar's first impact from the paper's initial
/// state (its §3), with the
/// normal law alone, the normal restitution −D_NE/D_NA is exactly the paper's e = 0.9 (k_N ≈ 85.36
/// for p = 3). It is computed at run time, never hard-coded.
#include <array>

#include "fremond/core/impact_problem.hpp"
#include "fremond/scenes/presets.hpp"
#include "fremond/scenes/scene.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond {

/// Where a scene's first free flight ends.
struct FirstImpact {
  bool found = false;
  /// False when the event search ran out of its budget (kDefaultEventSearchBudget per contact)
  /// before deciding: the body turns too fast for its events to be resolved, and found is false.
  bool resolved = true;
  double t = 0.0;
  PlanarState state;  ///< just before the impact.
  int contact_count = 0;
  std::array<int, kMaxSceneContacts> contacts{};
};

/// Flies the scene's initial state exactly until its first contact event, before `t_max`.
/// Contacts within `simultaneity_tolerance` of the first event are included.
FirstImpact first_impact(const Scene& scene, double t_max, double simultaneity_tolerance = 1e-12);

/// The impact problem of contacts `contacts[0..n)` (n ≤ 4) of a validated scene at `state`.
SmallImpactProblem impact_problem(const Scene& scene, const PlanarState& state, const int* contacts,
                                  int n);

/// The outcome of a calibration.
struct StiffnessCalibration {
  double k_N = 0.0;          ///< the stiffness found.
  double restitution = 0.0;  ///< −D_NE/D_NA it gives.
  int solves = 0;            ///< impact solves used.
  bool converged = false;    ///< the root was bracketed and refined to rounding.
};

/// k such that under ImpactLaw::fremond(PowerPotential(k, p)) — the normal law alone, the
/// problem's tangential rows dropped — contact `contact` of `problem` leaves with
/// −D_NE/D_NA = restitution. The restitution grows from 0 (k = 0: the reaction alone, plastic) to
/// 1 (k → ∞: z → 0, elastic), so one bracket in log k and Brent's method find it. Throws
/// InvalidArgument unless 0 < restitution < 1, p > 1 and the contact approaches (D_NA < 0).
StiffnessCalibration calibrate_normal_stiffness(const SmallImpactProblem& problem, double p,
                                                double restitution, int contact = 0,
                                                const SolverOptions& options = {});

/// The k_N that gives `restitution` at the first impact of `scene` from its initial state, with
/// the normal law alone: calibrate_normal_stiffness at the first contact of that impact. The
/// scene's own law is not used. Throws InvalidArgument if the scene never touches before 10⁴ s,
/// its first flight cannot be resolved, or the calibration does not converge.
double first_impact_normal_stiffness(const Scene& scene, double p, double restitution);

/// docs/laws.md's k_N for the bar: first_impact_normal_stiffness of the bar of §5 (p = 3,
/// restitution e = 0.9).
double paper_bar_normal_stiffness(const BarParameters& bar = {});

/// The paper's scene (the paper's Fig. 1) with one of its laws, Frémond's k_N calibrated as above.
Scene paper_bar_scene(PaperLaw law, const BarParameters& bar = {});

}  // namespace fremond
