// Our classical laws (Newton, Poisson, with Coulomb) on the benchmark problems of problems.hpp, at
// three depths, each labelled so that bench/compare.py can set them beside the Siconos peers:
//
//  - BM_Classical_FromData: from (M, W, q̇_A) to the percussions, i.e. the contact space
//    (G = Wᵀ M⁻¹ W on the stack) then the law. This is what the Siconos peers time; same label.
//  - BM_Classical_Law: the law alone, from G and D_A: closed form, Lemke, and the minimum-norm
//    choice where G is singular ("from=G" in the label).
//  - BM_Classical_Kernel: the exact method alone on the contact-space data of one phase: the closed
//    form for one contact; for several, G's factor, the eq. 6 guess (every contact closed and
//    sticking, in its semidefinite form where G is singular), then Lemke on the phase's LCP if the
//    guess fails ("stage=kernel"); no minimum-norm choice, no uniqueness check. This is the work
//    the Siconos peers' solvers do after assembly.
//  - BM_Classical_Prepared: the prepared solver (ImpactSolver) built once per problem, then
//    solve(q̇_A) with the same answer, certificate and residual as solve_impact ("stage=prepared").
//  - BM_Classical_SolveImpact: the public entry point, with input validation, the result's
//    velocities, the law's residual and the admissibility report ("stage=solve_impact"); uniqueness
//    checked by mode enumeration or not ("checked=1|0").
//
// After timing, each benchmark checks its answer against the closed forms of problems.hpp and
// reports the percussions as counters.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "problems.hpp"
#include "solvers/detail/classical_law.hpp"

