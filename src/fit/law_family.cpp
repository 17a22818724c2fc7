#include "fremond/fit/law_family.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "fremond/core/error.hpp"
#include "fremond/potentials/deadzone_power.hpp"
#include "fremond/potentials/power.hpp"

namespace fremond {

namespace {

constexpr std::array<std::string_view, 9> kNames{
    "newton",          "poisson", "newton_coulomb",  "poisson_coulomb", "stronge",
    "stronge_coulomb", "fremond", "fremond_coulomb", "fremond_deadzone"};

}  // namespace

const std::vector<LawFamily>& law_families() {
  static const std::vector<LawFamily> all{
      LawFamily::newton,          LawFamily::poisson,         LawFamily::newton_coulomb,
      LawFamily::poisson_coulomb, LawFamily::stronge,         LawFamily::stronge_coulomb,
      LawFamily::fremond,         LawFamily::fremond_coulomb, LawFamily::fremond_deadzone};
  return all;
}

std::string_view to_string(LawFamily family) {
  return kNames[static_cast<std::size_t>(family)];
}

LawFamily law_family_from_string(std::string_view name) {
  for (const LawFamily f : law_families())
    if (to_string(f) == name) return f;
  std::string known;
  for (const auto n : kNames) known += (known.empty() ? "" : ", ") + std::string(n);
  throw InvalidArgument("law",
                        "unknown law family '" + std::string(name) + "' (known: " + known + ")");
}

std::vector<std::string> fitted_parameters(LawFamily family) {
  switch (family) {
    case LawFamily::newton:
    case LawFamily::poisson:
    case LawFamily::stronge:
      return {"e"};
    case LawFamily::newton_coulomb:
    case LawFamily::poisson_coulomb:
    case LawFamily::stronge_coulomb:
      return {"e", "mu"};
    case LawFamily::fremond:
      return {"k", "p"};
    case LawFamily::fremond_coulomb:
      return {"k", "p", "mu"};
    case LawFamily::fremond_deadzone:
      return {"k", "p", "k_T"};
  }
  return {};
}

std::map<std::string, double> held_parameters(LawFamily family) {
  // q = 2: a viscous tangential law, linear in the mean velocity outside the dead zone; r = 0: no
  // dead zone. Both are poorly determined by velocities alone, so they are held unless given.
  if (family == LawFamily::fremond_deadzone) return {{"q", 2.0}, {"r", 0.0}};
  return {};
}

ImpactLaw make_law(LawFamily family, const std::map<std::string, double>& values) {
  std::map<std::string, double> v = held_parameters(family);
  const auto names = fitted_parameters(family);
  for (const auto& [name, value] : values) {
    const bool known =
        v.count(name) > 0 || std::find(names.begin(), names.end(), name) != names.end();
    if (!known) {
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      for (const auto& [n, x] : held_parameters(family)) list += ", " + n;
      throw InvalidArgument(name, "is not a parameter of " + std::string(to_string(family)) +
                                      " (its parameters: " + list + ")");
    }
    v[name] = value;
  }
  for (const auto& n : names)
    if (!v.count(n))
      throw InvalidArgument(n, "missing: " + std::string(to_string(family)) + " needs it");
  switch (family) {
    case LawFamily::newton:
      return ImpactLaw::newton(v["e"]);
    case LawFamily::poisson:
      return ImpactLaw::poisson(v["e"]);
    case LawFamily::newton_coulomb:
      return ImpactLaw::newton_coulomb(v["e"], v["mu"]);
    case LawFamily::poisson_coulomb:
      return ImpactLaw::poisson_coulomb(v["e"], v["mu"]);
    case LawFamily::stronge:
    case LawFamily::stronge_coulomb: {
      StrongeLaw law;
      law.e = v["e"];
      law.coulomb = family == LawFamily::stronge_coulomb;
      if (law.coulomb) law.mu = v["mu"];
      return ImpactLaw(law);
    }
    case LawFamily::fremond:
      return ImpactLaw::fremond(PowerPotential(v["k"], v["p"]));
    case LawFamily::fremond_coulomb:
      return ImpactLaw::fremond_coulomb(PowerPotential(v["k"], v["p"]), v["mu"]);
    case LawFamily::fremond_deadzone:
      return ImpactLaw::fremond(PowerPotential(v["k"], v["p"]),
                                DeadZonePowerPotential(v["k_T"], v["q"], v["r"]));
  }
  throw InvalidArgument("law", "unknown law family");
}

}  // namespace fremond
