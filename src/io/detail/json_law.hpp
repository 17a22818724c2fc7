#pragma once
// Private to the library: the impact law's JSON schema (docs/problem-file.md, `law`), shared by the
// impact-problem reader and the scene reader.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fremond/core/error.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/potentials/registry.hpp"
#include "io/detail/json_reader.hpp"

namespace fremond::io::detail {

/// An impact law from its JSON object (docs/problem-file.md, `law`): `type` is the name of a law
/// of law_list.hpp, read by that law's schema (its read_law, e.g. laws/fremond/schema.cpp).
/// Keys a law does not use are refused. Messages are prefixed by `where` (e.g. "law", so
/// `law.normal.p: must be > 1, got 0.5`). The law is validated for `contacts` contacts.
ImpactLaw law_from_json(const json& j, int contacts, const PotentialRegistry& registry,
                        const std::string& where);

// What the laws' schemas share.

/// One potential {"potential": NAME, parameters...} of the registry, every parameter a number or
/// one per contact.
PerContactPotential potential_from_json(const json& j, const std::string& where, int contacts,
                                        const PotentialRegistry& registry);

/// The values of obj[key] under the key path obj_key.key: a number or one per contact.
std::vector<double> values(const json& obj, const std::string& obj_key, std::string_view key,
                           int contacts);

/// A restitution law's keys, {"type", "e"} and with Coulomb "mu", each a number or one per contact:
/// (e, μ), μ = {0} without Coulomb. Refuses other keys, naming the law `name`.
std::pair<std::vector<double>, std::vector<double>> restitution_values(const json& j,
                                                                       const std::string& where,
                                                                       std::string_view name,
                                                                       bool coulomb, int contacts);

/// The library names the law's values `law.e`, `law.mu[1]`, `law.normal`; the file spells them
/// under `where`, Frémond's Coulomb μ under `where.tangential`, and a list of one value as
/// `key[0]`.
InvalidArgument with_file_key(const InvalidArgument& e, const json& j, const std::string& where);

/// The law make() builds, validated for `contacts`. The factories and validate() refuse bad values
/// under the library's names; the refusal names the file's key instead.
template <class Make>
ImpactLaw built(const Make& make, int contacts, const json& j, const std::string& where) {
  try {
    ImpactLaw law = make();
    law.validate(contacts);
    return law;
  } catch (const InvalidArgument& e) {
    throw with_file_key(e, j, where);
  }
}

}  // namespace fremond::io::detail
