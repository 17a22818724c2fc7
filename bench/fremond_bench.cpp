// Frémond's solvers on the fixed suite of fremond_suite.hpp (issue 6, item 1), method by method, at
// three depths, each labelled "problem=... law=..." so that bench/compare.py can set them beside a
// Siconos peer where one exists:
//
//  - BM_Fremond/<problem>/<law>/<method>: the public entry point solve_impact on the stack-stored
//    problem, with the method forced (or automatic): validation, the contact space, the solver, the
//    split of the reaction, the uniqueness test and the admissibility certificate
//    ("stage=solve_impact method=...").
//  - BM_FremondPrepared/<problem>/<law>: the prepared solver (ImpactSolver), set up once per
//    problem, then solved from q̇_A with its certificate ("stage=prepared method=automatic").
//  - BM_FremondLaw/<problem>/<law>: the contact space and the automatic method chain alone, without
//    validation and certificate ("stage=law").
//  - BM_FremondKernel/<problem>/<law>: for one decoupled row (a point mass, the bar's normal law),
//    the exact method alone on the contact-space data: one prox of the potential, the reaction's
//    clamp and the percussion ("stage=kernel").
//  - BM_Siconos_LCP_*/<problem>/fremond_p2: Frémond's normal law with p = 2 is linear, so with its
//    reaction it is an LCP, which Siconos Numerics solves (the only Frémond law Siconos can): with
//    z = D_A + G P/2, P = −K z + R, D_E = 2z − D_A and A = I + G K/2 it reads
//    0 ≤ R ⊥ D_E = A⁻¹G R + (2A⁻¹ − I) D_A ≥ 0. Timed from the data like every Siconos peer: G, A,
//    the LCP, then Siconos's driver; and, with _driver ("stage=driver"), Siconos's driver alone on
//    the LCP assembled before the timing, beside our kernel, which also starts from G and D_A.
//
// After timing, every benchmark checks its answers against the quad reference (untimed) and reports
// `err` (‖q̇_E − q̇_E,ref‖_M/‖q̇_A‖_M, the worst over the case's problems), `residual` and
// `converged` (the fraction of the case's problems solved). A method that does not converge says
// so in `converged`; an answer marked converged that is wrong (err > 1e-9) is an error.
#include <benchmark/benchmark.h>

#include <chrono>
#include <string>
#include <vector>

#include "fremond_suite.hpp"
#include "solvers/detail/fremond.hpp"
#ifdef FREMOND_HAVE_SICONOS
#include "siconos_peers.hpp"
#endif

