// Newton's and Poisson's laws without friction (docs/laws.md; paper eqs. 5-6), against eq. (6), the
// LCP solved on its own, and hand derivations.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "fremond/solvers/lemke.hpp"
#include "unit/classical_support.hpp"

namespace fremond {
namespace {

using test::bar_first_impact;
using test::flat_bar;
using test::kL;

// G_NN = W_Nᵀ M⁻¹ W_N and D_NA = W_Nᵀ q̇_A from the data.
MatrixX delassus_nn(const ImpactProblem& p) {
  return p.W_N.transpose() * p.M.llt().solve(p.W_N);
}
VectorX dna(const ImpactProblem& p) {
  return p.W_N.transpose() * p.qdot_A;
}

TEST(ClassicalNewton, OneContactMatchesEquation6AndTheLcp) {
  const ImpactProblem p = bar_first_impact(false);
  for (const double e : {0.0, 0.3, 0.9, 1.0}) {
    const ImpactResult r = solve_impact(p, ImpactLaw::newton(e));
    ASSERT_TRUE(r.ok()) << r.solver.message;
    // Eq. (6): q̇_E = q̇_A − M⁻¹ W_N G_N⁻¹ (1 + e) D_NA.
    const MatrixX GN = delassus_nn(p);
    const VectorX eq6 = p.qdot_A - p.M.llt().solve(p.W_N) * GN.inverse() * ((1 + e) * dna(p));
    EXPECT_LE((r.qdot_E - eq6).cwiseAbs().maxCoeff(), 1e-12) << "e=" << e;
    // The same impact as LCP(G_NN, (1 + e) D_NA), solved by the public Lemke solver.
    const LcpResult lcp = solve_lcp(GN, VectorX((1 + e) * dna(p)));
    ASSERT_TRUE(lcp.ok());
    EXPECT_NEAR(r.P_N(0), lcp.z(0), 1e-12) << "e=" << e;
    // Eqs. (7)-(8): G_NN = (1 + 3 cos²θ)/m = 2.5 at θ = π/4.
    EXPECT_NEAR(GN(0, 0), 2.5, 1e-14);
    EXPECT_EQ(r.solver.method, SolverMethod::closed_form);
    EXPECT_EQ(r.solver.criterion, StopCriterion::exact);
    EXPECT_TRUE(r.unique);
    EXPECT_EQ(r.solutions_found, 1);
    EXPECT_LE(r.solver.residual, 1e-15);
    // The solve judged the answer at its own velocities, law_residual at velocities recomputed
    // from the percussions: both are rounding, 64ε apart at most.
    EXPECT_NEAR(law_residual(p, ImpactLaw::newton(e), r), r.solver.residual, 1.5e-14);
  }
}

TEST(ClassicalNewton, RestitutionZeroAndOneAreExact) {
  for (const ImpactProblem& p :
       {bar_first_impact(false), test::point_mass(0.7, -2.0, 3.0, false)}) {
    const double d = dna(p)(0);
    const ImpactResult plastic = solve_impact(p, ImpactLaw::newton(0.0));
    EXPECT_LE(std::fabs(plastic.D_NE(0)), 1e-15 * std::fabs(d));
    const ImpactResult elastic = solve_impact(p, ImpactLaw::newton(1.0));
    EXPECT_NEAR(elastic.D_NE(0), -d, 1e-15 * std::fabs(d));
    // e = 1 without friction conserves the kinetic energy (eq. 9: P·z = 0 since z_N = 0).
    const double TA = test::kinetic(p, p.qdot_A);
    EXPECT_LE(std::fabs(elastic.energy_change), 1e-14 * TA);
    EXPECT_NEAR(test::kinetic(p, elastic.qdot_E), TA, 1e-14 * TA);
    EXPECT_TRUE(elastic.admissibility.admissible);
  }
}

TEST(ClassicalNewton, FlatBarTwoContactsByHand) {
  // θ = 0, q̇_A = (2, −3, 1): D_NA = ẏ ∓ l θ̇ = (−3.5, −2.5); G_NN = [[4, −2], [−2, 4]] (m = 1,
  // l²/J = 3); G_NN⁻¹ = [[4, 2], [2, 4]]/12, so with e = 0.9 both ends stay closed and
  // P_N = 1.9 G_NN⁻¹ (3.5, 2.5) = 1.9 (19, 17)/12.
  const ImpactProblem p = flat_bar(Eigen::Vector3d(2, -3, 1), false);
  const ImpactResult r = solve_impact(p, ImpactLaw::newton(0.9));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_NEAR(r.P_N(0), 1.9 * 19 / 12, 1e-14);
  EXPECT_NEAR(r.P_N(1), 1.9 * 17 / 12, 1e-14);
  EXPECT_NEAR(r.D_NE(0), 0.9 * 3.5, 1e-14);
  EXPECT_NEAR(r.D_NE(1), 0.9 * 2.5, 1e-14);
  EXPECT_TRUE(r.unique);
  // Eq. (6) holds for both contacts at once.
  EXPECT_EQ(r.solver.method, SolverMethod::closed_form);
}

TEST(ClassicalNewton, AContactThatEq6WouldPullOpens) {
  // A point mass (m = 1) on two walls with normals n1 = (0, 1), n2 = (0.6, 0.8), q̇_A = (0.3, −1):
  // D_NA = (−1, −0.62), G_NN = [[1, 0.8], [0.8, 1]]. Eq. (6) would give P_2 < 0, so contact 2
  // opens: P = (1.5, 0) with e = 0.5, and D_NE,2 + e D_NA,2 = (−0.62 + 0.8·1.5) − 0.31 = 0.27 ≥ 0.
  ImpactProblem p;
  p.M = Eigen::Matrix2d::Identity();
  p.W_N.resize(2, 2);
  p.W_N << 0, 0.6, 1, 0.8;
  p.W_T.resize(2, 0);
  p.qdot_A = Eigen::Vector2d(0.3, -1.0);
  const MatrixX GN = delassus_nn(p);
  const VectorX eq6 = -GN.inverse() * (1.5 * dna(p));
  ASSERT_LT(eq6(1), 0.0);  // the closed form of eq. (6) does not apply here
  const ImpactResult r = solve_impact(p, ImpactLaw::newton(0.5));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_NEAR(r.P_N(0), 1.5, 1e-14);
  EXPECT_EQ(r.P_N(1), 0.0);
  EXPECT_NEAR(r.D_NE(1) + 0.5 * r.D_NA(1), 0.27, 1e-14);
  EXPECT_NEAR(r.qdot_E(1), 0.5, 1e-14);
  // Two frictionless contacts on a regular G: the mode with one contact open is a closed form
  // too (one_of_two_closed; against Lemke in the test below).
  EXPECT_EQ(r.solver.method, SolverMethod::closed_form);
  EXPECT_TRUE(r.unique);
}

TEST(ClassicalNewton, TwoFrictionlessContactsInEachModeAgreeWithLemke) {
  // The point mass on two walls of the test above (G_NN = [[1, 0.8], [0.8, 1]], e = 0.5, so
  // q = 1.5 D_NA), in each mode both contacts can take: both closed, G u = −q; contact k alone,
  // u_k = −q_k with the other's velocity q_o + 0.8 u_k ≥ 0. The closed forms (the all-closed
  // guess, one_of_two_closed) against the modes by hand and against Lemke's pivots, forced.
  struct Mode {
    Eigen::Vector2d qdot;
    double p0, p1;
  };
  // D_NA = (ẏ, 0.6 ẋ + 0.8 ẏ):
  //  (−1, −1.1): u = G⁻¹ (1.5, 1.65) = (0.18, 0.45) / 0.36, both closed;
  //  (−1, −0.62): u_0 = 1.5, then q_1 + 0.8 u_0 = 0.27 ≥ 0;
  //  (−0.1, −0.68): u_1 = 1.02, then q_0 + 0.8 u_1 = 0.666 ≥ 0.
  for (const Mode& m : {Mode{{-0.5, -1.0}, 0.5, 1.25}, Mode{{0.3, -1.0}, 1.5, 0.0},
                        Mode{{-1.0, -0.1}, 0.0, 1.02}}) {
    ImpactProblem p;
    p.M = Eigen::Matrix2d::Identity();
    p.W_N.resize(2, 2);
    p.W_N << 0, 0.6, 1, 0.8;
    p.W_T.resize(2, 0);
    p.qdot_A = m.qdot;
    const ImpactResult r = solve_impact(p, ImpactLaw::newton(0.5));
    ASSERT_TRUE(r.ok()) << r.solver.message;
    EXPECT_EQ(r.solver.method, SolverMethod::closed_form);
    EXPECT_NEAR(r.P_N(0), m.p0, 1e-14);
    EXPECT_NEAR(r.P_N(1), m.p1, 1e-14);
    EXPECT_TRUE(r.unique);
    SolverOptions lemke;
    lemke.method = SolverMethod::lemke;
    const ImpactResult l = solve_impact(p, ImpactLaw::newton(0.5), lemke);
    ASSERT_TRUE(l.ok()) << l.solver.message;
    EXPECT_EQ(l.solver.method, SolverMethod::lemke);
    EXPECT_NEAR(l.P_N(0), r.P_N(0), 1e-14);
    EXPECT_NEAR(l.P_N(1), r.P_N(1), 1e-14);
  }
}

TEST(ClassicalNewton, ASeparatingContactCarriesOnlyItsReaction) {
  // The flat bar turning fast: the right end (W_N = (0, 1, l)) moves up, D_NA = −0.5 + 0.5·3 = 1,
  // the left end arrives at −2. The left end's percussion would sink the right one, so both close:
  // D_NE = (0.5·2, 0) = D_NA + G P with G = [[4, −2], [−2, 4]] gives P = (5/6, 1/6).
  const ImpactProblem p = flat_bar(Eigen::Vector3d(0, -0.5, 3), false);
  const ImpactResult r = solve_impact(p, ImpactLaw::newton(0.5));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.takes_part(1), 0);
  EXPECT_NEAR(r.P_N(0), 5.0 / 6.0, 1e-14);
  EXPECT_NEAR(r.P_N(1), 1.0 / 6.0, 1e-14);
  EXPECT_NEAR(r.D_NE(0), 1.0, 1e-14);
  EXPECT_NEAR(r.D_NE(1), 0.0, 1e-14);
  // Leaving fast enough (D_NA = 4 > 2 P_N(0)), it is not driven: eq. (6) on the left end alone,
  // G_NN = 1 + l²/J = 4.
  const ImpactResult fast =
      solve_impact(flat_bar(Eigen::Vector3d(0, -0.5, 9), false), ImpactLaw::newton(0.5));
  ASSERT_TRUE(fast.ok());
  EXPECT_EQ(fast.P_N(1), 0.0);
  EXPECT_NEAR(fast.P_N(0), -1.5 * (-0.5 - kL * 9) / 4, 1e-14);
  // Everything separating: nothing happens.
  const ImpactResult none =
      solve_impact(flat_bar(Eigen::Vector3d(0, 1, 0), false), ImpactLaw::newton(0.5));
  EXPECT_EQ(none.solver.method, SolverMethod::trivial);
  EXPECT_TRUE(none.ok());
  EXPECT_EQ(none.qdot_E, Eigen::Vector3d(0, 1, 0));
}

// Every active set of LCP(G_NN, q), independent of the library: the solution for a P-matrix.
VectorX active_set_solution(const MatrixX& G, const VectorX& q) {
  const int c = static_cast<int>(q.size());
  for (int set = 0; set < (1 << c); ++set) {
    VectorX P = VectorX::Zero(c);
    std::vector<int> s;
    for (int i = 0; i < c; ++i)
      if (set & (1 << i)) s.push_back(i);
    const int k = static_cast<int>(s.size());
    MatrixX Gs(k, k);
    VectorX qs(k);
    for (int i = 0; i < k; ++i) {
      qs(i) = q(s[i]);
      for (int j = 0; j < k; ++j) Gs(i, j) = G(s[i], s[j]);
    }
    if (k) {
      const VectorX ps = Gs.lu().solve(-qs);
      for (int i = 0; i < k; ++i) P(s[i]) = ps(i);
    }
    const VectorX w = G * P + q;
    const double tol = 1e-12 * q.cwiseAbs().maxCoeff();
    if (P.minCoeff() >= -tol && w.minCoeff() >= -tol) return P;
  }
  return VectorX();
}

TEST(ClassicalNewton, RandomProblemsMatchTheActiveSetSolution) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int lemke_used = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 6, c = 1 + trial % 4;
    MatrixX A(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = u(rng);
    ImpactProblem p;
    p.M = A * A.transpose() / n + 0.5 * MatrixX::Identity(n, n);
    p.W_N.resize(n, c);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < c; ++j) p.W_N(i, j) = u(rng);
    p.W_T.resize(n, 0);
    p.qdot_A.resize(n);
    for (int i = 0; i < n; ++i) p.qdot_A(i) = u(rng);
    for (int j = 0; j < c; ++j)
      if (p.W_N.col(j).dot(p.qdot_A) > 0) p.W_N.col(j) *= -1;  // every contact takes part
    const double e = 0.5 * (1 + u(rng));
    const VectorX P = active_set_solution(delassus_nn(p), (1 + e) * dna(p));
    ASSERT_EQ(P.size(), c);
    const ImpactResult r = solve_impact(p, ImpactLaw::newton(e));
    const SmallImpactResult s = solve_impact(to_small(p), ImpactLaw::newton(e));
    ASSERT_TRUE(r.ok()) << "trial " << trial << ": " << r.solver.message;
    ASSERT_TRUE(s.ok()) << "trial " << trial << ": " << s.solver.message;
    EXPECT_LE((r.P_N - P).cwiseAbs().maxCoeff(), 1e-11 * (1 + P.cwiseAbs().maxCoeff()))
        << "trial " << trial;
    EXPECT_LE((VectorX(s.P_N) - r.P_N).cwiseAbs().maxCoeff(),
              1e-14 * (1 + P.cwiseAbs().maxCoeff()));
    lemke_used += r.solver.method == SolverMethod::lemke;
  }
  EXPECT_GT(lemke_used, 10);  // the sample reaches the LCP, not only the closed forms
}

