// Sparse problems (fremond/sparse/, docs/sparse.md) and Siconos's friction-contact files. Sparse
// matrices cross as scipy.sparse matrices (compressed columns).
#include <pybind11/eigen.h>

#include <fstream>
#include <sstream>

#include "fremond/core/error.hpp"
#include "fremond/io/siconos_file.hpp"
#include "fremond/sparse/sparse_solver.hpp"
#include "python/bind_helpers.hpp"

namespace fremond::python {

void bind_sparse(py::module_& m) {
  py::class_<SparseImpactProblem>(
      m, "SparseImpactProblem",
      "An impact problem stored sparse: M (n x n), W_N, W_T (n x c, W_T n x 0 without friction) "
      "as scipy.sparse matrices, w_N, w_T (c, or empty) and qdot_A (n) (docs/sparse.md).")
      .def(py::init([](const SparseMatrix& M, const SparseMatrix& W_N,
                       std::optional<SparseMatrix> W_T, const Eigen::VectorXd& qdot_A,
                       std::optional<Eigen::VectorXd> w_N, std::optional<Eigen::VectorXd> w_T) {
             SparseImpactProblem p;
             p.M = M;
             p.W_N = W_N;
             p.W_T = W_T ? *W_T : SparseMatrix(M.rows(), 0);
             p.qdot_A = qdot_A;
             if (w_N) p.w_N = *w_N;
             if (w_T) p.w_T = *w_T;
             validate(p);
             return p;
           }),
           py::arg("M"), py::arg("W_N"), py::arg("W_T") = py::none(), py::arg("qdot_A"),
           py::arg("w_N") = py::none(), py::arg("w_T") = py::none())
      .def_readonly("M", &SparseImpactProblem::M)
      .def_readonly("W_N", &SparseImpactProblem::W_N)
      .def_readonly("W_T", &SparseImpactProblem::W_T)
      .def_readonly("w_N", &SparseImpactProblem::w_N)
      .def_readonly("w_T", &SparseImpactProblem::w_T)
      .def_readonly("qdot_A", &SparseImpactProblem::qdot_A)
      .def("dofs", &SparseImpactProblem::dofs)
      .def("contacts", &SparseImpactProblem::contacts);

  py::class_<ContactProblem>(
      m, "ContactProblem",
      "An impact in contact coordinates: D_E = D_A + G P, rows grouped by contact (normal, "
      "tangent) (docs/sparse.md).")
      .def(py::init([](const SparseMatrix& G, const Eigen::VectorXd& D_A, bool tangential,
                       double G_rounding, double D_A_rounding) {
             ContactProblem p{G, D_A, tangential, G_rounding, D_A_rounding};
             validate(p);
             return p;
           }),
           py::arg("G"), py::arg("D_A"), py::arg("tangential") = true, py::arg("G_rounding") = 0.0,
           py::arg("D_A_rounding") = 0.0)
      .def_readonly("G", &ContactProblem::G)
      .def_readonly("D_A", &ContactProblem::D_A)
      .def_readonly("tangential", &ContactProblem::tangential)
      .def_readonly("G_rounding", &ContactProblem::G_rounding,
                    "How well G's numbers are known, relative to each (5e-6 for 6 printed "
                    "significant digits; 0: exact in double precision)")
      .def_readonly("D_A_rounding", &ContactProblem::D_A_rounding,
                    "How well D_A's numbers are known, relative to each")
      .def("contacts", &ContactProblem::contacts);

  auto options = py::class_<SparseSolverOptions>(
      m, "SparseSolverOptions",
      "Options of the sparse solver: tolerance (1e-10), max_sweeps (100000), "
      "admissibility_tolerance (1e-9), newton_polish (True), acceleration (True).");
  def_keyword_init<SparseSolverOptions>(options);
  options.def_readwrite("tolerance", &SparseSolverOptions::tolerance)
      .def_readwrite("max_sweeps", &SparseSolverOptions::max_sweeps)
      .def_readwrite("admissibility_tolerance", &SparseSolverOptions::admissibility_tolerance)
      .def_readwrite("newton_polish", &SparseSolverOptions::newton_polish)
      .def_readwrite("acceleration", &SparseSolverOptions::acceleration)
      .def("validate", &SparseSolverOptions::validate);

  m.def("contact_problem", &contact_problem, py::arg("problem"),
        "G = W^T M^-1 W and D_A of a sparse impact problem.");
  m.def("solve_sparse",
        py::overload_cast<const SparseImpactProblem&, const ImpactLaw&, const SparseSolverOptions&,
                          const ImpactResult*>(&solve_impact),
        py::arg("problem"), py::arg("law"), py::arg("options") = SparseSolverOptions{},
        py::arg("start") = nullptr, py::call_guard<py::gil_scoped_release>(),
        "Newton's law (with or without Coulomb) on a sparse problem by nonsmooth Gauss-Seidel; "
        "`start`: a previous result of the same contacts (a warm start).");
  m.def("solve_contact_problem", &solve_contact_problem, py::arg("problem"), py::arg("law"),
        py::arg("options") = SparseSolverOptions{}, py::arg("start") = nullptr,
        py::call_guard<py::gil_scoped_release>(),
        "The same in contact coordinates (the result's qdot_E is empty).");
  m.def("contact_residual", &contact_residual, py::arg("problem"), py::arg("law"),
        py::arg("result"), "The law's residual of a result, relative to the velocity scale.");

  py::class_<io::SiconosProblem> siconos(
      m, "SiconosProblem",
      "A Siconos 2-D friction-contact file: `form` 'local' (contact: a ContactProblem) or "
      "'global' (impact: a SparseImpactProblem), mu per contact, law() Newton + Coulomb e = 0.");
  siconos
      .def_property_readonly("form",
                             [](const io::SiconosProblem& p) {
                               return p.form == io::SiconosProblem::Form::local ? "local"
                                                                                : "global";
                             })
      .def_readonly("contact", &io::SiconosProblem::contact)
      .def_readonly("impact", &io::SiconosProblem::impact)
      .def_readonly("mu", &io::SiconosProblem::mu)
      .def("law", &io::SiconosProblem::law)
      .def("contacts", &io::SiconosProblem::contacts);
  m.def(
      "read_siconos_file",
      [](const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw InvalidArgument(path, "cannot open");
        std::stringstream text;
        text << in.rdbuf();
        try {
          return io::parse_siconos_file(text.str());
        } catch (const InvalidArgument& e) {
          throw InvalidArgument(path + ": " + e.name(),
                                std::string(e.what()).substr(e.name().size() + 2));
        }
      },
      py::arg("path"), "Reads a Siconos 2-D friction-contact file (docs/sparse.md).");
}

}  // namespace fremond::python
