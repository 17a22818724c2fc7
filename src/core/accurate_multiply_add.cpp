// The accurate sums of accurate_residual and accurate_dot (core/detail/accurate_dot.hpp), with a
// second build of each loop for processors with FMA (and AVX2), chosen at run time. This file is
// compiled without floating-point contraction: a contracted s + a·x would no longer be TwoSum's
// rounded sum.
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

// Dot2 (Ogita, Rump and Oishi), accurate_dot's loop; the fma is an instruction in the build for
// FMA processors and where the compiler targets them, else a library call.
[[gnu::always_inline]] inline double dot2(const double* x, std::ptrdiff_t incx, const double* y,
                                          std::ptrdiff_t incy, Eigen::Index n, double extra) {
  double s = extra, c = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double a = x[i * incx], b = y[i * incy];
    const double p = a * b;
    const double ep = std::fma(a, b, -p);  // p + ep = a b exactly
    const double t = s + p;
    const double z = t - s;
    const double es = (s - (t - z)) + (p - z);  // t + es = s + p exactly (TwoSum)
    s = t;
    c += ep + es;
  }
  // Overflow (|W| near 1e308): the error terms are ∞ − ∞; the plain sum says what overflowed.
  const double r = s + c;
  return std::isfinite(r) ? r : s;
}

#if defined(__x86_64__) && !defined(__FMA__)
#define FREMOND_FMA_AT_RUN_TIME 1
[[gnu::target("avx2,fma")]] void multiply_add_fma(const double* M, std::ptrdiff_t ld, int n, int m,
                                                  const double* x, double* s, double* e) {
  multiply_add<true>(M, ld, n, m, x, s, e);
}
[[gnu::target("fma")]] double dot2_fma(const double* x, std::ptrdiff_t incx, const double* y,
                                       std::ptrdiff_t incy, Eigen::Index n, double extra) {
  return dot2(x, incx, y, incy, n, extra);
}
// The loop with unit strides known: no index products (the same operations, in the same order).
[[gnu::target("fma")]] double dot2_fma_contiguous(const double* x, const double* y, Eigen::Index n,
                                                  double extra) {
  return dot2(x, 1, y, 1, n, extra);
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

namespace {
// The portable loops out of line, so that the dispatchers below are a test and a jump each (with
// a loop inlined beside the test, every call paid for saving the loop's registers first).
[[gnu::noinline]] double dot2_portable(const double* x, std::ptrdiff_t incx, const double* y,
                                       std::ptrdiff_t incy, Eigen::Index n, double extra) {
  return dot2(x, incx, y, incy, n, extra);
}
[[gnu::noinline]] double dot2_portable_contiguous(const double* x, const double* y, Eigen::Index n,
                                                  double extra) {
  return dot2(x, 1, y, 1, n, extra);
}
}  // namespace

double accurate_dot_strided(const double* x, std::ptrdiff_t incx, const double* y,
                            std::ptrdiff_t incy, Eigen::Index n, double extra) {
#ifdef FREMOND_FMA_AT_RUN_TIME
  if (__builtin_cpu_supports("fma")) return dot2_fma(x, incx, y, incy, n, extra);
#endif
  return dot2_portable(x, incx, y, incy, n, extra);
}

double accurate_dot_contiguous(const double* x, const double* y, Eigen::Index n, double extra) {
#ifdef FREMOND_FMA_AT_RUN_TIME
  if (__builtin_cpu_supports("fma")) return dot2_fma_contiguous(x, y, n, extra);
#endif
  return dot2_portable_contiguous(x, y, n, extra);
}

void accurate_multiply_add_portable(const double* M, std::ptrdiff_t ld, int n, int m,
                                    const double* x, double* s, double* e) {
  multiply_add<false>(M, ld, n, m, x, s, e);
}

}  // namespace fremond::detail
