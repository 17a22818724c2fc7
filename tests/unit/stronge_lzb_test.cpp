// Stronge's law on coupled contacts, by the distributing law of Liu, Zhao and Brogliato
// (docs/stronge.md, "Several contacts"): each assertion against an independent reference — a
// direct time integration of Hertz's contact, answers derived by hand, the closed form of one
// contact, and the balances of momentum and energy computed here from the velocities.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "fremond/fremond.hpp"
#include "laws/stronge/darboux_keller.hpp"
#include "laws/stronge/lzb.hpp"

namespace fremond {
namespace {

StrongeLaw stronge(double e, double eta, double mu = -1.0) {
  StrongeLaw law;
  law.e = e;
  law.eta = eta;
  if (mu >= 0.0) {
    law.coulomb = true;
    law.mu = mu;
  }
  return law;
}

double kinetic(const Eigen::MatrixXd& M, const Eigen::VectorXd& v) {
  return 0.5 * v.dot(M * v);
}

// Balls of mass 1 on a line, x_1 < x_2 < ..., touching; contact k between balls k and k+1 with
// D_N = ẋ_{k+1} − ẋ_k (< 0 when they approach).
ImpactProblem chain(const Eigen::VectorXd& qdot) {
  const int n = static_cast<int>(qdot.size());
  ImpactProblem pb;
  pb.M = Eigen::MatrixXd::Identity(n, n);
  pb.W_N = Eigen::MatrixXd::Zero(n, n - 1);
  for (int k = 0; k + 1 < n; ++k) {
    pb.W_N(k, k) = -1.0;
    pb.W_N(k + 1, k) = 1.0;
  }
  pb.qdot_A = qdot;
  return pb;
}

// Hertz's compliant contact in time: forces K δ^(3/2) on the overlaps of balls of mass 1 on a
// line, integrated to separation with a tight-tolerance Dormand-Prince stepper (e* = 1: elastic).
Eigen::VectorXd hertz_chain(const Eigen::VectorXd& qdot, double K) {
  namespace odeint = boost::numeric::odeint;
  const int n = static_cast<int>(qdot.size());
  using State = std::vector<double>;  // positions, then velocities
  State y(static_cast<std::size_t>(2 * n), 0.0);
  for (int i = 0; i < n; ++i) y[static_cast<std::size_t>(n + i)] = qdot(i);
  auto force = [&](const State& s, State& d, double /*t*/) {
    for (int i = 0; i < n; ++i) {
      d[static_cast<std::size_t>(i)] = s[static_cast<std::size_t>(n + i)];
      d[static_cast<std::size_t>(n + i)] = 0.0;
    }
    for (int k = 0; k + 1 < n; ++k) {
      const double overlap =
          std::max(0.0, s[static_cast<std::size_t>(k)] - s[static_cast<std::size_t>(k + 1)]);
      const double F = K * overlap * std::sqrt(overlap);
      d[static_cast<std::size_t>(n + k)] -= F;
      d[static_cast<std::size_t>(n + k + 1)] += F;
    }
  };
  // The contact lasts a few δ_max/v with δ_max ~ (v²/K)^(2/5): integrate well past it.
  const double t_end = 50.0 * std::pow(K, -0.4);
  odeint::integrate_adaptive(
      odeint::make_controlled(1e-13, 1e-13, odeint::runge_kutta_dopri5<State>()), force, y, 0.0,
      t_end, 1e-4 * t_end);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = y[static_cast<std::size_t>(n + i)];
  // Apart and separating: the impact is over.
  for (int k = 0; k + 1 < n; ++k) {
    EXPECT_LE(y[static_cast<std::size_t>(k)], y[static_cast<std::size_t>(k + 1)]);
    EXPECT_LE(v(k), v(k + 1));
  }
  return v;
}

// M(q̇_E − q̇_A) = W_N P_N + W_T P_T, to the rounding of its terms.
void expect_momentum(const ImpactProblem& pb, const ImpactResult& r, double tol = 1e-13) {
  Eigen::VectorXd balance = pb.M * (r.qdot_E - pb.qdot_A) - pb.W_N * r.P_N;
  if (pb.W_T.cols() > 0) balance -= pb.W_T * r.P_T;
  const double scale = (pb.M.cwiseAbs() * (r.qdot_E.cwiseAbs() + pb.qdot_A.cwiseAbs())).maxCoeff();
  EXPECT_LE(balance.cwiseAbs().maxCoeff(), tol * scale);
}

// Newton's cradle of 3 balls under Hertz's law (η = 3/2, e* = 1): the velocities after, against
// the compliant contact integrated in time at two stiffnesses 10⁶ apart (the rigid limit does not
// depend on K), to 1e-6.
TEST(StrongeLzb, ThreeBallChainAgreesWithHertzInTime) {
  const ImpactProblem pb = chain(Eigen::Vector3d(1.0, 0.0, 0.0));
  const ImpactResult r = solve_impact(pb, stronge(1.0, 1.5));
  ASSERT_EQ(r.solver.status, SolverStatus::converged) << r.solver.message;
  EXPECT_EQ(r.solver.method, SolverMethod::impulse_integration);
  const Eigen::VectorXd soft = hertz_chain(pb.qdot_A, 1.0);
  const Eigen::VectorXd stiff = hertz_chain(pb.qdot_A, 1e6);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(soft(i), stiff(i), 1e-7) << i;
    EXPECT_NEAR(r.qdot_E(i), soft(i), 1e-6) << i;
  }
  // Not Newton's cradle of the textbook (0, 0, 1): the middle ball keeps some velocity.
  EXPECT_GT(r.qdot_E(1), 0.05);
  expect_momentum(pb, r);
  EXPECT_TRUE(r.admissibility.admissible) << to_string(r.admissibility.failed);
}

// e* = 1, η = 1, no friction: no energy lost, to the integration's tolerance. T_E − T_A from
// the velocities here; the chain passes most of the blow to the last ball.
TEST(StrongeLzb, ElasticChainKeepsItsEnergy) {
  for (const Eigen::VectorXd& qdot : {Eigen::VectorXd(Eigen::Vector3d(1.0, 0.0, 0.0)),
                                      Eigen::VectorXd(Eigen::Vector3d(2.0, 0.5, -1.0))}) {
    const ImpactProblem pb = chain(qdot);
    const ImpactResult r = solve_impact(pb, stronge(1.0, 1.0));
    ASSERT_EQ(r.solver.status, SolverStatus::converged) << r.solver.message;
    const double T_A = kinetic(pb.M, pb.qdot_A);
    EXPECT_NEAR(kinetic(pb.M, r.qdot_E) - T_A, 0.0, 1e-10 * T_A);
    EXPECT_NEAR(r.energy_change, 0.0, 1e-10 * T_A);
    EXPECT_LE(r.solver.residual, 1e-10);
    expect_momentum(pb, r);
    for (int k = 0; k < 2; ++k) EXPECT_GE(r.D_NE(k), 0.0);
  }
}

// A ball in the middle struck from both sides at equal speeds, η = 1, equal stiffnesses: by
// symmetry P_1 = P_2 at every instant and the middle ball never moves, so each outer ball meets a
// wall: compression ends at P = 1 with work 1/2, restitution gives back e²/2, P = 1 + e.
TEST(StrongeLzb, MiddleBallStruckFromBothSides) {
  const double e = 0.6;
  const ImpactProblem pb = chain(Eigen::Vector3d(1.0, 0.0, -1.0));
  const ImpactResult r = solve_impact(pb, stronge(e, 1.0));
  ASSERT_EQ(r.solver.status, SolverStatus::converged) << r.solver.message;
  EXPECT_NEAR(r.P_N(0), 1.0 + e, 1e-10);
  EXPECT_NEAR(r.P_N(1), 1.0 + e, 1e-10);
  EXPECT_NEAR(r.qdot_E(0), -e, 1e-10);
  EXPECT_NEAR(r.qdot_E(1), 0.0, 1e-10);
  EXPECT_NEAR(r.qdot_E(2), e, 1e-10);
  EXPECT_NEAR(r.energy_change, -(1.0 - e * e), 1e-10);
}

// A ball A falling at speed v onto two balls B and C resting side by side (plane, masses 1,
// frictionless), its contact normals at ±θ from the vertical. η = 1 and equal stiffnesses: by
// symmetry P_B = P_C = p at every instant, and D_N of each contact moves by (G_BB + G_BC) dp with
// G_BB = 2 (A and B), G_BC = n_B·n_C = cos 2θ (through A): one contact's law, P = (1 + e)
// v cos θ / (2 + cos 2θ), D_NE = e v cos θ.
TEST(StrongeLzb, BallStrikesTwoBallsSymmetrically) {
  const double theta = std::numbers::pi / 6, v = 1.5, e = 0.8;
  const Eigen::Vector2d nB(std::sin(theta), -std::cos(theta));  // from A towards B (below right)
  const Eigen::Vector2d nC(-std::sin(theta), -std::cos(theta));
  ImpactProblem pb;  // q = (A, B, C), each (x, y)
  pb.M = Eigen::MatrixXd::Identity(6, 6);
  pb.W_N = Eigen::MatrixXd::Zero(6, 2);
  pb.W_N.block<2, 1>(0, 0) = -nB;  // D_N = n·(v_B − v_A): the balls approach when negative
  pb.W_N.block<2, 1>(2, 0) = nB;
  pb.W_N.block<2, 1>(0, 1) = -nC;
  pb.W_N.block<2, 1>(4, 1) = nC;
  pb.qdot_A = Eigen::VectorXd::Zero(6);
  pb.qdot_A(1) = -v;
  const ImpactResult r = solve_impact(pb, stronge(e, 1.0));
  ASSERT_EQ(r.solver.status, SolverStatus::converged) << r.solver.message;
  const double P = (1.0 + e) * v * std::cos(theta) / (2.0 + std::cos(2.0 * theta));
  EXPECT_NEAR(r.P_N(0), P, 1e-10);
  EXPECT_NEAR(r.P_N(1), P, 1e-10);
  EXPECT_NEAR(r.D_NE(0), e * v * std::cos(theta), 1e-10);
  EXPECT_NEAR(r.qdot_E(0), 0.0, 1e-10);  // A keeps to the vertical
  expect_momentum(pb, r);
}

// Random coupled problems, e* < 1 and friction: momentum to rounding, never energy created
// (T_E − T_A from the velocities), never a contact driven in (D_NE from W_Nᵀq̇_E), |P_T| ≤ μ P_N,
// and the certificate agrees. As many dofs as rows at least: with fewer, contacts that stick can
// jam (compression never ends), and the run says so (not converged).
TEST(StrongeLzb, RandomCoupledProblemsDissipate) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  int solved = 0, tried = 0;
  for (int k = 0; k < 3000; ++k) {
    const int c = 2 + k % 2, n = 2 * c + k % 3;
    Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return u(rng); });
    ImpactProblem pb;
    pb.M = A * A.transpose() + 0.2 * Eigen::MatrixXd::Identity(n, n);
    pb.W_N = Eigen::MatrixXd::NullaryExpr(n, c, [&] { return u(rng); });
    pb.W_T = Eigen::MatrixXd::NullaryExpr(n, c, [&] { return u(rng); });
    pb.qdot_A = Eigen::VectorXd::NullaryExpr(n, [&] { return u(rng); });
    // Every contact approaching: q̇_A moved along M⁻¹W_N until each D_NA < 0.
    const Eigen::MatrixXd Minv_WN = pb.M.llt().solve(pb.W_N);
    const Eigen::VectorXd target = -Eigen::VectorXd::NullaryExpr(c, [&] { return pos(rng); });
    pb.qdot_A +=
        Minv_WN *
        (pb.W_N.transpose() * Minv_WN).ldlt().solve(target - pb.W_N.transpose() * pb.qdot_A);
    std::vector<double> es(static_cast<std::size_t>(c)), mus(static_cast<std::size_t>(c));
    for (int i = 0; i < c; ++i) {
      es[static_cast<std::size_t>(i)] = 0.95 * pos(rng);
      mus[static_cast<std::size_t>(i)] = 1.5 * pos(rng);
    }
    StrongeLaw law;
    law.e = es;
    law.coulomb = true;
    law.mu = mus;
    law.eta = k % 3 == 0 ? 1.5 : 1.0;
    const ImpactResult r = solve_impact(pb, law);
    if (r.solver.status == SolverStatus::unsupported) continue;  // a tangent ∥ its normal in M⁻¹
    ++tried;
    if (r.solver.status != SolverStatus::converged) continue;
    ++solved;
    const double T_A = kinetic(pb.M, pb.qdot_A);
    const double dT = kinetic(pb.M, r.qdot_E) - T_A;
    EXPECT_LE(dT, 1e-9 * T_A) << k;
    EXPECT_NEAR(r.energy_change, dT, 1e-9 * T_A) << k;
    const Eigen::VectorXd D_NE = pb.W_N.transpose() * r.qdot_E;
    const double v_scale = (pb.W_N.transpose() * pb.qdot_A).cwiseAbs().maxCoeff();
    for (int i = 0; i < c; ++i) {
      EXPECT_GE(D_NE(i), -1e-9 * v_scale) << k << " contact " << i;
      EXPECT_GE(r.P_N(i), 0.0) << k;
      EXPECT_LE(std::fabs(r.P_T(i)), law.mu[i] * r.P_N(i) * (1 + 1e-6) + 1e-12) << k;
    }
    expect_momentum(pb, r, 1e-12);
    EXPECT_TRUE(r.admissibility.admissible) << k << " " << to_string(r.admissibility.failed);
  }
  EXPECT_GT(tried, 2900);
  EXPECT_GE(solved, tried - tried / 100) << "more than 1% of the runs did not converge";
}

