#pragma once
// The minimum-norm least-squares solution of a small linear system that may be singular (dependent
// contact rows: a flat bar touching at both ends). An SVD, because Eigen's complete orthogonal
// decomposition allocates in its solve.
#include <Eigen/SVD>

namespace fremond::detail {

template <class Mat, class Rhs>
auto min_norm_solve(const Mat& A, const Rhs& b) {
  const Eigen::JacobiSVD<Mat> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  return svd.solve(b).eval();
}

}  // namespace fremond::detail
