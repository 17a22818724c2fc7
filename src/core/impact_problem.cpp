#include "fremond/core/impact_problem.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <string>

#include "core/detail/impact_problem.hpp"
#include "core/detail/sized_vector.hpp"
#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"

namespace fremond {

namespace {
template <class Derived>
void require_all_finite(const char* name, const Eigen::MatrixBase<Derived>& m) {
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      if (!std::isfinite(m(i, j)))
        throw InvalidArgument(std::string(name) + "[" + std::to_string(i) +
                                  (m.cols() > 1 ? "][" + std::to_string(j) : "") + "]",
                              "must be a finite number, got " + detail::format_number(m(i, j)));
}
std::string dims(Eigen::Index r, Eigen::Index c) {
  return std::to_string(r) + "x" + std::to_string(c);
}

/// x − x over every entry: 0 where all are finite, NaN as soon as one is ∞ or NaN. The problem's
/// matrices and vectors are plain objects, stored packed (outer stride = rows).
template <class Derived>
double non_finite_probe(const Eigen::PlainObjectBase<Derived>& m) {
  const double* const d = m.data();
  double probe = 0.0;
  for (Eigen::Index k = 0; k < m.size(); ++k) probe += d[k] - d[k];
  return probe;
}

/// W's column `col` (n entries from `col`) dotted with q, plus w: a contact velocity as the
/// validation computes it, in index order (K: n where fixed), the same sum in the quick test and
/// in the test that names the failure, so that both judge an overflow alike.
template <int K>
double validation_dot(const double* col, const double* q, Eigen::Index n, double w) {
  if constexpr (K != Eigen::Dynamic) n = K;
  double d = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) d += col[k] * q[k];
  return d + w;
}

/// plainly_valid's tests of q̇_A, for a configuration already validated: its size, its entries
/// finite, and the kinetic energy and contact velocities it makes finite. K: the dofs where fixed.
template <int K, int N, int C>
bool plainly_valid_velocity_sized(const ImpactProblemT<N, C>& pb) {
  const Eigen::Index n = pb.M.rows(), c = pb.W_N.cols();
  if (pb.qdot_A.size() != n || non_finite_probe(pb.qdot_A) != 0.0) return false;
  // The same expressions as the tests below, so that an overflow is judged identically.
  if (!std::isfinite(detail::kinetic_energy(pb.M, pb.qdot_A))) return false;
  const double* const q = pb.qdot_A.data();
  const bool has_WT = pb.W_T.cols() != 0;
  for (Eigen::Index i = 0; i < c; ++i) {
    if (!std::isfinite(
            validation_dot<K>(pb.W_N.data() + n * i, q, n, pb.w_N.size() ? pb.w_N(i) : 0.0)))
      return false;
    if (has_WT && !std::isfinite(validation_dot<K>(pb.W_T.data() + n * i, q, n,
                                                   pb.w_T.size() ? pb.w_T(i) : 0.0)))
      return false;
  }
  return true;
}
template <int N, int C>
bool plainly_valid_velocity(const ImpactProblemT<N, C>& pb) {
  return detail::with_size<N>(static_cast<int>(pb.M.rows()), [&](auto size) {
    return plainly_valid_velocity_sized<decltype(size)::value>(pb);
  });
}

/// True only when validate_shapes' tests below all pass, in one pass over the data without
/// building any message: every solve validates its problem, and on a planar body the test by test
/// path (each its own loop) costs as much as a third of the law's own solve. False sends the caller
/// through those tests, which then name the first failure; false where they would all pass costs
/// only time. K: the dofs where fixed (with_size), so that the loops over M unroll.
template <int K, int N, int C>
bool plainly_valid_sized(const ImpactProblemT<N, C>& pb) {
  const Eigen::Index n = K == Eigen::Dynamic ? pb.M.rows() : K, c = pb.W_N.cols();
  if (n == 0 || pb.M.rows() != n || pb.M.cols() != n || pb.W_N.rows() != n || pb.qdot_A.size() != n)
    return false;
  const bool has_WT = pb.W_T.size() != 0 || pb.W_T.cols() != 0;
  if (has_WT && (pb.W_T.rows() != n || pb.W_T.cols() != c)) return false;
  if (pb.w_N.size() != 0 && pb.w_N.size() != c) return false;
  if (pb.w_T.size() != 0 && (pb.w_T.size() != c || pb.W_T.cols() == 0)) return false;
  const double probe = non_finite_probe(pb.M) + non_finite_probe(pb.W_N) +
                       non_finite_probe(pb.W_T) + non_finite_probe(pb.w_N) +
                       non_finite_probe(pb.w_T);
  if (probe != 0.0) return false;
  double scale = 0.0;
  const double* const m = pb.M.data();
  for (Eigen::Index k = 0; k < n * n; ++k) scale = std::max(scale, std::fabs(m[k]));
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i + 1; j < n; ++j)
      if (std::fabs(m[i + n * j] - m[j + n * i]) > 1e-12 * scale) return false;
  return plainly_valid_velocity_sized<K>(pb);
}
template <int N, int C>
bool plainly_valid(const ImpactProblemT<N, C>& pb) {
  return detail::with_size<N>(static_cast<int>(pb.M.rows()), [&](auto size) {
    return plainly_valid_sized<decltype(size)::value>(pb);
  });
}
}  // namespace

