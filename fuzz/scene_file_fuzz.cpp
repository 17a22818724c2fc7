// Fuzz target: the scene-file reader (`fremond simulate SCENE.json`), then a short simulation of
// what it accepts.
//
// Contract checked on every input:
//  - the reader either accepts or throws InvalidArgument with a name and a reason; nothing else
//    escapes;
//  - what it accepts validates again (Scene::validate, SimulationOptions::validate);
//  - a run of it, shortened so that one input stays cheap (t_end ≤ 0.2 s, at most 200 impacts,
//    2,000 steps and 200,000 gap evaluations per event search), ends with a status, at a finite
//    time and state, and never past t_end.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fremond/io/scene_file.hpp"
#include "fremond/simulation/simulate.hpp"
#include "fuzz_support.hpp"

using namespace fremond;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const PotentialRegistry registry = PotentialRegistry::with_builtins();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  io::SceneFile file;
  try {
    file = io::parse_scene_file(text, registry);
  } catch (const InvalidArgument& e) {
    fuzz::check_refusal(e);
    return 0;
  }
  try {
    Scene again = file.scene;
    again.validate();
    file.options.validate();
  } catch (const InvalidArgument& e) {
    fuzz::fail(std::string("the reader accepted an invalid scene: ") + e.what());
  }

  if (fuzz::classify_only(file.scene.law)) return 0;
  SimulationOptions o = file.options;
  o.t_end = std::min(o.t_end, 0.2);
  o.step = std::clamp(o.step, o.t_end / 2000.0, o.t_end);
  o.sample_interval = std::max(o.sample_interval, o.t_end / 50.0);
  o.max_impacts = std::min(o.max_impacts, 200L);
  o.max_gap_evaluations = std::min(o.max_gap_evaluations, 200'000L);
  o.accumulation_interval = std::min(o.accumulation_interval, o.t_end);
  try {
    o.validate();
  } catch (const InvalidArgument&) {
    return 0;  // the shortened options are ours, not the file's
  }
  SimulationResult r;
  try {
    r = simulate(file.scene, o);
  } catch (const InvalidArgument& e) {
    fuzz::fail(std::string("simulate refused a scene the reader accepted: ") + e.what());
  }
  if (r.status == SimulationStatus::not_run) fuzz::fail("simulate ended with status not_run");
  if (!std::isfinite(r.t) || r.t > o.t_end * (1 + 1e-12) + 1e-12)
    fuzz::fail("simulate stopped at t = " + std::to_string(r.t) + ", t_end " +
               std::to_string(o.t_end));
  if (r.ok() &&
      (!r.state.q.allFinite() || !r.state.qdot.allFinite() || !std::isfinite(r.energy_final)))
    fuzz::fail("simulate completed with a state that is not finite");
  return 0;
}
