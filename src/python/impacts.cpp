// One impact: the law, the problem (NumPy arrays in), the solver's options, the result with its
// admissibility certificate (NumPy arrays out), and the problem file.
#include <algorithm>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "fremond/admissibility/admissibility.hpp"
#include "fremond/core/impact_problem.hpp"
#include "fremond/io/problem_file.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/laws/residual.hpp"
#include "fremond/solvers/impact_solver.hpp"
#include "fremond/solvers/solve_impact.hpp"
#include "python/bind_helpers.hpp"
#include "python/docstrings.hpp"

namespace fremond::python {

namespace {

// A coefficient from Python: one number for every contact, or one per contact.
using Coefficient = std::variant<double, std::vector<double>>;
PerContact per_contact(const Coefficient& c) {
  if (const double* v = std::get_if<double>(&c)) return PerContact(*v);
  return PerContact(std::get<std::vector<double>>(c));
}

// Potentials from Python: one shared, or one per contact. The law keeps clones.
using Potentials = std::variant<const Potential*, std::vector<const Potential*>>;
PerContactPotential per_contact(const Potentials& p) {
  PerContactPotential out;
  if (const auto* one = std::get_if<const Potential*>(&p)) {
    out.potentials.emplace_back((*one)->clone());
    return out;
  }
  for (const Potential* q : std::get<std::vector<const Potential*>>(p))
    out.potentials.emplace_back(q->clone());
  return out;
}

py::list potentials_list(const PerContactPotential& p) {
  py::list out;
  for (const auto& h : p.potentials) out.append(py::cast(h->clone()));
  return out;
}

}  // namespace

void bind_impacts(py::module_& m) {
  m.def(
      "law_names",
      [] {
        std::vector<std::string> names;
        for (std::string_view n : law_names()) names.emplace_back(n);
        return names;
      },
      "The names of every impact law, as the problem file's law.type spells them.");
  py::class_<ImpactLaw>(m, "ImpactLaw", doc::kImpactLaw)
      .def_static(
          "newton", [](const Coefficient& e) { return ImpactLaw::newton(per_contact(e)); },
          py::arg("e"))
      .def_static(
          "poisson", [](const Coefficient& e) { return ImpactLaw::poisson(per_contact(e)); },
          py::arg("e"))
      .def_static(
          "newton_coulomb",
          [](const Coefficient& e, const Coefficient& mu) {
            return ImpactLaw::newton_coulomb(per_contact(e), per_contact(mu));
          },
          py::arg("e"), py::arg("mu"))
      .def_static(
          "poisson_coulomb",
          [](const Coefficient& e, const Coefficient& mu) {
            return ImpactLaw::poisson_coulomb(per_contact(e), per_contact(mu));
          },
          py::arg("e"), py::arg("mu"))
      .def_static(
          "fremond",
          [](const Potentials& normal, const std::optional<Potentials>& tangential) {
            if (!tangential) return ImpactLaw::fremond(per_contact(normal));
            return ImpactLaw::fremond(per_contact(normal), per_contact(*tangential));
          },
          py::arg("normal"), py::arg("tangential") = py::none())
      .def_static(
          "fremond_coulomb",
          [](const Potentials& normal, const Coefficient& mu) {
            return ImpactLaw::fremond_coulomb(per_contact(normal), per_contact(mu));
          },
          py::arg("normal"), py::arg("mu"))
      .def_static(
          "from_json",
          [](const std::string& text, int contacts, const PotentialRegistry* registry) {
            return io::parse_law(text, contacts,
                                 registry ? *registry : PotentialRegistry::with_builtins());
          },
          py::arg("text"), py::arg("contacts") = 1, py::arg("registry") = nullptr,
          "Any law by the problem file's schema, e.g. '{\"type\": \"stronge_coulomb\", \"e\": 0.9, "
          "\"mu\": 1}', validated for `contacts` contacts.")
      // Each value is the law's own, None where the law has no such value (e for Frémond's): asked
      // of any law's type by the member's name, so a new law needs nothing here.
      .def_property_readonly("type", [](const ImpactLaw& l) { return std::string(l.name()); })
      .def_property_readonly("tangential",
                             [](const ImpactLaw& l) -> std::optional<TangentialLaw> {
                               return l.visit([](const auto& law) -> std::optional<TangentialLaw> {
                                 if constexpr (requires { law.tangential; }) return law.tangential;
                                 return std::nullopt;
                               });
                             })
      .def_property_readonly(
          "e",
          [](const ImpactLaw& l) -> std::optional<std::vector<double>> {
            return l.visit([](const auto& law) -> std::optional<std::vector<double>> {
              if constexpr (requires { law.e; }) return law.e.values;
              return std::nullopt;
            });
          })
      .def_property_readonly("mu",
                             [](const ImpactLaw& l) -> std::optional<std::vector<double>> {
                               if (!l.uses_coulomb()) return std::nullopt;
                               return l.visit([](const auto& law) { return law.mu.values; });
                             })
      .def_property_readonly("normal",
                             [](const ImpactLaw& l) -> std::optional<py::list> {
                               return l.visit([](const auto& law) -> std::optional<py::list> {
                                 if constexpr (requires { law.normal; })
                                   return potentials_list(law.normal);
                                 return std::nullopt;
                               });
                             })
      // Stronge's distributing law on coupled contacts: None for the other laws.
      .def_property_readonly(
          "eta",
          [](const ImpactLaw& l) -> std::optional<std::vector<double>> {
            return l.visit([](const auto& law) -> std::optional<std::vector<double>> {
              if constexpr (requires { law.eta; }) return law.eta.values;
              return std::nullopt;
            });
          })
      .def_property_readonly(
          "stiffness",
          [](const ImpactLaw& l) -> std::optional<std::vector<double>> {
            return l.visit([](const auto& law) -> std::optional<std::vector<double>> {
              if constexpr (requires { law.stiffness; }) return law.stiffness.values;
              return std::nullopt;
            });
          })
      .def_property_readonly("tangential_potential",
                             [](const ImpactLaw& l) -> std::optional<py::list> {
                               if (!l.has_tangential_potential()) return std::nullopt;
                               return l.visit([](const auto& law) -> std::optional<py::list> {
                                 if constexpr (requires { law.tangential_potential; })
                                   return potentials_list(law.tangential_potential);
                                 return std::nullopt;
                               });
                             })
      .def("is_fremond", [](const ImpactLaw& l) { return l.is<FremondLaw>(); })
      .def("dissipative", &ImpactLaw::dissipative)
      .def("has_friction", &ImpactLaw::has_friction)
      .def("has_phases", &ImpactLaw::has_phases)
      .def("uses_coulomb", &ImpactLaw::uses_coulomb)
      .def("has_tangential_potential", &ImpactLaw::has_tangential_potential)
      .def("validate", &ImpactLaw::validate, py::arg("contacts"), doc::kLawValidate)
      .def("describe", &ImpactLaw::describe)
      .def("__repr__", [](const ImpactLaw& l) { return "<fremond law " + l.describe() + ">"; });

  py::class_<ImpactProblem>(m, "ImpactProblem", doc::kImpactProblem)
      .def(py::init([](const MatrixX& M, const MatrixX& W_N, const VectorX& qdot_A,
                       const std::optional<MatrixX>& W_T, const std::optional<VectorX>& w_N,
                       const std::optional<VectorX>& w_T) {
             ImpactProblem p;
             p.M = M;
             p.W_N = W_N;
             p.qdot_A = qdot_A;
             p.W_T = W_T ? *W_T : MatrixX(M.rows(), 0);
             p.w_N = w_N ? *w_N : VectorX::Zero(W_N.cols());
             p.w_T = w_T ? *w_T : VectorX::Zero(p.W_T.cols());
             validate(p);
             return p;
           }),
           py::arg("M"), py::arg("W_N"), py::arg("qdot_A"), py::arg("W_T") = py::none(),
           py::arg("w_N") = py::none(), py::arg("w_T") = py::none())
      .def_readonly("M", &ImpactProblem::M)
      .def_readonly("W_N", &ImpactProblem::W_N)
      .def_readonly("W_T", &ImpactProblem::W_T)
      .def_readonly("w_N", &ImpactProblem::w_N)
      .def_readonly("w_T", &ImpactProblem::w_T)
      .def_readonly("qdot_A", &ImpactProblem::qdot_A)
      .def_property_readonly("dofs", &ImpactProblem::dofs)
      .def_property_readonly("contacts", &ImpactProblem::contacts)
      .def("has_tangential", &ImpactProblem::has_tangential)
      .def("__repr__", [](const ImpactProblem& p) {
        return "<fremond ImpactProblem n=" + std::to_string(p.dofs()) +
               " c=" + std::to_string(p.contacts()) + (p.has_tangential() ? "" : " frictionless") +
               ">";
      });

  py::class_<SolverOptions> opt(m, "SolverOptions", doc::kSolverOptions);
  def_keyword_init<SolverOptions>(opt);
  opt.def_readwrite("method", &SolverOptions::method)
      .def_readwrite("tolerance", &SolverOptions::tolerance)
      .def_readwrite("nlopt_tolerance", &SolverOptions::nlopt_tolerance)
      .def_readwrite("max_iterations", &SolverOptions::max_iterations)
      .def_readwrite("max_proximal_iterations", &SolverOptions::max_proximal_iterations)
      .def_readwrite("max_nlopt_evaluations", &SolverOptions::max_nlopt_evaluations)
      .def_readwrite("admissibility_tolerance", &SolverOptions::admissibility_tolerance)
      .def_readwrite("check_uniqueness", &SolverOptions::check_uniqueness)
      .def("is_valid", [](const SolverOptions& o) { return o.is_valid(); })
      .def("validate", &SolverOptions::validate)
      .def("__repr__", [](const SolverOptions& o) {
        return repr_of(o, "SolverOptions",
                       {"method", "tolerance", "nlopt_tolerance", "max_iterations",
                        "admissibility_tolerance", "check_uniqueness"});
      });

  py::class_<Attempt>(m, "Attempt", "One method the chain ran: method, start, status, residual.")
      .def_readonly("method", &Attempt::method)
      .def_readonly("start", &Attempt::start)
      .def_readonly("status", &Attempt::status)
      .def_readonly("residual", &Attempt::residual)
      .def("__repr__", [](const Attempt& a) {
        return repr_of(a, "Attempt", {"method", "start", "status", "residual"});
      });

  py::class_<SolverReport>(m, "SolverReport", doc::kSolverReport)
      .def_readonly("method", &SolverReport::method)
      .def_readonly("status", &SolverReport::status)
      .def_readonly("criterion", &SolverReport::criterion)
      .def_property_readonly("message",
                             [](const SolverReport& r) { return std::string(r.message); })
      .def_readonly("iterations", &SolverReport::iterations)
      .def_readonly("residual", &SolverReport::residual)
      .def_readonly("native_code", &SolverReport::native_code)
      .def_readonly("fallbacks", &SolverReport::fallbacks)
      .def_property_readonly("attempts",
                             [](const SolverReport& r) {
                               const int n = std::min(r.attempt_count, SolverReport::kMaxAttempts);
                               return std::vector<Attempt>(r.attempts.begin(),
                                                           r.attempts.begin() + n);
                             })
      .def_readonly("attempt_count", &SolverReport::attempt_count)
      .def("__repr__", [](const SolverReport& r) {
        return repr_of(r, "SolverReport", {"method", "status", "iterations", "residual"});
      });

  using Report = AdmissibilityReportT<Dynamic>;
  py::class_<Report>(m, "AdmissibilityReport", doc::kAdmissibility)
      .def_readonly("kinetic_energy_A", &Report::kinetic_energy_A)
      .def_readonly("energy_change", &Report::energy_change)
      .def_readonly("total", &Report::total)
      .def_readonly("per_contact", &Report::per_contact)
      .def_readonly("reaction", &Report::reaction)
      .def_readonly("dissipation", &Report::dissipation)
      .def_readonly("complementarity", &Report::complementarity)
      .def_readonly("penetration", &Report::penetration)
      .def_readonly("fenchel_young_gap", &Report::fenchel_young_gap)
      .def_readonly("tolerance", &Report::tolerance)
      .def_readonly("admissible", &Report::admissible)
      .def_readonly("failed", &Report::failed)
      .def_readonly("failed_contact", &Report::failed_contact)
      .def_readonly("violation", &Report::violation)
      .def("__bool__", [](const Report& r) { return r.admissible; })
      .def("__repr__", [](const Report& r) {
        return repr_of(r, "AdmissibilityReport",
                       {"admissible", "failed", "total", "energy_change"});
      });

  py::class_<ImpactResult>(m, "ImpactResult", doc::kImpactResult)
      .def_readonly("qdot_E", &ImpactResult::qdot_E)
      .def_readonly("P_N", &ImpactResult::P_N)
      .def_readonly("P_T", &ImpactResult::P_T)
      .def_readonly("D_NA", &ImpactResult::D_NA)
      .def_readonly("D_TA", &ImpactResult::D_TA)
      .def_readonly("D_NE", &ImpactResult::D_NE)
      .def_readonly("D_TE", &ImpactResult::D_TE)
      .def_readonly("P_N_reaction", &ImpactResult::P_N_reaction)
      .def_readonly("has_phases", &ImpactResult::has_phases)
      .def_readonly("P_NC", &ImpactResult::P_NC)
      .def_readonly("P_TC", &ImpactResult::P_TC)
      .def_readonly("D_NC", &ImpactResult::D_NC)
      .def_readonly("D_TC", &ImpactResult::D_TC)
      .def_readonly("qdot_C", &ImpactResult::qdot_C)
      .def_readonly("takes_part", &ImpactResult::takes_part)
      .def_readonly("energy_change", &ImpactResult::energy_change)
      .def_readonly("unique", &ImpactResult::unique)
      .def_readonly("solutions_found", &ImpactResult::solutions_found)
      .def_readonly("admissibility", &ImpactResult::admissibility)
      .def_readonly("solver", &ImpactResult::solver)
      .def("ok", &ImpactResult::ok)
      .def("__repr__", [](const ImpactResult& r) {
        return repr_of(r, "ImpactResult",
                       {"qdot_E", "P_N", "P_T", "energy_change", "admissibility"});
      });

  m.def("solve_impact",
        py::overload_cast<const ImpactProblem&, const ImpactLaw&, const SolverOptions&>(
            &solve_impact<Dynamic, Dynamic>),
        py::arg("problem"), py::arg("law"), py::arg("options") = SolverOptions{},
        py::call_guard<py::gil_scoped_release>(), doc::kSolveImpact);
  py::class_<ImpactSolver>(m, "ImpactSolver", doc::kImpactSolver)
      .def(py::init<const ImpactProblem&, ImpactLaw, const SolverOptions&>(), py::arg("problem"),
           py::arg("law"), py::arg("options") = SolverOptions{})
      .def(
          "solve",
          [](ImpactSolver& s, const Eigen::VectorXd& qdot_A) -> ImpactResult {
            py::gil_scoped_release release;  // a law's Python potentials take it back
            return s.solve(qdot_A);
          },
          py::arg("qdot_A"), "Solves for the velocity before the impact; returns the answer.")
      .def(
          "solve",
          [](ImpactSolver& s) -> ImpactResult {
            py::gil_scoped_release release;
            return s.solve();
          },
          "Solves for the problem's current qdot_A.")
      .def(
          "update",
          [](ImpactSolver& s, const Eigen::MatrixXd& M, const Eigen::MatrixXd& W_N,
             const Eigen::MatrixXd& W_T, const Eigen::VectorXd& w_N,
             const Eigen::VectorXd& w_T) { s.update(M, W_N, W_T, w_N, w_T); },
          py::arg("M"), py::arg("W_N"), py::arg("W_T"), py::arg("w_N") = Eigen::VectorXd(),
          py::arg("w_T") = Eigen::VectorXd(),
          "A new configuration of the same sizes (W_T with no column: frictionless); qdot_A "
          "kept.")
      .def("update_law", &ImpactSolver::update_law, py::arg("law"),
           "Another law for the same contacts.")
      // Copies: a view would change under the caller at the next solve or update.
      .def_property_readonly("problem", [](const ImpactSolver& s) { return s.problem(); })
      .def_property_readonly("law", [](const ImpactSolver& s) { return s.law(); })
      .def_property_readonly("options", [](const ImpactSolver& s) { return s.options(); })
      .def_property_readonly(
          "result", [](const ImpactSolver& s) { return s.result(); }, "The last answer.");
  m.def("solve_impact_all", &solve_impact_all, py::arg("problem"), py::arg("law"),
        py::arg("options") = SolverOptions{}, py::call_guard<py::gil_scoped_release>(),
        doc::kSolveImpactAll);
  m.def("check_admissibility", &check_admissibility<Dynamic, Dynamic>, py::arg("problem"),
        py::arg("law"), py::arg("result"), py::arg("options") = SolverOptions{},
        py::call_guard<py::gil_scoped_release>(), doc::kCheckAdmissibility);
  m.def("law_residual", &law_residual<Dynamic, Dynamic>, py::arg("problem"), py::arg("law"),
        py::arg("result"), py::call_guard<py::gil_scoped_release>(), doc::kLawResidual);

  m.def(
      "parse_problem_file",
      [](const std::string& text, const PotentialRegistry* registry) {
        io::ProblemFile f =
            io::parse_problem_file(text, registry ? *registry : PotentialRegistry::with_builtins());
        return py::make_tuple(std::move(f.problem), std::move(f.law));
      },
      py::arg("text"), py::arg("registry") = nullptr, doc::kParseProblem);
  m.def("result_to_json", &io::result_to_json<Dynamic, Dynamic>, py::arg("result"),
        py::arg("indent") = -1, doc::kResultToJson);
}

}  // namespace fremond::python
