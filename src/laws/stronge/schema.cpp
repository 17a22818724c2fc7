// The problem file's schema of Stronge's law (docs/problem-file.md, `law`): {"type": "stronge",
// "e"} and {"type": "stronge_coulomb", "e", "mu"}, each a number or one per contact, and for
// coupled contacts the distributing law's "eta" and "stiffness" (optional, 1 by default).
#include <string>

#include "io/detail/json_law.hpp"
#include "laws/stronge/plugin.hpp"

namespace fremond::detail {

ImpactLaw read_law(std::type_identity<StrongeLaw>, std::string_view name, const nlohmann::json& j,
                   int contacts, const PotentialRegistry& /*registry*/, const std::string& where) {
  using namespace io::detail;
  StrongeLaw law;
  law.coulomb = name.ends_with("_coulomb");
  const std::string context = "a '" + std::string(name) + "' law";
  if (law.coulomb)
    check_keys(j, where, {"type", "e", "mu", "eta", "stiffness"}, context);
  else
    check_keys(j, where, {"type", "e", "eta", "stiffness"}, context);
  law.e.values = values(j, where, "e", contacts);
  if (law.coulomb) law.mu.values = values(j, where, "mu", contacts);
  if (optional_key(j, "eta")) law.eta.values = values(j, where, "eta", contacts);
  if (optional_key(j, "stiffness")) law.stiffness.values = values(j, where, "stiffness", contacts);
  return built([&] { return ImpactLaw(law); }, contacts, j, where);
}

}  // namespace fremond::detail
