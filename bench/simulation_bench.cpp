// The paper's bar (the paper's Fig. 1) over 3 s of simulated time, no files written: event-driven
// with Frémond's law (target < 0.1 ms a run) and Moreau–Jean on the same scene (target < 0.1 µs a
// step).
#include <benchmark/benchmark.h>

#include "fremond/scenes/presets.hpp"
#include "fremond/simulation/calibration.hpp"
#include "fremond/simulation/simulate.hpp"

namespace {

using fremond::PaperLaw;

const fremond::Scene& paper_scene(PaperLaw law) {
  static const fremond::Scene scenes[] = {fremond::paper_bar_scene(PaperLaw::newton),
                                          fremond::paper_bar_scene(PaperLaw::newton_coulomb),
                                          fremond::paper_bar_scene(PaperLaw::poisson_coulomb),
                                          fremond::paper_bar_scene(PaperLaw::fremond_coulomb),
                                          fremond::paper_bar_scene(PaperLaw::fremond_viscous)};
  return scenes[static_cast<int>(law)];
}

void run(benchmark::State& state, PaperLaw law, fremond::Integrator integrator) {
  const fremond::Scene& scene = paper_scene(law);
  fremond::SimulationOptions options;
  options.t_end = 3.0;
  options.integrator = integrator;
  long impacts = 0, steps = 0;
  for (auto _ : state) {
    const fremond::SimulationResult r = fremond::simulate(scene, options);
    benchmark::DoNotOptimize(r.state);
    impacts = r.impacts;
    steps = r.steps;
  }
  state.counters["impacts"] = static_cast<double>(impacts);
  state.counters["mj_steps"] = static_cast<double>(steps);
  if (integrator == fremond::Integrator::moreau_jean)
    state.counters["per_step"] = benchmark::Counter(
        static_cast<double>(steps),
        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_EventDriven(benchmark::State& state) {
  run(state, static_cast<PaperLaw>(state.range(0)), fremond::Integrator::event_driven);
}
void BM_MoreauJean(benchmark::State& state) {
  run(state, static_cast<PaperLaw>(state.range(0)), fremond::Integrator::moreau_jean);
}

// Arguments: the PaperLaw, in the order newton, newton_coulomb, poisson_coulomb,
// fremond_coulomb (3, the one of the target), fremond_viscous.
BENCHMARK(BM_EventDriven)->DenseRange(0, 4)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MoreauJean)->DenseRange(0, 4)->Unit(benchmark::kMicrosecond);

}  // namespace
