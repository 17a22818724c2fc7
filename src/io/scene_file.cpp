// The scene file (scene_file.hpp): JSON → Scene + SimulationOptions, every key checked.
#include "fremond/io/scene_file.hpp"

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"
#include "fremond/scenes/presets.hpp"
#include "fremond/simulation/simulate.hpp"
#include "io/detail/json_law.hpp"
#include "io/detail/json_reader.hpp"

namespace fremond::io {

namespace {

using detail::json;
using detail::key_path;

double number_at(const json& obj, const std::string& where, std::string_view key) {
  return detail::number_from_json(detail::required_key(obj, where, key), key_path(where, key));
}

// A whole number (JSON has one number type: 3 and 3.0 are both accepted).
long integer_from_json(const json& j, const std::string& key) {
  const double v = detail::number_from_json(j, key);
  if (v != std::floor(v) || std::fabs(v) > 9e15)
    throw InvalidArgument(key, "must be a whole number, got " + fremond::detail::format_number(v));
  return static_cast<long>(v);
}

Eigen::Vector2d vector2(const json& j, const std::string& key) {
  const VectorX v = detail::vector_from_json(j, key);
  if (v.size() != 2)
    throw InvalidArgument(key, "must have 2 entries, got " + std::to_string(v.size()));
  return v;
}

Eigen::Vector3d vector3(const json& j, const std::string& key) {
  const VectorX v = detail::vector_from_json(j, key);
  if (v.size() != 3)
    throw InvalidArgument(key,
                          "must have 3 entries (x, y, theta), got " + std::to_string(v.size()));
  return v;
}

PlanarBody body_from_json(const json& j) {
  const std::string where = "body";
  detail::require_object(j, where);
  const json* shape = detail::optional_key(j, "shape");
  // The presets' bodies, through the presets themselves so that both agree.
  const auto preset_body = [](const Scene& s) { return s.body; };
  const ImpactLaw any = ImpactLaw::newton(0.0);
  if (!shape) {
    detail::check_keys(j, where, {"mass", "inertia", "points"}, "a body");
    PlanarBody b;
    b.mass = number_at(j, where, "mass");
    b.inertia = number_at(j, where, "inertia");
    const json& pts = detail::required_key(j, where, "points");
    if (!pts.is_array() || pts.empty())
      throw InvalidArgument(
          "body.points", "must be a non-empty list of points, got " + detail::describe_json(pts));
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const std::string pw = detail::index_path("body.points", i);
      detail::require_object(pts[i], pw);
      detail::check_keys(pts[i], pw, {"r", "radius"}, "a contact point");
      ContactPoint p;
      p.r = vector2(detail::required_key(pts[i], pw, "r"), key_path(pw, "r"));
      if (const json* r = detail::optional_key(pts[i], "radius"))
        p.radius = detail::number_from_json(*r, key_path(pw, "radius"));
      b.points.push_back(p);
    }
    return b;
  }
  const std::string kind = detail::string_from_json(*shape, "body.shape");
  // Dimensions are checked here, before the presets compute with them.
  const auto positive = [&](std::string_view key) {
    const double v = number_at(j, where, key);
    fremond::detail::require_finite_above(key_path(where, key), v, 0.0);
    return v;
  };
  if (kind == "bar") {
    detail::check_keys(j, where, {"shape", "mass", "half_length"}, "a bar");
    BarParameters p;
    p.mass = positive("mass");
    p.half_length = positive("half_length");
    return preset_body(bar_scene(p, any));
  }
  if (kind == "ball") {
    detail::check_keys(j, where, {"shape", "mass", "radius"}, "a ball");
    BallParameters p;
    p.mass = positive("mass");
    p.radius = positive("radius");
    return preset_body(ball_scene(p, any));
  }
  if (kind == "block") {
    detail::check_keys(j, where, {"shape", "mass", "width", "height"}, "a block");
    BlockParameters p;
    p.mass = positive("mass");
    p.width = positive("width");
    p.height = positive("height");
    return preset_body(block_scene(p, any));
  }
  throw InvalidArgument("body.shape", "unknown value '" + kind +
                                          "' (one of: bar, ball, block; or leave it out "
                                          "and give mass, inertia and points)");
}

std::vector<HalfPlane> obstacles_from_json(const json& j) {
  if (!j.is_array() || j.empty())
    throw InvalidArgument(
        "obstacles", "must be a non-empty list of half-planes, got " + detail::describe_json(j));
  std::vector<HalfPlane> out;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string w = detail::index_path("obstacles", i);
    detail::require_object(j[i], w);
    detail::check_keys(j[i], w, {"normal", "offset"}, "a half-plane");
    HalfPlane h;
    h.normal = vector2(detail::required_key(j[i], w, "normal"), key_path(w, "normal"));
    if (const json* o = detail::optional_key(j[i], "offset"))
      h.offset = detail::number_from_json(*o, key_path(w, "offset"));
    out.push_back(h);
  }
  return out;
}

