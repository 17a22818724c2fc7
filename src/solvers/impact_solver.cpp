// The prepared solver (impact_solver.hpp): solve_impact's stages (solve_stages.hpp) with the
// configuration validated once.
#include "fremond/solvers/impact_solver.hpp"

#include <string>
#include <utility>

#include "admissibility/detail/admissibility.hpp"
#include "contact_space/contact_space.hpp"
#include "core/detail/impact_problem.hpp"
#include "fremond/core/error.hpp"
#include "laws/detail/plugins.hpp"
#include "solvers/detail/batch_columns.hpp"
#include "solvers/detail/chain_workspace.hpp"
#include "solvers/detail/independent_groups.hpp"
#include "solvers/detail/result_copy.hpp"
#include "solvers/detail/solve_stages.hpp"

namespace fremond {

namespace detail {

/// pb.q̇_A = v where v is valid for pb's configuration (validate_velocity); else pb is left as it
/// was and InvalidArgument names `qdot_A`. The size is tested before any copy, so that a
/// stack-stored problem never holds more than it has room for; a v within the configuration's
/// `bounds` needs no further test; otherwise `previous` keeps the old q̇_A while validate_velocity
/// runs (its storage reused from one call to the next).
template <int N, int C>
void set_validated_velocity(const Eigen::Ref<const Eigen::VectorXd>& v, ImpactProblemT<N, C>& pb,
                            const VelocityBounds& bounds, VecT<N>& previous) {
  if (v.size() != pb.dofs())
    throw InvalidArgument("qdot_A", "must have " + std::to_string(pb.dofs()) +
                                        " entries (one per degree of freedom), got " +
                                        std::to_string(v.size()));
  if (bounds.admit(v)) {
    pb.qdot_A = v;
    return;
  }
  previous = pb.qdot_A;
  pb.qdot_A = v;
  try {
    validate_velocity(pb);
  } catch (...) {
    pb.qdot_A = previous;
    throw;
  }
}

/// One problem, its contact space, its chain's storage and its answer, in one storage.
template <int N, int C>
struct PreparedStage {
  ImpactProblemT<N, C> pb;
  ContactSpaceT<N, C> cs;
  ChainWorkspace ws{.persistent = true, .sweeps = std::nullopt};
  ImpactResultT<N, C> out;
  VelocityBounds bounds;  // of the configuration: most q̇_A need no further test

  /// validate(pb) and its contact space on every contact: a Delassus entry that overflows is
  /// refused now, for every q̇_A to come, rather than at the solve where its contact approaches.
  void prepare(const ImpactLaw& law, const SolverOptions& options) {
    validate_shapes(pb);
    law.validate(pb.contacts());
    options.validate();
    build_contact_space(pb, tangential_rows(law), cs, HeldContacts::every);
    require_positive_definite(pb.M, cs.llt);
    bounds = VelocityBounds(pb);
    clear_result(out);
  }

  /// solve_impact_in_own_storage after its validation, into `into` (out, or the caller's): the
  /// same stages on the same data. The configuration's part of the contact space is kept from the
  /// last solve where the same contacts approach (update_velocities).
  void solve(const ImpactLaw& law, const SolverOptions& options, ImpactResultT<N, C>& into) {
    if (!update_velocities(pb, cs)) build_contact_space(pb, tangential_rows(law), cs);
    clear_result(into);
    solve_on_contact_space(pb, law, options, cs, into, ws);
  }

  /// solve() into column k of `answers`, through `scratch` (a result of earlier solves). Where
  /// the law's lane answers the one contact (solve_on_contact_space's first stage), its numbers
  /// and their certificate go into the column without the rest of a result (its attempt log, its
  /// report) being cleared or written; the whole solve otherwise, or where a dissipative law's
  /// certificate refuses the lane's answer (solve_impact then calls it stalled). The same numbers
  /// either way.
  void solve_into_column(const ImpactLaw& law, const SolverOptions& options, BatchAnswers& answers,
                         Eigen::Index k, ImpactResultT<N, C>& scratch) {
    if (!update_velocities(pb, cs)) build_contact_space(pb, tangential_rows(law), cs);
    if (cs.contacts == 1) {
      scratch.P_N_reaction.resize(0);  // the lane writes none; the certificate reads it
      const bool lane = law.visit(
          [&](const auto& l) { return solve_one_contact_lane(pb, cs, l, options, scratch); });
      if (lane) {
        const bool admissible =
            certify_one_contact(pb, law, one_contact_facts(scratch), options, cs).admissible;
        if (admissible || !law.dissipative()) {
          put_answer(scratch, admissible, answers, k);
          return;
        }
      }
    }
    clear_result(scratch);
    solve_on_contact_space(pb, law, options, cs, scratch, ws);
    put_answer(scratch, scratch.admissibility.admissible, answers, k);
  }
};

template <int N, int C>
struct PreparedWorkspace {
  PreparedStage<N, C> stage;