template <int N, int C>
void validate(const ImpactProblemT<N, C>& pb) {
  detail::validate_shapes(pb);
  const detail::CholeskyT<N> llt(pb.M);
  detail::require_positive_definite(pb.M, llt);
}

template <int N, int C>
void detail::validate_shapes(const ImpactProblemT<N, C>& pb) {
  if (plainly_valid(pb)) return;
  const auto n = pb.M.rows();
  if (n == 0) throw InvalidArgument("M", "the mass matrix is empty");
  if (pb.M.cols() != n) throw InvalidArgument("M", "must be square, got " + dims(n, pb.M.cols()));
  require_all_finite("M", pb.M);
  const double scale = pb.M.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i + 1; j < n; ++j)
      if (std::fabs(pb.M(i, j) - pb.M(j, i)) > 1e-12 * scale)
        throw InvalidArgument(
            "M", "must be symmetric; M[" + std::to_string(i) + "][" + std::to_string(j) +
                     "] = " + detail::format_number(pb.M(i, j)) + " but M[" + std::to_string(j) +
                     "][" + std::to_string(i) + "] = " + detail::format_number(pb.M(j, i)));
  if (pb.W_N.rows() != n)
    throw InvalidArgument("W_N", "must have " + std::to_string(n) +
                                     " rows (one per degree of "
                                     "freedom), got " +
                                     dims(pb.W_N.rows(), pb.W_N.cols()));
  const auto c = pb.W_N.cols();
  require_all_finite("W_N", pb.W_N);
  if (pb.W_T.size() != 0 || pb.W_T.cols() != 0) {
    if (pb.W_T.rows() != n || pb.W_T.cols() != c)
      throw InvalidArgument(
          "W_T", "must be " + dims(n, c) + " like W_N, got " + dims(pb.W_T.rows(), pb.W_T.cols()));
    require_all_finite("W_T", pb.W_T);
  }
  if (pb.w_N.size() != 0 && pb.w_N.size() != c)
    throw InvalidArgument("w_N", "must have " + std::to_string(c) +
                                     " entries (one per contact), got " +
                                     std::to_string(pb.w_N.size()));
  require_all_finite("w_N", pb.w_N);
  if (pb.w_T.size() != 0 && pb.w_T.size() != c)
    throw InvalidArgument("w_T", "must have " + std::to_string(c) +
                                     " entries (one per contact), got " +
                                     std::to_string(pb.w_T.size()));
  if (pb.w_T.size() != 0 && pb.W_T.cols() == 0) throw InvalidArgument("w_T", "given without W_T");
  require_all_finite("w_T", pb.w_T);
  detail::validate_velocity(pb);
}

template <int N, int C>
void detail::validate_velocity(const ImpactProblemT<N, C>& pb) {
  const auto n = pb.M.rows(), c = pb.W_N.cols();
  if (plainly_valid_velocity(pb)) return;
  if (pb.qdot_A.size() != n)
    throw InvalidArgument("qdot_A", "must have " + std::to_string(n) + " entries, got " +
                                        std::to_string(pb.qdot_A.size()));
  require_all_finite("qdot_A", pb.qdot_A);
  // Every datum finite is not enough: the certificate compares energies (docs/concepts.md, eq. 9)
  // and every law reads the contact velocities D_A (docs/concepts.md). Where those overflow, no
  // answer can be certified in double precision (T_E − T_A would be ∞ − ∞); refuse, rather than
  // return a NaN energy.
  const double kinetic = detail::kinetic_energy(pb.M, pb.qdot_A);
  if (!std::isfinite(kinetic))
    throw InvalidArgument("qdot_A",
                          "the kinetic energy 1/2 qdot_A^T M qdot_A overflows double "
                          "precision (max |qdot_A| = " +
                              detail::format_number(pb.qdot_A.cwiseAbs().maxCoeff()) +
                              ", max |M| = " + detail::format_number(pb.M.cwiseAbs().maxCoeff()) +
                              "); express the problem in other units");
  for (Eigen::Index i = 0; i < c; ++i) {
    const double dn = validation_dot<Eigen::Dynamic>(pb.W_N.data() + n * i, pb.qdot_A.data(), n,
                                                     pb.w_N.size() ? pb.w_N(i) : 0.0);
    if (!std::isfinite(dn))
      throw InvalidArgument("W_N", "contact " + std::to_string(i) +
                                       ": the normal velocity D_NA = W_N^T qdot_A + w_N overflows "
                                       "double precision; express the problem in other units");
    if (pb.W_T.cols() == 0) continue;
    const double dt = validation_dot<Eigen::Dynamic>(pb.W_T.data() + n * i, pb.qdot_A.data(), n,
                                                     pb.w_T.size() ? pb.w_T(i) : 0.0);
    if (!std::isfinite(dt))
      throw InvalidArgument("W_T", "contact " + std::to_string(i) +
                                       ": the tangential velocity D_TA = W_T^T qdot_A + w_T "
                                       "overflows double precision; express the problem in other "
                                       "units");
  }
}

