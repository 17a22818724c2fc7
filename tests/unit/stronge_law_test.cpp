// Stronge's law through the library's public path (solve_impact, the problem file, law_residual,
// the certificate): against answers derived by hand, Newton's closed form where the two coincide,
// the momentum balance and the energy on random problems.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fremond/fremond.hpp"
#include "support/fixtures.hpp"

namespace fremond {
namespace {

ImpactLaw stronge_impact_law(double e, double mu) {
  StrongeLaw law;
  law.e = e;
  law.coulomb = true;
  law.mu = mu;
  return law;
}

// The paper's bar at its first impact (θ = π/4, l = 0.5, m = 1, J = 1/12, q̇_A = (2, −v, 0) with
// v = √(2g(1 − l sin θ))): G_NN = G_TT = 1 + 12 l²/2 = 2.5, G_NT = −12 l²/2 = −1.5, D_TA = 2.
// With e* = 0.9, μ = 1 it slips forward (s = +1) with dD_T/dp = G_NT − μG_TT = −4 and
// dD_N/dp = G_NN − μG_NT = 4 until D_T = 0 at p1 = 1/2, still compressing (D_N(p1) = 2 − v);
// |G_NT| = 1.5 ≤ μG_TT = 2.5, so it sticks: dD_N/dp = det G/G_TT = 1.6, dP_T/dp = −G_NT/G_TT =
// 0.6. Compression ends at p_c = p1 + (v − 2)/1.6 with work W_c = −(v + (v − 2))/2·p1 −
// (v − 2)²/3.2; restitution in stick has work 0.8x² = e²|W_c|.
TEST(StrongeLaw, PaperBarFirstImpactSlipsThenSticks) {
  const ImpactProblem pb = fixtures::paper_bar_first_impact();
  const double v = -pb.qdot_A(1), e = 0.9;
  const double p1 = 0.5, dn1 = v - 2.0;
  const double W_c = -0.5 * (v + dn1) * p1 - dn1 * dn1 / 3.2;
  const double x = std::sqrt(e * e * -W_c / 0.8);
  const double P_N = p1 + dn1 / 1.6 + x;
  const double P_T = -p1 + 0.6 * (P_N - p1);
  const double dE = -(1.0 - e * e) * -W_c - 0.5 * 2.0 * p1;  // − μ∫|D_T|dp over the slip

  const ImpactResult r = solve_impact(pb, stronge_impact_law(e, 1.0));
  ASSERT_EQ(r.solver.status, SolverStatus::converged) << r.solver.message;
  EXPECT_NEAR(r.P_N(0), P_N, 1e-13 * P_N);
  EXPECT_NEAR(r.P_T(0), P_T, 1e-13 * P_N);
  EXPECT_NEAR(r.D_NE(0), 1.6 * x, 1e-13 * v);
  EXPECT_NEAR(r.D_TE(0), 0.0, 1e-13 * v);
  EXPECT_NEAR(r.energy_change, dE, 1e-12 * r.admissibility.kinetic_energy_A);
  EXPECT_LT(r.energy_change, 0.0);
  EXPECT_TRUE(r.admissibility.admissible) << to_string(r.admissibility.failed);
  EXPECT_LE(law_residual(pb, stronge_impact_law(e, 1.0), r), 1e-14);
  // Newton + Coulomb with the same e and μ creates energy at this impact (the paper's §4).
  EXPECT_GT(solve_impact(pb, ImpactLaw::newton_coulomb(e, 1.0)).energy_change, 0.0);
}

// Without friction Stronge's law is Newton's: D_NE = −e D_NA, P_N = −(1 + e) D_NA / G_NN.
TEST(StrongeLaw, FrictionlessIsNewton) {
  const ImpactProblem pb = fixtures::paper_bar_first_impact();
  StrongeLaw frictionless;
  frictionless.e = 0.7;
  const ImpactResult r = solve_impact(pb, frictionless);
  ASSERT_EQ(r.solver.status, SolverStatus::converged);
  EXPECT_NEAR(r.D_NE(0), -0.7 * r.D_NA(0), 1e-14 * std::fabs(r.D_NA(0)));
  EXPECT_NEAR(r.P_N(0), -1.7 * r.D_NA(0) / 2.5, 1e-14 * r.P_N(0));
  EXPECT_EQ(r.P_T(0), 0.0);
  const ImpactResult n = solve_impact(pb, ImpactLaw::newton(0.7));
  EXPECT_NEAR(r.qdot_E(2), n.qdot_E(2), 1e-14 * std::fabs(n.qdot_E(2)));
}

TEST(StrongeLaw, ReadFromTheProblemFile) {
  const io::ProblemFile f = io::parse_problem_file(R"({
    "M": [[1, 0], [0, 1]], "W_N": [[0], [1]], "W_T": [[1], [0]], "qdot_A": [1, -2],
    "law": {"type": "stronge_coulomb", "e": 0.5, "mu": 0.25}})",
                                                   PotentialRegistry::with_builtins());
  EXPECT_EQ(f.law.name(), "stronge_coulomb");
  EXPECT_EQ(f.law.describe(), "stronge_coulomb(e=0.5, mu=0.25)");
  // A point mass: G = I, slides throughout (μ G_NT = 0): P_N = (1 + e)·2, P_T = −μ P_N.
  const ImpactResult r = solve_impact(f.problem, f.law);
  EXPECT_NEAR(r.P_N(0), 3.0, 1e-15);
  EXPECT_NEAR(r.P_T(0), -0.75, 1e-15);
  for (const auto& [text, key] :
       {std::pair{R"({"type": "stronge", "e": 1.5})", "law.e"},
        std::pair{R"({"type": "stronge", "e": 0.5, "mu": 1})", "law.mu"},
        std::pair{R"({"type": "stronge_coulomb", "e": 0.5, "mu": [-1]})", "law.mu[0]"}}) {
    try {
      (void)io::parse_problem_file(
          R"({"M": [[1]], "W_N": [[1]], "qdot_A": [-1], "law": )" + std::string(text) + "}",
          PotentialRegistry::with_builtins());
      ADD_FAILURE() << text;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.name(), key) << text;
    }
  }
}

