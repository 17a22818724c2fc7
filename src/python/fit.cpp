// Laws against measurements (docs/measurements.md): measured impacts, predict, fit_law, fit_laws.
// Options are keyword arguments; results are objects with the C++ fields, parameters also as
// dicts by name.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fremond/core/error.hpp"
#include "fremond/fit/fit_law.hpp"
#include "fremond/fit/predict.hpp"
#include "fremond/io/measurements.hpp"
#include "python/bind_helpers.hpp"

namespace fremond::python {

namespace {

FitOptions options_of(const std::string& loss, double loss_scale, int global_evaluations,
                      int local_evaluations, double xtol_rel, const std::string& uncertainty,
                      int bootstrap_samples, bool absolute_sigma, int folds, std::uint64_t seed,
                      const std::map<std::string, double>& fixed,
                      const std::map<std::string, std::pair<double, double>>& bounds,
                      const std::optional<SolverOptions>& solver, int threads) {
  FitOptions o;
  o.loss = fit_loss_from_string(loss);
  o.loss_scale = loss_scale;
  o.global_evaluations = global_evaluations;
  o.local_evaluations = local_evaluations;
  o.xtol_rel = xtol_rel;
  o.uncertainty = fit_uncertainty_from_string(uncertainty);
  o.bootstrap_samples = bootstrap_samples;
  o.absolute_sigma = absolute_sigma;
  o.folds = folds;
  o.seed = seed;
  o.fixed = fixed;
  o.bounds = bounds;
  if (solver) o.solver = *solver;
  o.batch.threads = threads;
  o.validate();
  return o;
}

py::dict by_name(const std::vector<std::string>& names, const VectorX& v) {
  py::dict d;
  for (std::size_t i = 0; i < names.size(); ++i)
    d[py::str(names[i])] = v(static_cast<Eigen::Index>(i));
  return d;
}

LawFamily family_of(const std::string& name) {
  return law_family_from_string(name);
}

}  // namespace

void bind_fit(py::module_& m) {
  py::class_<MeasuredImpact>(m, "MeasuredImpact",
                             "An impact problem and the velocity measured after it "
                             "(docs/measurements.md).")
      .def(py::init([](const ImpactProblem& problem, const VectorX& qdot_E,
                       const std::optional<std::vector<bool>>& mask,
                       const std::optional<VectorX>& sigma) {
             MeasuredImpact mi = measured_impact(problem, qdot_E);
             if (mask) mi.mask = *mask;
             if (sigma) mi.sigma = *sigma;
             validate(mi);
             return mi;
           }),
           py::arg("problem"), py::arg("qdot_E"), py::arg("mask") = py::none(),
           py::arg("sigma") = py::none())
      .def_readonly("problem", &MeasuredImpact::problem)
      .def_readonly("qdot_E", &MeasuredImpact::qdot_E)
      .def_readonly("mask", &MeasuredImpact::mask)
      .def_readonly("sigma", &MeasuredImpact::sigma)
      .def("measured", &MeasuredImpact::measured)
      .def("__repr__", [](const MeasuredImpact& mi) {
        return "<fremond MeasuredImpact n=" + std::to_string(mi.problem.dofs()) +
               " measured=" + std::to_string(mi.measured()) + ">";
      });

  m.def(
      "parse_measurements", [](const std::string& text) { return io::parse_measurements(text); },
      py::arg("text"),
      "The measured-impact file from its JSON text; ValueError names the row and key "
      "(impacts[3].qdot_E: ...).");

  m.def("law_families", [] {
    std::vector<std::string> out;
    for (const LawFamily f : law_families()) out.emplace_back(to_string(f));
    return out;
  });
  m.def(
      "fitted_parameters",
      [](const std::string& family) { return fitted_parameters(family_of(family)); },
      py::arg("family"));
  m.def(
      "make_law",
      [](const std::string& family, const std::map<std::string, double>& values) {
        return make_law(family_of(family), values);
      },
      py::arg("family"), py::arg("values"),
      "A law family's law at the named values, e.g. make_law('newton_coulomb', {'e': 0.9, 'mu': "
      "0.3}).");

  py::class_<Prediction>(m, "Prediction", "A law's predictions beside the measurements.")
      .def_readonly("qdot_E", &Prediction::qdot_E)
      .def_readonly("residuals", &Prediction::residuals)
      .def_readonly("status", &Prediction::status)
      .def_readonly("rms", &Prediction::rms)
      .def_readonly("measured", &Prediction::measured)
      .def_readonly("failed", &Prediction::failed)
      .def("__repr__", [](const Prediction& p) {
        return "<fremond Prediction rms=" + std::to_string(p.rms) +
               " measured=" + std::to_string(p.measured) + ">";
      });
  m.def(
      "predict",
      [](const std::vector<MeasuredImpact>& impacts, const ImpactLaw& law,
         const std::optional<SolverOptions>& options, int threads) {
        BatchOptions batch;
        batch.threads = threads;
        return predict(impacts, law, options ? *options : fit_solver_options(), batch);
      },
      py::arg("impacts"), py::arg("law"), py::arg("options") = py::none(), py::arg("threads") = 0,
      py::call_guard<py::gil_scoped_release>(),
      R"(Each measured impact solved under `law`: Prediction with qdot_E (per impact), residuals
((predicted − measured)/sigma, NaN where not measured), status, rms (in sigmas), measured, failed.)");

  py::class_<FitResult>(m, "FitResult", "What a fit found (docs/measurements.md#fit).")
      .def_property_readonly("family",
                             [](const FitResult& r) { return std::string(to_string(r.family)); })
      .def_readonly("law", &FitResult::law)
      .def_readonly("names", &FitResult::names)
      .def_readonly("values", &FitResult::values)
      .def_readonly("uncertainties", &FitResult::uncertainties)
      .def_property_readonly("parameters",
                             [](const FitResult& r) { return by_name(r.names, r.values); })
      .def_property_readonly("parameter_uncertainties",
                             [](const FitResult& r) { return by_name(r.names, r.uncertainties); })
      .def_readonly("objective", &FitResult::objective)
      .def_readonly("training_rms", &FitResult::training_rms)
      .def_readonly("heldout_rms", &FitResult::heldout_rms)
      .def_readonly("measured", &FitResult::measured)
      .def_readonly("failed_solves", &FitResult::failed_solves)
      .def_readonly("global_status", &FitResult::global_status)
      .def_readonly("local_status", &FitResult::local_status)
      .def_readonly("status", &FitResult::status)
      .def_readonly("evaluations", &FitResult::evaluations)
      .def_readonly("fold_evaluations", &FitResult::fold_evaluations)
      .def_readonly("seconds", &FitResult::seconds)
      .def("__repr__", [](const FitResult& r) {
        return "<fremond FitResult " + r.law.describe() +
               " training_rms=" + std::to_string(r.training_rms) +
               " heldout_rms=" + std::to_string(r.heldout_rms) + ">";
      });

  const auto fit_one = [](const std::vector<MeasuredImpact>& impacts, const std::string& family,
                          const std::string& loss, double loss_scale, int global_evaluations,
                          int local_evaluations, double xtol_rel, const std::string& uncertainty,
                          int bootstrap_samples, bool absolute_sigma, int folds, std::uint64_t seed,
                          const std::map<std::string, double>& fixed,
                          const std::map<std::string, std::pair<double, double>>& bounds,
                          const std::optional<SolverOptions>& solver, int threads) {
    const FitOptions o =
        options_of(loss, loss_scale, global_evaluations, local_evaluations, xtol_rel, uncertainty,
                   bootstrap_samples, absolute_sigma, folds, seed, fixed, bounds, solver, threads);
    py::gil_scoped_release release;
    return fit_law(impacts, family_of(family), o);
  };
  const auto fit_many = [](const std::vector<MeasuredImpact>& impacts,
                           const std::vector<std::string>& families, const std::string& loss,
                           double loss_scale, int global_evaluations, int local_evaluations,
                           double xtol_rel, const std::string& uncertainty, int bootstrap_samples,
                           bool absolute_sigma, int folds, std::uint64_t seed,
                           const std::map<std::string, double>& fixed,
                           const std::map<std::string, std::pair<double, double>>& bounds,
                           const std::optional<SolverOptions>& solver, int threads) {
    const FitOptions o =
        options_of(loss, loss_scale, global_evaluations, local_evaluations, xtol_rel, uncertainty,
                   bootstrap_samples, absolute_sigma, folds, seed, fixed, bounds, solver, threads);
    std::vector<LawFamily> fams;
    for (const auto& f : families) fams.push_back(family_of(f));
    py::gil_scoped_release release;
    return fit_laws(impacts, fams, o);
  };
  const FitOptions d;
#define FREMOND_FIT_KEYWORDS                                                                   \
  py::arg("loss") = "least_squares", py::arg("loss_scale") = d.loss_scale,                     \
  py::arg("global_evaluations") = d.global_evaluations,                                        \
  py::arg("local_evaluations") = d.local_evaluations, py::arg("xtol_rel") = d.xtol_rel,        \
  py::arg("uncertainty") = "gauss_newton", py::arg("bootstrap_samples") = d.bootstrap_samples, \
  py::arg("absolute_sigma") = d.absolute_sigma, py::arg("folds") = d.folds,                    \
  py::arg("seed") = d.seed, py::arg("fixed") = std::map<std::string, double>{},                \
  py::arg("bounds") = std::map<std::string, std::pair<double, double>>{},                      \
  py::arg("solver") = py::none(), py::arg("threads") = 0
  m.def("fit_law", fit_one, py::arg("impacts"), py::arg("family"), py::kw_only(),
        FREMOND_FIT_KEYWORDS,
        R"(The family's parameters that best predict the measured impacts (GN_DIRECT_L, then
LN_BOBYQA), their uncertainties (gauss_newton or bootstrap), and the held-out RMS of k-fold
cross-validation (folds=0: none). family: one of law_families(); fixed: {name: value} held;
bounds: {name: (lower, upper)}. Returns a FitResult.)");
  m.def("fit_laws", fit_many, py::arg("impacts"), py::arg("families"), py::kw_only(),
        FREMOND_FIT_KEYWORDS, "fit_law for each family, ranked by held-out RMS (smallest first).");
#undef FREMOND_FIT_KEYWORDS
}

}  // namespace fremond::python
