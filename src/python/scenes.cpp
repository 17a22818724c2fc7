// Scenes: a planar rigid body against half-planes, the presets, the paper's bar and laws, and the
// calibration of Frémond's k_N (docs/concepts.md, the paper's Fig. 1).
#include <string>
#include <vector>

#include "fremond/core/error.hpp"
#include "fremond/io/scene_file.hpp"
#include "fremond/scenes/kinematics.hpp"
#include "fremond/scenes/presets.hpp"
#include "fremond/scenes/scene.hpp"
#include "fremond/simulation/calibration.hpp"
#include "python/bind_helpers.hpp"
#include "python/docstrings.hpp"

namespace fremond::python {

void bind_scenes(py::module_& m) {
  py::class_<ContactPoint> point(m, "ContactPoint", doc::kContactPoint);
  def_keyword_init<ContactPoint>(point);
  point.def_readwrite("r", &ContactPoint::r)
      .def_readwrite("radius", &ContactPoint::radius)
      .def("__repr__", [](const ContactPoint& c) {
        return repr_of(c, "ContactPoint", {"r", "radius"});
      });

  py::class_<PlanarBody> body(m, "PlanarBody", doc::kPlanarBody);
  def_keyword_init<PlanarBody>(body);
  body.def_readwrite("mass", &PlanarBody::mass)
      .def_readwrite("inertia", &PlanarBody::inertia)
      .def_readwrite("points", &PlanarBody::points)
      .def("mass_matrix", &PlanarBody::mass_matrix)
      .def("__repr__", [](const PlanarBody& b) {
        return repr_of(b, "PlanarBody", {"mass", "inertia", "points"});
      });

  py::class_<HalfPlane> plane(m, "HalfPlane", doc::kHalfPlane);
  def_keyword_init<HalfPlane>(plane);
  plane.def_readwrite("normal", &HalfPlane::normal)
      .def_readwrite("offset", &HalfPlane::offset)
      .def("__repr__", [](const HalfPlane& h) {
        return repr_of(h, "HalfPlane", {"normal", "offset"});
      });

  py::class_<PlanarState> state(m, "PlanarState", doc::kPlanarState);
  def_keyword_init<PlanarState>(state);
  state.def_readwrite("q", &PlanarState::q)
      .def_readwrite("qdot", &PlanarState::qdot)
      .def("__repr__", [](const PlanarState& s) {
        return repr_of(s, "PlanarState", {"q", "qdot"});
      });

  py::class_<Scene> scene(m, "Scene", doc::kScene);
  def_keyword_init<Scene>(scene);
  scene.def_readwrite("body", &Scene::body)
      .def_readwrite("obstacles", &Scene::obstacles)
      .def_readwrite("gravity", &Scene::gravity)
      .def_readwrite("initial", &Scene::initial)
      .def_readwrite("law", &Scene::law)
      .def("contact_count", &Scene::contact_count)
      .def("point_of", &Scene::point_of, py::arg("contact"))
      .def("obstacle_of", &Scene::obstacle_of, py::arg("contact"))
      .def("validate", &Scene::validate)
      .def("__repr__", [](const Scene& s) {
        return repr_of(s, "Scene", {"body", "obstacles", "gravity", "initial", "law"});
      });

  py::class_<BarParameters> bar(m, "BarParameters", doc::kBarParameters);
  def_keyword_init<BarParameters>(bar);
  bar.def_readwrite("mass", &BarParameters::mass)
      .def_readwrite("half_length", &BarParameters::half_length)
      .def_readwrite("gravity", &BarParameters::gravity)
      .def_readwrite("initial", &BarParameters::initial)
      .def("__repr__", [](const BarParameters& b) {
        return repr_of(b, "BarParameters", {"mass", "half_length", "gravity", "initial"});
      });
  py::class_<BallParameters> ball(m, "BallParameters");
  def_keyword_init<BallParameters>(ball);
  ball.def_readwrite("mass", &BallParameters::mass)
      .def_readwrite("radius", &BallParameters::radius)
      .def_readwrite("gravity", &BallParameters::gravity)
      .def_readwrite("initial", &BallParameters::initial);
  py::class_<BlockParameters> block(m, "BlockParameters");
  def_keyword_init<BlockParameters>(block);
  block.def_readwrite("mass", &BlockParameters::mass)
      .def_readwrite("width", &BlockParameters::width)
      .def_readwrite("height", &BlockParameters::height)
      .def_readwrite("gravity", &BlockParameters::gravity)
      .def_readwrite("initial", &BlockParameters::initial);

  m.def("bar_scene", &bar_scene, py::arg("bar"), py::arg("law"));
  m.def("ball_scene", &ball_scene, py::arg("ball"), py::arg("law"));
  m.def("block_scene", &block_scene, py::arg("block"), py::arg("law"));
  m.def("paper_law", &paper_law, py::arg("law"), py::arg("k_N"), doc::kPaperLawFn);
  m.def("paper_bar_scene", &paper_bar_scene, py::arg("law"), py::arg("bar") = BarParameters{},
        py::call_guard<py::gil_scoped_release>(), doc::kPaperBarScene);
  m.def("paper_bar_normal_stiffness", &paper_bar_normal_stiffness, py::arg("bar") = BarParameters{},
        py::call_guard<py::gil_scoped_release>(), doc::kPaperStiffness);
  using C = PaperConstants;
  m.attr("paper_constants") =
      py::dict(py::arg("e") = C::e, py::arg("mu") = C::mu, py::arg("p") = C::p,
               py::arg("k_T") = C::k_T, py::arg("q") = C::q, py::arg("r") = C::r);

  m.def("energy", static_cast<double (*)(const Scene&, const PlanarState&)>(&energy),
        py::arg("scene"), py::arg("state"), doc::kEnergy);
  m.def("kinetic_energy", &kinetic_energy, py::arg("body"), py::arg("qdot"));
  m.def(
      "contact_frame",
      [](const Scene& s, int contact, const Eigen::Vector3d& q) {
        if (contact < 0 || contact >= s.contact_count())
          throw InvalidArgument("contact", "no contact " + std::to_string(contact) +
                                               " (the scene has " +
                                               std::to_string(s.contact_count()) + ")");
        const ContactFrame f = contact_frame(s, contact, q);
        return py::make_tuple(f.gap, f.W_N, f.W_T);
      },
      py::arg("scene"), py::arg("contact"), py::arg("q"), doc::kContactFrame);

  py::class_<FirstImpact>(m, "FirstImpact")
      .def_readonly("found", &FirstImpact::found)
      .def_readonly("resolved", &FirstImpact::resolved)
      .def_readonly("t", &FirstImpact::t)
      .def_readonly("state", &FirstImpact::state)
      .def_property_readonly("contacts", [](const FirstImpact& f) {
        return std::vector<int>(f.contacts.begin(), f.contacts.begin() + f.contact_count);
      });
  m.def("first_impact", &first_impact, py::arg("scene"), py::arg("t_max"),
        py::arg("simultaneity_tolerance") = 1e-12,
        "Flies the scene's initial state exactly until its first contact event, before t_max.");
  m.def(
      "impact_problem",
      [](const Scene& s, const PlanarState& st, const std::vector<int>& contacts) {
        if (contacts.empty() || contacts.size() > static_cast<std::size_t>(kSmallContacts))
          throw InvalidArgument("contacts", "needs 1 to 4 contacts");
        for (int k : contacts)
          if (k < 0 || k >= s.contact_count())
            throw InvalidArgument("contacts", "no contact " + std::to_string(k));
        return to_dynamic(
            impact_problem(s, st, contacts.data(), static_cast<int>(contacts.size())));
      },
      py::arg("scene"), py::arg("state"), py::arg("contacts"),
      "The impact problem of the given contacts of a validated scene at a state.");

  py::class_<StiffnessCalibration>(m, "StiffnessCalibration")
      .def_readonly("k_N", &StiffnessCalibration::k_N)
      .def_readonly("restitution", &StiffnessCalibration::restitution)
      .def_readonly("solves", &StiffnessCalibration::solves)
      .def_readonly("converged", &StiffnessCalibration::converged);
  m.def(
      "calibrate_normal_stiffness",
      [](const ImpactProblem& problem, double p, double restitution, int contact,
         const SolverOptions& options) {
        return calibrate_normal_stiffness(to_small(problem), p, restitution, contact, options);
      },
      py::arg("problem"), py::arg("p"), py::arg("restitution"), py::arg("contact") = 0,
      py::arg("options") = SolverOptions{}, py::call_guard<py::gil_scoped_release>(),
      "k such that Frémond's normal law alone gives -D_NE/D_NA = restitution at that contact.");

  m.def(
      "parse_scene_file",
      [](const std::string& text, const PotentialRegistry* registry) {
        io::SceneFile f =
            io::parse_scene_file(text, registry ? *registry : PotentialRegistry::with_builtins());
        return py::make_tuple(std::move(f.scene), std::move(f.options));
      },
      py::arg("text"), py::arg("registry") = nullptr, doc::kParseScene);
}

}  // namespace fremond::python
