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
#include "fremond/simulation/simulate_bodies.hpp"
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

// A body at `where` ("body", or "bodies[i]" of a scene of several bodies, whose bodies also hold
// their state: `state_keys` are allowed beside the body's own and read by the caller).
PlanarBody body_from_json(const json& j, const std::string& where,
                          const std::vector<std::string_view>& state_keys = {}) {
  detail::require_object(j, where);
  const auto keys = [&](std::initializer_list<std::string_view> own, const char* context) {
    std::vector<std::string_view> allowed(own);
    allowed.insert(allowed.end(), state_keys.begin(), state_keys.end());
    detail::refuse_unknown_keys(j, where, allowed, std::string("unknown key of ") + context);
  };
  const json* shape = detail::optional_key(j, "shape");
  // The presets' bodies, through the presets themselves so that both agree.
  const auto preset_body = [](const Scene& s) { return s.body; };
  const ImpactLaw any = ImpactLaw::newton(0.0);
  if (!shape) {
    keys({"mass", "inertia", "points"}, "a body");
    PlanarBody b;
    b.mass = number_at(j, where, "mass");
    b.inertia = number_at(j, where, "inertia");
    const json& pts = detail::required_key(j, where, "points");
    const std::string points = key_path(where, "points");
    if (!pts.is_array() || pts.empty())
      throw InvalidArgument(
          points, "must be a non-empty list of points, got " + detail::describe_json(pts));
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const std::string pw = detail::index_path(points, i);
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
  const std::string kind = detail::string_from_json(*shape, key_path(where, "shape"));
  // Dimensions are checked here, before the presets compute with them.
  const auto positive = [&](std::string_view key) {
    const double v = number_at(j, where, key);
    fremond::detail::require_finite_above(key_path(where, key), v, 0.0);
    return v;
  };
  if (kind == "bar") {
    keys({"shape", "mass", "half_length"}, "a bar");
    BarParameters p;
    p.mass = positive("mass");
    p.half_length = positive("half_length");
    return preset_body(bar_scene(p, any));
  }
  if (kind == "ball") {
    keys({"shape", "mass", "radius"}, "a ball");
    BallParameters p;
    p.mass = positive("mass");
    p.radius = positive("radius");
    return preset_body(ball_scene(p, any));
  }
  if (kind == "block") {
    keys({"shape", "mass", "width", "height"}, "a block");
    BlockParameters p;
    p.mass = positive("mass");
    p.width = positive("width");
    p.height = positive("height");
    return preset_body(block_scene(p, any));
  }
  throw InvalidArgument(key_path(where, "shape"),
                        "unknown value '" + kind +
                            "' (one of: bar, ball, block; or leave it out "
                            "and give mass, inertia and points)");
}

// A scene of several bodies may have no obstacle (`allow_empty`): Newton's cradle.
std::vector<HalfPlane> obstacles_from_json(const json& j, bool allow_empty = false) {
  if (!j.is_array() || (j.empty() && !allow_empty))
    throw InvalidArgument("obstacles", std::string("must be a ") +
                                           (allow_empty ? "" : "non-empty ") +
                                           "list of half-planes, got " + detail::describe_json(j));
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

namespace {

// t_end, integrator and output, shared by both kinds of scene file.
void options_from_json(const json& doc, SimulationOptions& o) {
  if (const json* t = detail::optional_key(doc, "t_end"))
    o.t_end = detail::number_from_json(*t, "t_end");
  if (const json* i = detail::optional_key(doc, "integrator")) integrator_from_json(*i, o);
  if (const json* out_opts = detail::optional_key(doc, "output")) {
    detail::require_object(*out_opts, "output");
    detail::check_keys(*out_opts, "output", {"sample_interval"}, "the output options");
    if (const json* v = detail::optional_key(*out_opts, "sample_interval"))
      o.sample_interval = detail::number_from_json(*v, "output.sample_interval");
  }
}

SceneFile scene_from_json(const json& doc, const PotentialRegistry& registry) {
  if (detail::optional_key(doc, "bodies"))
    throw InvalidArgument("bodies",
                          "a scene of several bodies, where one body is expected (`body` and "
                          "`initial`); fremond simulate runs it");
  detail::check_keys(
      doc, "", {"body", "obstacles", "gravity", "initial", "law", "t_end", "integrator", "output"},
      "the scene file");
  for (const char* key : {"body", "initial", "law"}) detail::required_key(doc, "", key);

  SceneFile out;
  Scene& s = out.scene;
  s.body = body_from_json(doc["body"], "body");
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
  options_from_json(doc, o);

  // Body and obstacles first: the law's per-contact lists are counted against them.
  s.law = ImpactLaw::newton(0.0);
  s.validate();
  s.law = detail::law_from_json(doc["law"], s.contact_count(), registry, "law");
  s.validate();
  o.validate();
  validate_start(s, o);
  return out;
}

MultiBodySceneFile multibody_scene_from_json(const json& doc, const PotentialRegistry& registry) {
  detail::check_keys(doc, "",
                     {"bodies", "obstacles", "gravity", "law", "t_end", "integrator", "output"},
                     "a scene file of several bodies");
  for (const char* key : {"bodies", "law"}) detail::required_key(doc, "", key);
  MultiBodySceneFile out;
  MultiBodyScene& s = out.scene;
  const json& bodies = doc["bodies"];
  if (!bodies.is_array() || bodies.empty())
    throw InvalidArgument(
        "bodies", "must be a non-empty list of bodies, got " + detail::describe_json(bodies));
  const int n = static_cast<int>(bodies.size());
  s.initial.q.resize(3 * n);
  s.initial.qdot.resize(3 * n);
  for (int i = 0; i < n; ++i) {
    const std::string where = detail::index_path("bodies", static_cast<std::size_t>(i));
    s.bodies.push_back(body_from_json(bodies[i], where, {"q", "qdot"}));
    const std::string q = key_path(where, "q"), qdot = key_path(where, "qdot");
    s.initial.q.segment<3>(3 * i) = vector3(detail::required_key(bodies[i], where, "q"), q);
    if (const json* v = detail::optional_key(bodies[i], "qdot"))
      s.initial.qdot.segment<3>(3 * i) = vector3(*v, qdot);
    else
      s.initial.qdot.segment<3>(3 * i).setZero();
    for (int c = 0; c < 3; ++c) {
      fremond::detail::require_finite(q + "[" + std::to_string(c) + "]", s.initial.q(3 * i + c));
      fremond::detail::require_finite(qdot + "[" + std::to_string(c) + "]",
                                      s.initial.qdot(3 * i + c));
    }
  }
  if (const json* o = detail::optional_key(doc, "obstacles"))
    s.obstacles = obstacles_from_json(*o, true);
  else
    s.obstacles = {HalfPlane{}};
  if (const json* g = detail::optional_key(doc, "gravity"))
    s.gravity = detail::number_from_json(*g, "gravity");
  options_from_json(doc, out.options);
  // The bodies and obstacles first: the law's per-contact lists are counted against them.
  s.law = ImpactLaw::newton(0.0);
  s.validate();
  s.law = detail::law_from_json(doc["law"], s.contact_count(), registry, "law");
  s.validate();
  out.options.validate();
  validate_start(s, out.options);
  return out;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidArgument(path, "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InvalidArgument(path, "cannot read the scene file");
  return text.str();
}

json scene_document(std::string_view text) {
  json doc = detail::parse_json(text, "scene");
  detail::require_object(doc, "scene");
  return doc;
}

}  // namespace

SceneFile parse_scene_file(std::string_view text, const PotentialRegistry& registry) {
  return scene_from_json(scene_document(text), registry);
}

MultiBodySceneFile parse_multibody_scene_file(std::string_view text,
                                              const PotentialRegistry& registry) {
  return multibody_scene_from_json(scene_document(text), registry);
}

std::variant<SceneFile, MultiBodySceneFile> parse_any_scene_file(
    std::string_view text, const PotentialRegistry& registry) {
  const json doc = scene_document(text);
  if (detail::optional_key(doc, "bodies")) return multibody_scene_from_json(doc, registry);
  return scene_from_json(doc, registry);
}

std::variant<SceneFile, MultiBodySceneFile> read_any_scene_file(const std::string& path,
                                                                const PotentialRegistry& registry) {
  return parse_any_scene_file(read_text(path), registry);
}

SceneFile read_scene_file(const std::string& path, const PotentialRegistry& registry) {
  return parse_scene_file(read_text(path), registry);
}

}  // namespace fremond::io