namespace {

using namespace fremond;
using namespace fremond::bench;
using ContactSpace3 = detail::ContactSpaceT<kSmallDofs, kSmallContacts>;

struct Case {
  std::string problem, law_name;
  std::vector<SmallImpactProblem> problems;
  ImpactLaw law;
  std::vector<Eigen::VectorXd> expected;  ///< q̇_E per problem (empty: checked by residual only)
};

const std::vector<Case>& cases() {
  static const std::vector<Case> all = [] {
    std::vector<Case> v;
    const double e = kRestitution, mu = kFriction;
    auto newton_expected = [&](const SmallImpactProblem& p) {
      const ContactSpace cs = contact_space(p);
      return velocity_after(p, cs, newton_frictionless(cs.G, cs.D_A, e));
    };
    auto coulomb_expected = [&](const SmallImpactProblem& p) {
      const ContactSpace cs = contact_space(p);
      const Eigen::Matrix2d G = cs.G;
      return velocity_after(p, cs, newton_coulomb_one_contact(G, cs.D_A(0), cs.D_A(1), e, mu));
    };
    {
      Case c{"bar_first_impact", "newton", {bar_first_impact(false)}, ImpactLaw::newton(e), {}};
      c.expected.push_back(newton_expected(c.problems[0]));
      v.push_back(c);
    }
    {
      Case c{"bar_first_impact",
             "newton_coulomb",
             {bar_first_impact(true)},
             ImpactLaw::newton_coulomb(e, mu),
             {}};
      c.expected.push_back(coulomb_expected(c.problems[0]));
      v.push_back(c);
    }
    v.push_back(Case{"bar_first_impact",
                     "poisson_coulomb",
                     {bar_first_impact(true)},
                     ImpactLaw::poisson_coulomb(e, mu),
                     {}});
    {
      Case c{"point_mass",
             "newton_coulomb",
             {planar_point_mass()},
             ImpactLaw::newton_coulomb(e, mu),
             {}};
      c.expected.push_back(coulomb_expected(c.problems[0]));
      v.push_back(c);
    }
    {
      Case c{"flat_bar", "newton", {flat_bar_two_contacts(false)}, ImpactLaw::newton(e), {}};
      c.expected.push_back(newton_expected(c.problems[0]));
      v.push_back(c);
    }
    {
      Case c{"flat_bar",
             "newton_coulomb",
             {flat_bar_two_contacts(true)},
             ImpactLaw::newton_coulomb(e, mu),
             {}};
      c.expected.push_back(flat_bar_newton_coulomb_velocity(e, mu));
      v.push_back(c);
    }
    v.push_back(Case{"flat_bar",
                     "poisson_coulomb",
                     {flat_bar_two_contacts(true)},
                     ImpactLaw::poisson_coulomb(e, mu),
                     {}});
    {
      Case c{"random_n6_c3", "newton", {}, ImpactLaw::newton(e), {}};
      for (int i = 0; i < kRandomProblems; ++i) {
        c.problems.push_back(random_spd_problem(i, false));
        c.expected.push_back(newton_expected(c.problems.back()));
      }
      v.push_back(c);
    }
    {
      Case c{"random_n6_c3", "newton_coulomb", {}, ImpactLaw::newton_coulomb(e, mu), {}};
      for (int i = 0; i < kRandomProblems; ++i) c.problems.push_back(random_spd_problem(i, true));
      v.push_back(c);
    }
    return v;
  }();
  return all;
}

// Checks every problem of the case with the full entry point (untimed): converged, the law's
// residual at rounding, and q̇_E equal to the closed form where there is one.
void check(benchmark::State& state, const Case& c) {
  double worst = 0.0, residual = 0.0;
  for (std::size_t k = 0; k < c.problems.size(); ++k) {
    const SmallImpactResult r = solve_impact(c.problems[k], c.law);
    if (!r.ok()) {
      state.SkipWithError(("not solved: " + std::string(r.solver.message)).c_str());
      return;
    }
    residual = std::max(residual, r.solver.residual);
    if (k < c.expected.size())
      worst =
          std::max(worst, (Eigen::VectorXd(r.qdot_E) - c.expected[k]).lpNorm<Eigen::Infinity>());
    if (k == 0)
      for (int i = 0; i < r.P_N.size(); ++i) {
        state.counters["P_N" + std::to_string(i)] = r.P_N(i);
        state.counters["P_T" + std::to_string(i)] = r.P_T(i);
      }
  }
  state.counters["err"] = worst;
  state.counters["residual"] = residual;
  if (!(worst <= 1e-9) || !(residual <= 1e-12))
    state.SkipWithError(
        ("answer differs from the closed form by " + std::to_string(worst)).c_str());
}

void BM_Classical_FromData(benchmark::State& state, const Case* c) {
  ContactSpace3 cs;
  detail::classical::LawOutcome<kSmallContacts> lo;
  std::size_t k = 0;
  for (auto _ : state) {
    const SmallImpactProblem& p = c->problems[k++ % c->problems.size()];
    detail::build_contact_space(p, c->law.has_friction(), cs);
    detail::classical::solve_law(p, cs, c->law.get<RestitutionLaw>(), false, lo);
    benchmark::DoNotOptimize(lo.solutions[0].P.data());
  }
  state.SetLabel(bench_label(c->problem, c->law_name));
  check(state, *c);
}

void BM_Classical_Law(benchmark::State& state, const Case* c) {
  std::vector<ContactSpace3> spaces(c->problems.size());
  for (std::size_t k = 0; k < c->problems.size(); ++k)
    detail::build_contact_space(c->problems[k], c->law.has_friction(), spaces[k]);
  detail::classical::LawOutcome<kSmallContacts> lo;
  std::size_t k = 0;
  for (auto _ : state) {
    const std::size_t j = k++ % c->problems.size();
    detail::classical::solve_law(c->problems[j], spaces[j], c->law.get<RestitutionLaw>(), false,
                                 lo);
    benchmark::DoNotOptimize(lo.solutions[0].P.data());
  }
  state.SetLabel(bench_label(c->problem, c->law_name) + " from=G");
  check(state, *c);
}

void BM_Classical_SolveImpact(benchmark::State& state, const Case* c, bool checked) {
  SolverOptions options;
  options.check_uniqueness = checked;
  std::size_t k = 0;
  for (auto _ : state) {
    const SmallImpactResult r =
        solve_impact(c->problems[k++ % c->problems.size()], c->law, options);
    benchmark::DoNotOptimize(r.P_N.data());
  }
  state.SetLabel(bench_label(c->problem, c->law_name) +
                 " stage=solve_impact checked=" + (checked ? "1" : "0"));
  check(state, *c);
}

void BM_Classical_Prepared(benchmark::State& state, const Case* c, bool checked) {
  SolverOptions options;
  options.check_uniqueness = checked;
  std::vector<SmallImpactSolver> solvers;
  for (const SmallImpactProblem& p : c->problems) solvers.emplace_back(p, c->law, options);
  std::size_t k = 0;
  for (auto _ : state) {
    SmallImpactSolver& s = solvers[k++ % solvers.size()];
    const SmallImpactResult& r = s.solve(s.problem().qdot_A);
    benchmark::DoNotOptimize(r.P_N.data());
  }
  state.SetLabel(bench_label(c->problem, c->law_name) +
                 " stage=prepared checked=" + (checked ? "1" : "0"));
  // The prepared answers are solve_impact's, which check() holds to the closed forms.
  for (std::size_t i = 0; i < solvers.size(); ++i)
    if (!(Eigen::VectorXd(solvers[i].solve(c->problems[i].qdot_A).qdot_E) ==
          Eigen::VectorXd(solve_impact(c->problems[i], c->law, options).qdot_E))) {
      state.SkipWithError("the prepared solver's answer differs from solve_impact's");
      return;
    }
  check(state, *c);
}

// The first phase of the law (Newton: eq. 5; Poisson: compression) on contact space.
detail::classical::Phase<kSmallContacts> first_phase(const SmallImpactProblem& p,
                                                     const ContactSpace3& cs,
                                                     const ImpactLaw& law) {
  detail::classical::Phase<kSmallContacts> ph;
  ph.a = cs.active;
  ph.friction = cs.tangential;
  const int r = ph.rows(), a = ph.a;
  ph.G = cs.G.topLeftCorner(r, r);
  ph.q = cs.D_A.head(r);
  ph.mu.resize(a);
  ph.b0.setZero(a);
  const bool newton = law.name() == "newton" || law.name() == "newton_coulomb";
  for (int k = 0; k < a; ++k) {
    if (newton) ph.q(k) *= 1 + law.get<RestitutionLaw>().e[cs.index(k)];
    ph.mu(k) = ph.friction ? law.mu(cs.index(k)) : 0.0;
  }
  (void)p;
  return ph;
}

void BM_Classical_Kernel(benchmark::State& state, const Case* c) {
  const SmallImpactProblem& p = c->problems[0];
  ContactSpace3 cs;
  detail::build_contact_space(p, c->law.has_friction(), cs);
  const auto ph = first_phase(p, cs, c->law);
  const auto tol = detail::classical::tolerances(ph, cs.v_scale);
  detail::classical::Phase<kSmallContacts>::Rows u(ph.rows());
  int pivots = 0;
  for (auto _ : state) {
    if (ph.a == 1) {
      const bool f = ph.friction;
      const auto oc = detail::classical::one_contact(
          ph.G(0, 0), f ? ph.G(0, 1) : 0.0, f ? ph.G(1, 1) : 0.0, ph.q(0), f ? ph.q(1) : 0.0,
          f ? ph.mu(0) : 0.0, 0.0, f, tol);
      benchmark::DoNotOptimize(oc);
    } else {
      // G's factor (none for the flat bar: more rows than degrees of freedom) is in the loop; its
      // null space, which only the minimum-norm choice needs, is not.
      detail::classical::Factored<kSmallContacts> fg;
      fg.compute(ph.G, p.dofs());
      bool solved = false;
      benchmark::DoNotOptimize(detail::classical::exact_phase(ph, tol, fg, u, pivots, solved));
      benchmark::DoNotOptimize(u.data());
    }
  }
  state.counters["pivots"] = pivots;
  state.SetLabel(bench_label(c->problem, c->law_name) + " stage=kernel");
  // The kernel's own answer (Newton's laws: P = u) against the closed form, as check() does for
  // solve_impact's.
  const bool newton = c->law.name() == "newton" || c->law.name() == "newton_coulomb";
  if (ph.a > 1 && newton && !c->expected.empty()) {
    const Eigen::VectorXd qE = Eigen::VectorXd(p.qdot_A) + Eigen::MatrixXd(cs.MinvW) * u;
    const double err = (qE - c->expected[0]).lpNorm<Eigen::Infinity>();
    state.counters["kernel_err"] = err;
    if (!(err <= 1e-9)) {
      state.SkipWithError(
          ("the kernel's answer differs from the closed form by " + std::to_string(err)).c_str());
      return;
    }
  }
  check(state, *c);
}

const bool registered = [] {
  for (const Case& c : cases()) {
    const std::string suffix = "/" + c.problem + "/" + c.law_name;
    benchmark::RegisterBenchmark(("BM_Classical_FromData" + suffix).c_str(), BM_Classical_FromData,
                                 &c);
    benchmark::RegisterBenchmark(("BM_Classical_Law" + suffix).c_str(), BM_Classical_Law, &c);
    if (c.problems.size() == 1)
      benchmark::RegisterBenchmark(("BM_Classical_Kernel" + suffix).c_str(), BM_Classical_Kernel,
                                   &c);
    for (const bool checked : {false, true})
      benchmark::RegisterBenchmark(
          ("BM_Classical_SolveImpact" + suffix + (checked ? "/checked" : "/unchecked")).c_str(),
          BM_Classical_SolveImpact, &c, checked);
    for (const bool checked : {false, true})
      benchmark::RegisterBenchmark(
          ("BM_Classical_Prepared" + suffix + (checked ? "/checked" : "/unchecked")).c_str(),
          BM_Classical_Prepared, &c, checked);
  }
  return true;
}();

}  // namespace