namespace {

using namespace fremond;
using namespace fremond::bench;

const std::vector<FremondCase>& suite() {
  static const std::vector<FremondCase> all = fremond_suite();
  return all;
}

std::string label(const FremondCase& c, const std::string& extra) {
  return bench_label(c.problem, c.law_name) + " " + extra;
}

/// Solves every problem of the case with `opt` (untimed) and sets the counters; an answer marked
/// converged that is wrong is an error.
void check(benchmark::State& state, const FremondCase& c, const SolverOptions& opt) {
  double err = 0.0, residual = 0.0;
  int converged = 0;
  for (std::size_t k = 0; k < c.problems.size(); ++k) {
    const SmallImpactResult r = solve_impact(c.problems[k], c.law, opt);
    if (!r.ok()) continue;
    ++converged;
    residual = std::max(residual, r.solver.residual);
    const double e = relative_error(c.problems[k], c.reference[k], r.qdot_E);
    if (!std::isnan(e)) err = std::max(err, e);
  }
  state.counters["err"] = err;
  state.counters["residual"] = residual;
  state.counters["converged"] =
      static_cast<double>(converged) / static_cast<double>(c.problems.size());
  if (!(err <= 1e-9))
    state.SkipWithError(
        ("an answer marked converged is off the reference by " + std::to_string(err)).c_str());
}

void BM_Fremond(benchmark::State& state, const FremondCase* c, SolverMethod method) {
  SolverOptions opt;
  opt.method = method;
  std::size_t k = 0;
  const std::size_t n = c->problems.size();
  for (auto _ : state) {
    const SmallImpactResult r = solve_impact(c->problems[k], c->law, opt);
    k = k + 1 == n ? 0 : k + 1;
    benchmark::DoNotOptimize(r.qdot_E.data());
  }
  state.SetLabel(label(*c, "method=" + std::string(to_string(method)) + " stage=solve_impact"));
  check(state, *c, opt);
}

/// The prepared solver (ImpactSolver): built once per problem, then solved from its q̇_A with
/// the certificate, as a simulation does impact after impact on one configuration.
void BM_FremondPrepared(benchmark::State& state, const FremondCase* c) {
  const SolverOptions opt;
  std::vector<SmallImpactSolver> solvers;
  for (const SmallImpactProblem& p : c->problems) solvers.emplace_back(p, c->law, opt);
  std::size_t k = 0;
  for (auto _ : state) {
    SmallImpactSolver& s = solvers[k];
    k = k + 1 == solvers.size() ? 0 : k + 1;
    benchmark::DoNotOptimize(s.solve(s.problem().qdot_A).qdot_E.data());
  }
  state.SetLabel(label(*c, "method=automatic stage=prepared"));
  // The prepared answers are solve_impact's to the last bit, which check() holds to the reference.
  for (std::size_t i = 0; i < solvers.size(); ++i)
    if (!(Eigen::VectorXd(solvers[i].solve(c->problems[i].qdot_A).qdot_E) ==
          Eigen::VectorXd(solve_impact(c->problems[i], c->law, opt).qdot_E))) {
      state.SkipWithError("the prepared solver's answer differs from solve_impact's");
      return;
    }
  check(state, *c, opt);
}

void BM_NloptTooSlow(benchmark::State& state, const FremondCase* c) {
  for (auto _ : state) {
  }
  state.SetLabel(label(*c, "method=nlopt stage=solve_impact"));
  state.SkipWithError(
      "not timed: NLopt does not stop on its own within 2000 evaluations and 50 ms here; its "
      "default budget can take minutes (see work_precision.csv for its budget sweep)");
}

void BM_FremondLaw(benchmark::State& state, const FremondCase* c) {
  const SolverOptions opt;
  std::size_t k = 0;
  const std::size_t n = c->problems.size();
  detail::ContactSpaceT<kSmallDofs, kSmallContacts> cs;
  SmallImpactResult out;
  const bool tangential = c->law.get<FremondLaw>().tangential != TangentialLaw::none;
  for (auto _ : state) {
    const SmallImpactProblem& p = c->problems[k];
    k = k + 1 == n ? 0 : k + 1;
    detail::build_contact_space(p, tangential, cs);
    detail::solve_fremond(p, cs, c->law.get<FremondLaw>(), opt, out);
    benchmark::DoNotOptimize(out.qdot_E.data());
  }
  state.SetLabel(label(*c, "method=automatic stage=law"));
  check(state, *c, opt);
}

/// One decoupled normal row: z = max(prox_{(g/2)φ}(D_A), D_A/2), P = 2(z − D_A)/g.
void BM_FremondKernel(benchmark::State& state, const FremondCase* c) {
  const SmallImpactProblem& p = c->problems[0];
  detail::ContactSpaceT<kSmallDofs, kSmallContacts> cs;
  detail::build_contact_space(p, false, cs);
  const Potential& phi = c->law.get<FremondLaw>().normal[0];
  const double g = cs.G(0, 0), D = cs.D_A(0);
  double P = 0.0;
  for (auto _ : state) {
    // Not benchmark::DoNotOptimize on a double lvalue: its "+m,r" constraint is miscompiled by
    // GCC here (the value comes back as garbage). An SSE-register constraint instead.
    double x = D;
    asm volatile("" : "+x"(x));
    const double z = std::max(phi.prox(x, 0.5 * g), 0.5 * x);
    P = 2.0 * (z - x) / g;
    asm volatile("" : "+x"(P));
  }
  const SmallImpactResult r = solve_impact(p, c->law);
  state.counters["P_N"] = P;
  state.counters["err"] = std::fabs(P - r.P_N(0)) / std::max(std::fabs(r.P_N(0)), 1e-300);
  state.SetLabel(label(*c, "method=" + std::string(to_string(r.solver.method)) + " stage=kernel"));
}

#ifdef FREMOND_HAVE_SICONOS
/// Frémond p = 2 (normal law alone, k the same for every contact) as an LCP for Siconos; see the
/// file comment. Returns q̇_E.
struct FremondLcp {
  static constexpr int kMax = kSmallContacts;
  using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMax, kMax>;
  using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMax, 1>;
  Mat G, A, Mlcp;
  Vec D_A, q, z, w, P;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kSmallDofs, kMax> MinvW;

