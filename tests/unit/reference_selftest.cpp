// The quad-precision reference (tests/reference/fremond_reference.hpp) against closed forms:
// Frémond's point mass at p = 2 (docs/laws.md, paper eq. 24 corrected), the reaction of a point
// mass (docs/laws.md's corrected I_reac), Newton's eq. (6); Frémond + Coulomb at p = 2 against its
// piecewise-linear closed forms; and its own consistency: the law's residual in quad precision, and
// the one-contact scalar method against the several-contact velocity-space method on the same
// problems.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "reference/fremond_reference.hpp"

namespace {

namespace ref = fremond_reference;
using ref::quad;

quad q(double x) {
  return static_cast<quad>(x);
}
double d(quad x) {
  return static_cast<double>(x);
}
quad rel(quad a, quad b) {
  return fabsq(a - b) / fmaxq(fmaxq(fabsq(a), fabsq(b)), ldexpq(1, -16000));
}
const quad kTight = q(1e-30);

/// A point mass m in the plane, q = (x, y), ground y = 0: W_N = (0, 1), W_T = (1, 0), G = I/m.
ref::Problem point_mass(quad m, quad xdot, quad ydot, bool tangential = true) {
  ref::Problem p;
  p.M = {{m, 0}, {0, m}};
  p.W_N = {{0, 1}};
  if (tangential) p.W_T = {{1, 0}};
  p.qdot_A = {xdot, ydot};
  return p;
}

/// The paper's bar at θ (the paper's Fig. 1): M = diag(m, m, m l²/3), the lower end's W_N, W_T.
ref::Problem bar(quad theta, quad xdot, quad ydot, quad thetadot) {
  const quad m = 1, l = q(0.5), J = m * l * l / 3;
  ref::Problem p;
  p.M = {{m, 0, 0}, {0, m, 0}, {0, 0, J}};
  p.W_N = {{0, 1, -l * cosq(theta)}};
  p.W_T = {{1, 0, l * sinq(theta)}};
  p.qdot_A = {xdot, ydot, thetadot};
  return p;
}

/// The contact-space data of bar(theta, ...), by hand: G = WᵀM⁻¹W and D_A = Wᵀq̇_A.
struct BarContact {
  quad GNN, GNT, GTT, DNA, DTA;
};
BarContact bar_contact(quad theta, const ref::Problem& p) {
  const quad l = q(0.5), J = l * l / 3;
  return {1 + l * l * cosq(theta) * cosq(theta) / J, -l * l * sinq(theta) * cosq(theta) / J,
          1 + l * l * sinq(theta) * sinq(theta) / J, p.qdot_A[1] - l * cosq(theta) * p.qdot_A[2],
          p.qdot_A[0] + l * sinq(theta) * p.qdot_A[2]};
}

/// SplitMix64, for reproducible random cases.
struct Rng {
  std::uint64_t s;
  double uniform(double lo, double hi) {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return lo + (hi - lo) * static_cast<double>(z >> 11) * 0x1.0p-53;
  }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
};

/// A random problem: n dofs, c contacts, M = B Bᵀ/n + I/2 scaled per dof by up to `mass_ratio`,
/// every contact taking part, velocities of size `speed`.
ref::Problem random_problem(Rng& rng, int n, int c, double speed, double mass_ratio = 1) {
  std::vector<std::vector<double>> B(n, std::vector<double>(n));
  for (auto& row : B)
    for (double& x : row) x = rng.uniform(-1, 1);
  std::vector<double> scale(n);
  for (double& s : scale) s = std::sqrt(rng.log_uniform(1, mass_ratio));
  ref::Problem p;
  p.M.assign(n, ref::QVec(n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double s = i == j ? 0.5 : 0.0;
      for (int k = 0; k < n; ++k) s += B[i][k] * B[j][k] / n;
      p.M[i][j] = q(s * scale[i] * scale[j]);
    }
  p.qdot_A.resize(n);
  for (auto& v : p.qdot_A) v = q(speed * rng.uniform(-1, 1));
  for (int k = 0; k < c; ++k) {
    ref::QVec wn(n), wt(n);
    for (int i = 0; i < n; ++i) {
      wn[i] = q(rng.uniform(-1, 1));
      wt[i] = q(rng.uniform(-1, 1));
    }
    quad dn = 0;
    for (int i = 0; i < n; ++i) dn += wn[i] * p.qdot_A[i];
    if (dn > 0)
      for (auto& x : wn) x = -x;
    p.W_N.push_back(wn);
    p.W_T.push_back(wt);
  }
  return p;
}

// ---------------------------------------------------------------------------------------------
// Closed forms

// docs/laws.md (paper eq. 24 in our scaling): p = 2, one point mass, normal law alone:
// ε = −D_NE/D_NA = (k − 2m)/(k + 2m), for k ≥ 2m (below, the reaction stops the mass: D_NE = 0).
TEST(ReferenceSelfTest, PointMassLinearLawGivesPaperRestitution) {
  for (double m : {1.0, 3.7, 1e3, 1e-3})
    for (double k_over : {1.0, 1.5, 10.0, 1e3, 1e6})
      for (double v : {1e-10, 0.3, 3.5613, 1e6}) {
        const quad mq = q(m), k = q(2 * m * k_over);
        const auto sols = ref::fremond_one_contact(point_mass(mq, 0, -q(v), false), {k, 2},
                                                   ref::TangentialLaw::none());
        ASSERT_EQ(sols.size(), 1u);
        const ref::Solution& s = sols[0];
        const quad eps = (k - 2 * mq) / (k + 2 * mq);
        EXPECT_LT(d(fabsq(-s.D_NE[0] / s.D_NA[0] - eps)), 1e-31) << m << " " << k_over << " " << v;
        // The reaction is zero (at k = 2m, ε = 0, it is zero up to rounding).
        EXPECT_LT(d(fabsq(s.P_reaction[0]) / s.P_N[0]), 1e-31);
        EXPECT_LT(d(s.residual), 1e-31);
      }
}

// docs/laws.md's corrected erratum: with D_NE = 0, I_reac = (m − k_paper|D_NA|^(p−2)) D_NA ≤ 0 with
// k_paper = k 2^(1−p); our reaction percussion is P_reac = −I_reac. k is chosen below the value at
// which the normal law alone would stop the mass, so the reaction acts.
TEST(ReferenceSelfTest, PointMassReactionMatchesCorrectedErratum) {
  for (double p : {1.01, 1.1, 1.5, 2.0, 3.0, 10.0, 50.0})
    for (double m : {1.0, 7.5})
      for (double v : {1e-10, 1e-3, 1.0, 3.5613, 1e6})
        for (double frac : {0.0, 0.25, 0.9}) {
          const quad pq = q(p), mq = q(m), D = -q(v);
          // Largest k with a reaction: m = k 2^(1−p) |D|^(p−2).
          const quad k_max = mq * powq(2, pq - 1) / powq(fabsq(D), pq - 2);
          const quad k = q(frac) * k_max;
          const auto sols =
              ref::fremond_one_contact(point_mass(mq, 1, D), {k, pq}, ref::TangentialLaw::none());
          ASSERT_EQ(sols.size(), 1u);
          const ref::Solution& s = sols[0];
          const quad k_paper = k * powq(2, 1 - pq);
          const quad I_reac = (mq - k_paper * powq(fabsq(D), pq - 2)) * D;
          EXPECT_LE(d(I_reac), 0.0);
          EXPECT_LT(d(rel(s.P_reaction[0], -I_reac)), 1e-31) << p << " " << m << " " << v;
          EXPECT_LT(d(fabsq(s.D_NE[0]) / fabsq(D)), 1e-32);
          EXPECT_LT(d(s.residual), 1e-31);
        }
}

// Newton's eq. (6) on one contact: P_N = −(1 + e) D_NA / G_NN; here on the paper's bar at its first
// impact (G_NN = (1 + 3 cos²θ)/m, the paper's Fig. 1), and q̇_E = q̇_A + M⁻¹ W_N P_N.
TEST(ReferenceSelfTest, NewtonOneContactIsEquationSix) {
  const quad theta = acosq(q(-1)) / 4, vy = -sqrtq(2 * q(9.81) * (1 - q(0.5) * sinq(theta)));
  ref::Problem p = bar(theta, 2, vy, 0);
  p.W_T.clear();
  for (double e : {0.0, 0.5, 0.9, 1.0}) {
    const auto sols = ref::newton_frictionless(p, {q(e)});
    ASSERT_EQ(sols.size(), 1u);
    const quad GNN = (1 + 3 * cosq(theta) * cosq(theta)) / 1;
    const quad PN = -(1 + q(e)) * vy / GNN;
    EXPECT_LT(d(rel(sols[0].P_N[0], PN)), 1e-32);
    EXPECT_LT(d(rel(sols[0].D_NE[0], -q(e) * vy)), 1e-32);
    // ẏ_E = ẏ_A + P_N/m, θ̇_E = −l cos θ P_N / J.
    EXPECT_LT(d(rel(sols[0].qdot_E[1], vy + PN)), 1e-32);
    EXPECT_LT(d(rel(sols[0].qdot_E[2], -q(0.5) * cosq(theta) * PN / (q(0.25) / 3))), 1e-32);
    EXPECT_LT(d(sols[0].residual), 1e-32);
  }
}

// Newton on the flat bar with both ends down (θ = 0): G_NN = [[4, −2], [−2, 4]], so both active
// gives P = G_NN⁻¹ (−(1 + e) D_NA) = ((4 b₁ + 2 b₂)/12, (2 b₁ + 4 b₂)/12) with b = −(1 + e) D_NA.
TEST(ReferenceSelfTest, NewtonFlatBarTwoContacts) {
  ref::Problem p = bar(0, 2, -3, 1);
  p.W_N = {{0, 1, q(0.5)}, {0, 1, -q(0.5)}};
  p.W_T.clear();
  const quad e = q(0.9);
  const auto sols = ref::newton_frictionless(p, {e});
  ASSERT_EQ(sols.size(), 1u);
  const quad b1 = -(1 + e) * (-3 + q(0.5)), b2 = -(1 + e) * (-3 - q(0.5));
  EXPECT_LT(d(rel(sols[0].P_N[0], (4 * b1 + 2 * b2) / 12)), 1e-32);
  EXPECT_LT(d(rel(sols[0].P_N[1], (2 * b1 + 4 * b2) / 12)), 1e-32);
  EXPECT_LT(d(sols[0].residual), 1e-32);
  // A separating contact gets nothing: θ̇ large enough that end 1 moves up.
  p.qdot_A = {0, -1, 5};
  const auto sep = ref::newton_frictionless(p, {e});
  ASSERT_EQ(sep.size(), 1u);
  EXPECT_EQ(sep[0].takes_part[0], 0);
  EXPECT_EQ(d(sep[0].P_N[0]), 0.0);
  EXPECT_LT(d(rel(sep[0].P_N[1], -(1 + e) * (-1 - q(2.5)) / 4)), 1e-32);
}

// Frémond + Coulomb at p = 2 is piecewise linear: every mode is a linear system in (P_N, P_T),
// solved here directly (not through the reference's reduction to z_N), and the reference must find
// exactly the solutions these closed forms find, including Painlevé cases (μ|G_NT| > G_NN: several
// solutions, or none).
struct LinearSolution {
  quad PN, PT;
};

std::vector<LinearSolution> coulomb_p2_closed_forms(quad GNN, quad GNT, quad GTT, quad DNA,
                                                    quad DTA, quad k, quad mu) {
  std::vector<LinearSolution> out;
  auto keep = [&](quad PN, quad PT, bool reaction) {
    const quad DNE = DNA + GNN * PN + GNT * PT, zN = (DNA + DNE) / 2;
    const quad zT = DTA + (GNT * PN + GTT * PT) / 2;
    const quad tol = q(1e-28) * (fabsq(DNA) + fabsq(DTA));
    if (reaction && !(PN + k * zN >= -tol)) return;
    if (!reaction && !(DNE >= -tol)) return;
    if (!(fabsq(PT) <= mu * fabsq(PN) + tol)) return;
    if (fabsq(PT) < mu * fabsq(PN) - tol && fabsq(zT) > tol) return;  // inside: must stick
    if (fabsq(zT) > tol && !(PT * zT <= 0)) return;                   // slides against
    for (const auto& s : out)
      if (fabsq(s.PN - PN) + fabsq(s.PT - PT) <= q(1e-25) * (fabsq(PN) + fabsq(PT) + 1)) return;
    out.push_back({PN, PT});
  };
  auto solve2 = [](quad a, quad b, quad c, quad dd, quad r1, quad r2, quad& x, quad& y) {
    const quad det = a * dd - b * c;
    if (det == 0) return false;
    x = (r1 * dd - b * r2) / det;
    y = (a * r2 - c * r1) / det;
    return true;
  };
  quad PN, PT;
  // Stick (z_T = 0: G_NT P_N + G_TT P_T = −2 D_TA), free (P_N = −k z_N) or reaction (D_NE = 0).
  if (solve2(1 + k * GNN / 2, k * GNT / 2, GNT, GTT, -k * DNA, -2 * DTA, PN, PT))
    keep(PN, PT, false);
  if (solve2(GNN, GNT, GNT, GTT, -DNA, -2 * DTA, PN, PT)) keep(PN, PT, true);
  // Slide: P_T = c P_N with c = ±μ.
  for (quad c : {mu, -mu}) {
    const quad alpha = GNN + c * GNT;
    if (1 + k * alpha / 2 != 0)
      keep(-k * DNA / (1 + k * alpha / 2), c * (-k * DNA / (1 + k * alpha / 2)), false);
    if (alpha != 0) keep(-DNA / alpha, c * (-DNA / alpha), true);
  }
  return out;
}

TEST(ReferenceSelfTest, CoulombP2MatchesPiecewiseLinearClosedForms) {
  Rng rng{11};
  int several = 0, none = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const quad theta = q(rng.uniform(0.05, 1.5));
    ref::Problem p =
        bar(theta, q(rng.uniform(-4, 4)), -q(rng.uniform(0.1, 4)), q(rng.uniform(-3, 3)));
    const quad k = q(rng.log_uniform(0.01, 100));
    const quad mu = q(rng.log_uniform(0.05, 20));  // well past Painlevé's μ|G_NT| = G_NN sometimes
    const auto sols = ref::fremond_one_contact(p, {k, 2}, ref::TangentialLaw::coulomb(mu));
    const auto [GNN, GNT, GTT, DNA, DTA] = bar_contact(theta, p);
    if (DNA > 0) continue;
    const auto expected = coulomb_p2_closed_forms(GNN, GNT, GTT, DNA, DTA, k, mu);
    ASSERT_EQ(sols.size(), expected.size()) << "trial " << trial << " mu " << d(mu);
    for (const auto& s : sols) {
      EXPECT_LT(d(s.residual), 1e-30) << s.mode;
      bool match = false;
      for (const auto& e : expected)
        match = match || (rel(s.P_N[0], e.PN) < q(1e-28) &&
                          fabsq(s.P_T[0] - e.PT) <= q(1e-28) * (fabsq(e.PT) + fabsq(e.PN)));
      EXPECT_TRUE(match) << "trial " << trial << " " << s.mode;
    }
    several += sols.size() > 1;
    none += sols.empty();
  }
  // The random draws do reach the Painlevé cases. (None of them has no solution: with the
  // two-sided power law the number of solutions found is odd, 1 or 3, in every draw tried.)
  EXPECT_GT(several, 0);
  EXPECT_EQ(none, 0);
}

// The paper's bar at μ = 1 is below Painlevé's condition (μ|G_NT| = 1.5 < G_NN = 2.5): one
// solution, for every p of the cross-check list.
TEST(ReferenceSelfTest, CoulombPaperBarHasOneSolution) {
  const quad theta = acosq(q(-1)) / 4, vy = -sqrtq(2 * q(9.81) * (1 - q(0.5) * sinq(theta)));
  for (double p : {1.01, 1.1, 1.5, 2.0, 3.0, 10.0, 50.0}) {
    // k_N of docs/laws.md: the normal law alone gives restitution 0.9 at this impact.
    const quad pq = q(p), e = q(0.9);
    const quad k = (1 + e) / (q(2.5) * powq((1 - e) / 2, pq - 1) * powq(fabsq(vy), pq - 2));
    const auto normal_only =
        ref::fremond_one_contact(bar(theta, 2, vy, 0), {k, pq}, ref::TangentialLaw::none());
    ASSERT_EQ(normal_only.size(), 1u);
    EXPECT_LT(d(rel(-normal_only[0].D_NE[0] / normal_only[0].D_NA[0], e)), 1e-31);
    const auto sols =
        ref::fremond_one_contact(bar(theta, 2, vy, 0), {k, pq}, ref::TangentialLaw::coulomb(1));
    ASSERT_EQ(sols.size(), 1u) << p;
    EXPECT_LT(d(sols[0].residual), 1e-31) << p;
  }
}

TEST(ReferenceSelfTest, CoulombStickWithSingularDelassusIsFound) {
  // One degree of freedom: W_N = a, W_T = b, so G = [a² ab; ab b²]/m is singular and the stick
  // mode z_T = 0 fixes q̇_E (stress fremond_coulomb #83520 of seed 7, which the reference missed
  // while the library found it). Reference values: the same formulas on the same doubles in
  // 60-digit decimal arithmetic (q̇_E from z_T = 0, P_N = −k z_N|z_N|^(p−2), P_T from the momentum
  // balance m(q̇_E − q̇_A) = a P_N + b P_T), |P_T| = 0.0028 μ|P_N|: inside the cone.
  ref::Problem pb;
  pb.M = {{q(0.0028379215886040884)}};
  pb.W_N = {{q(0.42917416608492132)}};
  pb.W_T = {{q(-0.65327746418471921)}};
  pb.w_N = {q(-4455216.1252557226)};
  pb.w_T = {q(15788121.301822092)};
  pb.qdot_A = {q(-18298939.238373473)};
  const auto sols = ref::fremond_one_contact(pb, {q(43.708842614189592), q(3.054328906495555)},
                                             ref::TangentialLaw::coulomb(q(235.7948076084015)));
  ASSERT_EQ(sols.size(), 3u);  // the stick and two slides with P_N of either sign
  const ref::Solution* stick = nullptr;
  for (const auto& s : sols)
    if (s.mode.find("stick") != std::string::npos) stick = &s;
  ASSERT_NE(stick, nullptr);
  EXPECT_LT(d(rel(stick->P_N[0], -strtoflt128("3570052178866716.83537083350183131481", nullptr))),
            1e-28);
  EXPECT_LT(d(rel(stick->P_T[0], -strtoflt128("2345365102863212.70316143691780912242", nullptr))),
            1e-28);
  // D_NE from q̇_A + M⁻¹WP, where the percussions of 3.6e15 cancel to 2e5: 1e10 times quad's ε.
  EXPECT_LT(d(rel(stick->D_NE[0], strtoflt128("24142399.3535064840217217296283299", nullptr))),
            1e-22);
  // Its backward error, by the same cancellation.
  EXPECT_LT(d(stick->residual), 1e-22);
}

TEST(ReferenceSelfTest, RootBelowQuadRangeGivesItsPercussion) {
  // p = 1 + 1e-5: the normal root of a point mass m = 1 hit at v = −1 with k = 4 solves
  // z + (G/2) k|z|^(p−1) sign(z) = D_NA, |z|^(p−1) = 1/2, i.e. |z| = 2^-100000 ≈ 1e-30103: below
  // quad's smallest number (stress fremond_coulomb #65030 of seed 23 met it with p = 1 + 2.7e-6,
  // where the reference missed the solution the library found). In exact arithmetic
  // D_NE = 1 − 2|z| and P_N = m (D_NE − D_NA) = 2 − 2|z|: 1 and 2 to every digit quad has. Before,
  // the root came out as the bracket [−2^-16300, 0] and P_N = k |z|^(p−1) = 3.57 from it.
  const auto sols = ref::fremond_one_contact(point_mass(1, 0, -1), {q(4), 1 + q(1e-5)},
                                             ref::TangentialLaw::none());
  ASSERT_EQ(sols.size(), 1u);
  EXPECT_LT(d(rel(sols[0].P_N[0], q(2))), 1e-32);
  EXPECT_LT(d(rel(sols[0].D_NE[0], q(1))), 1e-32);
  EXPECT_LT(d(sols[0].residual), 1e-32);
}

// ---------------------------------------------------------------------------------------------
// Internal consistency over the ranges the cross-checks use.

TEST(ReferenceSelfTest, OneContactResidualsAreQuadSmall) {
  Rng rng{2024};
  const double ps[] = {1.01, 1.1, 1.5, 2.0, 3.0, 10.0, 50.0};
  for (int trial = 0; trial < 150; ++trial) {
    const int n = 2 + trial % 5;
    const double speed = rng.log_uniform(1e-10, 1e6);
    ref::Problem p = random_problem(rng, n, 1, speed, trial % 3 == 0 ? 1e6 : 1.0);
    const quad pq = q(ps[trial % 7]);
    const quad k = q(rng.log_uniform(1e-6, 1e6));
    const double qexp = rng.uniform(1.01, 3);
    const double r = trial % 4 == 0 ? 0.0 : (trial % 4 == 1 ? 10 * speed : rng.uniform(0, speed));
    const ref::TangentialLaw laws[] = {
        ref::TangentialLaw::none(),
        ref::TangentialLaw::dead_zone(q(rng.log_uniform(1e-6, 1e6)), q(qexp), q(r)),
        ref::TangentialLaw::coulomb(q(rng.uniform(0, 2)))};
    for (const auto& law : laws) {
      const auto sols = ref::fremond_one_contact(p, {k, pq}, law);
      if (law.kind != ref::TangentialKind::coulomb) {
        ASSERT_EQ(sols.size(), 1u);
      }
      // Ill-conditioned M (ratios 1e6) costs its condition number in the last digits.
      const double bound = trial % 3 == 0 ? 1e-26 : 1e-30;
      for (const auto& s : sols)
        EXPECT_LT(d(s.residual), bound) << "trial " << trial << " p " << d(pq) << " " << s.mode;
    }
  }
}

// Two independent methods of the reference on the same one-contact problems: the scalar reduction
// (fremond_one_contact: nested monotone root finding) and the contact-space system
// (fremond_several: Gauss-Seidel then Levenberg-Marquardt on the resolvents) agree to nearly quad
// precision.
TEST(ReferenceSelfTest, ScalarReductionAgreesWithContactSpaceSolver) {
  Rng rng{7};
  const double ps[] = {1.01, 1.1, 1.5, 2.0, 3.0, 10.0, 50.0};
  for (int trial = 0; trial < 70; ++trial) {
    const double speed = rng.log_uniform(1e-10, 1e6);
    ref::Problem p = random_problem(rng, 3, 1, speed);
    const quad pq = q(ps[trial % 7]);
    const quad k = q(rng.log_uniform(1e-6, 1e6));
    const double r = trial % 3 == 0 ? 0.0 : (trial % 3 == 1 ? 10 * speed : rng.uniform(0, speed));
    const auto law =
        ref::TangentialLaw::dead_zone(q(rng.log_uniform(1e-6, 1e6)), q(rng.uniform(1.01, 3)), q(r));
    const auto one = ref::fremond_one_contact(p, {k, pq}, law);
    const auto sev = ref::fremond_several(p, {{k, pq}}, {law});
    ASSERT_EQ(one.size(), 1u);
    ASSERT_TRUE(sev.ok) << "trial " << trial;
    const quad vs = fmaxq(fabsq(one[0].D_NA[0]), fabsq(one[0].D_TA[0]));
    EXPECT_LT(d(fabsq(one[0].D_NE[0] - sev.D_NE[0]) / vs), 1e-28) << "trial " << trial;
    EXPECT_LT(d(fabsq(one[0].D_TE[0] - sev.D_TE[0]) / vs), 1e-28) << "trial " << trial;
  }
}

TEST(ReferenceSelfTest, SeveralContactsResidualsAreQuadSmall) {
  Rng rng{99};
  const double ps[] = {1.01, 1.1, 1.5, 2.0, 3.0, 10.0, 50.0};
  for (int trial = 0; trial < 40; ++trial) {
    // Up to 4 contacts on 6 dofs: 8 rows, so G is singular when the dead zone is on.
    const int c = 2 + trial % 3;
    const double speed = rng.log_uniform(1e-10, 1e6);
    const bool stiff_mass = trial % 5 == 4;
    ref::Problem p = random_problem(rng, 6, c, speed, stiff_mass ? 1e6 : 1.0);
    std::vector<ref::PowerLaw> normal;
    std::vector<ref::TangentialLaw> tangential;
    for (int i = 0; i < c; ++i) {
      normal.push_back({q(rng.log_uniform(1e-6, 1e6)), q(ps[(trial + i) % 7])});
      const double r = trial % 6 == 1 ? 10 * speed : (trial % 6 == 3 ? 0.0 : rng.uniform(0, speed));
      tangential.push_back(trial % 2
                               ? ref::TangentialLaw::none()
                               : ref::TangentialLaw::dead_zone(q(rng.log_uniform(1e-6, 1e6)),
                                                               q(rng.uniform(1.01, 3)), q(r)));
    }
    const ref::Solution s = ref::fremond_several(p, normal, tangential);
    EXPECT_TRUE(s.ok) << "trial " << trial;
    EXPECT_LT(d(s.residual), stiff_mass ? 1e-26 : 1e-30) << "trial " << trial << " " << s.mode;
  }
}

// ---------------------------------------------------------------------------------------------
// The classical laws by their contact modes (classical_modes)

// Without friction the modes are newton_frictionless's active sets: the same solutions, on random
// bodies with two to four contacts on six dofs (G_NN regular).
TEST(ReferenceSelfTest, ClassicalModesFrictionlessAreNewtonsActiveSets) {
  Rng rng{5};
  for (int trial = 0; trial < 60; ++trial) {
    const int c = 2 + trial % 3;
    ref::Problem p = random_problem(rng, 6, c, rng.log_uniform(1e-3, 1e3), trial % 4 ? 1 : 1e6);
    p.W_T.clear();
    const ref::QVec e{q(rng.uniform(0, 1))};
    const auto lcp = ref::newton_frictionless(p, e);
    const auto modes = ref::classical_modes(p, ref::ClassicalLaw::newton, e, {});
    ASSERT_TRUE(modes.complete) << trial;
    ASSERT_EQ(modes.solutions.size(), lcp.size()) << trial;
    for (std::size_t k = 0; k < lcp.size(); ++k) {
      EXPECT_LT(d(modes.solutions[k].residual), 1e-28) << trial;
      bool match = false;
      for (const auto& s : lcp) {
        quad diff = 0, size = 0;
        for (int i = 0; i < c; ++i) {
          diff = fmaxq(diff, fabsq(s.P_N[i] - modes.solutions[k].P_N[i]));
          size = fmaxq(size, fabsq(s.P_N[i]));
        }
        match = match || diff <= q(1e-28) * size;
      }
      EXPECT_TRUE(match) << trial;
    }
  }
}

// One contact with Coulomb, by hand: closed, then stick (G P = −((1 + e) D_NA, D_TA), inside the
// cone) or slide with v_T of sign s (P_T = −sμP_N, P_N = −(1 + e) D_NA/(G_NN − sμG_NT), v_T
// of sign s), each a 2×2 or scalar equation solved here by Cramer's rule. Poisson's compression is
// the same with e = 0, and on one contact its expansion adds P_NE = e P_NC in the compression's
// direction only where the contact sticks or slides on: checked through the residual. The paper's
// bar with random velocities and μ past Painlevé's condition (a slide mode whose α = G_NN − sμG_NT
// is negative, so that its P_N would be negative).
TEST(ReferenceSelfTest, ClassicalModesOneContactCoulombByHand) {
  Rng rng{17};
  int painleve = 0, sticks = 0, slides = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const quad theta = q(rng.uniform(0.05, 1.5));
    const ref::Problem p =
        bar(theta, q(rng.uniform(-4, 4)), -q(rng.uniform(0.1, 4)), q(rng.uniform(-3, 3)));
    const quad mu = q(rng.log_uniform(0.05, 20)), e = q(rng.uniform(0, 1));
    const auto [GNN, GNT, GTT, DNA, DTA] = bar_contact(theta, p);
    if (DNA > 0) continue;
    std::vector<LinearSolution> expected;
    const quad tol = q(1e-28) * (fabsq(DNA) + fabsq(DTA));
    const quad b = -(1 + e) * DNA;
    // Open: P = 0 where D_NA + e D_NA ≥ 0, i.e. never here (D_NA < 0).
    const quad det = GNN * GTT - GNT * GNT;
    const quad PN_st = (b * GTT + GNT * DTA) / det, PT_st = (-GNN * DTA - GNT * b) / det;
    if (PN_st >= -tol && fabsq(PT_st) <= mu * PN_st + tol) expected.push_back({PN_st, PT_st});
    for (quad sgn : {q(1), q(-1)}) {
      const quad alpha = GNN - sgn * mu * GNT;
      painleve += alpha < 0;
      if (alpha == 0) continue;
      const quad PN = b / alpha, PT = -sgn * mu * PN;
      const quad vT = DTA + GNT * PN + GTT * PT;
      if (PN >= -tol && sgn * vT >= -tol) expected.push_back({PN, PT});
    }
    const auto found = ref::classical_modes(p, ref::ClassicalLaw::newton, {e}, {mu});
    ASSERT_TRUE(found.complete);
    // A stick answer on the cone's edge is also a slide answer: count distinct ones.
    std::vector<LinearSolution> distinct;
    for (const auto& x : expected) {
      bool seen = false;
      for (const auto& y : distinct)
        seen = seen || (rel(x.PN, y.PN) < q(1e-25) && fabsq(x.PT - y.PT) <= q(1e-25) * x.PN);
      if (!seen) distinct.push_back(x);
    }
    ASSERT_EQ(found.solutions.size(), distinct.size()) << "trial " << trial << " mu " << d(mu);
    for (const auto& s : found.solutions) {
      EXPECT_LT(d(s.residual), 1e-30) << trial;
      bool match = false;
      for (const auto& x : distinct)
        match =
            match || (rel(s.P_N[0], x.PN) < q(1e-28) && fabsq(s.P_T[0] - x.PT) <= q(1e-28) * x.PN);
      EXPECT_TRUE(match) << trial;
      const quad zT = s.D_TE[0];
      (fabsq(zT) <= tol ? sticks : slides) += 1;
    }
    // Poisson: the compression is Newton's phase with e = 0; every answer satisfies both phases.
    const auto poisson = ref::classical_modes(p, ref::ClassicalLaw::poisson, {e}, {mu});
    ASSERT_TRUE(poisson.complete);
    const auto compression = ref::classical_modes(p, ref::ClassicalLaw::newton, {q(0)}, {mu});
    for (const auto& s : poisson.solutions) {
      EXPECT_LT(d(s.residual), 1e-30) << trial;
      bool match = false;
      for (const auto& c : compression.solutions)
        match = match || (rel(s.P_NC[0], c.P_N[0]) < q(1e-28) &&
                          fabsq(s.P_TC[0] - c.P_T[0]) <= q(1e-28) * c.P_N[0]);
      EXPECT_TRUE(match) << trial;
    }
  }
  EXPECT_GT(sticks, 0);
  EXPECT_GT(slides, 0);
  EXPECT_GT(painleve, 0);  // μ|G_NT| > G_NN is reached: a slide mode with α < 0
}

