// The impact law's JSON schema (docs/problem-file.md, `law`). The library stays the authority on
// values: ImpactLaw's factories and validate(), the potentials' constructors and the registry
// refuse a bad e, μ or parameter; this file reads types, shapes and key names, refuses keys nobody
// asked for, and renames the library's keys to the ones the file spells.
#include "io/detail/json_law.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <variant>

#include "fremond/core/error.hpp"
#include "laws/detail/plugins.hpp"

namespace fremond::io::detail {

namespace {

// The reason part of an InvalidArgument ("name: reason"), to rename the key it names.
std::string reason_of(const InvalidArgument& e) {
  return std::string(e.what()).substr(e.name().size() + 2);
}

// "where.k: <reason>" from the registry or a constructor, renamed to the list element when the
// parameter was a per-contact list: "where.k[1]: <reason>".
[[noreturn]] void rethrow_for_contact(const InvalidArgument& e, const std::string& where,
                                      const std::map<std::string, std::vector<double>>& params,
                                      std::size_t contact) {
  const std::string prefix = where + ".";
  if (e.name().rfind(prefix, 0) == 0) {
    const auto it = params.find(e.name().substr(prefix.size()));
    if (it != params.end()) {
      if (it->second.size() == 1) throw e;  // the same value for every contact
      throw InvalidArgument(index_path(e.name(), contact), reason_of(e));
    }
  }
  throw InvalidArgument(e.name(), reason_of(e) + " (contact " + std::to_string(contact) + ")");
}

}  // namespace

PerContactPotential potential_from_json(const json& j, const std::string& where, int contacts,
                                        const PotentialRegistry& registry) {
  require_object(j, where);
  const std::string name_key = key_path(where, "potential");
  const std::string name = string_from_json(required_key(j, where, "potential"), name_key);
  const PotentialKind* kind = nullptr;
  try {
    kind = &registry.kind(name);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(name_key, reason_of(e));
  }
  // Keys first, so that a misspelt parameter is reported as such and not as a bad value.
  std::vector<std::string_view> allowed{"potential"};
  for (const auto& r : kind->required) allowed.push_back(r);
  for (const auto& [o, v] : kind->optional) allowed.push_back(o);
  refuse_unknown_keys(j, where, allowed,
                      "unknown key: not a parameter of potential '" + name + "'");
  for (const auto& r : kind->required)
    if (!j.contains(r))
      throw InvalidArgument(key_path(where, r), "missing, required by potential '" + name + "'");

  std::map<std::string, std::vector<double>> lists;
  bool per_contact = false;
  for (const auto& item : j.items()) {
    if (item.key() == "potential") continue;
    lists[item.key()] = number_or_list(item.value(), key_path(where, item.key()), contacts);
    per_contact = per_contact || item.value().is_array();
  }
  auto parameters_of = [&](std::size_t contact) {
    PotentialParameters p;
    for (const auto& [k, v] : lists) p[k] = v.size() == 1 ? v[0] : v[contact];
    return p;
  };
  PerContactPotential out;
  if (!per_contact) {
    out.potentials.emplace_back(registry.make(name, parameters_of(0), where));
    return out;
  }
  // A list of one value is the same for every contact; only a longer list makes one potential per
  // contact, so a problem with one contact and `"k": [2]` still has one potential.
  std::size_t count = 1;
  for (const auto& [k, v] : lists) count = std::max(count, v.size());
  for (std::size_t i = 0; i < count; ++i) {
    try {
      out.potentials.emplace_back(registry.make(name, parameters_of(i), where));
    } catch (const InvalidArgument& e) {
      rethrow_for_contact(e, where, lists, i);
    }
  }
  return out;
}

InvalidArgument with_file_key(const InvalidArgument& e, const json& j, const std::string& where) {
  const std::string& name = e.name();
  if (name.rfind("law", 0) != 0) return e;
  const std::string rest = name.substr(3);  // "", ".e", ".mu[1]", ...
  const std::string member = rest.empty() ? "" : rest.substr(1, rest.find('[') - 1);
  std::string file = where + rest;
  const json* value = member.empty() ? nullptr : optional_key(j, member);
  if (member == "mu" && !value) {  // Frémond's law: `tangential: {"potential": "coulomb", "mu"}`
    const json* tangential = optional_key(j, "tangential");
    value = tangential && tangential->is_object() ? optional_key(*tangential, "mu") : nullptr;
    file = key_path(where, "tangential") + rest;
  }
  if (rest == "." + member && value && value->is_array() && value->size() == 1) file += "[0]";
  return InvalidArgument(file, reason_of(e));
}

std::vector<double> values(const json& obj, const std::string& obj_key, std::string_view key,
                           int contacts) {
  return number_or_list(required_key(obj, obj_key, key), key_path(obj_key, key), contacts);
}

std::pair<std::vector<double>, std::vector<double>> restitution_values(const json& j,
                                                                       const std::string& where,
                                                                       std::string_view name,
                                                                       bool coulomb, int contacts) {
  const std::string context = "a '" + std::string(name) + "' law";
  if (coulomb)
    check_keys(j, where, {"type", "e", "mu"}, context);
  else
    check_keys(j, where, {"type", "e"}, context);
  auto e = values(j, where, "e", contacts);
  auto mu = coulomb ? values(j, where, "mu", contacts) : std::vector<double>{0.0};
  return {std::move(e), std::move(mu)};
}

namespace {
// The law named `name` read by its own schema (its read_law); nothing for a name no law has.
template <std::size_t I = 0>
std::optional<ImpactLaw> read_named(std::string_view name, const json& j, int contacts,
                                    const PotentialRegistry& registry, const std::string& where) {
  if constexpr (I == std::variant_size_v<LawVariant>) {
    return std::nullopt;
  } else {
    using Law = std::variant_alternative_t<I, LawVariant>;
    for (std::string_view n : Law::names)
      if (n == name)
        return fremond::detail::read_law(std::type_identity<Law>{}, name, j, contacts, registry,
                                         where);
    return read_named<I + 1>(name, j, contacts, registry, where);
  }
}
}  // namespace

ImpactLaw law_from_json(const json& j, int contacts, const PotentialRegistry& registry,
                        const std::string& where) {
  require_object(j, where);
  const std::string key = key_path(where, "type");
  const std::string name = string_from_json(required_key(j, where, "type"), key);
  try {
    check_law_name(name);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(key, reason_of(e));
  }
  // A known name: every law of the list has its schema.
  return std::move(*read_named(name, j, contacts, registry, where));
}

}  // namespace fremond::io::detail