// Two bars in one problem (block-diagonal M): independent contacts, each its own closed form.
// Two ends of one bar interact (G_01 ≠ 0): simultaneous impacts, for the distributing law, which
// no closed form solves (stronge_lzb_test.cpp holds its answers).
TEST(StrongeLaw, IndependentContactsApartCoupledContactsDistributed) {
  const ImpactProblem one = fixtures::paper_bar_first_impact();
  ImpactProblem two;
  two.M = Eigen::MatrixXd::Zero(6, 6);
  two.M.topLeftCorner(3, 3) = one.M;
  two.M.bottomRightCorner(3, 3) = one.M;
  two.W_N = Eigen::MatrixXd::Zero(6, 2);
  two.W_T = Eigen::MatrixXd::Zero(6, 2);
  two.W_N.block(0, 0, 3, 1) = one.W_N;
  two.W_N.block(3, 1, 3, 1) = one.W_N;
  two.W_T.block(0, 0, 3, 1) = one.W_T;
  two.W_T.block(3, 1, 3, 1) = one.W_T;
  two.qdot_A = Eigen::VectorXd(6);
  two.qdot_A << one.qdot_A, 0.5 * one.qdot_A;
  const ImpactResult alone = solve_impact(one, stronge_impact_law(0.9, 1.0));
  const ImpactResult both = solve_impact(two, stronge_impact_law(0.9, 1.0));
  ASSERT_EQ(both.solver.status, SolverStatus::converged) << both.solver.message;
  EXPECT_NEAR(both.P_N(0), alone.P_N(0), 1e-14 * alone.P_N(0));
  EXPECT_NEAR(both.P_N(1), 0.5 * alone.P_N(0), 1e-14 * alone.P_N(0));  // linear in the velocity
  EXPECT_TRUE(both.admissibility.admissible);

  const ImpactProblem flat = fixtures::bar(0.0, Eigen::Vector3d(0.3, -1.0, 0.2), true);
  const ImpactResult r = solve_impact(flat, stronge_impact_law(0.9, 1.0));
  EXPECT_EQ(r.solver.status, SolverStatus::converged) << r.solver.message;
  EXPECT_EQ(r.solver.method, SolverMethod::impulse_integration);
  EXPECT_TRUE(r.admissibility.admissible) << to_string(r.admissibility.failed);
  EXPECT_LT(r.energy_change, 0.0);
  SolverOptions closed;
  closed.method = SolverMethod::closed_form;
  EXPECT_EQ(solve_impact(flat, stronge_impact_law(0.9, 1.0), closed).solver.status,
            SolverStatus::unsupported);
}

// On random one-contact problems: P_N ≥ 0, |P_T| ≤ μP_N, momentum M(q̇_E − q̇_A) = W P, no
// penetration, no energy created, and the certificate agrees.
TEST(StrongeLaw, RandomOneContactProblemsDissipate) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  int solved = 0;
  for (int k = 0; k < 20000; ++k) {
    const int n = 2 + k % 3;
    Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return u(rng); });
    ImpactProblem pb;
    pb.M = A * A.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    pb.W_N = Eigen::MatrixXd::NullaryExpr(n, 1, [&] { return u(rng); });
    pb.W_T = Eigen::MatrixXd::NullaryExpr(n, 1, [&] { return u(rng); });
    pb.qdot_A = Eigen::VectorXd::NullaryExpr(n, [&] { return u(rng); });
    const double D_NA = pb.W_N.col(0).dot(pb.qdot_A);
    if (D_NA > 0.0) pb.qdot_A -= 2.0 * D_NA / pb.W_N.squaredNorm() * pb.W_N.col(0);
    const double e = pos(rng), mu = 2.0 * pos(rng);
    const ImpactResult r = solve_impact(pb, stronge_impact_law(e, mu));
    if (r.solver.status == SolverStatus::unsupported) continue;  // w_T ∥ w_N in M⁻¹
    ASSERT_EQ(r.solver.status, SolverStatus::converged) << k;
    ++solved;
    const double T_A = r.admissibility.kinetic_energy_A;
    EXPECT_GE(r.P_N(0), 0.0) << k;
    EXPECT_LE(std::fabs(r.P_T(0)), mu * r.P_N(0) * (1 + 1e-12) + 1e-300) << k;
    const Eigen::VectorXd momentum =
        pb.M * (r.qdot_E - pb.qdot_A) - pb.W_N * r.P_N - pb.W_T * r.P_T;
    const double scale =
        (pb.M.cwiseAbs() * (r.qdot_E.cwiseAbs() + pb.qdot_A.cwiseAbs())).maxCoeff();
    EXPECT_LE(momentum.cwiseAbs().maxCoeff(), 1e-13 * scale) << k;
    EXPECT_GE(r.D_NE(0), -1e-12 * std::fabs(r.D_NA(0))) << k;
    EXPECT_LE(r.energy_change, 1e-12 * T_A) << k;
    EXPECT_TRUE(r.admissibility.admissible) << k << " " << to_string(r.admissibility.failed);
  }
  EXPECT_GT(solved, 19900);
}

}  // namespace
}  // namespace fremond
