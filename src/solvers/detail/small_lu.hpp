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
// Two rows (one contact with friction, or two frictionless contacts: the flat bar) take a path on
// scalars: the same operations in the same order as the general loops, so the same bits, without
// their bookkeeping (the resize and copy of the 8×8-capacity storage, the loop bounds), which cost
// ten times the arithmetic: 600 instructions per Newton iteration of the flat bar, now 60.
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
    n_ = n;
    if (n == 2) {
      compute2(A(0, 0), A(0, 1), A(1, 0), A(1, 1));
      return;
    }
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
    const int n = n_;
    x.resize(n);
    if (n == 2) {
      solve2(b(0), b(1), x(0), x(1));
      return;
    }
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
    const int n = n_;
    double inv_norm1 = 0.0;
    if (n == 2) {
      double c0, c1;
      solve2(1.0, 0.0, c0, c1);
      inv_norm1 = std::fmax(inv_norm1, std::fabs(c0) + std::fabs(c1));
      solve2(0.0, 1.0, c0, c1);
      inv_norm1 = std::fmax(inv_norm1, std::fabs(c0) + std::fabs(c1));
      if (!std::isfinite(inv_norm1)) return 0.0;
      return 1.0 / (norm1_ * inv_norm1);
    }
    Vec e(n), col(n);
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

  Mat lu_;
  double u_[4] = {0, 0, 0, 0};
  bool swapped_ = false;
  int n_ = 0;
  Eigen::Matrix<int, Eigen::Dynamic, 1, Eigen::ColMajor, MaxRows, 1> perm_;
  bool singular_ = true;
  double norm1_ = 0.0;
};

}  // namespace fremond::detail
