// Siconos Numerics on the benchmark problems of problems.hpp: Newton's law as an LCP, Newton +
// Coulomb as an LCP (the planar friction LCP, Glocker's form) and as a 2-D friction-contact problem
// (Siconos's NSGS, Lemke and enumeration), at two depths:
//  - BM_Siconos_<problem type>_<solver>: from the problem (M, W, q̇_A) to the percussions, the
//    Delassus matrix G = Wᵀ M⁻¹ W (docs/concepts.md) on the stack, then Siconos's driver: the work
//    of our BM_Classical_FromData.
//  - the same with _Driver ("stage=driver" in the label): Siconos's driver alone on its own problem
//    (G and q assembled before the timing), the work of our BM_Classical_Kernel, which also starts
//    from G and D_A.
// After timing, each checks its answer against the closed form of problems.hpp and reports it as
// counters (P_N0, P_T0, ... and err, the largest deviation of q̇_E).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "problems.hpp"
#ifdef FREMOND_HAVE_SICONOS
#include "siconos_peers.hpp"
#endif

namespace {

using namespace fremond;
using namespace fremond::bench;

#ifndef FREMOND_HAVE_SICONOS

void BM_Siconos_NotBuilt(benchmark::State& state) {
  state.SkipWithError(
      "built without Siconos: install libsiconos-numerics-dev and libsiconos-kernel-dev, then "
      "reconfigure with CMake");
  for (auto _ : state) {
  }
}
BENCHMARK(BM_Siconos_NotBuilt);

#else

constexpr int kMaxRows = 2 * kSmallContacts;
using RowMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxRows, kMaxRows>;
using RowVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxRows, 1>;
using WMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kSmallDofs, kMaxRows>;

/// G and D_A in Siconos's row order (N, T per contact; N only without friction), on the stack.
struct Delassus {
  RowMat G;
  RowVec D_A;
  WMat W;
};

void assemble(const SmallImpactProblem& p, Delassus& d) {
  const int c = p.contacts(), r = p.has_tangential() ? 2 : 1, n = p.dofs();
  d.W.resize(n, r * c);
  for (int i = 0; i < c; ++i) {
    d.W.col(r * i) = p.W_N.col(i);
    if (r == 2) d.W.col(r * i + 1) = p.W_T.col(i);
  }
  const Eigen::LLT<SmallImpactProblem::Mat> llt(p.M);
  const WMat MinvW = llt.solve(d.W);
  d.G.noalias() = d.W.transpose() * MinvW;
  d.D_A.noalias() = d.W.transpose() * p.qdot_A;
  for (int i = 0; i < c; ++i) {
    if (p.w_N.size()) d.D_A(r * i) += p.w_N(i);
    if (r == 2 && p.w_T.size()) d.D_A(r * i + 1) += p.w_T(i);
  }
}

/// One benchmark case: problems (the loop cycles through them), the law, and the closed-form
/// answers (every admissible q̇_E of each problem: the solver's must be one of them).
struct Case {
  std::string problem, law;
  std::vector<SmallImpactProblem> problems;
  double e = kRestitution, mu = kFriction;
  std::vector<std::vector<Eigen::VectorXd> > expected;
};

Case make_case(std::string problem, std::string law, std::vector<SmallImpactProblem> problems) {
  Case c;
  c.problem = std::move(problem);
  c.law = std::move(law);
  c.problems = std::move(problems);
  return c;
}

Eigen::VectorXd qdot_from(const SmallImpactProblem& p, const Delassus& d, const double* P) {
  const Eigen::Map<const Eigen::VectorXd> Pv(P, d.W.cols());
  const Eigen::MatrixXd M = p.M;
  return Eigen::VectorXd(p.qdot_A) + M.ldlt().solve(d.W * Pv);
}

/// The largest distance of q̇_E to the nearest closed-form answer, relative to |q̇_A|.
double error_against(const Case& c, int k, const Eigen::VectorXd& qE) {
  double best = 1e300;
  for (const auto& ref : c.expected[k])
    best = std::min(best, (ref - qE).lpNorm<Eigen::Infinity>() /
                              (1.0 + c.problems[k].qdot_A.lpNorm<Eigen::Infinity>()));
  return best;
}

/// Counters and checks after timing: the percussions of the first problem, the largest deviation
/// from the closed form over the problems Siconos solved, and how many it failed (info ≠ 0). A
/// benchmark whose every solve failed, or whose answers are wrong, reports an error.
void report(benchmark::State& state, const Case& c, const std::vector<double>& P0, int rows_per,
            double worst, int failed, int iterations, bool driver) {
  const int contacts = c.problems[0].contacts();
  for (int i = 0; i < contacts; ++i) {
    state.counters["P_N" + std::to_string(i)] = P0[rows_per * i];
    if (rows_per >= 2) state.counters["P_T" + std::to_string(i)] = P0[rows_per * i + 1];
  }
  state.counters["err"] = worst;
  state.counters["iter"] = iterations;
  state.counters["failed"] = failed;
  state.SetLabel(bench_label(c.problem, c.law) + (driver ? " stage=driver" : ""));
  if (failed == static_cast<int>(c.problems.size()))
    state.SkipWithError("Siconos failed on every problem (info != 0)");
  else if (!(worst <= 1e-9))
    state.SkipWithError(
        ("answer differs from the closed form by " + std::to_string(worst)).c_str());
}

/// Newton (+ Coulomb) as an LCP. Frictionless: z = P_N, w = G_NN P_N + (1 + e) D_NA (eq. 6).
/// With Coulomb, per contact z = (P_N, P_T⁺, P_T⁻, λ), P_T = P_T⁺ − P_T⁻ and
///   w_N = D_NE + e D_NA,  w_+ = D_TE + λ,  w_− = −D_TE + λ,  w_λ = μ P_N − P_T⁺ − P_T⁻,
/// whose solutions are those of Newton + Coulomb (λ = |D_TE|).
void fill_lcp(const Delassus& d, int c, bool friction, double e, double mu, double* M, double* q) {
  if (!friction) {
    for (int j = 0; j < c; ++j) {
      q[j] = (1 + e) * d.D_A(j);
      for (int i = 0; i < c; ++i) M[i + c * j] = d.G(i, j);
    }
    return;
  }
  const int n = 4 * c;
  std::fill(M, M + n * n, 0.0);
  auto at = [&](int i, int j) -> double& { return M[i + n * j]; };
  for (int a = 0; a < c; ++a) {
    q[a] = (1 + e) * d.D_A(2 * a);
    q[c + a] = d.D_A(2 * a + 1);
    q[2 * c + a] = -d.D_A(2 * a + 1);
    q[3 * c + a] = 0.0;
    for (int b = 0; b < c; ++b) {
      const double nn = d.G(2 * a, 2 * b), nt = d.G(2 * a, 2 * b + 1);
      const double tn = d.G(2 * a + 1, 2 * b), tt = d.G(2 * a + 1, 2 * b + 1);
      at(a, b) = nn, at(a, c + b) = nt, at(a, 2 * c + b) = -nt;
      at(c + a, b) = tn, at(c + a, c + b) = tt, at(c + a, 2 * c + b) = -tt;
      at(2 * c + a, b) = -tn, at(2 * c + a, c + b) = -tt, at(2 * c + a, 2 * c + b) = tt;
    }
    at(c + a, 3 * c + a) = 1.0;
    at(2 * c + a, 3 * c + a) = 1.0;
    at(3 * c + a, a) = mu;
    at(3 * c + a, c + a) = -1.0;
    at(3 * c + a, 2 * c + a) = -1.0;
  }
}

/// The percussions, in Siconos's row order, from an LCP solution z.
void lcp_percussions(const double* z, int c, bool friction, double* P) {
  for (int a = 0; a < c; ++a) {
    if (!friction) {
      P[a] = z[a];
    } else {
      P[2 * a] = z[a];
      P[2 * a + 1] = z[c + a] - z[2 * c + a];
    }
  }
}

void BM_Siconos_LCP(benchmark::State& state, const Case* c, siconos::LcpSolver solver,
                    bool driver) {
  const int contacts = c->problems[0].contacts();
  const bool friction = c->problems[0].has_tangential();
  const int n = friction ? 4 * contacts : contacts, rows_per = friction ? 2 : 1;
  siconos::Lcp lcp(n, solver);
  std::vector<double> M(n * n), q(n), z(n), w(n), P(rows_per * contacts);
  Delassus d;
  siconos::SolveInfo info;
  std::size_t k = 0;
  if (driver) {
    // Siconos's own problem, (M, q) assembled once per problem: the driver's work alone.
    std::vector<std::vector<double> > Ms(c->problems.size(), M), qs(c->problems.size(), q);
    for (std::size_t j = 0; j < c->problems.size(); ++j) {
      assemble(c->problems[j], d);
      fill_lcp(d, contacts, friction, c->e, c->mu, Ms[j].data(), qs[j].data());
    }
    for (auto _ : state) {
      const std::size_t j = k++ % c->problems.size();
      info = lcp.solve(Ms[j].data(), qs[j].data(), z.data(), w.data());
      benchmark::DoNotOptimize(z.data());
    }
  } else {
    for (auto _ : state) {
      const SmallImpactProblem& p = c->problems[k++ % c->problems.size()];
      assemble(p, d);
      fill_lcp(d, contacts, friction, c->e, c->mu, M.data(), q.data());
      info = lcp.solve(M.data(), q.data(), z.data(), w.data());
      benchmark::DoNotOptimize(z.data());
    }
  }
  // Check every problem of the case, untimed.
  double worst = 0.0;
  int failed = 0;
  std::vector<double> P0(P.size(), 0.0);
  for (std::size_t j = 0; j < c->problems.size(); ++j) {
    assemble(c->problems[j], d);
    fill_lcp(d, contacts, friction, c->e, c->mu, M.data(), q.data());
    info = lcp.solve(M.data(), q.data(), z.data(), w.data());
    if (info.info != 0) {
      ++failed;
      continue;
    }
    lcp_percussions(z.data(), contacts, friction, P.data());
    if (j == 0) P0 = P;
    worst = std::max(
        worst, error_against(*c, static_cast<int>(j), qdot_from(c->problems[j], d, P.data())));
  }
  report(state, *c, P0, rows_per, worst, failed, info.iterations, driver);
}

void BM_Siconos_FC2D(benchmark::State& state, const Case* c, siconos::Fc2dSolver solver,
                     bool driver) {
  const int contacts = c->problems[0].contacts(), n = 2 * contacts;
  siconos::FrictionContact2d fc(contacts, solver);
  std::vector<double> M(n * n), q(n), mu(contacts, c->mu), r(n), u(n);
  Delassus d;
  siconos::SolveInfo info;
  auto fill = [&](const SmallImpactProblem& p) {
    assemble(p, d);
    for (int j = 0; j < n; ++j) {
      q[j] = (j % 2 == 0 ? 1 + c->e : 1.0) * d.D_A(j);
      for (int i = 0; i < n; ++i) M[i + n * j] = d.G(i, j);
    }
  };
  std::size_t k = 0;
  if (driver) {
    std::vector<std::vector<double> > Ms, qs;
    for (const SmallImpactProblem& p : c->problems) {
      fill(p);
      Ms.push_back(M);
      qs.push_back(q);
    }
    for (auto _ : state) {
      const std::size_t j = k++ % c->problems.size();
      info = fc.solve(Ms[j].data(), qs[j].data(), mu.data(), r.data(), u.data());
      benchmark::DoNotOptimize(r.data());
    }
  } else {
    for (auto _ : state) {
      fill(c->problems[k++ % c->problems.size()]);
      info = fc.solve(M.data(), q.data(), mu.data(), r.data(), u.data());
      benchmark::DoNotOptimize(r.data());
    }
  }
  double worst = 0.0;
  int failed = 0;
  std::vector<double> P0(n, 0.0);
  for (std::size_t j = 0; j < c->problems.size(); ++j) {
    fill(c->problems[j]);
    info = fc.solve(M.data(), q.data(), mu.data(), r.data(), u.data());
    if (info.info != 0) {
      ++failed;
      continue;
    }
    if (j == 0) P0 = r;
    worst = std::max(
        worst, error_against(*c, static_cast<int>(j), qdot_from(c->problems[j], d, r.data())));
  }
  report(state, *c, P0, 2, worst, failed, info.iterations, driver);
}

// ---------------------------------------------------------------------------------------------
// The cases, with their closed forms.

Case newton_case(std::string name, std::vector<SmallImpactProblem> problems) {
  Case c = make_case(std::move(name), "newton", std::move(problems));
  for (const auto& p : c.problems) {
    const ContactSpace cs = contact_space(p);
    c.expected.push_back({velocity_after(p, cs, newton_frictionless(cs.G, cs.D_A, c.e))});
  }
  return c;
}

const std::vector<Case>& cases() {
  static const std::vector<Case> all = [] {
    std::vector<Case> v;
    // (i) the bar at its first impact.
    v.push_back(newton_case("bar_first_impact", {bar_first_impact(false)}));
    {
      Case c = make_case("bar_first_impact", "newton_coulomb", {bar_first_impact(true)});
      const ContactSpace cs = contact_space(c.problems[0]);
      const Eigen::Vector2d P = newton_coulomb_one_contact(cs.G, cs.D_A(0), cs.D_A(1), c.e, c.mu);
      c.expected.push_back({velocity_after(c.problems[0], cs, P)});
      v.push_back(std::move(c));
    }
    // (ii) the flat bar with two contacts (G singular with the friction rows).
    v.push_back(newton_case("flat_bar", {flat_bar_two_contacts(false)}));
    {
      Case c = make_case("flat_bar", "newton_coulomb", {flat_bar_two_contacts(true)});
      c.expected.push_back({flat_bar_newton_coulomb_velocity(c.e, c.mu)});
      v.push_back(std::move(c));
    }
    // A point mass sliding.
    {
      Case c = make_case("point_mass", "newton_coulomb", {planar_point_mass()});
      const ContactSpace cs = contact_space(c.problems[0]);
      const Eigen::Vector2d P = newton_coulomb_one_contact(cs.G, cs.D_A(0), cs.D_A(1), c.e, c.mu);
      c.expected.push_back({velocity_after(c.problems[0], cs, P)});
      v.push_back(std::move(c));
    }
    // Random SPD problems, n = 6, 3 contacts, fixed seed.
    {
      std::vector<SmallImpactProblem> ps;
      for (int i = 0; i < kRandomProblems; ++i) ps.push_back(random_spd_problem(i, false));
      v.push_back(newton_case("random_n6_c3", std::move(ps)));
    }
    {
      Case c = make_case("random_n6_c3", "newton_coulomb", {});
      for (int i = 0; i < kRandomProblems; ++i) {
        SmallImpactProblem p = random_spd_problem(i, true);
        auto sols = newton_coulomb_enumerate(p, c.e, c.mu);
        if (sols.empty()) continue;  // no solution: nothing to compare against
        c.problems.push_back(std::move(p));
        c.expected.push_back(std::move(sols));
      }
      v.push_back(std::move(c));
    }
    return v;
  }();
  return all;
}

std::string camel(const std::string& s) {
  std::string out;
  bool up = true;
  for (char ch : s) {
    if (ch == '_') {
      up = true;
      continue;
    }
    out += up ? static_cast<char>(std::toupper(static_cast<unsigned char>(ch))) : ch;
    up = false;
  }
  return out;
}

const bool registered = [] {
  using siconos::Fc2dSolver;
  using siconos::LcpSolver;
  benchmark::AddCustomContext("siconos", siconos::version());
  for (const Case& c : cases()) {
    const std::string suffix = "/" + c.problem + "/" + c.law;
    const bool friction = c.problems[0].has_tangential();
    for (LcpSolver s : {LcpSolver::lemke, LcpSolver::enumeration}) {
      if (s == LcpSolver::enumeration && c.problems[0].contacts() > 2 && friction) continue;
      for (const bool driver : {false, true})
        benchmark::RegisterBenchmark(
            ("BM_Siconos_LCP_" + camel(siconos::to_string(s)) + (driver ? "_Driver" : "") + suffix)
                .c_str(),
            BM_Siconos_LCP, &c, s, driver);
    }
    if (!friction) continue;
    for (Fc2dSolver s : {Fc2dSolver::nsgs, Fc2dSolver::lemke, Fc2dSolver::enumeration}) {
      if (s == Fc2dSolver::enumeration && c.problems[0].contacts() > 2) continue;
      for (const bool driver : {false, true})
        benchmark::RegisterBenchmark(
            ("BM_Siconos_FC2D_" + camel(siconos::to_string(s)) + (driver ? "_Driver" : "") + suffix)
                .c_str(),
            BM_Siconos_FC2D, &c, s, driver);
    }
  }
  return true;
}();

#endif  // FREMOND_HAVE_SICONOS

}  // namespace
