#pragma once
/// @file An impact problem stored sparse (docs/sparse.md): the same data and meaning as
/// ImpactProblem (docs/concepts.md), for systems of many bodies and hundreds of contacts.
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace fremond {

/// Compressed-column storage, as Eigen and CHOLMOD keep it.
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// M (q̇_E − q̇_A) = W_N P_N + W_T P_T, with contact velocities D_N = W_Nᵀq̇ + w_N and
/// D_T = W_Tᵀq̇ + w_T, as in ImpactProblem. M is typically block diagonal (a block a body) and
/// each column of W has the few non-zeros of the one or two bodies its contact touches.
struct SparseImpactProblem {
  SparseMatrix M;          ///< n×n, symmetric positive definite.
  SparseMatrix W_N;        ///< n×c normal directions.
  SparseMatrix W_T;        ///< n×c tangential directions, or n×0: a frictionless problem.
  Eigen::VectorXd w_N;     ///< c, or empty: zero (fixed obstacles).
  Eigen::VectorXd w_T;     ///< c, or empty: zero.
  Eigen::VectorXd qdot_A;  ///< n, the velocity before the impact.

  int dofs() const { return static_cast<int>(M.rows()); }
  int contacts() const { return static_cast<int>(W_N.cols()); }
  bool has_tangential() const { return W_T.cols() > 0; }
};

/// Checks sizes, finiteness, symmetry and positive definiteness of M (each of its diagonal
/// blocks factorised; see contact_problem()). Throws InvalidArgument naming the member (`M`,
/// `W_N`, `W_T`, `w_N`, `w_T`, `qdot_A`) and the reason.
void validate(const SparseImpactProblem& problem);

}  // namespace fremond
