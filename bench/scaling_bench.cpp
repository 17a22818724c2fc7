// Scaling (issue 6, item 4): the cost of one impact solve as the contacts grow, and the throughput
// of a batch of independent impacts on both cores.
//
//  - BM_Contacts/<law>/<c>: a flat plate (the bar of the paper's Fig. 1 lying at θ = 0) touching
//  the ground at
//    c = 1, 2, 4, 8, 16, 32 points at once; 3 degrees of freedom, so G is singular from c = 4 on.
//    Heap-stored problem (ImpactProblem); for c ≤ 4 also the stack-stored one ("storage=small").
//  - BM_RandomSize/<law>/<n>: random bodies with n = 6, 12, 18, 24, 30 degrees of freedom and n/2
//    contacts (fremond_suite.hpp's generator), cycling through 8 problems.
//  - BM_PreparedContacts, BM_PreparedRandomSize (Newton + Coulomb): the same plates (8 to 32
//    contacts) and random bodies (n = 12 to 30) on the prepared solver, set up once per problem.
//  - BM_Siconos_*: Siconos Numerics on the Newton and Newton + Coulomb cases (LCP by Lemke, and the
//    2-D friction-contact NSGS), from the data like every peer, labelled alike for compare.py.
//  - BM_Throughput/<law>/threads:T: 4096 independent impacts of the bar (its first impact with
//    q̇_A spread around the paper's), split over T threads; items_per_second is impacts per second.
// solve_impact runs with check_uniqueness off (the Siconos peers do not look for other solutions).
// Each benchmark reports the fraction of solves that converged, the worst law residual, and for
// Frémond's law without Coulomb the worst error of q̇_E against the quad reference (`err`).
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "fremond_suite.hpp"
#ifdef FREMOND_HAVE_SICONOS
#include "siconos_peers.hpp"
#endif

namespace {

using namespace fremond;
using namespace fremond::bench;

struct Law {
  std::string name;
  ImpactLaw law;
  bool friction;
  FremondLawSpec spec;  ///< for the quad reference (Frémond without Coulomb)
  bool has_reference;
};

const std::vector<Law>& laws() {
  static const std::vector<Law> all = [] {
    const double k3 = bar_fremond_k_normal(3.0);
    const FremondLawSpec p3 = normal_only(k3, 3.0),
                         viscous = with_dead_zone(k3, 3.0, 1.5, 2.0, 0.2);
    return std::vector<Law>{
        {"fremond_p3", p3.law(), false, p3, true},
        {"fremond_p3_viscous", viscous.law(), true, viscous, true},
        {"fremond_p3_coulomb",
         ImpactLaw::fremond_coulomb(PowerPotential(k3, 3.0), kFriction),
         true,
         {},
         false},
        {"newton", ImpactLaw::newton(kRestitution), false, {}, false},
        {"newton_coulomb", ImpactLaw::newton_coulomb(kRestitution, kFriction), true, {}, false}};
  }();
  return all;
}

SolverOptions options() {
  SolverOptions o;
  o.check_uniqueness = false;
  return o;
}

/// ‖q̇_E − q̇_E,ref‖_M / ‖q̇_A‖_M against the quad reference (fremond_several), as in the suite.
template <class Problem, class Vec>
double reference_error(const Problem& p, const Law& law, const Vec& qdot_E) {
  const Eigen::MatrixXd M = p.M, WN = p.W_N;
  const Eigen::MatrixXd WT = law.spec.tangential == FremondLawSpec::Tangential::none
                                 ? Eigen::MatrixXd(p.dofs(), 0)
                                 : Eigen::MatrixXd(p.W_T);
  const Eigen::VectorXd qA = p.qdot_A;
  const ref::Solution s = ref::fremond_several(
      ref::problem_from(M, WN, WT, qA), {law.spec.ref_normal()}, {law.spec.ref_tangential()});
  if (!s.ok) return std::nan("");
  const int n = p.dofs();
  ref::quad num = 0, den = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const ref::quad di = static_cast<ref::quad>(qdot_E(i)) - s.qdot_E[i];
      const ref::quad dj = static_cast<ref::quad>(qdot_E(j)) - s.qdot_E[j];
      num += di * static_cast<ref::quad>(M(i, j)) * dj;
      den += static_cast<ref::quad>(qA(i)) * static_cast<ref::quad>(M(i, j)) *
             static_cast<ref::quad>(qA(j));
    }
  return static_cast<double>(sqrtq(num / den));
}