template <int N>
void detail::require_positive_definite(const MatT<N, N>& M, const CholeskyT<N>& llt) {
  bool spd = llt.info() == Eigen::Success;
  if (spd) {  // a positive pivot that is rounding noise is not positive definite either
    const double scale = M.cwiseAbs().maxCoeff();
    spd = llt.matrixLLT().diagonal().minCoeff() > 1e-12 * std::sqrt(scale);
  }
  if (!spd) throw InvalidArgument("M", "must be positive definite (Cholesky factorisation failed)");
}

template void validate(const ImpactProblemT<Dynamic, Dynamic>&);
template void validate(const ImpactProblemT<kSmallDofs, kSmallContacts>&);
template void detail::validate_shapes(const ImpactProblemT<Dynamic, Dynamic>&);
template void detail::validate_shapes(const ImpactProblemT<kSmallDofs, kSmallContacts>&);
template <int N, int C>
detail::VelocityBounds::VelocityBounds(const ImpactProblemT<N, C>& pb) {
  m_abs_sum = pb.M.cwiseAbs().sum();
  w_col_sum = 0.0;
  w_abs_max = 0.0;
  for (Eigen::Index j = 0; j < pb.W_N.cols(); ++j) {
    w_col_sum = std::max(w_col_sum, pb.W_N.col(j).cwiseAbs().sum());
    if (pb.W_T.cols() != 0) w_col_sum = std::max(w_col_sum, pb.W_T.col(j).cwiseAbs().sum());
  }
  if (pb.w_N.size() != 0) w_abs_max = std::max(w_abs_max, pb.w_N.cwiseAbs().maxCoeff());
  if (pb.w_T.size() != 0) w_abs_max = std::max(w_abs_max, pb.w_T.cwiseAbs().maxCoeff());
}

template detail::VelocityBounds::VelocityBounds(const ImpactProblemT<Dynamic, Dynamic>&);
template detail::VelocityBounds::VelocityBounds(const ImpactProblemT<kSmallDofs, kSmallContacts>&);
template void detail::validate_velocity(const ImpactProblemT<Dynamic, Dynamic>&);
template void detail::validate_velocity(const ImpactProblemT<kSmallDofs, kSmallContacts>&);
template void detail::require_positive_definite(const MatT<Dynamic, Dynamic>&,
                                                const detail::CholeskyT<Dynamic>&);
template void detail::require_positive_definite(const MatT<kSmallDofs, kSmallDofs>&,
                                                const detail::CholeskyT<kSmallDofs>&);

bool fits_small(const ImpactProblem& pb) {
  return pb.M.rows() <= kSmallDofs && pb.M.cols() <= kSmallDofs && pb.W_N.rows() <= kSmallDofs &&
         pb.W_N.cols() <= kSmallContacts && pb.W_T.rows() <= kSmallDofs &&
         pb.W_T.cols() <= kSmallContacts && pb.w_N.size() <= kSmallContacts &&
         pb.w_T.size() <= kSmallContacts && pb.qdot_A.size() <= kSmallDofs;
}

SmallImpactProblem to_small(const ImpactProblem& pb) {
  if (!fits_small(pb))
    throw InvalidArgument("problem", "does not fit the small form (at most " +
                                         std::to_string(kSmallDofs) + " degrees of freedom and " +
                                         std::to_string(kSmallContacts) + " contacts)");
  SmallImpactProblem s;
  s.M = pb.M;
  s.W_N = pb.W_N;
  s.W_T = pb.W_T;
  s.w_N = pb.w_N;
  s.w_T = pb.w_T;
  s.qdot_A = pb.qdot_A;
  return s;
}

ImpactProblem to_dynamic(const SmallImpactProblem& s) {
  ImpactProblem pb;
  pb.M = s.M;
  pb.W_N = s.W_N;
  pb.W_T = s.W_T;
  pb.w_N = s.w_N;
  pb.w_T = s.w_T;
  pb.qdot_A = s.qdot_A;
  return pb;
}

}  // namespace fremond
