#pragma once
/// @file The Cholesky factor L Lᵀ of a symmetric positive definite matrix, by hand loops for the
/// stack-stored sizes and by Eigen's LLT for the heap-stored ones.
///
/// Eigen's LLT on a bounded dynamic-size 3×3 matrix goes through its blocked driver, a GEMV per
/// column and the 1-norm it keeps for rcond(): about 500 instructions, more than the rest of a
/// one-contact impact's contact space. The hand loop is Eigen's unblocked algorithm (the same
/// pivot test, the same operations per column), summing in index order.
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "core/detail/small_dense.hpp"
#include "fremond/core/types.hpp"

namespace fremond::detail {

template <int MaxN>
class CholeskyT {
 public:
  using Mat = MatT<MaxN, MaxN>;
  static constexpr bool kHandLoops = MaxN != Dynamic;

  CholeskyT() = default;
  explicit CholeskyT(const Mat& A) { compute(A); }

  /// Factorises the lower triangle of A. info() says whether every pivot was positive.
  CholeskyT& compute(const Mat& A) {
    if constexpr (kHandLoops) {
      L_ = A;
      scan_diagonal(A, diagonal_, matrix_diagonal_);
      info_ = factorize_in_place(L_, diagonal_) ? Eigen::Success : Eigen::NumericalIssue;
    } else {
      bool lower = true;
      scan_diagonal(A, lower, matrix_diagonal_);
      llt_.compute(A);
    }
    // ‖A‖₁ now (the factor keeps only one triangle of A), ‖L⁻¹‖_F² when condition_bound() asks.
    condition_bound_ = std::numeric_limits<double>::infinity();
    if (!matrix_diagonal_ && info() == Eigen::Success) {
      norm1_ = 0.0;
      for (Eigen::Index j = 0; j < A.cols(); ++j)
        norm1_ = std::max(norm1_, A.col(j).cwiseAbs().sum());
      condition_bound_ = -1.0;
    }
    return *this;
  }

  /// compute(A) for an A its caller has found diagonal in both triangles: the same factor, pivot
  /// test and flags, without the scan (the fixed-size contact space makes it with its own sizes).
  CholeskyT& compute_diagonal(const Mat& A) {
    static_assert(kHandLoops, "the heap-stored sizes factorise through Eigen's LLT");
    L_ = A;
    diagonal_ = matrix_diagonal_ = true;
    info_ = factorize_in_place(L_, true) ? Eigen::Success : Eigen::NumericalIssue;
    condition_bound_ = std::numeric_limits<double>::infinity();  // not read: no solve is refined
    return *this;
  }

  /// Whether the matrix factorised is diagonal, both triangles (every off-diagonal entry exactly
  /// zero): what the callers' is_diagonal(M) would say, found by the scan the factor needs anyway.
  bool matrix_is_diagonal() const { return matrix_diagonal_; }

  /// An upper bound of cond₂(A), to rounding, for a matrix that is not diagonal: ‖A‖₁ ‖L⁻¹‖_F²
  /// (‖A‖₂ ≤ ‖A‖₁ for a symmetric A, and ‖A⁻¹‖₂ = ‖L⁻¹‖₂² ≤ ‖L⁻¹‖_F²). At most n^1.5 times too
  /// large: a well-conditioned mass matrix of 30 dofs (cond 3.5) reads about 120. ∞ for a diagonal
  /// matrix (it needs no bound: its solves are divisions) and where the factorisation failed.
  /// Computed on first use (n³/6 products), since most factors (of G, in validation) never ask.
  double condition_bound() const {
    if (condition_bound_ < 0.0) condition_bound_ = bound_condition();
    return condition_bound_;
  }

  Eigen::ComputationInfo info() const {
    if constexpr (kHandLoops)
      return info_;
    else
      return llt_.info();
  }

  /// L in the lower triangle (the upper one holds A's, as Eigen's LLT::matrixLLT()).
  const Mat& matrixLLT() const {
    if constexpr (kHandLoops)
      return L_;
    else
      return llt_.matrixLLT();
  }

  /// A⁻¹ b by forward and backward substitution (what Eigen's LLT::solveInPlace does).
  template <class Rhs>
  VecT<MaxN> solve(const Rhs& b) const {
    VecT<MaxN> x = b;
    solve_lower_in_place(x);
    solve_upper_in_place(x);
    return x;
  }

  /// Y ← L⁻¹ Y.
  template <class Y>
  void solve_lower_in_place(Y& y) const {
    if constexpr (kHandLoops) {
      if (diagonal_) {
        divide_by_diagonal(y);
        return;
      }
      with_size(L_.rows(),
                [&](auto k) { small_dense::forward_substitute<decltype(k)::value>(L_, y); });
    } else
      llt_.matrixL().solveInPlace(y);
  }

  /// X ← L⁻ᵀ X.
  template <class X>
  void solve_upper_in_place(X& x) const {
    if constexpr (kHandLoops) {
      if (diagonal_) {
        divide_by_diagonal(x);
        return;
      }
      with_size(L_.rows(), [&](auto k) {
        small_dense::backward_substitute_transposed<decltype(k)::value>(L_, x);
      });
    } else
      llt_.matrixU().solveInPlace(x);
  }

