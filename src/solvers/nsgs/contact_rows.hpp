#pragma once
/// @file Contact rows under Newton's law (docs/sparse.md): what the sweeps and the mode Newton
/// read of one problem and law, and the law's residual at given percussions.
#include <Eigen/SparseCore>
#include <limits>
#include <vector>

#include "solvers/nsgs/coulomb_contact.hpp"

namespace fremond::detail {

using RowMajorMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

/// What the sweeps need of one problem and law, gathered once.
struct Layout {
  int contacts = 0;
  int step = 2;           ///< rows a contact
  bool friction = false;  ///< Coulomb rows solved
  RowMajorMatrix G;       ///< row access
  std::vector<ContactBlock> block;
  std::vector<double> e, mu;
  std::vector<double> shift;  ///< e min(D_NA, 0): the restitution term of each normal row
  double v_scale = std::numeric_limits<double>::min();
  /// G = Wᵀ X (X = M⁻¹ W) on a body with at most half as many degrees of freedom as rows (a rigid
  /// body on many contacts), n × rows in the layout's row order; empty otherwise. Given, the sweeps
  /// and the mode Newton work on the n velocities X P: a sweep costs rows · n instead of G's
  /// entries, a Newton step an n × n factorisation instead of one of its unknowns
  /// (velocity_factors).
  Eigen::MatrixXd W, X;
  /// How well G's and D_A's numbers are known (ContactProblem::G_rounding, D_A_rounding); 0 for
  /// numbers formed in double precision. Set by the caller; lay_out leaves them.
  double G_rounding = 0.0, D_A_rounding = 0.0;

  bool has_velocity_factors() const { return X.size() != 0; }
  bool has_data_rounding() const { return G_rounding > 0.0 || D_A_rounding > 0.0; }
};

/// The layout of G (rows grouped by contact: with `tangential`, row 2i contact i's normal and
/// 2i + 1 its tangent), D_A and each contact's e and μ (μ read only with `coulomb`).
/// G in row-major storage (the sweeps read it by rows) is taken over; a column-major one converts.
Layout layout(RowMajorMatrix&& G, const Eigen::VectorXd& D_A, bool tangential, bool coulomb,
              const std::vector<double>& e, const std::vector<double>& mu);
/// The same in L's own storage (kept from one solve to the next), L.G holding G compressed.
void lay_out(Layout& L, const Eigen::VectorXd& D_A, bool tangential, bool coulomb,
             const std::vector<double>& e, const std::vector<double>& mu);

/// Whether a body of `dofs` degrees of freedom on `rows` contact rows pays for the velocity
/// factors (Layout::W, X): a contact's update reads two rows and moves v twice through the
/// velocities (4n), against two rows of G (2 rows), so from 2n ≤ rows.
inline bool velocity_factors_pay(Eigen::Index dofs, Eigen::Index rows) {
  return 2 * dofs <= rows;
}

/// Row `row` of G times P; *size, when given, gets Σ|G_rk P_k|.
inline double row_times(const RowMajorMatrix& G, int row, const Eigen::VectorXd& P, double* size) {
  const int* idx = G.innerIndexPtr();
  const double* val = G.valuePtr();
  double sum = 0.0, abs_sum = 0.0;
  for (int k = G.outerIndexPtr()[row]; k < G.outerIndexPtr()[row + 1]; ++k) {
    const double t = val[k] * P(idx[k]);
    sum += t;
    abs_sum += std::fabs(t);
  }
  if (size) *size = abs_sum;
  return sum;
}

/// The law's residual at P: D_E = D_A + G P, each row's rounding 16ε (|D_A| + Σ|G P|), and,
/// where the layout has data rounding, what the data leave undetermined of it,
/// G_rounding Σ|G P| + D_A_rounding |D_A|.
struct Measure {
  double residual = 0.0;          ///< max |R|, velocity units
  double excess = 0.0;            ///< max (|R| − rounding of its rows)
  double data_excess = 0.0;       ///< max (|R| − rounding − data rounding of its rows)
  double squares = 0.0;           ///< ½ Σ R² over the rows: the mode Newton's merit
  Eigen::VectorXd D_E, rounding;  ///< rows
  Eigen::VectorXd data;           ///< rows: the data rounding; empty without it
};

Measure measure(const Layout& L, const Eigen::VectorXd& D_A, const Eigen::VectorXd& P);
/// The same into `m`, whose vectors keep their storage from one measure to the next.
void measure(const Layout& L, const Eigen::VectorXd& D_A, const Eigen::VectorXd& P, Measure& m);

/// One Gauss–Seidel sweep of the contacts' local laws (coulomb_contact), in order or `backward`;
/// returns the largest change of a contact's velocity it made. `velocities`: the room the sweep
/// keeps the body's velocities in when L has velocity factors, its storage reused by the next.
double sweep(const Layout& L, const Eigen::VectorXd& D_A, Eigen::VectorXd& P, bool backward,
             Eigen::VectorXd& velocities);

}  // namespace fremond::detail
