// The eq. 6 guess of the classical laws where G is singular (closed_sticking_semidefinite in
// src/solvers/detail/classical_phase.hpp): every contact closed and sticking, G u = −q on a line
// of solutions, the point of the line nearest its minimum-norm point that satisfies Coulomb's
// inequalities. Checked against references it does not use: the flat bar's hand-derived answer,
// the pseudo-inverse (Eigen's complete orthogonal decomposition) for the minimum-norm point, and
// feasible points built by construction, which bound the answer's norm.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <random>

#include "classical_support.hpp"
#include "solvers/detail/classical_phase.hpp"

namespace {

using namespace fremond;
using fremond::test::flat_bar;
using Phase = detail::classical::Phase<4>;

/// Newton's phase (q = ((1 + e) D_NA, D_TA)) of a problem whose contacts all take part.
Phase newton_phase(const ImpactProblem& p, double e, double mu) {
  const int c = static_cast<int>(p.W_N.cols());
  Eigen::MatrixXd W(p.M.rows(), 2 * c);
  W << p.W_N, p.W_T;
  const Eigen::MatrixXd G = W.transpose() * p.M.llt().solve(W);
  Eigen::VectorXd q = W.transpose() * p.qdot_A;
  q.head(c) *= 1 + e;
  Phase ph;
  ph.a = c;
  ph.friction = true;
  ph.G = G;
  ph.q = q;
  ph.mu.setConstant(c, mu);
  ph.b0.setZero(c);
  return ph;
}

/// G = Wᵀ M⁻¹ W of `a` contacts with friction (r = 2a rows) on a body of r − 1 degrees of
/// freedom, W and M random (M symmetric positive definite): rank r − 1, one line of null space.
Eigen::MatrixXd random_semidefinite_G(std::mt19937& gen, int a) {
  std::uniform_real_distribution<double> sym(-1.0, 1.0);
  const int r = 2 * a, n = r - 1;
  Eigen::MatrixXd W(n, r), A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < r; ++j) W(i, j) = sym(gen);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = sym(gen);
  const Eigen::MatrixXd M = A * A.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
  return W.transpose() * M.llt().solve(W);
}

/// The phase whose percussion u_true makes every velocity zero (q = −G u_true), friction μ per
/// contact and no fixed bound: every contact closed and sticking solves it where u_true does.
Phase sticking_phase(const Eigen::MatrixXd& G, const Eigen::VectorXd& mu,
                     const Eigen::VectorXd& u_true) {
  Phase ph;
  ph.a = static_cast<int>(mu.size());
  ph.friction = true;
  ph.G = G;
  ph.q = -G * u_true;
  ph.mu = mu;
  ph.b0.setZero(ph.a);
  return ph;
}

detail::classical::Tolerances tolerances(const Phase& ph) {
  return detail::classical::tolerances(ph, ph.q.cwiseAbs().maxCoeff());
}

TEST(ClassicalStickingGuess, FlatBarSticksWithTheHandDerivedAnswer) {
  // The flat bar falling and turning, q̇_A = (ẋ, −3, 1), e = 0.9, μ = 1: both ends close
  // (D_NA = −3 ∓ l = −3.5, −2.5), and ẋ = 0.5 is stopped by the ends' friction, as
  // m|ẋ| = 0.5 ≤ μ(P_N1 + P_N2) = 1.9 · 3 m. By hand: the normal percussions of Newton's law alone
  // (the tangential ones do not move the normal rows: W_T = (1, 0, 0)) are
  // P_N1 + P_N2 = 1.9 · 3 m and (P_N1 − P_N2) l = 1.9 · J θ̇ (end 1, at −l, closes faster); the
  // tangential ones sum to −m ẋ and, at the minimum norm, split evenly.
  const double xdot = 0.5, e = 0.9, mu = 1.0;
  const Phase ph = newton_phase(flat_bar(Eigen::Vector3d(xdot, -3.0, 1.0)), e, mu);
  Phase::Rows u;
  ASSERT_TRUE(detail::classical::closed_sticking_semidefinite(ph, tolerances(ph), u));
  using test::kJ, test::kL, test::kM;
  const double sum = 1.9 * 3 * kM, diff = 1.9 * kJ * 1.0 / kL;
  EXPECT_NEAR(u(0), 0.5 * (sum + diff), 1e-13);
  EXPECT_NEAR(u(1), 0.5 * (sum - diff), 1e-13);
  EXPECT_NEAR(u(2), -0.5 * kM * xdot, 1e-13);
  EXPECT_NEAR(u(3), -0.5 * kM * xdot, 1e-13);
}

TEST(ClassicalStickingGuess, FlatBarThatSlidesIsLeftToLemke) {
  // ẋ = 20: m|ẋ| > μ ΣP_N = 5.7 m, no sticking answer: the guess says so (false), for Lemke.
  const Phase ph = newton_phase(flat_bar(Eigen::Vector3d(20.0, -3.0, 1.0)), 0.9, 1.0);
  Phase::Rows u;
  EXPECT_FALSE(detail::classical::closed_sticking_semidefinite(ph, tolerances(ph), u));
  // A q outside G's range (the two tangential rows disagree, W_T being the same for both): no
  // percussion makes every velocity zero.
  Phase off = ph;
  off.q(2) += 1.0;
  off.q(0) = -1.0;
  off.q(1) = -1.0;
  EXPECT_FALSE(detail::classical::closed_sticking_semidefinite(off, tolerances(off), u));
}

