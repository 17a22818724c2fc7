#pragma once
/// @file Private helpers of the impact problem: the kinetic energy, and validate() split for the
/// callers that factorise M anyway.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/detail/cholesky.hpp"
#include "core/detail/sized_vector.hpp"
#include "core/detail/small_dense.hpp"
#include "fremond/core/impact_problem.hpp"

namespace fremond {

namespace detail {
/// ½ vᵀ M v. A hand loop for the stack-stored sizes, where Eigen's dynamic-size matrix-vector
/// product costs more in dispatch than in arithmetic.
template <int N>
double kinetic_energy(const MatT<N, N>& M, const VecT<N>& v) {
  if constexpr (N != Dynamic) {
    return with_size<N>(static_cast<int>(v.size()), [&](auto size) {
      return small_dense::half_quadratic_form<decltype(size)::value>(M, v);
    });
  } else {
    return 0.5 * v.dot(M * v);
  }
}

/// validate() without the positive-definiteness test, for callers that factorise M anyway.
template <int MaxDofs, int MaxContacts>
void validate_shapes(const ImpactProblemT<MaxDofs, MaxContacts>& problem);
/// validate_shapes' tests of q̇_A alone (its size, finite entries, a finite kinetic energy and
/// finite contact velocities), for a configuration (M, W, w) validated before: the same errors.
template <int MaxDofs, int MaxContacts>
void validate_velocity(const ImpactProblemT<MaxDofs, MaxContacts>& problem);
/// What a validated configuration (M, W, w) lets a new q̇_A through without computing its kinetic
/// energy and contact velocities: with q = max |q̇_A,i|, |q̇ᵀMq̇| ≤ q² Σ|M_ij| and
/// |Wⱼᵀq̇ + wⱼ| ≤ q Σᵢ|W_ij| + |wⱼ|; below 1e300 neither overflows (every partial sum is within
/// the same bound), so validate_velocity would pass. Beyond, it decides.
struct VelocityBounds {
  double m_abs_sum = std::numeric_limits<double>::infinity();  ///< Σ|M_ij|
  double w_col_sum = std::numeric_limits<double>::infinity();  ///< max over columns of Σᵢ|W_ij|
  double w_abs_max = std::numeric_limits<double>::infinity();  ///< max |w_N|, |w_T|

  template <int MaxDofs, int MaxContacts>
  explicit VelocityBounds(const ImpactProblemT<MaxDofs, MaxContacts>& pb);
  VelocityBounds() = default;

  /// True where v (of the configuration's size) is finite and plainly within the bounds.
  template <class Vec>
  bool admit(const Vec& v) const {
    double q = 0.0;
    bool finite = true;
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      const double a = std::fabs(v(i));
      finite = finite && a <= std::numeric_limits<double>::max();  // NaN fails too
      q = std::max(q, a);
    }
    constexpr double kLimit = 1e300;
    return finite && q <= 1e150 && q * q * m_abs_sum <= kLimit &&
           q * w_col_sum + w_abs_max <= kLimit;
  }
};

/// The positive-definiteness test of validate() on a Cholesky factorisation of M.
template <int MaxDofs>
void require_positive_definite(const MatT<MaxDofs, MaxDofs>& M, const CholeskyT<MaxDofs>& llt);
}  // namespace detail

}  // namespace fremond
