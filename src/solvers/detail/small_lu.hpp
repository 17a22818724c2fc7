#pragma once
// A dense LU factorisation with partial pivoting for the stack-stored small systems of semismooth
// Newton (at most 8 rows: 4 contacts with friction). Eigen's PartialPivLU on a dynamic-size matrix
// goes through its blocked kernels and its rcond() estimator through several triangular solves of
// general size: on a 2×2 Jacobian that machinery costs far more than the arithmetic.
//
// rcond() is the exact reciprocal 1-norm condition number 1/(‖A‖₁ ‖A⁻¹‖₁), from the r columns of
// A⁻¹ (O(r³), a few dozen flops at these sizes). Eigen's estimate is a lower bound of ‖A⁻¹‖₁, so
// the exact value is never above it: a step accepted here would be accepted by the estimator too.
#include <Eigen/Core>
#include <cmath>

namespace fremond::detail {

template <int MaxRows>
class SmallLU {
 public:
  using Mat =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, MaxRows, MaxRows>;
  using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, MaxRows, 1>;

  /// Factorises P A = L U (L unit lower, U upper, stored together). A zero pivot marks A singular.
  void compute(const Mat& A) {
    const int n = static_cast<int>(A.rows());
    lu_ = A;
    perm_.resize(n);
    for (int i = 0; i < n; ++i) perm_[i] = i;
    singular_ = false;
    norm1_ = 0.0;
    for (int j = 0; j < n; ++j) norm1_ = std::fmax(norm1_, A.col(j).cwiseAbs().sum());
    for (int k = 0; k < n; ++k) {
      int p = k;
      for (int i = k + 1; i < n; ++i)
        if (std::fabs(lu_(i, k)) > std::fabs(lu_(p, k))) p = i;
      if (p != k) {
        lu_.row(k).swap(lu_.row(p));
        std::swap(perm_[k], perm_[p]);
      }
      const double pivot = lu_(k, k);
      if (!(pivot != 0.0) || !std::isfinite(pivot)) {
        singular_ = true;
        return;
      }
      for (int i = k + 1; i < n; ++i) {
        const double l = lu_(i, k) / pivot;
        lu_(i, k) = l;
        for (int j = k + 1; j < n; ++j) lu_(i, j) -= l * lu_(k, j);
      }
    }
  }

  /// x = A⁻¹ b (only when !singular()).
  void solve(const Vec& b, Vec& x) const {
    const int n = static_cast<int>(lu_.rows());
    x.resize(n);
    for (int i = 0; i < n; ++i) {
      double s = b(perm_[i]);
      for (int j = 0; j < i; ++j) s -= lu_(i, j) * x(j);
      x(i) = s;
    }
    for (int i = n - 1; i >= 0; --i) {
      double s = x(i);
      for (int j = i + 1; j < n; ++j) s -= lu_(i, j) * x(j);
      x(i) = s / lu_(i, i);
    }
  }

  /// 1/(‖A‖₁ ‖A⁻¹‖₁); 0 for a singular A (or one whose inverse is not finite).
  double rcond() const {
    if (singular_ || !(norm1_ > 0.0)) return 0.0;
    const int n = static_cast<int>(lu_.rows());
    Vec e(n), col(n);
    double inv_norm1 = 0.0;
    for (int j = 0; j < n; ++j) {
      e.setZero();
      e(j) = 1.0;
      solve(e, col);
      inv_norm1 = std::fmax(inv_norm1, col.cwiseAbs().sum());
    }
    if (!std::isfinite(inv_norm1)) return 0.0;
    return 1.0 / (norm1_ * inv_norm1);
  }

  bool singular() const { return singular_; }

 private:
  Mat lu_;
  Eigen::Matrix<int, Eigen::Dynamic, 1, Eigen::ColMajor, MaxRows, 1> perm_;
  bool singular_ = true;
  double norm1_ = 0.0;
};

}  // namespace fremond::detail
