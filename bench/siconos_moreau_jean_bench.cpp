// Siconos Kernel's Moreau-Jean time stepping on the paper's bar (the paper's Fig. 1): x = 0, ẋ = 2,
// y = 1, ẏ = 0, θ = π/4, θ̇ = 0, both ends may touch, Newton e = 0.9 with Coulomb μ = 1, h = 1e-4, 3
// s. Counters: µs per step, the impact times, the largest penetration, the energies. After timing
// it checks the first impact against the closed form of problems.hpp: its time within two steps of
// t₁ = √(2 (y₀ − l sin θ₀)/g), and the velocity after it within O(h g) of Newton + Coulomb's.
#include <benchmark/benchmark.h>

#include <string>

#include "problems.hpp"
#ifdef FREMOND_HAVE_SICONOS
#include "siconos_peers.hpp"
#endif

namespace {

using namespace fremond;
using namespace fremond::bench;

#ifndef FREMOND_HAVE_SICONOS

void BM_Siconos_MoreauJean_NotBuilt(benchmark::State& state) {
  state.SkipWithError(
      "built without Siconos: install libsiconos-numerics-dev and libsiconos-kernel-dev, then "
      "reconfigure with CMake");
  for (auto _ : state) {
  }
}
BENCHMARK(BM_Siconos_MoreauJean_NotBuilt);

#else

void BM_Siconos_MoreauJean(benchmark::State& state, siconos::Fc2dSolver solver) {
  siconos::MoreauJeanSettings settings;
  settings.solver = solver;
  siconos::MoreauJeanRun run;
  double seconds = 0.0;
  for (auto _ : state) {
    run = siconos::simulate_bar_moreau_jean(settings);
    seconds += run.cpu_seconds;
  }
  const double runs = static_cast<double>(state.iterations());
  state.counters["us_per_step"] = 1e6 * seconds / (runs * run.steps);  // CPU time
  state.counters["steps"] = run.steps;
  state.counters["impacts"] = static_cast<double>(run.impact_times.size());
  for (std::size_t i = 0; i < run.impact_times.size() && i < 3; ++i)
    state.counters["t_impact" + std::to_string(i)] = run.impact_times[i];
  state.counters["penetration"] = run.max_penetration;
  state.counters["E0"] = run.energy_initial;
  state.counters["E_end"] = run.energy_final;
  state.counters["dE_max"] = run.energy_max_increase;
  state.SetLabel(bench_label("bar_fall_3s", "newton_coulomb"));

  // The first impact in closed form: the lower end (s = −1) at t₁, then Newton + Coulomb on it.
  const double t1 = bar_first_impact_time();
  const SmallImpactProblem p = bar_first_impact(true);
  const ContactSpace cs = contact_space(p);
  const Eigen::VectorXd qE = velocity_after(
      p, cs, newton_coulomb_one_contact(cs.G, cs.D_A(0), cs.D_A(1), settings.e, settings.mu));
  if (run.impact_times.empty()) {
    state.SkipWithError("no impact");
    return;
  }
  double dv = 0.0;
  for (int i = 0; i < 3; ++i) dv = std::max(dv, std::abs(run.qdot_after_first_impact[i] - qE(i)));
  state.counters["t1_err"] = run.impact_times[0] - t1;
  state.counters["v1_err"] = dv;
  // Moreau-Jean closes the contact at the step whose end would penetrate, so the impact lands
  // within a step or two of t₁, and the velocity after it differs from the impact law's by the
  // gravity and rotation within the step: O(h g) with a modest constant.
  if (run.impact_ends[0] != -1 || std::abs(run.impact_times[0] - t1) > 2 * settings.h)
    state.SkipWithError("first impact at the wrong end or time");
  else if (dv > 50 * settings.h * kGravity)
    state.SkipWithError(("velocity after the first impact off by " + std::to_string(dv)).c_str());
}

const bool registered = [] {
  using siconos::Fc2dSolver;
  benchmark::AddCustomContext("siconos", siconos::version());
  for (Fc2dSolver s : {Fc2dSolver::nsgs, Fc2dSolver::lemke}) {
    benchmark::RegisterBenchmark(("BM_Siconos_MoreauJean/" + std::string(siconos::to_string(s)) +
                                  "/bar_fall_3s/newton_coulomb")
                                     .c_str(),
                                 BM_Siconos_MoreauJean, s)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(1.0);
  }
  return true;
}();

#endif  // FREMOND_HAVE_SICONOS

}  // namespace
