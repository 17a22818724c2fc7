#pragma once
// The checks every law makes of its per-contact lists, with the messages that name them.
#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

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

/// A restitution coefficient in [0, 1], for each contact.
inline bool unit_interval_fits(const PerContact& e, int contacts) {
  if (!count_fits(e.values.size(), contacts)) return false;
  for (double v : e.values)
    if (!(v >= 0.0 && v <= 1.0)) return false;
  return true;
}
inline void check_unit_interval(const char* name, const PerContact& e, int contacts) {
  check_count(name, e.values.size(), contacts);
  for (std::size_t i = 0; i < e.values.size(); ++i)
    require_in_unit_interval(entry_name(name, e, i), e.values[i]);
}

/// A list of values as describe() writes it: "0.5" or "[0.2, 0.3]".
inline std::string describe_list(const PerContact& v) {
  std::string s;
  for (double x : v.values) s += (s.empty() ? "" : ", ") + format_number(x);
  return v.values.size() == 1 ? s : "[" + s + "]";
}

/// "name(e=..., mu=...)": a restitution law's description, μ where it has Coulomb's.
inline std::string describe_restitution(std::string_view name, const PerContact& e, bool coulomb,
                                        const PerContact& mu) {
  std::string out = std::string(name) + "(e=" + describe_list(e);
  if (coulomb) out += ", mu=" + describe_list(mu);
  return out + ")";
}

/// The restitution of every contact, 0 for the separating ones (D_N > 0): their reaction alone
/// (docs/concepts.md).
inline PerContact without_separating(const PerContact& e, std::span<const double> D_N) {
  std::vector<double> each(D_N.size());
  for (std::size_t i = 0; i < D_N.size(); ++i)
    each[i] = D_N[i] > 0.0 ? 0.0 : e[static_cast<int>(i)];
  return PerContact(std::move(each));
}

}  // namespace fremond::detail