// The linear program that decides a singular mode: small polyhedra whose emptiness is known by
// hand, among them singular equations (consistent or not) and a degenerate vertex.
TEST(ReferenceSelfTest, PolyhedronTestOnHandCases) {
  using ref::detail::Mat;
  using ref::detail::polyhedron_nonempty;
  auto mat = [](int r, int c, std::vector<double> v) {
    Mat m(r, c);
    for (int i = 0; i < r * c; ++i) m.a[static_cast<std::size_t>(i)] = q(v[i]);
    return m;
  };
  const Mat none(0, 2);
  // u1 + u2 = 1 with u ≥ 0: the segment; with u1 ≥ 2 as well: empty.
  ref::QVec point;
  EXPECT_TRUE(polyhedron_nonempty(mat(1, 2, {1, 1}), {1}, mat(2, 2, {1, 0, 0, 1}), {0, 0}, &point));
  EXPECT_LT(d(fabsq(point[0] + point[1] - 1)), 1e-30);
  EXPECT_GE(d(point[0]), -1e-30);
  EXPECT_GE(d(point[1]), -1e-30);
  EXPECT_FALSE(polyhedron_nonempty(mat(1, 2, {1, 1}), {1}, mat(2, 2, {1, 0, 0, 1}), {2, 0}));
  // Singular equations: [1 1; 2 2] u = (1, 2) is a line, (1, 3) is nothing.
  EXPECT_TRUE(polyhedron_nonempty(mat(2, 2, {1, 1, 2, 2}), {1, 2}, mat(0, 2, {}), {}));
  EXPECT_FALSE(polyhedron_nonempty(mat(2, 2, {1, 1, 2, 2}), {1, 3}, mat(0, 2, {}), {}));
  // Free variables: u1 − u2 = −5 needs u1 ≤ −4 when u2 ≤ 1; u1 ≥ −3 then makes it empty.
  EXPECT_TRUE(polyhedron_nonempty(mat(1, 2, {1, -1}), {-5}, mat(1, 2, {0, -1}), {-1}, &point));
  EXPECT_LT(d(fabsq(point[0] - point[1] + 5)), 1e-30);
  EXPECT_FALSE(polyhedron_nonempty(mat(1, 2, {1, -1}), {-5}, mat(2, 2, {0, -1, 1, 0}), {-1, -3}));
  // A degenerate vertex (three constraints through the origin of the plane) and only inequalities.
  EXPECT_TRUE(polyhedron_nonempty(none, {}, mat(3, 2, {1, 0, 0, 1, -1, -1}), {0, 0, 0}));
  EXPECT_FALSE(polyhedron_nonempty(none, {}, mat(3, 2, {1, 0, 0, 1, -1, -1}), {0, 0, 1e-20}));
}

