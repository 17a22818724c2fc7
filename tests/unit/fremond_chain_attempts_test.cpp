// Frémond's chain records every method it runs: what it ran, from where, and how that ended. The
// answer is checked against a second method (or a closed form), and the log against what was
// asked for.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fremond/io/problem_file.hpp"
#include "fremond/potentials/deadzone_power.hpp"
#include "fremond/potentials/power.hpp"
#include "fremond/solvers/solve_impact.hpp"
#include "support/block_landing.hpp"
#include "support/test_problems.hpp"

namespace fremond {
namespace {

std::vector<Attempt> log_of(const SolverReport& s) {
  return {s.attempts.begin(),
          s.attempts.begin() + std::min(s.attempt_count, SolverReport::kMaxAttempts)};
}

// Eq. (24): a point mass under φ_N = k z²/2 leaves with D_NE = (k − 2m)/(k + 2m) |D_NA|, one prox.
TEST(FremondChainAttempts, OneDecoupledRowIsOneExactAttempt) {
  const ImpactResult r =
      solve_impact(testing::point_mass(1.0, -2.0), ImpactLaw::fremond(PowerPotential(38.0, 2.0)));
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.D_NE(0), 2.0 * 36.0 / 40.0, 1e-15);
  ASSERT_EQ(r.solver.attempt_count, 1);
  EXPECT_EQ(r.solver.attempts[0].method, SolverMethod::closed_form);
  EXPECT_EQ(r.solver.attempts[0].start, AttemptStart::none);
  EXPECT_EQ(r.solver.attempts[0].status, SolverStatus::converged);
  EXPECT_EQ(r.solver.fallbacks, 0);
}

// A forced method runs alone, from zero, and its answer is the automatic chain's.
TEST(FremondChainAttempts, AForcedMethodIsTheOnlyAttemptAndAgreesWithTheChain) {
  const ImpactProblem pb = testing::paper_bar_first_impact();
  const ImpactLaw law =
      ImpactLaw::fremond(PowerPotential(85.36, 3.0), DeadZonePowerPotential(1.5, 2.0, 0.2));
  const ImpactResult chain = solve_impact(pb, law);
  ASSERT_TRUE(chain.ok());
  for (SolverMethod m : {SolverMethod::proximal, SolverMethod::nlopt}) {
    SolverOptions opt;
    opt.method = m;
    const ImpactResult r = solve_impact(pb, law, opt);
    ASSERT_TRUE(r.ok()) << to_string(m) << ": " << r.solver.message;
    const auto attempts = log_of(r.solver);
    ASSERT_EQ(attempts.size(), 1u) << to_string(m);
    EXPECT_EQ(attempts[0].method, m);
    EXPECT_EQ(attempts[0].start, AttemptStart::zero);
    EXPECT_EQ(attempts[0].status, SolverStatus::converged);
    const double tol = m == SolverMethod::nlopt ? 1e-6 : 1e-10;
    EXPECT_LT((r.qdot_E - chain.qdot_E).norm(), tol * chain.qdot_E.norm()) << to_string(m);
  }
}

// Another law's method forced on Frémond's (the classical laws' Lemke and sweeps, Stronge's
// integration) is refused by name, the state before the impact returned, not answered by NLopt.
TEST(FremondChainAttempts, AnotherLawsMethodIsRefusedNotAnsweredByNlopt) {
  const ImpactProblem pb = testing::paper_bar_first_impact();
  for (const ImpactLaw& law : {ImpactLaw::fremond(PowerPotential(85.36, 3.0)),
                               ImpactLaw::fremond_coulomb(PowerPotential(85.36, 3.0), 0.3)}) {
    for (SolverMethod m :
         {SolverMethod::lemke, SolverMethod::nsgs, SolverMethod::impulse_integration}) {
      SCOPED_TRACE(std::string(to_string(m)) + " on " + law.describe());
      SolverOptions opt;
      opt.method = m;
      const ImpactResult r = solve_impact(pb, law, opt);
      EXPECT_EQ(r.solver.status, SolverStatus::unsupported);
      EXPECT_EQ(r.solver.method, m);
      EXPECT_EQ(r.P_N(0), 0.0);
      EXPECT_EQ(r.qdot_E, pb.qdot_A);
      for (const Attempt& a : log_of(r.solver)) EXPECT_NE(a.method, SolverMethod::nlopt);
    }
  }
}

// A case where every method fails or nearly (test_problems.hpp): the log holds Newton, the
// splitting and NLopt in the chain's order, the answer's method is the last converged attempt or
// the nearest failure, and no attempt is recorded twice by mistake (the count stays within the
// table's length).
TEST(FremondChainAttempts, AHardCaseLogsTheStagesInOrder) {
  const auto [pb, law] = testing::every_method_failing_case();
  const ImpactResult r = solve_impact(pb, law);
  const auto attempts = log_of(r.solver);
  ASSERT_GE(attempts.size(), 2u);
  EXPECT_LE(r.solver.attempt_count, SolverReport::kMaxAttempts);
  EXPECT_EQ(r.solver.fallbacks, r.solver.attempt_count - 1);
  // The first is Newton from the decoupled guess (in velocity or contact space).
  EXPECT_EQ(attempts[0].method, SolverMethod::semismooth_newton);
  EXPECT_EQ(attempts[0].start, AttemptStart::decoupled_guess);
  // The answer's method ran, and if it converged, it is the last attempt.
  bool ran = false;
  for (const Attempt& a : attempts) ran = ran || a.method == r.solver.method;
  EXPECT_TRUE(ran) << to_string(r.solver.method);
  if (r.solver.status == SolverStatus::converged) {
    EXPECT_EQ(attempts.back().method, r.solver.method);
    EXPECT_EQ(attempts.back().status, SolverStatus::converged);
  }
  // No attempt before the last converged: the chain stops at the first answer.
  for (std::size_t i = 0; i + 1 < attempts.size(); ++i)
    EXPECT_NE(attempts[i].status, SolverStatus::converged) << i;
}

// One test per later stage of the chain: a problem the earlier stages do not solve, the stage that
// answers it, and that every attempt before it failed. The answers themselves are checked in
// regression_fremond_test.cpp; here only that they are answers (converged, admissible).

/// The answer's attempt is the last of the log, `m` from `from`, and the only one that converged
/// before it is the `converged_before`-th from the end, if any.
template <class Result>
void expect_answered_by(const Result& r, SolverMethod m, AttemptStart from,
                        std::size_t converged_before = 0) {
  ASSERT_TRUE(r.ok()) << to_string(r.solver.status) << ": " << r.solver.message;
  EXPECT_TRUE(r.admissibility.admissible);
  const auto attempts = log_of(r.solver);
  ASSERT_GE(attempts.size(), 2u);
  EXPECT_EQ(attempts.back().method, m) << to_string(attempts.back().method);
  EXPECT_EQ(attempts.back().start, from) << to_string(attempts.back().start);
  EXPECT_EQ(attempts.back().status, SolverStatus::converged);
  for (std::size_t i = 0; i + 1 < attempts.size(); ++i)
    if (i + 1 + converged_before != attempts.size()) {
      EXPECT_NE(attempts[i].status, SolverStatus::converged) << i;
    }
}

ImpactResult solve_file(const char* json) {
  const auto file = io::parse_problem_file(json, PotentialRegistry::with_builtins());
  return solve_impact(file.problem, file.law);
}

// Coulomb with a steep normal law (p = 1.1) at speeds of 1e-6: Newton from the decoupled guess
// stalls, Newton from zero converges.
TEST(FremondChainAttempts, NewtonRestartsFromZero) {
  const ImpactResult r = solve_file(
      R"({"M": [[34.832422524320791,-400.94579235082705],[-400.94579235082705,60519.482819093108]],
          "W_N": [[0.23154132527734161,0.093284482225310272],[0.18541964068402927,-0.28432395107291986]],
          "W_T": [[0.15110854627609305,0.52018868693718323],[-0.17911350296887352,-0.23516561057544549]],
          "qdot_A": [-2.2397687300158853e-06,8.2094214115504115e-07],
          "law": {"type": "fremond", "normal": {"potential": "power", "k": 1000000, "p": 1.1},
                  "tangential": {"potential": "coulomb", "mu": 10}}})");
  expect_answered_by(r, SolverMethod::semismooth_newton, AttemptStart::zero);
}

