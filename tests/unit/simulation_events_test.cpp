// Free flight and event detection: closed forms, a dense brute-force reference, grazing touches.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <Eigen/LU>

#include "fremond/scenes/kinematics.hpp"
#include "fremond/scenes/presets.hpp"
#include "fremond/simulation/event_detection.hpp"
#include "fremond/simulation/free_flight.hpp"

#include "simulation/detail/ulp.hpp"

namespace fremond {
namespace {

TEST(FreeFlight, GapFunctionMatchesTheKinematicsAlongTheFlight) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int trial = 0; trial < 200; ++trial) {
    ContactPoint p{{u(rng), u(rng)}, std::fabs(u(rng)) / 3};
    HalfPlane o{Eigen::Vector2d(u(rng), u(rng)).normalized(), u(rng)};
    FreeFlight f{
        0.0,
        {Eigen::Vector3d(u(rng), u(rng), u(rng)), Eigen::Vector3d(u(rng), u(rng), 5 * u(rng))},
        9.81};
    const GapFunction g = GapFunction::make(p, o, f);
    for (double s : {0.0, 0.1, 0.37, 1.5}) {
      const PlanarState st = f.at_elapsed(s);
      const ContactFrame fr =
          contact_frame(p, o, st.q.head<2>(), std::cos(st.q.z()), std::sin(st.q.z()));
      double gv, gd, gdd;
      g.eval(s, gv, gd, gdd);
      EXPECT_NEAR(gv, fr.gap, 1e-12);
      // D_N = W_Nᵀ q̇ is the gap's derivative (docs/concepts.md).
      EXPECT_NEAR(gd, fr.W_N.dot(st.qdot), 1e-12);
      // g'' by central differences of g'.
      double a, da, dda, b, db, ddb;
      g.eval(s - 1e-6, a, da, dda);
      g.eval(s + 1e-6, b, db, ddb);
      EXPECT_NEAR(gdd, (db - da) / 2e-6, 1e-6 * (1 + std::fabs(gdd)));
      EXPECT_LE(std::fabs(gdd), g.K);
    }
  }
}

TEST(FreeFlight, SpecSection5ContactDirectionsOfTheBar) {
  // the paper's Fig. 1: lower end at θ = π/4, W_N = (0, 1, −l cos θ), W_T = (1, 0, l sin θ).
  const Scene bar = bar_scene({}, ImpactLaw::newton(0.9));
  const double l = 0.5, th = std::numbers::pi / 4;
  const ContactFrame f = contact_frame(bar, 0, Eigen::Vector3d(0.0, 1.0, th));
  EXPECT_NEAR(f.gap, 1.0 - l * std::sin(th), 1e-15);
  EXPECT_NEAR((f.W_N - Eigen::Vector3d(0, 1, -l * std::cos(th))).norm(), 0.0, 1e-15);
  EXPECT_NEAR((f.W_T - Eigen::Vector3d(1, 0, l * std::sin(th))).norm(), 0.0, 1e-15);
  // The Delassus matrix of eqs. (7)-(8): G_NN = (1 + 3cos²θ)/m, G_NT = −3 sinθ cosθ/m, G_TT = (1 +
  // 3sin²θ)/m.
  const Eigen::Matrix3d Minv = bar.body.mass_matrix().inverse();
  EXPECT_NEAR(f.W_N.dot(Minv * f.W_N), 1 + 3 * std::cos(th) * std::cos(th), 1e-14);
  EXPECT_NEAR(f.W_N.dot(Minv * f.W_T), -3 * std::sin(th) * std::cos(th), 1e-14);
  EXPECT_NEAR(f.W_T.dot(Minv * f.W_T), 1 + 3 * std::sin(th) * std::sin(th), 1e-14);
}