// A vertex the linear program must reach through small pivots: Newton + Coulomb with μ = 1e8 on
// a 6-dof body, one contact sliding on P_N = 1.4e-4 (P_T = −1.4e4) and two sticking with P_N = 9e5.
// That mode's equations are regular (pivot 1e-13 of the largest, below the enumeration's 2^-40)
// and their solution meets every inequality with slack; the program took pivots down to 2^-100 of
// their column, its tableau drifted by 1e-7, and it called the polyhedron empty (stress
// newton_coulomb #71778 of seed 23, where the library converged to this answer).
TEST(ReferenceSelfTest, PolyhedronOfALargeMuModeIsNotCalledEmpty) {
  ref::Problem p;
  const std::vector<std::vector<double>> M = {
      {20207.647852902795, 4476.76026298953, -8635.288987136848, 11273.252680417767,
       -6666.899668494869, -16059.82195132682},
      {4476.76026298953, 16239.584443813588, -4712.341293945614, 6523.470026066114,
       12124.996981811806, 6501.445701506309},
      {-8635.288987136848, -4712.341293945614, 22516.90994111805, 8320.024164039143,
       -7370.898401106853, 7970.334002043254},
      {11273.252680417767, 6523.470026066114, 8320.024164039143, 35744.059577807624,
       -7404.926000112, -4726.123086907719},
      {-6666.899668494869, 12124.996981811806, -7370.898401106853, -7404.926000112,
       18864.610367508245, 13052.44118582522},
      {-16059.82195132682, 6501.445701506309, 7970.334002043254, -4726.123086907719,
       13052.44118582522, 19941.41729495258}};
  const std::vector<std::vector<double>> WN = {
      {0.36607877291921276, 0.42912183067063236, -0.5723548366901124, 0.9700378813078021,
       0.5516982625467963, 0.1518916587436545},
      {0.36208355822411065, -0.5952285698667076, 0.3180921492047175, -0.3863270979068436,
       -0.4137919560365927, 0.07738920477518607},
      {-0.2626856090612867, -0.7675126253330109, 0.7098818280220835, 0.9190663856768115,
       0.8076748180590485, -0.030400547811632928},
      {-0.30168189972293524, 0.7386436050633218, 0.017071781389445206, 0.3382465605346807,
       -0.5189847597244597, 0.469497073983975}};
  const std::vector<std::vector<double>> WT = {
      {0.8036903217681908, -0.8459385843781588, 0.7577624815635196, 0.23705128949866938,
       -0.6636567998848781, 0.6258504437418335},
      {0.06060197772740805, -0.21234018210898387, 0.23069921703285146, 0.15090230128993198,
       0.7750838774430941, 0.3073785635632085},
      {0.5492718989457601, 0.18182092966095853, 0.7886605132149485, -0.7108867022386862,
       0.6628519518748806, -0.4997706263551268},
      {-0.291971226837625, -0.5516842844606827, 0.5531650981067704, 0.42720031981551343,
       0.49001426620953814, -0.422674512388198}};
  const std::vector<double> qdot = {26.29870859982304, -18.858740677581924, -7.182814030552544,
                                    -6.28822195987506, -24.34249009411725,  -8.503008507687639};
  for (const auto& row : M) {
    p.M.emplace_back();
    for (double x : row) p.M.back().push_back(q(x));
  }
  for (const auto& col : WN) {
    p.W_N.emplace_back();
    for (double x : col) p.W_N.back().push_back(q(x));
  }
  for (const auto& col : WT) {
    p.W_T.emplace_back();
    for (double x : col) p.W_T.back().push_back(q(x));
  }
  for (double x : qdot) p.qdot_A.push_back(q(x));
  const std::vector<double> e = {0, 0.6363607249753587, 0.1464428238255093, 0.19037491255952424};
  ref::QVec eq;
  for (double x : e) eq.push_back(q(x));
  const auto found = ref::classical_modes(p, ref::ClassicalLaw::newton, eq, {q(1e8)});
  EXPECT_FALSE(found.complete);
  EXPECT_TRUE(found.exists);
  ASSERT_FALSE(found.singular_example.empty());
  EXPECT_LT(d(found.singular_example[0].residual), 1e-20);
  // The answer: contact 0 slides on P_N = 1.4127585787e-4, contacts 2 and 3 stick.
  bool seen = false;
  for (const auto& s : found.singular_example)
    seen = seen || d(rel(s.P_N[0], q(1.4127585787287515e-4))) < 1e-9;
  EXPECT_TRUE(seen);
}

