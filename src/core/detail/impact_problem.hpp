#pragma once
/// @file Private helpers of the impact problem: the kinetic energy, and validate() split for the
/// callers that factorise M anyway.
#include "core/detail/cholesky.hpp"
#include "core/detail/small_dense.hpp"
#include "fremond/core/impact_problem.hpp"

namespace fremond {

namespace detail {
/// ½ vᵀ M v. A hand loop for the stack-stored sizes, where Eigen's dynamic-size matrix-vector
/// product costs more in dispatch than in arithmetic.
template <int N>
double kinetic_energy(const MatT<N, N>& M, const VecT<N>& v) {
  if constexpr (N != Dynamic) {
    return small_dense::half_quadratic_form(M, v);
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
/// The positive-definiteness test of validate() on a Cholesky factorisation of M.
template <int MaxDofs>
void require_positive_definite(const MatT<MaxDofs, MaxDofs>& M, const CholeskyT<MaxDofs>& llt);
}  // namespace detail

}  // namespace fremond
