#pragma once
/// @file Vectors whose size is a template argument where the caller knows it (the dofs of the
/// paper's planar bodies, 3; a point mass, 1 or 2; a body in space, 6), dynamic otherwise: the
/// same loops over them unroll where the size is fixed, and give the same bits either way.
#include <Eigen/Core>
#include <type_traits>

namespace fremond::detail {

/// K entries, K fixed; or a dynamic size bounded by Max where K is Eigen::Dynamic.
template <int K, int Max>
using SizedVecT = Eigen::Matrix<double, K, 1, Eigen::ColMajor, K == Eigen::Dynamic ? Max : K, 1>;

/// The number of entries of a SizedVecT<K, ·> holding n: K where it is fixed.
template <int K>
constexpr int sized(int n) {
  return K == Eigen::Dynamic ? n : K;
}

/// Calls f(std::integral_constant<int, K>{}) with K = n for the sizes 3, 2, 1 and 6 of a
/// stack-stored problem (Max fixed, at least K), else with K = Eigen::Dynamic; returns what f
/// returns. A heap-stored problem is beyond those sizes or holds more contacts than the stack
/// form: it keeps the dynamic loops, one instantiation.
template <int Max, class F>
decltype(auto) with_size(int n, F&& f) {
  if constexpr (Max != Eigen::Dynamic) {
    if constexpr (Max >= 3)
      if (n == 3) return f(std::integral_constant<int, 3>{});
    if constexpr (Max >= 2)
      if (n == 2) return f(std::integral_constant<int, 2>{});
    if (n == 1) return f(std::integral_constant<int, 1>{});
    if constexpr (Max >= 6)
      if (n == 6) return f(std::integral_constant<int, 6>{});
  }
  return f(std::integral_constant<int, Eigen::Dynamic>{});
}

}  // namespace fremond::detail
