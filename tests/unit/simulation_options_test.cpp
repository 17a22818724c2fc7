// Options of a run, the names of the simulation's enumerations, and what the observer receives.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fremond/core/error.hpp"
#include "fremond/scenes/presets.hpp"
#include "fremond/simulation/persistent_contact.hpp"
#include "fremond/simulation/simulate.hpp"

namespace fremond {
namespace {

TEST(SimulationOptions, EveryEnumRoundTripsThroughItsName) {
  for (auto v : {Integrator::event_driven, Integrator::moreau_jean})
    EXPECT_EQ(integrator_from_string(to_string(v)), v);
  for (auto v : {Phase::event_driven, Phase::moreau_jean})
    EXPECT_EQ(phase_from_string(to_string(v)), v);
  for (auto v : {SimulationStatus::not_run, SimulationStatus::completed,
                 SimulationStatus::max_impacts, SimulationStatus::impact_failed,
                 SimulationStatus::contact_failed, SimulationStatus::event_search_failed})
    EXPECT_EQ(simulation_status_from_string(to_string(v)), v);
  for (auto v : {ImpactKind::event, ImpactKind::time_step, ImpactKind::accumulation})
    EXPECT_EQ(impact_kind_from_string(to_string(v)), v);
  for (auto v :
       {ContactMode::open, ContactMode::stick, ContactMode::slide_forward, ContactMode::slide_back})
    EXPECT_EQ(contact_mode_from_string(to_string(v)), v);
  for (auto v : {StepVelocity::end, StepVelocity::mean})
    EXPECT_EQ(step_velocity_from_string(to_string(v)), v);
  for (auto v : {PaperLaw::newton, PaperLaw::newton_coulomb, PaperLaw::poisson_coulomb,
                 PaperLaw::fremond_coulomb, PaperLaw::fremond_viscous})
    EXPECT_EQ(paper_law_from_string(to_string(v)), v);
  EXPECT_THROW(integrator_from_string("rk4"), InvalidArgument);
  EXPECT_THROW(paper_law_from_string("hertz"), InvalidArgument);
}

TEST(SimulationOptions, EachOutOfRangeValueIsNamed) {
  const auto refused = [](auto edit, const std::string& name) {
    SimulationOptions o;
    edit(o);
    std::string why;
    EXPECT_FALSE(o.is_valid(&why)) << name;
    EXPECT_EQ(why.rfind(name + ":", 0), 0u) << why;
    try {
      o.validate();
      ADD_FAILURE() << name;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.name(), name);
    }
  };
  EXPECT_TRUE(SimulationOptions{}.is_valid());
  refused([](SimulationOptions& o) { o.t_end = 0; }, "t_end");
  refused([](SimulationOptions& o) { o.t_end = NAN; }, "t_end");
  refused([](SimulationOptions& o) { o.step = 4.0; }, "integrator.step");
  refused([](SimulationOptions& o) { o.max_impacts = 0; }, "integrator.max_impacts");
  refused([](SimulationOptions& o) { o.max_gap_evaluations = 99; },
          "integrator.max_gap_evaluations");
  refused([](SimulationOptions& o) { o.simultaneity_tolerance = -1; },
          "integrator.simultaneity_tolerance");
  refused([](SimulationOptions& o) { o.gap_tolerance = INFINITY; }, "integrator.gap_tolerance");
  refused([](SimulationOptions& o) { o.velocity_tolerance = -1e-9; },
          "integrator.velocity_tolerance");
  refused([](SimulationOptions& o) { o.accumulation_interval = 0; },
          "integrator.accumulation_interval");
  refused([](SimulationOptions& o) { o.accumulation_impacts = 1; },
          "integrator.accumulation_impacts");
  refused([](SimulationOptions& o) { o.return_after_free_steps = 0; },
          "integrator.return_after_free_steps");
  refused([](SimulationOptions& o) { o.sample_interval = 0; }, "output.sample_interval");
  refused([](SimulationOptions& o) { o.solver.tolerance = 1.0; }, "solver");
}

struct EventLog : SimulationObserver {
  std::vector<TrajectorySample> samples;
  std::vector<ImpactRecord> impacts;
  std::vector<double> progress;
  void on_sample(const TrajectorySample& s) override { samples.push_back(s); }
  void on_impact(const ImpactRecord& r) override { impacts.push_back(r); }
  void on_progress(double t, double) override { progress.push_back(t); }
};

TEST(SimulationOptions, SamplesFallOnTheGridAndAroundEveryImpact) {
  SimulationOptions o;
  o.t_end = 1.0;
  o.sample_interval = 0.01;
  EventLog log;
  const SimulationResult r = simulate(ball_scene({}, ImpactLaw::newton(0.9)), o, &log);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r.impacts, 1);  // at 0.4515 s; the next at 0.4515 + 2·0.9·4.429/9.81 = 1.264 s
  std::size_t grid = 0, around = 0;
  for (const TrajectorySample& s : log.samples) {
    const double k = std::round(s.t / 0.01);
    if (std::fabs(s.t - k * 0.01) < 1e-15)
      ++grid;
    else
      ++around;
    EXPECT_NEAR(s.energy,
                0.5 * s.state.qdot.squaredNorm() + 9.81 * s.state.q.y() +
                    0.5 * 0.4 * 0.01 * s.state.qdot.z() * s.state.qdot.z(),
                1e-12);
  }
  EXPECT_EQ(grid, 101u);
  EXPECT_EQ(around, 2u * log.impacts.size());
  EXPECT_EQ(log.samples.front().t, 0.0);
  EXPECT_EQ(log.samples.back().t, 1.0);
  // Progress: at most about a hundred calls, in order, the last at the end.
  ASSERT_FALSE(log.progress.empty());
  EXPECT_LE(log.progress.size(), 102u);
  for (std::size_t i = 1; i < log.progress.size(); ++i)
    EXPECT_GE(log.progress[i], log.progress[i - 1]);
  EXPECT_EQ(log.progress.back(), 1.0);
}

