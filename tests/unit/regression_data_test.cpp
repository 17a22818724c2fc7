// Regression cases as data: every problem file under tests/data/regression/<law>/ (the format the
// command reads, docs/problem-file.md) beside its <name>.expected.json, solved with the default
// options in both storages (heap, and stack where it fits). The expected file states the status,
// the largest law residual allowed, whether the certificate must accept the answer, and reference
// values with their tolerances: `tolerance` bounds every entry's absolute error, and for q̇_E
// `kinetic_tolerance` bounds the error in the kinetic-energy norm relative to q̇_A's. Values may be
// strings, to keep every digit of a high-precision reference; `why` says what the case is about.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fremond/fremond.hpp"
#include "fremond/io/problem_file.hpp"
#include "stress/invariants.hpp"
#include "support/why.hpp"

namespace fremond {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::why;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The problem files under the regression folder, sorted (their expected files left out).
std::vector<fs::path> regression_cases() {
  std::vector<fs::path> found;
  for (const auto& entry : fs::recursive_directory_iterator(FREMOND_REGRESSION_DATA)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && entry.path().extension() == ".json" &&
        name.find(".expected.") == std::string::npos)
      found.push_back(entry.path());
  }
  std::sort(found.begin(), found.end());
  return found;
}

double number(const json& v) {
  return v.is_string() ? std::stod(v.get<std::string>()) : v.get<double>();
}

Eigen::VectorXd values(const json& v) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) out(static_cast<Eigen::Index>(i)) = number(v[i]);
  return out;
}

/// `actual` within the expected entry `key` of `expected`, if it has one.
template <class Problem, class Vec>
void expect_values(const Problem& pb, const json& expected, const char* key, const Vec& actual) {
  if (!expected.contains(key)) return;
  const json& e = expected[key];
  const Eigen::VectorXd ref = values(e["value"]);
  ASSERT_EQ(actual.size(), ref.size()) << key;
  if (e.contains("kinetic_tolerance")) {
    EXPECT_LT(robust::kinetic_distance(pb, actual, ref), number(e["kinetic_tolerance"])) << key;
  }
  if (e.contains("tolerance")) {
    for (Eigen::Index i = 0; i < ref.size(); ++i)
      EXPECT_NEAR(actual(i), ref(i), number(e["tolerance"])) << key << "(" << i << ")";
  }
}

class RegressionData : public ::testing::TestWithParam<fs::path> {};

TEST_P(RegressionData, MatchesItsReference) {
  const fs::path path = GetParam();
  fs::path expected_path = path;
  expected_path.replace_extension(".expected.json");
  ASSERT_TRUE(fs::exists(expected_path)) << expected_path << " is missing";
  const auto file = io::parse_problem_file(read_text(path), PotentialRegistry::with_builtins());
  const json expected = json::parse(read_text(expected_path));
  SCOPED_TRACE(expected.value("why", ""));
  const SolverStatus status = solver_status_from_string(expected.at("status").get<std::string>());
  const auto check = [&](const auto& pb, const char* storage) {
    SCOPED_TRACE(storage);
    const SolverOptions opt;
    const auto r = solve_impact(pb, file.law, opt);
    ASSERT_EQ(r.solver.status, status) << why(r);
    EXPECT_EQ(robust::check_result(pb, file.law, opt, r), "");
    EXPECT_LE(law_residual(pb, file.law, r), number(expected.at("law_residual")));
    if (expected.contains("admissible")) {
      EXPECT_EQ(r.admissibility.admissible, expected["admissible"].get<bool>())
          << to_string(r.admissibility.failed) << " by " << r.admissibility.violation;
    }
    expect_values(pb, expected, "qdot_E", r.qdot_E);
    expect_values(pb, expected, "P_N", r.P_N);
    expect_values(pb, expected, "P_T", r.P_T);
    expect_values(pb, expected, "P_NC", r.P_NC);
    expect_values(pb, expected, "P_TC", r.P_TC);
  };
  check(file.problem, "heap");
  if (file.problem.dofs() <= kSmallDofs && file.problem.contacts() <= kSmallContacts)
    check(to_small(file.problem), "stack");
}

INSTANTIATE_TEST_SUITE_P(Files, RegressionData, ::testing::ValuesIn(regression_cases()),
                         [](const ::testing::TestParamInfo<fs::path>& info) {
                           // <law>_<name>, with only the characters a test name may hold.
                           std::string name = info.param.parent_path().filename().string() + "_" +
                                              info.param.stem().string();
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

}  // namespace
}  // namespace fremond