// A block landing flat, one corner at the edge of sticking: Newton stalls from both starts at a
// kink of the residual; with Coulomb's modes fixed the rows are smooth.
TEST(FremondChainAttempts, CoulombModesAreEnumeratedWhereNewtonStallsFromBothStarts) {
  const ImpactProblem pb = fixtures::block_landing_flat();
  const ImpactResult r = solve_impact(
      pb, ImpactLaw::fremond_coulomb(PowerPotential(fixtures::block_landing_flat_k, 3.0), 1.0));
  expect_answered_by(r, SolverMethod::mode_enumeration, AttemptStart::decoupled_guess);
  const auto attempts = log_of(r.solver);
  ASSERT_EQ(attempts.size(), 3u);
  EXPECT_EQ(attempts[1].method, SolverMethod::semismooth_newton);
  EXPECT_EQ(attempts[1].start, AttemptStart::zero);
}

// Viscous dead zones on four contacts of a 2-dof body: Newton and the splitting stall, Newton from
// where the splitting stopped converges.
TEST(FremondChainAttempts, NewtonRestartsFromTheSplittingsEnd) {
  const ImpactResult r = solve_file(
      R"({"M": [[0.7077193479239462,-0.17045052276871808],[-0.17045052276871808,0.86054087999774287]],
          "W_N": [[0.68002268311234437,0.85570860612568245,0.47805157281625399,0.35927537561422818],[0.39857834852343665,0.28981319197035504,-0.80487345646448483,-0.19467436896913837]],
          "W_T": [[-0.36530050373185552,0.54294512133894801,0.35457656764183598,-0.53793989408720266],[0.16649189990020852,0.094865895389332655,0.52357273998550324,-0.97723269422870573]],
          "qdot_A": [-0.96021194525707099,0.63806566635368678],
          "law": {"type": "fremond", "normal": {"potential": "power", "k": 91.505437149853876, "p": 1.2299736407473134},
                  "tangential": {"potential": "deadzone_power", "k": 91.505437149853876, "q": 2.9245042322444896, "r": 0.1}}})");
  expect_answered_by(r, SolverMethod::semismooth_newton, AttemptStart::splitting_end);
}

