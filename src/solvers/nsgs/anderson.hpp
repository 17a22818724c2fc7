#pragma once
/// @file Anderson acceleration of a fixed-point map x ↦ g(x) (docs/sparse.md#acceleration): the
/// next input mixes the last outputs so that their residuals g(x) − x cancel in least squares.
#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace fremond::detail {

/// Type-II Anderson mixing of depth m (Walker and Ni, SIAM J. Numer. Anal. 49, 2011): with
/// f_k = g(x_k) − x_k and the differences ΔF, ΔG of the last m residuals and outputs,
/// γ = argmin |f_k − ΔF γ|₂ and x_{k+1} = g(x_k) − ΔG γ. On an affine map it is GMRES in
/// disguise; on a piecewise-affine one (the sweeps once the contacts' modes settle) the same.
/// The storage is kept from one solve to the next (room, not state: reset() forgets).
class AndersonMixing {
 public:
  explicit AndersonMixing(int depth = 5) : depth_(depth) {}

  /// Forgets the history: the next mix() returns g itself.
  void reset() {
    count_ = head_ = 0;
    has_last_ = false;
  }

  /// Given the map's input x and its output g (g = g(x)): the next input, written into g. The
  /// history restarts, and g is kept as it is, when the residual grew more than twofold since
  /// the last call (the modes changed: the old differences no longer describe the map) or when
  /// the least-squares step is not finite.
  void mix(const Eigen::VectorXd& x, Eigen::VectorXd& g);

 private:
  int depth_;
  int count_ = 0;  // columns 0 .. count_ − 1 of dF, dG hold differences (count_ ≤ depth_)
  int head_ = 0;   // the column the next difference goes to
  bool has_last_ = false;  // f_last_, g_last_ hold the last call's residual and output
  double last_norm_ = 0.0;
  Eigen::MatrixXd dF_, dG_, gram_;  // columns, and dFᵀdF kept column by column
  Eigen::MatrixXd system_;
  Eigen::LDLT<Eigen::MatrixXd> ldlt_;
  Eigen::VectorXd f_, f_last_, g_last_, rhs_, gamma_;
};

}  // namespace fremond::detail
