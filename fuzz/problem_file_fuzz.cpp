// Fuzz target: the impact-problem file reader (docs/problem-file.md), then every solver fed from
// what it accepts, then the JSON writer.
//
// Contract checked on every input:
//  - the reader either accepts or throws InvalidArgument with a name and a reason; nothing else
//    escapes (any other exception, a crash, a sanitizer report or a hang is a finding);
//  - what it accepts is a valid problem and law (validate() holds again);
//  - solve_impact on it (and solve_impact_all, as `fremond impact --all-solutions` does) ends with
//    a status and satisfies tests/stress/invariants.hpp, or refuses data the reader cannot judge
//    without solving (a Delassus entry WᵀM⁻¹W beyond 1e308) with InvalidArgument, name and reason,
//    as the solver target allows;
//  - the result prints as JSON that reads back.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string_view>

#include "fremond/io/problem_file.hpp"
#include "fuzz_support.hpp"

using namespace fremond;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const PotentialRegistry registry = PotentialRegistry::with_builtins();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  io::ProblemFile file;
  try {
    file = io::parse_problem_file(text, registry);
  } catch (const InvalidArgument& e) {
    fuzz::check_refusal(e);
    return 0;
  }
  try {
    validate(file.problem);
    file.law.validate(file.problem.contacts());
  } catch (const InvalidArgument& e) {
    fuzz::fail(std::string("the reader accepted an invalid problem: ") + e.what());
  }
  if (fuzz::classify_only(file.law)) return 0;
  // Keep every run short: the solvers' cost grows with the size, which says nothing new here.
  if (file.problem.dofs() > 8 || file.problem.contacts() > 4) return 0;

  const SolverOptions options;
  ImpactResult result;
  try {
    result = solve_impact(file.problem, file.law, options);
  } catch (const InvalidArgument& e) {
    fuzz::check_refusal(e);
    return 0;
  }
  fuzz::check(file.problem, file.law, options, result, "solve_impact");
  const std::string json = io::result_to_json(result, -1);
  if (!nlohmann::json::accept(json)) fuzz::fail("result_to_json printed invalid JSON: " + json);

  if (fits_small(file.problem)) {
    const auto small = to_small(file.problem);
    const auto r = solve_impact(small, file.law, options);
    fuzz::check(small, file.law, options, r, "solve_impact (small)");
  }
  if (file.problem.contacts() <= 3) {
    const auto all = solve_impact_all(file.problem, file.law, options);
    for (const auto& r : all) fuzz::check(file.problem, file.law, options, r, "solve_impact_all");
    const std::string list = io::solutions_to_json(all, -1);
    if (!nlohmann::json::accept(list)) fuzz::fail("solutions_to_json printed invalid JSON");
  }
  return 0;
}
