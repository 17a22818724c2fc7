// The measured-impact file (docs/measurements.md): what the reader accepts and fills in, and the
// row and key its refusals name.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "fremond/core/error.hpp"
#include "fremond/fit/measured_impact.hpp"
#include "fremond/io/measurements.hpp"

namespace fremond {
namespace {

using io::parse_measurements;

// The paper's bar at its first impact, measured after: its keys and their JSON values.
const std::vector<std::pair<std::string, std::string>> kBarKeys{
    {"M", "[[1, 0, 0], [0, 1, 0], [0, 0, 0.0833333333333]]"},
    {"W_N", "[[0], [1], [-0.353553390593]]"},
    {"W_T", "[[1], [0], [0.353553390593]]"},
    {"qdot_A", "[2, -3.5613, 0]"},
    {"qdot_E", "[1.5, 2.0, -1.0]"}};

// The bar's row with `extra` keys added, those named in `without` taken out first (JSON refuses a
// key given twice).
std::string bar_with(const std::string& extra, const std::string& without = "") {
  std::string row = "{";
  for (const auto& [key, value] : kBarKeys) {
    if (key == without) continue;
    row += (row.size() > 1 ? ", \"" : "\"") + key + "\": " + value;
  }
  if (!extra.empty()) row += ", " + extra;
  return row + "}";
}
const std::string kBar = bar_with("");

std::string refusal(const std::string& text) {
  try {
    parse_measurements(text);
  } catch (const InvalidArgument& e) {
    return e.name();
  }
  return "";
}

TEST(Measurements, ReadsAWholeVelocityWithSigmaOne) {
  const auto m = parse_measurements("[" + kBar + "]");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].problem.dofs(), 3);
  EXPECT_TRUE(m[0].problem.has_tangential());
  EXPECT_EQ(m[0].problem.w_N.size(), 1);  // fixed obstacle filled in
  EXPECT_EQ(m[0].qdot_E(1), 2.0);
  EXPECT_EQ(m[0].measured(), 3);
  EXPECT_EQ(m[0].sigma, VectorX::Ones(3));
}

TEST(Measurements, MaskNullsAndSigma) {
  const auto m = parse_measurements(
      "[" + bar_with("\"mask\": [true, false, true], \"sigma\": 0.1") + "," +
      bar_with(R"("qdot_E": [null, 2, null], "sigma": [1, 0.5, 2])", "qdot_E") + "]");
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].mask, (std::vector<bool>{true, false, true}));
  EXPECT_EQ(m[0].sigma(2), 0.1);
  EXPECT_EQ(m[1].mask, (std::vector<bool>{false, true, false}));  // the nulls were not measured
  EXPECT_EQ(m[1].measured(), 1);
  EXPECT_EQ(m[1].sigma(1), 0.5);
}

TEST(Measurements, RefusalsNameTheRowAndTheKey) {
  const std::string ok = kBar;
  EXPECT_EQ(refusal("{}"), "impacts");
  EXPECT_EQ(refusal("[]"), "impacts");
  EXPECT_EQ(refusal("[1"), "impacts[1]");  // where the text stops being JSON
  EXPECT_EQ(refusal("[" + ok + ", 3]"), "impacts[1]");
  EXPECT_EQ(refusal("[" + ok + "," + ok + "," + bar_with("", "qdot_E") + "]"), "impacts[2].qdot_E");
  EXPECT_EQ(refusal("[" + ok + "," + bar_with("\"Sigma\": 1") + "]"), "impacts[1].Sigma");
  EXPECT_EQ(refusal("[" + bar_with(R"("qdot_E": [1, 2])", "qdot_E") + "]"), "impacts[0].qdot_E");
  EXPECT_EQ(refusal("[" + bar_with(R"("qdot_E": [1, "a", 2])", "qdot_E") + "]"),
            "impacts[0].qdot_E[1]");
  EXPECT_EQ(refusal("[" + bar_with("\"sigma\": 0") + "]"), "impacts[0].sigma[0]");
  EXPECT_EQ(refusal("[" + bar_with("\"sigma\": [1, -1, 1]") + "]"), "impacts[0].sigma[1]");
  EXPECT_EQ(refusal("[" + bar_with("\"sigma\": [1, 1]") + "]"), "impacts[0].sigma");
  EXPECT_EQ(refusal("[" + bar_with("\"mask\": [true, true]") + "]"), "impacts[0].mask");
  EXPECT_EQ(refusal("[" + bar_with("\"mask\": [false, false, false]") + "]"), "impacts[0].mask");
  EXPECT_EQ(refusal("[" + bar_with("\"mask\": [true, 1, true]") + "]"), "impacts[0].mask[1]");
  EXPECT_EQ(
      refusal("[" + bar_with(R"("qdot_E": [null, 2, 3], "mask": [true, true, true])", "qdot_E") +
              "]"),
      "impacts[0].qdot_E[0]");
  // The impact itself, validated as impact problems are.
  EXPECT_EQ(
      refusal("[" + ok + "," + bar_with(R"("M": [[1, 0, 0], [0, -1, 0], [0, 0, 1]])", "M") + "]"),
      "impacts[1].M");
  EXPECT_EQ(refusal("[" + bar_with(R"("W_T": [[1], [0]])", "W_T") + "]"), "impacts[0].W_T");
  EXPECT_EQ(refusal("[" + bar_with(R"("w_N": [0, 0])") + "]"), "impacts[0].w_N");
  EXPECT_EQ(refusal("[" + bar_with(R"("qdot_A": [1, 2])", "qdot_A") + "]"), "impacts[0].qdot_A");
  // The message says why, after the key.
  try {
    parse_measurements("[" + ok + "," + bar_with("\"sigma\": [1, -1, 1]") + "]");
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("impacts[1].sigma[1]: must be a finite number > 0", 0),
              0u)
        << e.what();
  }
}

TEST(Measurements, ValidateNamesTheMember) {
  ImpactProblem pb;
  pb.M = MatrixX::Identity(2, 2);
  pb.W_N = MatrixX::Zero(2, 1);
  pb.W_N(1, 0) = 1;
  pb.W_T.resize(2, 0);
  pb.qdot_A = VectorX::Zero(2);
  MeasuredImpact m = measured_impact(pb, VectorX::Zero(2));
  EXPECT_NO_THROW(validate(m));
  m.qdot_E(0) = std::nan("");
  try {
    validate(m);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "qdot_E[0]");
  }
  m.mask[0] = false;  // not measured: not read
  EXPECT_NO_THROW(validate(m));
}

}  // namespace
}  // namespace fremond