// A contact listed twice makes every mode that closes both singular (its W_N twice in G), and such
// a problem has a solution exactly when the contacts without the copy have one (the two
// percussions add up to the single one, and so do Coulomb's cones). Random bodies with two
// contacts under Newton + Coulomb, μ up to 20 (where some have no solution): existence with the
// copy, decided by the linear programs of its singular modes, against the regular enumeration
// without it.
TEST(ReferenceSelfTest, SingularModesAreDecidedByTheirPolyhedra) {
  Rng rng{29};
  int with = 0, without = 0;
  for (int trial = 0; trial < 600 && (with < 40 || without < 8); ++trial) {
    const ref::Problem p = random_problem(rng, 2 + trial % 3, 2, 1.0);
    const ref::QVec e{q(rng.uniform(0, 1))}, mu{q(rng.log_uniform(0.1, 20))};
    const auto two = ref::classical_modes(p, ref::ClassicalLaw::newton, e, mu);
    if (!two.complete) continue;  // G singular already (2 dofs, one contact a copy of the other)
    ref::Problem copy = p;
    copy.W_N.push_back(p.W_N[0]);
    copy.W_T.push_back(p.W_T[0]);
    const auto three = ref::classical_modes(copy, ref::ClassicalLaw::newton, e, mu);
    if (three.complete) continue;  // the copied contact does not take part
    ASSERT_TRUE(three.existence_known) << trial;
    EXPECT_EQ(three.exists, !two.solutions.empty()) << "trial " << trial << " mu " << d(mu[0]);
    (two.solutions.empty() ? without : with) += 1;
  }
  EXPECT_GE(with, 40);
  // None of these has no solution (nor any of the stress's regular problems under Newton +
  // Coulomb); the empty case is the next test's.
  EXPECT_EQ(without, 0);
}

