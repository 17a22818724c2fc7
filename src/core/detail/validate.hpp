#pragma once
/// @file Parameter checks shared by the built-in potentials and laws (messages name the parameter).
#include <cmath>
#include <sstream>
#include <string>

#include "fremond/core/error.hpp"

namespace fremond::detail {

inline std::string format_number(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

inline void require_finite(const std::string& name, double v) {
  if (!std::isfinite(v))
    throw InvalidArgument(name, "must be a finite number, got " + format_number(v));
}
inline void require_finite_at_least(const std::string& name, double v, double lo) {
  require_finite(name, v);
  if (!(v >= lo))
    throw InvalidArgument(name, "must be >= " + format_number(lo) + ", got " + format_number(v));
}
inline void require_finite_above(const std::string& name, double v, double lo) {
  require_finite(name, v);
  if (!(v > lo))
    throw InvalidArgument(name, "must be > " + format_number(lo) + ", got " + format_number(v));
}
inline void require_in_unit_interval(const std::string& name, double v) {
  require_finite(name, v);
  if (!(v >= 0.0 && v <= 1.0))
    throw InvalidArgument(name, "must lie in [0, 1], got " + format_number(v));
}

}  // namespace fremond::detail
