#pragma once
/// @file A solver prepared for one configuration (docs/solvers.md#prepared-solver): built once
/// from (M, W_N, W_T, law, options), which it validates and factors; then solve(q̇_A) as often as
/// wanted, and update(...) for the next configuration.
#include <Eigen/Core>
#include <memory>

#include "fremond/core/impact_problem.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/batch_answers.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond {

namespace detail {
template <int MaxDofs, int MaxContacts>
struct PreparedWorkspace;
}  // namespace detail

/// The prepared form of solve_impact. Every answer is solve_impact's on the same data, to the last
/// bit (the same chain and certificate); what is done once instead of at every solve is the
/// validation of M, W, w, the law and the options, M's positive-definiteness test, and the setting
/// up of the storage the answer lives in. A solve checks only the new q̇_A.
///
/// For small problems (SmallImpactSolver, and an ImpactSolver whose problem fits the small form)
/// solve() allocates nothing, except for potentials whose prox goes through the NLopt fallback.
///
/// Not thread-safe: one solver per thread (a solver holds its answer). Copyable and movable.
template <int MaxDofs, int MaxContacts>
class ImpactSolverT {
 public:
  using Problem = ImpactProblemT<MaxDofs, MaxContacts>;
  using Result = ImpactResultT<MaxDofs, MaxContacts>;
  using Velocity = VecT<MaxDofs>;

  /// Validates `problem` (its q̇_A included: it is the one solve() uses), the law against its
  /// contacts, and the options. Throws InvalidArgument naming the member, key or option, as
  /// solve_impact does.
  ImpactSolverT(const Problem& problem, ImpactLaw law, const SolverOptions& options = {});
  ~ImpactSolverT();
  ImpactSolverT(const ImpactSolverT& other);
  ImpactSolverT& operator=(const ImpactSolverT& other);
  ImpactSolverT(ImpactSolverT&&) noexcept;
  ImpactSolverT& operator=(ImpactSolverT&&) noexcept;

  /// Solves the impact for the velocity before it; the answer stays in result() until the next
  /// solve or update. Throws InvalidArgument naming `qdot_A` (its size, a non-finite entry, a
  /// kinetic energy or contact velocity that overflows) and then keeps the previous q̇_A and answer.
  const Result& solve(const Eigen::Ref<const Eigen::VectorXd>& qdot_A);
  /// Solves for the problem's current q̇_A.
  const Result& solve();
  /// solve(qdot_A) with the answer written into `out` (its storage reused) instead of the
  /// solver's own result(), which stays as it was; the solver's q̇_A becomes qdot_A. The same
  /// answer to the last bit, without a copy: what a batch of velocities keeps (solve_batch).
  void solve_into(const Eigen::Ref<const Eigen::VectorXd>& qdot_A, Result& out);
  /// solve(qdot_A) with the answer written into column `column` of `answers` (BatchAnswers, sized
  /// for this solver's dofs and contacts) instead of result(), which stays as it was; the
  /// solver's q̇_A becomes qdot_A. The same numbers to the last bit, without a whole result where
  /// the law answers one contact on scalars: what solve_batch does for each velocity, and what a
  /// loop of your own (your threads, one solver each) can do. Throws InvalidArgument naming
  /// `answers` (of other sizes) or `column` (outside them) before solving, as solve() names a bad
  /// `qdot_A`.
  void solve_into(const Eigen::Ref<const Eigen::VectorXd>& qdot_A, BatchAnswers& answers,
                  Eigen::Index column);

  /// A new configuration (as a simulation has between impacts): M, W_N, W_T and the obstacles'
  /// velocity terms w_N, w_T (empty: zero), the number of degrees of freedom and contacts
  /// unchanged, q̇_A kept. Validated as the constructor does; on InvalidArgument the solver keeps
  /// its previous configuration. Clears the answer.
  void update(const Eigen::Ref<const Eigen::MatrixXd>& M,
              const Eigen::Ref<const Eigen::MatrixXd>& W_N,
              const Eigen::Ref<const Eigen::MatrixXd>& W_T,
              const Eigen::Ref<const Eigen::VectorXd>& w_N = Eigen::VectorXd(),
              const Eigen::Ref<const Eigen::VectorXd>& w_T = Eigen::VectorXd());
  /// Another law (or other parameters) for the same contacts: validated against them; on
  /// InvalidArgument the previous law is kept. Clears the answer.
  void update_law(ImpactLaw law);

  const Problem& problem() const;
  const ImpactLaw& law() const { return law_; }
  const SolverOptions& options() const { return options_; }
  /// The last answer; SolverStatus::not_run before the first solve and after an update.
  const Result& result() const;

 private:
  ImpactLaw law_;
  SolverOptions options_;
  std::unique_ptr<detail::PreparedWorkspace<MaxDofs, MaxContacts>> work_;
};

using ImpactSolver = ImpactSolverT<Dynamic, Dynamic>;
using SmallImpactSolver = ImpactSolverT<kSmallDofs, kSmallContacts>;

}  // namespace fremond
