// Stronge's law with Coulomb friction (docs/stronge.md) on the paper's bar at its first impact,
// beside Newton + Coulomb on the same problem:
//  - BM_Stronge_Kernel: the closed form alone, from the contact's Delassus matrix and velocities
//    (what BM_Classical_Kernel times for Newton + Coulomb);
//  - BM_Stronge_SolveImpact / BM_NewtonCoulomb_SolveImpact: the public entry point with
//    validation, the contact space, the result's velocities and the certificate.
// After timing, each checks its answer against the hand-derived one of tests/unit/stronge_law_test.
//  - BM_Stronge_ThreeBallChain/eta: one impact of a ball at speed 1 on two touching balls at rest
//    (masses 1, e* = 1) by the distributing law on the coupled contacts, η = 1 (linear) and 1.5
//    (Hertz); BM_Stronge_LzbKernel the same integration from G alone. Checked after timing
//    against the conservation of momentum and of energy, and the middle ball's velocity against
//    Hertz's contact integrated in time (tests/unit/stronge_lzb_test).
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>

#include "fremond/fremond.hpp"
#include "laws/stronge/darboux_keller.hpp"
#include "laws/stronge/lzb.hpp"
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

// The chain's velocities after: Σ v = 1 and ½ Σ v² = ½ (elastic), each to 1e-9; under Hertz's law
// (η = 1.5) the middle ball leaves at 0.0764030 (the time integration's 0.07640303907).
void check_chain(benchmark::State& state, const Eigen::Vector3d& v, double eta) {
  state.counters["v2"] = v(1);
  if (!(std::fabs(v.sum() - 1.0) <= 1e-9 && std::fabs(0.5 * v.squaredNorm() - 0.5) <= 1e-9))
    state.SkipWithError("the chain's momentum or energy is not kept");
  if (eta == 1.5 && !(std::fabs(v(1) - 0.07640303907) <= 1e-6))
    state.SkipWithError("the middle ball's velocity differs from Hertz's in time");
}

ImpactProblem three_ball_chain() {
  ImpactProblem pb;
  pb.M = Eigen::Matrix3d::Identity();
  pb.W_N = Eigen::MatrixXd(3, 2);
  pb.W_N << -1.0, 0.0, 1.0, -1.0, 0.0, 1.0;  // D_N = ẋ_2 − ẋ_1, ẋ_3 − ẋ_2
  pb.qdot_A = Eigen::Vector3d(1.0, 0.0, 0.0);
  return pb;
}

void BM_Stronge_ThreeBallChain(benchmark::State& state) {
  const double eta = static_cast<double>(state.range(0)) / 10.0;
  const ImpactProblem pb = three_ball_chain();
  StrongeLaw stronge;
  stronge.e = 1.0;
  stronge.eta = eta;
  const ImpactLaw law = stronge;
  ImpactResult r;
  for (auto _ : state) {
    r = solve_impact(pb, law);
    benchmark::DoNotOptimize(r.P_N.data());
  }
  state.counters["steps"] = r.solver.iterations;
  if (r.solver.status != SolverStatus::converged) state.SkipWithError("not converged");
  check_chain(state, r.qdot_E, eta);
}
BENCHMARK(BM_Stronge_ThreeBallChain)->Arg(10)->Arg(15)->Unit(benchmark::kMicrosecond);

void BM_Stronge_LzbKernel(benchmark::State& state) {
  const double eta = static_cast<double>(state.range(0)) / 10.0;
  Eigen::Matrix2d G;
  G << 2.0, -1.0, -1.0, 2.0;
  const Eigen::Vector2d D_A(-1.0, 0.0);
  std::array<detail::LzbContact, 2> contacts{};
  for (auto& c : contacts) {
    c.e = 1.0;
    c.eta = eta;
  }
  detail::LzbOptions options;
  options.tolerance = 1e-13;  // what solve_impact uses at the default tolerance
  detail::LzbAnswer a;
  for (auto _ : state) {
    a = detail::lzb_impact(G, D_A, contacts, options);
    benchmark::DoNotOptimize(a.P_N.data());
  }
  state.counters["steps"] = a.steps;
  check_chain(state, Eigen::Vector3d(1.0 - a.P_N(0), a.P_N(0) - a.P_N(1), a.P_N(1)), eta);
}
BENCHMARK(BM_Stronge_LzbKernel)->Arg(10)->Arg(15)->Unit(benchmark::kMicrosecond);

}  // namespace
