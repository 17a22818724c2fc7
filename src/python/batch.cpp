// Many impacts at once (solve_batch): a list of problems, or NumPy arrays of shape (N, ...) in and
// out, solved on every core with the interpreter's lock released.
#include <pybind11/numpy.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "fremond/core/error.hpp"
#include "fremond/solvers/solve_batch.hpp"
#include "python/bind_helpers.hpp"

namespace fremond::python {

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A per-problem operand of shape `one` (shared by every problem) or (N, *one).
struct Operand {
  const char* name;
  Array a;
  bool shared = true;

  // Checks the shape against `one` (the trailing dimensions) and the count N; throws naming it.
  void check(const std::vector<py::ssize_t>& one, py::ssize_t count) {
    const auto nd = static_cast<std::size_t>(a.ndim());
    shared = nd == one.size();
    bool ok = shared || nd == one.size() + 1;
    for (std::size_t k = 0; ok && k < one.size(); ++k)
      ok = a.shape(static_cast<py::ssize_t>(nd - one.size() + k)) == one[k];
    if (!ok)
      throw InvalidArgument(name, "needs shape " + shape_text(one) + " or (N, ...) of it, got " +
                                      shape_text({a.shape(), a.shape() + a.ndim()}));
    if (!shared && a.shape(0) != count)
      throw InvalidArgument(
          name, "has " + std::to_string(a.shape(0)) + " problems, qdot_A " + std::to_string(count));
  }
  static std::string shape_text(const std::vector<py::ssize_t>& shape) {
    std::string s = "(";
    for (std::size_t k = 0; k < shape.size(); ++k) s += (k ? ", " : "") + std::to_string(shape[k]);
    return s + (shape.size() == 1 ? ",)" : ")");
  }
  // The i-th problem's data, row-major.
  const double* at(py::ssize_t i) const {
    return a.data() + (shared ? 0 : i * (a.size() / a.shape(0)));
  }
};

// Row-major data (NumPy's) as an Eigen matrix.
auto matrix(const double* p, int rows, int cols) {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  return Eigen::Map<const RowMajor>(p, rows, cols);
}

py::dict solve_arrays(const Array& M, const Array& W_N, const Array& qdot_A, const ImpactLaw& law,
                      const std::optional<Array>& W_T, const std::optional<Array>& w_N,
                      const std::optional<Array>& w_T, const SolverOptions& options, int threads) {
  if (qdot_A.ndim() != 2)
    throw InvalidArgument("qdot_A", "needs shape (N, n): one velocity per problem, got " +
                                        std::to_string(qdot_A.ndim()) + " dimensions");
  const py::ssize_t n = qdot_A.shape(1);
  Operand m{"M", M}, wn{"W_N", W_N};
  const py::ssize_t count = qdot_A.shape(0);
  m.check({n, n}, count);
  const py::ssize_t c = W_N.ndim() >= 2 ? W_N.shape(W_N.ndim() - 1) : -1;
  wn.check({n, c}, count);
  std::optional<Operand> wt, vn, vt;
  if (W_T) (wt = Operand{"W_T", *W_T})->check({n, c}, count);
  if (w_N) (vn = Operand{"w_N", *w_N})->check({c}, count);
  if (w_T) (vt = Operand{"w_T", *w_T})->check({c}, count);
  const int ni = static_cast<int>(n), ci = static_cast<int>(c);
  auto out2 = [&](py::ssize_t cols) { return Array({count, cols}); };
  Array qdot_E = out2(n), P_N = out2(c), P_T = out2(c), D_NE = out2(c), D_TE = out2(c);
  Array energy({count}), residual({count});
  py::array_t<std::uint8_t> status({count});
  py::array_t<bool> admissible({count}), unique({count});
  // Solved in the small form where the shape fits it (no heap memory per problem or result), as
  // solve_impact would: the answers are the same to the last bit.
  // Every operand but qdot_A shared: one configuration, prepared once (validated and factored),
  // and each velocity solved on it (solve_batch of a prepared solver), the same answers.
  const bool one_configuration = count > 0 && m.shared && wn.shared && (!wt || wt->shared) &&
                                 (!vn || vn->shared) && (!vt || vt->shared);
  auto run = [&](auto problem_type) {
    using Problem = decltype(problem_type);
    auto problem = [&](py::ssize_t i) {
      Problem p;
      p.M = matrix(m.at(i), ni, ni);
      p.W_N = matrix(wn.at(i), ni, ci);
      if (wt)
        p.W_T = matrix(wt->at(i), ni, ci);
      else
        p.W_T.resize(ni, 0);
      p.w_N = vn ? VectorX(Eigen::Map<const VectorX>(vn->at(i), ci)) : VectorX::Zero(ci);
      p.w_T = vt ? VectorX(Eigen::Map<const VectorX>(vt->at(i), ci)) : VectorX::Zero(p.W_T.cols());
      p.qdot_A = Eigen::Map<const VectorX>(qdot_A.data() + i * n, ni);
      return p;
    };
    BatchOptions batch;
    batch.threads = threads;
    auto row = [](Array& a, py::ssize_t i) { return a.mutable_data() + i * a.shape(1); };
    if (one_configuration) {
      // Prepared at rest, a velocity always valid for a valid configuration, so that each
      // velocity is judged, and named, by its own index.
      Problem p = problem(0);
      p.qdot_A.setZero(ni);
      const ImpactSolverT<Problem::kMaxDofs, Problem::kMaxContacts> solver(p, law, options);
      // The (N, n) row-major array is the n × N column-major matrix of one velocity a column, and
      // the answers' n × N and c × N columns are the (N, n) and (N, c) arrays returned.
      BatchAnswers a;
      solve_batch(solver, Eigen::Map<const Eigen::MatrixXd>(qdot_A.data(), ni, count), a, batch);
      auto copy = [](const auto& from, auto& to) {
        std::copy(from.data(), from.data() + from.size(), to.mutable_data());
      };
      copy(a.qdot_E, qdot_E);
      copy(a.P_N, P_N);
      copy(a.P_T, P_T);
      copy(a.D_NE, D_NE);
      copy(a.D_TE, D_TE);
      copy(a.energy_change, energy);
      copy(a.residual, residual);
      for (py::ssize_t i = 0; i < count; ++i) {
        const auto k = static_cast<std::size_t>(i);
        status.mutable_data()[i] = static_cast<std::uint8_t>(a.status[k]);
        admissible.mutable_data()[i] = a.admissible[k] != 0;
        unique.mutable_data()[i] = a.unique[k] != 0;
      }
      return;
    }
    std::vector<Problem> problems;
    problems.reserve(static_cast<std::size_t>(count));
    for (py::ssize_t i = 0; i < count; ++i) problems.push_back(problem(i));
    const auto results = solve_batch(std::span<const Problem>(problems), law, options, batch);
    // A row the answer has not (a method the law does not support leaves it empty) is NaN.
    auto put = [&](Array& a, py::ssize_t i, const auto& v) {
      Eigen::Map<VectorX> to(row(a, i), a.shape(1));
      if (v.size() == to.size())
        to = v;
      else
        to.setConstant(std::numeric_limits<double>::quiet_NaN());
    };
    for (py::ssize_t i = 0; i < count; ++i) {
      const auto& r = results[static_cast<std::size_t>(i)];
      put(qdot_E, i, r.qdot_E);
      put(P_N, i, r.P_N);
      put(P_T, i, r.P_T);
      put(D_NE, i, r.D_NE);
      put(D_TE, i, r.D_TE);
      energy.mutable_data()[i] = r.energy_change;
      residual.mutable_data()[i] = r.solver.residual;
      status.mutable_data()[i] = static_cast<std::uint8_t>(r.solver.status);
      admissible.mutable_data()[i] = r.admissibility.admissible;
      unique.mutable_data()[i] = r.unique;
    }
  };
  {
    py::gil_scoped_release release;  // the output arrays' buffers are written, not resized
    if (ni <= kSmallDofs && ci <= kSmallContacts)
      run(SmallImpactProblem{});
    else
      run(ImpactProblem{});
  }
  py::dict d;
  d["qdot_E"] = qdot_E;
  d["P_N"] = P_N;
  d["P_T"] = P_T;
  d["D_NE"] = D_NE;
  d["D_TE"] = D_TE;
  d["energy_change"] = energy;
  d["residual"] = residual;
  d["status"] = status;
  d["admissible"] = admissible;
  d["unique"] = unique;
  return d;
}

}  // namespace

