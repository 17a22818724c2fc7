// The refinement's residual B − M X (accurate_dot.hpp: accurate_residual) against two references:
// the one-entry-at-a-time Dot2 it replaces (bit for bit: the same terms in the same order, the
// same error-free transformations, whether the product's error comes from an fma or from
// Veltkamp's splitting; the two differ only where a product's error is subnormal), and a __float128
// computation (Dot2's bound: ε of the result plus a few ε² of the terms' sum). The residuals are
// made to cancel, as refinement's do: B = M X rounded.
#include <gtest/gtest.h>
#include <quadmath.h>

#include <cmath>
#include <random>

#include "core/detail/accurate_dot.hpp"

namespace {

using fremond::detail::accurate_dot;
using fremond::detail::accurate_residual;

template <class Mat>
void fill(Mat& M, std::mt19937& gen, double spread) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(-spread, spread);
  for (Eigen::Index j = 0; j < M.cols(); ++j)
    for (Eigen::Index i = 0; i < M.rows(); ++i) M(i, j) = u(gen) * std::pow(10.0, e(gen));
}

template <class MatM, class MatX>
void check(const MatM& M, const MatX& X, const MatX& B, const char* what, int trial) {
  MatX D;
  accurate_residual(M, X, B, D);
  ASSERT_EQ(D.rows(), M.rows());
  ASSERT_EQ(D.cols(), X.cols());
  for (Eigen::Index c = 0; c < X.cols(); ++c)
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
      const double one = -accurate_dot(M.row(i), X.col(c), -B(i, c));
      // Bit for bit (a NaN-free comparison: every entry here is finite).
      ASSERT_EQ(D(i, c), one) << what << " " << trial << " (" << i << ", " << c << ")";
      __float128 exact = B(i, c), terms = fabsq(B(i, c));
      for (Eigen::Index j = 0; j < M.cols(); ++j) {
        exact -= static_cast<__float128>(M(i, j)) * X(j, c);
        terms += fabsq(static_cast<__float128>(M(i, j)) * X(j, c));
      }
      const double eps = std::numeric_limits<double>::epsilon();
      const double n = static_cast<double>(M.cols()) + 1;
      const double bound = eps * std::fabs(static_cast<double>(exact)) +
                           4 * n * n * eps * eps * static_cast<double>(terms);
      EXPECT_LE(std::fabs(D(i, c) - static_cast<double>(exact)), bound)
          << what << " " << trial << " (" << i << ", " << c << ")";
    }
}

TEST(AccurateResidual, MatchesDot2EntryByEntryAndTheQuadReference) {
  std::mt19937 gen(17);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + trial % 30, k = 1 + (trial / 30) % 6;
    const double spread = (trial / 180) % 2 ? 8.0 : 1.0;  // entries over 1 or 16 decades
    Eigen::MatrixXd M(n, n), X(n, k);
    fill(M, gen, spread);
    fill(X, gen, spread);
    const Eigen::MatrixXd B = M * X;  // the residual cancels to the rounding of this product
    check(M, X, B, "dynamic", trial);
    if (n <= 6) {  // the stack-stored sizes of the small problems
      using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
      check(Small(M), Small(X), Small(B), "small", trial);
    }
  }
}

// The loop's two builds, with FMA instructions where the processor has them and by Veltkamp's
// splitting, give the same bits: both products' errors are exact.
TEST(AccurateResidual, PortableLoopGivesTheSameBits) {
  std::mt19937 gen(23);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 1 + trial % 30, m = 1 + (trial * 7) % 30;
    Eigen::MatrixXd M(n, m), x(m, 1), start(n, 1);
    fill(M, gen, 8.0);
    fill(x, gen, 8.0);
    fill(start, gen, 8.0);
    Eigen::VectorXd s1 = -start, s2 = -start, e1 = Eigen::VectorXd::Zero(n), e2 = e1;
    fremond::detail::accurate_multiply_add(M.data(), n, n, m, x.data(), s1.data(), e1.data());
    fremond::detail::accurate_multiply_add_portable(M.data(), n, n, m, x.data(), s2.data(),
                                                    e2.data());
    for (int i = 0; i < n; ++i) {
      ASSERT_EQ(s1(i), s2(i)) << trial << " " << i;
      ASSERT_EQ(e1(i), e2(i)) << trial << " " << i;
    }
    // And the sum is the product's to twice the precision (Dot2's bound, as in check()).
    __float128 exact = -static_cast<__float128>(start(0)), terms = fabsq(start(0));
    for (int j = 0; j < m; ++j) {
      exact += static_cast<__float128>(M(0, j)) * x(j);
      terms += fabsq(static_cast<__float128>(M(0, j)) * x(j));
    }
    const double eps = std::numeric_limits<double>::epsilon(), k = m + 1.0;
    EXPECT_LE(std::fabs(s1(0) + e1(0) - static_cast<double>(exact)),
              eps * std::fabs(static_cast<double>(exact)) +
                  4 * k * k * eps * eps * static_cast<double>(terms))
        << trial;
  }
}

// Entries beyond what Veltkamp's splitting takes (|x| ≥ 2^995: its factor 2^27 + 1 would
// overflow): those go through accurate_dot, still bit for bit.
TEST(AccurateResidual, HugeEntriesTakeTheSafePath) {
  std::mt19937 gen(5);
  Eigen::MatrixXd M(4, 4), X(4, 2);
  fill(M, gen, 1.0);
  fill(X, gen, 1.0);
  M(1, 2) = 1e300;
  X.col(1) *= 1e-290;
  const Eigen::MatrixXd B = M * X;
  check(M, X, B, "huge", 0);
}

// Dot2 written out with std::fma, one term after the other (Ogita, Rump and Oishi, algorithm Dot2):
// the reference accurate_dot's loop, chosen at run time (FMA instructions where the processor has
// them), must match bit for bit on rows with their stride and on columns, cancelling sums and
// overflowing ones included.
double dot2_reference(const Eigen::VectorXd& x, const Eigen::VectorXd& y, double extra) {
  double s = extra, c = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double p = x(i) * y(i), ep = std::fma(x(i), y(i), -p);
    const double t = s + p, z = t - s, es = (s - (t - z)) + (p - z);
    s = t;
    c += ep + es;
  }
  const double r = s + c;
  return std::isfinite(r) ? r : s;
}

TEST(AccurateDot, MatchesDot2WrittenOutBitForBit) {
  std::mt19937 gen(31);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 12;
    Eigen::MatrixXd M(n + 2, n);
    Eigen::VectorXd x(n);
    fill(M, gen, trial % 2 ? 8.0 : 1.0);
    fill(x, gen, trial % 2 ? 8.0 : 1.0);
    double extra = -(M.row(1) * x)(0);                   // the sum cancels to its rounding
    if (trial % 50 == 49) M(1, 0) = 1e300, x(0) = 1e10;  // the product overflows
    const double got = accurate_dot(M.row(1), x, extra);
    const double want = dot2_reference(M.row(1).transpose(), x, extra);
    if (std::isnan(want)) {
      EXPECT_TRUE(std::isnan(got)) << trial;
      continue;
    }
    ASSERT_EQ(got, want) << trial;
    ASSERT_EQ(accurate_dot(M.col(0), M.col(n - 1)), dot2_reference(M.col(0), M.col(n - 1), 0.0))
        << trial;
  }
}

}  // namespace
