// The accurate sums of accurate_residual (core/detail/accurate_dot.hpp), with a second build of
// the loop for processors with AVX2 and FMA, chosen at run time. This file is compiled without
// floating-point contraction: a contracted s + a·x would no longer be TwoSum's rounded sum.
#include <cmath>
#include <cstddef>

#include "core/detail/accurate_dot.hpp"

namespace fremond::detail {

namespace {

template <bool Fma>
[[gnu::always_inline]] inline void multiply_add(const double* M, std::ptrdiff_t ld, int n, int m,
                                                const double* x, double* s, double* e) {
  for (int j = 0; j < m; ++j) {
    const double xj = x[j];
    const double* const col = M + j * ld;
    for (int i = 0; i < n; ++i) {
      const double a = col[i];
      const double p = a * xj;
      double ep;
      if constexpr (Fma)
        ep = std::fma(a, xj, -p);
      else
        ep = two_product_error(a, xj, p);
      const double t = s[i] + p;
      const double z = t - s[i];
      const double es = (s[i] - (t - z)) + (p - z);  // t + es = s_i + p exactly (TwoSum)
      s[i] = t;
      e[i] += ep + es;
    }
  }
}

#if defined(__x86_64__) && !defined(__FMA__)
#define FREMOND_FMA_AT_RUN_TIME 1
[[gnu::target("avx2,fma")]] void multiply_add_fma(const double* M, std::ptrdiff_t ld, int n, int m,
                                                  const double* x, double* s, double* e) {
  multiply_add<true>(M, ld, n, m, x, s, e);
}
#endif

}  // namespace

void accurate_multiply_add(const double* M, std::ptrdiff_t ld, int n, int m, const double* x,
                           double* s, double* e) {
#if defined(__FMA__)
  multiply_add<true>(M, ld, n, m, x, s, e);
#else
#ifdef FREMOND_FMA_AT_RUN_TIME
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    return multiply_add_fma(M, ld, n, m, x, s, e);
#endif
  accurate_multiply_add_portable(M, ld, n, m, x, s, e);
#endif
}

void accurate_multiply_add_portable(const double* M, std::ptrdiff_t ld, int n, int m,
                                    const double* x, double* s, double* e) {
  multiply_add<false>(M, ld, n, m, x, s, e);
}

}  // namespace fremond::detail