 private:
  // Eigen's llt_inplace<Lower>::unblocked: column k's pivot A_kk − |L_k,0:k|², refused unless
  // positive (a NaN pivot passes, as in Eigen; the callers test the data's finiteness first), then
  // the column below it.
  static bool factorize_in_place(Mat& A, bool diagonal) {
    const Eigen::Index n = A.rows();
    if (diagonal) {  // the same pivots: every product below subtracts an exact zero
      for (Eigen::Index k = 0; k < n; ++k) {
        if (A(k, k) <= 0.0) return false;
        A(k, k) = std::sqrt(A(k, k));
      }
      return true;
    }
    return with_size(n, [&](auto k) { return factorize_in_place_n<decltype(k)::value>(A); });
  }

  // The sizes of a few contacts' Delassus matrix and of a planar body's M (1 to 4) with their trip
  // counts known to the compiler, for the factor and both substitutions: the same operations in
  // the same order (the same bits), without the loop bookkeeping that is half of a 2×2 factor's
  // instructions. f receives std::integral_constant<int, n>, or Dynamic beyond 4.
  template <class F>
  static decltype(auto) with_size(Eigen::Index n, F&& f) {
    switch (n) {
      case 1:
        return f(std::integral_constant<int, 1>{});
      case 2:
        return f(std::integral_constant<int, 2>{});
      case 3:
        return f(std::integral_constant<int, 3>{});
      case 4:
        return f(std::integral_constant<int, 4>{});
      default:
        return f(std::integral_constant<int, Dynamic>{});
    }
  }

  template <int K>
  static bool factorize_in_place_n(Mat& A) {
    const Eigen::Index n = K == Dynamic ? A.rows() : K;
    for (Eigen::Index k = 0; k < n; ++k) {
      double x = A(k, k);
      for (Eigen::Index j = 0; j < k; ++j) x -= A(k, j) * A(k, j);
      if (x <= 0.0) return false;
      x = std::sqrt(x);
      A(k, k) = x;
      for (Eigen::Index i = k + 1; i < n; ++i) {
        double s = A(i, k);
        for (Eigen::Index j = 0; j < k; ++j) s -= A(i, j) * A(k, j);
        A(i, k) = s / x;
      }
    }
    return true;
  }

  // A diagonal M (a body in principal axes: the bar, a point mass, the plate) has a diagonal
  // factor, and both substitutions are one division per entry: the general loops would only
  // subtract products with its zeros (exact), at a third of a one-contact impact's contact space.
  // The upper triangle is scanned in the same pass (M is symmetric only to 1e-12 of its scale, so
  // a diagonal lower triangle does not make M diagonal).
  static void scan_diagonal(const Mat& A, bool& lower, bool& both) {
    const Eigen::Index n = A.rows();
    lower = both = true;
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index i = j + 1; i < n; ++i) {
        if (A(i, j) != 0.0) lower = both = false;
        if (A(j, i) != 0.0) both = false;
        if (!lower) return;  // both is false too
      }
  }

  // condition_bound(): ‖L⁻¹‖_F² column by column (L⁻¹e_j is zero above row j), n³/6 products,
  // against the n²·rows twice-precise products of one step of refinement it can spare.
  double bound_condition() const {
    const Mat& L = matrixLLT();
    const Eigen::Index n = L.rows();
    VecT<MaxN> y(n);
    double inverse = 0.0;
    for (Eigen::Index j = 0; j < n; ++j) {
      y(j) = 1.0 / L(j, j);
      inverse += y(j) * y(j);
      for (Eigen::Index i = j + 1; i < n; ++i) {
        double s = 0.0;
        for (Eigen::Index k = j; k < i; ++k) s += L(i, k) * y(k);
        y(i) = -s / L(i, i);
        inverse += y(i) * y(i);
      }
    }
    const double bound = norm1_ * inverse;
    return std::isfinite(bound) ? bound : std::numeric_limits<double>::infinity();
  }

  template <class Y>
  void divide_by_diagonal(Y& y) const {
    const Eigen::Index n = L_.rows();
    for (Eigen::Index k = 0; k < y.cols(); ++k)
      for (Eigen::Index i = 0; i < n; ++i) y(i, k) /= L_(i, i);
  }

  struct Empty {};
  bool diagonal_ = false;         // the lower triangle: the factor is diagonal
  bool matrix_diagonal_ = false;  // the whole matrix
  double norm1_ = 0.0;            // ‖A‖₁, for condition_bound()
  mutable double condition_bound_ = std::numeric_limits<double>::infinity();  // < 0: not yet
  std::conditional_t<kHandLoops, Mat, Empty> L_{};
  Eigen::ComputationInfo info_ = Eigen::InvalidInput;
  std::conditional_t<kHandLoops, Empty, Eigen::LLT<Mat>> llt_{};
};

/// κ(M) estimated from M's Cholesky factor L: (max L_ii / min L_ii)², a lower bound (at least 1)
/// that has the order of κ in practice, for the price of a look at the diagonal. 0 where the
/// factor has no positive diagonal.
template <class Factor>
double condition_estimate(const Factor& llt) {
  const auto L = llt.matrixLLT().diagonal().cwiseAbs();
  if (L.size() == 0 || !(L.minCoeff() > 0.0)) return 0.0;
  const double ratio = L.maxCoeff() / L.minCoeff();
  return ratio * ratio;
}

}  // namespace fremond::detail
