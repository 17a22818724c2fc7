// Newton + Coulomb and Poisson + Coulomb (docs/laws.md, paper §4): stick, slide and reversal
// against hand derivations, the frictionless limit, several solutions, the singular flat bar, and
// the enumeration against Lemke.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "fremond/solvers/lemke.hpp"
#include "unit/classical_support.hpp"

namespace fremond {
namespace {

using test::bar;
using test::bar_first_impact;
using test::flat_bar;
using test::point_mass;

constexpr double kPi4 = std::numbers::pi / 4;

TEST(ClassicalCoulomb, PointMassSticksByHand) {
  // G = I: P_N = −(1 + e) D_NA = 1.5; |D_TA| = 0.5 ≤ μ P_N, so P_T = −D_TA and D_TE = 0.
  const ImpactResult r = solve_impact(point_mass(0.5, -1.0), ImpactLaw::newton_coulomb(0.5, 1.0));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_NEAR(r.P_N(0), 1.5, 1e-15);
  EXPECT_NEAR(r.P_T(0), -0.5, 1e-15);
  EXPECT_NEAR(r.D_TE(0), 0.0, 1e-15);
  EXPECT_EQ(r.solver.method, SolverMethod::closed_form);
  EXPECT_TRUE(r.unique);
  EXPECT_EQ(r.solutions_found, 1);
}

TEST(ClassicalCoulomb, PointMassSlidesEitherWayByHand) {
  // P_N = 1.5, μ P_N = 0.75 < |D_TA| = 2: P_T = −0.75 sign(D_TA), D_TE = D_TA + P_T.
  for (const double vx : {2.0, -2.0}) {
    const ImpactResult r =
        solve_impact(point_mass(vx, -1.0, 2.0), ImpactLaw::newton_coulomb(0.5, 0.5));
    ASSERT_TRUE(r.ok()) << r.solver.message;
    // m = 2: G = I/2, P_N = 1.5·2 = 3, bound 1.5, D_TE = vx + P_T/2.
    EXPECT_NEAR(r.P_N(0), 3.0, 1e-15);
    EXPECT_NEAR(r.P_T(0), -std::copysign(1.5, vx), 1e-15);
    EXPECT_NEAR(r.D_TE(0), vx - std::copysign(0.75, vx), 1e-15);
    EXPECT_LE(r.solver.residual, 1e-15);
  }
}

TEST(ClassicalCoulomb, TiltedBarReversesItsSlidingByHand) {
  // The paper's bar at θ = π/4 (eqs. 7-8: G_NN = G_TT = 2.5, G_NT = −1.5) with e = 0.9, μ = 0.2.
  // Stick and forward sliding both fail; backward sliding (σ = −1, P_T = +μ P_N) gives
  // P_N = −(1 + e) D_NA/(G_NN + μ G_NT) and D_TE = D_TA + (G_NT + μ G_TT) P_N < 0 < D_TA.
  const double gnn = 2.5, gnt = -1.5, gtt = 2.5, e = 0.9, mu = 0.2;
  const double dna = test::first_impact_ydot(), dta = 2.0;
  const double qn = (1 + e) * dna;
  // Stick: G P = (−q_N, −D_TA) violates |P_T| ≤ μ P_N.
  const double det = gnn * gtt - gnt * gnt;
  const double stick_n = (gnt * dta - gtt * qn) / det, stick_t = (gnt * qn - gnn * dta) / det;
  ASSERT_GT(std::fabs(stick_t), mu * stick_n);
  // Forward sliding ends with D_TE < 0: contradicts σ = +1.
  const double fwd_n = -qn / (gnn - mu * gnt);
  ASSERT_LT(dta + (gnt - mu * gtt) * fwd_n, 0.0);
  const double pn = -qn / (gnn + mu * gnt), dte = dta + (gnt + mu * gtt) * pn;
  ASSERT_LT(dte, 0.0);

  const ImpactResult r = solve_impact(bar_first_impact(), ImpactLaw::newton_coulomb(e, mu));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_NEAR(r.P_N(0), pn, 1e-13);
  EXPECT_NEAR(r.P_T(0), mu * pn, 1e-13);
  EXPECT_NEAR(r.D_TE(0), dte, 1e-13);
  EXPECT_NEAR(r.D_NE(0), -e * dna, 1e-13);
  EXPECT_TRUE(r.unique);
}

// Newton + Coulomb on one contact as the planar friction LCP, built here: z = (P_N, β⁺, β⁻, λ),
//   w = (D_NE + e D_NA, D_TE + λ, −D_TE + λ, μ P_N − β⁺ − β⁻),   P_T = β⁺ − β⁻,
// and solved by the public Lemke solver: a second method beside the library's closed form.
TEST(ClassicalCoulomb, OneContactClosedFormMatchesTheLcp) {
  int compared = 0;
  for (const double theta : {0.3, kPi4, 1.2})
    for (const double mu : {0.1, 0.5, 1.0, 2.0})
      for (const double e : {0.0, 0.5, 1.0})
        for (const double vx : {-2.0, 0.3, 2.0}) {
          const ImpactProblem p = bar(theta, Eigen::Vector3d(vx, -1.5, 0.7));
          MatrixX W(3, 2);
          W << p.W_N, p.W_T;
          const MatrixX G = W.transpose() * p.M.llt().solve(W);
          const VectorX D = W.transpose() * p.qdot_A;
          ASSERT_LT(D(0), 0.0);
          MatrixX M = MatrixX::Zero(4, 4);
          M << G(0, 0), G(0, 1), -G(0, 1), 0,  //
              G(1, 0), G(1, 1), -G(1, 1), 1,   //
              -G(1, 0), -G(1, 1), G(1, 1), 1,  //
              mu, -1, -1, 0;
          const VectorX q = Eigen::Vector4d((1 + e) * D(0), D(1), -D(1), 0);
          const LcpResult lcp = solve_lcp(M, q);
          const ImpactResult r = solve_impact(p, ImpactLaw::newton_coulomb(e, mu));
          ASSERT_TRUE(r.ok()) << r.solver.message;
          EXPECT_EQ(r.solver.method, SolverMethod::closed_form);
          ASSERT_TRUE(r.unique);
          if (!lcp.ok()) continue;  // Lemke may end on a ray for this copositive matrix
          ++compared;
          EXPECT_NEAR(r.P_N(0), lcp.z(0), 1e-12) << theta << " " << mu << " " << e << " " << vx;
          EXPECT_NEAR(r.P_T(0), lcp.z(1) - lcp.z(2), 1e-12) << theta << " " << mu << " " << e;
        }
  EXPECT_GE(compared, 100);  // of 108
}

TEST(ClassicalCoulomb, ZeroFrictionIsTheFrictionlessLaw) {
  const std::vector<ImpactProblem> problems = {bar_first_impact(), point_mass(2, -1),
                                               flat_bar(Eigen::Vector3d(2, -3, 1))};
  for (const ImpactProblem& p : problems) {
    for (const double e : {0.0, 0.6, 1.0}) {
      const ImpactResult n = solve_impact(p, ImpactLaw::newton(e));
      const ImpactResult nc = solve_impact(p, ImpactLaw::newton_coulomb(e, 0.0));
      ASSERT_TRUE(nc.ok()) << nc.solver.message;
      EXPECT_EQ(nc.P_T.cwiseAbs().maxCoeff(), 0.0);
      EXPECT_LE((nc.qdot_E - n.qdot_E).cwiseAbs().maxCoeff(), 1e-14);
      const ImpactResult q = solve_impact(p, ImpactLaw::poisson(e));
      const ImpactResult qc = solve_impact(p, ImpactLaw::poisson_coulomb(e, 0.0));
      ASSERT_TRUE(qc.ok()) << qc.solver.message;
      EXPECT_LE((qc.qdot_E - q.qdot_E).cwiseAbs().maxCoeff(), 1e-14);
      // The friction machinery itself (a tiny μ, not the frictionless shortcut) tends to it.
      const ImpactResult tiny = solve_impact(p, ImpactLaw::newton_coulomb(e, 1e-12));
      ASSERT_TRUE(tiny.ok()) << tiny.solver.message;
      EXPECT_LE((tiny.qdot_E - n.qdot_E).cwiseAbs().maxCoeff(), 1e-10);
    }
  }
}

TEST(ClassicalCoulomb, RestitutionZeroAndOneAreExactWithFriction) {
  for (const double mu : {0.2, 1.0}) {
    for (const ImpactProblem& p : {bar_first_impact(), point_mass(1.0, -1.0)}) {
      const double dna = (p.W_N.transpose() * p.qdot_A)(0);
      const ImpactResult plastic = solve_impact(p, ImpactLaw::newton_coulomb(0.0, mu));
      ASSERT_TRUE(plastic.ok());
      EXPECT_LE(std::fabs(plastic.D_NE(0)), 1e-15 * std::fabs(dna));
      const ImpactResult elastic = solve_impact(p, ImpactLaw::newton_coulomb(1.0, mu));
      ASSERT_TRUE(elastic.ok());
      EXPECT_NEAR(elastic.D_NE(0), -dna, 2e-15 * std::fabs(dna));
      const ImpactResult pe = solve_impact(p, ImpactLaw::poisson_coulomb(0.0, mu));
      ASSERT_TRUE(pe.ok());
      EXPECT_LE(std::fabs(pe.D_NE(0)), 1e-15 * std::fabs(dna));
      EXPECT_EQ(pe.P_N(0), pe.P_NC(0));  // e = 0: no expansion percussion
    }
  }
}

TEST(ClassicalPoissonCoulomb, PointMassPhasesByHand) {
  // G = I, q̇_A = (1.1, −1), μ = 0.8, e = 0.5. Compression: P_NC = 1, bound 0.8 < 1.1: slides,
  // P_TC = −0.8, D_TC = 0.3. Expansion: P_NE = 0.5, bound 0.4 ≥ 0.3: sticks, P_TE = −0.3.
  const ImpactResult r = solve_impact(point_mass(1.1, -1.0), ImpactLaw::poisson_coulomb(0.5, 0.8));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  ASSERT_TRUE(r.has_phases);
  EXPECT_NEAR(r.P_NC(0), 1.0, 1e-15);
  EXPECT_NEAR(r.P_TC(0), -0.8, 1e-15);
  EXPECT_NEAR(r.D_NC(0), 0.0, 1e-15);
  EXPECT_NEAR(r.D_TC(0), 0.3, 1e-15);
  EXPECT_NEAR(r.P_N(0), 1.5, 1e-15);
  EXPECT_NEAR(r.P_T(0), -1.1, 1e-15);
  EXPECT_NEAR(r.D_TE(0), 0.0, 1e-15);
  // Decoupled, so it is also Newton + Coulomb's answer (stick iff |D_TA| ≤ μ(1 + e)|D_NA|).
  const ImpactResult n = solve_impact(point_mass(1.1, -1.0), ImpactLaw::newton_coulomb(0.5, 0.8));
  EXPECT_LE((n.qdot_E - r.qdot_E).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(ClassicalPoissonCoulomb, SlidesThroughBothPhasesByHand) {
  // q̇_A = (2, −1), μ = 0.8, e = 0.5: compression P_TC = −0.8, D_TC = 1.2; expansion bound 0.4
  // < 1.2: still sliding, P_TE = −0.4, D_TE = 0.8.
  const ImpactResult r = solve_impact(point_mass(2.0, -1.0), ImpactLaw::poisson_coulomb(0.5, 0.8));
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.D_TC(0), 1.2, 1e-15);
  EXPECT_NEAR(r.P_T(0), -1.2, 1e-15);
  EXPECT_NEAR(r.D_TE(0), 0.8, 1e-15);
}

TEST(ClassicalCoulomb, GrazingBarHasTwoSolutionsForLargeFriction) {
  // The bar at θ = π/4 touching with D_NA = 0 and sliding back, D_TA = −1 (q̇_A = (−1, 0, 0)). The
  // open contact (P = 0) is a solution. So is sticking, G P = (0, 1): P = (−G_NT, G_NN)/det =
  // (1.5, 2.5)/4 with w_N = 0, admissible when |P_T| ≤ μ P_N, i.e. μ ≥ G_NN/|G_NT| = 5/3.
  const ImpactProblem p = bar(kPi4, Eigen::Vector3d(-1, 0, 0));
  const auto all = solve_impact_all(p, ImpactLaw::newton_coulomb(0.5, 2.0));
  ASSERT_EQ(all.size(), 2u);
  // Sorted by dissipation: sticking loses ½ P_T D_TA = 0.3125 of energy, the open contact none.
  EXPECT_NEAR(all[0].P_N(0), 0.375, 1e-15);
  EXPECT_NEAR(all[0].P_T(0), 0.625, 1e-15);
  EXPECT_NEAR(all[0].energy_change, -0.3125, 1e-15);
  EXPECT_EQ(all[1].P_N(0), 0.0);
  EXPECT_EQ(all[1].P_T(0), 0.0);
  for (const auto& r : all) {
    EXPECT_FALSE(r.unique);
    EXPECT_EQ(r.solutions_found, 2);
    EXPECT_TRUE(r.ok());
    EXPECT_LE(r.solver.residual, 1e-15);
  }
  const ImpactResult one = solve_impact(p, ImpactLaw::newton_coulomb(0.5, 2.0));
  EXPECT_FALSE(one.unique);
  EXPECT_EQ(one.solutions_found, 2);
  EXPECT_NEAR(one.P_T(0), 0.625, 1e-15);  // the most dissipative is the one returned
  // Below the threshold only the open contact is left.
  const auto below = solve_impact_all(p, ImpactLaw::newton_coulomb(0.5, 1.6));
  ASSERT_EQ(below.size(), 1u);
  EXPECT_TRUE(below[0].unique);
  EXPECT_EQ(below[0].P_N(0), 0.0);
}

TEST(ClassicalCoulomb, FlatBarWithSingularGSticksWithTheMinimumNormSplit) {
  // θ = 0: G_NT = 0 and both tangents are (1, 0, 0), so the tangential rows of the 4×4 G are equal
  // (rank 3). Normal part as without friction: P_N = 1.9 (19, 17)/12, ΣP_N = 5.7. Tangentially the
  // bar is one mass: D_TE = D_TA + ΣP_T with D_TA = 2 ≤ μ ΣP_N, so it sticks with ΣP_T = −2;
  // the split is free within |P_T,i| ≤ μ P_N,i and the minimum-norm one is (−1, −1).
  const ImpactProblem p = flat_bar(Eigen::Vector3d(2, -3, 1));
  SolverOptions lemke_only;
  lemke_only.check_uniqueness = false;
  for (const SolverOptions& o : {SolverOptions{}, lemke_only}) {
    const ImpactResult r = solve_impact(p, ImpactLaw::newton_coulomb(0.9, 1.0), o);
    ASSERT_TRUE(r.ok()) << r.solver.message;
    EXPECT_NEAR(r.P_N(0), 1.9 * 19 / 12, 1e-13);
    EXPECT_NEAR(r.P_N(1), 1.9 * 17 / 12, 1e-13);
    EXPECT_NEAR(r.P_T(0), -1.0, 1e-13);
    EXPECT_NEAR(r.P_T(1), -1.0, 1e-13);
    EXPECT_NEAR(r.qdot_E(0), 0.0, 1e-13);
    EXPECT_NEAR(r.qdot_E(1), 2.7, 1e-13);
    EXPECT_NEAR(r.qdot_E(2), -0.9, 1e-13);
    EXPECT_FALSE(r.unique);  // the percussions are not unique, the velocities are
    EXPECT_NE(std::string(r.solver.message).find("minimum-norm"), std::string::npos);
    EXPECT_LE(r.solver.residual, 1e-14);
  }
  // Unchecked, the cheapest exact method answers: eq. 6's guess (both ends closed and sticking) in
  // its semidefinite form, on the line of solutions of the singular G, before Lemke.
  const ImpactResult lemke = solve_impact(p, ImpactLaw::newton_coulomb(0.9, 1.0), lemke_only);
  EXPECT_EQ(lemke.solver.method, SolverMethod::closed_form);
  EXPECT_EQ(lemke.solutions_found, 0);  // not checked
  // Sliding (μ = 0.2, μ ΣP_N = 1.14 < 2): each end's P_T = −μ P_N,i, unique.
  for (const SolverOptions& o : {SolverOptions{}, lemke_only}) {
    const ImpactResult s = solve_impact(p, ImpactLaw::newton_coulomb(0.9, 0.2), o);
    ASSERT_TRUE(s.ok()) << s.solver.message;
    EXPECT_NEAR(s.P_T(0), -0.2 * 1.9 * 19 / 12, 1e-13);
    EXPECT_NEAR(s.P_T(1), -0.2 * 1.9 * 17 / 12, 1e-13);
    EXPECT_NEAR(s.qdot_E(0), 2 - 0.2 * 5.7, 1e-13);
  }
  EXPECT_TRUE(solve_impact(p, ImpactLaw::newton_coulomb(0.9, 0.2)).unique);
  // μ at the bound, μ ΣP_N = 2 = D_TA: the bar just sticks, and only P_T,i = −μ P_N,i sums to −2
  // inside both cones: the line of percussions with these velocities is pinned to one point, so
  // the answer is unique (the minimum-norm choice says so, however the stick was found).
  for (const SolverOptions& o : {SolverOptions{}, lemke_only}) {
    const double mu = 2 / 5.7;
    const ImpactResult b = solve_impact(p, ImpactLaw::newton_coulomb(0.9, mu), o);
    ASSERT_TRUE(b.ok()) << b.solver.message;
    EXPECT_NEAR(b.P_T(0), -mu * 1.9 * 19 / 12, 1e-13);
    EXPECT_NEAR(b.P_T(1), -mu * 1.9 * 17 / 12, 1e-13);
    EXPECT_NEAR(b.qdot_E(0), 0.0, 1e-13);
    EXPECT_EQ(b.unique, o.check_uniqueness) << b.solver.message;
  }
  // Poisson + Coulomb on the same bar: compression P_NC = G_NN⁻¹ (3.5, 2.5) = (19, 17)/12 with
  // bound μ ΣP_NC = 3 ≥ 2: sticks with the split (−1, −1); the expansion starts at rest
  // tangentially (bound e μ ΣP_NC > 0) and stays there: P_TE = 0.
  const ImpactResult q = solve_impact(p, ImpactLaw::poisson_coulomb(0.9, 1.0));
  ASSERT_TRUE(q.ok()) << q.solver.message;
  EXPECT_NEAR(q.P_TC(0), -1.0, 1e-13);
  EXPECT_NEAR(q.P_TC(1), -1.0, 1e-13);
  EXPECT_NEAR(q.P_T(0), -1.0, 1e-13);
  EXPECT_NEAR(q.qdot_E(0), 0.0, 1e-13);
  EXPECT_FALSE(q.unique);
}

// ---------------------------------------------------------------------------------------------
// Several contacts: an independent enumeration of contact modes in the test, Lemke, and the
// library's enumeration must agree.

struct Reference {
  std::vector<VectorX> velocities;  // distinct D_E = (D_NE, D_TE) of every solution
};

// Newton + Coulomb by brute force over (open | stick | slide+ | slide−) per contact, for a regular
// G: each mode is a square linear system; a mode counts when its inequalities hold.
Reference brute_force_newton_coulomb(const ImpactProblem& p, double e, double mu) {
  const int c = p.contacts(), r = 2 * c;
  MatrixX W(p.dofs(), r);
  W << p.W_N, p.W_T;
  const MatrixX G = W.transpose() * p.M.llt().solve(W);
  const VectorX DA = W.transpose() * p.qdot_A;
  VectorX q = DA;
  q.head(c) *= (1 + e);
  Reference ref;
  const double tol = 1e-10 * DA.cwiseAbs().maxCoeff();
  int modes = 1;
  for (int i = 0; i < c; ++i) modes *= 4;
  for (int code = 0; code < modes; ++code) {
    MatrixX K = MatrixX::Zero(r, r);
    VectorX b = VectorX::Zero(r);
    std::vector<int> mode(c);
    for (int i = 0, k = code; i < c; ++i, k /= 4) mode[i] = k % 4;
    for (int i = 0; i < c; ++i) {
      if (mode[i] == 0) {  // open: P_N = P_T = 0
        K(i, i) = 1;
        K(c + i, c + i) = 1;
      } else {
        K.row(i) = G.row(i);  // D_NE + e D_NA = 0
        b(i) = -q(i);
        if (mode[i] == 1) {
          K.row(c + i) = G.row(c + i);  // D_TE = 0
          b(c + i) = -q(c + i);
        } else {  // P_T = −σ μ P_N
          const double sigma = mode[i] == 2 ? 1 : -1;
          K(c + i, c + i) = 1;
          K(c + i, i) = sigma * mu;
        }
      }
    }
    const VectorX P = K.fullPivLu().solve(b);
    const VectorX D = G * P + q;
    bool ok = true;
    for (int i = 0; i < c && ok; ++i) {
      if (mode[i] == 0)
        ok = D(i) >= -tol;
      else
        ok = P(i) >= -tol;
      if (mode[i] == 1) ok = ok && std::fabs(P(c + i)) <= mu * P(i) + tol;
      if (mode[i] == 2) ok = ok && D(c + i) > tol;
      if (mode[i] == 3) ok = ok && D(c + i) < -tol;
    }
    if (!ok) continue;
    VectorX DE = G * P + DA;
    bool seen = false;
    for (const auto& v : ref.velocities) seen = seen || (v - DE).cwiseAbs().maxCoeff() < 1e-8;
    if (!seen) ref.velocities.push_back(DE);
  }
  return ref;
}

ImpactProblem random_problem(std::mt19937& rng, int c) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 6;
  MatrixX A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = u(rng);
  ImpactProblem p;
  p.M = A * A.transpose() / n + 0.5 * MatrixX::Identity(n, n);
  p.W_N.resize(n, c);
  p.W_T.resize(n, c);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < c; ++j) {
      p.W_N(i, j) = u(rng);
      p.W_T(i, j) = u(rng);
    }
  p.qdot_A.resize(n);
  for (int i = 0; i < n; ++i) p.qdot_A(i) = u(rng);
  for (int j = 0; j < c; ++j)
    if (p.W_N.col(j).dot(p.qdot_A) > 0) p.W_N.col(j) *= -1;
  return p;
}

VectorX contact_velocities(const ImpactProblem& p, const ImpactResult& r) {
  VectorX D(2 * p.contacts());
  D << r.D_NE, r.D_TE;
  return D;
}

// Two point masses, each on its own obstacle, whose velocities differ by up to 16 orders of
// magnitude (the core issue's range, 1e-10 to 1e6): the first (mass 2) approaches at v with a
// tangential 0.2 v and sticks, the second (mass 0.5) approaches at 1 and slides at D_TA. Decoupled,
// each contact has its one-contact answer by hand, under Newton and Poisson alike (a contact that
// sticks in compression stays stuck; one that slides keeps sliding):
//     stick: P_N = (1 + e) m v, P_T = −0.2 m v;   slide: P_N = (1 + e) m, P_T = −μ P_N sign(D_TA).
// Every percussion to 1e-13 of itself: the small contact is not rounding beside the large one.
TEST(ClassicalCoulomb, ContactsOfVeryDifferentScalesEachGetTheirOwnAnswer) {
  const double e = 0.5, mu = 0.3, m1 = 2.0, m2 = 0.5;
  for (const double v : {1e-10, 1e-6, 1e-3, 1.0})
    for (const double slide : {-1.0, 1e3, 1e6}) {
      ImpactProblem p;
      p.M = VectorX{{m1, m1, m2, m2}}.asDiagonal();
      p.W_N = MatrixX::Zero(4, 2);
      p.W_T = MatrixX::Zero(4, 2);
      p.W_N(0, 0) = p.W_T(1, 0) = p.W_N(2, 1) = p.W_T(3, 1) = 1.0;
      p.qdot_A = VectorX{{-v, 0.2 * v, -1.0, slide}};
      const double expected_PN[] = {(1 + e) * m1 * v, (1 + e) * m2};
      const double expected_PT[] = {-0.2 * m1 * v, -mu * (1 + e) * m2 * (slide > 0 ? 1 : -1)};
      for (const ImpactLaw& law :
           {ImpactLaw::newton_coulomb(e, mu), ImpactLaw::poisson_coulomb(e, mu)}) {
        const ImpactResult r = solve_impact(p, law);
        const std::string what =
            law.describe() + " v = " + std::to_string(v) + " D_TA = " + std::to_string(slide);
        ASSERT_TRUE(r.ok()) << what << ": " << r.solver.message;
        for (int i = 0; i < 2; ++i) {
          EXPECT_NEAR(r.P_N(i), expected_PN[i], 1e-13 * std::fabs(expected_PN[i])) << what;
          EXPECT_NEAR(r.P_T(i), expected_PT[i], 1e-13 * std::fabs(expected_PT[i])) << what;
        }
        EXPECT_TRUE(r.admissibility.admissible) << what;
      }
    }
}

TEST(ClassicalEnumeration, FindsEverySolutionAndAgreesWithLemkeWhenUnique) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> mus(0.0, 4.0);
  int several = 0, single = 0, lemke_checked = 0;
  SolverOptions lemke_only;
  lemke_only.check_uniqueness = false;
  for (int trial = 0; trial < 300; ++trial) {
    const int c = 2 + trial % 2;
    const ImpactProblem p = random_problem(rng, c);
    const double e = 0.5, mu = mus(rng);
    const Reference ref = brute_force_newton_coulomb(p, e, mu);
    const ImpactLaw law = ImpactLaw::newton_coulomb(e, mu);
    const auto all = solve_impact_all(p, law);
    ASSERT_EQ(all.size(), ref.velocities.size()) << "trial " << trial << " mu=" << mu;
    for (const auto& r : all) {
      EXPECT_TRUE(r.ok()) << "trial " << trial;
      EXPECT_LE(r.solver.residual, 1e-12) << "trial " << trial;
      const VectorX D = contact_velocities(p, r);
      bool matched = false;
      for (const auto& v : ref.velocities)
        matched = matched || (v - D).cwiseAbs().maxCoeff() < 1e-9;
      EXPECT_TRUE(matched) << "trial " << trial;
      EXPECT_EQ(r.unique, all.size() == 1) << "trial " << trial;
    }
    several += all.size() > 1;
    if (all.size() == 1) {
      ++single;
      const ImpactResult l = solve_impact(p, law, lemke_only);
      if (l.ok()) {
        ++lemke_checked;
        EXPECT_LE((contact_velocities(p, l) - contact_velocities(p, all[0])).cwiseAbs().maxCoeff(),
                  1e-10)
            << "trial " << trial;
        EXPECT_LE((l.P_T - all[0].P_T).cwiseAbs().maxCoeff(), 1e-10) << "trial " << trial;
      }
    }
  }
  EXPECT_GT(several, 5);  // large μ gives several solutions in part of the sample
  EXPECT_GT(single, 100);
  EXPECT_GT(lemke_checked,
            single * 9 / 10);  // Lemke answers nearly everywhere a solution is unique
}

