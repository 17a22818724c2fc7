// Stronge's energetic restitution with Coulomb friction for one contact (docs/stronge.md): every
// regime against a hand derivation, the closed forms where Stronge's law is Newton's, energy and
// momentum on random problems, a numerical Darboux-Keller integration, and the refusals.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "fremond/core/error.hpp"
#include "laws/stronge/darboux_keller.hpp"

namespace fremond::detail {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// A planar rigid body (x, y, θ), mass m, inertia I about its centre, touching the ground y = 0
// at offset r = (rx, ry) from the centre. The contact point moves at (ẋ − θ̇ ry, ẏ + θ̇ rx), so
// w_N = (0, 1, rx), w_T = (1, 0, −ry) and G_NN = 1/m + rx²/I, G_TT = 1/m + ry²/I, G_NT = −rx ry/I.
struct Body {
  MatrixXd M;
  VectorXd w_N, w_T;
};
Body planar_body(double m, double I, double rx, double ry) {
  Body b;
  b.M = Eigen::Vector3d(m, m, I).asDiagonal();
  b.w_N = Eigen::Vector3d(0.0, 1.0, rx);
  b.w_T = Eigen::Vector3d(1.0, 0.0, -ry);
  return b;
}
// m = 1, I = 1, r = (1, −1): G_NN = 2, G_NT = 1, G_TT = 2, det G = 3; stick holds iff μ ≥ 1/2.
Body body_a() {
  return planar_body(1.0, 1.0, 1.0, -1.0);
}
// m = 1, I = 1/4, r = (1, −1): G_NN = 5, G_NT = 4, G_TT = 5, det G = 9; stick holds iff μ ≥ 4/5.
Body body_b() {
  return planar_body(1.0, 0.25, 1.0, -1.0);
}

VectorXd vec3(double a, double b, double c) {
  return Eigen::Vector3d(a, b, c);
}

double kinetic(const MatrixXd& M, const VectorXd& v) {
  return 0.5 * v.dot(M * v);
}

void expect_vec_near(const VectorXd& got, const VectorXd& want, double tol) {
  ASSERT_EQ(got.size(), want.size());
  for (Eigen::Index i = 0; i < got.size(); ++i) EXPECT_NEAR(got(i), want(i), tol) << "entry " << i;
}

constexpr double kTol = 1e-14;

// ---------------------------------------------------------------------------------------------
// 1. Each regime by hand. Notation: slip in direction s has dD_N/dp = a_s = G_NN − μ s G_NT,
// dD_T/dp = b_s = G_NT − μ s G_TT, dp_T/dp = −μ s; stick has dD_N/dp = det G / G_TT and
// dp_T/dp = −G_NT/G_TT. With ω_A = 0: D_NA = ẏ_A, D_TA = ẋ_A.

TEST(StrongeOneContact, SlidesThroughoutByHand) {
  // Body A, μ = 1/4, q̇_A = (1, −7/4, 0), e = 1/2. s = +1: a = 7/4, b = 1/2 > 0 (never sticks).
  // p_Nc = 1, W_c = −7/4·1/2 = −7/8; restitution (7/8) x² = e²·7/8 ⇒ x = 1/2, P_N = 3/2,
  // P_T = −3/8, D_NE = 7/8 = −e D_NA, D_TE = 1 + 3/4 = 7/4.
  // Dissipation: normal (1 − e²)·7/8 = 21/32; tangential μ (1 + 7/4)/2 · 3/2 = 33/64.
  // q̇_E = (1 + P_T, −7/4 + P_N, P_N + P_T) = (5/8, −1/4, 9/8); T_A = 65/32, T_E = 55/64.
  const Body b = body_a();
  const StrongeAnswer r = stronge_one_contact(b.M, b.w_N, b.w_T, vec3(1, -1.75, 0), 0.5, 0.25);
  EXPECT_EQ(r.regime, StrongeRegime::slide);
  EXPECT_NEAR(r.P_N, 1.5, kTol);
  EXPECT_NEAR(r.P_T, -0.375, kTol);
  EXPECT_NEAR(r.D_NE, 0.875, kTol);
  EXPECT_NEAR(r.D_TE, 1.75, kTol);
  EXPECT_NEAR(r.p_N_compression, 1.0, kTol);
  EXPECT_TRUE(std::isnan(r.p_N_transition));
  EXPECT_NEAR(r.work_compression, -0.875, kTol);
  EXPECT_NEAR(r.dissipated_normal, 21.0 / 32, kTol);
  EXPECT_NEAR(r.dissipated_tangential, 33.0 / 64, kTol);
  EXPECT_NEAR(r.energy_change, 55.0 / 64 - 65.0 / 32, kTol);
  expect_vec_near(r.qdot_E, vec3(0.625, -0.25, 1.125), kTol);
}

TEST(StrongeOneContact, SlipsThenSticksDuringCompressionByHand) {
  // Body B, μ = 2, q̇_A = (6, −1, 0). s = +1: a_1 = 5 − 8 = −3 < 0 (D_N falls while slipping),
  // b_1 = 4 − 10 = −6, so D_T = 0 at p_1 = 1 with D_N = −4; stick (4 ≤ 2·5) with slope 9/5 and
  // dp_T/dp = −4/5: p_Nc = 1 + 4·5/9 = 29/9, P_T(p_Nc) = −2 − 16/9 = −34/9.
  // W_c = (−1 − 4)/2·1 + (−4/2)·20/9 = −125/18.
  // e = 0: P = (29/9, −34/9). e = 1: (9/10) x² = 125/18 ⇒ x = 25/9, P_N = 6, P_T = −6,
  // D_NE = 9/5·25/9 = 5 (not Newton's 1), q̇_E = (0, 5, 0); energy lost = μ·(6/2)·1 = 6.
  const Body b = body_b();
  const VectorXd qA = vec3(6, -1, 0);
  const StrongeAnswer plastic = stronge_one_contact(b.M, b.w_N, b.w_T, qA, 0.0, 2.0);
  EXPECT_EQ(plastic.regime, StrongeRegime::slip_stick);
  EXPECT_NEAR(plastic.P_N, 29.0 / 9, kTol);
  EXPECT_NEAR(plastic.P_T, -34.0 / 9, kTol);
  EXPECT_NEAR(plastic.D_NE, 0.0, kTol);
  EXPECT_EQ(plastic.D_TE, 0.0);
  EXPECT_NEAR(plastic.p_N_transition, 1.0, kTol);
  EXPECT_NEAR(plastic.work_compression, -125.0 / 18, 1e-13);

  const StrongeAnswer elastic = stronge_one_contact(b.M, b.w_N, b.w_T, qA, 1.0, 2.0);
  EXPECT_EQ(elastic.regime, StrongeRegime::slip_stick);
  EXPECT_NEAR(elastic.p_N_compression, 29.0 / 9, kTol);
  EXPECT_NEAR(elastic.P_N, 6.0, 1e-13);
  EXPECT_NEAR(elastic.P_T, -6.0, 1e-13);
  EXPECT_NEAR(elastic.D_NE, 5.0, 1e-13);
  EXPECT_EQ(elastic.D_TE, 0.0);
  EXPECT_NEAR(elastic.dissipated_normal, 0.0, kTol);
  EXPECT_NEAR(elastic.dissipated_tangential, 6.0, 1e-13);
  expect_vec_near(elastic.qdot_E, vec3(0, 5, 0), 1e-13);
}

TEST(StrongeOneContact, SlipsThenSticksDuringRestitutionByHand) {
  // Body A, μ = 1, q̇_A = (1, −3/4, 0), e = 1. s = +1: a_1 = 1, b_1 = −1: p_Nc = 3/4 before
  // p_1 = 1, W_c = −(3/4)²/2 = −9/32. Restitution on [3/4, 1] in slip does (1/4)²/2 = 1/32, the
  // other 1/4 in stick (slope 3/2, D_N from 1/4): x/4 + 3x²/4 = 1/4 ⇒ x = (√13 − 1)/6.
  // P_N = 1 + x, P_T = −1 − x/2, D_NE = 1/4 + 3x/2 = √13/4; had it kept slipping, the
  // restitution would have ended at p = 3/2 with D_NE = 3/4 = −e D_NA.
  const Body b = body_a();
  const StrongeAnswer r = stronge_one_contact(b.M, b.w_N, b.w_T, vec3(1, -0.75, 0), 1.0, 1.0);
  const double x = (std::sqrt(13.0) - 1) / 6;
  EXPECT_EQ(r.regime, StrongeRegime::slip_stick);
  EXPECT_NEAR(r.p_N_compression, 0.75, kTol);
  EXPECT_NEAR(r.p_N_transition, 1.0, kTol);
  EXPECT_NEAR(r.P_N, 1 + x, kTol);
  EXPECT_NEAR(r.P_T, -1 - x / 2, kTol);
  EXPECT_NEAR(r.D_NE, std::sqrt(13.0) / 4, kTol);
  EXPECT_EQ(r.D_TE, 0.0);
  expect_vec_near(r.qdot_E, vec3(1 + r.P_T, -0.75 + r.P_N, r.P_N + r.P_T), kTol);
  EXPECT_NEAR(r.dissipated_tangential, 0.5, kTol);  // μ·(1 + 0)/2·1
}

TEST(StrongeOneContact, SlipsThenReversesDuringCompressionByHand) {
  // Body A, μ = 1/4 (< 1/2: no stick), q̇_A = (−3/2, −3, 0), e = 1/2. s = −1: a_1 = 9/4,
  // b_1 = 3/2: p_1 = 1, D_N(1) = −3/4. Reversal s = +1: a_2 = 7/4, b_2 = 1/2, dp_T/dp = −1/4.
  // p_Nc = 1 + 3/7 = 10/7; W_c = (−3 − 3/4)/2 − (3/8)(3/7) = −57/28.
  // (7/8) x² = e²·57/28 ⇒ x = √(57/98). P_N = 10/7 + x, P_T = 1/4 − (P_N − 1)/4,
  // D_TE = (P_N − 1)/2, D_NE = 7x/4.
  const Body b = body_a();
  const StrongeAnswer r = stronge_one_contact(b.M, b.w_N, b.w_T, vec3(-1.5, -3, 0), 0.5, 0.25);
  const double x = std::sqrt(57.0 / 98), P_N = 10.0 / 7 + x;
  EXPECT_EQ(r.regime, StrongeRegime::slip_reversal);
  EXPECT_NEAR(r.p_N_transition, 1.0, kTol);
  EXPECT_NEAR(r.p_N_compression, 10.0 / 7, kTol);
  EXPECT_NEAR(r.work_compression, -57.0 / 28, kTol);
  EXPECT_NEAR(r.P_N, P_N, kTol);
  EXPECT_NEAR(r.P_T, 0.25 - (P_N - 1) / 4, kTol);
  EXPECT_NEAR(r.D_TE, (P_N - 1) / 2, kTol);
  EXPECT_NEAR(r.D_NE, 1.75 * x, kTol);
}

TEST(StrongeOneContact, SlipsThenReversesDuringRestitutionByHand) {
  // Body A, μ = 1/4, q̇_A = (−3/4, −1, 0), e = 1. s = −1: a_1 = 9/4, b_1 = 3/2: p_1 = 1/2 and
  // p_Nc = 4/9 < p_1; W_c = −(1/2)(4/9) = −2/9. Restitution: on [4/9, 1/2] in slip, D_N rises
  // to 1/8 and does 1/288; the remaining 63/288 = 7/32 in reversed slip (a_2 = 7/4):
  // x/8 + 7x²/8 = 7/32 ⇒ 28x² + 4x − 7 = 0 ⇒ x = (5√2 − 1)/14.
  // P_N = 1/2 + x, P_T = 1/8 − x/4, D_TE = x/2, D_NE = 1/8 + 7x/4 = 5√2/8 (Newton: 1).
  const Body b = body_a();
  const StrongeAnswer r = stronge_one_contact(b.M, b.w_N, b.w_T, vec3(-0.75, -1, 0), 1.0, 0.25);
  const double x = (5 * std::sqrt(2.0) - 1) / 14;
  EXPECT_EQ(r.regime, StrongeRegime::slip_reversal);
  EXPECT_NEAR(r.p_N_compression, 4.0 / 9, kTol);
  EXPECT_NEAR(r.p_N_transition, 0.5, kTol);
  EXPECT_NEAR(r.P_N, 0.5 + x, kTol);
  EXPECT_NEAR(r.P_T, 0.125 - x / 4, kTol);
  EXPECT_NEAR(r.D_TE, x / 2, kTol);
  EXPECT_NEAR(r.D_NE, 5 * std::sqrt(2.0) / 8, kTol);
  expect_vec_near(r.qdot_E, vec3(-0.75 + r.P_T, -1 + r.P_N, r.P_N + r.P_T), kTol);
}

TEST(StrongeOneContact, SticksFromRestByHand) {
  // Body A, μ = 1, q̇_A = (0, −3, 0), e = 1/2: D_TA = 0 and 1 ≤ 1·2, stick throughout: slope
  // 3/2, dp_T/dp = −1/2. p_Nc = 2, W_c = −3, (3/4) x² = 3/4 ⇒ x = 1: P = (3, −3/2),
  // q̇_E = (−3/2, 0, 3/2), D_NE = 3/2 = −e D_NA.
  const Body b = body_a();
  const StrongeAnswer r = stronge_one_contact(b.M, b.w_N, b.w_T, vec3(0, -3, 0), 0.5, 1.0);
  EXPECT_EQ(r.regime, StrongeRegime::stick);
  EXPECT_NEAR(r.P_N, 3.0, kTol);
  EXPECT_NEAR(r.P_T, -1.5, kTol);
  EXPECT_NEAR(r.D_NE, 1.5, kTol);
  EXPECT_EQ(r.D_TE, 0.0);
  EXPECT_NEAR(r.dissipated_tangential, 0.0, kTol);
  expect_vec_near(r.qdot_E, vec3(-1.5, 0, 1.5), kTol);
}

TEST(StrongeOneContact, SlidesFromRestByHand) {
  // Body A, μ = 1/4, q̇_A = (0, −7/4, 0), e = 1: D_TA = 0 but 1 > 1/4·2, so it slides the way
  // G_NT > 0 drives D_T: s = +1, a = 7/4, b = 1/2. p_Nc = 1, P_N = 2, P_T = −1/2, D_TE = 1.
  const Body b = body_a();
  const StrongeAnswer r = stronge_one_contact(b.M, b.w_N, b.w_T, vec3(0, -1.75, 0), 1.0, 0.25);
  EXPECT_EQ(r.regime, StrongeRegime::slide);
  EXPECT_NEAR(r.P_N, 2.0, kTol);
  EXPECT_NEAR(r.P_T, -0.5, kTol);
  EXPECT_NEAR(r.D_TE, 1.0, kTol);
  EXPECT_NEAR(r.D_NE, 1.75, kTol);
  EXPECT_NEAR(r.dissipated_tangential, 0.25 * 0.5 * 1.0 * 2.0, kTol);  // μ·(0 + 1)/2·2
}

TEST(StrongeOneContact, NoImpactWhenNotApproaching) {
  const Body b = body_a();
  for (const double vy : {0.0, 0.5}) {
    const VectorXd qA = vec3(1, vy, 0);
    const StrongeAnswer r = stronge_one_contact(b.M, b.w_N, b.w_T, qA, 0.5, 1.0);
    EXPECT_EQ(r.regime, StrongeRegime::no_impact);
    EXPECT_EQ(r.P_N, 0.0);
    EXPECT_EQ(r.P_T, 0.0);
    EXPECT_EQ(r.energy_change, 0.0);
    EXPECT_EQ(r.qdot_E, qA);
  }
  EXPECT_EQ(to_string(StrongeRegime::slip_reversal), "slip_reversal");
}

// ---------------------------------------------------------------------------------------------
// 2. Where Stronge's law is Newton's: one affine phase in p_N (μ = 0, or G_NT = 0 where the
// stick and slide slopes of D_N are both G_NN) gives D_N² = 2 G_NN |W| and so D_NE = −e D_NA,
// P_N = −(1 + e) D_NA / G_NN.

TEST(StrongeOneContact, FrictionlessIsNewton) {
  // Body A: G_NN = 2, G_NT = 1; P_T = 0 and D_TE = D_TA + G_NT P_N, whatever D_T does.
  const Body b = body_a();
  for (const double e : {0.0, 0.3, 1.0})
    for (const double vx : {-2.0, 0.0, 0.7}) {
      const VectorXd qA = vec3(vx, -1.3, 0.4);
      const double D_NA = -0.9, D_TA = vx + 0.4;
      const StrongeAnswer r = stronge_one_contact(b.M, b.w_N, b.w_T, qA, e, 0.0);
      const double P_N = -(1 + e) * D_NA / 2;
      EXPECT_NEAR(r.P_N, P_N, kTol);
      EXPECT_EQ(r.P_T, 0.0);
      EXPECT_NEAR(r.D_NE, -e * D_NA, kTol);
      EXPECT_NEAR(r.D_TE, D_TA + P_N, kTol);
      EXPECT_NEAR(r.dissipated_normal, 0.5 * (1 - e * e) * D_NA * D_NA / 2, kTol);
      EXPECT_EQ(r.dissipated_tangential, 0.0);
      expect_vec_near(r.qdot_E, qA + vec3(0, P_N, P_N), kTol);
    }
}

TEST(StrongeOneContact, ContactBelowTheCentreIsNewtonCoulomb) {
  // r = (0, ry), ry < 0: G_NT = 0, G_NN = 1/m, G_TT = 1/m + ry²/I. It keeps sliding iff
  // |D_TA| ≥ μ G_TT P_N; then P_T = −μ s P_N, D_TE = D_TA + G_TT P_T; else it sticks with
  // P_T = −D_TA / G_TT. Either way D_NE = −e D_NA.
  const double m = 2.0, I = 0.5, ry = -0.4;
  const Body b = planar_body(m, I, 0.0, ry);
  const double G_NN = 1 / m, G_TT = 1 / m + ry * ry / I;
  for (const double e : {0.0, 0.6, 1.0})
    for (const double mu : {0.1, 0.5, 2.0})
      for (const double D_TA : {-3.0, -0.2, 0.05, 1.5}) {
        const double D_NA = -1.2;
        const VectorXd qA = vec3(D_TA, D_NA, 0.0);
        const StrongeAnswer r = stronge_one_contact(b.M, b.w_N, b.w_T, qA, e, mu);
        const double P_N = -(1 + e) * D_NA / G_NN, s = D_TA > 0 ? 1.0 : -1.0;
        const bool slides = std::fabs(D_TA) >= mu * G_TT * P_N;
        const double P_T = slides ? -mu * s * P_N : -D_TA / G_TT;
        EXPECT_EQ(r.regime, slides ? StrongeRegime::slide : StrongeRegime::slip_stick);
        EXPECT_NEAR(r.P_N, P_N, kTol);
        EXPECT_NEAR(r.D_NE, -e * D_NA, kTol);
        EXPECT_NEAR(r.P_T, P_T, kTol);
        EXPECT_NEAR(r.D_TE, D_TA + G_TT * P_T, kTol);
        expect_vec_near(r.qdot_E, qA + vec3(P_T / m, P_N / m, -ry * P_T / I), kTol);
      }
}

TEST(StrongeOneContact, PointMassIsNewtonCoulomb) {
  // M = diag(m, m), w_N = (0, 1), w_T = (1, 0): G = I/m. P_N = (1 + e) m |D_NA|;
  // P_T = −μ s P_N if μ P_N ≤ m |D_TA| (slides), else −m D_TA (sticks).
  const double m = 3.0, e = 0.4;
  const MatrixXd M = Eigen::Vector2d(m, m).asDiagonal();
  const VectorXd w_N = Eigen::Vector2d(0, 1), w_T = Eigen::Vector2d(1, 0);
  for (const double mu : {0.2, 1.0}) {
    const VectorXd qA = Eigen::Vector2d(-1.0, -2.0);
    const StrongeAnswer r = stronge_one_contact(M, w_N, w_T, qA, e, mu);
    const double P_N = (1 + e) * m * 2.0;
    const double P_T = mu * P_N <= m * 1.0 ? mu * P_N : m * 1.0;
    EXPECT_NEAR(r.P_N, P_N, kTol);
    EXPECT_NEAR(r.P_T, P_T, kTol);
    expect_vec_near(r.qdot_E, Eigen::Vector2d(-1.0 + P_T / m, e * 2.0), kTol);
  }
}

// ---------------------------------------------------------------------------------------------
// Random one-contact problems for 3-5.

struct Problem {
  MatrixXd M;
  VectorXd w_N, w_T, qdot_A;
  double e = 0, mu = 0;
};

Problem random_problem(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit;
  Problem p;
  const int n = 2 + static_cast<int>(rng() % 3);
  for (;;) {
    MatrixXd A(n, n);
    for (double& a : A.reshaped()) a = normal(rng);
    p.M = A * A.transpose() + (0.05 + unit(rng)) * MatrixXd::Identity(n, n);
    p.w_N = VectorXd(n);
    p.w_T = VectorXd(n);
    p.qdot_A = VectorXd(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      p.w_N(i) = normal(rng);
      p.w_T(i) = normal(rng);
      p.qdot_A(i) = normal(rng);
    }
    // Keep clear of the refused near-parallel (w_N, w_T) in the metric M⁻¹.
    const MatrixXd Minv = p.M.inverse();
    const double NN = p.w_N.dot(Minv * p.w_N), TT = p.w_T.dot(Minv * p.w_T),
                 NT = p.w_N.dot(Minv * p.w_T);
    if (NN * TT - NT * NT < 1e-8 * NN * TT) continue;
    const double D_NA = p.w_N.dot(p.qdot_A);
    if (D_NA == 0.0) continue;
    if (D_NA > 0.0) p.qdot_A -= 2 * D_NA / p.w_N.squaredNorm() * p.w_N;  // now approaching
    break;
  }
  const unsigned pick = rng() % 10;
  p.e = pick == 0 ? 0.0 : pick == 1 ? 1.0 : unit(rng);
  p.mu = pick == 2 ? 0.0 : 2.0 * unit(rng);
  return p;
}

// 3. Never creates energy; P_N ≥ 0, inside the cone, no penetration after. T_E − T_A is computed
// here from the velocities, and must also agree with the kernel's work split.
TEST(StrongeOneContact, RandomProblemsNeverCreateEnergy) {
  std::mt19937 rng(20240611);
  std::map<StrongeRegime, int> seen;
  for (int trial = 0; trial < 100000; ++trial) {
    const Problem p = random_problem(rng);
    const StrongeAnswer r = stronge_one_contact(p.M, p.w_N, p.w_T, p.qdot_A, p.e, p.mu);
    ++seen[r.regime];
    const double T_A = kinetic(p.M, p.qdot_A), dT = kinetic(p.M, r.qdot_E) - T_A;
    // q̇_E carries the rounding of M⁻¹w_N P_N + M⁻¹w_T P_T, each term of which can be far larger
    // than their sum when w_N, w_T are nearly parallel in the metric M⁻¹ (then P is large).
    const double dv = (p.M.llt().solve(p.w_N) * r.P_N).norm() +
                      (p.M.llt().solve(p.w_T) * r.P_T).norm() + p.qdot_A.norm();
    const double rounding = p.M.norm() * p.qdot_A.norm() * dv;
    const double scale = p.w_N.norm() * dv;
    ASSERT_LE(dT, 1e-12 * T_A) << "trial " << trial;
    ASSERT_NEAR(r.energy_change, dT, 1e-12 * (T_A + rounding)) << "trial " << trial;
    ASSERT_GE(r.P_N, 0.0) << "trial " << trial;
    ASSERT_LE(std::fabs(r.P_T), p.mu * r.P_N * (1 + 1e-12)) << "trial " << trial;
    ASSERT_GE(p.w_N.dot(r.qdot_E), -1e-12 * scale) << "trial " << trial;
    ASSERT_GE(r.dissipated_normal, 0.0);
    ASSERT_GE(r.dissipated_tangential, 0.0);
  }
  // The generator reaches every regime that a generic D_TA ≠ 0 allows.
  EXPECT_GT(seen[StrongeRegime::slide], 1000);
  EXPECT_GT(seen[StrongeRegime::slip_stick], 1000);
  EXPECT_GT(seen[StrongeRegime::slip_reversal], 1000);
}

// 4. M(q̇_E − q̇_A) = w_N P_N + w_T P_T.
TEST(StrongeOneContact, RandomProblemsBalanceMomentum) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20000; ++trial) {
    const Problem p = random_problem(rng);
    const StrongeAnswer r = stronge_one_contact(p.M, p.w_N, p.w_T, p.qdot_A, p.e, p.mu);
    const VectorXd impulse = p.w_N * r.P_N + p.w_T * r.P_T;
    const VectorXd lhs = p.M * (r.qdot_E - p.qdot_A);
    // q̇_E is rounded at the size of q̇_A, so an impulse far below it is seen through that.
    const double scale = p.M.norm() * (p.qdot_A.norm() + r.qdot_E.norm()) + p.w_N.norm() * r.P_N +
                         p.w_T.norm() * std::fabs(r.P_T);
    ASSERT_LE((lhs - impulse).norm(), 1e-13 * scale) << "trial " << trial;
  }
}

