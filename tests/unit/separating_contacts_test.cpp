// Every contact of an impact problem takes part (docs/concepts.md): a touching contact that
// separates before the impact (D_NA > 0) carries the non-penetration reaction, so the others'
// percussions cannot drive it into its obstacle. The cases are the flat bar (m = 1, l = 0.5,
// J = 1/12) touching with both ends, solved by hand: W_N = (0, 1, ∓l), so G = [[4, −2], [−2, 4]].
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "classical_support.hpp"
#include "fremond/fremond.hpp"
#include "support/disk_pile.hpp"

namespace fremond {
namespace {

using test::flat_bar;

// v_y = −1, ω = −4: the left end leaves at D_NA = +1, the right end arrives at −3.
const Eigen::Vector3d kSpinning(0.0, -1.0, -4.0);

double mean(double a, double b) {
  return 0.5 * (a + b);
}

TEST(SeparatingContacts, NewtonStopsTheLeavingEndOfTheFlatBar) {
  const ImpactProblem pb = flat_bar(kSpinning, false);
  const ImpactResult r = solve_impact(pb, ImpactLaw::newton(0.9));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  // Both contacts closed: D_NE = (0, 0.9·3) = D_NA + G P, so G P = (−1, 5.7) and
  // P = G⁻¹(−1, 5.7) = (37/60, 26/15).
  EXPECT_NEAR(r.P_N(0), 37.0 / 60.0, 1e-14);
  EXPECT_NEAR(r.P_N(1), 26.0 / 15.0, 1e-14);
  EXPECT_NEAR(r.D_NE(0), 0.0, 1e-14);
  EXPECT_NEAR(r.D_NE(1), 2.7, 1e-14);
  EXPECT_EQ(r.takes_part(0), 0);  // separating: the reaction alone
  EXPECT_LE(law_residual(pb, ImpactLaw::newton(0.9), r), 1e-14);
  // T_E − T_A = P·z = (37/60)(1/2) + (26/15)(−0.15) = 29/600: Newton's law creates energy here,
  // and the certificate says so (the law's finding, not the solver's failure).
  EXPECT_NEAR(r.energy_change, 29.0 / 600.0, 1e-14);
  EXPECT_FALSE(r.admissibility.admissible);
  EXPECT_EQ(r.admissibility.failed, Inequality::total_15);
}

TEST(SeparatingContacts, PoissonStopsTheLeavingEndInBothPhases) {
  const ImpactProblem pb = flat_bar(kSpinning, false);
  const ImpactResult r = solve_impact(pb, ImpactLaw::poisson(0.9));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  ASSERT_TRUE(r.has_phases);
  // Compression stops both ends: G P_C = −D_A = (−1, 3), P_C = (1/6, 5/6), both ≥ 0.
  EXPECT_NEAR(r.P_NC(0), 1.0 / 6.0, 1e-14);
  EXPECT_NEAR(r.P_NC(1), 5.0 / 6.0, 1e-14);
  // Expansion: e P_C moves the ends by 0.9·(−D_A) = (−0.9, 2.7); the left end's ΔP = 0.9/4 stops
  // it, and the right end leaves at 2.7 − 2·0.225 = 2.25.
  EXPECT_NEAR(r.P_N(0), 1.9 / 6.0 + 0.225, 1e-14);
  EXPECT_NEAR(r.P_N(1), 1.9 * 5.0 / 6.0, 1e-14);
  EXPECT_NEAR(r.D_NE(0), 0.0, 1e-14);
  EXPECT_NEAR(r.D_NE(1), 2.25, 1e-14);
  EXPECT_LE(law_residual(pb, ImpactLaw::poisson(0.9), r), 1e-14);
  EXPECT_TRUE(r.admissibility.admissible);
}

TEST(SeparatingContacts, FremondAppliesNoPotentialToTheLeavingEnd) {
  // φ_N = 4 z²/2 on both contacts. The right end: −P_R = 4 z_R (it leaves, no reaction); the left
  // end: the reaction alone with D_NE = 0. Then 0 = 1 + 4 P_L − 2 P_R, D_R = −3 − 2 P_L + 4 P_R and
  // P_R = 2 (3 − D_R): P = (15/28, 11/7), D_NE = (0, 31/14).
  const ImpactProblem pb = flat_bar(kSpinning, false);
  const ImpactLaw law = ImpactLaw::fremond(PowerPotential(4.0, 2.0));
  const ImpactResult r = solve_impact(pb, law);
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_NEAR(r.P_N(0), 15.0 / 28.0, 1e-13);
  EXPECT_NEAR(r.P_N(1), 11.0 / 7.0, 1e-13);
  EXPECT_NEAR(r.D_NE(0), 0.0, 1e-13);
  EXPECT_NEAR(r.D_NE(1), 31.0 / 14.0, 1e-13);
  EXPECT_NEAR(r.P_N_reaction(0), r.P_N(0), 1e-13);  // all of it is the reaction
  EXPECT_LE(law_residual(pb, law, r), 1e-13);
  // (17) read with the law's velocity before the impact, min(D_NA, 0) = 0: −P_L D_NE/2 = 0;
  // (19) on the right end: −P_R z_R = (11/7)(3 − 31/14)/2 = 121/196.
  EXPECT_NEAR(r.admissibility.reaction, 0.0, 1e-13);
  EXPECT_NEAR(r.admissibility.dissipation, 121.0 / 196.0, 1e-13);
  // (15) with the true mean velocities: −(P_L/2 + P_R z_R).
  const double total = -(r.P_N(0) * mean(1.0, r.D_NE(0)) + r.P_N(1) * mean(-3.0, r.D_NE(1)));
  EXPECT_NEAR(r.admissibility.total, total, 1e-13);
  EXPECT_NEAR(total, 121.0 / 196.0 - 15.0 / 56.0, 1e-13);
  EXPECT_TRUE(r.admissibility.admissible);
}

TEST(SeparatingContacts, FremondWithCoulombAndViscousKeepTheLeavingEndOut) {
  const ImpactProblem pb = flat_bar(kSpinning, true);
  for (const ImpactLaw& law :
       {ImpactLaw::fremond_coulomb(PowerPotential(4.0, 2.0), 0.5),
        ImpactLaw::fremond(PowerPotential(4.0, 2.0), DeadZonePowerPotential(1.5, 2.0, 0.2))}) {
    const ImpactResult r = solve_impact(pb, law);
    ASSERT_TRUE(r.ok()) << law.describe() << ": " << r.solver.message;
    EXPECT_GE(r.D_NE(0), -1e-14) << law.describe();
    EXPECT_GE(r.D_NE(1), -1e-14) << law.describe();
    EXPECT_GT(r.P_N(0), 0.1) << law.describe();  // the left end is stopped, not left to sink
    EXPECT_LE(law_residual(pb, law, r), 1e-12) << law.describe();
  }
}

TEST(SeparatingContacts, NewtonWithCoulombStopsTheLeavingEnd) {
  const ImpactProblem pb = flat_bar(kSpinning, true);
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.9, 0.3);
  const ImpactResult r = solve_impact(pb, law);
  ASSERT_TRUE(r.ok()) << r.solver.message;
  // ẋ = 0 and W_T = (1, 0, 0) on both ends: no tangential motion, so P_T = 0 and the answer is
  // the frictionless one.
  EXPECT_NEAR(r.P_N(0), 37.0 / 60.0, 1e-14);
  EXPECT_NEAR(r.P_N(1), 26.0 / 15.0, 1e-14);
  EXPECT_NEAR(r.P_T(0) + r.P_T(1), 0.0, 1e-14);
  EXPECT_LE(law_residual(pb, law, r), 1e-14);
  for (const ImpactResult& s : solve_impact_all(pb, law)) {
    EXPECT_GE(s.D_NE(0), -1e-14);
    EXPECT_GE(s.D_NE(1), -1e-14);
    EXPECT_LE(law_residual(pb, law, s), 1e-12);
  }
}

TEST(SeparatingContacts, ALeavingContactsFrictionSolvesWhatTheArrivingOneCannot) {
  // One dof (m = 1, q̇_A = 0) against two moving obstacles. Contact 2 arrives (W_N = −1, w_N =
  // −0.5: D_NA = −0.5; W_T = 1, w_T = 0, μ = 2, e = 0) and alone has no solution: closing it needs
  // q̇_E = −0.5, where it slides back (D_TE = −0.5) and the friction P_T = 2 P_N drives q̇ up,
  // (μ − 1) P_N > 0; sticking (q̇_E = 0) and staying open both leave D_NE = −0.5. Contact 1 leaves
  // (W_N = 1, w_N = 1: D_NA = 1; W_T = 1, w_T = 2, μ = 3). Held too, it closes: q̇_E = −1, where it
  // slides forward (D_TE = 1) with P_T = −3 P_N, so P_N (1 − 3) = −1 gives P_N = 1/2, P_T = −3/2;
  // contact 2 then leaves at D_NE = 0.5 ≥ 0 with no percussion. That is the law's one solution.
  ImpactProblem pb;
  pb.M = Eigen::MatrixXd::Identity(1, 1);
  pb.W_N = Eigen::MatrixXd{{1.0, -1.0}};
  pb.W_T = Eigen::MatrixXd{{1.0, 1.0}};
  pb.w_N = Eigen::Vector2d(1.0, -0.5);
  pb.w_T = Eigen::Vector2d(2.0, 0.0);
  pb.qdot_A = Eigen::VectorXd::Zero(1);
  const ImpactLaw law = ImpactLaw::newton_coulomb({0.0, 0.0}, {3.0, 2.0});
  const ImpactResult r = solve_impact(pb, law);
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_NEAR(r.qdot_E(0), -1.0, 1e-14);
  EXPECT_NEAR(r.P_N(0), 0.5, 1e-14);
  EXPECT_NEAR(r.P_T(0), -1.5, 1e-14);
  EXPECT_NEAR(r.P_N(1), 0.0, 1e-14);
  EXPECT_NEAR(r.P_T(1), 0.0, 1e-14);
  EXPECT_NEAR(r.D_NE(0), 0.0, 1e-14);
  EXPECT_NEAR(r.D_NE(1), 0.5, 1e-14);
  EXPECT_EQ(r.takes_part(0), 0);
  EXPECT_LE(law_residual(pb, law, r), 1e-14);
  const std::vector<ImpactResult> all = solve_impact_all(pb, law);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_NEAR(all.front().P_N(0), 0.5, 1e-14);
  EXPECT_NEAR(all.front().P_T(0), -1.5, 1e-14);
}

TEST(SeparatingContacts, AnUndrivenLeavingEndChangesNothing) {
  // ω = 9: the left end arrives at −5, the right end leaves at +4. Newton e = 0.5 on the left end
  // alone gives P = 1.5·5/4 and leaves the right end at 4 − 2·1.875 = 0.25 > 0: the same bits as
  // the problem without the right end.
  const ImpactProblem pb = flat_bar(Eigen::Vector3d(0.0, -0.5, 9.0), false);
  ImpactProblem left = pb;
  left.W_N = pb.W_N.leftCols(1);
  for (const ImpactLaw& law : {ImpactLaw::newton(0.5), ImpactLaw::poisson(0.5),
                               ImpactLaw::fremond(PowerPotential(1.0, 3.0))}) {
    const ImpactResult r = solve_impact(pb, law);
    const ImpactResult one = solve_impact(left, law);
    ASSERT_TRUE(r.ok() && one.ok()) << law.describe();
    EXPECT_EQ(r.P_N(1), 0.0) << law.describe();
    EXPECT_GT(r.D_NE(1), 0.0) << law.describe();
    EXPECT_EQ(r.P_N(0), one.P_N(0)) << law.describe();
    EXPECT_EQ(r.qdot_E, one.qdot_E) << law.describe();
  }
  const ImpactResult newton = solve_impact(pb, ImpactLaw::newton(0.5));
  EXPECT_NEAR(newton.P_N(0), 1.875, 1e-14);
  EXPECT_NEAR(newton.D_NE(1), 0.25, 1e-14);
}

TEST(SeparatingContacts, EveryCertificateHoldsTheSameContacts) {
  // One dof between two contacts on opposite sides, the second leaving at 4.6e3: held, it stops
  // the body (q̇_E = 0 to rounding) with reactions of 1e12 that are not unique. The certificate of
  // solve_impact_all's answer, and the user's check_admissibility, must allow the rounding of the
  // rows solve_impact held, the separating one included (found by the solver fuzz target).
  ImpactProblem pb;
  pb.M = MatrixX::Constant(1, 1, 0.14486888932637201);
  pb.W_N.resize(1, 2);
  pb.W_N << -0.46078215337441919, 0.59876868651998061;
  pb.W_T.resize(1, 2);
  pb.W_T << -0.76494098002144584, -0.76494098002144584;
  pb.qdot_A = VectorX::Constant(1, 7636.352270757593);
  const ImpactLaw law =
      ImpactLaw::fremond(PowerPotential(0.068688124335027217, 5.2249649865217105));
  const ImpactResult r = solve_impact(pb, law);
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_LE(std::fabs(r.qdot_E(0)), 1e-6 * pb.qdot_A(0));
  EXPECT_GT(r.P_N(1), 0.0);
  EXPECT_TRUE(r.admissibility.admissible) << to_string(r.admissibility.failed);
  const auto again = check_admissibility(pb, law, r);
  EXPECT_EQ(again.admissible, r.admissibility.admissible);
  EXPECT_EQ(again.complementarity, r.admissibility.complementarity);
  for (const ImpactResult& s : solve_impact_all(pb, law))
    EXPECT_TRUE(s.admissibility.admissible) << to_string(s.admissibility.failed);
}

// Piles of disks handed over dense: groups of contacts approach, and their answer drives touching
// contacts that separate, so the pile is solved on every contact (docs/solvers.md). The sparse
// solve of the same pile, on every contact at once and by its own path, is the second method: the
// velocities agree, each contact meets the law by law_residual, and separating contacts are
// stopped (P_N > 0), not driven through.
TEST(SeparatingContacts, DensePilesAgreeWithTheirSparseSolve) {
  for (const int side : {3, 6}) {
    const SparseImpactProblem sparse = fixtures::disk_pile(side);
    for (const ImpactLaw& law : {ImpactLaw::newton_coulomb(0.0, 0.5), ImpactLaw::newton(0.3),
                                 ImpactLaw::newton_coulomb(0.5, 0.2)}) {
      SparseImpactProblem sp = sparse;
      if (!law.has_friction()) sp.W_T.resize(sp.dofs(), 0);
      ImpactProblem pb;
      pb.M = Eigen::MatrixXd(sp.M);
      pb.W_N = Eigen::MatrixXd(sp.W_N);
      pb.W_T = Eigen::MatrixXd(sp.W_T);
      pb.qdot_A = sp.qdot_A;
      const ImpactResult dense = solve_impact(pb, law);
      const ImpactResult other = solve_impact(sp, law, {.tolerance = 1e-11});
      SCOPED_TRACE(std::to_string(side) + " " + std::string(law.name()));
      ASSERT_TRUE(dense.ok()) << dense.solver.message;
      ASSERT_TRUE(other.ok()) << other.solver.message;
      EXPECT_LE(law_residual(pb, law, dense), 1e-12);
      EXPECT_LE((dense.qdot_E - other.qdot_E).norm(), 1e-9 * dense.qdot_E.norm());
      int stopped = 0;
      for (int i = 0; i < pb.contacts(); ++i) {
        EXPECT_GE(dense.D_NE(i), -1e-12) << i;
        stopped += dense.D_NA(i) > 0.0 && dense.P_N(i) > 0.0;
      }
      EXPECT_GE(stopped, 5);
    }
  }
}

// A leaving contact whose W_N is so large that its Delassus entry overflows (|W|²/|M| = 1e320):
// M = I, W_N = [(0, 1), (1e160, −10)], q̇_A = (3e−160, −2), so D_NA = (−2, 23). With φ_N = 0
// (the reaction alone) the arriving contact's answer is P = 2, q̇_E = (3e−160, 0), and the
// leaving one stays at D_NE = 3. A given P = 3 instead drives it to 23 − 30 = −7: its row's
// residual is 7/2 against 1/2 of the arriving row's, scaled by the largest |D_A|, 23. The same
// problem with the leaving column 1e150 (its entries finite) is the second method.
TEST(SeparatingContacts, ALeavingContactWhoseDelassusEntryOverflowsIsJudgedByItsVelocity) {
  ImpactProblem pb;
  pb.M = Eigen::Matrix2d::Identity();
  pb.W_N.resize(2, 2);
  pb.W_N << 0.0, 1e160, 1.0, -10.0;
  pb.qdot_A = Eigen::Vector2d(3e-160, -2.0);
  ImpactProblem twin = pb;
  twin.W_N(0, 1) = 1e150;
  twin.qdot_A(0) = 3e-150;
  const ImpactLaw law = ImpactLaw::fremond(PowerPotential(0.0, 2.0));

  const ImpactResult r = solve_impact(pb, law);
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_EQ(r.P_N(0), 2.0);
  EXPECT_EQ(r.P_N(1), 0.0);
  EXPECT_EQ(r.D_NE(1), 3.0);
  EXPECT_EQ(law_residual(pb, law, r), 0.0);

  ImpactResult driven = r;
  driven.P_N(0) = 3.0;
  const double expected = 3.5 / 23.0;
  EXPECT_DOUBLE_EQ(law_residual(pb, law, driven), expected);
  EXPECT_DOUBLE_EQ(law_residual(twin, law, driven), expected);

  ImpactResult loaded = r;  // a percussion on the leaving contact moves q̇ beyond double precision
  loaded.P_N(1) = 1.0;
  EXPECT_EQ(law_residual(pb, law, loaded), std::numeric_limits<double>::infinity());
  // Its certificate is still given, without the rounding allowance G would give: the leaving
  // contact's work −P z = −(23 + 3)/2 is energy created, and (15) fails on it.
  const auto rep = check_admissibility(pb, law, loaded);
  EXPECT_FALSE(rep.admissible);
  EXPECT_EQ(rep.per_contact(1), -13.0);
}

}  // namespace
}  // namespace fremond
