#pragma once
// A row count known at run time, turned into one known at compile time, for the small dense
// kernels of the solvers (LU of a Newton Jacobian, the pivoted LDLᵀ of a singular Delassus
// matrix): over 2 to 8 rows, loops of run-time length cost several times their arithmetic, loops of
// compile-time length unroll.
#include <type_traits>

namespace fremond::detail {

/// Returns f(std::integral_constant<int, K>{}) with K = n where 1 ≤ n ≤ Cap (Cap at most 8), and
/// f(std::integral_constant<int, 0>{}) otherwise: the caller's path for other sizes (its run-time
/// loops, or a refusal).
template <int Cap, class F>
decltype(auto) with_fixed_size(int n, F&& f) {
  static_assert(Cap <= 8, "sizes above 8 rows are not unrolled");
  using std::integral_constant;
  switch (n) {
    case 1:
      if constexpr (Cap >= 1) return f(integral_constant<int, 1>{});
      break;
    case 2:
      if constexpr (Cap >= 2) return f(integral_constant<int, 2>{});
      break;
    case 3:
      if constexpr (Cap >= 3) return f(integral_constant<int, 3>{});
      break;
    case 4:
      if constexpr (Cap >= 4) return f(integral_constant<int, 4>{});
      break;
    case 5:
      if constexpr (Cap >= 5) return f(integral_constant<int, 5>{});
      break;
    case 6:
      if constexpr (Cap >= 6) return f(integral_constant<int, 6>{});
      break;
    case 7:
      if constexpr (Cap >= 7) return f(integral_constant<int, 7>{});
      break;
    case 8:
      if constexpr (Cap >= 8) return f(integral_constant<int, 8>{});
      break;
    default:
      break;
  }
  return f(integral_constant<int, 0>{});
}

}  // namespace fremond::detail
