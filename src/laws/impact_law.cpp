#include "fremond/laws/impact_law.hpp"

#include <algorithm>

#include "fremond/core/error.hpp"

namespace fremond {

std::vector<std::string_view> law_names() {
  std::vector<std::string_view> all;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (..., all.insert(all.end(), std::variant_alternative_t<I, LawVariant>::names.begin(),
                     std::variant_alternative_t<I, LawVariant>::names.end()));
  }
  (std::make_index_sequence<std::variant_size_v<LawVariant>>{});
  return all;
}

void check_law_name(std::string_view name) {
  const auto all = law_names();
  if (std::find(all.begin(), all.end(), name) != all.end()) return;
  std::string known;
  for (std::string_view n : all) known += (known.empty() ? "" : ", ") + std::string(n);
  throw InvalidArgument("law.type",
                        "unknown value '" + std::string(name) + "' (one of: " + known + ")");
}

// A law is refused where it is made: its values (e in [0, 1], μ ≥ 0, potentials present) for as
// many contacts as its longest list; the count against a problem waits for validate(contacts).
void ImpactLaw::check_values() const {
  visit([](const auto& l) { l.validate(static_cast<int>(l.longest_list())); });
}

void ImpactLaw::throw_not(std::string_view wanted) const {
  throw InvalidArgument(
      "law", "is a '" + std::string(name()) + "' law, not a '" + std::string(wanted) + "' one");
}

ImpactLaw ImpactLaw::newton(PerContact e) {
  return RestitutionLaw{RestitutionLaw::Kind::newton, std::move(e)};
}
ImpactLaw ImpactLaw::poisson(PerContact e) {
  return RestitutionLaw{RestitutionLaw::Kind::poisson, std::move(e)};
}
ImpactLaw ImpactLaw::newton_coulomb(PerContact e, PerContact mu) {
  return RestitutionLaw{RestitutionLaw::Kind::newton, std::move(e), true, std::move(mu)};
}
ImpactLaw ImpactLaw::poisson_coulomb(PerContact e, PerContact mu) {
  return RestitutionLaw{RestitutionLaw::Kind::poisson, std::move(e), true, std::move(mu)};
}
ImpactLaw ImpactLaw::fremond(PerContactPotential normal) {
  FremondLaw law;
  law.normal = std::move(normal);
  return law;
}
ImpactLaw ImpactLaw::fremond(PerContactPotential normal, PerContactPotential tangential) {
  FremondLaw law;
  law.normal = std::move(normal);
  law.tangential = TangentialLaw::potential;
  law.tangential_potential = std::move(tangential);
  return law;
}
ImpactLaw ImpactLaw::fremond_coulomb(PerContactPotential normal, PerContact mu) {
  FremondLaw law;
  law.normal = std::move(normal);
  law.tangential = TangentialLaw::coulomb;
  law.mu = std::move(mu);
  return law;
}

}  // namespace fremond
