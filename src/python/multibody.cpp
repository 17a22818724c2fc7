// Scenes of several bodies (scenes/multibody.hpp): the scene, its presets, the impact problem of
// its touching contacts, and the event-driven run (simulation/simulate_bodies.hpp).
#include <string>
#include <vector>

#include "fremond/io/scene_file.hpp"
#include "fremond/scenes/multibody.hpp"
#include "fremond/scenes/presets.hpp"
#include "fremond/simulation/simulate_bodies.hpp"
#include "python/bind_helpers.hpp"

namespace fremond::python {

namespace {

// Everything a run of several bodies reports, gathered by its observer.
struct BodiesRun : MultiBodyObserver {
  MultiBodyResult result;
  std::vector<double> t, energy;
  std::vector<Eigen::VectorXd> q, qdot;
  std::vector<MultiBodyImpact> impacts;
  void on_sample(const MultiBodySample& s) override {
    t.push_back(s.t);
    energy.push_back(s.energy);
    q.push_back(s.state.q);
    qdot.push_back(s.state.qdot);
  }
  void on_impact(const MultiBodyImpact& i) override { impacts.push_back(i); }
};

// Samples as rows of a (samples × 3·bodies) array.
py::array_t<double> rows(const std::vector<Eigen::VectorXd>& v) {
  const py::ssize_t n = static_cast<py::ssize_t>(v.size());
  const py::ssize_t m = v.empty() ? 0 : static_cast<py::ssize_t>(v[0].size());
  py::array_t<double> out({n, m});
  auto a = out.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i)
    for (py::ssize_t j = 0; j < m; ++j) a(i, j) = v[static_cast<std::size_t>(i)](j);
  return out;
}

}  // namespace

