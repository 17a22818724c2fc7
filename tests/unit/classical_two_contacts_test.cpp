// Two frictionless contacts, the commonest case of several (a bar landing flat): G's 2×2 factor
// L D Lᵀ (Factored in src/solvers/detail/classical_law.hpp) and the closed forms of every mode
// (the all-closed guess, then one_of_two_closed). Checked against references they do not use:
// G⁻¹b in long double by Cramer's rule, and Lemke's pivots on the same LCP.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "solvers/detail/classical_law.hpp"

namespace {

using namespace fremond;
using Phase = detail::classical::Phase<4>;
using Factored = detail::classical::Factored<4>;

/// A random symmetric positive definite 2×2 G = R diag(1, 10^-k) Rᵀ scaled by 10^s: condition
/// number 10^k, entries around 10^s.
Phase::RowMat random_spd(std::mt19937& gen, double log_cond, double log_scale) {
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
  const double t = angle(gen), c = std::cos(t), s = std::sin(t);
  const double scale = std::pow(10.0, log_scale), small = scale * std::pow(10.0, -log_cond);
  Phase::RowMat G(2, 2);
  G(0, 0) = c * c * scale + s * s * small;
  G(1, 1) = s * s * scale + c * c * small;
  G(0, 1) = G(1, 0) = c * s * (scale - small);
  return G;
}

TEST(ClassicalTwoContacts, FactorSolvesToTheConditionNumberTimesRounding) {
  // Forward error of a backward-stable solve: ‖x − x̂‖ ≤ c·cond(G)·ε‖x‖. The reference is
  // Cramer's rule in long double on the stored G (its own error ~cond·1e-19, far below).
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), lc(0.0, 12.0), ls(-8.0, 8.0);
  constexpr double eps = std::numeric_limits<double>::epsilon();
  double worst = 0.0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double log_cond = lc(gen);
    const Phase::RowMat G = random_spd(gen, log_cond, ls(gen));
    Factored f;
    f.compute(G, 3);
    ASSERT_TRUE(f.regular) << "trial " << trial << ": cond 1e" << log_cond;
    Phase::Rows b(2);
    b << u(gen), u(gen);
    const Phase::Rows x = f.solve(b);
    using L = long double;
    const L a = G(0, 0), o = G(1, 0), d = G(1, 1);
    const L det = a * d - o * o;
    const L x0 = (L(b(0)) * d - o * L(b(1))) / det, x1 = (a * L(b(1)) - o * L(b(0))) / det;
    const L size = std::max(std::fabs(x0), std::fabs(x1));
    const double err =
        static_cast<double>(std::max(std::fabs(L(x(0)) - x0), std::fabs(L(x(1)) - x1)) / size);
    const double cond = std::pow(10.0, log_cond);
    worst = std::max(worst, err / (cond * eps));
    ASSERT_LE(err, 8 * cond * eps) << "trial " << trial;
  }
  EXPECT_GT(worst, 0.01);  // the bound is met, not met by a reference that is the solve itself
}

TEST(ClassicalTwoContacts, RegularityIsDecidedAtTheCholeskyThreshold) {
  // Pivots 1e-14 apart: the Cholesky diagonal's 1e-7, squared. G = [[1, ½], [½, ¼ + δ]] has the
  // pivots 1 and δ (exactly, to the rounding of ¼ + δ), and its mirror image δ, then 1.
  for (const double delta : {1e-13, 1e-15}) {
    Phase::RowMat G(2, 2);
    G << 1.0, 0.5, 0.5, 0.25 + delta;
    Factored f;
    f.compute(G, 3);
    EXPECT_EQ(f.regular, delta > 1e-14) << delta;
    G << delta, 0.0, 0.0, 1.0;
    f.compute(G, 3);
    EXPECT_EQ(f.regular, delta > 1e-14) << delta;
  }
  Phase::RowMat G(2, 2);
  G << 1.0, 1.0, 1.0, 1.0;  // exactly singular: its second pivot is 0
  Factored f;
  f.compute(G, 3);
  EXPECT_FALSE(f.regular);
  G << -1.0, 0.0, 0.0, 1.0;  // not positive definite
  f.compute(G, 3);
  EXPECT_FALSE(f.regular);
  G << 1.0, 0.0, 0.0, 1.0;  // two rows on one degree of freedom: singular for sure
  f.compute(G, 1);
  EXPECT_FALSE(f.regular);
}

TEST(ClassicalTwoContacts, EveryModeAgreesWithLemke) {
  // Random positive definite LCPs of two frictionless contacts (q of either sign, so every mode
  // occurs): the closed forms, where they answer, give Lemke's z to rounding; they answer on all
  // but the borders between modes.
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), lc(0.0, 6.0);
  int answered = 0, modes[3] = {0, 0, 0};
  constexpr int kTrials = 20000;
  for (int trial = 0; trial < kTrials; ++trial) {
    Phase ph;
    ph.a = 2;
    ph.friction = false;
    ph.G = random_spd(gen, lc(gen), 0.0);
    ph.q.resize(2);
    ph.q << u(gen), u(gen);
    ph.mu.setZero(2);
    ph.b0.setZero(2);
    const auto tol = detail::classical::tolerances(ph, ph.q.cwiseAbs().maxCoeff());
    Factored f;
    f.compute(ph.G, 3);
    Phase::Rows closed(2), lemke(2);
    int pivots = 0;
    ASSERT_EQ(detail::classical::lemke_phase(ph, LemkeOptions{}, lemke, pivots), LcpStatus::solved);
    if (!detail::classical::closed_guess(ph, tol, f, closed)) continue;
    ++answered;
    ++modes[(closed(0) > 0) + (closed(1) > 0)];
    const double size = 1.0 + lemke.cwiseAbs().maxCoeff();
    for (int i = 0; i < 2; ++i)
      EXPECT_NEAR(closed(i), std::max(0.0, lemke(i)), 1e-9 * size) << "trial " << trial;
  }
  EXPECT_GE(answered, kTrials - 10);
  for (const int m : modes) EXPECT_GT(m, kTrials / 10);  // none, one and both contacts closed
}

}  // namespace
