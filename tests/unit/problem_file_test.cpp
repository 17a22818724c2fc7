// The impact-problem file (docs/problem-file.md): what the reader accepts and fills in, the names
// its refusals give, user-registered potentials by name, and the JSON form of results.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "fremond/fremond.hpp"
#include "fremond/io/problem_file.hpp"
#include "io/detail/json_law.hpp"

namespace fremond {
namespace {

using io::parse_problem_file;

const PotentialRegistry& builtins() {
  static const PotentialRegistry r = PotentialRegistry::with_builtins();
  return r;
}

// The name of the InvalidArgument that parsing `text` throws ("" if none).
std::string refusal(const std::string& text, const PotentialRegistry& registry = builtins()) {
  try {
    parse_problem_file(text, registry);
  } catch (const InvalidArgument& e) {
    return e.name();
  }
  return "";
}

constexpr const char* kSpecExample = R"({
  "M":     [[1, 0, 0], [0, 1, 0], [0, 0, 0.0833333333333]],
  "W_N":   [[0], [1], [-0.353553390593]],
  "W_T":   [[1], [0], [0.353553390593]],
  "w_N":   [0], "w_T": [0],
  "qdot_A": [2, -3.5613, 0],
  "law":   {"type": "newton_coulomb", "e": 0.9, "mu": 1.0}
})";

TEST(ProblemFile, ReadsTheExampleOfSpec7) {
  const auto file = parse_problem_file(kSpecExample, builtins());
  const ImpactProblem& pb = file.problem;
  EXPECT_EQ(pb.dofs(), 3);
  EXPECT_EQ(pb.contacts(), 1);
  EXPECT_TRUE(pb.has_tangential());
  EXPECT_EQ(pb.M(2, 2), 0.0833333333333);
  EXPECT_EQ(pb.W_N(2, 0), -0.353553390593);  // rows of the file are rows of the matrix
  EXPECT_EQ(pb.W_T(0, 0), 1.0);
  EXPECT_EQ(pb.qdot_A(1), -3.5613);
  EXPECT_EQ(file.law.name(), "newton_coulomb");
  EXPECT_EQ(file.law.get<RestitutionLaw>().e.values, std::vector<double>{0.9});
  EXPECT_EQ(file.law.get<RestitutionLaw>().mu.values, std::vector<double>{1.0});
}

TEST(ProblemFile, OptionalKeysMeanFrictionlessAndFixedObstacles) {
  const auto file = parse_problem_file(
      R"({"M": [[2, 0], [0, 2]], "W_N": [[1, 0], [0, 1]], "qdot_A": [-1, -1],
          "law": {"type": "poisson", "e": [0.5, 1]}})",
      builtins());
  EXPECT_FALSE(file.problem.has_tangential());
  EXPECT_EQ(file.problem.W_T.rows(), 2);
  EXPECT_EQ(file.problem.W_T.cols(), 0);
  EXPECT_EQ(file.problem.w_N, Eigen::VectorXd::Zero(2));
  EXPECT_EQ(file.law.get<RestitutionLaw>().e.values, (std::vector<double>{0.5, 1.0}));
}