void bind_batch(py::module_& m) {
  m.def(
      "solve_batch",
      [](const std::vector<ImpactProblem>& problems, const ImpactLaw& law,
         const SolverOptions& options, int threads) {
        BatchOptions batch;
        batch.threads = threads;
        return solve_batch(problems, law, options, batch);
      },
      py::arg("problems"), py::arg("law"), py::arg("options") = SolverOptions{},
      py::arg("threads") = 0, py::call_guard<py::gil_scoped_release>(),
      R"(Solves a list of problems under one law on every core (threads=0: one per core); returns
the list of results, result i equal to solve_impact(problems[i], law, options) to the last bit.
An invalid problem raises ValueError naming it by index (problems[17].M: ...) and nothing is
returned.)");
  m.def("solve_batch_arrays", &solve_arrays, py::arg("M"), py::arg("W_N"), py::arg("qdot_A"),
        py::arg("law"), py::arg("W_T") = py::none(), py::arg("w_N") = py::none(),
        py::arg("w_T") = py::none(), py::arg("options") = SolverOptions{}, py::arg("threads") = 0,
        R"(Many problems of one shape from NumPy arrays: qdot_A of shape (N, n); M of shape (n, n)
shared by every problem or (N, n, n); W_N and W_T of shape (n, c) or (N, n, c); w_N and w_T of
shape (c,) or (N, c). Solved on every core with the interpreter's lock released (threads=0: one
per core). Returns a dict of arrays: qdot_E (N, n); P_N, P_T, D_NE, D_TE (N, c); energy_change,
residual (N,); status (N,) as SolverStatus codes (fremond.SolverStatus(int(code)));
admissible, unique (N,) booleans. Entry i equals solve_impact on problem i to the last bit.
Where only qdot_A has N rows (one configuration, many velocities), the configuration is validated
and factored once (a prepared solver) and a bad velocity is named qdot_A[i][k]; otherwise a bad
problem is named problems[i].member.)");
}

}  // namespace fremond::python