TEST(ClassicalEnumeration, SmallAndDynamicAgree) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 40; ++trial) {
    const ImpactProblem p = random_problem(rng, 1 + trial % 3);
    for (const ImpactLaw& law :
         {ImpactLaw::newton_coulomb(0.7, 0.6), ImpactLaw::poisson_coulomb(0.7, 0.6)}) {
      const ImpactResult d = solve_impact(p, law);
      const SmallImpactResult s = solve_impact(to_small(p), law);
      ASSERT_EQ(d.solver.status, s.solver.status);
      if (!d.ok()) continue;
      EXPECT_LE((VectorX(s.qdot_E) - d.qdot_E).cwiseAbs().maxCoeff(), 1e-13);
      EXPECT_EQ(d.unique, s.unique);
      EXPECT_EQ(d.solutions_found, s.solutions_found);
    }
  }
}

TEST(ClassicalPoissonCoulomb, RandomAnswersSatisfyTheLaw) {
  std::mt19937 rng(13);
  int ok = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const ImpactProblem p = random_problem(rng, 1 + trial % 3);
    const ImpactLaw law = ImpactLaw::poisson_coulomb(0.8, 0.4);
    for (const auto& r : solve_impact_all(p, law)) {
      EXPECT_TRUE(r.ok()) << "trial " << trial << ": " << r.solver.message;
      EXPECT_LE(law_residual(p, law, r), 1e-12) << "trial " << trial;
      // Pfeiffer & Glocker: Poisson + Coulomb in the plane does not create energy (paper §4.1).
      EXPECT_LE(r.energy_change, 1e-12 * test::kinetic(p, p.qdot_A)) << "trial " << trial;
      ok += r.ok();
    }
  }
  EXPECT_GT(ok, 90);
}