// ---------------------------------------------------------------------------------------------
// 5. A second method: Darboux-Keller's ODE dq̇/dp_N = M⁻¹(w_N + w_T τ), dp_T/dp_N = τ,
// dW/dp_N = D_N, by fixed-step RK4 in p_N. Off D_T = 0, τ = −μ sign(D_T); a step across D_T = 0,
// D_N = 0 or the end is shortened by bisection onto it. At D_T = 0 it slides the way D_T moves if
// it can (Filippov), and otherwise sticks with the τ ∈ [−μ, μ] that holds dD_T/dp_N = 0.
struct Integrated {
  VectorXd qdot;
  double P_N = 0, P_T = 0;
  int steps = 0;
};

Integrated integrate_rk4(const Problem& p, int steps_per_unit) {
  const Eigen::Index n = p.M.rows();
  const MatrixXd Minv = p.M.inverse();
  const VectorXd u_N = Minv * p.w_N, u_T = Minv * p.w_T;
  // State y = (q̇, p_T, W); τ is fixed for a step.
  auto rhs = [&](const VectorXd& y, double tau) {
    VectorXd f(n + 2);
    f.head(n) = u_N + u_T * tau;
    f(n) = tau;
    f(n + 1) = p.w_N.dot(y.head(n));
    return f;
  };
  auto rk4 = [&](const VectorXd& y, double tau, double h) {
    const VectorXd k1 = rhs(y, tau), k2 = rhs(y + h / 2 * k1, tau), k3 = rhs(y + h / 2 * k2, tau),
                   k4 = rhs(y + h * k3, tau);
    return VectorXd(y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4));
  };
  auto D_N = [&](const VectorXd& y) { return p.w_N.dot(y.head(n)); };
  auto D_T = [&](const VectorXd& y) { return p.w_T.dot(y.head(n)); };
  // Filippov at D_T = 0: the rates of D_T when slipping forwards (τ = −μ) and backwards (τ = μ).
  auto tau_at_zero = [&]() {
    const double up = p.w_T.dot(u_N - p.mu * u_T), down = p.w_T.dot(u_N + p.mu * u_T);
    if (up > 0) return -p.mu;
    if (down < 0) return p.mu;
    return p.mu == 0 ? 0.0 : -p.mu + 2 * p.mu * up / (up - down);
  };

  VectorXd y(n + 2);
  y << p.qdot_A, 0.0, 0.0;
  double P_N = 0;
  double tau = D_T(y) > 0 ? -p.mu : D_T(y) < 0 ? p.mu : tau_at_zero();
  bool slipping = D_T(y) != 0 || std::fabs(tau) == p.mu;
  bool compressing = true;
  double W_target = 0;
  // At least steps_per_unit steps in compression: |dD_N/dp_N| ≤ w_N·u_N + μ |w_N·u_T|.
  const double h = -D_N(y) / (p.w_N.dot(u_N) + p.mu * std::fabs(p.w_N.dot(u_T))) / steps_per_unit;
  Integrated out;
  while (++out.steps < 50'000'000) {
    // The event reached by state z, if any: 1 D_T crosses 0 while slipping, 2 compression ends,
    // 3 the restitution work reaches its target (docs/stronge.md, eq. (7)).
    const double s = tau > 0 ? -1.0 : 1.0;
    auto event = [&](const VectorXd& z) {
      if (slipping && p.mu > 0 && s * D_T(z) < 0) return 1;
      if (compressing && D_N(z) >= 0) return 2;
      if (!compressing && z(n + 1) >= W_target) return 3;
      return 0;
    };
    VectorXd next = rk4(y, tau, h);
    double step = h;
    if (event(next) != 0) {
      double lo = 0, hi = h;
      for (int it = 0; it < 80; ++it) {
        const double mid = 0.5 * (lo + hi);
        (event(rk4(y, tau, mid)) != 0 ? hi : lo) = mid;
      }
      step = hi;
      next = rk4(y, tau, hi);
    }
    const int ev = event(next);
    y = next;
    P_N += step;
    if (ev == 1) {
      tau = tau_at_zero();
      slipping = std::fabs(tau) == p.mu;
    } else if (ev == 2) {
      compressing = false;
      W_target = (1 - p.e * p.e) * y(n + 1);
      if (y(n + 1) >= W_target) break;  // e = 0
    } else if (ev == 3) {
      break;
    }
  }
  out.qdot = y.head(n);
  out.P_N = P_N;
  out.P_T = y(n);
  return out;
}

