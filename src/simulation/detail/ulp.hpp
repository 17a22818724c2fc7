#pragma once
/// @file The unit in the last place of a double, as the event search and the accumulation test use
/// it to say "within rounding of a time".
#include <bit>
#include <cmath>
#include <cstdint>

namespace fremond::detail {

/// The gap from |x| to the next larger double, nextafter(|x|, +∞) − |x|, with the same value for
/// every x (+∞ and NaN give NaN, the largest finite double gives +∞). By the bit pattern: the
/// doubles ≥ 0 are ordered as their patterns are, so the next one up is the pattern plus one.
/// The event search takes it at every interval it splits; std::nextafter is an out-of-line libm
/// call costing as much as the rest of a split.
inline double ulp(double x) {
  const double a = std::fabs(x);
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(a) + 1) - a;
}

}  // namespace fremond::detail
