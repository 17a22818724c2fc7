#pragma once
// A complete-pivoting LU for the singular but consistent Newton systems of semismooth Newton on the
// stack-stored sizes (at most 8 rows): two contacts sticking with one tangent, the flat bar's two
// identical tangential rows. It makes Eigen's FullPivLU's choices — the largest remaining entry as
// pivot, the first one met in column-major order on a tie; rank = the pivots above
// ε·size·|largest pivot|; the free unknowns set to zero — so that the particular solution, hence
// the split of a percussion between identical rows, is the one FullPivLU gives. Eigen's
// dynamic-size FullPivLU on the 8×8-capacity storage went through its general blocked code, far
// more than the arithmetic of a 2×2 … 8×8 system. Loops of compile-time length (fixed_size.hpp)
// for sizes 1 … 8.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "core/detail/fixed_size.hpp"
#include "core/detail/small_lu.hpp"

namespace fremond::detail {

template <int MaxRows>
class SmallFullPivLU {
  static_assert(MaxRows != Eigen::Dynamic && MaxRows <= 8, "for the stack-stored sizes only");

 public:
  // The storage of SmallLU, whose Newton systems these are.
  using Mat = typename SmallLU<MaxRows>::Mat;
  using Vec = typename SmallLU<MaxRows>::Vec;

  /// Factorises P A Q = L U of the square A (1 ≤ rows ≤ MaxRows).
  void compute(const Mat& A) {
    n_ = static_cast<int>(A.rows());
    with_fixed_size<MaxRows>(n_, [&](auto k) { factor<decltype(k)::value>(A); });
  }

  /// A solution x of A x = b where the system is consistent (the free unknowns zero), as
  /// FullPivLU::solve; the caller checks the residual.
  void solve(const Vec& b, Vec& x) const {
    x.resize(n_);
    with_fixed_size<MaxRows>(n_, [&](auto k) { substitute<decltype(k)::value>(b, x); });
  }

  int rank() const { return rank_; }

 private:
  template <int K>
  void factor(const Mat& A) {
    if constexpr (K == 0) {  // no rows (the only size outside 1 … MaxRows that Mat can hold)
      rank_ = 0;
      return;
    }
    for (int j = 0; j < K; ++j)
      for (int i = 0; i < K; ++i) lu_[i][j] = A(i, j);
    for (int i = 0; i < K; ++i) row_perm_[i] = col_perm_[i] = i;
    double max_pivot = 0.0;
    int nonzero = K;
    for (int k = 0; k < K; ++k) {
      // The largest |entry| of the remaining corner, column by column (FullPivLU's maxCoeff).
      int pr = k, pc = k;
      double biggest = std::fabs(lu_[k][k]);
      for (int j = k; j < K; ++j)
        for (int i = k; i < K; ++i)
          if (std::fabs(lu_[i][j]) > biggest) {
            biggest = std::fabs(lu_[i][j]);
            pr = i;
            pc = j;
          }
      if (biggest == 0.0) {
        nonzero = k;
        break;
      }
      max_pivot = std::max(max_pivot, biggest);
      if (pr != k) {
        std::swap(lu_[k], lu_[pr]);
        std::swap(row_perm_[k], row_perm_[pr]);
      }
      if (pc != k) {
        for (int i = 0; i < K; ++i) std::swap(lu_[i][k], lu_[i][pc]);
        std::swap(col_perm_[k], col_perm_[pc]);
      }
      const double pivot = lu_[k][k];
      for (int i = k + 1; i < K; ++i) lu_[i][k] /= pivot;
      for (int i = k + 1; i < K; ++i)
        for (int j = k + 1; j < K; ++j) lu_[i][j] -= lu_[i][k] * lu_[k][j];
    }
    const double threshold = std::numeric_limits<double>::epsilon() * K * max_pivot;
    rank_ = 0;
    for (int i = 0; i < nonzero; ++i) rank_ += std::fabs(lu_[i][i]) > threshold ? 1 : 0;
  }

  template <int K>
  void substitute(const Vec& b, Vec& x) const {
    if (rank_ == 0) {
      x.setZero();
      return;
    }
    std::array<double, (K > 0 ? K : 1)> c;
    for (int i = 0; i < K; ++i) c[i] = b(row_perm_[i]);
    for (int i = 0; i < K; ++i)
      for (int j = 0; j < i; ++j) c[i] -= lu_[i][j] * c[j];
    for (int i = rank_ - 1; i >= 0; --i) {
      for (int j = i + 1; j < rank_; ++j) c[i] -= lu_[i][j] * c[j];
      c[i] /= lu_[i][i];
    }
    for (int i = 0; i < K; ++i) x(col_perm_[i]) = i < rank_ ? c[i] : 0.0;
  }

  std::array<std::array<double, MaxRows>, MaxRows> lu_{};  // lu_[row][column]
  std::array<int, MaxRows> row_perm_{}, col_perm_{};       // original index of row / column k
  int n_ = 0;
  int rank_ = 0;
};

}  // namespace fremond::detail