/// The answers' counters of a benchmark over `problems`: the share converged, the worst law
/// residual and (where the quad reference covers the law) the worst error; the label with the
/// method of the last answer.
template <class Problem>
void answer_counters(benchmark::State& state, const std::vector<Problem>& problems, const Law& law,
                     const std::string& label) {
  const SolverOptions opt = options();
  int converged = 0;
  double residual = 0.0, err = 0.0;
  std::string method;
  for (const Problem& p : problems) {
    const auto r = solve_impact(p, law.law, opt);
    if (r.ok()) {
      ++converged;
      residual = std::max(residual, law_residual(p, law.law, r));
      if (law.has_reference) err = std::max(err, reference_error(p, law, r.qdot_E));
    }
    method = std::string(to_string(r.solver.method));
  }
  if (law.has_reference) state.counters["err"] = err;
  state.counters["contacts"] = problems[0].contacts();
  state.counters["dofs"] = problems[0].dofs();
  state.counters["converged"] =
      static_cast<double>(converged) / static_cast<double>(problems.size());
  state.counters["residual"] = residual;
  state.SetLabel(label + " method=" + method);
}

template <class Problem>
void solve_loop(benchmark::State& state, const std::vector<Problem>& problems, const Law& law,
                const std::string& label) {
  const SolverOptions opt = options();
  std::size_t k = 0;
  for (auto _ : state) {
    const auto r = solve_impact(problems[k], law.law, opt);
    k = k + 1 == problems.size() ? 0 : k + 1;
    benchmark::DoNotOptimize(r.qdot_E.data());
  }
  answer_counters(state, problems, law, label);
}

/// The prepared solver (ImpactSolver), set up once per problem, then solved from its q̇_A: what a
/// caller pays per impact once the configuration is known. Its answers are solve_impact's to the
/// last bit, which the loop checks before the counters.
void prepared_loop(benchmark::State& state, const std::vector<ImpactProblem>& problems,
                   const Law& law, const std::string& label) {
  std::vector<ImpactSolver> solvers;
  for (const ImpactProblem& p : problems) solvers.emplace_back(p, law.law, options());
  std::size_t k = 0;
  for (auto _ : state) {
    const ImpactResult& r = solvers[k].solve(problems[k].qdot_A);
    k = k + 1 == solvers.size() ? 0 : k + 1;
    benchmark::DoNotOptimize(r.qdot_E.data());
  }
  for (std::size_t i = 0; i < problems.size(); ++i)
    if (!(solvers[i].solve(problems[i].qdot_A).qdot_E ==
          solve_impact(problems[i], law.law, options()).qdot_E)) {
      state.SkipWithError("the prepared solver's answer differs from solve_impact's");
      return;
    }
  answer_counters(state, problems, law, label);
}

std::string plate_name(int c) {
  return "plate_c" + std::to_string(c);
}
std::string random_name(int n) {
  return "random_n" + std::to_string(n) + "_c" + std::to_string(n / 2);
}

void BM_Contacts(benchmark::State& state, const Law* law, bool small) {
  const int c = static_cast<int>(state.range(0));
  const ImpactProblem p = plate_many_contacts(c, law->friction);
  const std::string label = bench_label(plate_name(c), law->name) + " stage=solve_impact" +
                            (small ? " storage=small" : "");
  if (small)
    solve_loop(state, std::vector<SmallImpactProblem>{to_small(p)}, *law, label);
  else
    solve_loop(state, std::vector<ImpactProblem>{p}, *law, label);
}

std::vector<ImpactProblem> random_set(int n, bool friction) {
  std::vector<ImpactProblem> v;
  for (int i = 0; i < 8; ++i) v.push_back(random_problem_any(n, n / 2, i, friction));
  return v;
}

void BM_RandomSize(benchmark::State& state, const Law* law) {
  const int n = static_cast<int>(state.range(0));
  solve_loop(state, random_set(n, law->friction), *law,
             bench_label(random_name(n), law->name) + " stage=solve_impact");
}

