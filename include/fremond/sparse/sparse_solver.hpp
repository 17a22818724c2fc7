#pragma once
/// @file Newton's law, with or without Coulomb friction, on sparse problems of many contacts
/// (docs/sparse.md): nonsmooth Gauss–Seidel over the contacts, each contact's law solved exactly
/// given the others, at a cost per sweep linear in the non-zeros of G.
#include <string>

#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/sparse/contact_problem.hpp"

namespace fremond {

/// Options of the sparse solver. The solver never writes into them.
struct SparseSolverOptions {
  /// Relative tolerance on the law's residual, as SolverOptions::tolerance: converged when the
  /// largest natural-map residual of a contact is ≤ tolerance · v_scale, v_scale the largest
  /// |D_A| of the contacts that take part. Range [1e-16, 1e-2].
  double tolerance = 1e-10;
  /// Gauss–Seidel sweeps over every contact. Range ≥ 1.
  int max_sweeps = 100000;
  /// Admissibility tolerance, as SolverOptions::admissibility_tolerance: relative to T_A, or,
  /// in contact coordinates where T_A is not known, to the impact's energy scale
  /// max|P| · v_scale. Range [0, 1).
  double admissibility_tolerance = 1e-9;
  /// After the first sweeps, semismooth Newton on the contacts' modes tries to finish from their
  /// point (docs/sparse.md#mode-newton): exact to rounding in a few factorisations where the modes
  /// read are right; dropped, the sweeps going on, where not.
  bool newton_polish = true;
  /// On more than 64 contacts, Anderson acceleration of the sweeps (docs/sparse.md#acceleration):
  /// each forward and backward pair of sweeps starts from the mix of the pairs before that best
  /// cancels their changes. Dropped, and the sweeps started again without it, where 128 sweeps
  /// do not halve the residual.
  bool acceleration = true;

  /// True when every option is within its range; otherwise false with the reason in *why.
  bool is_valid(std::string* why = nullptr) const;
  /// Throws InvalidArgument naming the option when !is_valid().
  void validate() const;
};

/// True for the laws the sparse path solves: Newton's, with or without Coulomb friction, and
/// Poisson's with every e = 0 (the same law).
bool solved_sparse(const ImpactLaw& law);

/// Solves Newton's law (`newton`, `newton_coulomb`; e and μ one value or one per contact) on a
/// problem in contact coordinates. `start`, when given, is a previous answer of the same
/// contacts whose percussions start the sweeps (a warm start). The result's qdot_E is empty
/// (contact coordinates hold no q̇), its certificate's kinetic_energy_A NaN; velocities,
/// percussions, energy_change, the certificate (15 in sum and per contact, non-penetration) and
/// the report (method `nsgs`, status, sweeps as iterations, residual) are filled. Another law
/// ends with status `unsupported`, saying why. Throws InvalidArgument for a problem, a law or
/// options that validate() refuses.
ImpactResult solve_contact_problem(const ContactProblem& problem, const ImpactLaw& law,
                                   const SparseSolverOptions& options = {},
                                   const ImpactResult* start = nullptr);

/// The same on a sparse impact problem: G = Wᵀ M⁻¹ W and D_A formed once (contact_problem()),
/// then q̇_E = q̇_A + M⁻¹ W P, T_A and T_E − T_A from the velocities.
ImpactResult solve_impact(const SparseImpactProblem& problem, const ImpactLaw& law,
                          const SparseSolverOptions& options = {},
                          const ImpactResult* start = nullptr);

/// The largest natural-map residual of Newton's law (with Coulomb when the law has it) over the
/// contacts of `result` on `problem`, in velocity units relative to v_scale, with D_E recomputed
/// from the percussions: 0 for an exact answer. The same measure as law_residual on a dense
/// problem.
double contact_residual(const ContactProblem& problem, const ImpactLaw& law,
                        const ImpactResult& result);

}  // namespace fremond
