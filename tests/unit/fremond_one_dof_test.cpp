// Frémond's law without Coulomb on one degree of freedom, where every contact-space method fails
// and the scalar velocity-space solve (src/solvers/fremond_one_dof.cpp) answers. The references
// are 60-digit minimisers of docs/laws.md's F(u) = M u² + Σ φ_j(D_A,j + W_j u) over the reactions'
// domain, found by golden-section search on F's values (mpmath; no subdifferential, no prox: a
// different method from the library's bisection on ∂F). The four problems are stress cases of
// fremond_viscous at seed 7 (#233, #729, #1834, #3973); before this solve each returned a velocity
// off by its own size or more (#233: +3146 against −3159.47, with D_NE = −1091).
#include <gtest/gtest.h>

#include <cmath>

#include "fremond/fremond.hpp"
#include "stress/invariants.hpp"

namespace fremond {
namespace {

ImpactProblem one_dof(double m, double qA, std::vector<double> WN, std::vector<double> WT,
                      std::vector<double> wN, std::vector<double> wT) {
  const int c = static_cast<int>(WN.size());
  ImpactProblem p;
  p.M = Eigen::MatrixXd::Constant(1, 1, m);
  p.qdot_A = Eigen::VectorXd::Constant(1, qA);
  p.W_N = Eigen::Map<Eigen::MatrixXd>(WN.data(), 1, c);
  p.W_T = Eigen::Map<Eigen::MatrixXd>(WT.data(), 1, c);
  p.w_N = Eigen::Map<Eigen::VectorXd>(wN.data(), c);
  p.w_T = Eigen::Map<Eigen::VectorXd>(wT.data(), c);
  return p;
}

/// The momentum balance M(q̇_E − q̇_A) = Σ W P to the rounding of its terms.
void expect_momentum(const ImpactProblem& p, const ImpactResult& r) {
  double sum = 0.0, terms = 0.0;
  for (int i = 0; i < p.contacts(); ++i) {
    sum += p.W_N(0, i) * r.P_N(i) + p.W_T(0, i) * r.P_T(i);
    terms += std::fabs(p.W_N(0, i) * r.P_N(i)) + std::fabs(p.W_T(0, i) * r.P_T(i));
  }
  const double dq = p.M(0, 0) * (r.qdot_E(0) - p.qdot_A(0));
  EXPECT_NEAR(sum, dq, 64 * 2.2e-16 * (terms + std::fabs(dq)));
}

// One contact on a moving obstacle whose reaction holds it (D_NE = 0), the tangential dead zone
// far outside its width: percussions 2e14 against velocities of 3e3. The velocity is exact; the
// percussions cannot reproduce it within the law's test (z = D_A + GP/2 is rounded to 1e-2 of
// ε|G||P|, beyond 1e-6 of the velocity scale), so the answer stays `stalled` with that reason.
TEST(FremondOneDof, ReactionOnAMovingObstacleGivesTheExactVelocity) {
  const ImpactProblem p =
      one_dof(0.0083108455477935977, 1492.9356988123577, {-0.17304369682320031},
              {-0.66192693213081211}, {-546.72614222040636}, {2062.9663802813607});
  const auto law = ImpactLaw::fremond(
      PowerPotential(0.0, 3.6578106644183883),
      DeadZonePowerPotential(125502.72517807371, 3.533474581799517, 98.156804329069601));
  const ImpactResult r = solve_impact(p, law);
  EXPECT_NEAR(r.qdot_E(0), -3159.4686906105539532, 4e-16 * 3159.47);
  EXPECT_EQ(r.solver.method, SolverMethod::scalar_newton);
  EXPECT_EQ(r.solver.status, SolverStatus::stalled);
  EXPECT_EQ(r.solver.criterion, StopCriterion::rounding);
  EXPECT_NEAR(r.D_NE(0), 0.0, 1e-12 * 3159.47);  // held by the reaction
  EXPECT_GT(r.P_N(0), 0.0);
  EXPECT_NEAR(r.P_N_reaction(0), r.P_N(0), 1e-12 * r.P_N(0));  // k_N = 0: all of it reaction
  expect_momentum(p, r);
  EXPECT_TRUE(r.admissibility.admissible);
}

// Four rows on one dof, a tangential sum of a dead zone and b|y| whose kink holds the answer:
// z = 0 on every row, so q̇_E = −q̇_A exactly (an elastic reversal), P_N = 0 (φ_N'(0) = 0, no
// reaction) and P_T is a continuum (two set-valued rows on one dof), split by least norm.
TEST(FremondOneDof, KinkOfFourRowsGivesTheReversalAndZeroNormalPercussion) {
  const ImpactProblem p = one_dof(0.0032826607520469028, -2347687.1111628814,
                                  {0.41064105137448137, 0.34244059803105387},
                                  {-0.9103301285256904, -0.97161174110243753}, {0, 0}, {0, 0});
  const SumPotential tangential(DeadZonePowerPotential(0.0007486105933, 2.312161814, 14737.39961),
                                AbsoluteValuePotential(7954940.457));
  const auto law =
      ImpactLaw::fremond(PowerPotential(61934.652714663047, 4.8783391892390595), tangential);
  const ImpactResult r = solve_impact(p, law);
  ASSERT_EQ(r.solver.status, SolverStatus::converged) << r.solver.message;
  EXPECT_EQ(r.qdot_E(0), 2347687.1111628814);
  EXPECT_EQ(r.P_N(0), 0.0);
  EXPECT_EQ(r.P_N(1), 0.0);
  EXPECT_FALSE(std::signbit(r.P_N(0)));  // no −0 in the answer
  EXPECT_FALSE(r.unique);
  // Least norm: P_T ∝ W_T, inside Coulomb-like bounds b.
  EXPECT_NEAR(r.P_T(0) / r.P_T(1), p.W_T(0, 0) / p.W_T(0, 1), 1e-14);
  EXPECT_LE(std::fabs(r.P_T(0)), 7954940.457);
  expect_momentum(p, r);
  EXPECT_EQ(robust::check_result(p, law, SolverOptions{}, r), "");
}

// Three contacts at speeds of 1e-11, one normal law almost linear (p = 1 + 5e-5): the reactions'
// domain ends at u = 8.6e-11, which is the answer. (The stress case had a fourth contact, leaving
// at D_NA = 1.9e-11 on the other side, W_N = −0.85, w_N = 2.8e-12: held with the others, its
// obstacle and contact 0's close in on the body, D_NE ≥ 0 asks u ≥ 2.6e-11 and u ≤ 3.3e-12, so the
// law has no solution, which the last lines check.)
TEST(FremondOneDof, ThreeContactsAtTinySpeedsConverge) {
  const ImpactProblem p =
      one_dof(0.51041527414561838, -1.914934250583979e-11,
              {0.45840554258339017, 0.10672335289785218, 0.97320450453861307},
              {0.84188928136191388, 0.36649857114925188, 0.80829604723212167},
              {-1.1916471948263793e-11, -1.634328558252934e-11, -4.3353772922717655e-12},
              {1.2305860613472173e-11, 1.6179426196886907e-11, -2.1036214611362736e-11});
  PerContactPotential normal(PowerPotential(0.0, 18.077445441136941));
  normal.potentials.emplace_back(std::make_unique<PowerPotential>(0.00052043059924276229, 2.0));
  normal.potentials.emplace_back(
      std::make_unique<PowerPotential>(0.011497907361241498, 1.0000480157205487));
  PerContactPotential tangential(
      DeadZonePowerPotential(5.3499614384723214e-06, 2.0, 3.7175741114025769e-14));
  tangential.potentials.emplace_back(
      std::make_unique<DeadZonePowerPotential>(507.36552946566093, 2.0, 1.0712382117676927e-14));
  tangential.potentials.emplace_back(std::make_unique<DeadZonePowerPotential>(
      0.00034790106502862736, 2.0, 1.9976271882685692e-15));
  const ImpactLaw law = ImpactLaw::fremond(normal, tangential);
  const ImpactResult r = solve_impact(p, law);
  ASSERT_EQ(r.solver.status, SolverStatus::converged) << r.solver.message;
  EXPECT_NEAR(r.qdot_E(0), 1.5313692025935451217e-10, 1e-15 * 1.53e-10);
  expect_momentum(p, r);
  EXPECT_EQ(robust::check_result(p, law, SolverOptions{}, r), "");

  ImpactProblem with_leaving = p;
  with_leaving.W_N.conservativeResize(1, 4);
  with_leaving.W_T.conservativeResize(1, 4);
  with_leaving.w_N.conservativeResize(4);
  with_leaving.w_T.conservativeResize(4);
  with_leaving.W_N(0, 3) = -0.85070917453656736;
  with_leaving.W_T(0, 3) = 0.27532236336114968;
  with_leaving.w_N(3) = 2.8105205588814761e-12;
  with_leaving.w_T(3) = -2.2595265879366724e-12;
  normal.potentials.emplace_back(
      std::make_unique<PowerPotential>(3.7962022075654855e-05, 3.6297385002223397));
  tangential.potentials.emplace_back(
      std::make_unique<DeadZonePowerPotential>(3.2368446325042814, 3.4832954107645238, 0.0));
  const ImpactResult none =
      solve_impact(with_leaving, ImpactLaw::fremond(std::move(normal), std::move(tangential)));
  EXPECT_GT(none.D_NA(3), 0.0);
  EXPECT_EQ(none.solver.status, SolverStatus::no_solution) << none.solver.message;
}

// Two contacts, steep laws (p = 38, q = 39): the first contact's reaction ends the domain.
TEST(FremondOneDof, SteepLawsOnTwoContactsGiveTheExactVelocity) {
  const ImpactProblem p = one_dof(
      0.070089441505248165, 5478.5040995038134, {-0.79088969621211214, -0.20326053900592445},
      {0.81053371440051269, 0.24769928724242618}, {6550.4762781600866, -6087.8118942532465},
      {5996.0804178891458, -2758.4327784630773});
  PerContactPotential normal(PowerPotential(6243.3785249685243, 38.39989823581373));
  normal.potentials.emplace_back(
      std::make_unique<PowerPotential>(32.850012512153683, 2.5993258760198161));
  PerContactPotential tangential(
      DeadZonePowerPotential(69298.57425510489, 39.313862485983108, 49.054739474158829));
  tangential.potentials.emplace_back(std::make_unique<DeadZonePowerPotential>(
      0.27315819488233084, 14.6333936765099, 0.61376538314450813));
  const ImpactLaw law = ImpactLaw::fremond(std::move(normal), std::move(tangential));
  const ImpactResult r = solve_impact(p, law);
  EXPECT_NEAR(r.qdot_E(0), -29950.781022359705028, 4e-16 * 29950.8);
  EXPECT_EQ(r.solver.method, SolverMethod::scalar_newton);
  EXPECT_GE(r.D_NE.minCoeff(), -1e-12 * 29950.8);
}

}  // namespace
}  // namespace fremond
