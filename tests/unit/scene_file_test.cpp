// The scene file: what it reads, what it refuses and how it names the key.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <variant>

#include "fremond/core/error.hpp"
#include "fremond/io/scene_file.hpp"
#include "fremond/potentials/power.hpp"
#include "fremond/scenes/presets.hpp"
#include "fremond/simulation/simulate.hpp"

namespace fremond {
namespace {

const PotentialRegistry& registry() {
  static const PotentialRegistry r = PotentialRegistry::with_builtins();
  return r;
}

const char* kBar = R"({
  "body": {"shape": "bar", "mass": 1, "half_length": 0.5},
  "obstacles": [{"normal": [0, 2], "offset": 0}],
  "initial": {"q": [0, 1, 0.7853981633974483], "qdot": [2, 0, 0]},
  "law": {"type": "newton_coulomb", "e": 0.9, "mu": [1.0, 0.5]},
  "t_end": 3,
  "integrator": {"method": "moreau_jean", "step": 0.002, "max_impacts": 50},
  "output": {"sample_interval": 0.01}
})";

TEST(SceneFile, ReadsTheBarAsThePresetMakesIt) {
  const io::SceneFile f = io::parse_scene_file(kBar, registry());
  const Scene preset = bar_scene({}, ImpactLaw::newton(0.9));
  EXPECT_EQ(f.scene.body.mass, preset.body.mass);
  EXPECT_EQ(f.scene.body.inertia, preset.body.inertia);
  ASSERT_EQ(f.scene.body.points.size(), 2u);
  EXPECT_EQ(f.scene.body.points[0].r, preset.body.points[0].r);
  EXPECT_EQ(f.scene.body.points[1].r, preset.body.points[1].r);
  ASSERT_EQ(f.scene.obstacles.size(), 1u);
  EXPECT_EQ(f.scene.obstacles[0].normal, Eigen::Vector2d(0, 1));  // normalised
  EXPECT_EQ(f.scene.gravity, 9.81);                               // the default
  EXPECT_EQ(f.scene.initial.q, preset.initial.q);
  EXPECT_EQ(f.scene.initial.qdot, preset.initial.qdot);
  EXPECT_EQ(f.scene.law.name(), "newton_coulomb");
  EXPECT_EQ(f.scene.law.mu(1), 0.5);  // one value per contact, in contact order
  EXPECT_EQ(f.options.integrator, Integrator::moreau_jean);
  EXPECT_EQ(f.options.t_end, 3.0);
  EXPECT_EQ(f.options.step, 0.002);
  EXPECT_EQ(f.options.max_impacts, 50);
  EXPECT_EQ(f.options.sample_interval, 0.01);
  EXPECT_EQ(f.options.accumulation_impacts, SimulationOptions{}.accumulation_impacts);
}

TEST(SceneFile, ReadsGeneralBodiesBallsBlocksAndFremondLaws) {
  const io::SceneFile general = io::parse_scene_file(R"({
    "body": {"mass": 2, "inertia": 0.5, "points": [{"r": [0.1, -0.2], "radius": 0.05}, {"r": [0, 0]}]},
    "obstacles": [{"normal": [0, 1]}, {"normal": [-1, 0], "offset": -3}],
    "gravity": 0,
    "initial": {"q": [0, 1, 0], "qdot": [1, 0, 0]},
    "law": {"type": "fremond", "normal": {"potential": "power", "k": 85.36, "p": 3},
            "tangential": {"potential": "deadzone_power", "k": 1.5, "q": 2, "r": 0.2}}})",
                                                     registry());
  EXPECT_EQ(general.scene.contact_count(), 4);
  EXPECT_EQ(general.scene.body.points[0].radius, 0.05);
  EXPECT_EQ(general.scene.body.points[1].radius, 0.0);
  EXPECT_EQ(general.scene.obstacles[1].offset, -3.0);
  EXPECT_EQ(general.scene.gravity, 0.0);
  EXPECT_EQ(general.scene.law.get<FremondLaw>().tangential, TangentialLaw::potential);
  EXPECT_EQ(general.options.t_end, SimulationOptions{}.t_end);

  const io::SceneFile ball = io::parse_scene_file(
      R"({"body": {"shape": "ball", "mass": 2, "radius": 0.2},
          "initial": {"q": [0, 1, 0], "qdot": [0, 0, 0]}, "law": {"type": "newton", "e": 0.5}})",
      registry());
  EXPECT_NEAR(ball.scene.body.inertia, 0.4 * 2 * 0.04, 1e-15);
  EXPECT_EQ(ball.scene.body.points[0].radius, 0.2);
  const io::SceneFile block = io::parse_scene_file(
      R"({"body": {"shape": "block", "mass": 3, "width": 0.4, "height": 0.2},
          "initial": {"q": [0, 1, 0], "qdot": [0, 0, 0]}, "law": {"type": "newton", "e": 0.5}})",
      registry());
  EXPECT_NEAR(block.scene.body.inertia, 3 * (0.16 + 0.04) / 12, 1e-15);
  EXPECT_EQ(block.scene.body.points.size(), 4u);
}

