// Regressions of the simulation found by the seeded fuzzing. A test named DISABLED_ would be an
// open library issue (see tests/stress/known_issues.txt), to enable when fixed.
#include <gtest/gtest.h>

#include "fremond/fremond.hpp"
#include "fremond/io/scene_file.hpp"

namespace fremond {
namespace {

// The fuzzer's input (scene_file_fuzz, seed 1): the bar falls at 1.4e67 m/s, and its first impact
// (Frémond + Coulomb) sets it spinning at a comparable rate. The exhaustive event search of the
// next free flight would split every turn of the next 0.5 s, about 1e66 of them (it ran for over
// 100 s in Release before the search had a budget). The run must end after its one impact, with
// the status that says the flight cannot be resolved, after at most a budget per contact.
// The fuzzer's bar had its left end level with the right one, so that both ends took part at that
// speed; their impact is symmetric and gives no spin, which Newton now finds to the last bit (a
// spin of 7e52 rad/s before, rounding, was what the search could not resolve). The left end is
// lifted 1 m here, so that the right end hits alone and the spin is the law's.
TEST(RegressionSimulation, EventSearchOnAnUnresolvableSpinEnds) {
  const auto file = io::parse_scene_file(R"({
    "body": {"mass": 1, "inertia": 0.1,
             "points": [{"r": [-0.5, 1]}, {"r": [0.5, 0], "radius": 0.05}]},
    "obstacles": [{"normal": [0, 2], "offset": 0}],
    "gravity": 0,
    "initial": {"q": [0, 0.2, 0], "qdot": [0, -1.4444444444444444e67, 0]},
    "law": {"type": "fremond", "normal": {"potential": "power", "k": 3, "p": 3},
            "tangential": {"potential": "coulomb", "mu": 0.5}},
    "t_end": 0.5,
    "integrator": {"max_impacts": 10, "accumulation_impacts": 4}})",
                                         PotentialRegistry::with_builtins());
  const SimulationResult r = simulate(file.scene, file.options);
  EXPECT_EQ(r.status, SimulationStatus::event_search_failed) << r.message;
  EXPECT_EQ(r.impacts, 1);
  // Both ends fall 0.2 m (the right one with its radius, 0.15 m) at 1.44e67 m/s: the first impact
  // is the right end's, at 0.15/1.44e67 s.
  EXPECT_NEAR(r.t, 0.15 / 1.4444444444444444e67, 1e-12 * r.t);
  EXPECT_LE(r.gap_evaluations, 4 * file.options.max_gap_evaluations);
}

}  // namespace
}  // namespace fremond