void BM_PreparedContacts(benchmark::State& state, const Law* law) {
  const int c = static_cast<int>(state.range(0));
  prepared_loop(state, {plate_many_contacts(c, law->friction)}, *law,
                bench_label(plate_name(c), law->name) + " stage=prepared");
}

void BM_PreparedRandomSize(benchmark::State& state, const Law* law) {
  const int n = static_cast<int>(state.range(0));
  prepared_loop(state, random_set(n, law->friction), *law,
                bench_label(random_name(n), law->name) + " stage=prepared");
}

/// The bar's first impact with q̇_A spread around the paper's: a batch of independent problems.
const std::vector<SmallImpactProblem>& batch() {
  static const std::vector<SmallImpactProblem> v = [] {
    std::vector<SmallImpactProblem> b;
    SplitMix64 rng(kRandomSeed);
    for (int i = 0; i < 4096; ++i) {
      SmallImpactProblem p = bar_first_impact(true);
      p.qdot_A(0) += rng.uniform(-1.0, 1.0);
      p.qdot_A(1) *= rng.uniform(0.5, 1.5);
      p.qdot_A(2) = rng.uniform(-2.0, 2.0);
      b.push_back(p);
    }
    return b;
  }();
  return v;
}

void BM_Throughput(benchmark::State& state, const Law* law) {
  const auto& b = batch();
  const SolverOptions opt = options();
  const std::size_t per = b.size() / static_cast<std::size_t>(state.threads());
  const std::size_t first = per * static_cast<std::size_t>(state.thread_index());
  long failed = 0;
  for (auto _ : state) {
    for (std::size_t i = first; i < first + per; ++i) {
      const SmallImpactResult r = solve_impact(b[i], law->law, opt);
      failed += r.ok() ? 0 : 1;
      benchmark::DoNotOptimize(r.qdot_E.data());
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(per));
  state.counters["failed"] = static_cast<double>(failed);
  state.SetLabel("problem=bar_batch4096 law=" + law->name + " stage=solve_impact");
}

#ifdef FREMOND_HAVE_SICONOS
/// G = Wᵀ M⁻¹ W and D_A in Siconos's row order (N, T per contact), dynamic sizes.
void assemble(const ImpactProblem& p, bool friction, Eigen::MatrixXd& G, Eigen::VectorXd& D) {
  const int c = p.contacts(), r = friction ? 2 : 1;
  Eigen::MatrixXd W(p.dofs(), r * c);
  for (int i = 0; i < c; ++i) {
    W.col(r * i) = p.W_N.col(i);
    if (friction) W.col(r * i + 1) = p.W_T.col(i);
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(p.M);
  G.noalias() = W.transpose() * llt.solve(W);
  D.noalias() = W.transpose() * p.qdot_A;
}

/// Newton as an LCP (z = P_N, w = G_NN P_N + (1 + e) D_NA), Lemke; Newton + Coulomb as a 2-D
/// friction-contact problem (q = ((1 + e) D_NA, D_TA) per contact), NSGS. There is no closed form
/// here: `err` is the distance of Siconos's q̇_E to ours (‖Δq̇‖_M/‖q̇_A‖_M; q̇_E is unique for these
/// laws and data even where the percussions are not).
void siconos_loop(benchmark::State& state, const std::vector<ImpactProblem>& problems,
                  bool friction, const std::string& label) {
  const int c = problems[0].contacts(), n = friction ? 2 * c : c;
  Eigen::MatrixXd G;
  Eigen::VectorXd D, q(n), z(n), w(n);
  std::vector<double> mu(c, kFriction);
  siconos::SolveInfo info;
  std::unique_ptr<siconos::Lcp> lcp;
  std::unique_ptr<siconos::FrictionContact2d> fc;
  if (friction)
    fc = std::make_unique<siconos::FrictionContact2d>(c, siconos::Fc2dSolver::nsgs, 1e-12);
  else
    lcp = std::make_unique<siconos::Lcp>(c, siconos::LcpSolver::lemke);
  int failed = 0, runs = 0;
  std::size_t k = 0;
  auto solve = [&](const ImpactProblem& p) {
    assemble(p, friction, G, D);
    for (int j = 0; j < n; ++j) q(j) = (friction && j % 2 == 1 ? 1.0 : 1.0 + kRestitution) * D(j);
    info = friction ? fc->solve(G.data(), q.data(), mu.data(), z.data(), w.data())
                    : lcp->solve(G.data(), q.data(), z.data(), w.data());
  };
  for (auto _ : state) {
    solve(problems[k]);
    k = k + 1 == problems.size() ? 0 : k + 1;
    benchmark::DoNotOptimize(z.data());
  }
  double err = 0.0;
  const ImpactLaw law = friction ? ImpactLaw::newton_coulomb(kRestitution, kFriction)
                                 : ImpactLaw::newton(kRestitution);
  for (const ImpactProblem& p : problems) {
    solve(p);
    ++runs;
    failed += info.info != 0;
    if (info.info != 0) continue;
    Eigen::MatrixXd W(p.dofs(), n);
    for (int i = 0; i < c; ++i) {
      W.col(friction ? 2 * i : i) = p.W_N.col(i);
      if (friction) W.col(2 * i + 1) = p.W_T.col(i);
    }
    const Eigen::VectorXd qE = p.qdot_A + p.M.llt().solve(W * z);
    const ImpactResult ours = solve_impact(p, law, options());
    const Eigen::VectorXd d = qE - ours.qdot_E;
    err = std::max(err, std::sqrt(d.dot(p.M * d) / p.qdot_A.dot(p.M * p.qdot_A)));
  }
  state.counters["err"] = err;
  state.counters["contacts"] = c;
  state.counters["converged"] = 1.0 - static_cast<double>(failed) / runs;
  state.counters["iter"] = info.iterations;
  state.SetLabel(label + (friction ? " solver=fc2d_nsgs" : " solver=lcp_lemke"));
}

void BM_Siconos_Contacts(benchmark::State& state, bool friction) {
  const int c = static_cast<int>(state.range(0));
  siconos_loop(state, {plate_many_contacts(c, friction)}, friction,
               bench_label(plate_name(c), friction ? "newton_coulomb" : "newton"));
}

void BM_Siconos_RandomSize(benchmark::State& state, bool friction) {
  const int n = static_cast<int>(state.range(0));
  siconos_loop(state, random_set(n, friction), friction,
               bench_label(random_name(n), friction ? "newton_coulomb" : "newton"));
}
#endif

const bool registered = [] {
  for (const Law& law : laws()) {
    benchmark::RegisterBenchmark(("BM_Contacts/" + law.name).c_str(), BM_Contacts, &law, false)
        ->RangeMultiplier(2)
        ->Range(1, 32);
    benchmark::RegisterBenchmark(("BM_Contacts/" + law.name + "/small").c_str(), BM_Contacts, &law,
                                 true)
        ->RangeMultiplier(2)
        ->Range(1, 4);
    benchmark::RegisterBenchmark(("BM_RandomSize/" + law.name).c_str(), BM_RandomSize, &law)
        ->DenseRange(6, 30, 6);
    // The prepared solver where the performance report sets it beside Siconos (Newton +
    // Coulomb); "unchecked" names check_uniqueness off, as the report reads the other prepared
    // benchmarks' names.
    if (law.name == "newton_coulomb") {
      benchmark::RegisterBenchmark(("BM_PreparedContacts/" + law.name + "/unchecked").c_str(),
                                   BM_PreparedContacts, &law)
          ->RangeMultiplier(2)
          ->Range(8, 32);
      benchmark::RegisterBenchmark(("BM_PreparedRandomSize/" + law.name + "/unchecked").c_str(),
                                   BM_PreparedRandomSize, &law)
          ->DenseRange(12, 30, 6);
    }
    benchmark::RegisterBenchmark(("BM_Throughput/" + law.name).c_str(), BM_Throughput, &law)
        ->Threads(1)
        ->Threads(2)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
#ifdef FREMOND_HAVE_SICONOS
  for (const bool friction : {false, true}) {
    benchmark::RegisterBenchmark(
        friction ? "BM_Siconos_Contacts/newton_coulomb" : "BM_Siconos_Contacts/newton",
        BM_Siconos_Contacts, friction)
        ->RangeMultiplier(2)
        ->Range(1, 32);
    benchmark::RegisterBenchmark(
        friction ? "BM_Siconos_RandomSize/newton_coulomb" : "BM_Siconos_RandomSize/newton",
        BM_Siconos_RandomSize, friction)
        ->DenseRange(6, 30, 6);
  }
#endif
  return true;
}();

}  // namespace