TEST(EventDetection, DroppedBallHitsAtTheClosedFormTime) {
  const ContactPoint ball{{0, 0}, 0.1};
  for (double h : {1e-6, 0.01, 1.0, 100.0}) {
    const FreeFlight f{0.0, {Eigen::Vector3d(0, h + 0.1, 0), Eigen::Vector3d::Zero()}, 9.81};
    const auto r = find_first_event(GapFunction::make(ball, HalfPlane{}, f), 1e3, false);
    ASSERT_TRUE(r.found());
    // The drop height as the flight sees it: (h + ρ) − ρ, rounded once.
    const double drop = (h + 0.1) - 0.1;
    EXPECT_NEAR(r.s, std::sqrt(2 * drop / 9.81), 4e-16 * std::sqrt(2 * drop / 9.81)) << h;
  }
}

// A time scale far below the search's depth bound (2⁻²⁰⁰ of s_max ≈ 3e-61 s here): under
// g = 1e200 and 1e300 m/s² a drop of 0.9 m takes 1.3e-100 s and 1.3e-150 s, and a bounce back up at
// 1 m/s lasts 2/g. Both come at their closed-form times, not at the end of the deepest interval.
TEST(EventDetection, EventsFarBelowTheDepthBoundOfTheSearchAreRefined) {
  for (const double g : {1e100, 1e200, 1e300, 1.7e308}) {
    GapFunction drop;
    drop.alpha = 0.9;
    drop.gamma = -0.5 * g;
    drop.K = g * (1 + 1e-12);
    const auto r = find_first_event(drop, 0.5, false);
    ASSERT_TRUE(r.found()) << g;
    EXPECT_NEAR(r.s, std::sqrt(1.8 / g), 4e-16 * std::sqrt(1.8 / g)) << g;

    GapFunction bounce = drop;  // just left an impact, rising at 1 m/s
    bounce.alpha = 0.0;
    bounce.beta = 1.0;
    const auto b = find_first_event(bounce, 0.5, true);
    ASSERT_TRUE(b.found()) << g;
    EXPECT_NEAR(b.s, 2.0 / g, 4e-16 * (2.0 / g)) << g;
  }
}

// The first root of g on [0, s_max] by dense sampling and bisection: the independent reference.
double brute_first_root(const GapFunction& g, double s_max, double ds) {
  double a = 0.0, ga = g.value(0.0);
  for (double b = ds; b <= s_max; b += ds) {
    const double gb = g.value(b);
    if (ga > 0.0 && gb <= 0.0) {
      for (int i = 0; i < 200; ++i) {
        const double m = 0.5 * (a + b);
        (g.value(m) > 0.0 ? a : b) = m;
      }
      return b;
    }
    a = b;
    ga = gb;
  }
  return std::numeric_limits<double>::infinity();
}

// A flight of the paper's bar from 0.4-0.9 m up at any angle, spinning at up to 60 rad/s (a turn
// every 0.1 s): its ends dip down many times.
FreeFlight random_spinning_bar_flight(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double y = 0.4 + 0.5 * u(rng), theta = 2 * std::numbers::pi * u(rng);
  const double ydot = 3 * u(rng), omega = (u(rng) - 0.5) * 120;
  return FreeFlight{0.0, {Eigen::Vector3d(0, y, theta), Eigen::Vector3d(1, ydot, omega)}, 9.81};
}