TEST(ClassicalStickingGuess, RandomSemidefinitePhasesGiveTheNearestFeasiblePoint) {
  // Two or three contacts on a body with one degree of freedom fewer than G's rows (G of rank
  // r − 1), q = −G u_true with u_true sticking strictly inside Coulomb's cone: the guess must find
  // an answer, with G u + q = 0, inside the cone, no longer than u_true (u_true is on the same
  // line of solutions), and equal to the pseudo-inverse's minimum-norm solution whenever that one
  // is inside the cone.
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u01(0.0, 1.0), sym(-1.0, 1.0);
  int min_norm_inside = 0, found = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const int a = 2 + trial % 2, r = 2 * a;
    const Eigen::MatrixXd G = random_semidefinite_G(gen, a);
    const double mu = 0.2 + 2 * u01(gen);
    Eigen::VectorXd ut(r);
    for (int i = 0; i < a; ++i) {
      ut(i) = 0.1 + u01(gen);
      ut(a + i) = 0.9 * mu * ut(i) * sym(gen);
    }
    const Phase ph = sticking_phase(G, Eigen::VectorXd::Constant(a, mu), ut);
    const auto tol = tolerances(ph);
    Phase::Rows u;
    ASSERT_TRUE(detail::classical::closed_sticking_semidefinite(ph, tol, u)) << trial;
    ++found;
    const Eigen::VectorXd ud = u;
    EXPECT_LE((G * ud + ph.q).cwiseAbs().maxCoeff(), tol.v) << trial;
    for (int i = 0; i < a; ++i) {
      EXPECT_GE(ud(i), 0.0) << trial;
      EXPECT_LE(std::fabs(ud(a + i)), mu * ud(i) + tol.p) << trial;
    }
    EXPECT_LE(ud.norm(), ut.norm() * (1 + 1e-12)) << trial;
    const Eigen::VectorXd pinv = -G.completeOrthogonalDecomposition().solve(ph.q);
    bool inside = true;
    for (int i = 0; i < a; ++i)
      inside = inside && pinv(i) > 0.0 && std::fabs(pinv(a + i)) < mu * pinv(i);
    if (inside) {
      ++min_norm_inside;
      EXPECT_LE((ud - pinv).norm(), 1e-10 * ut.norm()) << trial;
    }
  }
  EXPECT_EQ(found, 500);
  EXPECT_GT(min_norm_inside, 50);  // both branches (clamped or not) were exercised
  EXPECT_LT(min_norm_inside, 450);
}

TEST(ClassicalStickingGuess, ItsMinimumNormChoiceIsTheGeneralOne) {
  // The law takes the guess's answer as its own minimum-norm choice, without computing null(G)
  // (GuessNorm). Checked against minimum_norm itself, from null(G) and Lemke's projection, on
  // random semidefinite phases: sticking inside the cone (a whole interval of answers: not
  // unique), on its boundary at every contact (the interval pinned to a point, or not, as the
  // line's direction meets the boundaries), and with μ = 0 at one contact (its t pinned to 0).
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u01(0.0, 1.0), sym(-1.0, 1.0);
  int compared = 0, unique = 0, several = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const int a = 2 + trial % 2, r = 2 * a, kind = (trial / 2) % 3;
    const Eigen::MatrixXd G = random_semidefinite_G(gen, a);
    Eigen::VectorXd mu(a), ut(r);
    for (int i = 0; i < a; ++i) {
      mu(i) = kind == 2 && i == 0 ? 0.0 : 0.2 + 2 * u01(gen);
      ut(i) = 0.1 + u01(gen);
      const double side = sym(gen) < 0 ? -1.0 : 1.0;
      ut(a + i) = kind == 1 ? side * mu(i) * ut(i) : 0.9 * mu(i) * ut(i) * sym(gen);
    }
    const Phase ph = sticking_phase(G, mu, ut);
    const auto tol = tolerances(ph);
    Phase::Rows u;
    detail::classical::GuessNorm norm;
    if (!detail::classical::closed_sticking_semidefinite(ph, tol, u, &norm)) {
      // Only where ut sits on the cone's boundary may rounding leave no sticking answer.
      EXPECT_EQ(kind, 1) << trial;
      continue;
    }
    ASSERT_TRUE(norm.minimum) << trial;  // G of rank r − 1 by a wide margin
    const Phase::Rows zero = Phase::Rows::Zero(r);
    Phase::Rows general = u;
    const bool general_unique = detail::classical::minimum_norm<4>(
        ph, tol, detail::classical::null_space<4>(ph.G), zero, general);
    ++compared;
    EXPECT_LE((general - u).cwiseAbs().maxCoeff(), 1e-10 * ut.cwiseAbs().maxCoeff()) << trial;
    EXPECT_EQ(norm.unique, general_unique) << trial;
    (norm.unique ? unique : several)++;
  }
  EXPECT_GT(compared, 500);
  EXPECT_GT(unique, 50);  // both verdicts were exercised
  EXPECT_GT(several, 50);
}

}  // namespace
