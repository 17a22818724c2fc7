#pragma once
/// @file An impact problem in contact coordinates (docs/sparse.md): D_E = D_A + G P, the local form
/// of Siconos's friction-contact problems.
#include <Eigen/Core>

#include "fremond/sparse/sparse_problem.hpp"

namespace fremond {

/// The impact in contact coordinates only: with G = Wᵀ M⁻¹ W (the Delassus matrix) and D_A the
/// contact velocities before the impact, the velocities after are D_E = D_A + G P. Rows are
/// grouped by contact: with tangential rows, row 2i is contact i's normal and row 2i + 1 its
/// tangent (Siconos's order); without, row i is contact i's normal. Enough to solve a law and to
/// certify its energy, T_E − T_A = P·(D_A + D_E)/2 for fixed obstacles; not enough for q̇_E.
struct ContactProblem {
  SparseMatrix G;       ///< symmetric positive semidefinite, rows × rows.
  Eigen::VectorXd D_A;  ///< the contact velocities before the impact, rows.
  bool tangential = true;
  /// How well the numbers of G and of D_A are known, relative to each entry: 0 for numbers formed
  /// in double precision (contact_problem()), 5·10⁻ᵖ for numbers printed with p significant
  /// digits (io::parse_siconos_file sets them from the file). D_E = D_A + G P is then known to
  /// G_rounding Σ|G_jk P_k| + D_A_rounding |D_A,j| row by row, beside its own rounding: the
  /// certificate allows that much, and sweeps that stall with every contact's residual within it
  /// end converged (criterion `data`, docs/sparse.md#numbers-as-printed). Range [0, 1e-2].
  double G_rounding = 0.0;
  double D_A_rounding = 0.0;  ///< see G_rounding.

  int rows() const { return static_cast<int>(D_A.size()); }
  int contacts() const { return tangential ? rows() / 2 : rows(); }
};

/// Checks that G is square with D_A's size (even with tangential rows), every number finite, G
/// symmetric to 1e-6 of its largest entry (files keep a few digits), each contact's diagonal
/// block positive semidefinite, and G_rounding and D_A_rounding in [0, 1e-2]. Throws
/// InvalidArgument naming `G`, `D_A`, `G_rounding` or `D_A_rounding` and the reason.
void validate(const ContactProblem& problem);

/// The contact form of a sparse impact problem: G = Wᵀ M⁻¹ W (M's diagonal blocks factorised
/// once, so the cost follows the non-zeros) and D_A = Wᵀ q̇_A + w. Validates `problem` first.
ContactProblem contact_problem(const SparseImpactProblem& problem);

/// M⁻¹ [W_N W_T] with the columns grouped by contact as in ContactProblem: q̇_E = q̇_A + X P.
/// Validates `problem` first.
SparseMatrix inverse_mass_times_jacobian(const SparseImpactProblem& problem);

}  // namespace fremond
