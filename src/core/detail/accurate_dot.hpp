#pragma once
/// @file A dot product as accurate as if computed in twice the working precision (Ogita, Rump and
/// Oishi, "Accurate sum and dot product", SIAM J. Sci. Comput. 26, 2005: algorithm Dot2).
///
/// What it is for: the contacts that take part are those with D_NA = W_Nᵀ q̇_A + w_N ≤ 0
/// (docs/concepts.md), and a contact that touches (D_NA = 0 up to the data's last bits) is decided
/// by the sign of a sum that cancels. The plain dot product is off by up to n ε Σ|W_i q̇_i| and can
/// give that sign wrongly (+8.5e-22 for an exact −8.9e-23 beside velocities of 3e-5): the contact
/// then takes no part and the answer lets it penetrate at a quarter of the velocity scale. Dot2's
/// error is at most ε|x·y| + γ_n² Σ|x_i y_i| (γ_n = nε/(1 − nε)), so its sign is the sign of the
/// exact dot product of the stored doubles unless that is below about n² ε² Σ|x_i y_i| (1e-31
/// relative).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <type_traits>

namespace fremond::detail {

/// accurate_dot on n doubles x[i·incx], y[i·incy] (accurate_multiply_add.cpp): on a processor
/// with FMA instructions their loop, chosen at run time, else std::fma (a library call each in
/// the portable build); the same bits either way, since fma is exactly rounded in both.
double accurate_dot_strided(const double* x, std::ptrdiff_t incx, const double* y,
                            std::ptrdiff_t incy, Eigen::Index n, double extra);

/// accurate_dot_strided with unit strides (the same bits), for vectors and columns.
double accurate_dot_contiguous(const double* x, const double* y, Eigen::Index n, double extra);

/// x·y + extra, with the products and the sum error-free transformed (TwoProduct by fma, TwoSum):
/// accurate_dot_strided on two Eigen vectors of the same size whose doubles lie in memory
/// (columns, rows, vectors, maps).
template <class X, class Y>
double accurate_dot(const X& x, const Y& y, double extra = 0.0) {
  static_assert((Eigen::internal::traits<X>::Flags & Eigen::DirectAccessBit) &&
                    (Eigen::internal::traits<Y>::Flags & Eigen::DirectAccessBit) &&
                    std::is_same_v<typename X::Scalar, double> &&
                    std::is_same_v<typename Y::Scalar, double>,
                "accurate_dot reads doubles in memory: evaluate an expression first");
  if constexpr (Eigen::internal::inner_stride_at_compile_time<X>::ret == 1 &&
                Eigen::internal::inner_stride_at_compile_time<Y>::ret == 1)
    return accurate_dot_contiguous(x.data(), y.data(), x.size(), extra);
  else
    return accurate_dot_strided(x.data(), x.innerStride(), y.data(), y.innerStride(), x.size(),
                                extra);
}

/// The rounding error of the product p = a·b (p + e = a·b exactly, barring underflow). With an
/// FMA instruction, one fma; without one (the portable build), Dekker's TwoProduct by Veltkamp's
/// splitting, since std::fma is then a library call per product. The splitting is exact for
/// |a|, |b| below 2^995 (`two_product_safe`). Without FMA instructions the compiler cannot contract
/// the splitting's a·C − (a·C − a) into one, which would break it.
inline double two_product_error(double a, double b, double p) {
#if defined(__FMA__) || defined(FP_FAST_FMA)
  return std::fma(a, b, -p);
#else
  constexpr double kSplit = 134217729.0;  // 2^27 + 1
  const double ta = kSplit * a, tb = kSplit * b;
  const double ah = ta - (ta - a), al = a - ah;
  const double bh = tb - (tb - b), bl = b - bh;
  return ((ah * bh - p) + ah * bl + al * bh) + al * bl;
#endif
}

/// Whether two_product_error's splitting is exact for every product of entries of magnitude up to
/// `largest` (its factor 2^27 + 1 must not overflow).
inline bool two_product_safe(double largest) {
  return largest < 0x1p995;
}

/// s_i + e_i += Σ_j M(i, j) x_j for i < n, j < m (M column-major, leading dimension ld), each
/// product's and sum's rounding error carried in e (TwoProduct, TwoSum): the rows of a column side
/// by side, in accurate_residual's order. Every entry must pass two_product_safe. On a processor
/// with AVX2 and FMA the products' errors are one instruction each and four rows go at once, with
/// the same bits (TwoProduct is exact either way).
void accurate_multiply_add(const double* M, std::ptrdiff_t ld, int n, int m, const double* x,
                           double* s, double* e);
/// accurate_multiply_add's portable loop (Veltkamp's splitting), whatever the processor.
void accurate_multiply_add_portable(const double* M, std::ptrdiff_t ld, int n, int m,
                                    const double* x, double* s, double* e);

/// D = B − M X, each entry exactly as −accurate_dot(M.row(i), X.col(c), −B(i, c)) gives it (the
/// same terms in the same order, the same error-free transformations; only a product whose error
/// is subnormal may differ in that error's last bits), but with the rows of a
/// column summed side by side: each row's sum is a dependency chain, and n of them at once keep
/// the floating-point units busy and vectorise, where one accurate_dot per entry waits on each
/// addition. For iterative refinement (refined_solve.hpp), where these residuals are most of the
/// cost. Entries beyond two_product_safe go through accurate_dot one by one.
template <class MatM, class MatX, class MatB, class MatD>
void accurate_residual(const MatM& M, const MatX& X, const MatB& B, MatD& D) {
  const Eigen::Index n = M.rows(), m = M.cols(), k = X.cols();
  D.resize(n, k);
  if (n == 0 || k == 0) return;
  const double largest = std::max(M.cwiseAbs().maxCoeff(), X.cwiseAbs().maxCoeff());
  if (!two_product_safe(largest)) {
    for (Eigen::Index c = 0; c < k; ++c)
      for (Eigen::Index i = 0; i < n; ++i) D(i, c) = -accurate_dot(M.row(i), X.col(c), -B(i, c));
    return;
  }
  using Column = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, MatM::MaxRowsAtCompileTime, 1>;
  using Row = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, MatM::MaxColsAtCompileTime, 1>;
  Column sum(n), err(n);
  Row x(m);
  for (Eigen::Index c = 0; c < k; ++c) {
    for (Eigen::Index i = 0; i < n; ++i) {
      sum(i) = -B(i, c);
      err(i) = 0.0;
    }
    for (Eigen::Index j = 0; j < m; ++j) x(j) = X(j, c);
    accurate_multiply_add(M.data(), M.outerStride(), static_cast<int>(n), static_cast<int>(m),
                          x.data(), sum.data(), err.data());
    for (Eigen::Index i = 0; i < n; ++i) {
      const double r = sum(i) + err(i);
      D(i, c) = -(std::isfinite(r) ? r : sum(i));
    }
  }
}

}  // namespace fremond::detail
