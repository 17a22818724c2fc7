// The persistent-contact step: Signorini and Coulomb hold on random problems, the impulse balance
// holds, the energy identity P·z, and the cases known by hand (resting ball, flat bar).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "fremond/simulation/persistent_contact.hpp"

namespace fremond {
namespace {

// Checks every condition of the law on a solution, independently of the mode the solver chose.
void expect_law_holds(const PersistentContactProblem& pb, const PersistentContactResult& r,
                      const char* what) {
  ASSERT_TRUE(r.solved) << what;
  Eigen::Vector3d impulse = Eigen::Vector3d::Zero();
  double vs = 1e-300, ps = 1e-300;
  for (int k = 0; k < pb.contacts; ++k) {
    impulse += r.P_N[k] * pb.W_N[k] + r.P_T[k] * pb.W_T[k];
    vs = std::max({vs, std::fabs(pb.W_N[k].dot(pb.v_free)), std::fabs(pb.W_T[k].dot(pb.v_free)),
                   std::fabs(pb.W_T[k].dot(pb.v_before))});
    ps = std::max({ps, std::fabs(r.P_N[k]), std::fabs(r.P_T[k])});
  }
  // M (v⁺ − v_free) = W P.
  EXPECT_LT((r.v - pb.v_free - pb.minv.cwiseProduct(impulse)).norm(), 1e-13 * (1 + r.v.norm()));
  const double tv = 1e-9 * vs, tp = 1e-9 * ps;
  for (int k = 0; k < pb.contacts; ++k) {
    const auto vel = [&](StepVelocity which, const Eigen::Vector3d& w) {
      return which == StepVelocity::mean ? 0.5 * w.dot(pb.v_before + r.v) : w.dot(r.v);
    };
    const double vn = vel(pb.normal, pb.W_N[k]), vt = vel(pb.friction, pb.W_T[k]);
    const double pn = r.P_N[k], pt = r.P_T[k], mu = pb.mu[k];
    // Signorini: V_N ≥ 0, P_N ≥ 0, P_N V_N = 0.
    EXPECT_GE(vn, -tv) << what << " contact " << k;
    EXPECT_GE(pn, -tp) << what;
    EXPECT_LE(std::fabs(pn * vn), tp * tv * 1e3 + 1e-9 * std::fabs(pn) * vs) << what;
    // Coulomb: |P_T| ≤ μP_N; V_T = 0 inside the cone; P_T = −μP_N sign(V_T) when slipping.
    EXPECT_LE(std::fabs(pt), mu * pn + tp) << what;
    if (std::fabs(vt) > tv) {
      EXPECT_NEAR(pt, -mu * pn * (vt > 0 ? 1 : -1), tp) << what;
    }
  }
}

PersistentContactProblem random_problem(std::mt19937_64& rng, int c) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PersistentContactProblem pb;
  pb.minv = {1.0 / (0.5 + std::fabs(u(rng))), 0.0, 1.0 / (0.05 + std::fabs(u(rng)))};
  pb.minv.y() = pb.minv.x();
  pb.contacts = c;
  for (int k = 0; k < c; ++k) {
    const double angle = 0.3 * u(rng);  // obstacles near the ground, so that contacts interact
    const Eigen::Vector2d n(std::sin(angle), std::cos(angle)), t(n.y(), -n.x());
    const Eigen::Vector2d a(0.6 * u(rng), -0.2 - 0.2 * std::fabs(u(rng)));
    pb.W_N[k] = {n.x(), n.y(), a.x() * n.y() - a.y() * n.x()};
    pb.W_T[k] = {t.x(), t.y(), a.x() * t.y() - a.y() * t.x()};
    pb.mu[k] = k == 1 ? 0.0 : 0.8 * std::fabs(u(rng));
  }
  pb.v_before = {u(rng), 0.3 * u(rng), u(rng)};
  for (int k = 0; k < c; ++k)  // the contacts start at rest or approaching, as in a step
    pb.v_before -= std::max(0.0, pb.W_N[k].dot(pb.v_before)) * pb.minv.cwiseProduct(pb.W_N[k]) /
                   pb.W_N[k].dot(pb.minv.cwiseProduct(pb.W_N[k]));
  pb.v_free = pb.v_before + Eigen::Vector3d(0.0, -9.81e-3, 0.0);
  return pb;
}

TEST(PersistentContact, SignoriniAndCoulombHoldOnRandomProblems) {
  std::mt19937_64 rng(3);
  int solved = 0, total = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int c = 1 + trial % 3;
    PersistentContactProblem pb = random_problem(rng, c);
    for (StepVelocity n : {StepVelocity::end, StepVelocity::mean}) {
      for (StepVelocity f : {StepVelocity::end, StepVelocity::mean}) {
        pb.normal = n;
        pb.friction = f;
        const PersistentContactResult r = solve_persistent_contact(pb);
        ++total;
        if (!r.solved) continue;  // a Painlevé-type case may have no solution
        ++solved;
        expect_law_holds(pb, r, "random");
        // On the mean (both), the step never creates energy: P·z ≤ 0 (P_N z_N = 0, P_T z_T ≤ 0).
        if (n == StepVelocity::mean && f == StepVelocity::mean) {
          double rounding = 0.0;
          EXPECT_LE(step_energy(pb, r, &rounding), rounding);
        }
        // The warm start returns the same answer.
        const PersistentContactResult w = solve_persistent_contact(pb, r.mode.data());
        EXPECT_EQ(w.modes_tried, 1);
        EXPECT_LT((w.v - r.v).norm(), 1e-14 * (1 + r.v.norm()));
      }
    }
  }
  EXPECT_GT(solved, total * 95 / 100);
}