TEST(ProblemFile, ReadsFremondLawsWithEveryTangentialForm) {
  const std::string head = R"({"M": [[1, 0], [0, 1]], "W_N": [[0], [1]], "W_T": [[1], [0]],
                              "qdot_A": [2, -1], "law": {"type": "fremond",
                              "normal": {"potential": "power", "k": 85.36, "p": 3})";
  auto law = parse_problem_file(head + "}}", builtins()).law;
  EXPECT_EQ(law.get<FremondLaw>().tangential, TangentialLaw::none);
  const auto* power = dynamic_cast<const PowerPotential*>(&law.get<FremondLaw>().normal[0]);
  ASSERT_NE(power, nullptr);
  EXPECT_EQ(power->k(), 85.36);
  EXPECT_EQ(power->p(), 3.0);

  law = parse_problem_file(head + R"(, "tangential": {"potential": "coulomb", "mu": 1.0}}})",
                           builtins())
            .law;
  EXPECT_EQ(law.get<FremondLaw>().tangential, TangentialLaw::coulomb);
  EXPECT_EQ(law.get<FremondLaw>().mu.values, std::vector<double>{1.0});

  law = parse_problem_file(
            head + R"(, "tangential": {"potential": "deadzone_power", "k": 1.5, "q": 2}}})",
            builtins())
            .law;
  EXPECT_EQ(law.get<FremondLaw>().tangential, TangentialLaw::potential);
  const auto* dz =
      dynamic_cast<const DeadZonePowerPotential*>(&law.get<FremondLaw>().tangential_potential[0]);
  ASSERT_NE(dz, nullptr);
  EXPECT_EQ(dz->r(), 0.0);  // the registry's default for r, stated in the kind
}

TEST(ProblemFile, PerContactParametersMakeOnePotentialPerContact) {
  const std::string pb = R"({"M": [[1, 0], [0, 1]], "W_N": [[1, 0], [0, 1]], "qdot_A": [-1, -1],
                             "law": {"type": "fremond", "normal": )";
  auto law =
      parse_problem_file(pb + R"({"potential": "power", "k": [1, 2], "p": 2}}})", builtins()).law;
  ASSERT_EQ(law.get<FremondLaw>().normal.potentials.size(), 2u);
  EXPECT_EQ(dynamic_cast<const PowerPotential&>(law.get<FremondLaw>().normal[0]).k(), 1.0);
  EXPECT_EQ(dynamic_cast<const PowerPotential&>(law.get<FremondLaw>().normal[1]).k(), 2.0);
  EXPECT_EQ(dynamic_cast<const PowerPotential&>(law.get<FremondLaw>().normal[1]).p(), 2.0);
  // A list of one value is the same value for every contact: one shared potential.
  law = parse_problem_file(pb + R"({"potential": "power", "k": [3], "p": 2}}})", builtins()).law;
  EXPECT_EQ(law.get<FremondLaw>().normal.potentials.size(), 1u);
}

TEST(ProblemFile, UsersPotentialsAreFoundByNameInTheRegistryPassed) {
  // A user's kind: the normal power law with p = 2 written as a callable, parameter "stiffness",
  // with an optional "scale".
  PotentialRegistry registry = PotentialRegistry::with_builtins();
  registry.add("my_quadratic", {{"stiffness"},
                                {{"scale", 1.0}},
                                [](const PotentialParameters& a) -> PotentialPtr {
                                  const double k = a.at("stiffness") * a.at("scale");
                                  if (k < 0) throw InvalidArgument("stiffness", "must be >= 0");
                                  return std::make_unique<PowerPotential>(k, 2.0);
                                },
                                "k z^2 / 2"});
  const std::string text = R"({"M": [[2]], "W_N": [[1]], "qdot_A": [-3], "law": {"type":
      "fremond", "normal": {"potential": "my_quadratic", "stiffness": 6, "scale": 2}}})";
  const auto file = parse_problem_file(text, registry);
  EXPECT_EQ(dynamic_cast<const PowerPotential&>(file.law.get<FremondLaw>().normal[0]).k(), 12.0);
  // The built-in registry does not know it: the registry is what the caller passes, not global.
  EXPECT_EQ(refusal(text), "law.normal.potential");
  // Its parameters are checked by name, and its own refusals are renamed to the file's keys.
  EXPECT_EQ(refusal(R"({"M": [[2]], "W_N": [[1]], "qdot_A": [-3], "law": {"type": "fremond",
      "normal": {"potential": "my_quadratic", "k": 6}}})",
                    registry),
            "law.normal.k");
  EXPECT_EQ(refusal(R"({"M": [[2]], "W_N": [[1]], "qdot_A": [-3], "law": {"type": "fremond",
      "normal": {"potential": "my_quadratic", "stiffness": -6}}})",
                    registry),
            "law.normal.stiffness");
}

