#include "fremond/solvers/solve_batch.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "core/detail/impact_problem.hpp"
#include "fremond/core/error.hpp"
#include "fremond/solvers/solve_impact.hpp"
#include "solvers/detail/result_copy.hpp"
#include "solvers/detail/solve_stages.hpp"

namespace fremond {

void BatchOptions::validate() const {
  if (threads < 0)
    throw InvalidArgument("threads",
                          "must be 0 (one per core) or at least 1, got " + std::to_string(threads));
}

namespace {
// The machine's cores, asked once: std::thread::hardware_concurrency reads a kernel file on every
// call, three system calls that cost more than a small batch's solves.
unsigned machine_cores() {
  static const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  return cores;
}

// The number of workers for `count` problems: never more than problems, at least one.
int workers_for(std::size_t count, int threads) {
  const std::size_t wanted = threads == 0 ? machine_cores() : static_cast<std::size_t>(threads);
  return static_cast<int>(std::max<std::size_t>(1, std::min(wanted, count)));
}

// The error solve_impact gives for problem i, named by its index: `problems[i].M: ...` for the
// problem's members, the law's key with the problem's index for a law that does not fit it.
[[noreturn]] void refuse(std::size_t i, const InvalidArgument& e) {
  const std::string index = "problems[" + std::to_string(i) + "]";
  const std::string reason = std::string(e.what()).substr(e.name().size() + 2);
  if (e.name().rfind("law", 0) == 0) throw InvalidArgument(e.name(), reason + " (" + index + ")");
  throw InvalidArgument(index + "." + e.name(), reason);
}

/// results[i] = solve_impact(problem, ...), written in place: a small answer straight into its
/// result, a heap-stored one through the small form where it fits (as solve_impact solves it),
/// copied into the storage the result already has.
template <int N, int C>
void solve_into(const ImpactProblemT<N, C>& pb, const ImpactLaw& law, const SolverOptions& options,
                ImpactResultT<N, C>& out, SmallImpactResult& small) {
  if constexpr (N == Dynamic && C == Dynamic) {
    if (fits_small(pb)) {
      detail::solve_impact_into(to_small(pb), law, options, small);
      detail::copy_into(small, out);
      return;
    }
  }
  detail::solve_impact_into(pb, law, options, out);
}

// Starting a worker costs the calling thread 13 to 35 µs and the worker 19 to 60 µs more before
// it runs (this project's 2-core machine, measured on different days), more than a short batch (a
// fit's evaluation on a few dozen measured impacts) takes to solve. The other workers start once
// the work left, estimated from the calling thread's pace over at least kPaceAfter, exceeds
// kWorthSharing.
constexpr double kPaceAfter = 20e-6;      // s
constexpr double kWorthSharing = 200e-6;  // s

/// solve(state, i) for every i < count on the batch's workers, each with its own state from
/// make_state(). The calling thread solves first; the other workers start once the work left is
/// worth sharing (kWorthSharing). Workers take contiguous blocks in order from a shared counter
/// as they become free, so one that starts late or meets a run of hard problems (NLopt) leaves its
/// share to the others. The first InvalidArgument by index is handed to refuse(i, e), which
/// throws, once every item before it has been tried. `min_block`: items a block at least (64
/// where each writes a byte of a shared array, so that two workers do not write one cache line).
template <class MakeState, class Solve, class Refuse>
void run_on_workers(std::size_t count, const BatchOptions& batch, const MakeState& make_state,
                    const Solve& solve, const Refuse& refuse, std::size_t min_block = 1) {
  const std::size_t block = std::clamp<std::size_t>(count / 512, min_block, 64);
  const int n = workers_for(count, batch.threads);
  std::atomic<std::size_t> next_block{0};
  std::atomic<std::size_t> first_bad{count};
  std::mutex refused_lock;  // the error of the first invalid item, kept as it was thrown
  std::optional<InvalidArgument> refused;
  std::exception_ptr unexpected;
  std::atomic<bool> broken{false};
  // Blocks until none is left, calling after_block() after each.
  auto work = [&](const auto& after_block) {
    try {
      auto state = make_state();
      for (;;) {
        const std::size_t begin = next_block.fetch_add(block, std::memory_order_relaxed);
        if (begin >= count || begin > first_bad.load(std::memory_order_relaxed) || broken.load())
          return;
        const std::size_t end = std::min(begin + block, count);
        for (std::size_t i = begin; i < end; ++i) {
          try {
            solve(state, i);
          } catch (const InvalidArgument& e) {
            std::lock_guard<std::mutex> lock(refused_lock);
            if (i < first_bad.load()) {
              first_bad.store(i);
              refused = e;
            }
            return;
          }
        }
        after_block(end - begin);
      }
    } catch (...) {  // not expected; kept so that no worker ends the program
      if (!broken.exchange(true)) unexpected = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  const auto start = std::chrono::steady_clock::now();
  // Items solved, and since the clock was read: after each of the first few (an NLopt problem
  // takes milliseconds), then every fourth (a read costs 37 ns, a bar's impact 300).
  std::size_t solved = 0, unclocked = 0;
  work([&](std::size_t items) {
    if (static_cast<int>(pool.size()) + 1 >= n) return;
    solved += items;
    if ((unclocked += items) < 4 && solved > 8) return;
    unclocked = 0;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::size_t left = count - std::min(next_block.load(std::memory_order_relaxed), count);
    if (elapsed < kPaceAfter ||
        elapsed * static_cast<double>(left) < kWorthSharing * static_cast<double>(solved))
      return;
    pool.reserve(static_cast<std::size_t>(n - 1));
    for (int t = 1; t < n; ++t) pool.emplace_back([&] { work([](std::size_t) {}); });
  });
  for (auto& t : pool) t.join();
  if (unexpected) std::rethrow_exception(unexpected);
  if (refused) refuse(first_bad.load(), *refused);
}

// results of the wrong size, named.
void require_results(std::size_t results, std::size_t count, const char* per) {
  if (results != count)
    throw InvalidArgument("results", "needs one entry per " + std::string(per) + " (" +
                                         std::to_string(count) + "), got " +
                                         std::to_string(results));
}

/// The velocities of a batch of one configuration: n rows, one per degree of freedom of the
/// solver; their count.
template <int N, int C>
std::size_t velocities_of(const ImpactSolverT<N, C>& solver,
                          const Eigen::Ref<const Eigen::MatrixXd>& qdot_A) {
  const int n = solver.problem().dofs();
  if (qdot_A.rows() != n)
    throw InvalidArgument("qdot_A", "must have " + std::to_string(n) +
                                        " rows (one per degree of freedom, a column per impact), "
                                        "got " +
                                        std::to_string(qdot_A.rows()) + "x" +
                                        std::to_string(qdot_A.cols()));
  return static_cast<std::size_t>(qdot_A.cols());
}

/// The error the prepared solve gave for velocity i: its own refusal named by index
/// (`qdot_A[7][1]`: velocity 7, its entry 1); another member's (W_N: a contact velocity that
/// overflows) keeps its name and says which velocity.
[[noreturn]] void refuse_velocity(std::size_t i, const InvalidArgument& e) {
  const std::string index = "qdot_A[" + std::to_string(i) + "]";
  const std::string reason = std::string(e.what()).substr(e.name().size() + 2);
  if (e.name().rfind("qdot_A", 0) == 0) throw InvalidArgument(index + e.name().substr(6), reason);
  throw InvalidArgument(e.name(), reason + " (" + index + ")");
}
}  // namespace

template <int N, int C>
void solve_batch(std::span<const ImpactProblemT<N, C>> problems, const ImpactLaw& law,
                 std::span<ImpactResultT<N, C>> results, const SolverOptions& options,
                 const BatchOptions& batch) {
  batch.validate();
  options.validate();
  require_results(results.size(), problems.size(), "problem");
  // solve_impact validates each problem; the first invalid one by index is reported.
  run_on_workers(
      problems.size(), batch, [] { return SmallImpactResult{}; },  // a heap-stored one's answer
      [&](SmallImpactResult& small, std::size_t i) {
        solve_into(problems[i], law, options, results[i], small);
      },
      refuse);
}

template <int N, int C>
void solve_batch(const ImpactSolverT<N, C>& solver, const Eigen::Ref<const Eigen::MatrixXd>& qdot_A,
                 std::span<ImpactResultT<N, C>> results, const BatchOptions& batch) {
  batch.validate();
  const std::size_t count = velocities_of(solver, qdot_A);
  require_results(results.size(), count, "velocity");
  run_on_workers(
      count, batch, [&] { return ImpactSolverT<N, C>(solver); },
      [&](ImpactSolverT<N, C>& own, std::size_t i) {
        own.solve_into(qdot_A.col(static_cast<Eigen::Index>(i)), results[i]);
      },
      refuse_velocity);
}

template <int N, int C>
void solve_batch(const ImpactSolverT<N, C>& solver, const Eigen::Ref<const Eigen::MatrixXd>& qdot_A,
                 BatchAnswers& answers, const BatchOptions& batch) {
  batch.validate();
  const std::size_t count = velocities_of(solver, qdot_A);
  answers.resize(solver.problem().dofs(), solver.problem().contacts(),
                 static_cast<Eigen::Index>(count));
  // A worker's own solver, which writes each answer into its column.
  run_on_workers(
      count, batch, [&] { return ImpactSolverT<N, C>(solver); },
      [&](ImpactSolverT<N, C>& own, std::size_t i) {
        const auto k = static_cast<Eigen::Index>(i);
        own.solve_into(qdot_A.col(k), answers, k);
      },
      refuse_velocity, 64);
}

template <int N, int C>
std::vector<ImpactResultT<N, C>> solve_batch(const ImpactSolverT<N, C>& solver,
                                             const Eigen::Ref<const Eigen::MatrixXd>& qdot_A,
                                             const BatchOptions& batch) {
  std::vector<ImpactResultT<N, C>> results(static_cast<std::size_t>(qdot_A.cols()));
  solve_batch(solver, qdot_A, std::span<ImpactResultT<N, C>>(results), batch);
  return results;
}

template <int N, int C>
std::vector<ImpactResultT<N, C>> solve_batch(std::span<const ImpactProblemT<N, C>> problems,
                                             const ImpactLaw& law, const SolverOptions& options,
                                             const BatchOptions& batch) {
  std::vector<ImpactResultT<N, C>> results(problems.size());
  solve_batch(problems, law, std::span<ImpactResultT<N, C>>(results), options, batch);
  return results;
}

template std::vector<ImpactResult> solve_batch(std::span<const ImpactProblem>, const ImpactLaw&,
                                               const SolverOptions&, const BatchOptions&);
template std::vector<SmallImpactResult> solve_batch(std::span<const SmallImpactProblem>,
                                                    const ImpactLaw&, const SolverOptions&,
                                                    const BatchOptions&);
template void solve_batch(std::span<const ImpactProblem>, const ImpactLaw&, std::span<ImpactResult>,
                          const SolverOptions&, const BatchOptions&);
template void solve_batch(std::span<const SmallImpactProblem>, const ImpactLaw&,
                          std::span<SmallImpactResult>, const SolverOptions&, const BatchOptions&);
template void solve_batch(const ImpactSolver&, const Eigen::Ref<const Eigen::MatrixXd>&,
                          std::span<ImpactResult>, const BatchOptions&);
template void solve_batch(const SmallImpactSolver&, const Eigen::Ref<const Eigen::MatrixXd>&,
                          std::span<SmallImpactResult>, const BatchOptions&);
template void solve_batch(const ImpactSolver&, const Eigen::Ref<const Eigen::MatrixXd>&,
                          BatchAnswers&, const BatchOptions&);
template void solve_batch(const SmallImpactSolver&, const Eigen::Ref<const Eigen::MatrixXd>&,
                          BatchAnswers&, const BatchOptions&);
template std::vector<ImpactResult> solve_batch(const ImpactSolver&,
                                               const Eigen::Ref<const Eigen::MatrixXd>&,
                                               const BatchOptions&);
template std::vector<SmallImpactResult> solve_batch(const SmallImpactSolver&,
                                                    const Eigen::Ref<const Eigen::MatrixXd>&,
                                                    const BatchOptions&);

}  // namespace fremond
