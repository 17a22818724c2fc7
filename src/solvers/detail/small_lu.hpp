#pragma once
// A dense LU factorisation with partial pivoting for the stack-stored small systems of semismooth
// Newton (at most 8 rows: 4 contacts with friction). Eigen's PartialPivLU on a dynamic-size matrix
// goes through its blocked kernels and its rcond() estimator through several triangular solves of
// general size: on a 2×2 Jacobian that machinery costs far more than the arithmetic.
//
// rcond() is the exact reciprocal 1-norm condition number 1/(‖A‖₁ ‖A⁻¹‖₁), from the r columns of
// A⁻¹ (O(r³), a few dozen flops at these sizes). Eigen's estimate is a lower bound of ‖A⁻¹‖₁, so
// the exact value is never above it: a step accepted here would be accepted by the estimator too.
//
// The factors live in a plain row-major array, and the sizes 3 … 8 run loops of compile-time
// length (with_size): with run-time bounds on the dynamic-size, 8×8-capacity Eigen storage, the
// 4×4 Jacobian of the flat bar with friction cost 1,700 instructions per Newton iteration in the
// factorisation, the exact rcond and the solve, now 900. The sums of the 1-norms run in index
// order.
//
// Two rows (one contact with friction, or two frictionless contacts: the flat bar) take a path on
// scalars: the same operations in the same order as the general loops, so the same bits, without
// even their loop bounds.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <type_traits>
#include <utility>
#include <vector>

#include "fixed_size.hpp"

namespace fremond::detail {

template <int MaxRows>
class SmallLU {
 public:
  using Mat =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, MaxRows, MaxRows>;
  using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, MaxRows, 1>;

  /// Factorises P A = L U (L unit lower, U upper, stored together). A zero pivot marks A singular.
  void compute(const Mat& A) {
    n_ = static_cast<int>(A.rows());
    if (n_ == 2) {
      compute2(A(0, 0), A(0, 1), A(1, 0), A(1, 1));
      return;
    }
    with_size(n_, [&](auto k) { factor<decltype(k)::value>(A); });
  }

  /// x = A⁻¹ b (only when !singular()).
  void solve(const Vec& b, Vec& x) const {
    x.resize(n_);
    if (n_ == 2) {
      solve2(b(0), b(1), x(0), x(1));
      return;
    }
    with_size(n_, [&](auto k) { substitute<decltype(k)::value>(b.data(), x.data()); });
  }

  /// 1/(‖A‖₁ ‖A⁻¹‖₁); 0 for a singular A (or one whose inverse is not finite).
  double rcond() const {
    if (singular_ || !(norm1_ > 0.0)) return 0.0;
    double inv_norm1 = 0.0;
    if (n_ == 2) {
      double c0, c1;
      solve2(1.0, 0.0, c0, c1);
      inv_norm1 = std::fmax(inv_norm1, std::fabs(c0) + std::fabs(c1));
      solve2(0.0, 1.0, c0, c1);
      inv_norm1 = std::fmax(inv_norm1, std::fabs(c0) + std::fabs(c1));
    } else {
      inv_norm1 = with_size(n_, [&](auto k) { return inverse_norm1<decltype(k)::value>(); });
    }
    if (!std::isfinite(inv_norm1)) return 0.0;
    return 1.0 / (norm1_ * inv_norm1);
  }

  bool singular() const { return singular_; }

 private:
  static constexpr bool kDynamic = MaxRows == Eigen::Dynamic;

  // Sizes 3 … MaxRows on loops of compile-time length K (fixed_size.hpp); K = 0, n_ read at run
  // time, for the dynamic size.
  template <class F>
  static decltype(auto) with_size(int n, F&& f) {
    return with_fixed_size<(kDynamic ? 0 : (MaxRows < 8 ? MaxRows : 8))>(n, f);
  }

