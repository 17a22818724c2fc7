// Poisson's law with Coulomb friction creates energy on two coupled contacts where no single
// contact can (Glocker 2013, "Energetic consistency conditions for standard impacts, Part II",
// shows the kind; the atlas shows one contact never gains): the ladder preset, its lower end on
// frictional ground (e = 0, mu = 2), its upper end against a frictionless elastic wall (e = 1).
// The answer is checked to be the law's by the law's own residual from the data, the momentum
// balance and solve_impact_all's enumeration of every contact mode; the energy from its velocities.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fremond/fremond.hpp"

namespace fremond {
namespace {

constexpr int kGroundContact = 0, kWallContact = 3;  // presets.hpp: points × [ground, wall]

SmallImpactProblem ladder_impact(const Eigen::Vector3d& velocity, int contacts = 2) {
  LadderParameters p;
  p.velocity = velocity;
  const Scene scene = ladder_scene(p, ImpactLaw::poisson(0.5));
  const int both[2] = {kGroundContact, kWallContact};
  return impact_problem(scene, scene.initial, both, contacts);
}

double kinetic(const SmallImpactProblem& pb, const Eigen::VectorXd& v) {
  return 0.5 * v.dot(Eigen::MatrixXd(pb.M) * v);
}

TEST(LadderEnergy, PoissonCoulombOnTwoContactsCreatesEnergy) {
  const SmallImpactProblem pb = ladder_impact({1.0, -1.0, 0.0});
  // Both ends approach at unit speed: D_NA = (−1, −1).
  EXPECT_NEAR(pb.W_N.col(0).dot(pb.qdot_A), -1.0, 1e-15);
  EXPECT_NEAR(pb.W_N.col(1).dot(pb.qdot_A), -1.0, 1e-15);
  const ImpactLaw law = ImpactLaw::poisson_coulomb({0.0, 1.0}, {2.0, 0.0});
  const SmallImpactResult r = solve_impact(pb, law);
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_LE(law_residual(pb, law, r), 1e-13);
  const Eigen::VectorXd balance = Eigen::MatrixXd(pb.M) * (r.qdot_E - pb.qdot_A) -
                                  Eigen::MatrixXd(pb.W_N) * r.P_N - Eigen::MatrixXd(pb.W_T) * r.P_T;
  EXPECT_LE(balance.lpNorm<Eigen::Infinity>(), 1e-14);
  const double T_A = kinetic(pb, pb.qdot_A), T_E = kinetic(pb, r.qdot_E);
  EXPECT_GT(T_E - T_A, 0.5 * T_A);  // 70 % of the kinetic energy before is created
  EXPECT_FALSE(r.admissibility.admissible);
  EXPECT_EQ(r.admissibility.failed, Inequality::total_15);
  // Every contact mode enumerated: this is the law's only answer, so no choice avoids the gain.
  const auto all = solve_impact_all(to_dynamic(pb), law);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_NEAR(all[0].energy_change, T_E - T_A, 1e-12 * T_A);
}

// Each contact alone, on the same body at the same velocities, never gains energy: the one
// frictional contact (the ground) over a fan of velocities, under the same law.
TEST(LadderEnergy, EachContactAloneDissipates) {
  int approaching = 0;
  for (int k = 0; k < 64; ++k) {
    const double a = -std::numbers::pi * (k + 0.5) / 64;
    for (const double spin : {-2.0, 0.0, 2.0}) {
      for (int c = 0; c < 2; ++c) {
        LadderParameters p;
        p.velocity = {std::cos(a), std::sin(a), spin};
        const Scene scene = ladder_scene(p, ImpactLaw::poisson(0.5));
        const int one[1] = {c == 0 ? kGroundContact : kWallContact};
        const SmallImpactProblem pb = impact_problem(scene, scene.initial, one, 1);
        if (!(pb.W_N.col(0).dot(pb.qdot_A) < 0)) continue;
        ++approaching;
        const ImpactLaw law = ImpactLaw::poisson_coulomb(c == 0 ? 0.0 : 1.0, c == 0 ? 2.0 : 0.0);
        const SmallImpactResult r = solve_impact(pb, law);
        ASSERT_TRUE(r.ok());
        const double T_A = kinetic(pb, pb.qdot_A);
        EXPECT_LE(kinetic(pb, r.qdot_E) - T_A, 1e-13 * T_A) << "contact " << c << " angle " << a;
      }
    }
  }
  EXPECT_GT(approaching, 150);
}

TEST(LadderEnergy, PresetRefusesAnAngleOutsideTheQuarterTurn) {
  LadderParameters p;
  p.angle = 1.6;
  EXPECT_THROW(ladder_scene(p, ImpactLaw::newton(0.5)), InvalidArgument);
}

}  // namespace
}  // namespace fremond