// Replaces the first occurrence of `from` in the bar's file by `to`, and expects a refusal naming
// `key` whose reason contains `reason`.
void expect_refused(const std::string& from, const std::string& to, const std::string& key,
                    const std::string& reason) {
  std::string text = kBar;
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  try {
    io::parse_scene_file(text, registry());
    ADD_FAILURE() << "accepted: " << to;
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
  }
}

TEST(SceneFile, RefusesUnknownKeysAndBadValuesNamingTheKey) {
  expect_refused(R"("t_end": 3)", R"("t_end": 3, "tend": 4)", "tend", "unknown key");
  expect_refused(R"("half_length": 0.5)", R"("half_length": 0.5, "length": 1)", "body.length",
                 "unknown key");
  expect_refused(R"("shape": "bar")", R"("shape": "rod")", "body.shape", "unknown value 'rod'");
  expect_refused(R"("mass": 1)", R"("mass": -1)", "body.mass", "must be > 0");
  expect_refused(R"("half_length": 0.5)", R"("half_length": "long")", "body.half_length",
                 "must be a number");
  expect_refused(R"("normal": [0, 2])", R"("normal": [0, 0])", "obstacles[0].normal",
                 "must not be zero");
  expect_refused(R"("normal": [0, 2])", R"("normal": [0, 2, 1])", "obstacles[0].normal",
                 "must have 2 entries");
  expect_refused(R"("offset": 0})", R"("offset": 0, "side": 1})", "obstacles[0].side",
                 "unknown key");
  expect_refused(R"("qdot": [2, 0, 0])", R"("qdot": [2, 0])", "initial.qdot", "3 entries");
  expect_refused(R"("q": [0, 1, 0.7853981633974483], )", "", "initial.q", "missing");
  expect_refused(R"("e": 0.9)", R"("e": 1.5)", "law.e", "[0, 1]");
  expect_refused(R"("mu": [1.0, 0.5])", R"("mu": [1.0, 0.5, 0.2])", "law.mu", "one per contact");
  expect_refused(R"("method": "moreau_jean")", R"("method": "rk4")", "integrator.method",
                 "unknown value 'rk4'");
  expect_refused(R"("step": 0.002)", R"("step": 0)", "integrator.step", "(0, t_end]");
  expect_refused(R"("step": 0.002)", R"("step": 0.002, "order": 2)", "integrator.order",
                 "unknown key");
  expect_refused(R"("max_impacts": 50)", R"("max_impacts": 2.5)", "integrator.max_impacts",
                 "whole number");
  expect_refused(R"("t_end": 3)", R"("t_end": -1)", "t_end", "> 0");
  expect_refused(R"("sample_interval": 0.01)", R"("sample_interval": 0)", "output.sample_interval",
                 "> 0");
  expect_refused(R"("t_end": 3)", R"("t_end": 3, "t_end": 4)", "t_end", "");  // given twice
}

