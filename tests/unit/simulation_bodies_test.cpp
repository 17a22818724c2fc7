// The event-driven run of scenes of several bodies (simulate_bodies.hpp): Newton's cradle and a
// ball dropped on a resting ball against their flights and impacts worked out by hand, the
// accumulation of the dropped ball's bounces closed, and what the run refuses or stops on.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fremond/fremond.hpp"
#include "fremond/simulation/simulate_bodies.hpp"

namespace fremond {
namespace {

struct BodiesLog : MultiBodyObserver {
  std::vector<MultiBodyImpact> impacts;
  std::vector<MultiBodySample> samples;
  void on_impact(const MultiBodyImpact& i) override { impacts.push_back(i); }
  void on_sample(const MultiBodySample& s) override { samples.push_back(s); }
};

SimulationOptions until(double t_end) {
  SimulationOptions o;
  o.t_end = t_end;
  o.sample_interval = 0.01;
  return o;
}

// Three balls (g = 0), Newton e = 1: one impact at t = 0 leaving (−1/3, 2/3, 2/3)
// (ball_chain_test.cpp); balls 1 and 2 then move together, touching, and nothing else happens:
// at t = 1, x = (−1/3, 0.2 + 2/3, 0.4 + 2/3).
TEST(SimulateBodies, NewtonsCradleFliesApartAfterOneImpact) {
  const MultiBodyScene s = cradle_scene(CradleParameters{}, ImpactLaw::newton(1.0));
  BodiesLog log;
  const MultiBodyResult r = simulate(s, until(1.0), &log);
  ASSERT_EQ(r.status, SimulationStatus::completed) << r.message;
  ASSERT_EQ(r.impacts, 1);
  ASSERT_EQ(log.impacts.size(), 1u);
  EXPECT_EQ(log.impacts[0].t, 0.0);
  EXPECT_EQ(log.impacts[0].contacts, (std::vector<int>{0, 2}));
  EXPECT_NEAR(r.state.q(0), -1.0 / 3, 1e-15);
  EXPECT_NEAR(r.state.q(3), 0.2 + 2.0 / 3, 1e-15);
  EXPECT_NEAR(r.state.q(6), 0.4 + 2.0 / 3, 1e-15);
  EXPECT_NEAR(r.energy_final, 0.5, 1e-15);
  EXPECT_LE(r.max_energy_rise, 1e-15);
  // Samples on the grid, t = 0 twice (before and after the impact) and the end.
  EXPECT_EQ(log.samples.front().t, 0.0);
  EXPECT_EQ(log.samples.back().t, 1.0);
}

// Five balls under Stronge's distributing law (e* = 1, Hertz): one impact; momentum 1 and energy
// ½ kept; every pair separates (x increasing with the ball's index after the impact).
TEST(SimulateBodies, NewtonsCradleOfFiveUnderStronge) {
  StrongeLaw hertz;
  hertz.e = 1.0;
  hertz.eta = 1.5;
  CradleParameters p;
  p.balls = 5;
  const MultiBodyResult r = simulate(cradle_scene(p, hertz), until(1.0));
  ASSERT_EQ(r.status, SimulationStatus::completed) << r.message;
  EXPECT_EQ(r.impacts, 1);
  double momentum_x = 0.0;
  for (int i = 0; i < 5; ++i) momentum_x += r.state.qdot(3 * i);
  EXPECT_NEAR(momentum_x, 1.0, 1e-12);
  EXPECT_NEAR(r.energy_final, 0.5, 1e-9);
  EXPECT_GT(r.state.qdot(12), 0.9);
}

// Ball 1 falls from a gap h = 0.5 on ball 0 resting on the ground: contact at t₁ = √(2h/g) at
// v = √(2gh). Newton e = 1 (ball_chain_test.cpp): ball 0 stays, ball 1 leaves at v and is back
// 2v/g later: impacts at t₁ and 3t₁ within t_end = 1; ball 0 never moves.
TEST(SimulateBodies, BallDroppedOnARestingBallBouncesBackElastically) {
  const double g = 9.81, h = 0.5, t1 = std::sqrt(2 * h / g), v = std::sqrt(2 * g * h);
  const MultiBodyScene s = ball_on_ball_scene(BallOnBallParameters{}, ImpactLaw::newton(1.0));
  BodiesLog log;
  const MultiBodyResult r = simulate(s, until(1.0), &log);
  ASSERT_EQ(r.status, SimulationStatus::completed) << r.message;
  ASSERT_EQ(r.impacts, 2);
  EXPECT_NEAR(log.impacts[0].t, t1, 1e-12);
  EXPECT_NEAR(log.impacts[1].t, 3 * t1, 1e-12);
  EXPECT_EQ(log.impacts[0].contacts, (std::vector<int>{0, 2}));  // ball 0 on the ground, the pair
  EXPECT_NEAR(log.impacts[0].qdot_A(4), -v, 1e-12);
  EXPECT_NEAR(log.impacts[0].qdot_E(4), v, 1e-12);
  EXPECT_NEAR(log.impacts[0].qdot_E(1), 0.0, 1e-12);
  for (const MultiBodySample& smp : log.samples) EXPECT_EQ(smp.state.q(1), 0.1);
  EXPECT_NEAR(r.energy_final, r.energy_initial, 1e-12);
}

// e = 0.8: bounces at speeds v eᵏ, 2 v eᵏ/g apart, accumulating at t∞ = t₁ + 2ve/(g(1 − e)),
// closed by a plastic impact; then ball 1 rests on ball 0: y₁ = 3ρ, energy m g (ρ + 3ρ).
TEST(SimulateBodies, BallDroppedOnARestingBallComesToRest) {
  const double g = 9.81, h = 0.5, v = std::sqrt(2 * g * h);
  const double t_inf = std::sqrt(2 * h / g) + 2 * v * 0.8 / (g * 0.2);
  const MultiBodyScene s = ball_on_ball_scene(BallOnBallParameters{}, ImpactLaw::newton(0.8));
  BodiesLog log;
  const MultiBodyResult r = simulate(s, until(t_inf + 1.0), &log);
  ASSERT_EQ(r.status, SimulationStatus::completed) << r.message;
  EXPECT_EQ(r.accumulations, 1);
  EXPECT_LT(log.impacts.back().t, t_inf);
  EXPECT_GT(log.impacts.back().t, t_inf - 0.05);
  EXPECT_NEAR(r.state.q(4), 0.3, 1e-9);
  EXPECT_NEAR(r.state.q(1), 0.1, 1e-12);
  EXPECT_NEAR(r.energy_final, g * 0.4, 1e-6);
  EXPECT_LE(r.max_energy_rise, 1e-12);
}

// Every law: the run ends, nothing sinks, and no energy is created (the laws on these
// impacts are 1-D and frictionless in effect, so Newton's and Poisson's with e ≤ 1 dissipate too).
TEST(SimulateBodies, BallDroppedOnARestingBallUnderEveryLaw) {
  StrongeLaw hertz;
  hertz.e = 0.9;
  hertz.eta = 1.5;
  for (const ImpactLaw& law : {ImpactLaw::newton(0.9), ImpactLaw::newton_coulomb(0.9, 0.5),
                               ImpactLaw::poisson(0.9), ImpactLaw::poisson_coulomb(0.9, 0.5),
                               ImpactLaw::fremond(PowerPotential(40.0, 3.0)), ImpactLaw(hertz)}) {
    const MultiBodyScene s = ball_on_ball_scene(BallOnBallParameters{}, law);
    SimulationOptions o = until(2.0);
    o.max_impacts = 500;
    const MultiBodyResult r = simulate(s, o);
    ASSERT_TRUE(r.ok()) << law.describe() << ": " << r.message;
    EXPECT_GE(r.impacts, 1) << law.describe();
    EXPECT_LE(r.energy_final, r.energy_initial + 1e-9) << law.describe();
    EXPECT_LE(r.max_energy_rise, 1e-9) << law.describe();
    for (const int k : {0, 1, 2})
      EXPECT_GE(contact_frame(s, s.contacts()[k], r.state.q).gap, -1e-9) << law.describe();
  }
}

TEST(SimulateBodies, RefusesWhatItCannotRun) {
  const auto refusal = [](const MultiBodyScene& s, const SimulationOptions& o) {
    try {
      simulate(s, o);
    } catch (const InvalidArgument& e) {
      return e.name();
    }
    return std::string("accepted");
  };
  MultiBodyScene s = cradle_scene(CradleParameters{}, ImpactLaw::newton(1.0));
  EXPECT_EQ(refusal(s, until(1.0)), "accepted");
  SimulationOptions mj = until(1.0);
  mj.integrator = Integrator::moreau_jean;
  EXPECT_EQ(refusal(s, mj), "integrator.method");
  MultiBodyScene off = s;
  off.bodies[1].points[0].r = Eigen::Vector2d(0.01, 0.0);
  off.initial.q(3) -= 0.01;
  EXPECT_EQ(refusal(off, until(1.0)), "bodies[1].points[0].r");
  MultiBodyScene deep = s;
  deep.initial.q(3) = 0.1;  // ball 1 half inside ball 0
  EXPECT_EQ(refusal(deep, until(1.0)), "initial");
}

// A ball rolling on the ground while another flies: a moving body in lasting contact, which the
// run does not simulate; it stops saying so.
TEST(SimulateBodies, StopsOnAMovingBodyInLastingContact) {
  BallOnBallParameters p;
  MultiBodyScene s = ball_on_ball_scene(p, ImpactLaw::newton(0.5));
  s.initial.qdot(0) = 1.0;
  const MultiBodyResult r = simulate(s, until(1.0));
  EXPECT_EQ(r.status, SimulationStatus::contact_failed);
  EXPECT_EQ(r.t, 0.0);
}

}  // namespace
}  // namespace fremond