TEST(ProblemFile, RefusalsNameTheKeyAsTheFileSpellsIt) {
  const std::string ok_head = R"({"M": [[1, 0], [0, 1]], "W_N": [[1, 0], [0, 1]],
                                  "qdot_A": [-1, -1], "law": )";
  EXPECT_EQ(refusal(""), "problem");
  EXPECT_EQ(refusal("[]"), "problem");
  EXPECT_EQ(refusal(R"({"M": [[1e999]]})"), "M[0][0]");
  EXPECT_EQ(refusal(R"({"M": [[1]], "M": [[1]]})"), "M");
  EXPECT_EQ(refusal(R"({"M": [[1]], "W_N": [[1]], "qdot_A": [-1], "law": {}, "x": 1})"), "x");
  EXPECT_EQ(refusal(R"({"M": [[1]], "W_N": [[1]], "qdot_A": [-1]})"), "law");
  EXPECT_EQ(refusal(ok_head + R"({"type": "newton", "e": [0.5, 1.5]}})"), "law.e[1]");
  EXPECT_EQ(refusal(ok_head + R"({"type": "newton", "e": [0.5, 0.5, 0.5]}})"), "law.e");
  EXPECT_EQ(refusal(ok_head + R"({"type": "newton_coulomb", "e": 0.5, "mu": -1}})"), "law.mu");
  EXPECT_EQ(refusal(ok_head + R"({"type": "fremond", "normal": {"potential": "power", "k": 1,
                                  "p": [2, 1]}}})"),
            "law.normal.p[1]");
  EXPECT_EQ(refusal(ok_head + R"({"type": "fremond", "normal": {"potential": "power", "k": 1,
                                  "p": 2}, "tangential": {"potential": "coulomb", "mu": [1, -1]}}})"),
            "law.tangential.mu[1]");
  EXPECT_EQ(refusal(R"({"M": [[1, 0], [0, 1]], "W_N": [[1], [0]], "W_T": [[1, 0], [0, 1]],
                       "qdot_A": [-1, -1], "law": {"type": "newton", "e": 0.5}})"),
            "W_T");
  EXPECT_EQ(refusal(R"({"M": [[1, 0], [0, -1]], "W_N": [[1], [0]], "qdot_A": [-1, -1],
                       "law": {"type": "newton", "e": 0.5}})"),
            "M");
}

TEST(ProblemFile, ReadsFromAStream) {
  std::istringstream in(kSpecExample);
  EXPECT_EQ(io::read_problem_file(in, builtins()).problem.dofs(), 3);
}

TEST(LawFromJson, PrefixesMessagesWithWhereTheLawIs) {
  // The scene reader calls it with its own prefix; the library's messages say "law.…".
  const auto j = nlohmann::json::parse(R"({"type": "newton", "e": [0.5, 0.5, 0.5]})");
  try {
    io::detail::law_from_json(j, 2, builtins(), "bodies[0].law");
    FAIL() << "accepted three values for two contacts";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "bodies[0].law.e");
  }
  const auto law = io::detail::law_from_json(
      nlohmann::json::parse(R"({"type": "fremond", "normal": {"potential": "power", "k": 2,
                               "p": 3}})"),
      2, builtins(), "law");
  EXPECT_EQ(law.describe(), "fremond(normal=power(k=2, p=3))");
}

TEST(JsonHelpers, NumbersListsAndMatricesNameTheirKeys) {
  using io::detail::json;
  EXPECT_EQ(io::detail::number_or_list(json(2.5), "k"), std::vector<double>{2.5});
  EXPECT_EQ(io::detail::number_or_list(json::parse("[1, 2]"), "k", 2), (std::vector<double>{1, 2}));
  EXPECT_THROW(io::detail::number_or_list(json(true), "k"), InvalidArgument);
  EXPECT_THROW(io::detail::number_from_json(json(std::numeric_limits<double>::infinity()), "x"),
               InvalidArgument);
  const auto m = io::detail::matrix_from_json(json::parse("[[1, 2, 3], [4, 5, 6]]"), "A");
  EXPECT_EQ(m.rows(), 2);
  EXPECT_EQ(m(1, 0), 4.0);
  try {
    io::detail::matrix_from_json(json::parse(R"([[1, 2], [3, "4"]])"), "A");
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "A[1][1]");
  }
}

