// One impact of a scene of several bodies (scenes/multibody.hpp), as a run meets it: the touching
// contacts found, the problem posed from the bodies (M of 3 entries a body, W from both bodies of
// each contact) and solved.
//  - BM_Scene_CradleImpact/balls/law: Newton's cradle of 3 or 5 equal balls, the first struck at
//    1 m/s; law 0 Newton (e = 1), 1 Stronge's distributing law (Liu-Zhao-Brogliato, e* = 1, Hertz's
//    η = 1.5). Checked after timing: momentum 1 and energy ½ kept (to 1e-9), and Newton's answer
//    against the hand-derived one (tests/unit/ball_chain_test), the last ball at 2/3 (3 balls) or
//    0.4 (5 balls).
//  - BM_Scene_CradleSolveOnly: the same problem posed once, solve_impact alone, for the share of
//    posing in the above.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "fremond/fremond.hpp"

namespace {
using namespace fremond;

ImpactLaw cradle_law(int which) {
  if (which == 0) return ImpactLaw::newton(1.0);
  StrongeLaw s;
  s.e = 1.0;
  s.eta = 1.5;
  return s;
}

void check(benchmark::State& state, const MultiBodyScene& s, const Eigen::VectorXd& v, int law) {
  const int n = static_cast<int>(s.bodies.size());
  const double last = v(3 * (n - 1));
  state.counters["v_last"] = last;
  double p = 0.0, e = 0.0;
  for (int i = 0; i < n; ++i) {
    p += v(3 * i);
    e += 0.5 * v(3 * i) * v(3 * i);
  }
  if (!(std::fabs(p - 1.0) <= 1e-9 && std::fabs(e - 0.5) <= 1e-9))
    state.SkipWithError("the cradle's momentum or energy is not kept");
  if (law == 0 && !(std::fabs(last - (n == 3 ? 2.0 / 3 : 0.4)) <= 1e-15))
    state.SkipWithError("Newton's answer differs from the hand-derived one");
}

MultiBodyScene cradle(benchmark::State& state) {
  CradleParameters p;
  p.balls = static_cast<int>(state.range(0));
  return cradle_scene(p, cradle_law(static_cast<int>(state.range(1))));
}

void BM_Scene_CradleImpact(benchmark::State& state) {
  const MultiBodyScene s = cradle(state);
  ImpactResult r;
  for (auto _ : state) {
    const std::vector<int> idx = touching_contacts(s, s.initial.q);
    r = solve_impact(impact_problem(s, s.initial, idx), s.law);
    benchmark::DoNotOptimize(r.P_N.data());
  }
  if (!r.ok()) state.SkipWithError("not converged");
  check(state, s, r.qdot_E, static_cast<int>(state.range(1)));
}
BENCHMARK(BM_Scene_CradleImpact)
    ->ArgNames({"balls", "law"})
    ->Args({3, 0})
    ->Args({3, 1})
    ->Args({5, 0})
    ->Args({5, 1})
    ->Unit(benchmark::kMicrosecond);

void BM_Scene_CradleSolveOnly(benchmark::State& state) {
  const MultiBodyScene s = cradle(state);
  const ImpactProblem pb = impact_problem(s, s.initial, touching_contacts(s, s.initial.q));
  ImpactResult r;
  for (auto _ : state) {
    r = solve_impact(pb, s.law);
    benchmark::DoNotOptimize(r.P_N.data());
  }
  if (!r.ok()) state.SkipWithError("not converged");
  check(state, s, r.qdot_E, static_cast<int>(state.range(1)));
}
BENCHMARK(BM_Scene_CradleSolveOnly)
    ->ArgNames({"balls", "law"})
    ->Args({3, 0})
    ->Args({3, 1})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