TEST(EventDetection, FastSpinningBarMissesNoEventAgainstDenseSampling) {
  // Every first dip of a spinning bar that reaches the ground must be found, none invented.
  std::mt19937_64 rng(11);
  const Scene bar = bar_scene({}, ImpactLaw::newton(0.9));
  int found = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const FreeFlight f = random_spinning_bar_flight(rng);
    for (int k = 0; k < 2; ++k) {
      const GapFunction g = GapFunction::make(bar.body.points[k], bar.obstacles[0], f);
      if (g.value(0.0) <= 0.0) continue;
      const auto r = find_first_event(g, 1.0, false);
      const double ref = brute_first_root(g, 1.0, 2e-5);
      if (std::isinf(ref)) {
        // The sampling may miss a shallow dip; the search may not invent one: any event found
        // must be a genuine crossing.
        if (r.found()) {
          EXPECT_LE(g.value(r.s), 0.0);
          EXPECT_GT(g.value(r.s - 1e-9), 0.0);
        }
        continue;
      }
      ASSERT_TRUE(r.found()) << trial;
      EXPECT_LE(r.s, ref + 1e-12) << trial;  // never later than the first sampled crossing
      EXPECT_LE(g.value(r.s), 0.0);
      // Nothing before: the gap is positive just before, and on a fine grid before it.
      for (double s = 0.0; s < r.s - 1e-12; s += 1e-5) EXPECT_GT(g.value(s), 0.0) << trial;
      ++found;
    }
  }
  EXPECT_GT(found, 100);
}

TEST(EventDetection, GrazingTouchesAreFoundOrIgnoredByTheirSign) {
  // A ball thrown up towards a ceiling at y = H: the apex of its top point is H + δ. A crossing
  // by δ = 1e-12 m is an event; an apex δ below the ceiling is none.
  const ContactPoint ball{{0, 0}, 0.0};
  const HalfPlane ceiling{{0.0, -1.0}, -2.0};
  const double g = 9.81, v = 3.0, apex = v * v / (2 * g);
  for (double delta : {1e-12, 1e-9, 1e-6}) {
    for (double sign : {+1.0, -1.0}) {
      const double y0 = 2.0 - apex + sign * delta;
      const FreeFlight f{0.0, {Eigen::Vector3d(0, y0, 0), Eigen::Vector3d(0, v, 0)}, g};
      const GapFunction gap = GapFunction::make(ball, ceiling, f);
      const auto r = find_first_event(gap, 2.0, false);
      if (sign < 0) {
        EXPECT_FALSE(r.found()) << delta;
        continue;
      }
      ASSERT_TRUE(r.found()) << delta;
      // y(s) = y0 + v s − g s²/2 = 2 at s = (v − √(2gδ'))/g, δ' = apex + y0 − 2.
      const double d = apex + y0 - 2.0;
      const double s_ref = (v - std::sqrt(2 * g * d)) / g;
      EXPECT_NEAR(r.s, s_ref, 1e-3 * (v / g - s_ref) + 1e-12) << delta;
      EXPECT_LE(gap.value(r.s), 0.0);
    }
  }
}

TEST(EventDetection, ALeavingContactDoesNotRetrigger) {
  // Just after an impact the gap may be −1e-17 with the contact leaving: not an event; the next
  // one is the closed-form return of the bounce.
  const ContactPoint ball{{0, 0}, 0.1};
  const FreeFlight f{0.0, {Eigen::Vector3d(0, 0.1 - 1e-17, 0), Eigen::Vector3d(0, 2.0, 0)}, 9.81};
  const auto r = find_first_event(GapFunction::make(ball, HalfPlane{}, f), 10.0, true);
  ASSERT_TRUE(r.found());
  EXPECT_NEAR(r.s, 2 * 2.0 / 9.81, 1e-15);
  // Touching, at rest, and lifted by the rotation (g'' > 0): no event either.
  const FreeFlight spin{
      0.0, {Eigen::Vector3d(0, 0.5, -std::numbers::pi / 2), Eigen::Vector3d(0, 0, 10.0)}, 9.81};
  const Scene bar = bar_scene({}, ImpactLaw::newton(0.9));
  const GapFunction g1 = GapFunction::make(bar.body.points[1], bar.obstacles[0], spin);
  double g, gd, gdd;
  g1.eval(0.0, g, gd, gdd);
  ASSERT_NEAR(g, 0.0, 1e-15);
  ASSERT_GT(gdd, 0.0);
  const auto r1 = find_first_event(g1, 0.05, true);
  EXPECT_FALSE(r1.found());
}