// One contact through the distributing law is the closed form, to 1e-10: through the kernel on
// random contacts of every regime, and through solve_impact with the method forced.
TEST(StrongeLzb, OneContactIsTheClosedForm) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    const double G_NN = 0.2 + pos(rng), G_TT = 0.2 + pos(rng);
    const double G_NT = 0.95 * u(rng) * std::sqrt(G_NN * G_TT);
    const double D_NA = -0.1 - pos(rng), D_TA = k % 5 == 0 ? 0.0 : 2.0 * u(rng);
    const double e = k % 7 == 0 ? 0.0 : pos(rng), mu = 2.0 * pos(rng);
    const detail::StrongeAnswer exact =
        detail::stronge_contact(G_NN, G_NT, G_TT, D_NA, D_TA, e, mu);
    Eigen::Matrix2d G;
    G << G_NN, G_NT, G_NT, G_TT;
    const detail::LzbContact contact{e, mu, 1.0 + pos(rng), 1.0};
    const detail::LzbAnswer a = detail::lzb_impact(G, Eigen::Vector2d(D_NA, D_TA), {&contact, 1});
    ASSERT_TRUE(a.converged) << k << " " << a.message;
    const double scale = std::max(exact.P_N, 1e-300);
    EXPECT_NEAR(a.P_N(0), exact.P_N, 1e-10 * scale) << k << " " << to_string(exact.regime);
    EXPECT_NEAR(a.P_T(0), exact.P_T, 1e-10 * scale) << k << " " << to_string(exact.regime);
    EXPECT_NEAR(a.energy_change, exact.energy_change, 1e-10 * scale * std::fabs(D_NA)) << k;
    EXPECT_NEAR(a.work_compression(0), exact.work_compression, 1e-10 * scale * std::fabs(D_NA));
  }
  // The public path with the method forced: the paper's bar, slip then stick.
  ImpactProblem bar;
  bar.M = Eigen::Vector3d(1.0, 1.0, 1.0 / 12).asDiagonal();
  bar.W_N = Eigen::Vector3d(0.0, 1.0, -0.5 * std::cos(std::numbers::pi / 4));
  bar.W_T = Eigen::Vector3d(1.0, 0.0, 0.5 * std::sin(std::numbers::pi / 4));
  bar.qdot_A = Eigen::Vector3d(2.0, -2.5, 0.0);
  SolverOptions forced;
  forced.method = SolverMethod::impulse_integration;
  const ImpactResult closed = solve_impact(bar, stronge(0.9, 1.0, 1.0));
  const ImpactResult integrated = solve_impact(bar, stronge(0.9, 1.0, 1.0), forced);
  ASSERT_EQ(closed.solver.method, SolverMethod::closed_form);
  ASSERT_EQ(integrated.solver.status, SolverStatus::converged) << integrated.solver.message;
  EXPECT_EQ(integrated.solver.method, SolverMethod::impulse_integration);
  EXPECT_NEAR(integrated.P_N(0), closed.P_N(0), 1e-10 * closed.P_N(0));
  EXPECT_NEAR(integrated.P_T(0), closed.P_T(0), 1e-10 * closed.P_N(0));
  // The closed form's residual measures the integrated answer, and the other way round.
  EXPECT_LE(law_residual(bar, stronge(0.9, 1.0, 1.0), integrated), 1e-10);
}