// A point mass between a floor and a ceiling that both approach it (w_N = −1 each: normals (0, 1)
// and (0, −1)): D_NE,1 + D_NE,2 = −2 whatever the percussions, so both cannot separate and Newton's
// law has no solution, with or without friction. The mode closing both is singular (G of rank
// one) and its polyhedron is empty; the others are regular and have no answer.
TEST(ReferenceSelfTest, SingularModeOfASqueezeHasNoAnswer) {
  ref::Problem p = point_mass(1, q(0.3), 0);
  p.W_N = {{0, 1}, {0, -1}};
  p.W_T = {{1, 0}, {1, 0}};
  p.w_N = {-1, -1};
  for (const ref::QVec& mu : {ref::QVec{}, ref::QVec{q(0.5)}}) {
    const auto found = ref::classical_modes(p, ref::ClassicalLaw::newton, {q(0.5)}, mu);
    EXPECT_FALSE(found.complete);
    EXPECT_TRUE(found.existence_known);
    EXPECT_FALSE(found.exists);
    EXPECT_TRUE(found.solutions.empty());
  }
  // The ceiling receding instead (w_N,2 = +1): only the floor takes part, and there is a solution.
  p.w_N = {-1, 1};
  const auto some = ref::classical_modes(p, ref::ClassicalLaw::newton, {q(0.5)}, {});
  EXPECT_TRUE(some.exists);
}

