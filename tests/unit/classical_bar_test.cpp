// The paper's bar at its first impact (the paper's Fig. 1, paper §4.1 and Figs. 5, 7): Newton +
// Coulomb creates kinetic energy and the admissibility report says so; Poisson + Coulomb does not.
// Both against a hand computation from eqs. (7)-(9).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "unit/classical_support.hpp"

namespace fremond {
namespace {

struct Hand {
  double gnn, gnt, gtt, dna, dta;
};

// Eqs. (7)-(8) at θ = π/4 and the velocities just before the first impact.
Hand hand() {
  const double th = std::numbers::pi / 4, c = std::cos(th), s = std::sin(th), m = test::kM;
  Hand h;
  h.gnn = (1 + 3 * c * c) / m;
  h.gnt = -3 * s * c / m;
  h.gtt = (1 + 3 * s * s) / m;
  // The centre falls from y = 1 to y = l sin θ with θ̇ = 0; the lower end's D_N is ẏ.
  h.dna = -std::sqrt(2 * test::kG * (1 - test::kL * s));
  h.dta = 2.0;
  return h;
}

TEST(ClassicalBar, NewtonCoulombCreatesEnergyAsInFigure5) {
  const Hand h = hand();
  const double e = 0.9, mu = 1.0;
  // Newton fixes D_NE = −e D_NA. Sticking (D_TE = 0): G P = (D_NE − D_NA, −D_TA), by Cramer.
  const double det = h.gnn * h.gtt - h.gnt * h.gnt;
  const double bn = -(1 + e) * h.dna, bt = -h.dta;
  const double pn = (bn * h.gtt - h.gnt * bt) / det, pt = (h.gnn * bt - h.gnt * bn) / det;
  ASSERT_GT(pn, 0.0);
  ASSERT_LE(std::fabs(pt), mu * pn);        // the stick mode holds...
  for (const double sigma : {1.0, -1.0}) {  // ...and neither slide does: the answer is unique
    const double x = bn / (h.gnn - sigma * mu * h.gnt);
    ASSERT_LE(sigma * (h.dta + (h.gnt - sigma * mu * h.gtt) * x), 0.0);
  }
  // Eq. (9): T_E − T_A = ½ Pᵀ(D_E + D_A).
  const double gain = 0.5 * pn * (-e * h.dna + h.dna) + 0.5 * pt * (0.0 + h.dta);
  ASSERT_GT(gain, 0.6);  // ≈ 0.668 J: the energy the paper's Fig. 5 shows appearing

  const ImpactProblem p = test::bar_first_impact();
  const ImpactResult r = solve_impact(p, ImpactLaw::newton_coulomb(e, mu));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_NEAR(r.P_N(0), pn, 1e-13);
  EXPECT_NEAR(r.P_T(0), pt, 1e-13);
  EXPECT_NEAR(r.D_TE(0), 0.0, 1e-14);
  EXPECT_NEAR(r.energy_change, gain, 1e-13);
  EXPECT_NEAR(test::kinetic(p, r.qdot_E) - test::kinetic(p, p.qdot_A), gain, 1e-13);
  EXPECT_TRUE(r.unique);
  // The certificate: (15) in sum fails, by −P·z = −gain.
  EXPECT_FALSE(r.admissibility.admissible);
  EXPECT_EQ(r.admissibility.failed, Inequality::total_15);
  EXPECT_NEAR(r.admissibility.violation, -gain, 1e-13);
  EXPECT_NEAR(r.admissibility.total, -gain, 1e-13);
  EXPECT_NEAR(r.admissibility.per_contact(0), -gain, 1e-13);
}

TEST(ClassicalBar, PoissonCoulombDissipatesAsInFigure7) {
  const Hand h = hand();
  const double e = 0.9, mu = 1.0;
  const double det = h.gnn * h.gtt - h.gnt * h.gnt;
  // Compression sticks: G P_C = (−D_NA, −D_TA), so D_NC = D_TC = 0.
  const double pnc = (-h.dna * h.gtt + h.gnt * h.dta) / det;
  const double ptc = (-h.gnn * h.dta + h.gnt * h.dna) / det;
  ASSERT_LE(std::fabs(ptc), mu * pnc);
  // Expansion from rest: P_NE = e P_NC; sticking needs G_TN P_NE + G_TT P_TE = 0.
  const double pne = e * pnc, pte = -h.gnt * pne / h.gtt;
  ASSERT_LE(std::fabs(pte), mu * pne);
  const double dne = h.gnn * pne + h.gnt * pte;  // > 0: no extra ΔP needed
  ASSERT_GT(dne, 0.0);
  const double loss = 0.5 * (pnc + pne) * (h.dna + dne) + 0.5 * (ptc + pte) * (h.dta + 0.0);
  ASSERT_LT(loss, -1.0);  // ≈ −1.13 J

  const ImpactProblem p = test::bar_first_impact();
  const ImpactResult r = solve_impact(p, ImpactLaw::poisson_coulomb(e, mu));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  ASSERT_TRUE(r.has_phases);
  EXPECT_NEAR(r.P_NC(0), pnc, 1e-13);
  EXPECT_NEAR(r.P_TC(0), ptc, 1e-13);
  EXPECT_NEAR(r.D_NC(0), 0.0, 1e-14);
  EXPECT_NEAR(r.D_TC(0), 0.0, 1e-14);
  EXPECT_NEAR(r.P_N(0), pnc + pne, 1e-13);
  EXPECT_NEAR(r.P_T(0), ptc + pte, 1e-13);
  EXPECT_NEAR(r.D_NE(0), dne, 1e-13);
  EXPECT_NEAR(r.energy_change, loss, 1e-13);
  EXPECT_TRUE(r.unique);
  EXPECT_TRUE(r.admissibility.admissible);
  EXPECT_EQ(r.admissibility.failed, Inequality::none);
  EXPECT_NEAR(r.admissibility.total, -loss, 1e-13);
}

TEST(ClassicalBar, NewtonWithoutFrictionConservesWhatEq6Says) {
  // Frictionless Newton on the same impact: D_NE = −e D_NA, and eq. (9) gives
  // T_E − T_A = ½ P_N (1 − e) D_NA < 0 with P_N = −(1 + e) D_NA/G_NN.
  const Hand h = hand();
  const double e = 0.9, pn = -(1 + e) * h.dna / h.gnn;
  const ImpactResult r = solve_impact(test::bar_first_impact(), ImpactLaw::newton(e));
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.energy_change, 0.5 * pn * (1 - e) * h.dna, 1e-13);
  EXPECT_TRUE(r.admissibility.admissible);
}

}  // namespace
}  // namespace fremond
