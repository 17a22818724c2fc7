#pragma once
/// @file M⁻¹ applied to a sparse matrix through M's diagonal blocks (docs/sparse.md).
#include <Eigen/SparseCore>
#include <string>

#include "fremond/sparse/contact_problem.hpp"

namespace fremond::detail {

/// Contact columns grouped by contact: column 2i = W_N's column i, 2i + 1 = W_T's (only W_N's
/// columns when W_T has none).
SparseMatrix interleaved_jacobian(const SparseMatrix& W_N, const SparseMatrix& W_T);

/// M⁻¹ X. M's connected blocks (a block a body) of up to 64 rows are inverted densely, so M⁻¹ keeps
/// M's pattern and the product costs what its non-zeros cost; a larger block sends the whole of M
/// to a sparse Cholesky factorisation. Throws InvalidArgument(`name`, ...) unless every block is
/// positive definite, with the test validate(ImpactProblem) uses: a positive Cholesky pivot above
/// 1e-12 √max|M|.
SparseMatrix solve_mass(const SparseMatrix& M, const SparseMatrix& X,
                        const std::string& name = "M");

/// W = interleaved_jacobian(problem.W_N, problem.W_T) and X = M⁻¹ W, the problem's shapes validated
/// first (and M's blocks by solve_mass): what contact_form needs, W built once.
struct ContactJacobians {
  SparseMatrix W, X;
};
ContactJacobians contact_jacobians(const SparseImpactProblem& problem);

/// G = Wᵀ X and D_A = Wᵀ q̇_A + w, with W = interleaved_jacobian(...) and X = M⁻¹ W.
ContactProblem contact_form(const SparseImpactProblem& problem, const SparseMatrix& W,
                            const SparseMatrix& X);

}  // namespace fremond::detail
