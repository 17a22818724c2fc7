#pragma once
// The checks every law makes of its per-contact lists, with the messages that name them.
#include <cmath>
#include <cstddef>
#include <string>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"
#include "fremond/laws/per_contact.hpp"

namespace fremond::detail {

inline bool count_fits(std::size_t size, int contacts) {
  return size == 1 || static_cast<int>(size) == contacts;
}

/// Throws InvalidArgument(name, ...) unless the list holds one value or one per contact.
inline void check_count(const char* name, std::size_t size, int contacts) {
  if (count_fits(size, contacts)) return;
  throw InvalidArgument(name, "needs one value or one per contact (" + std::to_string(contacts) +
                                  "), got " + std::to_string(size));
}

/// The name of entry i of a list: `law.e` for a list of one, `law.e[1]` otherwise.
inline std::string entry_name(const char* name, const PerContact& v, std::size_t i) {
  return v.values.size() == 1 ? std::string(name)
                              : std::string(name) + "[" + std::to_string(i) + "]";
}

/// μ ≥ 0 and finite, for each contact.
inline bool friction_fits(const PerContact& mu, int contacts) {
  if (!count_fits(mu.values.size(), contacts)) return false;
  for (double v : mu.values)
    if (!(v >= 0.0 && std::isfinite(v))) return false;
  return true;
}
inline void check_friction(const PerContact& mu, int contacts) {
  check_count("law.mu", mu.values.size(), contacts);
  for (std::size_t i = 0; i < mu.values.size(); ++i)
    require_finite_at_least(entry_name("law.mu", mu, i), mu.values[i], 0.0);
}

/// A list of values as describe() writes it: "0.5" or "[0.2, 0.3]".
inline std::string describe_list(const PerContact& v) {
  std::string s;
  for (double x : v.values) s += (s.empty() ? "" : ", ") + format_number(x);
  return v.values.size() == 1 ? s : "[" + s + "]";
}

}  // namespace fremond::detail
