#pragma once
/// @file One impact problem (docs/concepts.md): M (q̇_E − q̇_A) = W_N P_N + W_T P_T.
#include <Eigen/Core>

#include "fremond/core/types.hpp"

namespace fremond {

/// The data of one impact: mass matrix, contact Jacobians (one column a contact), the obstacles'
/// velocity terms and the velocity before the impact. Contact velocities are
/// D_N = W_Nᵀ q̇ + w_N, D_T = W_Tᵀ q̇ + w_T. Without tangential rows (W_T with no columns) the
/// problem is frictionless and P_T is zero.
///
/// MaxDofs/MaxContacts bound the sizes; finite bounds keep everything on the stack.
template <int MaxDofs, int MaxContacts>
struct ImpactProblemT {
  using Vec = VecT<MaxDofs>;
  using Mat = MatT<MaxDofs, MaxDofs>;
  using Jac = MatT<MaxDofs, MaxContacts>;
  using CVec = VecT<MaxContacts>;
  static constexpr int kMaxDofs = MaxDofs;
  static constexpr int kMaxContacts = MaxContacts;

  Mat M;       ///< n×n, symmetric positive definite.
  Jac W_N;     ///< n×c normal directions.
  Jac W_T;     ///< n×c tangential directions, or n×0 for a frictionless problem.
  CVec w_N;    ///< c, zero for fixed obstacles (may be left empty: zero).
  CVec w_T;    ///< c (may be left empty: zero).
  Vec qdot_A;  ///< n, the velocity before the impact.

  int dofs() const { return static_cast<int>(M.rows()); }
  int contacts() const { return static_cast<int>(W_N.cols()); }
  bool has_tangential() const { return W_T.cols() > 0; }
};

using ImpactProblem = ImpactProblemT<Dynamic, Dynamic>;
using SmallImpactProblem = ImpactProblemT<kSmallDofs, kSmallContacts>;

/// Checks sizes, finiteness, symmetry and positive definiteness of M. Throws InvalidArgument naming
/// the member (`M`, `W_N`, `W_T`, `w_N`, `w_T`, `qdot_A`) and the reason.
template <int MaxDofs, int MaxContacts>
void validate(const ImpactProblemT<MaxDofs, MaxContacts>& problem);

/// Copies a problem into the stack-stored small form; throws InvalidArgument if it does not fit.
SmallImpactProblem to_small(const ImpactProblem& problem);
/// Copies a small problem into the heap-stored form.
ImpactProblem to_dynamic(const SmallImpactProblem& problem);
/// True when the problem fits the small form.
bool fits_small(const ImpactProblem& problem);

}  // namespace fremond
