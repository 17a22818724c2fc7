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
// The factors live in a plain row-major array, and the sizes 1 … 8 run loops of compile-time
// length (with_size): with run-time bounds on the dynamic-size, 8×8-capacity Eigen storage, a
// Newton iteration's factorisation, exact rcond and solve take about twice to three times the
// instructions (4×4 Jacobian of the flat bar with friction: 1,700 against 900; the 2×2 one of the
// frictionless flat bar: 600 against 200). The sums of the 1-norms run in index order.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/detail/fixed_size.hpp"

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
    with_size(n_, [&](auto k) { factor<decltype(k)::value>(A); });
  }

  /// x = A⁻¹ b (only when !singular()).
  void solve(const Vec& b, Vec& x) const {
    x.resize(n_);
    with_size(n_, [&](auto k) { substitute<decltype(k)::value>(b.data(), x.data()); });
  }

  /// 1/(‖A‖₁ ‖A⁻¹‖₁); 0 for a singular A (or one whose inverse is not finite).
  double rcond() const {
    if (singular_ || !(norm1_ > 0.0)) return 0.0;
    const double inv_norm1 =
        with_size(n_, [&](auto k) { return inverse_norm1<decltype(k)::value>(); });
    if (!std::isfinite(inv_norm1)) return 0.0;
    return 1.0 / (norm1_ * inv_norm1);
  }

  bool singular() const { return singular_; }

  /// rcond() > threshold, without forming A⁻¹ where bounds on it already decide:
  ///  - no, where the pivots show it: A⁻¹ holds 1/u_nn as an entry, and
  ///    ‖U⁻¹‖₁ ≤ ‖A⁻¹‖₁ ‖L‖₁ ≤ n ‖A⁻¹‖₁ with |l_ij| ≤ 1, so rcond ≤ min(|u_nn|, n·min|u_ii|)/‖A‖₁
  ///    (a Newton system singular to rounding: two contacts sticking with one tangent);
  ///  - yes, where the comparison matrices show it: |T⁻¹| ≤ M(T)⁻¹ entrywise for a triangular T
  ///    (M(T): |t_ii| on the diagonal, −|t_ij| off it; Higham, "Accuracy and Stability of
  ///    Numerical Algorithms", §8.2), so ‖A⁻¹‖₁ ≤ ‖M(U)⁻¹‖₁ ‖M(L)⁻¹‖₁, each the largest entry
  ///    of M(T)⁻ᵀe: two substitutions of positive terms, where A⁻¹ takes n (the regular 4×4
  ///    Jacobians of the flat bar under the dead zone: 1,400 of a solve's 20,000 instructions).
  /// A factor of 2 on either bound leaves the rounding of the bounds and of rcond() itself aside:
  /// the answer is always rcond()'s.
  bool well_conditioned(double threshold) const {
    if (singular_ || !(norm1_ > 0.0)) return false;
    const double last = std::fabs(at(n_ - 1, n_ - 1));
    double smallest = last;
    for (int i = 0; i < n_; ++i) smallest = std::min(smallest, std::fabs(at(i, i)));
    if (std::min(last, n_ * smallest) <= 0.5 * threshold * norm1_) return false;
    const double bound =
        with_size(n_, [&](auto k) { return inverse_norm1_bound<decltype(k)::value>(); });
    if (std::isfinite(bound) && norm1_ * bound < 0.5 / threshold) return true;
    return rcond() > threshold;
  }

 private:
  static constexpr bool kDynamic = MaxRows == Eigen::Dynamic;

  // Sizes 1 … MaxRows on loops of compile-time length K (fixed_size.hpp); K = 0, n_ read at run
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

  // ‖A⁻¹‖₁ from the columns A⁻¹ e_j, all at once (X = U⁻¹ L⁻¹ P, the column loop innermost, where
  // it vectorises) with the pivots' reciprocals: a threshold on rcond does not need the last bit
  // that division gives, and one column at a time is a chain of n dependent divisions per
  // column: 27 % of the law stage on the flat bar with the viscous dead zone (regular 4×4
  // Jacobians, rcond 0.1, three steps). The same operations in the
  // same order for both storages, so that both give the same bits.
  template <int K>
  double inverse_norm1() const {
    const int n = K > 0 ? K : n_;
    std::conditional_t<(K > 0), std::array<double, (K > 0 ? K * K : 1)>, std::vector<double>> X;
    std::conditional_t<(K > 0), std::array<double, (K > 0 ? K : 1)>, std::vector<double>> inv;
    if constexpr (K == 0) {
      X.resize(static_cast<std::size_t>(n) * n);
      inv.resize(static_cast<std::size_t>(n));
    }
    for (int i = 0; i < n; ++i) inv[i] = 1.0 / at(i, i);
    for (int i = 0; i < n; ++i) {  // X[i][c], row-major: L⁻¹ P
      double* xi = &X[static_cast<std::size_t>(i) * n];
      for (int c = 0; c < n; ++c) xi[c] = perm_[i] == c ? 1.0 : 0.0;
      for (int j = 0; j < i; ++j) {
        const double l = at(i, j);
        const double* xj = &X[static_cast<std::size_t>(j) * n];
        for (int c = 0; c < n; ++c) xi[c] -= l * xj[c];
      }
    }
    for (int i = n - 1; i >= 0; --i) {  // then U⁻¹
      double* xi = &X[static_cast<std::size_t>(i) * n];
      for (int j = i + 1; j < n; ++j) {
        const double u = at(i, j);
        const double* xj = &X[static_cast<std::size_t>(j) * n];
        for (int c = 0; c < n; ++c) xi[c] -= u * xj[c];
      }
      for (int c = 0; c < n; ++c) xi[c] *= inv[i];
    }
    double norm = 0.0;
    for (int c = 0; c < n; ++c) {
      double s = 0.0;
      for (int i = 0; i < n; ++i) s += std::fabs(X[static_cast<std::size_t>(i) * n + c]);
      // A column that is not finite (an inverse beyond double precision): A is singular here.
      if (!std::isfinite(s)) return std::numeric_limits<double>::infinity();
      norm = std::max(norm, s);
    }
    return norm;
  }

  // ‖M(U)⁻¹‖₁ ‖M(L)⁻¹‖₁ ≥ ‖A⁻¹‖₁ (well_conditioned): y = M(U)⁻ᵀe by forward substitution,
  // w = M(L)⁻ᵀe by backward substitution (L unit lower), all terms positive.
  template <int K>
  double inverse_norm1_bound() const {
    const int n = K > 0 ? K : n_;
    std::conditional_t<(K > 0), std::array<double, (K > 0 ? K : 1)>, std::vector<double>> y, w;
    if constexpr (K == 0) {
      y.resize(static_cast<std::size_t>(n));
      w.resize(static_cast<std::size_t>(n));
    }
    double ymax = 0.0, wmax = 0.0;
    for (int j = 0; j < n; ++j) {
      double s = 1.0;
      for (int i = 0; i < j; ++i) s += std::fabs(at(i, j)) * y[i];
      y[j] = s / std::fabs(at(j, j));
      ymax = std::max(ymax, y[j]);
    }
    for (int j = n - 1; j >= 0; --j) {
      double s = 1.0;
      for (int i = j + 1; i < n; ++i) s += std::fabs(at(i, j)) * w[i];
      w[j] = s;
      wmax = std::max(wmax, s);
    }
    return ymax * wmax;
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
  int n_ = 0;
  std::conditional_t<kDynamic, std::vector<int>, std::array<int, kDynamic ? 1 : MaxRows>> perm_;
  bool singular_ = true;
  double norm1_ = 0.0;
};

}  // namespace fremond::detail
