// The problem file's schema of Frémond's laws (docs/problem-file.md, `law`): {"type": "fremond",
// "normal": POTENTIAL, "tangential": POTENTIAL or {"potential": "coulomb", "mu"}}, the potentials
// named by their registry name, every parameter a number or one per contact.
#include "io/detail/json_law.hpp"
#include "laws/fremond/plugin.hpp"

namespace fremond::detail {

ImpactLaw read_law(std::type_identity<FremondLaw>, std::string_view name, const nlohmann::json& j,
                   int contacts, const PotentialRegistry& registry, const std::string& where) {
  using namespace io::detail;
  check_keys(j, where, {"type", "normal", "tangential"}, "a '" + std::string(name) + "' law");
  const std::string normal_key = key_path(where, "normal");
  const json& normal = required_key(j, where, "normal");
  // Coulomb is a law on the tangential velocity, not a potential of the normal one (docs/laws.md).
  if (normal.is_object() && normal.contains("potential") && normal["potential"] == "coulomb")
    throw InvalidArgument(
        key_path(normal_key, "potential"),
        "'coulomb' is a tangential law only (use it under " + key_path(where, "tangential") + ")");
  auto normal_potential = potential_from_json(normal, normal_key, contacts, registry);
  const json* tangential = optional_key(j, "tangential");
  if (!tangential)  // docs/problem-file.md: omitted means no tangential percussion
    return built([&] { return ImpactLaw::fremond(std::move(normal_potential)); }, contacts, j,
                 where);
  const std::string tkey = key_path(where, "tangential");
  require_object(*tangential, tkey);
  const std::string tname =
      string_from_json(required_key(*tangential, tkey, "potential"), key_path(tkey, "potential"));
  if (tname == "coulomb") {
    check_keys(*tangential, tkey, {"potential", "mu"}, "the tangential law 'coulomb'");
    const auto mu = values(*tangential, tkey, "mu", contacts);
    return built([&] { return ImpactLaw::fremond_coulomb(std::move(normal_potential), mu); },
                 contacts, j, where);
  }
  auto tangential_potential = potential_from_json(*tangential, tkey, contacts, registry);
  return built(
      [&] {
        return ImpactLaw::fremond(std::move(normal_potential), std::move(tangential_potential));
      },
      contacts, j, where);
}

}  // namespace fremond::detail