// Velocities within 1e-12 of the velocity scale.
void expect_same_velocities(const ImpactResult& a, const ImpactResult& b, const std::string& what) {
  const double v = std::max(a.D_NA.cwiseAbs().maxCoeff(), a.D_TA.cwiseAbs().maxCoeff());
  EXPECT_LE((a.D_NE - b.D_NE).cwiseAbs().maxCoeff(), 1e-12 * v) << what;
  EXPECT_LE((a.D_TE - b.D_TE).cwiseAbs().maxCoeff(), 1e-12 * v) << what;
}

TEST(ClassicalMethods, EachLcpMethodCanBeForcedAndTheyAgree) {
  // The classical laws are solved by closed forms, Lemke or the enumeration, chosen per phase.
  // Each can be forced where it applies, and gives the automatic answer by its own route (so the
  // closed forms are checked against the LCP through the public entry point).
  const auto forced = [](const ImpactProblem& pb, const ImpactLaw& law, SolverMethod m) {
    SolverOptions o;
    o.method = m;
    return solve_impact(pb, law, o);
  };
  for (const ImpactLaw& law :
       {ImpactLaw::newton(0.9), ImpactLaw::poisson(0.5), ImpactLaw::newton_coulomb(0.9, 1.0),
        ImpactLaw::poisson_coulomb(0.5, 0.3)}) {
    const std::string name(law.name());
    // One contact: closed form (the default), Lemke and the enumeration.
    const ImpactProblem one = bar_first_impact(law.has_friction());
    const ImpactResult automatic = solve_impact(one, law);
    ASSERT_TRUE(automatic.ok()) << name << ": " << automatic.solver.message;
    EXPECT_EQ(automatic.solver.method, SolverMethod::closed_form) << name;
    for (SolverMethod m :
         {SolverMethod::closed_form, SolverMethod::lemke, SolverMethod::mode_enumeration}) {
      const ImpactResult r = forced(one, law, m);
      ASSERT_TRUE(r.ok()) << name << " " << to_string(m) << ": " << r.solver.message;
      EXPECT_EQ(r.solver.method, m) << name;
      expect_same_velocities(r, automatic, name + " one contact " + std::string(to_string(m)));
    }
    // The flat bar, both ends down: Lemke and the enumeration agree. On Poisson + Coulomb the
    // expansion's stick-stick mode is singular and the enumeration projects onto its
    // inequalities: exactly, so its answer meets the law's tolerance too (relaxed by the mode's
    // tolerance, 1e-9 of the velocities, it once stopped that far outside the cone: stalled).
    const ImpactProblem two = flat_bar(Eigen::Vector3d(0.3, -1.0, 0.2), law.has_friction());
    const ImpactResult lemke = forced(two, law, SolverMethod::lemke);
    const ImpactResult modes = forced(two, law, SolverMethod::mode_enumeration);
    ASSERT_TRUE(lemke.ok()) << name << ": " << lemke.solver.message;
    EXPECT_EQ(lemke.solver.method, SolverMethod::lemke) << name;
    EXPECT_EQ(modes.solver.method, SolverMethod::mode_enumeration) << name;
    ASSERT_TRUE(modes.ok()) << name << ": " << modes.solver.message;
    expect_same_velocities(lemke, modes, name + " flat bar");
    // Newton without friction: G is regular and both ends close, so eq. 6's guess is the closed
    // form. With friction the two tangential rows are one (G singular): the guess in its
    // semidefinite form (a line of percussions) holds for Newton + Coulomb, where both ends stick;
    // Poisson's expansion starts from D_C = 0 where the all-closed guess is -e P_C < 0: none with
    // friction; without, both ends open in the expansion (q = e G P_C ≥ 0 here), a mode of the
    // two-contact closed forms (one_of_two_closed).
    const ImpactResult closed = forced(two, law, SolverMethod::closed_form);
    if (law.name() == "poisson_coulomb") {
      EXPECT_EQ(closed.solver.status, SolverStatus::unsupported) << name;
      EXPECT_EQ(closed.qdot_E, two.qdot_A) << name;
    } else {
      ASSERT_TRUE(closed.ok()) << name << ": " << closed.solver.message;
      EXPECT_EQ(closed.solver.method, SolverMethod::closed_form) << name;
      expect_same_velocities(closed, lemke, name + " flat bar closed form");
    }
    EXPECT_EQ(forced(two, law, SolverMethod::trivial).solver.status, SolverStatus::unsupported);
  }
  // Four contacts: the most the enumeration takes; five: beyond it, within Lemke's reach.
  ImpactProblem four;
  four.M = Eigen::Matrix2d::Identity();
  four.W_N.resize(2, 4);
  four.W_N << 0.0, 0.1, -0.1, 0.2, 1.0, 1.0, 1.0, 1.0;
  four.qdot_A = Eigen::Vector2d(0.0, -1.0);
  ImpactProblem five = four;
  five.W_N.resize(2, 5);
  five.W_N << 0.0, 0.1, -0.1, 0.2, 0.3, 1.0, 1.0, 1.0, 1.0, 1.0;
  EXPECT_EQ(forced(five, ImpactLaw::newton(0.5), SolverMethod::mode_enumeration).solver.status,
            SolverStatus::unsupported);
  const ImpactResult r5 = forced(five, ImpactLaw::newton(0.5), SolverMethod::lemke);
  ASSERT_TRUE(r5.ok()) << r5.solver.message;
  EXPECT_NEAR(r5.qdot_E(1), 0.5, 1e-15);
  const ImpactResult e4 = forced(four, ImpactLaw::newton(0.5), SolverMethod::mode_enumeration);
  ASSERT_TRUE(e4.ok()) << e4.solver.message;
  EXPECT_NEAR(e4.qdot_E(1), 0.5, 1e-15);
  const ImpactResult r4 = forced(four, ImpactLaw::newton(0.5), SolverMethod::lemke);
  ASSERT_TRUE(r4.ok()) << r4.solver.message;
  EXPECT_NEAR(r4.qdot_E(1), 0.5, 1e-15);  // eq. 6 on the common normal: the point mass bounces
}

