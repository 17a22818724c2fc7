// Moreau–Jean against the event-driven integrator: first-order convergence on the first impact of
// the paper's bar, exact free steps, rest.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fremond/scenes/presets.hpp"
#include "fremond/simulation/calibration.hpp"
#include "fremond/simulation/simulate.hpp"

namespace fremond {
namespace {

struct FirstImpactLog : SimulationObserver {
  bool seen = false;
  ImpactRecord first;
  void on_impact(const ImpactRecord& r) override {
    if (!seen) first = r;
    seen = true;
  }
};

TEST(MoreauJean, FirstImpactConvergesAtFirstOrderToTheEventDrivenOne) {
  for (PaperLaw law : {PaperLaw::newton, PaperLaw::fremond_coulomb}) {
    const Scene scene = paper_bar_scene(law);
    SimulationOptions ed;
    ed.t_end = 0.5;  // the first impact only (the second comes at ~0.47 s with Newton, later else)
    ed.max_impacts = 1;
    FirstImpactLog ref;
    simulate(scene, ed, &ref);
    ASSERT_TRUE(ref.seen);
    const double t_star = ref.first.t, e_star = ref.first.energy_E;

    // Steps chosen so that the impact falls in the middle of a step, h = t*/(N + ½): the time
    // error of a first-order scheme is then a smooth C h, not the sawtooth of a fixed grid.
    std::vector<double> hs, dt, de;
    for (int N : {20, 40, 80, 160, 320, 640}) {
      SimulationOptions mj = ed;
      mj.integrator = Integrator::moreau_jean;
      mj.step = t_star / (N + 0.5);
      FirstImpactLog log;
      const SimulationResult r = simulate(scene, mj, &log);
      ASSERT_TRUE(r.ok()) << r.message;
      ASSERT_TRUE(log.seen);
      ASSERT_EQ(log.first.kind, ImpactKind::time_step);
      hs.push_back(mj.step);
      dt.push_back(std::fabs(log.first.t - t_star));
      de.push_back(std::fabs(log.first.energy_E - e_star));
    }
    for (std::size_t i = 0; i < hs.size(); ++i) {
      // The impact is found in the step that holds it, at its start: exactly half a step early.
      EXPECT_NEAR(dt[i], hs[i] / 2, 1e-12) << to_string(law);
      EXPECT_GT(de[i], 0.0);
    }
    // Energy after the impact: error / h tends to a constant (first order), and halving the step
    // halves the error.
    for (std::size_t i = 1; i < hs.size(); ++i) {
      const double order = std::log(de[i - 1] / de[i]) / std::log(hs[i - 1] / hs[i]);
      EXPECT_NEAR(order, 1.0, 0.1) << to_string(law) << " h=" << hs[i];
    }
    EXPECT_LT(de.back(), 1e-2 * e_star);
  }
}

TEST(MoreauJean, FreeStepsAreExactBallisticSteps) {
  // No contact for 0.3 s: Moreau–Jean's midpoint steps reproduce the closed-form flight and its
  // energy to rounding.
  const Scene scene = paper_bar_scene(PaperLaw::newton);
  SimulationOptions mj;
  mj.integrator = Integrator::moreau_jean;
  mj.t_end = 0.3;
  const SimulationResult r = simulate(scene, mj);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.impacts, 0);
  const double t = 0.3;
  EXPECT_NEAR(r.state.q.x(), 2 * t, 1e-13);
  EXPECT_NEAR(r.state.q.y(), 1 - 0.5 * 9.81 * t * t, 1e-13);
  EXPECT_NEAR(r.state.qdot.y(), -9.81 * t, 1e-13);
  EXPECT_NEAR(r.energy_final, r.energy_initial, 1e-13);
}

TEST(MoreauJean, ABallComesToRestAndStays) {
  BallParameters ball;
  SimulationOptions mj;
  mj.integrator = Integrator::moreau_jean;
  mj.t_end = 15.0;
  const SimulationResult r = simulate(ball_scene(ball, ImpactLaw::newton(0.8)), mj);
  ASSERT_TRUE(r.ok());
  EXPECT_GT(r.impacts, 5);
  EXPECT_LE(r.state.qdot.norm(), 1e-12);
  EXPECT_NEAR(r.state.q.y(), ball.radius, 1e-4);  // within a step's worth of gravity
  EXPECT_LE(r.max_energy_rise, 1e-12);
}

}  // namespace
}  // namespace fremond