void bind_multibody(py::module_& m) {
  py::class_<BodyContact>(m, "BodyContact",
                          "One contact of a scene of several bodies: a point of `body` against "
                          "obstacle `obstacle`, or against point `other_point` of `other_body`.")
      .def_readonly("body", &BodyContact::body)
      .def_readonly("point", &BodyContact::point)
      .def_readonly("obstacle", &BodyContact::obstacle)
      .def_readonly("other_body", &BodyContact::other_body)
      .def_readonly("other_point", &BodyContact::other_point)
      .def("is_pair", &BodyContact::is_pair)
      .def("__repr__", [](const BodyContact& c) {
        return repr_of(c, "BodyContact",
                       {"body", "point", "obstacle", "other_body", "other_point"});
      });

  py::class_<MultiBodyState> state(m, "MultiBodyState",
                                   "q and qdot of every body, three entries each (x, y, theta).");
  def_keyword_init<MultiBodyState>(state);
  state.def_readwrite("q", &MultiBodyState::q).def_readwrite("qdot", &MultiBodyState::qdot);

  py::class_<MultiBodyScene> scene(
      m, "MultiBodyScene",
      "Several planar bodies against fixed half-planes and against each other's disks.");
  def_keyword_init<MultiBodyScene>(scene);
  scene.def_readwrite("bodies", &MultiBodyScene::bodies)
      .def_readwrite("obstacles", &MultiBodyScene::obstacles)
      .def_readwrite("gravity", &MultiBodyScene::gravity)
      .def_readwrite("initial", &MultiBodyScene::initial)
      .def_readwrite("law", &MultiBodyScene::law)
      .def("contacts", &MultiBodyScene::contacts)
      .def("contact_count", &MultiBodyScene::contact_count)
      .def("dofs", &MultiBodyScene::dofs)
      .def("validate", &MultiBodyScene::validate)
      .def("__repr__", [](const MultiBodyScene& s) {
        return repr_of(s, "MultiBodyScene", {"bodies", "obstacles", "gravity", "law"});
      });

  py::class_<CradleParameters> cradle(m, "CradleParameters");
  def_keyword_init<CradleParameters>(cradle);
  cradle.def_readwrite("balls", &CradleParameters::balls)
      .def_readwrite("mass", &CradleParameters::mass)
      .def_readwrite("radius", &CradleParameters::radius)
      .def_readwrite("speed", &CradleParameters::speed);
  py::class_<BallOnBallParameters> drop(m, "BallOnBallParameters");
  def_keyword_init<BallOnBallParameters>(drop);
  drop.def_readwrite("mass", &BallOnBallParameters::mass)
      .def_readwrite("radius", &BallOnBallParameters::radius)
      .def_readwrite("drop_height", &BallOnBallParameters::drop_height)
      .def_readwrite("speed", &BallOnBallParameters::speed)
      .def_readwrite("gravity", &BallOnBallParameters::gravity);
  m.def("cradle_scene", &cradle_scene, py::arg("cradle"), py::arg("law"),
        "Newton's cradle: equal balls in a row, touching, the first striking the others.");
  m.def("ball_on_ball_scene", &ball_on_ball_scene, py::arg("drop"), py::arg("law"),
        "A ball dropped on an equal ball resting on the ground.");

  m.def(
      "touching_contacts",
      [](const MultiBodyScene& s, const Eigen::VectorXd& q, double tolerance) {
        return touching_contacts(s, q, tolerance);
      },
      py::arg("scene"), py::arg("q"), py::arg("tolerance") = 1e-9,
      "The indices of the contacts whose gap at q is at most `tolerance`.");
  m.def(
      "impact_problem",
      [](const MultiBodyScene& s, const MultiBodyState& st, const std::vector<int>& contacts) {
        return impact_problem(s, st, contacts);
      },
      py::arg("scene"), py::arg("state"), py::arg("contacts"),
      "The impact problem of the given contacts of a scene of several bodies at a state.");
  m.def(
      "law_of",
      [](const MultiBodyScene& s, const std::vector<int>& contacts) { return law_of(s, contacts); },
      py::arg("scene"), py::arg("contacts"), "The scene's law restricted to these contacts.");
  m.def(
      "energy", [](const MultiBodyScene& s, const MultiBodyState& st) { return energy(s, st); },
      py::arg("scene"), py::arg("state"));
  m.def(
      "momentum",
      [](const MultiBodyScene& s, const Eigen::VectorXd& qdot) { return momentum(s, qdot); },
      py::arg("scene"), py::arg("qdot"), "The linear momentum (x, y) of every body together.");

  py::class_<MultiBodyImpact>(m, "MultiBodyImpact")
      .def_readonly("index", &MultiBodyImpact::index)
      .def_readonly("t", &MultiBodyImpact::t)
      .def_readonly("kind", &MultiBodyImpact::kind)
      .def_readonly("contacts", &MultiBodyImpact::contacts)
      .def_readonly("q", &MultiBodyImpact::q)
      .def_readonly("qdot_A", &MultiBodyImpact::qdot_A)
      .def_readonly("qdot_E", &MultiBodyImpact::qdot_E)
      .def_readonly("P_N", &MultiBodyImpact::P_N)
      .def_readonly("P_T", &MultiBodyImpact::P_T)
      .def_readonly("D_NA", &MultiBodyImpact::D_NA)
      .def_readonly("D_NE", &MultiBodyImpact::D_NE)
      .def_readonly("energy_A", &MultiBodyImpact::energy_A)
      .def_readonly("energy_E", &MultiBodyImpact::energy_E)
      .def_readonly("admissible", &MultiBodyImpact::admissible);
  py::class_<MultiBodyResult>(m, "MultiBodyResult")
      .def_readonly("status", &MultiBodyResult::status)
      .def_property_readonly("message",
                             [](const MultiBodyResult& r) { return std::string(r.message); })
      .def_readonly("t", &MultiBodyResult::t)
      .def_readonly("state", &MultiBodyResult::state)
      .def_readonly("energy_initial", &MultiBodyResult::energy_initial)
      .def_readonly("energy_final", &MultiBodyResult::energy_final)
      .def_readonly("impacts", &MultiBodyResult::impacts)
      .def_readonly("inadmissible_impacts", &MultiBodyResult::inadmissible_impacts)
      .def_readonly("accumulations", &MultiBodyResult::accumulations)
      .def_readonly("max_energy_rise", &MultiBodyResult::max_energy_rise)
      .def("ok", &MultiBodyResult::ok);
  py::class_<BodiesRun>(m, "MultiBodySimulation")
      .def_readonly("result", &BodiesRun::result)
      .def_property_readonly(
          "t", [](const BodiesRun& r) { return py::array_t<double>(r.t.size(), r.t.data()); })
      .def_property_readonly(
          "energy",
          [](const BodiesRun& r) { return py::array_t<double>(r.energy.size(), r.energy.data()); })
      .def_property_readonly("q", [](const BodiesRun& r) { return rows(r.q); })
      .def_property_readonly("qdot", [](const BodiesRun& r) { return rows(r.qdot); })
      .def_readonly("impacts", &BodiesRun::impacts);
  m.def(
      "simulate",
      [](const MultiBodyScene& s, const SimulationOptions& options) {
        BodiesRun run;
        {
          py::gil_scoped_release released;
          run.result = simulate(s, options, &run);
        }
        return run;
      },
      py::arg("scene"), py::arg("options") = SimulationOptions{},
      "Runs a scene of several bodies event-driven: samples (t, q, qdot, energy as arrays) and "
      "the impact log.");
  m.def(
      "parse_multibody_scene_file",
      [](const std::string& text, const PotentialRegistry* registry) {
        io::MultiBodySceneFile f = io::parse_multibody_scene_file(
            text, registry ? *registry : PotentialRegistry::with_builtins());
        return py::make_tuple(std::move(f.scene), std::move(f.options));
      },
      py::arg("text"), py::arg("registry") = nullptr,
      "Reads a scene file of several bodies (docs/scene-file.md): (scene, options).");
}

}  // namespace fremond::python