// solve_dissipative_step forms once what its two solves share (the scales, and for one contact
// the Delassus entries and contact velocities). It must answer what those two solves answer, bit
// for bit: Coulomb on the end velocity, or on the mean where that creates energy.
TEST(PersistentContact, TheDissipativeStepIsTheTwoSolvesItStandsFor) {
  constexpr int kMax = PersistentContactProblem::kMax;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int on_the_mean = 0, created = 0, mean_failed = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const int c = 1 + trial % 3;
    PersistentContactProblem pb = random_problem(rng, c);
    // Slips as slow as what one step of gravity adds, where Coulomb on the end velocity can
    // create energy (persistent_contact.hpp) and the second solve is needed.
    const Eigen::Vector3d g_step = pb.v_free - pb.v_before;
    pb.v_before *= std::pow(10.0, -4.0 * u(rng));
    pb.v_free = pb.v_before + g_step;
    std::array<ContactMode, kMax> modes{};
    for (int k = 0; k < c; ++k) modes[k] = static_cast<ContactMode>(rng() % 4);
    const ContactMode* warm = trial % 2 ? modes.data() : nullptr;

    PersistentContactProblem ref = pb;
    ref.normal = StepVelocity::mean;
    ref.friction = StepVelocity::end;
    PersistentContactResult expected = solve_persistent_contact(ref, warm);
    double rounding = 0.0;
    if (!(expected.solved && step_energy(ref, expected, &rounding) <= rounding)) {
      ref.friction = StepVelocity::mean;
      ++on_the_mean;
      const PersistentContactResult m = solve_persistent_contact(ref, warm);
      if (m.solved)
        expected = m;
      else
        ++mean_failed;
    }

    PersistentContactProblem mine = pb;
    const PersistentContactResult got = solve_dissipative_step(mine, warm);
    ASSERT_EQ(got.solved, expected.solved) << "trial " << trial;
    EXPECT_EQ(mine.normal, ref.normal);
    EXPECT_EQ(mine.friction, ref.friction) << "trial " << trial;
    EXPECT_EQ(std::memcmp(got.v.data(), expected.v.data(), sizeof(double) * 3), 0) << trial;
    if (!got.solved) continue;
    for (int k = 0; k < c; ++k) {
      EXPECT_EQ(std::memcmp(&got.P_N[k], &expected.P_N[k], sizeof(double)), 0) << trial;
      EXPECT_EQ(std::memcmp(&got.P_T[k], &expected.P_T[k], sizeof(double)), 0) << trial;
      EXPECT_EQ(got.mode[k], expected.mode[k]) << trial;
    }
    expect_law_holds(mine, got, "dissipative step");
    // No energy created beyond rounding. step_energy's own bound scales with |v_before| + |v⁺|;
    // the zero mean velocity of a sticking contact is also rounded at the scale of v_free, from
    // which v⁺ = v_free + M⁻¹WP is formed.
    double rd = 0.0, scale = 0.0;
    const double e = step_energy(mine, got, &rd);
    for (int k = 0; k < c; ++k)
      scale += (std::fabs(got.P_N[k]) * mine.W_N[k].cwiseAbs() +
                std::fabs(got.P_T[k]) * mine.W_T[k].cwiseAbs())
                   .dot(mine.v_free.cwiseAbs() + mine.v_before.cwiseAbs());
    if (e > rd + 64 * std::numeric_limits<double>::epsilon() * scale) ++created;
  }
  EXPECT_GT(on_the_mean, 100);      // the second solve is exercised
  EXPECT_LE(created, mean_failed);  // energy only where no mode on the mean exists
}

