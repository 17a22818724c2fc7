// The problem file's schema of Stronge's law (docs/problem-file.md, `law`): {"type": "stronge",
// "e"} and {"type": "stronge_coulomb", "e", "mu"}, each a number or one per contact.
#include <tuple>

#include "io/detail/json_law.hpp"
#include "laws/stronge/plugin.hpp"

namespace fremond::detail {

ImpactLaw read_law(std::type_identity<StrongeLaw>, std::string_view name, const nlohmann::json& j,
                   int contacts, const PotentialRegistry& /*registry*/, const std::string& where) {
  using namespace io::detail;
  StrongeLaw law;
  law.coulomb = name.ends_with("_coulomb");
  std::tie(law.e.values, law.mu.values) = restitution_values(j, where, name, law.coulomb, contacts);
  return built([&] { return ImpactLaw(law); }, contacts, j, where);
}

}  // namespace fremond::detail