  VecT<N> previous;  // q̇_A kept while a new one is validated

  const ImpactProblemT<N, C>& problem() const { return stage.pb; }
  const ImpactResultT<N, C>& result() const { return stage.out; }
  ImpactProblemT<N, C>& editable() { return stage.pb; }
  void prepare(const ImpactLaw& law, const SolverOptions& options) { stage.prepare(law, options); }
  void set_velocity(const Eigen::Ref<const Eigen::VectorXd>& v) {
    set_validated_velocity(v, stage.pb, stage.bounds, previous);
  }
  void solve(const ImpactLaw& law, const SolverOptions& options) {
    stage.solve(law, options, stage.out);
  }
  void solve_into(const ImpactLaw& law, const SolverOptions& options, ImpactResultT<N, C>& into) {
    stage.solve(law, options, into);
  }
  void solve_into(const ImpactLaw& law, const SolverOptions& options, BatchAnswers& answers,
                  Eigen::Index k) {
    stage.solve_into_column(law, options, answers, k, scratch);
  }

  ImpactResultT<N, C> scratch;  // solve_into's column answers pass through it
};

/// The heap-stored solver: a problem that fits the small form is solved in it, as solve_impact
/// does (the same bits), and its answer copied out into storage kept from one solve to the next.
template <>
struct PreparedWorkspace<Dynamic, Dynamic> {
  ImpactProblem pb;
  bool small = false;
  PreparedStage<kSmallDofs, kSmallContacts> small_stage;
  PreparedStage<Dynamic, Dynamic> stage;
  ImpactResult out;
  Eigen::VectorXd previous;
  VecT<kSmallDofs> small_previous;

  const ImpactProblem& problem() const { return pb; }
  const ImpactResult& result() const { return out; }
  ImpactProblem& editable() { return pb; }
  void prepare(const ImpactLaw& law, const SolverOptions& options) {
    small = fits_small(pb);
    if (small) {
      small_stage.pb = to_small(pb);
      small_stage.prepare(law, options);
    } else {
      stage.pb = pb;
      stage.prepare(law, options);
    }
    clear_result(out);
  }
  // Validated in the storage it is solved in, as solve_impact does (the heap-stored test allocates
  // Eigen's temporaries).
  void set_velocity(const Eigen::Ref<const Eigen::VectorXd>& v) {
    if (small)
      set_validated_velocity(v, small_stage.pb, small_stage.bounds, small_previous);
    else
      set_validated_velocity(v, stage.pb, stage.bounds, previous);
    pb.qdot_A = v;
  }
  void solve(const ImpactLaw& law, const SolverOptions& options) { solve_into(law, options, out); }
  void solve_into(const ImpactLaw& law, const SolverOptions& options, ImpactResult& into) {
    if (small) {
      small_stage.solve(law, options, small_stage.out);
      copy_into(small_stage.out, into);
    } else {
      stage.solve(law, options, into);
    }
  }
  void solve_into(const ImpactLaw& law, const SolverOptions& options, BatchAnswers& answers,
                  Eigen::Index k) {
    if (small)
      small_stage.solve_into_column(law, options, answers, k, small_scratch);
    else
      stage.solve_into_column(law, options, answers, k, scratch);
  }