// Poisson without friction on one contact is Newton (docs/laws.md): P_N = (1 + e) P_NC with
// P_NC = −D_NA/G_NN; with friction, the residual of both phases is quad-small on random bodies.
TEST(ReferenceSelfTest, ClassicalModesPoissonOnRandomBodies) {
  Rng rng{23};
  for (int trial = 0; trial < 40; ++trial) {
    const int c = 1 + trial % 3;
    ref::Problem p = random_problem(rng, 6, c, rng.log_uniform(1e-3, 1e3));
    const ref::QVec e{q(rng.uniform(0, 1))};
    const ref::QVec mu{q(rng.log_uniform(0.01, 2))};
    const auto sols = ref::classical_modes(p, ref::ClassicalLaw::poisson, e, mu);
    ASSERT_TRUE(sols.complete) << trial;
    for (const auto& s : sols.solutions) EXPECT_LT(d(s.residual), 1e-28) << trial;
    if (c != 1) continue;
    p.W_T.clear();
    const auto plain = ref::classical_modes(p, ref::ClassicalLaw::poisson, e, {});
    const auto newton = ref::newton_frictionless(p, e);
    ASSERT_EQ(plain.solutions.size(), 1u);
    ASSERT_EQ(newton.size(), 1u);
    EXPECT_LT(d(rel(plain.solutions[0].P_N[0], newton[0].P_N[0])), 1e-30) << trial;
    EXPECT_LT(d(rel(plain.solutions[0].P_N[0], (1 + e[0]) * plain.solutions[0].P_NC[0])), 1e-30);
  }
}