  void assemble(const SmallImpactProblem& p, double k) {
    const int c = p.contacts();
    const Eigen::LLT<SmallImpactProblem::Mat> llt(p.M);
    MinvW = llt.solve(p.W_N);
    G.noalias() = p.W_N.transpose() * MinvW;
    D_A.noalias() = p.W_N.transpose() * p.qdot_A;
    A = Mat::Identity(c, c) + 0.5 * k * G;
    const Eigen::PartialPivLU<Mat> lu(A);
    Mlcp = lu.solve(G);
    q = 2.0 * lu.solve(D_A) - D_A;
    z.resize(c);
    w.resize(c);
  }
  Eigen::VectorXd velocity(const SmallImpactProblem& p, double k) {
    // z_mean = A⁻¹(D_A + G R/2), P = −k z_mean + R.
    const Vec zm = A.partialPivLu().solve(D_A + 0.5 * (G * z));
    P = -k * zm + z;
    return Eigen::VectorXd(p.qdot_A) + Eigen::MatrixXd(MinvW) * Eigen::VectorXd(P);
  }
};

/// `driver`: Siconos's driver alone, on the LCPs assembled before the timing ("stage=driver"), the
/// work of our kernel, which also starts from G and D_A.
void BM_Siconos_LCP_FremondP2(benchmark::State& state, const FremondCase* c,
                              siconos::LcpSolver solver, bool driver) {
  const int contacts = c->problems[0].contacts();
  const double k = c->spec.k_N;
  siconos::Lcp lcp(contacts, solver);
  FremondLcp f;
  siconos::SolveInfo info;
  std::size_t j = 0;
  const std::size_t n = c->problems.size();
  if (driver) {
    std::vector<FremondLcp> assembled(n);
    for (std::size_t i = 0; i < n; ++i) assembled[i].assemble(c->problems[i], k);
    for (auto _ : state) {
      FremondLcp& a = assembled[j];
      j = j + 1 == n ? 0 : j + 1;
      info = lcp.solve(a.Mlcp.data(), a.q.data(), a.z.data(), a.w.data());
      benchmark::DoNotOptimize(a.z.data());
    }
  } else {
    for (auto _ : state) {
      f.assemble(c->problems[j], k);
      j = j + 1 == n ? 0 : j + 1;
      info = lcp.solve(f.Mlcp.data(), f.q.data(), f.z.data(), f.w.data());
      benchmark::DoNotOptimize(f.z.data());
    }
  }
  double err = 0.0;
  int failed = 0;
  for (std::size_t i = 0; i < n; ++i) {
    f.assemble(c->problems[i], k);
    info = lcp.solve(f.Mlcp.data(), f.q.data(), f.z.data(), f.w.data());
    if (info.info != 0) {
      ++failed;
      continue;
    }
    const Eigen::VectorXd qE = f.velocity(c->problems[i], k);
    err = std::max(err, relative_error(c->problems[i], c->reference[i], qE));
  }
  state.counters["err"] = err;
  state.counters["failed"] = failed;
  state.counters["iter"] = info.iterations;
  state.SetLabel(bench_label(c->problem, c->law_name) + (driver ? " stage=driver" : ""));
  if (failed == static_cast<int>(n)) state.SkipWithError("Siconos failed on every problem");
}
#endif

const bool registered = [] {
  for (const FremondCase& c : suite()) {
    const std::string suffix = "/" + c.problem + "/" + c.law_name;
    // Which methods apply: the exact ones only where they do (not `unsupported`). NLopt only where
    // it stops on its own criterion within 2000 evaluations and 50 ms: elsewhere its run at the
    // default budget can take minutes (MMA's inner loop, for Coulomb), so the benchmark says so
    // instead (the work-precision CSV has its budget sweep).
    std::vector<SolverMethod> methods{SolverMethod::automatic};
    for (SolverMethod m :
         {SolverMethod::closed_form, SolverMethod::scalar_newton, SolverMethod::mode_enumeration,
          SolverMethod::semismooth_newton, SolverMethod::proximal}) {
      SolverOptions opt;
      opt.method = m;
      if (solve_impact(c.problems[0], c.law, opt).solver.status != SolverStatus::unsupported)
        methods.push_back(m);
    }
    bool nlopt_fast =
        !(c.spec.tangential == FremondLawSpec::Tangential::coulomb && c.problems[0].contacts() > 2);
    for (std::size_t k = 0; k < c.problems.size() && nlopt_fast; ++k) {
      SolverOptions opt;
      opt.method = SolverMethod::nlopt;
      opt.max_nlopt_evaluations = 2000;
      const auto t0 = std::chrono::steady_clock::now();
      const SmallImpactResult r = solve_impact(c.problems[k], c.law, opt);
      const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      nlopt_fast = t < 0.05 && r.solver.native_code != 5;  // 5: NLOPT_MAXEVAL_REACHED
    }
    if (nlopt_fast)
      methods.push_back(SolverMethod::nlopt);
    else
      benchmark::RegisterBenchmark(("BM_Fremond" + suffix + "/nlopt").c_str(), BM_NloptTooSlow, &c);
    for (SolverMethod m : methods)
      benchmark::RegisterBenchmark(
          ("BM_Fremond" + suffix + "/" + std::string(to_string(m))).c_str(), BM_Fremond, &c, m);
    benchmark::RegisterBenchmark(("BM_FremondPrepared" + suffix).c_str(), BM_FremondPrepared, &c);
    benchmark::RegisterBenchmark(("BM_FremondLaw" + suffix).c_str(), BM_FremondLaw, &c);
    if (c.problems.size() == 1 && c.problems[0].contacts() == 1 &&
        c.spec.tangential == FremondLawSpec::Tangential::none)
      benchmark::RegisterBenchmark(("BM_FremondKernel" + suffix).c_str(), BM_FremondKernel, &c);
#ifdef FREMOND_HAVE_SICONOS
    if (c.law_name == "fremond_p2")
      for (siconos::LcpSolver s : {siconos::LcpSolver::lemke, siconos::LcpSolver::enumeration})
        for (const bool driver : {false, true})
          benchmark::RegisterBenchmark((std::string("BM_Siconos_LCP_FremondP2_") +
                                        siconos::to_string(s) + (driver ? "_driver" : "") + suffix)
                                           .c_str(),
                                       BM_Siconos_LCP_FremondP2, &c, s, driver);
#endif
  }
  return true;
}();

}  // namespace
