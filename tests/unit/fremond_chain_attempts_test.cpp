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

// Four contacts, three dofs, cond(M) = 1e10, speeds 1e-9 and p from 1.003 to 31 (a case where
// every method fails or nearly): the log holds Newton, the splitting and NLopt in the chain's
// order, the answer's method is the last converged attempt or the nearest failure, and no attempt
// is recorded twice by mistake (the count stays within the table's length).
TEST(FremondChainAttempts, AHardCaseLogsTheStagesInOrder) {
  ImpactProblem pb;
  pb.M.resize(3, 3);
  pb.M << 7951828.996842298, -16449933.183492143, 9020740.580749638, -16449933.183492143,
      34029946.10497301, -18661189.926689938, 9020740.580749638, -18661189.926689938,
      10233340.4170277;
  pb.W_N.resize(3, 4);
  pb.W_N << 0.9253293531650559, -0.5210114094630116, -0.8952477121556833, 0.9253293531650559,
      0.7692881614889511, 0.9739469124269164, 0.6066104889029429, 0.7692881614889511,
      0.9365482111065937, 0.1497906745901345, -0.7662332784780111, 0.9365482111065937;
  pb.W_T.resize(3, 4);
  pb.W_T << 0.2652742867339486, 0.6506144198035824, -0.028944442760205358, -0.015426005738093607,
      0.7485155773358516, 0.7430756335658784, -0.46716201977964655, 0.1842153471431538,
      -0.7941066387828781, -0.2129325428485339, -0.6341555452713468, -0.5201974050901444;
  pb.qdot_A =
      Eigen::Vector3d(3.643957871526755e-09, -3.3323752925316983e-09, -3.5348621602472427e-09);
  const double k[4] = {6.359817502633181, 66113.18883090747, 3005.291157828727, 3579.2234395360924};
  const double p[4] = {5.914055754085484, 31.137382733915185, 1.003390763568152, 2.403721887609679};
  PerContactPotential normal;
  for (int i = 0; i < 4; ++i)
    normal.potentials.emplace_back(std::make_unique<PowerPotential>(k[i], p[i]));
  const ImpactLaw law = ImpactLaw::fremond(
      std::move(normal),
      DeadZonePowerPotential(106.18344232384078, 4.973125386008597, 3.0569394144157536e-09));
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