TEST(StrongeOneContact, AgreesWithNumericalDarbouxKeller) {
  std::vector<Problem> cases;
  // The hand cases above, then random ones.
  const std::vector<std::tuple<Body, VectorXd, double, double>> hand = {
      {body_a(), vec3(1, -1.75, 0), 0.5, 0.25},  {body_b(), vec3(6, -1, 0), 1.0, 2.0},
      {body_a(), vec3(1, -0.75, 0), 1.0, 1.0},   {body_a(), vec3(-1.5, -3, 0), 0.5, 0.25},
      {body_a(), vec3(-0.75, -1, 0), 1.0, 0.25}, {body_a(), vec3(0, -3, 0), 0.5, 1.0},
      {body_a(), vec3(0, -1.75, 0), 1.0, 0.25}};
  for (const auto& [b, qA, e, mu] : hand) cases.push_back({b.M, b.w_N, b.w_T, qA, e, mu});
  std::mt19937 rng(99);
  for (int i = 0; i < 300; ++i) cases.push_back(random_problem(rng));

  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Problem& p = cases[i];
    const StrongeAnswer r = stronge_one_contact(p.M, p.w_N, p.w_T, p.qdot_A, p.e, p.mu);
    const Integrated num = integrate_rk4(p, 2000);
    const double scale = std::max(p.qdot_A.norm(), r.qdot_E.norm());
    EXPECT_GE(num.steps, 2000) << "case " << i;
    for (Eigen::Index j = 0; j < p.qdot_A.size(); ++j)
      EXPECT_NEAR(r.qdot_E(j), num.qdot(j), 1e-6 * scale) << "case " << i << " entry " << j;
    EXPECT_NEAR(r.P_N, num.P_N, 1e-6 * std::max(1.0, r.P_N)) << "case " << i;
    EXPECT_NEAR(r.P_T, num.P_T, 1e-6 * std::max(1.0, r.P_N)) << "case " << i;
  }
}

