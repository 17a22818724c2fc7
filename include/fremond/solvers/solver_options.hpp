#pragma once
/// @file Options of the impact solvers. The solver never writes into them.
#include <string>

#include "fremond/solvers/solver_status.hpp"

namespace fremond {

struct SolverOptions {
  /// Method: `automatic` picks the cheapest exact method the law and its potentials allow
  /// (closed form → scalar Newton → semismooth Newton → proximal iterations → NLopt; with Coulomb
  /// on two to four contacts, semismooth Newton per tangential mode before the proximal
  /// iterations, named mode_enumeration, only where Newton on the law fails). A method that
  /// does not apply gives status `unsupported`. The classical laws take closed_form, lemke and
  /// mode_enumeration (which `automatic` chooses among per phase, and falls back to where Lemke's
  /// answer misses the tolerance by rounding or ends on a ray, on up to 4 contacts); naming one
  /// forces it.
  SolverMethod method = SolverMethod::automatic;
  /// Relative tolerance on the law's residual: converged when ‖R‖∞ ≤ tolerance · v_scale, with
  /// v_scale = max(‖D_A‖∞ over the contacts that take part, tiny). Units: none.
  /// Range [1e-16, 1e-2].
  double tolerance = 1e-13;
  /// Relative residual accepted from the NLopt fallback (SLSQP on the velocity-space problem),
  /// which cannot reach Newton's tolerance on non-smooth potentials: NLopt's answer is accepted
  /// at nlopt_accepts() = max(nlopt_tolerance, tolerance), so that a looser `tolerance` alone
  /// loosens it too. Range [1e-16, 1e-2].
  double nlopt_tolerance = 1e-9;
  /// Newton iterations (semismooth, scalar). Range ≥ 1.
  int max_iterations = 100;
  /// Proximal iterations (Gauss–Seidel sweeps). Range ≥ 1. The splitting stops earlier, with
  /// max_iterations, when its observed linear rate predicts that this budget cannot reach the
  /// tolerance (a sweep costs up to tens of µs with a dead-zone power of q near 1).
  int max_proximal_iterations = 200000;
  /// NLopt function evaluations (shared by Coulomb's outer rounds). Range ≥ 1. NLopt is the last
  /// resort; SLSQP that has not converged in 2e4 evaluations (about 0.2 s on a small problem) is
  /// stuck on a non-smooth point, so a larger budget buys time, not answers.
  int max_nlopt_evaluations = 20000;
  /// Admissibility tolerance, relative to the kinetic energy before the impact: an inequality
  /// X ≥ 0 is taken as violated when X < −admissibility_tolerance · max(T_A, tiny). Range [0, 1).
  double admissibility_tolerance = 1e-9;
  /// Find every solution a mode enumeration can (classical laws with friction on up to 3
  /// contacts; solve_impact_all goes to 4) and set `unique` from it. Costs a few more solves; off
  /// leaves `unique` as the solver's cheap sufficient test.
  bool check_uniqueness = true;

  /// The relative residual at which an NLopt answer is accepted: max(nlopt_tolerance, tolerance).
  double nlopt_accepts() const { return nlopt_tolerance > tolerance ? nlopt_tolerance : tolerance; }

  /// True when every option is within its range; otherwise false with the reason in *why.
  bool is_valid(std::string* why = nullptr) const;
  /// Throws InvalidArgument naming the option when !is_valid().
  void validate() const;
};

}  // namespace fremond