TEST(SimulationOptions, MaxImpactsStopsTheRunThere) {
  SimulationOptions o;
  o.max_impacts = 3;
  EventLog log;
  const SimulationResult r = simulate(bar_scene({}, ImpactLaw::newton(0.9)), o, &log);
  EXPECT_EQ(r.status, SimulationStatus::max_impacts);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.impacts, 3);
  ASSERT_EQ(log.impacts.size(), 3u);
  EXPECT_EQ(r.t, log.impacts.back().t);
}

TEST(SimulationOptions, AFlightTooFastToResolveStopsTheRunWhereItStands) {
  // A bar 1 m above the ground, no gravity: its lowest point stays 0.5 m up, so no impact ever.
  // Spinning at 10³ rad/s the run proves it and completes with the energy it started with; at
  // 10⁹ rad/s the first flight's search spends its budget and the run stops at t = 0, unchanged.
  Scene bar = bar_scene({}, ImpactLaw::newton(0.9));
  bar.gravity = 0.0;
  SimulationOptions o;
  o.t_end = 1.0;
  o.max_gap_evaluations = 50000;
  for (double omega : {1e3, 1e9}) {
    bar.initial = {Eigen::Vector3d(0, 1.0, 0.3), Eigen::Vector3d(0, 0, omega)};
    EventLog log;
    const SimulationResult r = simulate(bar, o, &log);
    EXPECT_EQ(r.impacts, 0);
    if (omega < 1e6) {
      EXPECT_EQ(r.status, SimulationStatus::completed) << r.message;
      EXPECT_EQ(r.t, 1.0);
      EXPECT_NEAR(r.energy_final, r.energy_initial, 1e-12 * r.energy_initial);
      continue;
    }
    EXPECT_EQ(r.status, SimulationStatus::event_search_failed);
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.message.find("max_gap_evaluations"), std::string_view::npos) << r.message;
    EXPECT_EQ(r.t, 0.0);
    EXPECT_EQ(r.state.q, bar.initial.q);
    EXPECT_EQ(r.state.qdot, bar.initial.qdot);
    EXPECT_EQ(r.gap_evaluations, o.max_gap_evaluations);  // the first contact's search, then stop
    ASSERT_FALSE(log.samples.empty());
    EXPECT_EQ(log.samples.back().t, 0.0);
  }
}

}  // namespace
}  // namespace fremond