// The residual measures an answer: the integrated one passes, a perturbed one does not.
TEST(StrongeLzb, ResidualMeasuresTheAnswer) {
  const ImpactProblem pb = chain(Eigen::Vector3d(1.0, 0.0, 0.0));
  const ImpactLaw law = stronge(0.7, 1.5);
  const ImpactResult r = solve_impact(pb, law);
  ASSERT_EQ(r.solver.status, SolverStatus::converged) << r.solver.message;
  EXPECT_LE(law_residual(pb, law, r), 1e-10);
  ImpactResult off = r;
  off.P_N(1) += 1e-6;
  EXPECT_GT(law_residual(pb, law, off), 1e-7);
}

// With one exponent only the stiffnesses' ratios matter; a stiffer contact takes more of the blow.
TEST(StrongeLzb, OnlyStiffnessRatiosMatter) {
  const ImpactProblem pb = chain(Eigen::Vector4d(1.0, 0.0, 0.0, 0.0));
  StrongeLaw a = stronge(0.75, 1.5), b = a;
  a.stiffness = std::vector<double>{1.0, 2.0, 3.0};
  b.stiffness = std::vector<double>{1e5, 2e5, 3e5};
  const ImpactResult ra = solve_impact(pb, a), rb = solve_impact(pb, b);
  ASSERT_EQ(ra.solver.status, SolverStatus::converged) << ra.solver.message;
  ASSERT_EQ(rb.solver.status, SolverStatus::converged) << rb.solver.message;
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(ra.qdot_E(i), rb.qdot_E(i), 1e-9);
  EXPECT_EQ(a.describe(), "stronge(e=0.75, eta=1.5, stiffness=[1, 2, 3])");
}

