// A pivot's update of one row of Lemke's tableau (detail/lemke.hpp), with a second build of the
// loop for processors with AVX2, chosen at run time. No FMA: a fused product and difference would
// round once where the portable loop rounds twice, and the answers would differ by processor.
#include "solvers/detail/lemke.hpp"

namespace fremond::detail::lcp {

namespace {

[[gnu::always_inline]] inline void subtract(double* y, const double* x, double f, int len) {
  for (int c = 0; c < len; ++c) y[c] -= f * x[c];
}

#if defined(__x86_64__) && !defined(__AVX2__)
#define FREMOND_AVX2_AT_RUN_TIME 1
[[gnu::target("avx2")]] void subtract_avx2(double* y, const double* x, double f, int len) {
  subtract(y, x, f, len);
}
#endif

}  // namespace

void subtract_multiple(double* y, const double* x, double f, int len) {
#ifdef FREMOND_AVX2_AT_RUN_TIME
  if (__builtin_cpu_supports("avx2")) return subtract_avx2(y, x, f, len);
#endif
  subtract(y, x, f, len);
}

}  // namespace fremond::detail::lcp
