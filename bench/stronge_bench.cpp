// Stronge's law with Coulomb friction (docs/stronge.md) on the paper's bar at its first impact,
// beside Newton + Coulomb on the same problem:
//  - BM_Stronge_Kernel: the closed form alone, from the contact's Delassus matrix and velocities
//    (what BM_Classical_Kernel times for Newton + Coulomb);
//  - BM_Stronge_SolveImpact / BM_NewtonCoulomb_SolveImpact: the public entry point with
//    validation, the contact space, the result's velocities and the certificate.
// After timing, each checks its answer against the hand-derived one of tests/unit/stronge_law_test.
#include <benchmark/benchmark.h>

#include <cmath>

#include "fremond/fremond.hpp"
#include "laws/stronge/darboux_keller.hpp"
#include "support/fixtures.hpp"

namespace {
using namespace fremond;

// The bar's first impact: G_NN = G_TT = 2.5, G_NT = −1.5, D_TA = 2; slips then sticks.
double expected_P_N(double v) {
  const double dn1 = v - 2.0, W_c = -0.5 * (v + dn1) * 0.5 - dn1 * dn1 / 3.2;
  return 0.5 + dn1 / 1.6 + std::sqrt(0.81 * -W_c / 0.8);
}

void check(benchmark::State& state, double P_N, double v) {
  const double want = expected_P_N(v);
  state.counters["P_N"] = P_N;
  if (!(std::fabs(P_N - want) <= 1e-13 * want))
    state.SkipWithError("P_N differs from the hand-derived answer");
}

ImpactLaw stronge_coulomb() {
  StrongeLaw law;
  law.e = 0.9;
  law.coulomb = true;
  law.mu = 1.0;
  return law;
}

void BM_Stronge_Kernel(benchmark::State& state) {
  const SmallImpactProblem pb = fixtures::bar_first_impact();
  const double v = -pb.qdot_A(1);
  double D_NA = -v;
  detail::StrongeAnswer a;
  for (auto _ : state) {
    benchmark::DoNotOptimize(D_NA);
    a = detail::stronge_contact(2.5, -1.5, 2.5, D_NA, 2.0, 0.9, 1.0);
    benchmark::DoNotOptimize(a.P_N);
  }
  check(state, a.P_N, v);
}
BENCHMARK(BM_Stronge_Kernel);

void BM_Stronge_SolveImpact(benchmark::State& state) {
  const SmallImpactProblem pb = fixtures::bar_first_impact();
  const ImpactLaw law = stronge_coulomb();
  SmallImpactResult r;
  for (auto _ : state) {
    r = solve_impact(pb, law);
    benchmark::DoNotOptimize(r.P_N.data());
  }
  check(state, r.P_N(0), -pb.qdot_A(1));
}
BENCHMARK(BM_Stronge_SolveImpact);

void BM_NewtonCoulomb_SolveImpact(benchmark::State& state) {
  const SmallImpactProblem pb = fixtures::bar_first_impact();
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.9, 1.0);
  SmallImpactResult r;
  for (auto _ : state) {
    r = solve_impact(pb, law);
    benchmark::DoNotOptimize(r.P_N.data());
  }
  state.counters["P_N"] = r.P_N(0);
}
BENCHMARK(BM_NewtonCoulomb_SolveImpact);

}  // namespace
