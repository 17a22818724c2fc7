// Frémond's chain records every method it runs: what it ran, from where, and how that ended. The
// answer is checked against a second method (or a closed form), and the log against what was
// asked for.
#include <gtest/gtest.h>

#include <cmath>

#include "fremond/potentials/deadzone_power.hpp"
#include "fremond/potentials/power.hpp"
#include "fremond/solvers/solve_impact.hpp"
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

}  // namespace
}  // namespace fremond
