// The problem file's schema of Newton's and Poisson's laws (docs/problem-file.md, `law`):
// {"type": "newton" | "poisson", "e"} and, with Coulomb, {"type": "..._coulomb", "e", "mu"},
// each a number or one per contact.
#include <tuple>

#include "io/detail/json_law.hpp"
#include "laws/restitution/plugin.hpp"

namespace fremond::detail {

ImpactLaw read_law(std::type_identity<RestitutionLaw>, std::string_view name,
                   const nlohmann::json& j, int contacts, const PotentialRegistry& /*registry*/,
                   const std::string& where) {
  using namespace io::detail;
  RestitutionLaw law;
  law.kind =
      name.starts_with("poisson") ? RestitutionLaw::Kind::poisson : RestitutionLaw::Kind::newton;
  law.coulomb = name.ends_with("_coulomb");
  std::tie(law.e.values, law.mu.values) = restitution_values(j, where, name, law.coulomb, contacts);
  return built([&] { return ImpactLaw(law); }, contacts, j, where);
}

}  // namespace fremond::detail
