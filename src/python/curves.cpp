// The data of Figs. 8 and 9 (include/fremond/curves/curves.hpp), as NumPy arrays.
#include <variant>
#include <vector>

#include "fremond/curves/curves.hpp"
#include "python/bind_helpers.hpp"
#include "python/docstrings.hpp"

namespace fremond::python {

namespace {

// A curve and the parameters it was computed with.
struct Curve {
  std::variant<NormalCurveParameters, TangentialCurveParameters> parameters;
  std::vector<CurvePoint> points;
};

template <class T>
py::array_t<T> column(const Curve& c, T CurvePoint::*member) {
  py::array_t<T> out(static_cast<py::ssize_t>(c.points.size()));
  auto a = out.template mutable_unchecked<1>();
  for (std::size_t i = 0; i < c.points.size(); ++i)
    a(static_cast<py::ssize_t>(i)) = c.points[i].*member;
  return out;
}

}  // namespace

void bind_curves(py::module_& m) {
  py::class_<NormalCurveParameters> np(m, "NormalCurveParameters", doc::kNormalCurveParameters);
  def_keyword_init<NormalCurveParameters>(np);
  np.def_readwrite("mass", &NormalCurveParameters::mass)
      .def_readwrite("k", &NormalCurveParameters::k)
      .def_readwrite("p", &NormalCurveParameters::p)
      .def_readwrite("scaling", &NormalCurveParameters::scaling)
      .def("in_library_scaling", &NormalCurveParameters::in_library_scaling)
      .def("in_paper_scaling", &NormalCurveParameters::in_paper_scaling)
      .def("validate", &NormalCurveParameters::validate)
      .def("__repr__", [](const NormalCurveParameters& p) {
        return repr_of(p, "NormalCurveParameters", {"mass", "k", "p", "scaling"});
      });

  using TP = TangentialCurveParameters;
  py::class_<TP> tp(m, "TangentialCurveParameters", doc::kTangentialCurveParameters);
  def_keyword_init<TP>(tp);
  tp.def_readwrite("mass", &TP::mass)
      .def_readwrite("k_N", &TP::k_N)
      .def_readwrite("p", &TP::p)
      .def_readwrite("D_NA", &TP::D_NA)
      .def_readwrite("k_T", &TP::k_T)
      .def_readwrite("q", &TP::q)
      .def_readwrite("r", &TP::r)
      .def_readwrite("scaling", &TP::scaling)
      .def_static("paper_figure", &TP::paper_figure, py::arg("scaling"))
      .def("in_library_scaling", &TP::in_library_scaling)
      .def("in_paper_scaling", &TP::in_paper_scaling)
      .def("validate", &TP::validate)
      .def("__repr__", [](const TP& p) {
        return repr_of(p, "TangentialCurveParameters",
                       {"mass", "k_N", "p", "D_NA", "k_T", "q", "r", "scaling"});
      });

  py::class_<Curve>(m, "Curve", doc::kCurve)
      .def_property_readonly("parameters",
                             [](const Curve& c) {
                               return std::visit([](const auto& p) { return py::cast(p); },
                                                 c.parameters);
                             })
      .def_property_readonly("D_NA", [](const Curve& c) { return column(c, &CurvePoint::D_NA); })
      .def_property_readonly("D_NE", [](const Curve& c) { return column(c, &CurvePoint::D_NE); })
      .def_property_readonly("D_TA", [](const Curve& c) { return column(c, &CurvePoint::D_TA); })
      .def_property_readonly("D_TE", [](const Curve& c) { return column(c, &CurvePoint::D_TE); })
      .def_property_readonly("P_N", [](const Curve& c) { return column(c, &CurvePoint::P_N); })
      .def_property_readonly("P_N_reaction",
                             [](const Curve& c) { return column(c, &CurvePoint::P_N_reaction); })
      .def_property_readonly("P_T", [](const Curve& c) { return column(c, &CurvePoint::P_T); })
      .def_property_readonly("energy_change",
                             [](const Curve& c) { return column(c, &CurvePoint::energy_change); })
      .def_property_readonly("in_dead_zone",
                             [](const Curve& c) { return column(c, &CurvePoint::in_dead_zone); })
      .def_property_readonly("admissible",
                             [](const Curve& c) { return column(c, &CurvePoint::admissible); })
      .def_property_readonly("failed",
                             [](const Curve& c) {
                               std::vector<Inequality> v;
                               for (const auto& p : c.points) v.push_back(p.failed);
                               return v;
                             })
      .def_property_readonly("status",
                             [](const Curve& c) {
                               std::vector<SolverStatus> v;
                               for (const auto& p : c.points) v.push_back(p.status);
                               return v;
                             })
      .def("__len__", [](const Curve& c) { return c.points.size(); });

  m.def(
      "normal_restitution_curve",
      [](const NormalCurveParameters& parameters, const std::vector<double>& speeds,
         const SolverOptions& options) {
        return Curve{parameters, normal_restitution_curve(parameters, speeds, options)};
      },
      py::arg("parameters"), py::arg("speeds"), py::arg("options") = SolverOptions{},
      py::call_guard<py::gil_scoped_release>(), doc::kNormalCurve);
  m.def(
      "tangential_curve",
      [](const TP& parameters, const std::vector<double>& D_TA, const SolverOptions& options) {
        return Curve{parameters, tangential_curve(parameters, D_TA, options)};
      },
      py::arg("parameters"), py::arg("D_TA"), py::arg("options") = SolverOptions{},
      py::call_guard<py::gil_scoped_release>(), doc::kTangentialCurve);
  m.def("equivalent_restitution", &equivalent_restitution, py::arg("parameters"),
        doc::kEquivalentRestitution);
  m.def("normal_curve_law", &normal_curve_law, py::arg("parameters"));
  m.def("tangential_curve_law", &tangential_curve_law, py::arg("parameters"));
  m.def(
      "point_mass_problem",
      [](double mass, double D_NA, std::optional<double> D_TA) {
        return D_TA ? point_mass_problem(mass, D_NA, *D_TA) : point_mass_problem(mass, D_NA);
      },
      py::arg("mass"), py::arg("D_NA"), py::arg("D_TA") = py::none(), doc::kPointMassProblem);
}

}  // namespace fremond::python
