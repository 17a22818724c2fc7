#pragma once
/// @file The scene file: a body, its obstacles, the initial state, the law and the integrator's
/// options, as one JSON object (the input of `fremond simulate SCENE.json`).
///
///     {
///       "body": {"shape": "bar", "mass": 1, "half_length": 0.5},
///       "obstacles": [{"normal": [0, 1], "offset": 0}],
///       "gravity": 9.81,
///       "initial": {"q": [0, 1, 0.7853981633974483], "qdot": [2, 0, 0]},
///       "law": {"type": "newton_coulomb", "e": 0.9, "mu": 1.0},
///       "t_end": 3,
///       "integrator": {"method": "event_driven", "step": 0.001},
///       "output": {"sample_interval": 0.001}
///     }
///
/// `body` is either a shape with its dimensions — "bar" (mass, half_length: J = m l²/3, ends at
/// (∓l, 0)), "ball" (mass, radius: J = 2mρ²/5), "block" (mass, width, height: J = m(w² + h²)/12,
/// corners as in presets.hpp) — or a general body {"mass", "inertia", "points": [{"r": [x, y],
/// "radius": ρ}, ...]} ("radius" optional, 0). Required: body, initial, law. Optional, with their
/// defaults: obstacles (the ground y ≥ 0), gravity (9.81), t_end (3), integrator (every key of
/// SimulationOptions: method, step, max_impacts, max_gap_evaluations, simultaneity_tolerance,
/// gap_tolerance, velocity_tolerance, accumulation_interval, accumulation_impacts,
/// return_after_free_steps; the defaults of simulation_options.hpp), output (sample_interval).
/// The law is read exactly as in the impact-problem file (docs/problem-file.md), with one value per
/// contact in the order of Scene::contact_count(). Unknown keys, missing keys, wrong types and
/// out-of-range values are refused with an InvalidArgument naming the key (`body.mass`,
/// `integrator.step`, `law.e`, ...). So is what every impact of the scene would refuse
/// (Scene::validate): an inertia more than 1e24 times above or below the mass (named
/// `body.inertia`, or `body` when a shape's dimensions gave it), and an initial energy or contact
/// velocity beyond double precision
/// (`initial`).
#include <string>
#include <string_view>
#include <variant>

#include "fremond/potentials/registry.hpp"
#include "fremond/scenes/multibody.hpp"
#include "fremond/scenes/scene.hpp"
#include "fremond/simulation/simulation_options.hpp"

namespace fremond::io {

/// What a scene file holds.
struct SceneFile {
  Scene scene;                ///< validated.
  SimulationOptions options;  ///< validated.
};

/// Reads a scene file of one body from its text (a file with "bodies" is refused naming it). A
/// message without a key (empty input, not an object) is named "scene".
SceneFile parse_scene_file(std::string_view json_text, const PotentialRegistry& registry);

/// Reads the scene file at `path`; a file that cannot be read is refused naming the path.
SceneFile read_scene_file(const std::string& path, const PotentialRegistry& registry);

/// What a scene file of several bodies holds: a "bodies" list instead of "body" and "initial".
///
///     {
///       "bodies": [
///         {"shape": "ball", "mass": 1, "radius": 0.1, "q": [0, 0.1, 0]},
///         {"shape": "ball", "mass": 1, "radius": 0.1, "q": [0, 0.8, 0], "qdot": [0, 0, 0]}
///       ],
///       "obstacles": [{"normal": [0, 1], "offset": 0}],
///       "law": {"type": "newton", "e": 0.9}
///     }
///
/// Each body is read as the single body's `body` (a shape, or mass, inertia and points), with its
/// state: "q" (x, y, θ; required) and "qdot" (optional, zero). Obstacles default to the ground and
/// may be an empty list. gravity, t_end, integrator and output as above. The law has one value per
/// contact in the order of MultiBodyScene::contacts(). Errors name the key: `bodies[1].mass`,
/// `bodies[0].q`, `bodies[2].points[0].radius`, `law.e`; what MultiBodyScene::validate and
/// validate_start refuse about the state as a whole (disks at one centre, a contact starting in
/// penetration, an overflowing energy) is named `initial.q` or `initial`.
struct MultiBodySceneFile {
  MultiBodyScene scene;       ///< validated.
  SimulationOptions options;  ///< validated.
};
MultiBodySceneFile parse_multibody_scene_file(std::string_view json_text,
                                              const PotentialRegistry& registry);
/// Either kind of scene file, told apart by its "bodies" key.
std::variant<SceneFile, MultiBodySceneFile> parse_any_scene_file(std::string_view json_text,
                                                                 const PotentialRegistry& registry);
std::variant<SceneFile, MultiBodySceneFile> read_any_scene_file(const std::string& path,
                                                                const PotentialRegistry& registry);

}  // namespace fremond::io
