// The law's JSON schema leaves the range checks of e and μ to ImpactLaw (its factories and
// validate()) and renames the library's key to the one the file spells: under the law's own
// prefix, Frémond's Coulomb μ under `tangential`, and a list of one value as `key[0]`.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "fremond/fremond.hpp"
#include "io/detail/json_law.hpp"

namespace fremond {
namespace {

// The name and message of the refusal of `law` for `contacts` contacts ("" if accepted).
std::string refusal(const std::string& law, int contacts, const std::string& where = "law") {
  static const PotentialRegistry registry = PotentialRegistry::with_builtins();
  try {
    io::detail::law_from_json(nlohmann::json::parse(law), contacts, registry, where);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

TEST(LawSchema, RangeRefusalsNameTheKeyAsTheFileSpellsIt) {
  EXPECT_EQ(refusal(R"({"type": "newton", "e": 1.5})", 1), "law.e: must lie in [0, 1], got 1.5");
  EXPECT_EQ(refusal(R"({"type": "newton", "e": [1.5]})", 1),
            "law.e[0]: must lie in [0, 1], got 1.5");
  EXPECT_EQ(refusal(R"({"type": "poisson", "e": [0.5, -1]})", 2),
            "law.e[1]: must lie in [0, 1], got -1");
  EXPECT_EQ(refusal(R"({"type": "newton_coulomb", "e": 0.5, "mu": [-2]})", 2),
            "law.mu[0]: must be >= 0, got -2");
  const std::string fremond_coulomb =
      R"({"type": "fremond", "normal": {"potential": "power", "k": 1, "p": 2},
          "tangential": {"potential": "coulomb", "mu": )";
  EXPECT_EQ(refusal(fremond_coulomb + "-1}}", 1), "law.tangential.mu: must be >= 0, got -1");
  EXPECT_EQ(refusal(fremond_coulomb + "[-1]}}", 1), "law.tangential.mu[0]: must be >= 0, got -1");
  EXPECT_EQ(refusal(R"({"type": "newton", "e": [0.5, 2]})", 2, "bodies[0].law"),
            "bodies[0].law.e[1]: must lie in [0, 1], got 2");
  EXPECT_EQ(refusal(R"({"type": "newton", "e": [0.5]})", 2), "");
}

}  // namespace
}  // namespace fremond