TEST(EventDetection, TheBudgetCutsTheSearchAndChangesNoAnswer) {
  // The spinning bars above: a budget of at least the evaluations an unbounded search spends
  // gives the same answer from the same samples; any smaller one gives the same answer or ends
  // `exhausted` after exactly the budget, never a different event.
  std::mt19937_64 rng(12);
  const Scene bar = bar_scene({}, ImpactLaw::newton(0.9));
  int cut = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const FreeFlight f = random_spinning_bar_flight(rng);
    const GapFunction g = GapFunction::make(bar.body.points[trial % 2], bar.obstacles[0], f);
    if (g.value(0.0) <= 0.0) continue;
    const auto full = find_first_event(g, 1.0, false, std::numeric_limits<long>::max());
    ASSERT_FALSE(full.exhausted);
    const auto same = find_first_event(g, 1.0, false, full.evaluations);
    EXPECT_FALSE(same.exhausted) << trial;
    EXPECT_EQ(same.s, full.s) << trial;
    EXPECT_EQ(same.evaluations, full.evaluations) << trial;
    const long budget = std::max(2L, full.evaluations / 3);
    const auto part = find_first_event(g, 1.0, false, budget);
    if (part.exhausted) {
      ++cut;
      EXPECT_FALSE(part.found()) << trial;
      EXPECT_EQ(part.evaluations, budget) << trial;
    } else {
      EXPECT_EQ(part.s, full.s) << trial;
    }
  }
  EXPECT_GT(cut, 50);
}

TEST(EventDetection, ASpinTooFastToResolveEndsExhausted) {
  // A bar 1 m above the ground without gravity: its lowest point stays at 1 − 0.5 m, so no flight
  // has an event. At 10³ rad/s (160 turns) the search proves it; at 10⁹ rad/s it would need about
  // 10⁹ intervals, and ends at its budget instead.
  const Scene bar = bar_scene({}, ImpactLaw::newton(0.9));
  for (double omega : {1e3, 1e9}) {
    const FreeFlight f{0.0, {Eigen::Vector3d(0, 1.0, 0.3), Eigen::Vector3d(0, 0, omega)}, 0.0};
    const GapFunction g = GapFunction::make(bar.body.points[0], bar.obstacles[0], f);
    const auto r = find_first_event(g, 1.0, false, 100000);
    EXPECT_FALSE(r.found()) << omega;
    EXPECT_EQ(r.exhausted, omega > 1e6) << omega << " " << r.evaluations;
    if (r.exhausted) {
      EXPECT_EQ(r.evaluations, 100000);
    } else {
      EXPECT_LT(r.evaluations, 100000);
    }
  }
}

// The event search's unit in the last place by bit pattern is std::nextafter's, value for value:
// the smallest width it splits, and so which samples it takes, depend on it.
TEST(EventDetection, UlpIsNextafterAboveTheMagnitude) {
  const auto reference = [](double x) {
    x = std::fabs(x);
    return std::nextafter(x, std::numeric_limits<double>::infinity()) - x;
  };
  const auto same = [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); };
  using L = std::numeric_limits<double>;
  for (double x : {0.0, -0.0, L::denorm_min(), L::min(), 1.0, -1.0, 3.0, 0.1, 1e300, -L::max(),
                   L::max(), L::infinity(), -L::infinity(), L::quiet_NaN()})
    EXPECT_TRUE(same(detail::ulp(x), reference(x))) << x;
  std::mt19937_64 rng(5);
  for (int i = 0; i < 100000; ++i) {
    const double x = std::ldexp(std::uniform_real_distribution<double>(-1.0, 1.0)(rng),
                                static_cast<int>(rng() % 2100) - 1075);
    ASSERT_TRUE(same(detail::ulp(x), reference(x))) << x;
  }
}

}  // namespace
}  // namespace fremond
