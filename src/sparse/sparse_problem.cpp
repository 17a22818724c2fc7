// Checks of the sparse impact problem and of its contact form, and the Delassus matrix
// G = Wᵀ M⁻¹ W (docs/sparse.md).
#include <algorithm>
#include <cmath>
#include <string>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"
#include "fremond/sparse/contact_problem.hpp"
#include "sparse/detail/mass_inverse.hpp"

namespace fremond {

namespace {

std::string dims(Eigen::Index r, Eigen::Index c) {
  return std::to_string(r) + "x" + std::to_string(c);
}

void require_finite(const std::string& name, const SparseMatrix& A) {
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (!std::isfinite(it.value()))
        throw InvalidArgument(name, "must hold finite numbers; [" + std::to_string(it.row()) +
                                        "][" + std::to_string(j) +
                                        "] = " + detail::format_number(it.value()));
}

void require_finite(const std::string& name, const Eigen::VectorXd& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!std::isfinite(v(i)))
      throw InvalidArgument(name, "must hold finite numbers; [" + std::to_string(i) +
                                      "] = " + detail::format_number(v(i)));
}

double largest(const SparseMatrix& A) {
  double m = 0.0;
  for (Eigen::Index k = 0; k < A.nonZeros(); ++k) m = std::max(m, std::fabs(A.valuePtr()[k]));
  return m;
}

// |A − Aᵀ| ≤ rel · max|A|, else InvalidArgument naming the worst pair.
void require_symmetric(const std::string& name, const SparseMatrix& A, double rel) {
  const SparseMatrix At = A.transpose();
  const SparseMatrix D = A - At;
  const double limit = rel * largest(A);
  for (int j = 0; j < D.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(D, j); it; ++it)
      if (std::fabs(it.value()) > limit) {
        // Named upper triangle first, as the dense problem's check names it.
        const Eigen::Index i = std::min<Eigen::Index>(it.row(), j);
        const Eigen::Index k = std::max<Eigen::Index>(it.row(), j);
        throw InvalidArgument(name, "must be symmetric; " + name + "[" + std::to_string(i) + "][" +
                                        std::to_string(k) +
                                        "] = " + detail::format_number(A.coeff(i, k)) + " but " +
                                        name + "[" + std::to_string(k) + "][" + std::to_string(i) +
                                        "] = " + detail::format_number(A.coeff(k, i)));
      }
}

void validate_shapes(const SparseImpactProblem& pb) {
  const auto n = pb.M.rows();
  if (n == 0) throw InvalidArgument("M", "the mass matrix is empty");
  if (pb.M.cols() != n) throw InvalidArgument("M", "must be square, got " + dims(n, pb.M.cols()));
  require_finite("M", pb.M);
  require_symmetric("M", pb.M, 1e-12);
  const auto c = pb.W_N.cols();
  if (pb.W_N.rows() != n)
    throw InvalidArgument("W_N", "must have " + std::to_string(n) +
                                     " rows (one per degree of freedom), got " +
                                     dims(pb.W_N.rows(), c));
  require_finite("W_N", pb.W_N);
  if (pb.W_T.cols() != 0) {
    if (pb.W_T.rows() != n || pb.W_T.cols() != c)
      throw InvalidArgument(
          "W_T", "must be " + dims(n, c) + " like W_N, got " + dims(pb.W_T.rows(), pb.W_T.cols()));
    require_finite("W_T", pb.W_T);
  }
  for (const auto& [name, w] :
       {std::pair<const char*, const Eigen::VectorXd*>{"w_N", &pb.w_N}, {"w_T", &pb.w_T}}) {
    if (w->size() != 0 && w->size() != c)
      throw InvalidArgument(name, "must have " + std::to_string(c) +
                                      " entries (one per contact), got " +
                                      std::to_string(w->size()));
    require_finite(name, *w);
  }
  if (pb.w_T.size() != 0 && pb.W_T.cols() == 0) throw InvalidArgument("w_T", "given without W_T");
  if (pb.qdot_A.size() != n)
    throw InvalidArgument("qdot_A", "must have " + std::to_string(n) + " entries, got " +
                                        std::to_string(pb.qdot_A.size()));
  require_finite("qdot_A", pb.qdot_A);
}

}  // namespace

void validate(const SparseImpactProblem& problem) {
  validate_shapes(problem);
  const SparseMatrix none(problem.dofs(), 0);
  (void)detail::solve_mass(problem.M, none);
}