  template <int K>
  void factor(const Mat& A) {
    const int n = K > 0 ? K : n_;
    singular_ = false;
    norm1_ = 0.0;
    for (int j = 0; j < n; ++j) {
      double s = 0.0;
      for (int i = 0; i < n; ++i) s += std::fabs(A(i, j));
      norm1_ = std::fmax(norm1_, s);
    }
    if constexpr (kDynamic) {
      stride_ = n;
      lu_.resize(static_cast<std::size_t>(n) * n);
      perm_.resize(static_cast<std::size_t>(n));
    }
    for (int i = 0; i < n; ++i) {
      perm_[i] = i;
      for (int j = 0; j < n; ++j) at(i, j) = A(i, j);
    }
    for (int k = 0; k < n; ++k) {
      int p = k;
      for (int i = k + 1; i < n; ++i)
        if (std::fabs(at(i, k)) > std::fabs(at(p, k))) p = i;
      if (p != k) {
        for (int j = 0; j < n; ++j) std::swap(at(k, j), at(p, j));
        std::swap(perm_[k], perm_[p]);
      }
      const double pivot = at(k, k);
      if (!(pivot != 0.0) || !std::isfinite(pivot)) {
        singular_ = true;
        return;
      }
      for (int i = k + 1; i < n; ++i) {
        const double l = at(i, k) / pivot;
        at(i, k) = l;
        for (int j = k + 1; j < n; ++j) at(i, j) -= l * at(k, j);
      }
    }
  }

  // Forward then back substitution with the factors (b and x distinct).
  template <int K>
  void substitute(const double* b, double* x) const {
    const int n = K > 0 ? K : n_;
    for (int i = 0; i < n; ++i) {
      double s = b[perm_[i]];
      for (int j = 0; j < i; ++j) s -= at(i, j) * x[j];
      x[i] = s;
    }
    for (int i = n - 1; i >= 0; --i) {
      double s = x[i];
      for (int j = i + 1; j < n; ++j) s -= at(i, j) * x[j];
      x[i] = s / at(i, i);
    }
  }

  // ‖A⁻¹‖₁ from the columns A⁻¹ e_j.
  template <int K>
  double inverse_norm1() const {
    const int n = K > 0 ? K : n_;
    Vec e(n), col(n);
    double norm = 0.0;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) e(i) = i == j ? 1.0 : 0.0;
      substitute<K>(e.data(), col.data());
      double s = 0.0;
      for (int i = 0; i < n; ++i) s += std::fabs(col(i));
      norm = std::fmax(norm, s);
    }
    return norm;
  }

  // The general loops above for n = 2, unrolled: partial pivoting on column 0, then one
  // elimination; u_ holds the factors (row-major: u00, u01, l10, u11).
  void compute2(double a00, double a01, double a10, double a11) {
    singular_ = false;
    norm1_ =
        std::fmax(std::fmax(0.0, std::fabs(a00) + std::fabs(a10)), std::fabs(a01) + std::fabs(a11));
    swapped_ = std::fabs(a10) > std::fabs(a00);
    if (swapped_) {
      std::swap(a00, a10);
      std::swap(a01, a11);
    }
    if (!(a00 != 0.0) || !std::isfinite(a00)) {
      singular_ = true;
      return;
    }
    const double l = a10 / a00;
    a11 -= l * a01;
    u_[0] = a00;
    u_[1] = a01;
    u_[2] = l;
    u_[3] = a11;
    if (!(a11 != 0.0) || !std::isfinite(a11)) singular_ = true;
  }
  void solve2(double b0, double b1, double& x0, double& x1) const {
    if (swapped_) std::swap(b0, b1);
    const double y1 = b1 - u_[2] * b0;
    x1 = y1 / u_[3];
    x0 = (b0 - u_[1] * x1) / u_[0];
  }

  double& at(int i, int j) { return lu_[i * stride() + j]; }
  double at(int i, int j) const { return lu_[i * stride() + j]; }
  int stride() const {
    if constexpr (kDynamic)
      return stride_;
    else
      return MaxRows;
  }
  // Row-major factors, written by compute() before any read; a fixed stride where it can be.
  std::conditional_t<kDynamic, std::vector<double>,
                     std::array<double, kDynamic ? 1 : MaxRows * MaxRows>>
      lu_;
  int stride_ = 0;
  double u_[4] = {0, 0, 0, 0};
  bool swapped_ = false;
  int n_ = 0;
  std::conditional_t<kDynamic, std::vector<int>, std::array<int, kDynamic ? 1 : MaxRows>> perm_;
  bool singular_ = true;
  double norm1_ = 0.0;
};

}  // namespace fremond::detail
