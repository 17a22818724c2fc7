// Throughput of solve_batch: 4,096 bar impacts at random angles and velocities (the lower end
// approaching), certified, under Newton + Coulomb and Frémond + Coulomb (p = 3), on 1 and 2
// threads; and 4,096 velocities of one bar at a fixed angle, solved by a prepared solver (Monte
// Carlo over initial conditions). items_per_second is impacts per second.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <type_traits>
#include <vector>

#include "fremond/fremond.hpp"
#include "support/fixtures.hpp"

namespace {

using namespace fremond;

std::vector<ImpactProblem> bars(int count) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(0.05, 1.5), speed(-3.0, 3.0);
  std::vector<ImpactProblem> out;
  for (int i = 0; i < count; ++i)
    out.push_back(fixtures::bar(
        angle(rng), Eigen::Vector3d(speed(rng), -1.0 - std::fabs(speed(rng)), speed(rng))));
  return out;
}

template <class Problem = ImpactProblem>
void run(benchmark::State& state, const ImpactLaw& law) {
  std::vector<Problem> problems;
  for (const auto& p : bars(4096)) {
    if constexpr (std::is_same_v<Problem, ImpactProblem>)
      problems.push_back(p);
    else
      problems.push_back(to_small(p));
  }
  BatchOptions batch;
  batch.threads = static_cast<int>(state.range(0));
  // The results reused from one batch to the next, as a sweep does.
  std::vector<ImpactResultT<Problem::kMaxDofs, Problem::kMaxContacts>> results(problems.size());
  for (auto _ : state) {
    solve_batch(std::span<const Problem>(problems), law, std::span(results), {}, batch);
    benchmark::DoNotOptimize(results.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(problems.size()));
}

void BM_Batch_Bar_NewtonCoulomb(benchmark::State& state) {
  run(state, ImpactLaw::newton_coulomb(0.9, 1.0));
}
void BM_Batch_Bar_FremondCoulomb_p3(benchmark::State& state) {
  run(state, ImpactLaw::fremond_coulomb(PowerPotential(85.36, 3.0), 1.0));
}
// The same problems in the small form: results without heap memory.
void BM_Batch_SmallBar_NewtonCoulomb(benchmark::State& state) {
  run<SmallImpactProblem>(state, ImpactLaw::newton_coulomb(0.9, 1.0));
}
void BM_Batch_SmallBar_FremondCoulomb_p3(benchmark::State& state) {
  run<SmallImpactProblem>(state, ImpactLaw::fremond_coulomb(PowerPotential(85.36, 3.0), 1.0));
}

// One configuration (the bar at 0.7 rad), 4,096 velocities drawn as bars() draws them, each column
// one impact, solved by a prepared solver (range(1): 1 small, 0 heap-stored).
Eigen::MatrixXd bar_velocities(int count) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> speed(-3.0, 3.0);
  Eigen::MatrixXd v(3, count);
  for (int i = 0; i < count; ++i) v.col(i) << speed(rng), -1.0 - std::fabs(speed(rng)), speed(rng);
  return v;
}

// `columns`: the answers kept as BatchAnswers' columns instead of whole results.
template <class Solver, bool columns = false>
void run_prepared(benchmark::State& state, const ImpactLaw& law) {
  const ImpactProblem bar = fixtures::bar(0.7, Eigen::Vector3d(0.0, -1.0, 0.0));
  const Solver solver = [&] {
    if constexpr (std::is_same_v<Solver, SmallImpactSolver>)
      return Solver(to_small(bar), law);
    else
      return Solver(bar, law);
  }();
  const Eigen::MatrixXd v = bar_velocities(4096);
  BatchOptions batch;
  batch.threads = static_cast<int>(state.range(0));
  std::vector<typename Solver::Result> results(columns ? 0 : static_cast<std::size_t>(v.cols()));
  BatchAnswers answers;
  for (auto _ : state) {
    if constexpr (columns)
      solve_batch(solver, v, answers, batch);
    else
      solve_batch(solver, v, std::span(results), batch);
    benchmark::DoNotOptimize(results.data());
    benchmark::DoNotOptimize(answers.qdot_E.data());
  }
  state.SetItemsProcessed(state.iterations() * v.cols());
}

void BM_Batch_PreparedBar_NewtonCoulomb(benchmark::State& state) {
  run_prepared<ImpactSolver>(state, ImpactLaw::newton_coulomb(0.9, 1.0));
}
void BM_Batch_PreparedSmallBar_NewtonCoulomb(benchmark::State& state) {
  run_prepared<SmallImpactSolver>(state, ImpactLaw::newton_coulomb(0.9, 1.0));
}
void BM_Batch_PreparedSmallBarColumns_NewtonCoulomb(benchmark::State& state) {
  run_prepared<SmallImpactSolver, true>(state, ImpactLaw::newton_coulomb(0.9, 1.0));
}
void BM_Batch_PreparedSmallBarColumns_FremondCoulomb_p3(benchmark::State& state) {
  run_prepared<SmallImpactSolver, true>(
      state, ImpactLaw::fremond_coulomb(PowerPotential(85.36, 3.0), 1.0));
}
void BM_Batch_PreparedSmallBar_FremondCoulomb_p3(benchmark::State& state) {
  run_prepared<SmallImpactSolver>(state,
                                  ImpactLaw::fremond_coulomb(PowerPotential(85.36, 3.0), 1.0));
}

BENCHMARK(BM_Batch_Bar_NewtonCoulomb)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Batch_Bar_FremondCoulomb_p3)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Batch_SmallBar_NewtonCoulomb)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Batch_SmallBar_FremondCoulomb_p3)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Batch_PreparedBar_NewtonCoulomb)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Batch_PreparedSmallBar_NewtonCoulomb)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Batch_PreparedSmallBarColumns_NewtonCoulomb)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Batch_PreparedSmallBarColumns_FremondCoulomb_p3)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Batch_PreparedSmallBar_FremondCoulomb_p3)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
