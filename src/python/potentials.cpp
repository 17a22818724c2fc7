// Potentials: the shared interface bound once on the base class, the built-in kinds as thin
// subclasses, and a trampoline so that a Python class can be a potential (docs/laws.md: users add
// their own).
#include <memory>
#include <string>
#include <utility>

#include "fremond/potentials/absolute_value.hpp"
#include "fremond/potentials/conformance.hpp"
#include "fremond/potentials/deadzone_power.hpp"
#include "fremond/potentials/indicator.hpp"
#include "fremond/potentials/potential.hpp"
#include "fremond/potentials/power.hpp"
#include "fremond/potentials/registry.hpp"
#include "fremond/potentials/sum.hpp"
#include "python/bind_helpers.hpp"
#include "python/docstrings.hpp"

namespace fremond::python {

namespace {

Interval to_interval(const py::handle& h) {
  if (py::isinstance<Interval>(h)) return h.cast<Interval>();
  const auto t = h.cast<std::pair<double, double>>();
  return {t.first, t.second};
}

// The Python side of a potential: each protected hook calls the Python method of the same name.
// Capabilities follow from the hooks the Python class defines, as for CallablePotential.
class PyPotential : public Potential {
 public:
  PyPotential() = default;

 protected:
  std::string_view do_name() const override {
    py::gil_scoped_acquire gil;
    if (py::function f = py::get_override(this, "do_name")) {
      name_ = f().cast<std::string>();
    } else {
      name_ = py::type::of(py::cast(this, py::return_value_policy::reference))
                  .attr("__name__")
                  .cast<std::string>();
    }
    return name_;  // a view into this object: valid while the potential lives
  }

  // Potentials are values with fixed parameters, so the copy shares the Python object: the C++
  // side holds a reference that keeps it alive (and takes the GIL to do so).
  PotentialPtr do_clone() const override;

  PotentialCapabilities do_capabilities() const override {
    py::gil_scoped_acquire gil;
    if (py::function f = py::get_override(this, "do_capabilities"))
      return f().cast<PotentialCapabilities>();
    PotentialCapabilities c;
    c.subdifferential = static_cast<bool>(py::get_override(this, "do_subdifferential"));
    c.prox = static_cast<bool>(py::get_override(this, "do_prox")) || c.subdifferential;
    c.prox_derivative = c.prox;
    c.conjugate = static_cast<bool>(py::get_override(this, "do_conjugate"));
    return c;
  }

  double do_value(double z) const override {
    PYBIND11_OVERRIDE_PURE(double, Potential, do_value, z);
  }
  double do_subgradient(double z) const override {
    PYBIND11_OVERRIDE_PURE(double, Potential, do_subgradient, z);
  }
  Interval do_subdifferential(double z) const override {
    py::gil_scoped_acquire gil;
    if (py::function f = py::get_override(this, "do_subdifferential")) return to_interval(f(z));
    return Potential::do_subdifferential(z);
  }
  double do_prox(double x, double tau, double* dprox) const override {
    {
      py::gil_scoped_acquire gil;
      if (py::function f = py::get_override(this, "do_prox")) {
        const auto [y, dy] = f(x, tau).cast<std::pair<double, double>>();
        if (dprox) *dprox = dy;
        return y;
      }
    }
    return Potential::do_prox(x, tau, dprox);  // bisection on do_subdifferential
  }
  double do_conjugate(double s) const override {
    PYBIND11_OVERRIDE(double, Potential, do_conjugate, s);
  }
  std::string do_describe() const override {
    PYBIND11_OVERRIDE(std::string, Potential, do_describe);
  }

 private:
  mutable std::string name_;
};

// What clone() of a Python potential returns: a C++ potential forwarding to the Python object
// through its public interface (which calls back into its hooks).
class PythonPotentialRef final : public Potential {
 public:
  explicit PythonPotentialRef(py::object object) {
    py::gil_scoped_acquire gil;
    object_ = std::move(object);
    target_ = object_.cast<const Potential*>();
  }
  ~PythonPotentialRef() override {
    py::gil_scoped_acquire gil;
    object_ = py::object();
  }

