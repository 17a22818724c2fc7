#pragma once
/// @file Many independent impacts solved on every core (docs/solvers.md#batches): an atlas sweep,
/// a parameter fit, Monte Carlo over initial conditions.
#include <span>
#include <vector>

#include "fremond/core/impact_problem.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/batch_answers.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/impact_solver.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond {

/// How a batch is shared out; the solver's own options (SolverOptions) apply to every problem.
struct BatchOptions {
  /// Worker threads: 0 for one per core (std::thread::hardware_concurrency), else at least 1.
  /// Never more threads than problems; the calling thread is one of them, and the others start
  /// only where the work left is worth sharing (docs/solvers.md#batches).
  int threads = 0;
  /// Throws InvalidArgument naming `threads` when it is negative.
  void validate() const;
};

/// Solves every problem under one law. Result i is solve_impact(problems[i], law, options) to the
/// last bit, whatever the number of threads: each problem is solved by one thread, alone.
/// Problems in the small form (SmallImpactProblem: up to 6 degrees of freedom and 4 contacts) give
/// results in the small form, which hold no heap memory: a batch of them allocates only its list.
///
/// An invalid law or options, or any invalid problem, throws InvalidArgument and returns nothing:
/// the first invalid problem by index is named (`problems[17].M: ...`), a law that does not fit
/// one names its key and that problem. A solver that does not converge says so in its result, as
/// solve_impact does.
///
/// A law with potentials written in Python is called under the interpreter's lock, one thread at
/// a time; the built-in potentials run in parallel.
template <int MaxDofs, int MaxContacts>
std::vector<ImpactResultT<MaxDofs, MaxContacts>> solve_batch(
    std::span<const ImpactProblemT<MaxDofs, MaxContacts>> problems, const ImpactLaw& law,
    const SolverOptions& options = {}, const BatchOptions& batch = {});

/// solve_batch into the caller's `results` (as many entries as problems), which a sweep reuses
/// from one batch to the next: no memory is then allocated or first touched on the calling thread.
/// Throws InvalidArgument naming `results` when the sizes differ; on any InvalidArgument the
/// entries of `results` are unspecified.
template <int MaxDofs, int MaxContacts>
void solve_batch(std::span<const ImpactProblemT<MaxDofs, MaxContacts>> problems,
                 const ImpactLaw& law, std::span<ImpactResultT<MaxDofs, MaxContacts>> results,
                 const SolverOptions& options = {}, const BatchOptions& batch = {});

/// Many velocities before the impact for one configuration (Monte Carlo over initial conditions, a
/// sweep of the velocity at a fixed pose): column i of `qdot_A` (n × N) solved by `solver`'s law,
/// options and configuration. Result i is what solver.solve(qdot_A.col(i)) gives, which is
/// solve_impact's on that problem to the last bit, whatever the number of threads; each worker
/// solves with its own copy of `solver`, which is left as it was. The configuration was validated
/// and factored when the solver was built: a velocity costs only its own solve.
///
/// Throws InvalidArgument naming `qdot_A` when it has not n rows; for the first velocity by index
/// that solve() refuses, `qdot_A[i]` (`qdot_A[i][k]` for its entry k not finite), or the member
/// solve() names with "(qdot_A[i])" in the reason (a contact velocity that overflows names W_N);
/// `results` when it has not N entries. The entries of `results` are then unspecified.
template <int MaxDofs, int MaxContacts>
void solve_batch(const ImpactSolverT<MaxDofs, MaxContacts>& solver,
                 const Eigen::Ref<const Eigen::MatrixXd>& qdot_A,
                 std::span<ImpactResultT<MaxDofs, MaxContacts>> results,
                 const BatchOptions& batch = {});

/// The batch of one configuration with the answers kept as columns (BatchAnswers, resized to N
/// impacts): each worker solves into a result of its own and copies out what the columns hold,
/// the same numbers to the last bit. What a Monte Carlo run over many velocities keeps, in a tenth
/// of the memory of whole results. Throws as the overload above (`results` aside); the columns
/// are then unspecified.
template <int MaxDofs, int MaxContacts>
void solve_batch(const ImpactSolverT<MaxDofs, MaxContacts>& solver,
                 const Eigen::Ref<const Eigen::MatrixXd>& qdot_A, BatchAnswers& answers,
                 const BatchOptions& batch = {});

/// The batch of one configuration, its results returned.
template <int MaxDofs, int MaxContacts>
std::vector<ImpactResultT<MaxDofs, MaxContacts>> solve_batch(
    const ImpactSolverT<MaxDofs, MaxContacts>& solver,
    const Eigen::Ref<const Eigen::MatrixXd>& qdot_A, const BatchOptions& batch = {});

/// solve_batch for a list of heap-stored problems.
inline std::vector<ImpactResult> solve_batch(const std::vector<ImpactProblem>& problems,
                                             const ImpactLaw& law,
                                             const SolverOptions& options = {},
                                             const BatchOptions& batch = {}) {
  return solve_batch(std::span<const ImpactProblem>(problems), law, options, batch);
}
/// solve_batch for a list of small problems.
inline std::vector<SmallImpactResult> solve_batch(const std::vector<SmallImpactProblem>& problems,
                                                  const ImpactLaw& law,
                                                  const SolverOptions& options = {},
                                                  const BatchOptions& batch = {}) {
  return solve_batch(std::span<const SmallImpactProblem>(problems), law, options, batch);
}

}  // namespace fremond