// Bodies in principal axes (diagonal M) under Newton + Coulomb: the solve reports the law's
// residual at its answer's own velocities; law_residual, from the percussions through M, says the
// same within rounding, and both are within the tolerance wherever the solve converged.
TEST(ClassicalMethods, ResidualAtTheAnswersVelocitiesAgreesWithTheData) {
  std::mt19937 rng(20261205);
  std::uniform_real_distribution<double> u(-1.0, 1.0), mass(0.1, 10.0);
  int converged = 0;
  for (int k = 0; k < 400; ++k) {
    ImpactProblem pb = random_problem(rng, 1 + k % 3);
    const int n = pb.dofs();
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) pb.M(i, j) = i == j ? mass(rng) : 0.0;
    const ImpactLaw law = ImpactLaw::newton_coulomb(0.5 * (u(rng) + 1.0), 0.5 * (u(rng) + 1.0));
    const ImpactResult r = solve_impact(pb, law);
    if (!r.ok()) continue;
    ++converged;
    const double data = law_residual(pb, law, r);
    EXPECT_LE(r.solver.residual, 1e-13) << "case " << k;
    EXPECT_LE(data, 1e-13) << "case " << k;
    EXPECT_NEAR(data, r.solver.residual, 1e-14) << "case " << k;
  }
  EXPECT_GE(converged, 300);
}