TEST(StrongeLzb, BadParametersRefusedByName) {
  auto refused = [](const StrongeLaw& law, int contacts) -> std::string {
    try {
      law.validate(contacts);
    } catch (const InvalidArgument& e) {
      return e.name();
    }
    return "accepted";
  };
  StrongeLaw law = stronge(0.5, 1.0);
  EXPECT_EQ(refused(law, 2), "accepted");
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {0.0, -1.0, inf, std::numeric_limits<double>::quiet_NaN()}) {
    StrongeLaw eta = law;
    eta.eta = bad;
    EXPECT_EQ(refused(eta, 2), "law.eta") << bad;
    StrongeLaw stiffness = law;
    stiffness.stiffness = bad;
    EXPECT_EQ(refused(stiffness, 2), "law.stiffness") << bad;
  }
  law.stiffness = std::vector<double>{1.0, -2.0};
  EXPECT_EQ(refused(law, 2), "law.stiffness[1]");
  law.stiffness = std::vector<double>{1.0, 2.0, 3.0};
  EXPECT_EQ(refused(law, 2), "law.stiffness");

  // The problem file names its own keys.
  const std::string head =
      R"({"M": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "W_N": [[-1, 0], [1, -1], [0, 1]], )"
      R"("qdot_A": [1, 0, 0], )";
  for (const auto& [text, key] :
       {std::pair{R"({"type": "stronge", "e": 0.5, "eta": 0})", "law.eta"},
        std::pair{R"({"type": "stronge", "e": 0.5, "eta": [1.5, -1]})", "law.eta[1]"},
        std::pair{R"({"type": "stronge_coulomb", "e": 0.5, "mu": 1, "stiffness": -3})",
                  "law.stiffness"},
        std::pair{R"({"type": "stronge", "e": 0.5, "stiffness": "stiff"})", "law.stiffness"},
        std::pair{R"({"type": "stronge", "e": 0.5, "k": 1})", "law.k"}}) {
    try {
      (void)io::parse_problem_file(head + R"("law": )" + text + "}",
                                   PotentialRegistry::with_builtins());
      ADD_FAILURE() << text;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.name(), key) << text;
    }
  }
  const io::ProblemFile f = io::parse_problem_file(
      head + R"("law": {"type": "stronge", "e": 0.5, "eta": 1.5, "stiffness": 2}})",
      PotentialRegistry::with_builtins());
  EXPECT_EQ(f.law.describe(), "stronge(e=0.5, eta=1.5, stiffness=2)");
}

}  // namespace
}  // namespace fremond