  SmallImpactResult small_scratch;  // solve_into's column answers pass through them
  ImpactResult scratch;
};

}  // namespace detail

namespace {
/// A configuration's matrix of the shape the solver was prepared with.
void require_shape(const char* name, Eigen::Index rows, Eigen::Index cols, Eigen::Index want_rows,
                   Eigen::Index want_cols, const char* what) {
  if (rows != want_rows || cols != want_cols)
    throw InvalidArgument(name, std::string("must be ") + std::to_string(want_rows) + "x" +
                                    std::to_string(want_cols) + " (" + what + "), got " +
                                    std::to_string(rows) + "x" + std::to_string(cols));
}
}  // namespace

template <int N, int C>
ImpactSolverT<N, C>::ImpactSolverT(const Problem& problem, ImpactLaw law,
                                   const SolverOptions& options)
    : law_(std::move(law)),
      options_(options),
      work_(std::make_unique<detail::PreparedWorkspace<N, C>>()) {
  work_->editable() = problem;
  work_->prepare(law_, options_);
}

template <int N, int C>
ImpactSolverT<N, C>::~ImpactSolverT() = default;
template <int N, int C>
ImpactSolverT<N, C>::ImpactSolverT(const ImpactSolverT& other)
    : law_(other.law_),
      options_(other.options_),
      work_(std::make_unique<detail::PreparedWorkspace<N, C>>(*other.work_)) {}
template <int N, int C>
ImpactSolverT<N, C>& ImpactSolverT<N, C>::operator=(const ImpactSolverT& other) {
  if (this != &other) *this = ImpactSolverT(other);
  return *this;
}
template <int N, int C>
ImpactSolverT<N, C>::ImpactSolverT(ImpactSolverT&&) noexcept = default;
template <int N, int C>
ImpactSolverT<N, C>& ImpactSolverT<N, C>::operator=(ImpactSolverT&&) noexcept = default;

template <int N, int C>
const typename ImpactSolverT<N, C>::Result& ImpactSolverT<N, C>::solve(
    const Eigen::Ref<const Eigen::VectorXd>& qdot_A) {
  work_->set_velocity(qdot_A);
  work_->solve(law_, options_);
  return work_->result();
}

template <int N, int C>
void ImpactSolverT<N, C>::solve_into(const Eigen::Ref<const Eigen::VectorXd>& qdot_A, Result& out) {
  work_->set_velocity(qdot_A);
  work_->solve_into(law_, options_, out);
}

template <int N, int C>
void ImpactSolverT<N, C>::solve_into(const Eigen::Ref<const Eigen::VectorXd>& qdot_A,
                                     BatchAnswers& answers, Eigen::Index column) {
  const Problem& pb = work_->problem();
  const Eigen::Index n = pb.dofs(), c = pb.contacts(), count = answers.size();
  const auto sized = [&](const Eigen::MatrixXd& m, Eigen::Index rows) {
    return m.rows() == rows && m.cols() == count;
  };
  if (!sized(answers.qdot_E, n) || !sized(answers.P_N, c) || !sized(answers.P_T, c) ||
      !sized(answers.D_NE, c) || !sized(answers.D_TE, c) || answers.residual.size() != count ||
      answers.status.size() != static_cast<std::size_t>(count) ||
      answers.admissible.size() != static_cast<std::size_t>(count) ||
      answers.unique.size() != static_cast<std::size_t>(count))
    throw InvalidArgument("answers", "must be sized for " + std::to_string(n) +
                                         " degrees of freedom and " + std::to_string(c) +
                                         " contacts (answers.resize(" + std::to_string(n) + ", " +
                                         std::to_string(c) + ", count))");
  if (column < 0 || column >= count)
    throw InvalidArgument(
        "column", "must be in [0, " + std::to_string(count) + "), got " + std::to_string(column));
  work_->set_velocity(qdot_A);
  work_->solve_into(law_, options_, answers, column);
}

template <int N, int C>
const typename ImpactSolverT<N, C>::Result& ImpactSolverT<N, C>::solve() {
  work_->solve(law_, options_);
  return work_->result();
}

template <int N, int C>
void ImpactSolverT<N, C>::update(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                 const Eigen::Ref<const Eigen::MatrixXd>& W_N,
                                 const Eigen::Ref<const Eigen::MatrixXd>& W_T,
                                 const Eigen::Ref<const Eigen::VectorXd>& w_N,
                                 const Eigen::Ref<const Eigen::VectorXd>& w_T) {
  const Problem& pb = work_->problem();
  const int n = pb.dofs(), c = pb.contacts();
  require_shape("M", M.rows(), M.cols(), n, n, "the solver's degrees of freedom");
  require_shape("W_N", W_N.rows(), W_N.cols(), n, c, "one column per contact of the solver");
  if (W_T.size() != 0 || W_T.cols() != 0)
    require_shape("W_T", W_T.rows(), W_T.cols(), n, c, "one column per contact of the solver");
  if (w_N.size() != 0) require_shape("w_N", w_N.size(), 1, c, 1, "one entry per contact");
  if (w_T.size() != 0) require_shape("w_T", w_T.size(), 1, c, 1, "one entry per contact");
  detail::PreparedWorkspace<N, C> next(*work_);
  Problem& p = next.editable();
  p.M = M;
  p.W_N = W_N;
  p.W_T.resize(n, W_T.cols());
  if (W_T.cols() != 0) p.W_T = W_T;
  p.w_N = w_N;
  p.w_T = w_T;
  next.prepare(law_, options_);
  *work_ = std::move(next);
}

template <int N, int C>
void ImpactSolverT<N, C>::update_law(ImpactLaw law) {
  law.validate(work_->problem().contacts());
  law_ = std::move(law);
  work_->prepare(law_, options_);
}

template <int N, int C>
const typename ImpactSolverT<N, C>::Problem& ImpactSolverT<N, C>::problem() const {
  return work_->problem();
}

template <int N, int C>
const typename ImpactSolverT<N, C>::Result& ImpactSolverT<N, C>::result() const {
  return work_->result();
}

template class ImpactSolverT<Dynamic, Dynamic>;
template class ImpactSolverT<kSmallDofs, kSmallContacts>;

}  // namespace fremond
