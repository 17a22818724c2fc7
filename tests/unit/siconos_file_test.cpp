// Siconos's friction-contact files (io/siconos_file.hpp): small files written by hand in each
// storage the reader takes, the forms told apart, and each refusal naming its line.
#include <gtest/gtest.h>

#include <string>

#include "fremond/core/error.hpp"
#include "fremond/io/siconos_file.hpp"

namespace fremond::io {
namespace {

// One contact, W = [[2, 0.5], [0.5, 1]] dense (column-major), q = (−1, 0.25), μ = 0.3.
const char* kDenseLocal = "2\n1\n0\n2\n2\n2.0 0.5 0.5 1.0\n-1 0.25\n0.3\n";

// Two contacts, a diagonal W = diag(4, 3, 2, 1) as CSparse prints compressed columns.
const char* kSparseLocal =
    "2\n2\n2\n4\n4\n2\nCSparse Version 3.1.9\n4-by-4, nzmax: 4 nnz: 4, 1-norm: 4\n"
    "    col 0 : locations 0 to 0\n      0 : 4\n    col 1 : locations 1 to 1\n      1 : 3\n"
    "    col 2 : locations 2 to 2\n      2 : 2\n    col 3 : locations 3 to 3\n      3 : 1\n"
    "  -1 0 1 0\n  0.5 0.25\n";

// The global form: M = diag(2, 2) as triplets, H = [[1, 0], [0, 1]] (one contact: normal along
// the first dof, tangent along the second), q = (−2, 4), b = (0.5, 0), μ = 1.
const char* kGlobal =
    "2\n1\n2\n2\n2\n1\nCSparse Version 3.1.9\ntriplet: 2-by-2, nzmax: 2 nnz: 2\n    0 0 : 2\n"
    "    1 1 : 2\n2\n2\n2\n2\nCSparse Version 3.1.9\n2-by-2, nzmax: 2 nnz: 2, 1-norm: 1\n"
    "    col 0 : locations 0 to 0\n      0 : 1\n    col 1 : locations 1 to 1\n      1 : 1\n"
    "-2 4\n0.5 0\n1\n";

TEST(SiconosFile, ReadsTheLocalFormDense) {
  const SiconosProblem p = parse_siconos_file(kDenseLocal);
  EXPECT_EQ(p.form, SiconosProblem::Form::local);
  ASSERT_EQ(p.contacts(), 1);
  EXPECT_EQ(p.contact.G.coeff(0, 0), 2.0);
  EXPECT_EQ(p.contact.G.coeff(1, 0), 0.5);
  EXPECT_EQ(p.contact.G.coeff(1, 1), 1.0);
  EXPECT_EQ(p.contact.D_A(0), -1.0);
  EXPECT_EQ(p.contact.D_A(1), 0.25);
  EXPECT_EQ(p.mu[0], 0.3);
  EXPECT_EQ(p.law().name(), "newton_coulomb");
}

// Numbers as Siconos prints them: G sparse with 6 significant digits (CSparse's %g), q and μ with
// 25: each known to half a unit of its last digit, 5e-6 and 5e-25 of itself at most. Numbers of
// fewer than 6 digits are taken as written by hand, exact.
TEST(SiconosFile, TakesTheNumbersAsKnownToTheirPrintedDigits) {
  const char* printed =
      "2\n1\n2\n2\n2\n2\nCSparse Version 3.1.9\n2-by-2, nzmax: 3 nnz: 3, 1-norm: 1\n"
      "    col 0 : locations 0 to 1\n      0 : 814.288\n      1 : -1.60499e-06\n"
      "    col 1 : locations 2 to 2\n      1 : 2476.5\n"
      "-1.000000000000000000000000e+00 2.500000000000000000000000e-01\n"
      "5.000000000000000000000000e-01\n";
  const SiconosProblem p = parse_siconos_file(printed);
  EXPECT_EQ(p.contact.G.coeff(1, 0), -1.60499e-06);
  EXPECT_EQ(p.contact.G_rounding, 5e-6);
  EXPECT_EQ(p.contact.D_A_rounding, 5e-25);
  const SiconosProblem by_hand = parse_siconos_file(kDenseLocal);
  EXPECT_EQ(by_hand.contact.G_rounding, 0.0);
  EXPECT_EQ(by_hand.contact.D_A_rounding, 0.0);
  EXPECT_EQ(parse_siconos_file(kSparseLocal).contact.G_rounding, 0.0);
}

TEST(SiconosFile, ReadsTheLocalFormSparse) {
  const SiconosProblem p = parse_siconos_file(kSparseLocal);
  ASSERT_EQ(p.contacts(), 2);
  EXPECT_EQ(p.contact.G.nonZeros(), 4);
  EXPECT_EQ(p.contact.G.coeff(2, 2), 2.0);
  EXPECT_EQ(p.contact.D_A(2), 1.0);
  EXPECT_EQ(p.mu[1], 0.25);
}

// q̇_A = M⁻¹ q = (−1, 2); W_N = H's column 0, W_T its column 1; w = b.
TEST(SiconosFile, ReadsTheGlobalForm) {
  const SiconosProblem p = parse_siconos_file(kGlobal);
  EXPECT_EQ(p.form, SiconosProblem::Form::global);
  const auto& pb = p.impact;
  ASSERT_EQ(pb.dofs(), 2);
  ASSERT_EQ(pb.contacts(), 1);
  EXPECT_NEAR(pb.qdot_A(0), -1.0, 1e-15);
  EXPECT_NEAR(pb.qdot_A(1), 2.0, 1e-15);
  EXPECT_EQ(pb.W_N.coeff(0, 0), 1.0);
  EXPECT_EQ(pb.W_T.coeff(1, 0), 1.0);
  EXPECT_EQ(pb.w_N(0), 0.5);
  EXPECT_EQ(p.mu[0], 1.0);
}

TEST(SiconosFile, TellsItsFilesFromJson) {
  EXPECT_TRUE(looks_like_siconos_file(kDenseLocal));
  EXPECT_TRUE(looks_like_siconos_file("\n 2\r\n1\n"));
  EXPECT_FALSE(looks_like_siconos_file("{\"M\": [[1]]}"));
  EXPECT_FALSE(looks_like_siconos_file(""));
  EXPECT_FALSE(looks_like_siconos_file("3"));  // a JSON document holding a number
  EXPECT_FALSE(looks_like_siconos_file("2\n[1]\n"));
}

std::string refusal(const std::string& text) {
  try {
    parse_siconos_file(text);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SiconosFile, RefusesBadFilesNamingTheLine) {
  EXPECT_EQ(refusal("3\n1\n"),
            "line 1: the dimension must be 2 (a planar problem: one normal and one tangential "
            "row a contact), got 3");
  EXPECT_EQ(refusal("2\n0\n"),
            "line 2: the number of contacts must be an integer in [1, 5000000], got '0'");
  EXPECT_EQ(refusal("2\n1\n0\n2\n2\n2.0 0.5 x 1.0\n"), "line 6: 'x' is not a number");
  EXPECT_EQ(refusal("2\n1\n0\n2\n2\n2.0 0.5 0.5 1.0\n-1 0.25\n"),
            "line 7: the file ends where mu was expected");
  EXPECT_EQ(refusal("2\n1\n0\n2\n2\n2.0 0.5 0.5 1.0\n-1 0.25\n0.3\n7\n"),
            "line 9: unexpected text after the last friction coefficient");
  EXPECT_EQ(refusal("2\n1\n1\n2\n2\n"),
            "line 3: the first matrix: storage type 1 is not read (0 dense and 2 sparse are); "
            "have Siconos write the problem with one of those");
  EXPECT_EQ(refusal("2\n1\n0\n3\n3\n1 0 0 0 1 0 0 0 1\n0 0 0\n1\n"),
            "line 6: the Delassus matrix W must be 2x2 (two rows a contact), got 3x3");
  EXPECT_EQ(refusal("2\n1\n0\n2\n2\n2.0 0.5 0.5 1.0\n-1 0.25\n-0.3\n"),
            "mu[0]: must be >= 0, got -0.29999999999999999");
  const std::string out_of_range =
      "2\n1\n2\n2\n2\n2\nCSparse\n2-by-2, nzmax: 1 nnz: 1, 1-norm: 1\n    col 0 : locations 0 "
      "to 0\n      5 : 1\n";
  EXPECT_EQ(refusal(out_of_range), "line 10: the first matrix: entry index out of the 2x2 matrix");
  // A CSparse size line without its row count (found by fuzzing: it threw out_of_range).
  EXPECT_EQ(refusal("2\n2\n2\n4\n4\n2\nCSparse\n-by-4, nzmax: 4 nnz: 4, 1-norm: 4\n"),
            "line 8: the first matrix's rows is missing");
  // A dense matrix beyond what dense storage may hold.
  EXPECT_EQ(refusal("2\n1\n0\n10000\n10000\n"),
            "line 5: the first matrix is 10000x10000: too large for dense storage (at most "
            "10000000 entries); store it sparse (type 2)");
  // Not symmetric: G's validation names it.
  EXPECT_NE(refusal("2\n1\n0\n2\n2\n2.0 0.5 0.9 1.0\n-1 0.25\n0.3\n").find("G: must be symmetric"),
            std::string::npos);
}

}  // namespace
}  // namespace fremond::io