detail::ContactJacobians detail::contact_jacobians(const SparseImpactProblem& problem) {
  validate_shapes(problem);
  ContactJacobians j;
  j.W = interleaved_jacobian(problem.W_N, problem.W_T);
  j.X = solve_mass(problem.M, j.W);
  return j;
}

SparseMatrix inverse_mass_times_jacobian(const SparseImpactProblem& problem) {
  return detail::contact_jacobians(problem).X;
}

ContactProblem detail::contact_form(const SparseImpactProblem& problem, const SparseMatrix& W,
                                    const SparseMatrix& X) {
  ContactProblem out;
  out.tangential = problem.has_tangential();
  out.G = (W.transpose() * X).pruned();
  out.D_A = W.transpose() * problem.qdot_A;
  const int c = problem.contacts(), step = out.tangential ? 2 : 1;
  for (int i = 0; i < c; ++i) {
    if (problem.w_N.size()) out.D_A(step * i) += problem.w_N(i);
    if (problem.w_T.size()) out.D_A(step * i + 1) += problem.w_T(i);
  }
  for (Eigen::Index j = 0; j < out.D_A.size(); ++j)
    if (!std::isfinite(out.D_A(j)))
      throw InvalidArgument("qdot_A",
                            "the contact velocity of row " + std::to_string(j) +
                                " overflows double precision; express the problem in other units");
  // The sweeps divide by each contact's own W_Nᵀ M⁻¹ W_N, and read every entry of G.
  for (int k = 0; k < out.G.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(out.G, k); it; ++it)
      if (!std::isfinite(it.value()))
        throw InvalidArgument(it.col() % step == 0 ? "W_N" : "W_T",
                              "contact " + std::to_string(it.col() / step) +
                                  ": Wᵀ M⁻¹ W overflows double precision; express the problem in "
                                  "other units");
  for (int i = 0; i < c; ++i)
    if (const double a = out.G.coeff(step * i, step * i); !(a > 0.0))
      throw InvalidArgument("W_N",
                            "contact " + std::to_string(i) +
                                ": its column gives W_Nᵀ M⁻¹ W_N = " + detail::format_number(a) +
                                " (a zero column, or one below double precision): no "
                                "percussion moves the contact");
  return out;
}

ContactProblem contact_problem(const SparseImpactProblem& problem) {
  const detail::ContactJacobians j = detail::contact_jacobians(problem);
  return detail::contact_form(problem, j.W, j.X);
}

void validate(const ContactProblem& problem) {
  const auto rows = problem.D_A.size();
  if (rows == 0) throw InvalidArgument("D_A", "the problem has no contact");
  if (problem.tangential && rows % 2 != 0)
    throw InvalidArgument(
        "D_A", "must have two rows per contact (normal, tangential), got " + std::to_string(rows));
  if (problem.G.rows() != rows || problem.G.cols() != rows)
    throw InvalidArgument("G", "must be " + dims(rows, rows) + " like D_A, got " +
                                   dims(problem.G.rows(), problem.G.cols()));
  require_finite("G", problem.G);
  require_finite("D_A", problem.D_A);
  require_symmetric("G", problem.G, 1e-6);
  for (const auto& [name, value] : {std::pair{"G_rounding", problem.G_rounding},
                                    std::pair{"D_A_rounding", problem.D_A_rounding}})
    if (!(value >= 0.0 && value <= 1e-2))
      throw InvalidArgument(name,
                            "must lie in [0, 1e-2] (the relative rounding of the numbers "
                            "as given), got " +
                                detail::format_number(value));
  const int step = problem.tangential ? 2 : 1;
  for (int i = 0; i < problem.contacts(); ++i) {
    const double a = problem.G.coeff(step * i, step * i);
    const double d = problem.tangential ? problem.G.coeff(step * i + 1, step * i + 1) : 0.0;
    const double b = problem.tangential ? problem.G.coeff(step * i, step * i + 1) : 0.0;
    if (!(a > 0.0) || d < 0.0 || a * d - b * b < -1e-12 * (a * d + b * b))
      throw InvalidArgument("G", "contact " + std::to_string(i) +
                                     ": its diagonal block must be positive semidefinite with a "
                                     "positive normal entry, got G[" +
                                     std::to_string(step * i) + "][" + std::to_string(step * i) +
                                     "] = " + detail::format_number(a));
  }
}

}  // namespace fremond