// How many of `problems` under Newton + Coulomb (e = 0.3, μ = 0.1, 0.5, 2) Lemke answers, and on
// how many of those the automatic chain gives Lemke's velocities. Wherever Lemke answers the chain
// must answer too: the law met to the tolerance by law_residual, no contact penetrating, and
// Lemke's velocities unless the law has several solutions there (Lemke's then meets it as well).
struct AgainstLemke {
  int compared = 0, agreed = 0;
};
void many_contacts_against_lemke(const std::vector<ImpactProblem>& problems, AgainstLemke& count) {
  for (const ImpactProblem& pb : problems) {
    for (const double mu : {0.1, 0.5, 2.0}) {
      const ImpactLaw law = ImpactLaw::newton_coulomb(0.3, mu);
      SolverOptions lemke;
      lemke.method = SolverMethod::lemke;
      const ImpactResult l = solve_impact(pb, law, lemke);
      if (!l.ok()) continue;
      ++count.compared;
      const ImpactResult r = solve_impact(pb, law);
      const std::string what = std::to_string(pb.dofs()) + " dofs, " +
                               std::to_string(pb.contacts()) + " contacts, mu " +
                               std::to_string(mu);
      ASSERT_TRUE(r.ok()) << what << ": " << r.solver.message;
      EXPECT_LE(law_residual(pb, law, r), 1e-13) << what;
      EXPECT_LE(r.admissibility.penetration, 1e-12) << what;
      if ((r.qdot_E - l.qdot_E).cwiseAbs().maxCoeff() <= 1e-10 * l.qdot_E.cwiseAbs().maxCoeff())
        ++count.agreed;
      else
        EXPECT_LE(law_residual(pb, law, l), 1e-13) << what;
    }
  }
}

