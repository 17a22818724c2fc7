#pragma once
/// @file A double for JSON output: JSON has no NaN or infinity, so a value that is not finite (a
/// residual never computed, a failed solve) is written as null, which any JSON reader accepts.
#include <cmath>
#include <nlohmann/json.hpp>

namespace fremond::io::detail {

inline nlohmann::ordered_json json_number(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

}  // namespace fremond::io::detail
