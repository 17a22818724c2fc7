// Sparse problems of hundreds and thousands of contacts (docs/sparse.md): Siconos's own 2-D
// granular-flow problems, solved by our nonsmooth Gauss-Seidel and, from the same files, by
// Siconos's 2-D solvers. Each benchmark reports the contacts, the sweeps or iterations, and the
// residual of its answer by one measure, ours (contact_residual), beside Siconos's own.
#include <benchmark/benchmark.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fremond/fremond.hpp"
#ifdef FREMOND_HAVE_SICONOS
#include "siconos_peers.hpp"
#include "support/disk_pile.hpp"
#endif

namespace fremond::bench {
namespace {

const std::vector<std::string>& files() {
  static const std::vector<std::string> names{
      "gfc2d_granularflowonwall_00069_00350.dat", "gfc2d_granularflowonwall_00230_00206.dat",
      "fc2d_granularflowonwall_00667_00000.dat", "fc2d_granularflowonwall_02020_00213.dat",
      "fc2d_granularflowonwall_07002_00801.dat"};
  return names;
}

std::string path(const std::string& name) {
  return std::string(FREMOND_SICONOS_DATA) + "/" + name;
}

const io::SiconosProblem& problem(const std::string& name) {
  static std::map<std::string, io::SiconosProblem> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  std::ifstream in(path(name));
  std::stringstream text;
  text << in.rdbuf();
  return cache.emplace(name, io::parse_siconos_file(text.str())).first->second;
}

ContactProblem contact_form(const io::SiconosProblem& p) {
  return p.form == io::SiconosProblem::Form::local ? p.contact : contact_problem(p.impact);
}

// Ours from the file's data, to 1e-8 of the velocity scale (the files' G keeps 6 digits: the two
// largest stop near 1e-6, docs/sparse.md).
void BM_Sparse_Nsgs(benchmark::State& state, const std::string& name) {
  const io::SiconosProblem& p = problem(name);
  const SparseSolverOptions options{.tolerance = 1e-8};
  ImpactResult r;
  for (auto _ : state) {
    r = p.form == io::SiconosProblem::Form::local
            ? solve_contact_problem(p.contact, p.law(), options)
            : solve_impact(p.impact, p.law(), options);
    benchmark::DoNotOptimize(r.P_N.data());
  }
  state.counters["contacts"] = p.contacts();
  state.counters["sweeps"] = r.solver.iterations;
  state.counters["residual"] = r.solver.residual;
  state.counters["admissible"] = r.admissibility.admissible;
  // "converged(data)": converged as far as the file's printed digits go (docs/sparse.md).
  const bool to_digits = r.solver.criterion == StopCriterion::data;
  state.SetLabel(std::string(to_string(r.solver.status)) + (to_digits ? "(data)" : "") + " " +
                 name);
}

// Reading the file (the reader's cost beside the solve's).
void BM_Sparse_ReadFile(benchmark::State& state, const std::string& name) {
  std::ifstream in(path(name));
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  for (auto _ : state) benchmark::DoNotOptimize(io::parse_siconos_file(s).mu.data());
  state.counters["MB"] = static_cast<double>(s.size()) / 1e6;
  state.SetLabel(name);
}

const std::vector<int>& pile_sides() {
  static const std::vector<int> sides{3, 6, 12, 19, 32, 59};  // 15 to 6,903 contacts
  return sides;
}

// Beds: piles that grow in width only, four layers deep. A sweep costs what G's non-zeros cost on
// both; the sweeps a solve needs grow with the height a blow crosses, not with the width.
constexpr int kBedLayers = 4;
const std::vector<int>& bed_columns() {
  static const std::vector<int> columns{3, 8, 32, 128, 512, 875};  // 20 to 6,996 contacts
  return columns;
}

// The pile of range(0) columns and range(1) layers.
SparseImpactProblem pile_of(const benchmark::State& state) {
  return fixtures::disk_pile(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
}

void BM_Sparse_Pile(benchmark::State& state) {
  const SparseImpactProblem pb = pile_of(state);
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.0, 0.5);
  ImpactResult r;
  for (auto _ : state) {
    r = solve_impact(pb, law, {.tolerance = 1e-8});
    benchmark::DoNotOptimize(r.P_N.data());
  }
  state.counters["contacts"] = pb.contacts();
  state.counters["nonzeros_G"] = static_cast<double>(contact_problem(pb).G.nonZeros());
  state.counters["sweeps"] = r.solver.iterations;
  state.counters["residual"] = r.solver.residual;
  state.SetLabel(std::string(to_string(r.solver.status)));
}

// The same pile handed over dense (solve_impact's dense path, its contact space and chain): what
// a user of dense M and W pays beside the sparse form. Its contacts in separate groups approach
// alone first; the answer drives separating ones, and the pile is solved again on every contact.
void BM_Dense_Pile(benchmark::State& state, const ImpactLaw& law) {
  const SparseImpactProblem sparse = pile_of(state);
  ImpactProblem pb;
  pb.M = Eigen::MatrixXd(sparse.M);
  pb.W_N = Eigen::MatrixXd(sparse.W_N);
  pb.W_T = Eigen::MatrixXd(sparse.W_T);
  pb.qdot_A = sparse.qdot_A;
  ImpactResult r;
  for (auto _ : state) {
    r = solve_impact(pb, law);  // the dense default: to 1e-9
    benchmark::DoNotOptimize(r.P_N.data());
  }
  state.counters["contacts"] = pb.contacts();
  state.counters["iterations"] = r.solver.iterations;
  state.counters["residual"] = r.solver.residual;
  state.SetLabel(std::string(to_string(r.solver.status)));
}

#ifdef FREMOND_HAVE_SICONOS
// Siconos's 2-D NSGS on the same pile, from the dense contact form its 2-D driver takes (q = D_A:
// e = 0); `our_residual` measures its answer as ours is measured.
void BM_Siconos_Pile(benchmark::State& state) {
  const SparseImpactProblem pb = pile_of(state);
  const ContactProblem cp = contact_problem(pb);
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.0, 0.5);
  const int c = cp.contacts();
  const Eigen::MatrixXd G(cp.G);
  const std::vector<double> mu(static_cast<std::size_t>(c), 0.5);
  std::vector<double> r(2 * static_cast<std::size_t>(c)), u(r.size());
  siconos::FrictionContact2d peer(c, siconos::Fc2dSolver::nsgs, 1e-8, 100000);
  siconos::SolveInfo info;
  for (auto _ : state) {
    info = peer.solve(G.data(), cp.D_A.data(), mu.data(), r.data(), u.data());
    benchmark::DoNotOptimize(r.data());
  }
  ImpactResult answer;
  answer.P_N.resize(c);
  answer.P_T.resize(c);
  for (int i = 0; i < c; ++i) {
    answer.P_N(i) = r[2 * static_cast<std::size_t>(i)];
    answer.P_T(i) = r[2 * static_cast<std::size_t>(i) + 1];
  }
  state.counters["contacts"] = c;
  state.counters["iterations"] = info.iterations;
  state.counters["our_residual"] = contact_residual(cp, law, answer);
  state.SetLabel("solver=fc2d_nsgs info=" + std::to_string(info.info));
}

// Siconos's 2-D driver on the same file, read by Siconos's own reader; `our_residual` measures its
// answer as ours is measured.
void BM_Siconos_Fc2dFile(benchmark::State& state, const std::string& name,
                         siconos::Fc2dSolver solver, double tolerance) {
  siconos::Fc2dFile peer(path(name), solver, tolerance, 100000);
  std::vector<double> r, u;
  siconos::SolveInfo info;
  for (auto _ : state) {
    info = peer.solve(r, u);
    benchmark::DoNotOptimize(r.data());
  }
  const io::SiconosProblem& p = problem(name);
  ImpactResult answer;
  answer.P_N.resize(p.contacts());
  answer.P_T.resize(p.contacts());
  for (int i = 0; i < p.contacts(); ++i) {
    answer.P_N(i) = r[2 * static_cast<std::size_t>(i)];
    answer.P_T(i) = r[2 * static_cast<std::size_t>(i) + 1];
  }
  state.counters["contacts"] = p.contacts();
  state.counters["iterations"] = info.iterations;
  state.counters["siconos_residual"] = info.residual;
  state.counters["our_residual"] = contact_residual(contact_form(p), p.law(), answer);
  state.SetLabel(std::string("solver=fc2d_") + siconos::to_string(solver) +
                 " info=" + std::to_string(info.info) + " " + name);
}
#endif

const bool registered = [] {
  for (const int side : pile_sides())
    benchmark::RegisterBenchmark("BM_Sparse_Pile", BM_Sparse_Pile)
        ->Args({side, side})
        ->Unit(benchmark::kMillisecond);
  for (const int columns : bed_columns())
    benchmark::RegisterBenchmark("BM_Sparse_Bed", BM_Sparse_Pile)
        ->Args({columns, kBedLayers})
        ->Unit(benchmark::kMillisecond);
  const std::pair<const char*, ImpactLaw> dense_laws[] = {
      {"newton_coulomb", ImpactLaw::newton_coulomb(0.0, 0.5)},
      {"fremond_coulomb", ImpactLaw::fremond_coulomb(PowerPotential(1.0, 2.0), 0.5)}};
  for (const auto& [name, law] : dense_laws)
    for (const int side : pile_sides())
      if (side <= 6)
        benchmark::RegisterBenchmark(("BM_Dense_Pile/" + std::string(name)).c_str(), BM_Dense_Pile,
                                     law)
            ->Args({side, side})
            ->Unit(benchmark::kMillisecond);
#ifdef FREMOND_HAVE_SICONOS
  // Siconos's solves of 27 s to 8 minutes (the pile of 703 contacts, the bed of 1,020, the file
  // of 2,020) run once, whatever the report's repetitions; beyond them its dense form is not run.
  auto once = [](benchmark::internal::Benchmark* b) { b->Iterations(1)->Repetitions(1); };
  for (const int side : pile_sides())
    if (side <= 19) {
      auto* b = benchmark::RegisterBenchmark("BM_Siconos_Pile", BM_Siconos_Pile)
                    ->Args({side, side})
                    ->Unit(benchmark::kMillisecond);
      if (side == 19) once(b);
    }
  for (const int columns : bed_columns())
    if (columns <= 128) {
      auto* b = benchmark::RegisterBenchmark("BM_Siconos_Bed", BM_Siconos_Pile)
                    ->Args({columns, kBedLayers})
                    ->Unit(benchmark::kMillisecond);
      if (columns == 128) once(b);
    }
#endif
  for (const auto& name : files()) {
    benchmark::RegisterBenchmark(("BM_Sparse_Nsgs/" + name).c_str(), BM_Sparse_Nsgs, name)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_Sparse_ReadFile/" + name).c_str(), BM_Sparse_ReadFile, name)
        ->Unit(benchmark::kMillisecond);
  }
#ifdef FREMOND_HAVE_SICONOS
  using S = siconos::Fc2dSolver;
  const std::string small = "fc2d_granularflowonwall_00667_00000.dat";
  for (const S s : {S::nsgs, S::cpg, S::enumeration})
    benchmark::RegisterBenchmark(
        ("BM_Siconos_Fc2dFile/" + std::string(siconos::to_string(s)) + "/" + small).c_str(),
        BM_Siconos_Fc2dFile, small, s, 1e-8)
        ->Unit(benchmark::kMillisecond);
  // Siconos's NSGS needs about 70 s to reach its own 1e-6 on 2,020 contacts (1e-8: past 5
  // minutes): one run.
  const std::string large = "fc2d_granularflowonwall_02020_00213.dat";
  once(benchmark::RegisterBenchmark(("BM_Siconos_Fc2dFile/nsgs/" + large).c_str(),
                                    BM_Siconos_Fc2dFile, large, S::nsgs, 1e-6)
           ->Unit(benchmark::kMillisecond));
#endif
  return true;
}();

}  // namespace
}  // namespace fremond::bench