// Newton + Coulomb on many contacts with more rows than degrees of freedom goes to the sweeps and
// the mode Newton first: on plates of 8 to 32 contacts (G of rank 3) and random bodies of 6 to 14
// dofs on as many contacts, the chain answers wherever Lemke (a second method) does, with its
// velocities but in 2 of 43 cases, where the law has several solutions.
TEST(ClassicalMethods, ManyContactsMeetTheLawAndAgreeWithLemke) {
  std::vector<ImpactProblem> problems;
  for (int c : {8, 16, 32}) problems.push_back(fixtures::plate_many_contacts(c, true));
  for (int n : {8, 11, 14})
    for (int index = 0; index < 4; ++index)
      problems.push_back(fixtures::random_problem_any(n, n, index, true));
  AgainstLemke count;
  many_contacts_against_lemke(problems, count);
  EXPECT_EQ(count.compared, 43);  // Lemke ends on a ray on 2 of the 45
  EXPECT_GE(count.agreed, 41);
}

// With G regular the chain goes to the sweeps from 12 contacts on: on random bodies of 24 to 36
// dofs on half as many contacts (G square and regular), as drawn, with every third contact
// touching (D_NA = 0), with a separating obstacle at every fourth, and with M given a stiff
// direction (cond(M) about 1e9), the same holds: Lemke's velocities but in 3 of 144 cases, where
// the law has several solutions.
TEST(ClassicalMethods, ManyContactsOnARegularGMeetTheLawAndAgreeWithLemke) {
  std::vector<ImpactProblem> problems;
  for (int c : {12, 15, 18})
    for (int index = 0; index < 4; ++index) {
      const ImpactProblem drawn = fixtures::random_problem_any(2 * c, c, index, true);
      problems.push_back(drawn);
      ImpactProblem touching = drawn, obstacle = drawn, stiff = drawn;
      for (int k = 0; k < c; k += 3) touching.w_N(k) = -drawn.W_N.col(k).dot(drawn.qdot_A);
      for (int k = 1; k < c; k += 4) obstacle.w_N(k) = 0.3;
      const Eigen::VectorXd u = Eigen::VectorXd::Ones(2 * c).normalized();
      stiff.M += 1e9 * u * u.transpose();
      problems.insert(problems.end(), {touching, obstacle, stiff});
    }
  AgainstLemke count;
  many_contacts_against_lemke(problems, count);
  EXPECT_EQ(count.compared, 144);
  EXPECT_GE(count.agreed, 141);
}

