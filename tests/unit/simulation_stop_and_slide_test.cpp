// How a run ends: an observer that asks it to stop gets status interrupted with everything up to
// there, and a slide the law does not resist (the viscous dead zone below r) is named, while
// Coulomb's friction stops the same bar.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "fremond/scenes/kinematics.hpp"
#include "fremond/scenes/presets.hpp"
#include "fremond/simulation/calibration.hpp"
#include "fremond/simulation/simulate.hpp"
#include "fremond/simulation/unresisted_slide.hpp"

namespace fremond {
namespace {

// Keeps the samples and asks the run to stop once `stop_after` samples came.
class StopAfter final : public SimulationObserver {
 public:
  explicit StopAfter(std::size_t n) : stop_after_(n) {}
  void on_sample(const TrajectorySample& s) override { samples.push_back(s); }
  void on_impact(const ImpactRecord& r) override { impacts.push_back(r); }
  bool stop_requested() override { return samples.size() >= stop_after_; }
  std::vector<TrajectorySample> samples;
  std::vector<ImpactRecord> impacts;

 private:
  std::size_t stop_after_;
};

TEST(SimulationStop, AnObserverStopsTheRunWhereItIs) {
  const Scene scene = paper_bar_scene(PaperLaw::fremond_viscous);
  SimulationOptions opt;
  opt.t_end = 100.0;
  StopAfter obs(2000);  // 1 ms samples: about 2 s in, after the bar came to lie on the ground
  const SimulationResult r = simulate(scene, opt, &obs);
  EXPECT_EQ(r.status, SimulationStatus::interrupted);
  EXPECT_FALSE(r.ok());
  ASSERT_FALSE(obs.samples.empty());
  // The run stopped within one step of the request, and its last sample is its state.
  EXPECT_GT(r.t, 1.5);
  EXPECT_LT(r.t, 2.5);
  EXPECT_EQ(obs.samples.back().t, r.t);
  EXPECT_EQ(obs.samples.back().state.q, r.state.q);
  EXPECT_EQ(obs.samples.back().energy, r.energy_final);
  // The same run not stopped passes through the same state at the same time: the
  // run stops before a flight, so just after an impact, at the impact's time (to the ulp of the
  // clock's sum) and with its velocities.
  StopAfter all(~std::size_t{0});
  SimulationOptions three = opt;
  three.t_end = 3.0;
  ASSERT_EQ(simulate(scene, three, &all).status, SimulationStatus::completed);
  const ImpactRecord* same = nullptr;
  for (const ImpactRecord& im : all.impacts)
    if (std::fabs(im.t - r.t) <= 4 * std::numeric_limits<double>::epsilon() * r.t) same = &im;
  ASSERT_NE(same, nullptr) << r.t;
  EXPECT_LT((same->q - r.state.q).norm(), 1e-12);
  EXPECT_LT((same->qdot_E - r.state.qdot).norm(), 1e-12 * r.state.qdot.norm());
}

TEST(UnresistedSlide, TheViscousDeadZoneLetsTheBarSlideAndCoulombStopsIt) {
  SimulationOptions opt;
  opt.t_end = 30.0;
  const Scene viscous = paper_bar_scene(PaperLaw::fremond_viscous);
  const SimulationResult r = simulate(viscous, opt);
  ASSERT_EQ(r.status, SimulationStatus::completed);
  const auto slide = unresisted_slide(viscous, opt, r);
  ASSERT_TRUE(slide.has_value());
  // D_T of that contact from the kinematics, and the dead zone of the law: 0 < |D_T| <= r = 0.2.
  const ContactFrame f = contact_frame(viscous, slide->contact, r.state.q);
  EXPECT_EQ(slide->speed, f.W_T.dot(r.state.qdot));
  EXPECT_GT(std::fabs(slide->speed), 1e-3);
  EXPECT_LE(std::fabs(slide->speed), 0.2);
  // It keeps sliding at that speed: 30 s later it has moved by speed × 30 s.
  SimulationOptions longer = opt;
  longer.t_end = 60.0;
  const SimulationResult later = simulate(viscous, longer);
  EXPECT_NEAR(later.state.q.x() - r.state.q.x(), 30.0 * r.state.qdot.x(), 1e-9);

  const Scene coulomb = paper_bar_scene(PaperLaw::fremond_coulomb);
  const SimulationResult stopped = simulate(coulomb, opt);
  ASSERT_EQ(stopped.status, SimulationStatus::completed);
  EXPECT_FALSE(unresisted_slide(coulomb, opt, stopped).has_value());
  EXPECT_LT(stopped.state.qdot.norm(), 1e-9);
}

TEST(UnresistedSlide, AFlightIsNoSlide) {
  const Scene scene = paper_bar_scene(PaperLaw::fremond_viscous);
  SimulationOptions opt;
  opt.t_end = 0.1;  // still falling
  const SimulationResult r = simulate(scene, opt);
  EXPECT_FALSE(unresisted_slide(scene, opt, r).has_value());
}

}  // namespace
}  // namespace fremond
