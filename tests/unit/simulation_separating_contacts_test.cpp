// A body that lands on one end or corner while touching with another, its other end leaving:
// every closed contact goes to the impact law (docs/concepts.md), so the leaving one is stopped by
// its reaction and nothing ends the impact below the ground. By hand on the flat bar (m = 1,
// l = 0.5, J = 1/12), v_y = −1, ω = −4: the left end leaves at +1, the right end arrives at −3,
// and Newton's e = 0.9 on the right end alone would leave the left end at D_NE = −1.85.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fremond/core/error.hpp"
#include "fremond/scenes/presets.hpp"
#include "fremond/simulation/calibration.hpp"
#include "fremond/simulation/simulate.hpp"
#include "support/simulation_log.hpp"

namespace fremond {
namespace {

using Log = testing::SimulationLog;

constexpr PaperLaw kLaws[] = {PaperLaw::newton, PaperLaw::newton_coulomb, PaperLaw::poisson_coulomb,
                              PaperLaw::fremond_coulomb, PaperLaw::fremond_viscous};

// Lowest height above the ground of the points (a_x, a_y) of the body frame, at a sample.
double lowest(const TrajectorySample& s, const std::vector<Eigen::Vector2d>& points) {
  const double c = std::cos(s.state.q.z()), sn = std::sin(s.state.q.z());
  double low = INFINITY;
  for (const Eigen::Vector2d& a : points)
    low = std::min(low, s.state.q.y() + sn * a.x() + c * a.y());
  return low;
}

// The first impact stops the leaving contact (0) and no sample lies below the ground.
void expect_no_penetration(const Scene& scene, const std::vector<Eigen::Vector2d>& points,
                           const char* what) {
  SimulationOptions opt;
  opt.t_end = 0.3;
  opt.sample_interval = 1e-3;
  Log log;
  const SimulationResult r = simulate(scene, opt, &log);
  ASSERT_TRUE(r.ok()) << what << ": " << r.message;
  ASSERT_FALSE(log.impacts.empty()) << what;
  const ImpactRecord& first = log.impacts.front();
  EXPECT_EQ(first.t, 0.0) << what;
  ASSERT_EQ(first.contact_count, 2) << what;
  for (int i = 0; i < 2; ++i) {
    const double scale = std::fabs(first.D_NA(i)) + 1.0;
    EXPECT_GE(first.D_NE(i), -1e-12 * scale) << what << " contact " << first.contacts[i];
  }
  const int leaving = first.D_NA(0) > 0 ? 0 : 1;
  EXPECT_GT(first.D_NA(leaving), 0.5) << what;
  EXPECT_GT(first.P_N(leaving), 0.01) << what << ": the leaving contact is stopped by its reaction";
  for (const TrajectorySample& s : log.samples)
    EXPECT_GE(lowest(s, points), -1e-6) << what << " at t = " << s.t;
}

TEST(SimulationSeparatingContacts, AFlatBarLandingOnOneEndDoesNotSinkTheOther) {
  const double k_N = paper_bar_normal_stiffness();
  for (PaperLaw law : kLaws) {
    BarParameters bar;
    bar.initial.q = {0.0, 0.0, 0.0};
    bar.initial.qdot = {0.0, -1.0, -4.0};
    const Scene scene = bar_scene(bar, paper_law(law, k_N));
    const double l = bar.half_length;
    expect_no_penetration(scene, {{-l, 0.0}, {l, 0.0}}, to_string(law).data());
  }
}

TEST(SimulationSeparatingContacts, ABlockLandingOnACornerDoesNotSinkTheOther) {
  // The block lying flat (width 0.4, height 0.2): the bottom corners (∓0.2, −0.1). ω = −10 lifts
  // the left corner at +1 and brings the right one down at −3; ẋ = 1 keeps the corners from
  // sliding before the impact (D_TA = ẋ + 0.1 ω = 0).
  const double k_N = paper_bar_normal_stiffness();
  // Not Frémond + Coulomb: on the corners' identical tangential rows, coupled to the normal ones,
  // its solver stalls (which corner sticks is decided by rounding) and the run stops there.
  for (PaperLaw law : {PaperLaw::newton, PaperLaw::newton_coulomb, PaperLaw::poisson_coulomb,
                       PaperLaw::fremond_viscous}) {
    BlockParameters block;
    block.initial.q = {0.0, 0.5 * block.height, 0.0};
    block.initial.qdot = {1.0, -1.0, -10.0};
    const Scene scene = block_scene(block, paper_law(law, k_N));
    const double w = 0.5 * block.width, h = 0.5 * block.height;
    expect_no_penetration(scene, {{-w, -h}, {w, -h}, {-w, h}, {w, h}}, to_string(law).data());
  }
}

TEST(SimulationStart, ABodyStartingInsideTheGroundIsRefused) {
  BarParameters bar;
  bar.initial.q = {0.0, -0.5, 0.0};  // both ends 0.5 m deep
  const Scene scene = bar_scene(bar, ImpactLaw::newton(0.9));
  try {
    simulate(scene, SimulationOptions{});
    FAIL() << "a buried start was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "initial");
    EXPECT_NE(std::string(e.what()).find("0.5"), std::string::npos) << e.what();
  }
  bar.initial.q = {0.0, 0.0, 0.0};  // lying on the ground: a valid start
  EXPECT_TRUE(simulate(bar_scene(bar, ImpactLaw::newton(0.9)), SimulationOptions{}).ok());
}

}  // namespace
}  // namespace fremond