// What every impact of the scene would refuse (validate(ImpactProblem): M positive definite to
// rounding, a finite kinetic energy) is refused when the scene is read, not after its output has
// begun; a preset says its dimensions gave the inertia.
TEST(SceneFile, RefusesWhatItsFirstImpactWouldRefuse) {
  expect_refused(R"("half_length": 0.5)", R"("half_length": 1e13)", "body",
                 "the bar's mass and half_length give mass 1 and inertia");
  expect_refused(R"("half_length": 0.5)", R"("half_length": 1e-13)", "body", "too far apart");
  expect_refused(R"("qdot": [2, 0, 0])", R"("qdot": [2e160, 0, 0])", "initial",
                 "energy 1/2 qdot^T M qdot + m g y overflows");
  // A start inside the ground (the lower end of the bar at y = 0.2 − 0.354): refused by the
  // reader, as simulate() refuses it, naming the point, the obstacle and the depth.
  expect_refused(R"("q": [0, 1, 0.7853981633974483])", R"("q": [0, 0.2, 0.7853981633974483])",
                 "initial", "contact point 0 starts 0.153553 m inside obstacle 0");
  const auto general = [](const std::string& inertia) {
    return R"({"body": {"mass": 1, "inertia": )" + inertia +
           R"(, "points": [{"r": [1, 0]}]}, "initial": {"q": [0, 1, 0], "qdot": [0, 0, 0]},
               "law": {"type": "newton", "e": 0.5}})";
  };
  for (const char* bad : {"1e-25", "1e25"}) {
    try {
      io::parse_scene_file(general(bad), registry());
      ADD_FAILURE() << "accepted inertia " << bad;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.name(), "body.inertia") << e.what();
      EXPECT_NE(std::string(e.what()).find("J/m must lie within 1e-24 and 1e24"), std::string::npos)
          << e.what();
    }
  }
  // Just inside the bound, the scene is read and its impacts are solved.
  for (const char* fine : {"1e-23", "1e23"}) {
    const io::SceneFile f = io::parse_scene_file(general(fine), registry());
    SimulationOptions o = f.options;
    o.t_end = 1.0;
    const SimulationResult r = simulate(f.scene, o);
    EXPECT_TRUE(r.ok()) << fine << ": " << r.message;
    EXPECT_GE(r.impacts, 1) << fine;
  }
  // The scene the fuzzer found: a block 1e40 m wide (J = 8.3e79 for m = 1).
  try {
    io::parse_scene_file(R"({"body": {"shape": "block", "mass": 1, "width": 1e40, "height": 0.2},
                            "initial": {"q": [0.5, 0.3, 0.2], "qdot": [6, 0, 1]},
                            "law": {"type": "newton", "e": 0.5}})",
                         registry());
    ADD_FAILURE() << "accepted the 1e40 m block";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "body") << e.what();
    EXPECT_NE(std::string(e.what()).find("the block's mass, width and height give"),
              std::string::npos)
        << e.what();
  }
}

TEST(SceneFile, RefusesUnreadableFilesNamingThePath) {
  EXPECT_THROW(io::read_scene_file("/nonexistent/scene.json", registry()), InvalidArgument);
  EXPECT_THROW(io::parse_scene_file("", registry()), InvalidArgument);
  EXPECT_THROW(io::parse_scene_file("[1, 2]", registry()), InvalidArgument);
}

// A file of several bodies: each body as the single body's, with its q and qdot; the same scene
// as the preset; told apart from a file of one body by its "bodies" key.
TEST(SceneFile, ReadsSeveralBodiesAsThePresetMakesThem) {
  const char* text = R"({
    "bodies": [
      {"shape": "ball", "mass": 1, "radius": 0.1, "q": [0, 0.1, 0]},
      {"mass": 1, "inertia": 0.004, "points": [{"r": [0, 0], "radius": 0.1}],
       "q": [0, 0.8, 0], "qdot": [0, -2, 0]}
    ],
    "law": {"type": "newton", "e": [0.9, 0.8, 0.7]},
    "gravity": 9.81,
    "t_end": 2
  })";
  const auto any = io::parse_any_scene_file(text, registry());
  ASSERT_TRUE(std::holds_alternative<io::MultiBodySceneFile>(any));
  const io::MultiBodySceneFile& f = std::get<io::MultiBodySceneFile>(any);
  BallOnBallParameters p;
  p.speed = 2.0;
  const MultiBodyScene preset = ball_on_ball_scene(p, ImpactLaw::newton(0.9));
  ASSERT_EQ(f.scene.bodies.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(f.scene.bodies[i].mass, preset.bodies[i].mass);
    EXPECT_NEAR(f.scene.bodies[i].inertia, preset.bodies[i].inertia, 1e-18);
    EXPECT_EQ(f.scene.bodies[i].points[0].radius, preset.bodies[i].points[0].radius);
  }
  EXPECT_EQ(f.scene.initial.q, preset.initial.q);
  EXPECT_EQ(f.scene.initial.qdot, preset.initial.qdot);
  ASSERT_EQ(f.scene.obstacles.size(), 1u);  // the ground by default
  EXPECT_EQ(f.scene.contact_count(), 3);
  EXPECT_EQ(f.options.t_end, 2.0);
  EXPECT_TRUE(std::holds_alternative<io::SceneFile>(io::parse_any_scene_file(kBar, registry())));
  try {
    io::parse_scene_file(text, registry());
    ADD_FAILURE() << "a file of several bodies read as one body";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "bodies");
  }
}

}  // namespace
}  // namespace fremond
