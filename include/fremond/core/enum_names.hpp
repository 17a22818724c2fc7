#pragma once
/// @file The one table-driven implementation behind every to_string / from_string pair.
#include <array>
#include <string>
#include <string_view>
#include <utility>

#include "fremond/core/error.hpp"

namespace fremond::detail {

template <class E, std::size_t N>
using EnumNames = std::array<std::pair<E, std::string_view>, N>;

template <class E, std::size_t N>
std::string_view enum_to_string(const EnumNames<E, N>& names, E value) {
  for (const auto& [v, s] : names)
    if (v == value) return s;
  return "unknown";
}

/// Throws InvalidArgument(what, "unknown value 'x' (one of: a, b, c)").
template <class E, std::size_t N>
E enum_from_string(const EnumNames<E, N>& names, std::string_view text, const char* what) {
  for (const auto& [v, s] : names)
    if (s == text) return v;
  std::string known;
  for (const auto& [v, s] : names) known += (known.empty() ? "" : ", ") + std::string(s);
  throw InvalidArgument(what, "unknown value '" + std::string(text) + "' (one of: " + known + ")");
}

}  // namespace fremond::detail