// ---------------------------------------------------------------------------------------------
// Frémond + Coulomb near an answer (the check the stress program runs on several contacts)

// On one contact every solution is known (fremond_one_contact): from each, moved by 1e-7 of the
// percussion scale, fremond_coulomb_near comes back to it, whichever of its modes it is in, for
// stiff and soft laws and past Painlevé's condition (several solutions: the nearest is the one).
TEST(ReferenceSelfTest, CoulombNearReturnsToEachOneContactSolution) {
  Rng rng{41};
  int checked = 0, several = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const quad theta = q(rng.uniform(0.05, 1.5));
    const ref::Problem p =
        bar(theta, q(rng.uniform(-4, 4)), -q(rng.uniform(0.1, 4)), q(rng.uniform(-3, 3)));
    if (bar_contact(theta, p).DNA > 0) continue;
    const double pp = trial % 3 == 0 ? 1.2 : (trial % 3 == 1 ? 2.0 : 3.0);
    const ref::PowerLaw normal{q(rng.log_uniform(0.01, 100)), q(pp)};
    const quad mu = q(rng.log_uniform(0.05, 20));
    const auto sols = ref::fremond_one_contact(p, normal, ref::TangentialLaw::coulomb(mu));
    several += sols.size() > 1;
    for (const auto& s : sols) {
      const quad scale = fmaxq(fabsq(s.P_N[0]), fabsq(s.P_T[0]));
      const auto near = ref::fremond_coulomb_near(p, {normal}, {mu}, {s.P_N[0] + 1e-7 * scale},
                                                  {s.P_T[0] - 1e-7 * scale});
      ASSERT_TRUE(near.ok) << "trial " << trial << " " << s.mode;
      EXPECT_LT(d(fabsq(near.P_N[0] - s.P_N[0]) / scale), 1e-28) << trial << " " << s.mode;
      EXPECT_LT(d(fabsq(near.P_T[0] - s.P_T[0]) / scale), 1e-28) << trial << " " << s.mode;
      EXPECT_LT(d(near.residual), 1e-28);
      ++checked;
    }
  }
  EXPECT_GT(checked, 150);
  EXPECT_GT(several, 0);
}