TEST(ClassicalPoisson, EqualsNewtonForOneFrictionlessContact) {
  const ImpactProblem p = bar_first_impact(false);
  for (const double e : {0.0, 0.5, 0.9, 1.0}) {
    const ImpactResult n = solve_impact(p, ImpactLaw::newton(e));
    const ImpactResult q = solve_impact(p, ImpactLaw::poisson(e));
    ASSERT_TRUE(q.ok()) << q.solver.message;
    EXPECT_LE((q.qdot_E - n.qdot_E).cwiseAbs().maxCoeff(), 1e-14) << "e=" << e;
    EXPECT_NEAR(q.P_N(0), n.P_N(0), 1e-14);
    // Phases: compression stops the contact, P_NC = −D_NA/G_NN, then P_NE = e P_NC.
    ASSERT_TRUE(q.has_phases);
    EXPECT_NEAR(q.P_NC(0), -dna(p)(0) / 2.5, 1e-14);
    EXPECT_NEAR(q.D_NC(0), 0.0, 1e-15);
    EXPECT_NEAR(q.P_N(0), (1 + e) * q.P_NC(0), 1e-14);
    EXPECT_TRUE(q.unique);
    EXPECT_LE(q.solver.residual, 1e-15);
  }
}

TEST(ClassicalPoisson, EqualsNewtonOnTheFlatBarWithOneRestitution) {
  // Every contact closed in compression and one e: D_NE = e G P_NC = −e D_NA, Newton's answer.
  const ImpactProblem p = flat_bar(Eigen::Vector3d(2, -3, 1), false);
  const ImpactResult n = solve_impact(p, ImpactLaw::newton(0.7));
  const ImpactResult q = solve_impact(p, ImpactLaw::poisson(0.7));
  ASSERT_TRUE(q.ok());
  EXPECT_LE((q.qdot_E - n.qdot_E).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(ClassicalPoisson, DiffersFromNewtonWithSeveralContactsByHand) {
  // The flat bar with e = (0.9, 0.1). G_NN = [[4, −2], [−2, 4]], D_NA = (−3.5, −2.5).
  const ImpactProblem p = flat_bar(Eigen::Vector3d(2, -3, 1), false);
  const PerContact e{0.9, 0.1};
  Eigen::Matrix2d G;
  G << 4, -2, -2, 4;
  const Eigen::Vector2d D(-3.5, -2.5), ev(0.9, 0.1);
  // Newton: both closed, P = −G⁻¹ (1 + e)∘D_NA > 0, D_NE = −e∘D_NA.
  const ImpactResult n = solve_impact(p, ImpactLaw::newton(e));
  ASSERT_TRUE(n.ok());
  const Eigen::Vector2d Pn = -G.inverse() * (Eigen::Vector2d(1, 1) + ev).cwiseProduct(D);
  ASSERT_GT(Pn.minCoeff(), 0.0);
  EXPECT_NEAR(n.D_NE(0), 3.15, 1e-14);
  EXPECT_NEAR(n.D_NE(1), 0.25, 1e-14);
  EXPECT_LE((VectorX(n.P_N) - VectorX(Pn)).cwiseAbs().maxCoeff(), 1e-14);
  // Poisson: compression P_NC = −G⁻¹ D_NA > 0; expansion from D_NC = 0 with P_NE = e∘P_NC gives
  // G (e∘P_NC) whose second entry is negative, so ΔP_2 = −that/G_22 > 0 closes contact 2 and
  // D_NE,1 = first entry + G_12 ΔP_2.
  const ImpactResult q = solve_impact(p, ImpactLaw::poisson(e));
  ASSERT_TRUE(q.ok()) << q.solver.message;
  const Eigen::Vector2d PC = -G.inverse() * D;
  const Eigen::Vector2d free_exp = G * ev.cwiseProduct(PC);
  ASSERT_LT(free_exp(1), 0.0);
  const double dP2 = -free_exp(1) / G(1, 1);
  EXPECT_NEAR(q.P_NC(0), PC(0), 1e-14);
  EXPECT_NEAR(q.P_NC(1), PC(1), 1e-14);
  EXPECT_NEAR(q.D_NE(0), free_exp(0) + G(0, 1) * dP2, 1e-13);
  EXPECT_NEAR(q.D_NE(1), 0.0, 1e-14);
  EXPECT_NEAR(q.P_N(1), PC(1) + ev(1) * PC(1) + dP2, 1e-14);
  EXPECT_NEAR(q.D_NE(0), 4.275, 1e-13);  // against Newton's 3.15: the laws differ here
  EXPECT_TRUE(q.unique);
}

TEST(ClassicalPoisson, NonUniqueCompressionUsesTheMinimumNorm) {
  // A point mass on two coincident contacts (W_N = (0, 1) twice, G_NN = [[1, 1], [1, 1]] singular),
  // q̇_A = (0, −1), e = (1, 0). Compression needs P_NC,1 + P_NC,2 = 1: any split solves it, the
  // minimum-norm one is (1/2, 1/2). Expansion: P_NE = e∘P_NC = (1/2, 0) gives D_NE = 1/2 > 0, so
  // ΔP = 0 and q̇_E = (0, −1/2 + 1). The split (1, 0) would give D_NE = 1: the outcome depends on
  // it.
  ImpactProblem p;
  p.M = Eigen::Matrix2d::Identity();
  p.W_N.resize(2, 2);
  p.W_N << 0, 0, 1, 1;
  p.W_T.resize(2, 0);
  p.qdot_A = Eigen::Vector2d(0, -1);
  const ImpactResult r = solve_impact(p, ImpactLaw::poisson(PerContact{1.0, 0.0}));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_NEAR(r.P_NC(0), 0.5, 1e-14);
  EXPECT_NEAR(r.P_NC(1), 0.5, 1e-14);
  EXPECT_NEAR(r.P_N(0), 1.0, 1e-14);
  EXPECT_NEAR(r.P_N(1), 0.5, 1e-14);
  EXPECT_NEAR(r.qdot_E(1), 0.5, 1e-14);
  EXPECT_FALSE(r.unique);
  EXPECT_NE(std::string(r.solver.message).find("minimum-norm"), std::string::npos);
  EXPECT_LE(r.solver.residual, 1e-15);
}

TEST(ClassicalResidual, RecomputesVelocitiesAndCatchesAWrongAnswer) {
  const ImpactProblem p = bar_first_impact();
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.9, 1.0);
  ImpactResult r = solve_impact(p, law);
  ASSERT_LE(law_residual(p, law, r), 1e-14);
  // Velocities that do not balance the percussions are not trusted: the residual is then the
  // one at the velocities the percussions make (as for a result without velocities).
  ImpactResult wrong_v = r;
  wrong_v.qdot_E *= 2;
  wrong_v.D_NE *= 2;
  ImpactResult no_v = r;
  no_v.qdot_E.resize(0);
  EXPECT_DOUBLE_EQ(law_residual(p, law, wrong_v), law_residual(p, law, no_v));
  EXPECT_LE(law_residual(p, law, no_v), 1e-14);
  ImpactResult wrong_p = r;
  wrong_p.P_N(0) *= 1.01;
  EXPECT_GT(law_residual(p, law, wrong_p), 1e-3);
  ImpactResult wrong_t = r;
  wrong_t.P_T(0) = -wrong_t.P_T(0);
  EXPECT_GT(law_residual(p, law, wrong_t), 1e-2);
  // Poisson needs its phases.
  ImpactResult no_phases = r;
  EXPECT_TRUE(std::isinf(law_residual(p, ImpactLaw::poisson_coulomb(0.9, 1.0), no_phases)));
}

}  // namespace
}  // namespace fremond
