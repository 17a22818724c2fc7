#pragma once
// Private to the library: the impact law's JSON schema (docs/problem-file.md, `law`), shared by the
// impact-problem reader and the scene reader.
#include <string>

#include "fremond/laws/impact_law.hpp"
#include "fremond/potentials/registry.hpp"
#include "io/detail/json_reader.hpp"

namespace fremond::io::detail {

/// An impact law from its JSON object (docs/problem-file.md, `law`): `type` is one of newton,
/// poisson, newton_coulomb, poisson_coulomb, fremond; e and mu are a number or one per contact; a
/// Frémond law names its potentials by their registry name ("normal", optional "tangential", which
/// may also be {"potential": "coulomb", "mu": ...}), every parameter a number or one per contact.
/// Keys a law type does not use are refused. Messages are prefixed by `where` (e.g. "law", so
/// `law.normal.p: must be > 1, got 0.5`). The law is validated for `contacts` contacts.
ImpactLaw law_from_json(const json& j, int contacts, const PotentialRegistry& registry,
                        const std::string& where);

}  // namespace fremond::io::detail
