// Frémond's law (docs/laws.md and docs/concepts.md, paper §5) against closed forms, between
// methods, and on random data.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "fremond/fremond.hpp"
#include "support/test_problems.hpp"

namespace fremond {
namespace {

using testing::bar;
using testing::paper_bar_first_impact;
using testing::point_mass;
using testing::random_problem;

SolverOptions with_method(SolverMethod m) {
  SolverOptions o;
  o.method = m;
  return o;
}

// docs/laws.md, eq. (24) in our scaling: p = 2 on a point mass is Newton's law with
// ε = (k − 2m)/(k + 2m) for k ≥ 2m; for k < 2m the reaction stops the mass (D_NE = 0).
TEST(FremondPointMass, P2IsNewtonWithEq24Restitution) {
  for (double m : {1e-3, 0.5, 1.0, 7.0, 1e3}) {
    for (double ratio : {0.1, 0.5, 1.0, 2.5, 4.0, 100.0}) {
      const double k = ratio * 2.0 * m;
      const double v = -3.0;
      const auto r = solve_impact(point_mass(m, v), ImpactLaw::fremond(PowerPotential(k, 2.0)));
      ASSERT_TRUE(r.ok()) << r.solver.message;
      const double eps = (k - 2 * m) / (k + 2 * m);
      // A negative ε would mean D_NE < 0: the reaction stops the contact instead (D_NE = 0).
      const double expected = -std::max(eps, 0.0) * v;
      EXPECT_NEAR(r.D_NE(0), expected, 1e-14 * std::fabs(v)) << "m=" << m << " k=" << k;
      EXPECT_EQ(r.solver.method, SolverMethod::closed_form);
      EXPECT_TRUE(r.admissibility.admissible);
      EXPECT_NEAR(r.energy_change, 0.5 * m * (expected * expected - v * v), 1e-13 * m * v * v);
    }
  }
}

// docs/laws.md (erratum of the paper): when the reaction acts, D_NE = 0 and
// I_reac = (m − k_paper |D_NA|^{p−2}) D_NA ≤ 0 with k_paper = k 2^{1−p}.
TEST(FremondPointMass, ReactionMatchesCorrectedFormula) {
  for (double p : {1.5, 2.0, 3.0, 5.0}) {
    const double m = 2.0, v = -1.5;
    // A weak law (k_paper|D_NA|^{p−2} < m) cannot stop the mass by itself: the reaction does.
    const double k_paper = 0.1 * m / std::pow(std::fabs(v), p - 2.0);
    const double k = k_paper * std::pow(2.0, p - 1.0);
    const auto r = solve_impact(point_mass(m, v), ImpactLaw::fremond(PowerPotential(k, p)));
    ASSERT_TRUE(r.ok());
    EXPECT_NEAR(r.D_NE(0), 0.0, 1e-15);
    const double I_reac = (m - k_paper * std::pow(std::fabs(v), p - 2.0)) * v;
    ASSERT_LT(I_reac, 0.0);
    EXPECT_NEAR(-r.P_N_reaction(0), I_reac, 1e-12 * std::fabs(I_reac)) << "p=" << p;
    EXPECT_LE(-r.P_N_reaction(0), 0.0);  // eq. 16: I_reac ≤ 0
    EXPECT_TRUE(r.admissibility.admissible);
    EXPECT_NEAR(r.P_N(0), -m * v, 1e-13 * m * std::fabs(v));  // stopped dead
  }
}

// A point mass obeys 2m(|D_NA| − t) = k t^{p−1} with t = −z the mean velocity's size (eq. 23 in
// the library's convention), unless t > |D_NA|/2 where the reaction stops it (D_NE = 0). The
// reference solves that scalar equation by bisection in long double, independently of the library's
// prox.
long double point_mass_reference(long double m, long double k, long double p, long double v) {
  const long double D = -v;
  long double lo = 0.0L, hi = D;
  for (int i = 0; i < 20000 && hi - lo > 0.0L; ++i) {
    const long double mid = 0.5L * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    if (2.0L * m * (D - mid) - k * std::pow(mid, p - 1.0L) > 0.0L)
      lo = mid;
    else
      hi = mid;
  }
  const long double t = 0.5L * (lo + hi);
  return t >= 0.5L * D ? 0.0L : D - 2.0L * t;
}

TEST(FremondPointMass, NormalLawAgainstLongDoubleForEveryExponent) {
  for (double p : {1.01, 1.1, 1.5, 2.0, 3.0, 10.0, 50.0}) {
    for (double k : {1e-6, 1e-2, 1.0, 1e2, 1e6}) {
      for (double v : {-1e-10, -1e-3, -1.0, -1e3, -1e6}) {
        for (double m : {1e-3, 1.0, 1e3}) {
          const auto pb = point_mass(m, v);
          const auto law = ImpactLaw::fremond(PowerPotential(k, p));
          const auto r = solve_impact(pb, law);
          ASSERT_TRUE(r.ok()) << "p=" << p << " k=" << k << " v=" << v << ": " << r.solver.message;
          const double expected = static_cast<double>(point_mass_reference(m, k, p, v));
          EXPECT_NEAR(r.D_NE(0), expected, 4e-15 * std::fabs(v))
              << "p=" << p << " k=" << k << " v=" << v << " m=" << m;
          EXPECT_TRUE(r.admissibility.admissible);
          EXPECT_LE(law_residual(pb, law, r), 1e-13);
        }
      }
    }
  }
}

// The paper's bar at its first impact with each Frémond law: every method gives the same answer.
TEST(FremondBar, EveryMethodAgrees) {
  const ImpactProblem pb = paper_bar_first_impact();
  const std::vector<ImpactLaw> laws{
      ImpactLaw::fremond(PowerPotential(85.36, 3.0)),
      ImpactLaw::fremond(PowerPotential(85.36, 3.0), DeadZonePowerPotential(1.5, 2.0, 0.2)),
      ImpactLaw::fremond(PowerPotential(85.36, 3.0), DeadZonePowerPotential(1.5, 2.0, 0.0)),
      ImpactLaw::fremond(PowerPotential(20.0, 1.5), DeadZonePowerPotential(4.0, 1.3, 0.1)),
      ImpactLaw::fremond_coulomb(PowerPotential(85.36, 3.0), 1.0),
      ImpactLaw::fremond_coulomb(PowerPotential(85.36, 3.0), 0.05),
  };
  for (const auto& law : laws) {
    const auto ref = solve_impact(pb, law);
    ASSERT_TRUE(ref.ok()) << law.describe();
    EXPECT_TRUE(ref.admissibility.admissible) << law.describe();
    EXPECT_LE(ref.admissibility.fenchel_young_gap, 1e-12) << law.describe();
    for (auto m : {SolverMethod::semismooth_newton, SolverMethod::proximal, SolverMethod::nlopt}) {
      const auto r = solve_impact(pb, law, with_method(m));
      ASSERT_TRUE(r.ok()) << law.describe() << " " << to_string(m) << ": " << r.solver.message;
      EXPECT_EQ(r.solver.method, m);
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(r.qdot_E(i), ref.qdot_E(i), 1e-10 * ref.qdot_E.norm())
            << law.describe() << " " << to_string(m);
      EXPECT_NEAR(r.P_N(0), ref.P_N(0), 1e-10 * std::fabs(ref.P_N(0)));
      EXPECT_NEAR(r.P_T(0), ref.P_T(0), 1e-10 * std::fabs(ref.P_N(0)));
    }
  }
}

// One contact with Coulomb: the mode enumeration's answer satisfies the law written by hand.
TEST(FremondBar, CoulombOnTheMeanVelocityByHand) {
  const ImpactProblem pb = paper_bar_first_impact();
  const double mu = 1.0, k = 85.36;
  const auto r = solve_impact(pb, ImpactLaw::fremond_coulomb(PowerPotential(k, 3.0), mu));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.solver.method, SolverMethod::mode_enumeration);
  EXPECT_TRUE(r.unique);
  const double zN = 0.5 * (r.D_NA(0) + r.D_NE(0)), zT = 0.5 * (r.D_TA(0) + r.D_TE(0));
  // Normal law without reaction (D_NE > 0 here): −P_N = k zN|zN|.
  EXPECT_GT(r.D_NE(0), 0.0);
  EXPECT_NEAR(-r.P_N(0), k * zN * std::fabs(zN), 1e-12 * r.P_N(0));
  // Coulomb on the mean velocity: stick (z_T = 0, D_TE = −D_TA) inside the cone, or slide on it.
  if (std::fabs(r.P_T(0)) < mu * r.P_N(0) * (1 - 1e-12)) {
    EXPECT_NEAR(zT, 0.0, 1e-13);
    EXPECT_NEAR(r.D_TE(0), -r.D_TA(0), 1e-12);
  } else {
    EXPECT_NEAR(r.P_T(0), -mu * r.P_N(0) * (zT > 0 ? 1 : -1), 1e-12 * r.P_N(0));
  }
  // Momentum balance M(q̇_E − q̇_A) = W_N P_N + W_T P_T.
  const VectorX lhs = pb.M * (r.qdot_E - pb.qdot_A);
  const VectorX rhs = pb.W_N * r.P_N + pb.W_T * r.P_T;
  EXPECT_LE((lhs - rhs).cwiseAbs().maxCoeff(), 1e-13);
}

// The flat bar (θ = 0) hits with both ends at once: G is singular with tangential rows (both
// W_T columns are (1, 0, 0)); the symmetric answer has no rotation.
TEST(FremondBar, FlatBarTwoContactsSingularG) {
  const ImpactProblem pb = bar(0.0, Eigen::Vector3d(1.0, -3.0, 0.0), true);
  const std::vector<ImpactLaw> laws{
      ImpactLaw::fremond(PowerPotential(10.0, 3.0)),
      ImpactLaw::fremond(PowerPotential(10.0, 3.0), DeadZonePowerPotential(1.5, 2.0, 0.2)),
      ImpactLaw::fremond_coulomb(PowerPotential(10.0, 3.0), 0.3),
      ImpactLaw::fremond_coulomb(PowerPotential(10.0, 3.0), 5.0),
  };
  for (const auto& law : laws) {
    for (auto m :
         {SolverMethod::automatic, SolverMethod::semismooth_newton, SolverMethod::proximal}) {
      const auto r = solve_impact(pb, law, with_method(m));
      ASSERT_TRUE(r.ok()) << law.describe() << " " << to_string(m) << ": " << r.solver.message;
      EXPECT_NEAR(r.qdot_E(2), 0.0, 1e-12) << law.describe();
      EXPECT_TRUE(r.admissibility.admissible) << law.describe();
      // Both ends see the same normal velocity; the normal percussions are equal.
      EXPECT_NEAR(r.P_N(0), r.P_N(1), 1e-10 * std::fabs(r.P_N(0)));
      // The centre obeys the point-mass law with mass m/2 per end: z = mean of ẏ.
      const double zN = 0.5 * (pb.qdot_A(1) + r.qdot_E(1));
      EXPECT_NEAR(r.P_N(0) + r.P_N_reaction(0) * 0.0,
                  -10.0 * zN * std::fabs(zN) + r.P_N_reaction(0), 1e-10);
    }
  }
}

// docs/laws.md: "Frémond + Coulomb ... already with one contact when μ|G_NT| > G_NN" may have
// several solutions or none; the result says which. The bar at θ = π/4 has G_NN = 2.5, |G_NT|
// = 1.5: μ = 2 is beyond. Every reported solution satisfies the law (residual ~ 0) and is
// admissible.
TEST(FremondBar, PainleveCaseReportsEverySolution) {
  int cases_with_several = 0, cases_without = 0;
  for (double mu : {1.0, 1.7, 2.0, 4.0, 20.0}) {
    for (double vx : {-5.0, -2.0, 0.5, 2.0, 5.0}) {
      const ImpactProblem pb = bar(std::numbers::pi / 4, Eigen::Vector3d(vx, -1.0, 0.3));
      const auto law = ImpactLaw::fremond_coulomb(PowerPotential(5.0, 3.0), mu);
      const auto all = solve_impact_all(pb, law);
      const auto one = solve_impact(pb, law);
      if (all.empty()) {
        ++cases_without;
        EXPECT_EQ(one.solver.status, SolverStatus::no_solution);
        continue;
      }
      if (all.size() > 1) ++cases_with_several;
      EXPECT_EQ(one.unique, all.size() == 1);
      for (const auto& r : all) {
        EXPECT_EQ(r.solutions_found, static_cast<int>(all.size()));
        EXPECT_LE(law_residual(pb, law, r), 1e-12) << "mu=" << mu << " vx=" << vx;
        EXPECT_TRUE(r.admissibility.admissible);
      }
      if (mu * 1.5 < 2.5) {
        EXPECT_EQ(all.size(), 1u) << "below the Painlevé bound: unique";
      }
    }
  }
  EXPECT_GT(cases_with_several + cases_without, 0) << "the sweep must reach the Painlevé regime";
}

// A body between two obstacles that close in on it: q = (x, y), contact 0 is a wall moving right
// (normal −x, D_N = −ẋ + w₀), contact 1 one moving left (normal +x, D_N = ẋ + w₁), w = (−1, −1).
// Both take part (D_NA = (−1.5, −0.5)), and D_NE ≥ 0 asks ẋ_E ≤ −1 and ẋ_E ≥ 1: by Farkas, y = (1,
// 1) gives W_N y = 0 and y·w_N = −2 < 0, so no velocity after the impact keeps both from
// penetrating, and Frémond's reaction (docs/laws.md) admits no answer, whatever the potentials.
// Every method used to end "stalled" or "failed" after its budget; the law now says no_solution and
// returns the state before the impact. Where the walls move together (w = (1, −1), ẋ_A = 1: both
// touching, D_NA = 0) the single feasible velocity ẋ_E = 1 is the answer, with no percussion.
TEST(FremondLaw, ObstaclesClosingInLeaveNoSolution) {
  ImpactProblem pb;
  pb.M = Eigen::Vector2d(2.0, 2.0).asDiagonal();
  pb.W_N.resize(2, 2);
  pb.W_N << -1.0, 1.0, 0.0, 0.0;
  pb.W_T.resize(2, 2);
  pb.W_T << 0.0, 0.0, 1.0, 1.0;
  pb.w_N = Eigen::Vector2d(-1.0, -1.0);
  pb.qdot_A = Eigen::Vector2d(0.5, 0.3);
  const std::vector<ImpactLaw> laws{
      ImpactLaw::fremond(PowerPotential(10.0, 3.0)),
      ImpactLaw::fremond(PowerPotential(10.0, 2.0), DeadZonePowerPotential(1.5, 2.0, 0.2)),
      ImpactLaw::fremond_coulomb(PowerPotential(10.0, 3.0), 0.5),
  };
  for (const auto& law : laws) {
    for (auto m : {SolverMethod::automatic, SolverMethod::semismooth_newton, SolverMethod::proximal,
                   SolverMethod::nlopt}) {
      SCOPED_TRACE(law.describe() + " " + std::string(to_string(m)));
      const auto r = solve_impact(pb, law, with_method(m));
      EXPECT_EQ(r.solver.status, SolverStatus::no_solution) << r.solver.message;
      EXPECT_NE(r.solver.message.find("obstacles close in"), std::string::npos);
      EXPECT_EQ(r.qdot_E, pb.qdot_A);
      EXPECT_EQ(r.P_N, Eigen::Vector2d::Zero());
      EXPECT_EQ(r.P_T, Eigen::Vector2d::Zero());
      EXPECT_FALSE(r.unique);
      EXPECT_TRUE(solve_impact_all(pb, law).empty());
    }
    // The walls moving together: feasible at one velocity, reached with no percussion.
    ImpactProblem together = pb;
    together.w_N = Eigen::Vector2d(1.0, -1.0);
    together.qdot_A = Eigen::Vector2d(1.0, 0.0);
    const auto r = solve_impact(together, law);
    ASSERT_TRUE(r.ok()) << law.describe() << ": " << r.solver.message;
    EXPECT_NEAR(r.qdot_E(0), 1.0, 1e-15);
    EXPECT_NEAR(r.qdot_E(1), 0.0, 1e-15);
  }
}

// Thousands of random problems (n ≤ 6, up to 3 contacts): every result converges and satisfies
// (15) per contact and in sum, (17), (19), the complementarity (16) and Fenchel–Young.
TEST(FremondRandom, AdmissibleAndConvergedOnThousandsOfProblems) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int solved = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = 1 + static_cast<int>(u(rng) * 6);
    const int c = 1 + static_cast<int>(u(rng) * 3);
    const int kind = trial % 3;  // 0 normal only, 1 viscous, 2 Coulomb (small μ)
    // Separating contacts detached: driven ones are the stress runs' and
    // separating_contacts_test's.
    const ImpactProblem pb = testing::detach_separating(random_problem(rng, n, c, kind != 0));
    const double p = 1.1 + 4.0 * u(rng), k = std::pow(10.0, 4 * u(rng) - 2);
    ImpactLaw law = ImpactLaw::fremond(PowerPotential(k, p));
    if (kind == 1)
      law = ImpactLaw::fremond(
          PowerPotential(k, p),
          DeadZonePowerPotential(std::pow(10.0, 2 * u(rng) - 1), 1.1 + 2 * u(rng), 0.5 * u(rng)));
    if (kind == 2) law = ImpactLaw::fremond_coulomb(PowerPotential(k, p), 0.3 * u(rng));
    const auto r = solve_impact(pb, law);
    if (kind == 2 && !r.ok()) continue;  // Coulomb may have no solution with several contacts
    ASSERT_TRUE(r.ok()) << "trial " << trial << ": " << r.solver.message;
    ++solved;
    const auto& a = r.admissibility;
    EXPECT_TRUE(a.admissible) << "trial " << trial << " failed " << to_string(a.failed) << " by "
                              << a.violation;
    EXPECT_GE(a.total, -a.tolerance);
    EXPECT_GE(a.reaction, -a.tolerance);
    EXPECT_GE(a.dissipation, -a.tolerance);
    for (int i = 0; i < c; ++i) EXPECT_GE(a.per_contact(i), -a.tolerance);
    EXPECT_LE(a.fenchel_young_gap, 1e-12) << "trial " << trial;
    EXPECT_NEAR(a.total, -r.energy_change, 1e-9 * (1 + a.kinetic_energy_A));  // eq. (9)
    // M's condition up to 1e3 and percussions up to 1e3 times the velocities leave rounding of
    // ~1e-12 in z = D_A + GP/2.
    EXPECT_LE(law_residual(pb, law, r), 1e-11) << "trial " << trial;
  }
  EXPECT_GT(solved, 2900);
}