// The bar nearly upright on both ends, its normal rows nearly equal: every method stalls on a
// wrong split of P_N, and Newton from NLopt's answer converges.
TEST(FremondChainAttempts, NewtonPolishesNloptsAnswer) {
  const ImpactResult r = solve_file(R"({
    "M": [[179.32339602043095, 0, 0], [0, 179.32339602043095, 0], [0, 0, 14.943616335035912]],
    "W_N": [[0, 0], [1, 1], [-3.5741238053350548e-09, 3.5741238053350548e-09]],
    "W_T": [[1, 1], [0, 0], [0.5, -0.5]],
    "qdot_A": [-0.90311200536352632, -0.30976052981586705, 0.015417588641822787],
    "law": {"type": "fremond",
            "normal": {"potential": "power", "k": [6.8259324178360091e-06, 35.253899449369612],
                       "p": [2.5760277635250635, 2]},
            "tangential": {"potential": "deadzone_power",
                           "k": [8.7629353705275542e-05, 158.86181804355593], "q": [2, 2],
                           "r": [0, 0.017350158885100681]}}})");
  expect_answered_by(r, SolverMethod::semismooth_newton, AttemptStart::nlopt_end);
}

// The flat bar on a rotor 1e6 times lighter than the paper's, steep power law and dead zone: the
// contact-space methods stall, and Newton from velocity-space Newton's answer converges.
TEST(FremondChainAttempts, NewtonRestartsFromVelocitySpaceNewtonsEnd) {
  SmallImpactProblem pb = testing::flat_bar_two_contacts(true);
  pb.M(2, 2) *= 1e-6;
  const SmallImpactResult r = solve_impact(
      pb, ImpactLaw::fremond(PowerPotential(1e6, 3), DeadZonePowerPotential(1e6, 2, 0.2)));
  expect_answered_by(r, SolverMethod::semismooth_newton, AttemptStart::velocity_newton_end);
}

// The same bar at 1e6 m/s with p = 1.5: only the normal rows solved alone (G_NT = 0; that solve is
// logged, without a start), then Newton on every row from there, converge.
TEST(FremondChainAttempts, NewtonRestartsFromTheNormalRowsAlone) {
  SmallImpactProblem pb = testing::flat_bar_two_contacts(true);
  pb.qdot_A *= 1e6;
  pb.M(2, 2) *= 1e-6;
  const SmallImpactResult r = solve_impact(
      pb, ImpactLaw::fremond(PowerPotential(1e6, 1.5), DeadZonePowerPotential(1e6, 2.0, 0.0)));
  expect_answered_by(r, SolverMethod::semismooth_newton, AttemptStart::normal_rows, 1);
  const auto attempts = log_of(r.solver);
  EXPECT_EQ(attempts[attempts.size() - 2].start, AttemptStart::none);
}

// The plate on 16 contacts of 3 dofs (48 rows): the first attempt (Newton, in velocity space where
// rows outnumber the dofs) answers, in a few steps.
TEST(FremondChainAttempts, ManyRowsOnFewDofsAreAnsweredByTheFirstAttempt) {
  const ImpactProblem pb = testing::plate_many_contacts(16, true);
  const ImpactResult r =
      solve_impact(pb, ImpactLaw::fremond(PowerPotential(testing::bar_fremond_k_normal(3.0), 3.0),
                                          DeadZonePowerPotential(1.5, 2.0, 0.2)));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  ASSERT_EQ(r.solver.attempt_count, 1);
  EXPECT_EQ(r.solver.attempts[0].method, SolverMethod::semismooth_newton);
  EXPECT_EQ(r.solver.attempts[0].status, SolverStatus::converged);
  EXPECT_LE(r.solver.iterations, 16);
}

}  // namespace
}  // namespace fremond
