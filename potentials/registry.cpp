#include "fremond/potentials/registry.hpp"

#include <algorithm>

#include "fremond/core/error.hpp"
#include "fremond/potentials/absolute_value.hpp"
#include "fremond/potentials/deadzone_power.hpp"
#include "fremond/potentials/indicator.hpp"
#include "fremond/potentials/power.hpp"

namespace fremond {

PotentialRegistry PotentialRegistry::with_builtins() {
  PotentialRegistry r;
  r.add("power", {{"k", "p"},
                  {},
                  [](const PotentialParameters& a) {
                    return std::make_unique<PowerPotential>(a.at("k"), a.at("p"));
                  },
                  "k|z|^p/p, k >= 0, p > 1 (normal law, paper eq. 22)"});
  r.add("deadzone_power", {{"k", "q"},
                           {{"r", 0.0}},
                           [](const PotentialParameters& a) {
                             return std::make_unique<DeadZonePowerPotential>(a.at("k"), a.at("q"),
                                                                             a.at("r"));
                           },
                           "(k/q) max(0,|y|-r)^q, k >= 0, q > 1, r >= 0 (viscous law, eq. 25)"});
  r.add("absolute_value", {{"b"},
                           {},
                           [](const PotentialParameters& a) {
                             return std::make_unique<AbsoluteValuePotential>(a.at("b"));
                           },
                           "b|y|, b >= 0 (a fixed friction bound)"});
  r.add("indicator_nonnegative",
        {{},
         {},
         [](const PotentialParameters&) { return std::make_unique<IndicatorPotential>(false); },
         "indicator of R+ (eq. 16)"});
  r.add("indicator_nonpositive",
        {{},
         {},
         [](const PotentialParameters&) { return std::make_unique<IndicatorPotential>(true); },
         "indicator of R-"});
  return r;
}

void PotentialRegistry::add(const std::string& name, PotentialKind kind) {
  if (name.empty()) throw InvalidArgument("name", "a potential kind needs a non-empty name");
  if (name == "coulomb")
    throw InvalidArgument(name, "the name is reserved for Coulomb's law of the impact law");
  if (kinds_.count(name))
    throw InvalidArgument(name, "a potential of this name is already registered");
  if (!kind.make) throw InvalidArgument(name + ".make", "a potential kind needs a factory");
  kinds_.emplace(name, std::move(kind));
}

const PotentialKind& PotentialRegistry::kind(const std::string& name) const {
  auto it = kinds_.find(name);
  if (it == kinds_.end()) {
    std::string known;
    for (const auto& [n, k] : kinds_) known += (known.empty() ? "" : ", ") + n;
    throw InvalidArgument("potential", "unknown potential '" + name + "' (known: " + known + ")");
  }
  return it->second;
}

PotentialPtr PotentialRegistry::make(const std::string& name, const PotentialParameters& params,
                                     const std::string& where) const {
  const PotentialKind& k = kind(name);
  PotentialParameters full = k.optional;
  for (const auto& [key, v] : params) {
    const bool known = k.optional.count(key) ||
                       std::find(k.required.begin(), k.required.end(), key) != k.required.end();
    if (!known)
      throw InvalidArgument(where + "." + key, "not a parameter of potential '" + name + "'");
    full[key] = v;
  }
  for (const auto& req : k.required)
    if (!params.count(req))
      throw InvalidArgument(where + "." + req, "missing, required by potential '" + name + "'");
  try {
    return k.make(full);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(where + "." + e.name(),
                          std::string(e.what()).substr(e.name().size() + 2));
  }
}

std::vector<std::string> PotentialRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& [n, k] : kinds_) out.push_back(n);
  return out;
}

}  // namespace fremond