void integrator_from_json(const json& j, SimulationOptions& o) {
  const std::string where = "integrator";
  detail::require_object(j, where);
  detail::check_keys(j, where,
                     {"method", "step", "max_impacts", "max_gap_evaluations",
                      "simultaneity_tolerance", "gap_tolerance", "velocity_tolerance",
                      "accumulation_interval", "accumulation_impacts", "return_after_free_steps"},
                     "the integrator");
  const auto num = [&](std::string_view key, double& out) {
    if (const json* v = detail::optional_key(j, key))
      out = detail::number_from_json(*v, key_path(where, key));
  };
  if (const json* m = detail::optional_key(j, "method"))
    o.integrator = integrator_from_string(detail::string_from_json(*m, "integrator.method"));
  num("step", o.step);
  num("simultaneity_tolerance", o.simultaneity_tolerance);
  num("gap_tolerance", o.gap_tolerance);
  num("velocity_tolerance", o.velocity_tolerance);
  num("accumulation_interval", o.accumulation_interval);
  if (const json* v = detail::optional_key(j, "max_impacts"))
    o.max_impacts = integer_from_json(*v, "integrator.max_impacts");
  if (const json* v = detail::optional_key(j, "max_gap_evaluations"))
    o.max_gap_evaluations = integer_from_json(*v, "integrator.max_gap_evaluations");
  // Range-checked as long before narrowing, so that 1e12 is refused rather than wrapped.
  const auto small_int = [&](std::string_view key, int& out) {
    const json* v = detail::optional_key(j, key);
    if (!v) return;
    const long x = integer_from_json(*v, key_path(where, key));
    if (x < 1 || x > 1000000)
      throw InvalidArgument(key_path(where, key),
                            "must be in [1, 1000000], got " + std::to_string(x));
    out = static_cast<int>(x);
  };
  small_int("accumulation_impacts", o.accumulation_impacts);
  small_int("return_after_free_steps", o.return_after_free_steps);
}

}  // namespace

SceneFile parse_scene_file(std::string_view text, const PotentialRegistry& registry) {
  const json doc = detail::parse_json(text, "scene");
  detail::require_object(doc, "scene");
  detail::check_keys(
      doc, "", {"body", "obstacles", "gravity", "initial", "law", "t_end", "integrator", "output"},
      "the scene file");
  for (const char* key : {"body", "initial", "law"}) detail::required_key(doc, "", key);

  SceneFile out;
  Scene& s = out.scene;
  s.body = body_from_json(doc["body"]);
  if (const json* o = detail::optional_key(doc, "obstacles"))
    s.obstacles = obstacles_from_json(*o);
  else
    s.obstacles = {HalfPlane{}};
  if (const json* g = detail::optional_key(doc, "gravity"))
    s.gravity = detail::number_from_json(*g, "gravity");
  const json& init = doc["initial"];
  detail::require_object(init, "initial");
  detail::check_keys(init, "initial", {"q", "qdot"}, "the initial state");
  s.initial.q = vector3(detail::required_key(init, "initial", "q"), "initial.q");
  s.initial.qdot = vector3(detail::required_key(init, "initial", "qdot"), "initial.qdot");

  SimulationOptions& o = out.options;
  if (const json* t = detail::optional_key(doc, "t_end"))
    o.t_end = detail::number_from_json(*t, "t_end");
  if (const json* i = detail::optional_key(doc, "integrator")) integrator_from_json(*i, o);
  if (const json* out_opts = detail::optional_key(doc, "output")) {
    detail::require_object(*out_opts, "output");
    detail::check_keys(*out_opts, "output", {"sample_interval"}, "the output options");
    if (const json* v = detail::optional_key(*out_opts, "sample_interval"))
      o.sample_interval = detail::number_from_json(*v, "output.sample_interval");
  }

  // Body and obstacles first: the law's per-contact lists are counted against them.
  s.law = ImpactLaw::newton(0.0);
  s.validate();
  s.law = detail::law_from_json(doc["law"], s.contact_count(), registry, "law");
  s.validate();
  o.validate();
  validate_start(s, o);
  return out;
}

SceneFile read_scene_file(const std::string& path, const PotentialRegistry& registry) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidArgument(path, "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InvalidArgument(path, "cannot read the scene file");
  return parse_scene_file(text.str(), registry);
}

}  // namespace fremond::io
