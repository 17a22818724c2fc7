// A ball bouncing under Newton's law: every bounce and the accumulation of impacts against the
// closed forms, then rest.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fremond/scenes/presets.hpp"
#include "fremond/simulation/simulate.hpp"
#include "support/simulation_log.hpp"

namespace fremond {
namespace {

using Log = testing::SimulationLog;

// Dropped from rest with its lowest point at h0 under gravity g, restitution e (Newton): the n-th
// impact (n ≥ 1) leaves with speed e^n v1, v1 = √(2 g h0), and the n-th bounce rises to
// e^(2n) h0. The impacts come at t1 = √(2h0/g) and t_{n+1} = t_n + 2 e^n v1/g, which accumulate at
// t∞ = t1 + 2 v1 e / (g (1 − e)).
struct Closed {
  double g, h0, e;
  double v1() const { return std::sqrt(2 * g * h0); }
  double t1() const { return std::sqrt(2 * h0 / g); }
  double t_inf() const { return t1() + 2 * v1() * e / (g * (1 - e)); }
};

TEST(SimulationBall, BounceHeightsAndAccumulationTimeMatchTheClosedForms) {
  for (double e : {0.5, 0.9}) {
    BallParameters ball;  // m = 1, radius 0.1, lowest point 1 m above the ground, at rest
    const Scene scene = ball_scene(ball, ImpactLaw::newton(e));
    const Closed cf{ball.gravity, ball.initial.q.y() - ball.radius, e};
    SimulationOptions opt;
    opt.t_end = cf.t_inf() + 2.0;
    Log log;
    const SimulationResult r = simulate(scene, opt, &log);
    ASSERT_EQ(r.status, SimulationStatus::completed) << r.message;

    int n = 0;
    double t_expected = cf.t1();
    for (const ImpactRecord& imp : log.impacts) {
      if (imp.kind != ImpactKind::event) continue;
      ++n;
      EXPECT_NEAR(imp.t, t_expected, 1e-9) << "impact " << n;
      // Speed after the n-th impact, and the height of the n-th bounce from it.
      const double up = imp.qdot_E.y();
      EXPECT_NEAR(up, std::pow(e, n) * cf.v1(), 1e-9) << n;
      EXPECT_NEAR(up * up / (2 * cf.g), std::pow(e, 2 * n) * cf.h0, 1e-9) << n;
      EXPECT_NEAR(imp.q.y(), ball.radius, 1e-12);
      t_expected += 2 * up / cf.g;
    }
    EXPECT_GE(n, 10);
    // The accumulation: one, at the closed-form time.
    EXPECT_EQ(r.accumulations, 1);
    EXPECT_NEAR(r.first_accumulation_time, cf.t_inf(), 1e-9) << e;
    // Then at rest on the ground, with the energy m g ρ, and it stays there.
    EXPECT_NEAR(r.state.q.y(), ball.radius, 1e-12);
    EXPECT_LE(r.state.qdot.norm(), 1e-12);
    EXPECT_NEAR(r.energy_final, ball.mass * ball.gravity * ball.radius, 1e-12);
    for (const TrajectorySample& s : log.samples)
      if (s.t > cf.t_inf() + 1e-9) {
        EXPECT_NEAR(s.state.q.y(), ball.radius, 1e-12) << s.t;
        EXPECT_LE(s.state.qdot.norm(), 1e-12) << s.t;
      }
    // Flights conserve the energy and impacts of an admissible law lose it: no rise anywhere.
    EXPECT_EQ(r.inadmissible_impacts, 0);
    EXPECT_LE(r.max_energy_rise, 1e-13);
    // Each impact loses (1 − e²) of the kinetic energy at impact (eq. 9).
    for (const ImpactRecord& imp : log.impacts)
      if (imp.kind == ImpactKind::event) {
        const double ka = 0.5 * imp.qdot_A.squaredNorm(), ke = 0.5 * imp.qdot_E.squaredNorm();
        EXPECT_NEAR(ke, e * e * ka, 1e-12 * (1 + ka));
        EXPECT_NEAR(imp.energy_E - imp.energy_A, ke - ka, 1e-12 * (1 + ka));
      }
  }
}

// The same drop under gravities that leave 1e-50 to 1e-154 s between impacts and 0.5 s to run:
// the first impact at its closed-form time, and the bounces accumulate into rest as at 9.81 m/s².
// At g = 1.5e308 the speed at the ground (1.6e154 m/s) has a kinetic energy beyond a double: the
// run says so in its status, at the impact, and throws nothing.
TEST(SimulationBall, ExtremeGravitiesAreResolvedOrStopWithAStatus) {
  for (const double g : {1e100, 1e200, 1e300}) {
    BallParameters ball;
    ball.gravity = g;
    const Scene scene = ball_scene(ball, ImpactLaw::newton(0.5));
    const Closed cf{g, ball.initial.q.y() - ball.radius, 0.5};
    SimulationOptions opt;
    opt.t_end = 0.5;
    Log log;
    const SimulationResult r = simulate(scene, opt, &log);
    ASSERT_EQ(r.status, SimulationStatus::completed) << g << ": " << r.message;
    ASSERT_FALSE(log.impacts.empty());
    EXPECT_NEAR(log.impacts[0].t, cf.t1(), 1e-15 * cf.t1()) << g;
    EXPECT_EQ(r.accumulations, 1) << g;
    EXPECT_NEAR(r.state.q.y(), ball.radius, 1e-12) << g;
    EXPECT_NEAR(r.energy_final, ball.mass * g * ball.radius, 1e-12 * ball.mass * g) << g;
  }
  BallParameters ball;
  ball.gravity = 1.5e308;
  SimulationOptions opt;
  opt.t_end = 0.5;
  const SimulationResult r = simulate(ball_scene(ball, ImpactLaw::newton(0.5)), opt);
  EXPECT_EQ(r.status, SimulationStatus::impact_failed);
  EXPECT_NE(r.message.find("double precision"), std::string::npos) << r.message;
  const Closed cf{ball.gravity, ball.initial.q.y() - ball.radius, 0.5};
  EXPECT_NEAR(r.t, cf.t1(), 1e-15 * cf.t1());
}

TEST(SimulationBall, ASlidingBallWithFrictionStopsSlidingOrKeepsItsSpeedAsTheLawSays) {
  // Thrown sideways at 1 m/s: frictionless it keeps ẋ = 1 through every impact and the
  // accumulation and slides on; with Coulomb friction it ends at rest or rolling, never faster.
  BallParameters ball;
  ball.initial.qdot = {1.0, 0.0, 0.0};
  SimulationOptions opt;
  opt.t_end = 12.0;
  const SimulationResult frictionless = simulate(ball_scene(ball, ImpactLaw::newton(0.8)), opt);
  ASSERT_TRUE(frictionless.ok());
  EXPECT_NEAR(frictionless.state.qdot.x(), 1.0, 1e-12);
  EXPECT_NEAR(frictionless.state.q.x(), 12.0, 1e-9);
  EXPECT_NEAR(frictionless.state.qdot.y(), 0.0, 1e-12);
  const SimulationResult coulomb =
      simulate(ball_scene(ball, ImpactLaw::newton_coulomb(0.8, 0.3)), opt);
  ASSERT_TRUE(coulomb.ok()) << coulomb.message;
  EXPECT_LT(coulomb.state.qdot.x(), 1.0);
  EXPECT_NEAR(coulomb.state.qdot.y(), 0.0, 1e-9);
  // At the end the contact point does not slip: ẋ + ρ θ̇ = 0 (rolling), or the ball is at rest.
  EXPECT_NEAR(coulomb.state.qdot.x() + ball.radius * coulomb.state.qdot.z(), 0.0, 1e-9);
  EXPECT_LE(coulomb.max_energy_rise, 1e-12);
}

}  // namespace
}  // namespace fremond