TEST(PersistentContact, ARestingBallCarriesItsWeight) {
  // v_before = 0, one step of gravity: P_N = h m g, v⁺ = 0, no friction needed.
  const double m = 2.0, h = 1e-3, g = 9.81, rho = 0.1;
  PersistentContactProblem pb;
  pb.minv = {1 / m, 1 / m, 1 / (0.4 * m * rho * rho)};
  pb.contacts = 1;
  pb.W_N[0] = {0, 1, 0};
  pb.W_T[0] = {1, 0, rho};
  pb.mu[0] = 0.5;
  pb.v_free = {0, -h * g, 0};
  for (StepVelocity n : {StepVelocity::end, StepVelocity::mean}) {
    pb.normal = n;
    const PersistentContactResult r = solve_persistent_contact(pb);
    ASSERT_TRUE(r.solved);
    EXPECT_NEAR(r.P_N[0], h * m * g, 1e-15);
    EXPECT_NEAR(r.P_T[0], 0.0, 1e-15);
    EXPECT_LT(r.v.norm(), 1e-15);
  }
  // Sliding at 1 m/s: Coulomb's impulse μ h m g slows it down, on the end velocity.
  pb.normal = StepVelocity::end;
  pb.v_before = {1.0, 0.0, 0.0};
  pb.v_free = {1.0, -h * g, 0};
  const PersistentContactResult s = solve_persistent_contact(pb);
  ASSERT_TRUE(s.solved);
  EXPECT_EQ(s.mode[0], ContactMode::slide_forward);
  EXPECT_NEAR(s.P_N[0], h * m * g, 1e-15);
  EXPECT_NEAR(s.P_T[0], -0.5 * h * m * g, 1e-15);
}

TEST(PersistentContact, AFlatBarStickingOnBothEndsIsSolvedDespiteDependentRows) {
  // Two contacts, four rows, three degrees of freedom: G is singular.
  const double l = 0.5;
  PersistentContactProblem pb;
  pb.minv = {1.0, 1.0, 3.0 / (l * l)};
  pb.contacts = 2;
  pb.W_N[0] = {0, 1, -l};
  pb.W_T[0] = {1, 0, 0};
  pb.W_N[1] = {0, 1, l};
  pb.W_T[1] = {1, 0, 0};
  pb.mu = {1.0, 1.0};
  pb.v_before = {0.001, 0, 0};
  pb.v_free = {0.001, -9.81e-3, 0};
  const PersistentContactResult r = solve_persistent_contact(pb);
  expect_law_holds(pb, r, "flat bar");
  EXPECT_LT(r.v.norm(), 1e-15);
  EXPECT_NEAR(r.P_N[0] + r.P_N[1], 9.81e-3, 1e-15);
  EXPECT_NEAR(r.P_N[0], r.P_N[1], 1e-15);
  EXPECT_NEAR(r.P_T[0] + r.P_T[1], -0.001, 1e-15);
}

}  // namespace
}  // namespace fremond