TEST(ResultJson, DoublesReadBackExactlyAndNonFiniteIsNull) {
  ImpactResult r;
  r.qdot_E.resize(4);
  r.qdot_E << 1.0 / 3.0, 0.1 + 0.2, 1e-300, std::numeric_limits<double>::denorm_min();
  r.P_N = Eigen::VectorXd::Constant(1, std::nan(""));
  r.P_T = Eigen::VectorXd::Constant(1, std::numeric_limits<double>::infinity());
  r.energy_change = -std::numeric_limits<double>::infinity();
  r.takes_part.setOnes(1);
  // r.solver.residual is NaN by default: a solve that did not run.
  const auto j = nlohmann::json::parse(io::result_to_json(r));
  for (int i = 0; i < 4; ++i) EXPECT_EQ(j["qdot_E"][i].get<double>(), r.qdot_E(i));
  EXPECT_TRUE(j["P_N"][0].is_null());
  EXPECT_TRUE(j["P_T"][0].is_null());
  EXPECT_TRUE(j["energy_change"].is_null());
  EXPECT_TRUE(j["solver"]["residual"].is_null());
  EXPECT_EQ(j["solver"]["status"], "not_run");
  EXPECT_EQ(j["admissibility"]["failed"], "none");
  EXPECT_EQ(j["takes_part"][0], true);
  EXPECT_EQ(j["P_N_reaction"], nlohmann::json::parse("[0.0]"));  // "else 0"
  EXPECT_FALSE(j.contains("P_NC"));  // no phases unless the result has them
}

TEST(ResultJson, PrintsPoissonPhasesAndSmallResults) {
  SmallImpactResult r;
  r.has_phases = true;
  r.P_NC = SmallImpactResult::CVec::Constant(2, 1.5);
  r.solver.status = SolverStatus::converged;
  r.solver.method = SolverMethod::lemke;
  const auto j = nlohmann::json::parse(io::result_to_json(r, 2));
  EXPECT_EQ(j["P_NC"], nlohmann::json::parse("[1.5, 1.5]"));
  EXPECT_EQ(j["solver"]["method"], "lemke");
  EXPECT_EQ(j["solver"]["status"], "converged");
}

TEST(ResultJson, SolutionsListCountsThem) {
  EXPECT_EQ(nlohmann::json::parse(io::solutions_to_json({})),
            nlohmann::json::parse(R"({"count": 0, "solutions": []})"));
  const auto j = nlohmann::json::parse(io::solutions_to_json({ImpactResult{}, ImpactResult{}}));
  EXPECT_EQ(j["count"], 2);
  EXPECT_EQ(j["solutions"].size(), 2u);
}

TEST(ProblemFile, SolvesTheFremondClosedForm) {
  // p = 2 on a point mass m = 2, k = 12: ε = (k − 2m)/(k + 2m) = 1/2 (docs/laws.md).
  const auto file = parse_problem_file(R"({"M": [[2]], "W_N": [[1]], "qdot_A": [-3],
      "law": {"type": "fremond", "normal": {"potential": "power", "k": 12, "p": 2}}})",
                                       builtins());
  const auto r = solve_impact(file.problem, file.law);
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_NEAR(r.qdot_E(0), 1.5, 1e-14);
  const auto j = nlohmann::json::parse(io::result_to_json(r));
  EXPECT_NEAR(j["P_N"][0].get<double>(), 9.0, 1e-13);
}

}  // namespace
}  // namespace fremond