// ---------------------------------------------------------------------------------------------
// 6. Refusals name the value.

std::string refused(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidArgument& ex) {
    return ex.name();
  }
  return "(accepted)";
}

TEST(StrongeOneContact, RefusesBadInput) {
  const Body b = body_a();
  const VectorXd qA = vec3(1, -1, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto call = [&](const MatrixXd& M, const VectorXd& w_N, const VectorXd& w_T, const VectorXd& q,
                  double e, double mu) {
    return refused([&] { stronge_one_contact(M, w_N, w_T, q, e, mu); });
  };
  EXPECT_EQ(call(b.M, b.w_N, b.w_T, qA, 0.5, 0.3), "(accepted)");
  EXPECT_EQ(call(b.M, b.w_N, b.w_T, qA, 1.5, 0.3), "e");
  EXPECT_EQ(call(b.M, b.w_N, b.w_T, qA, -0.1, 0.3), "e");
  EXPECT_EQ(call(b.M, b.w_N, b.w_T, qA, nan, 0.3), "e");
  EXPECT_EQ(call(b.M, b.w_N, b.w_T, qA, 0.5, -1.0), "mu");
  EXPECT_EQ(call(b.M, b.w_N, b.w_T, qA, 0.5, inf), "mu");
  EXPECT_EQ(call(b.M, b.w_N, b.w_T, qA, 0.5, nan), "mu");

  MatrixXd M = b.M;
  M(0, 0) = -1;
  EXPECT_EQ(call(M, b.w_N, b.w_T, qA, 0.5, 0.3), "M");  // not positive definite
  M = b.M;
  M(0, 1) = 0.1;
  EXPECT_EQ(call(M, b.w_N, b.w_T, qA, 0.5, 0.3), "M");  // not symmetric
  M = b.M;
  M(2, 2) = nan;
  EXPECT_EQ(call(M, b.w_N, b.w_T, qA, 0.5, 0.3), "M");
  EXPECT_EQ(call(MatrixXd::Identity(3, 2), b.w_N, b.w_T, qA, 0.5, 0.3), "M");
  EXPECT_EQ(call(MatrixXd(0, 0), VectorXd(0), VectorXd(0), VectorXd(0), 0.5, 0.3), "M");

  EXPECT_EQ(call(b.M, Eigen::Vector2d(0, 1), b.w_T, qA, 0.5, 0.3), "w_N");
  EXPECT_EQ(call(b.M, vec3(0, 0, 0), b.w_T, qA, 0.5, 0.3), "w_N");
  EXPECT_EQ(call(b.M, vec3(0, inf, 0), b.w_T, qA, 0.5, 0.3), "w_N");
  EXPECT_EQ(call(b.M, b.w_N, Eigen::Vector4d(1, 0, 0, 0), qA, 0.5, 0.3), "w_T");
  EXPECT_EQ(call(b.M, b.w_N, vec3(0, 0, 0), qA, 0.5, 0.3), "w_T");
  EXPECT_EQ(call(b.M, b.w_N, 2.0 * b.w_N, qA, 0.5, 0.3), "w_T");  // singular G
  EXPECT_EQ(call(b.M, b.w_N, b.w_T, Eigen::Vector2d(1, -1), 0.5, 0.3), "qdot_A");
  EXPECT_EQ(call(b.M, b.w_N, b.w_T, vec3(nan, -1, 0), 0.5, 0.3), "qdot_A");
}

}  // namespace
}  // namespace fremond::detail
