#pragma once
/// @file Dense kernels by hand loops for the stack-stored small problems (n ≤ 6, ≤ 8 contact rows).
///
/// Eigen's products and triangular solves on the bounded dynamic-size types go through its general
/// GEMV/GEMM and blocked triangular kernels (packing, blocking), which cost more on a 3×2 problem
/// than the arithmetic. Heap-stored problems keep Eigen's kernels. Each loop sums in index order,
/// so a result does not depend on which caller formed it.
#include <Eigen/Core>

namespace fremond::detail::small_dense {

/// y += A x, column by column.
template <class Mat, class VecX, class VecY>
void add_product(const Mat& A, const VecX& x, VecY& y) {
  const Eigen::Index rows = A.rows(), cols = A.cols();
  for (Eigen::Index j = 0; j < cols; ++j) {
    const typename VecX::Scalar xj = x(j);  // double but in classical's extended precision
    for (Eigen::Index i = 0; i < rows; ++i) y(i) += A(i, j) * xj;
  }
}

/// ½ vᵀ A v (A symmetric: a kinetic energy with A = M); K, where given, is v's size known to the
/// compiler (the same operations).
template <int K = Eigen::Dynamic, class Mat, class Vec>
double half_quadratic_form(const Mat& A, const Vec& v) {
  const Eigen::Index n = K == Eigen::Dynamic ? v.size() : K;
  double e = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    double Av = 0.0;
    for (Eigen::Index j = 0; j < n; ++j) Av += A(i, j) * v(j);
    e += v(i) * Av;
  }
  return 0.5 * e;
}

/// Y ← L⁻¹ Y (forward substitution) with L the lower triangle of `L`; K, where given, is L's size
/// known to the compiler (the same operations).
template <int K = Eigen::Dynamic, class LMat, class Mat>
void forward_substitute(const LMat& L, Mat& Y) {
  const Eigen::Index n = K == Eigen::Dynamic ? L.rows() : K;
  for (Eigen::Index k = 0; k < Y.cols(); ++k)
    for (Eigen::Index i = 0; i < n; ++i) {
      double s = Y(i, k);
      for (Eigen::Index j = 0; j < i; ++j) s -= L(i, j) * Y(j, k);
      Y(i, k) = s / L(i, i);
    }
}

/// X ← L⁻ᵀ X (backward substitution with the transpose of the lower triangle of `L`); K as above.
template <int K = Eigen::Dynamic, class LMat, class Mat>
void backward_substitute_transposed(const LMat& L, Mat& X) {
  const Eigen::Index n = K == Eigen::Dynamic ? L.rows() : K;
  for (Eigen::Index k = 0; k < X.cols(); ++k)
    for (Eigen::Index i = n - 1; i >= 0; --i) {
      double s = X(i, k);
      for (Eigen::Index j = i + 1; j < n; ++j) s -= L(j, i) * X(j, k);
      X(i, k) = s / L(i, i);
    }
}

/// G ← YᵀY, both triangles from the same sums (exactly symmetric).
template <class Mat, class RowMat>
void gram(const Mat& Y, RowMat& G) {
  const Eigen::Index r = Y.cols(), n = Y.rows();
  G.resize(r, r);
  for (Eigen::Index j = 0; j < r; ++j)
    for (Eigen::Index k = j; k < r; ++k) {
      double s = 0.0;
      for (Eigen::Index i = 0; i < n; ++i) s += Y(i, j) * Y(i, k);
      G(j, k) = G(k, j) = s;
    }
}

}  // namespace fremond::detail::small_dense