// Newton's law without friction has one answer in velocities: the sweeps and the mode Newton
// forced on a body of at most half as many degrees of freedom as contacts (they then work on its
// velocities) give Lemke's, on plates of 8 to 32 contacts and random bodies of 6 dofs on 12.
TEST(ClassicalMethods, NsgsOnMoreContactsThanDofsGivesLemkesVelocities) {
  std::vector<ImpactProblem> problems;
  for (int c : {8, 16, 32}) problems.push_back(fixtures::plate_many_contacts(c, false));
  for (int index = 0; index < 4; ++index)
    problems.push_back(fixtures::random_problem_any(6, 12, index, false));
  for (const ImpactProblem& pb : problems) {
    const ImpactLaw law = ImpactLaw::newton(0.4);
    SolverOptions lemke, nsgs;
    lemke.method = SolverMethod::lemke;
    nsgs.method = SolverMethod::nsgs;
    const ImpactResult l = solve_impact(pb, law, lemke);
    const ImpactResult r = solve_impact(pb, law, nsgs);
    const std::string what =
        std::to_string(pb.dofs()) + " dofs, " + std::to_string(pb.contacts()) + " contacts";
    ASSERT_TRUE(l.ok()) << what;
    ASSERT_TRUE(r.ok()) << what << ": " << r.solver.message;
    EXPECT_LE(law_residual(pb, law, r), 1e-12) << what;
    EXPECT_LE((r.qdot_E - l.qdot_E).cwiseAbs().maxCoeff(), 1e-10 * l.qdot_E.cwiseAbs().maxCoeff())
        << what;
  }
}