 protected:
  std::string_view do_name() const override { return target_->name(); }
  PotentialPtr do_clone() const override {
    py::gil_scoped_acquire gil;
    return std::make_unique<PythonPotentialRef>(object_);
  }
  PotentialCapabilities do_capabilities() const override { return target_->capabilities(); }
  double do_value(double z) const override { return target_->value(z); }
  double do_subgradient(double z) const override { return target_->subgradient(z); }
  Interval do_subdifferential(double z) const override { return target_->subdifferential(z); }
  double do_prox(double x, double tau, double* dprox) const override {
    return target_->prox(x, tau, dprox);
  }
  double do_conjugate(double s) const override { return target_->conjugate(s); }
  std::string do_describe() const override { return target_->describe(); }

 private:
  py::object object_;
  const Potential* target_ = nullptr;
};

PotentialPtr PyPotential::do_clone() const {
  py::gil_scoped_acquire gil;
  return std::make_unique<PythonPotentialRef>(py::cast(this, py::return_value_policy::reference));
}

std::string potential_repr(const Potential& p) {
  return "<fremond potential " + p.describe() + ">";
}

}  // namespace

void bind_potentials(py::module_& m) {
  py::class_<Interval>(m, "Interval", doc::kInterval)
      .def(py::init<double, double>(), py::arg("lo"), py::arg("hi"))
      .def_readwrite("lo", &Interval::lo)
      .def_readwrite("hi", &Interval::hi)
      .def("is_empty", &Interval::is_empty)
      .def("contains", &Interval::contains, py::arg("s"), py::arg("tol") = 0.0)
      .def("distance", &Interval::distance, py::arg("s"))
      .def("__iter__", [](const Interval& i) { return py::iter(py::make_tuple(i.lo, i.hi)); })
      .def("__repr__", [](const Interval& i) {
        return "Interval(" + py::repr(py::float_(i.lo)).cast<std::string>() + ", " +
               py::repr(py::float_(i.hi)).cast<std::string>() + ")";
      });

  py::class_<PotentialCapabilities> caps(m, "PotentialCapabilities", doc::kCapabilities);
  def_keyword_init<PotentialCapabilities>(caps);
  caps.def_readwrite("prox", &PotentialCapabilities::prox)
      .def_readwrite("prox_derivative", &PotentialCapabilities::prox_derivative)
      .def_readwrite("subdifferential", &PotentialCapabilities::subdifferential)
      .def_readwrite("conjugate", &PotentialCapabilities::conjugate)
      .def_readwrite("quadratic", &PotentialCapabilities::quadratic)
      .def("__repr__", [](const PotentialCapabilities& c) {
        return repr_of(c, "PotentialCapabilities",
                       {"prox", "prox_derivative", "subdifferential", "conjugate", "quadratic"});
      });

  // The shared interface, bound once: every kind below inherits it.
  py::class_<Potential, PyPotential>(m, "Potential", doc::kPotential)
      .def(py::init<>())
      .def_property_readonly("name", [](const Potential& p) { return std::string(p.name()); })
      .def("capabilities", &Potential::capabilities)
      .def("value", &Potential::value, py::arg("z"), doc::kValue)
      .def("subgradient", &Potential::subgradient, py::arg("z"), doc::kSubgradient)
      .def("subdifferential", &Potential::subdifferential, py::arg("z"), doc::kSubdifferential)
      .def(
          "prox",
          [](const Potential& p, double x, double tau, bool derivative) -> py::object {
            double d = 0.0;
            const double y = p.prox(x, tau, derivative ? &d : nullptr);
            if (derivative) return py::make_tuple(y, d);
            return py::float_(y);
          },
          py::arg("x"), py::arg("tau"), py::arg("derivative") = false, doc::kProx)
      .def("conjugate", &Potential::conjugate, py::arg("s"), doc::kConjugate)
      .def("fenchel_young_gap", &Potential::fenchel_young_gap, py::arg("z"), py::arg("s"),
           doc::kFenchelYoung)
      .def("describe", &Potential::describe, doc::kDescribe)
      .def("clone", &Potential::clone, doc::kClone)
      .def("__repr__", &potential_repr)
      .def(
          "__add__", [](const Potential& f, const Potential& g) { return f + g; },
          py::is_operator())
      .def(
          "__rmul__", [](const Potential& f, double a) { return a * f; }, py::is_operator())
      .def(
          "__mul__", [](const Potential& f, double a) { return a * f; }, py::is_operator());

  py::class_<PowerPotential, Potential>(m, "PowerPotential", doc::kPower)
      .def(py::init<double, double>(), py::arg("k"), py::arg("p"))
      .def_property_readonly("k", &PowerPotential::k)
      .def_property_readonly("p", &PowerPotential::p);
  py::class_<DeadZonePowerPotential, Potential>(m, "DeadZonePowerPotential", doc::kDeadZone)
      .def(py::init<double, double, double>(), py::arg("k"), py::arg("q"), py::arg("r"))
      .def_property_readonly("k", &DeadZonePowerPotential::k)
      .def_property_readonly("q", &DeadZonePowerPotential::q)
      .def_property_readonly("r", &DeadZonePowerPotential::r);
  py::class_<AbsoluteValuePotential, Potential>(m, "AbsoluteValuePotential", doc::kAbsoluteValue)
      .def(py::init<double>(), py::arg("b"))
      .def_property_readonly("bound", &AbsoluteValuePotential::bound);
  py::class_<IndicatorPotential, Potential>(m, "IndicatorPotential", doc::kIndicator)
      .def(py::init<bool>(), py::arg("nonpositive") = false)
      .def_property_readonly("nonpositive", &IndicatorPotential::nonpositive);
  py::class_<SumPotential, Potential>(m, "SumPotential", doc::kSum)
      .def(py::init<const Potential&, const Potential&>(), py::arg("f"), py::arg("g"));
  py::class_<ScaledPotential, Potential>(m, "ScaledPotential", doc::kScaled)
      .def(py::init<double, const Potential&>(), py::arg("alpha"), py::arg("f"))
      .def_property_readonly("alpha", &ScaledPotential::alpha);

  py::class_<PotentialRegistry>(m, "PotentialRegistry", doc::kRegistry)
      .def(py::init<>())
      .def_static("with_builtins", &PotentialRegistry::with_builtins)
      .def(
          "add",
          [](PotentialRegistry& r, const std::string& name, py::function make,
             std::vector<std::string> required, PotentialParameters optional,
             std::string description) {
            PotentialKind kind;
            kind.required = std::move(required);
            kind.optional = std::move(optional);
            kind.description = std::move(description);
            // The registry owns what make returns: a clone, which for a Python potential keeps
            // the Python object alive.
            kind.make = [make](const PotentialParameters& params) -> PotentialPtr {
              py::gil_scoped_acquire gil;
              return make(params).cast<const Potential&>().clone();
            };
            r.add(name, std::move(kind));
          },
          py::arg("name"), py::arg("make"), py::arg("required") = std::vector<std::string>{},
          py::arg("optional") = PotentialParameters{}, py::arg("description") = "",
          doc::kRegistryAdd)
      .def("contains", &PotentialRegistry::contains, py::arg("name"))
      .def("make", &PotentialRegistry::make, py::arg("name"), py::arg("params"),
           py::arg("where") = "potential", doc::kRegistryMake)
      .def("names", &PotentialRegistry::names)
      .def(
          "description",
          [](const PotentialRegistry& r, const std::string& name) {
            return r.kind(name).description;
          },
          py::arg("name"));

  py::class_<ConformanceOptions> copt(m, "ConformanceOptions", doc::kConformanceOptions);
  def_keyword_init<ConformanceOptions>(copt);
  copt.def_readwrite("range", &ConformanceOptions::range)
      .def_readwrite("samples", &ConformanceOptions::samples)
      .def_readwrite("taus", &ConformanceOptions::taus)
      .def_readwrite("tolerance", &ConformanceOptions::tolerance)
      .def_readwrite("seed", &ConformanceOptions::seed);
  py::class_<ConformanceReport>(m, "ConformanceReport", doc::kConformanceReport)
      .def_readonly("ok", &ConformanceReport::ok)
      .def_readonly("failures", &ConformanceReport::failures)
      .def_readonly("checks", &ConformanceReport::checks)
      .def_readonly("max_fenchel_young_gap_at_prox",
                    &ConformanceReport::max_fenchel_young_gap_at_prox)
      .def_readonly("max_moreau_error", &ConformanceReport::max_moreau_error)
      .def_readonly("max_prox_optimality", &ConformanceReport::max_prox_optimality)
      .def("summary", &ConformanceReport::summary)
      .def("__bool__", [](const ConformanceReport& r) { return r.ok; })
      .def("__repr__", [](const ConformanceReport& r) { return r.summary(); });
  m.def("check_potential", &check_potential, py::arg("potential"),
        py::arg("options") = ConformanceOptions{}, py::call_guard<py::gil_scoped_release>(),
        doc::kCheckPotential);
}

}  // namespace fremond::python