// Every method agrees with every other on random problems without Coulomb (a convex problem with
// a unique velocity answer). The automatic chain always converges; each forced method either
// converges to the same velocities or says it did not (Newton can stall at a kink of its residual
// when more contacts than degrees of freedom stop at once; it must then say so).
TEST(FremondRandom, MethodsAgreeOnRandomProblems) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int converged[3] = {0, 0, 0};
  const int trials = 200;
  for (int trial = 0; trial < trials; ++trial) {
    const int n = 2 + static_cast<int>(u(rng) * 5);
    const int c = 1 + static_cast<int>(u(rng) * 3);
    const ImpactProblem pb = random_problem(rng, n, c, trial % 2 == 1);
    const double p = 2.0 + 2.0 * u(rng);
    ImpactLaw law = ImpactLaw::fremond(PowerPotential(1.0 + 5 * u(rng), p));
    if (trial % 2)
      law = ImpactLaw::fremond(PowerPotential(1.0 + 5 * u(rng), p),
                               DeadZonePowerPotential(1.0 + u(rng), 2.0 + u(rng), 0.2 * u(rng)));
    const auto ref = solve_impact(pb, law);
    ASSERT_TRUE(ref.ok()) << trial;
    int i = 0;
    for (auto m : {SolverMethod::semismooth_newton, SolverMethod::proximal, SolverMethod::nlopt}) {
      const auto r = solve_impact(pb, law, with_method(m));
      if (!r.ok()) {
        EXPECT_NE(r.solver.status, SolverStatus::not_run);
        EXPECT_GT(law_residual(pb, law, r), 1e-13) << "a failure must not be a solution";
        ++i;
        continue;
      }
      ++converged[i++];
      const double scale = ref.qdot_E.cwiseAbs().maxCoeff() + pb.qdot_A.cwiseAbs().maxCoeff();
      EXPECT_LE((r.qdot_E - ref.qdot_E).cwiseAbs().maxCoeff(), 1e-10 * scale)
          << "trial " << trial << " " << to_string(m);
    }
  }
  EXPECT_GE(converged[0], trials * 9 / 10) << "semismooth Newton";
  EXPECT_EQ(converged[1], trials) << "proximal splitting";
  EXPECT_GE(converged[2], trials * 9 / 10) << "NLopt";
}

}  // namespace
}  // namespace fremond