TEST(ClassicalMethods, AMethodOfFremondsLawIsUnsupported) {
  // An iterative method of Frémond's law is refused in the result, with no percussion, never
  // answered by another method under its name.
  for (const ImpactProblem& pb : {bar_first_impact(), flat_bar(Eigen::Vector3d(0.3, -1.0, 0.2))}) {
    for (const ImpactLaw& law :
         {ImpactLaw::newton_coulomb(0.9, 1.0), ImpactLaw::poisson_coulomb(0.5, 0.3)}) {
      for (SolverMethod m : {SolverMethod::scalar_newton, SolverMethod::semismooth_newton,
                             SolverMethod::proximal, SolverMethod::nlopt}) {
        SolverOptions o;
        o.method = m;
        const ImpactResult r = solve_impact(pb, law, o);
        EXPECT_EQ(r.solver.status, SolverStatus::unsupported) << to_string(m);
        EXPECT_EQ(r.solver.method, m);
        EXPECT_FALSE(r.ok());
        EXPECT_EQ(r.P_N.cwiseAbs().maxCoeff(), 0.0);
        EXPECT_EQ(r.qdot_E, pb.qdot_A);
        const auto all = solve_impact_all(pb, law, o);
        ASSERT_EQ(all.size(), 1u);
        EXPECT_EQ(all[0].solver.status, SolverStatus::unsupported);
      }
    }
  }
}

}  // namespace
}  // namespace fremond