/// The plate on c points (a bar of length 1 and mass 1 lying flat: M = diag(1, 1, 1/12), contact i
/// at x_i = −1/2 + i/(c − 1), W_N,i = (0, 1, x_i), every tangent (1, 0, 0)), sliding.
ref::Problem flat_plate(int c) {
  ref::Problem p;
  p.M = {{1, 0, 0}, {0, 1, 0}, {0, 0, q(1) / 12}};
  for (int i = 0; i < c; ++i) {
    p.W_N.push_back({0, 1, -q(0.5) + q(i) / (c - 1)});
    p.W_T.push_back({1, 0, 0});
  }
  p.qdot_A = {2, -3, 1};
  return p;
}

// The plate on three and four points; its exact answer by other means: the normal rows alone
// (fremond_several; G_NT = 0 here), then every contact sliding at its bound μ|P_N,i| along the
// shared tangent. From near it, fremond_coulomb_near finds it: to quad precision under p = 3. Under
// p = 1.2, k = 1e6, z_N lies near 1e-29, which double precision cannot tell from 0, and the split
// of P_N between the dependent normals rests on the power law's inverse alone: for n in the null
// space of W_N, Σ n_i z_N,i = 0 with z_N,i = −(P_N,i/k)^5. fremond_several leaves that split
// where its residual (7e-29, below its bound of 2^-90) stops resolving it, 30 % off; the
// velocities, which do not see the split, are exact. So under p = 1.2 the check is that condition,
// and the mode's pivot saying the split is not determined by the velocities. From the answer the
// library once returned there (P_N moved along the null space, each P_T at its moved bound: the
// law's test passes in double precision, the velocities are 10 % off), it finds no solution near,
// or the exact one far off.
TEST(ReferenceSelfTest, CoulombNearOnThePlateFindsTheExactSplit) {
  for (const int c : {3, 4})
    for (const double pp : {1.2, 3.0}) {
      SCOPED_TRACE("c = " + std::to_string(c) + ", p = " + std::to_string(pp));
      const ref::Problem p = flat_plate(c);
      const ref::PowerLaw normal{q(1e6), q(pp)};
      const quad mu = q(0.3);
      ref::Problem normal_part = p;
      normal_part.W_T.clear();
      const auto sn = ref::fremond_several(normal_part, {normal}, {ref::TangentialLaw::none()});
      ASSERT_TRUE(sn.ok);
      quad bound = 0;
      for (int i = 0; i < c; ++i) bound += mu * fabsq(sn.P_N[i]);
      ASSERT_LT(bound, 4);  // |2 D_TA / g| = 4 (g = 1): the plate slides, forwards
      ref::QVec PN = sn.P_N, PT(c);
      for (int i = 0; i < c; ++i) PT[i] = -mu * fabsq(PN[i]);
      const quad vx = 2 - bound;  // q̇_E,x: the tangential percussion −bound on a unit mass
      const ref::QVec n = c == 3 ? ref::QVec{1, -2, 1} : ref::QVec{1, -1, -1, 1};
      // From near it (1e-9 of the scale): the exact answer.
      ref::QVec PN1 = PN, PT1 = PT;
      for (int i = 0; i < c; ++i) {
        PN1[i] *= 1 + q(1e-9) * (i + 1);
        PT1[i] *= 1 - q(1e-9) * (i + 1);
      }
      const auto near = ref::fremond_coulomb_near(p, {normal}, {mu}, PN1, PT1);
      ASSERT_TRUE(near.ok);
      EXPECT_LT(d(near.residual), 1e-33);
      for (int k = 0; k < 3; ++k)  // the velocities, to fremond_several's residual
        EXPECT_LT(d(fabsq(near.qdot_E[k] - sn.qdot_E[k] - (k == 0 ? vx - 2 : 0))), 1e-26) << k;
      if (pp == 3.0) {
        for (int i = 0; i < c; ++i) {
          EXPECT_LT(d(rel(near.P_N[i], PN[i])), 1e-25) << i;
          EXPECT_LT(d(rel(near.P_T[i], PT[i])), 1e-25) << i;
        }
        EXPECT_GT(d(near.mode_pivot), 1e-10);
      } else {
        quad split = 0, zmax = 0;
        for (int i = 0; i < c; ++i) {
          const quad z = -powq(near.P_N[i] / normal.k, 1 / (normal.p - 1));
          split += n[i] * z;
          zmax = fmaxq(zmax, fabsq(z));
          EXPECT_LT(d(rel(near.P_T[i], -mu * near.P_N[i])), 1e-30) << i;
        }
        EXPECT_LT(d(fabsq(split) / zmax), 1e-3);
        EXPECT_LT(d(near.mode_pivot), 1e-20);
      }
      // The wrong split: n in null(W_N) (Σ n_i = 0, Σ n_i x_i = 0), large enough to flip signs.
      quad top = 0;
      for (int i = 0; i < c; ++i) top = fmaxq(top, fabsq(PN[i]));
      ref::QVec PN2 = PN, PT2(c);
      for (int i = 0; i < c; ++i) {
        PN2[i] += 1.5 * top * n[i];
        PT2[i] = -mu * fabsq(PN2[i]);
      }
      quad bound2 = 0;
      for (int i = 0; i < c; ++i) bound2 += mu * fabsq(PN2[i]);
      ASSERT_GT(fabsq(bound2 - bound), q(0.1) * bound);  // the velocities see the wrong split
      const auto far = ref::fremond_coulomb_near(p, {normal}, {mu}, PN2, PT2);
      if (far.ok) {
        EXPECT_LT(d(fabsq(far.qdot_E[0] - vx)), 1e-25);
        quad moved = 0;
        for (int i = 0; i < c; ++i) moved = fmaxq(moved, fabsq(far.P_N[i] - PN2[i]));
        EXPECT_GT(d(moved), 0.5 * d(top));
      }
    }
}

}  // namespace
