// The prepared solver (impact_solver.hpp) against the one-shot solve_impact, a second path through
// the same chain that validates and factors at every call: every answer equal to the last bit,
// over velocities, configurations and laws; the point mass against its closed form; and bad input
// refused with the previous state kept.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "fremond/fremond.hpp"
#include "support/disk_pile.hpp"
#include "support/fixtures.hpp"

namespace fremond {
namespace {

using namespace fremond::fixtures;

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

template <class V>
bool same_bits(const V& a, const V& b) {
  if (a.size() != b.size()) return false;
  for (Eigen::Index i = 0; i < a.size(); ++i)
    if (!same_bits(static_cast<double>(a(i)), static_cast<double>(b(i)))) return false;
  return true;
}

/// Every member of two results equal to the last bit; the first that differs is named.
template <int N, int C>
std::string first_difference(const ImpactResultT<N, C>& a, const ImpactResultT<N, C>& b) {
  const std::vector<std::pair<const char*, bool>> checks{
      {"qdot_E", same_bits(a.qdot_E, b.qdot_E)},
      {"P_N", same_bits(a.P_N, b.P_N)},
      {"P_T", same_bits(a.P_T, b.P_T)},
      {"D_NA", same_bits(a.D_NA, b.D_NA)},
      {"D_TA", same_bits(a.D_TA, b.D_TA)},
      {"D_NE", same_bits(a.D_NE, b.D_NE)},
      {"D_TE", same_bits(a.D_TE, b.D_TE)},
      {"P_N_reaction", same_bits(a.P_N_reaction, b.P_N_reaction)},
      {"has_phases", a.has_phases == b.has_phases},
      {"P_NC", !a.has_phases || same_bits(a.P_NC, b.P_NC)},
      {"qdot_C", !a.has_phases || same_bits(a.qdot_C, b.qdot_C)},
      {"takes_part", a.takes_part == b.takes_part},
      {"energy_change", same_bits(a.energy_change, b.energy_change)},
      {"unique", a.unique == b.unique},
      {"solutions_found", a.solutions_found == b.solutions_found},
      {"status", a.solver.status == b.solver.status},
      {"method", a.solver.method == b.solver.method},
      {"residual", same_bits(a.solver.residual, b.solver.residual)},
      {"iterations", a.solver.iterations == b.solver.iterations},
      {"attempt_count", a.solver.attempt_count == b.solver.attempt_count},
      {"message", a.solver.message == b.solver.message},
      {"admissible", a.admissibility.admissible == b.admissibility.admissible},
      {"failed", a.admissibility.failed == b.admissibility.failed},
      {"total", same_bits(a.admissibility.total, b.admissibility.total)},
      {"per_contact", same_bits(a.admissibility.per_contact, b.admissibility.per_contact)},
      {"penetration", same_bits(a.admissibility.penetration, b.admissibility.penetration)},
  };
  for (const auto& [name, same] : checks)
    if (!same) return name;
  return "";
}

std::vector<std::pair<std::string, ImpactLaw>> every_law() {
  const auto [p3, viscous, coulomb] = bar_fremond_laws();
  return {{"newton", ImpactLaw::newton(0.9)},
          {"poisson", ImpactLaw::poisson(0.9)},
          {"newton_coulomb", ImpactLaw::newton_coulomb(0.9, 0.5)},
          {"poisson_coulomb", ImpactLaw::poisson_coulomb(0.9, 0.5)},
          {"fremond p3 viscous", viscous},
          {"fremond p3 coulomb", coulomb},
          {"stronge_coulomb", StrongeLaw{0.8, true, 0.5}}};
}

/// Velocities of every kind for an n-dof body: approaching, separating, grazing, at rest; each
/// followed by itself 1e4 times smaller, whose tolerance (relative to the velocities) is too.
std::vector<Eigen::VectorXd> velocities(int n, std::uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::vector<Eigen::VectorXd> v;
  v.push_back(Eigen::VectorXd::Zero(n));
  for (int k = 0; k < count; ++k) {
    Eigen::VectorXd q(n);
    for (int i = 0; i < n; ++i) q(i) = u(rng);
    v.push_back(q);
    v.push_back(1e-4 * q);
  }
  return v;
}

// Stronge's law answers one contact (the bar, the point mass) or none coupled; the others every
// problem. Each answer of the prepared solver is solve_impact's on the same data, bit for bit.
TEST(ImpactSolver, EveryAnswerIsSolveImpactsToTheLastBit) {
  std::vector<std::pair<std::string, ImpactProblem>> problems{
      {"bar", to_dynamic(bar_first_impact(true))},
      {"planar point mass", to_dynamic(planar_point_mass(1.0, true))},
      {"flat bar", to_dynamic(flat_bar_two_contacts(true))},
      {"two point masses", to_dynamic(two_point_masses(true))},
      {"plate on 6 contacts", plate_many_contacts(6, true)},
      {"plate on 8 contacts", plate_many_contacts(8, true)},
      // The sweeps' storage, kept from one solve to the next, on a rigid body (velocity factors)
      // and on a regular G, as the contacts that approach change with the velocity.
      {"plate on 16 contacts", plate_many_contacts(16, true)},
      {"random body on 12 contacts", random_problem_any(24, 12, 0, true)}};
  for (int i = 0; i < 3; ++i)
    problems.push_back({"random " + std::to_string(i), random_problem_any(6, 3, i, true)});
  int compared = 0;
  for (const auto& [pname, pb] : problems)
    for (const auto& [lname, law] : every_law()) {
      ImpactSolver solver(pb, law);
      ImpactResult kept;
      ImpactProblem one_shot = pb;
      for (const Eigen::VectorXd& q : velocities(pb.dofs(), 7, 12)) {
        one_shot.qdot_A = q;
        const ImpactResult expected = solve_impact(one_shot, law);
        // solve_into writes the same answer into a result that held another one (the last
        // velocity's), and leaves the solver's own result alone.
        const ImpactResult before = solver.result();
        solver.solve_into(q, kept);
        EXPECT_EQ(first_difference(kept, expected), "")
            << lname << " on " << pname << " at qdot_A = " << q.transpose() << " (solve_into)";
        EXPECT_EQ(first_difference(solver.result(), before), "");
        const ImpactResult& got = solver.solve(q);
        EXPECT_EQ(first_difference(got, expected), "")
            << lname << " on " << pname << " at qdot_A = " << q.transpose();
        ++compared;
      }
    }
  EXPECT_EQ(compared, 11 * 7 * 25);
}

// The pile of 6 × 6 disks in dense form (66 contacts on 108 dofs, G singular): the classical chain
// sweeps it with Anderson mixing (beyond 64 contacts), whose history the prepared solver keeps
// room for from one solve to the next. Each answer is still solve_impact's, bit for bit, and
// meets the law.
TEST(ImpactSolver, MixedSweepsKeptFromSolveToSolveChangeNoBit) {
  const SparseImpactProblem sparse = fixtures::disk_pile(6);
  ImpactProblem pb;
  pb.M = Eigen::MatrixXd(sparse.M);
  pb.W_N = Eigen::MatrixXd(sparse.W_N);
  pb.W_T = Eigen::MatrixXd(sparse.W_T);
  pb.qdot_A = sparse.qdot_A;
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.0, 0.5);
  ImpactSolver solver(pb, law);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.5, 1.5);
  for (int k = 0; k < 3; ++k) {
    ImpactProblem one_shot = pb;
    for (Eigen::Index i = 0; i < pb.qdot_A.size(); ++i) one_shot.qdot_A(i) *= u(rng);
    const ImpactResult expected = solve_impact(one_shot, law);
    ASSERT_TRUE(expected.ok()) << expected.solver.message;
    EXPECT_LE(expected.solver.residual, SolverOptions{}.tolerance);
    EXPECT_EQ(first_difference(solver.solve(one_shot.qdot_A), expected), "") << "velocity " << k;
  }
}

TEST(ImpactSolver, SmallSolverMatchesSolveImpactAndTheDynamicSolver) {
  const SmallImpactProblem pb = flat_bar_two_contacts(true);
  const ImpactLaw law = ImpactLaw::poisson_coulomb(0.7, 0.4);
  SmallImpactSolver small(pb, law);
  ImpactSolver heap(to_dynamic(pb), law);
  SmallImpactProblem one_shot = pb;
  for (const Eigen::VectorXd& q : velocities(3, 11, 20)) {
    one_shot.qdot_A = q;
    const SmallImpactResult expected = solve_impact(one_shot, law);
    EXPECT_EQ(first_difference(small.solve(q), expected), "") << q.transpose();
    EXPECT_EQ(first_difference(heap.solve(q), to_dynamic(expected)), "") << q.transpose();
  }
}

// A point mass m falling at v onto the ground under Newton's law: q̇_E = −e v, P_N = m(1 + e)|v|.
TEST(ImpactSolver, PointMassMeetsNewtonsClosedFormAtEveryVelocity) {
  const double m = 2.5, e = 0.6;
  ImpactSolver solver(point_mass(m, -1.0), ImpactLaw::newton(e));
  for (double v : {-1e-6, -0.3, -1.0, -7.0, -1e6}) {
    const ImpactResult& r = solver.solve(Eigen::VectorXd::Constant(1, v));
    ASSERT_TRUE(r.ok());
    EXPECT_NEAR(r.qdot_E(0), -e * v, 1e-15 * std::abs(v));
    EXPECT_NEAR(r.P_N(0), m * (1 + e) * -v, 1e-15 * m * std::abs(v));
    EXPECT_NEAR(r.energy_change, 0.5 * m * v * v * (e * e - 1), 1e-14 * m * v * v);
    EXPECT_TRUE(r.admissibility.admissible);
  }
  // Moving away: no impact, no percussion.
  const ImpactResult& away = solver.solve(Eigen::VectorXd::Constant(1, 0.4));
  EXPECT_EQ(away.P_N(0), 0.0);
  EXPECT_EQ(away.qdot_E(0), 0.4);
}

// update(): the next configuration's answers are solve_impact's on it; the bar turned from θ =
// π/4 to π/3 changes W, not M.
TEST(ImpactSolver, UpdateTakesTheNextConfiguration) {
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.9, 1.0);
  const Eigen::Vector3d qdot(2.0, -3.5, 0.5);
  ImpactSolver solver(bar(std::numbers::pi / 4, qdot, false, true), law);
  const ImpactProblem next = bar(std::numbers::pi / 3, qdot, false, true);
  solver.update(next.M, next.W_N, next.W_T);
  EXPECT_EQ(solver.result().solver.status, SolverStatus::not_run);
  EXPECT_EQ(first_difference(solver.solve(qdot), solve_impact(next, law)), "");
  // A law updated: the same.
  solver.update_law(ImpactLaw::poisson_coulomb(0.5, 0.2));
  EXPECT_EQ(
      first_difference(solver.solve(), solve_impact(next, ImpactLaw::poisson_coulomb(0.5, 0.2))),
      "");
}

TEST(ImpactSolver, BadVelocityIsRefusedAndThePreviousOneKept) {
  const ImpactProblem pb = to_dynamic(bar_first_impact(true));
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.9, 1.0);
  ImpactSolver solver(pb, law);
  SmallImpactSolver small(to_small(pb), law);
  const ImpactResult expected = solve_impact(pb, law);
  auto refuses = [](auto& s, const Eigen::VectorXd& q, const std::string& why) {
    try {
      s.solve(q);
      ADD_FAILURE() << "accepted qdot_A = " << q.transpose();
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.name().rfind("qdot_A", 0), 0u) << e.name();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  for (auto* s : {&solver}) {
    refuses(*s, Eigen::VectorXd::Zero(7), "must have 3 entries");
    refuses(*s, Eigen::Vector3d(1.0, std::nan(""), 0.0), "finite");
    refuses(*s, Eigen::Vector3d(1e200, 1e200, 0.0), "overflows");
    EXPECT_EQ(first_difference(s->solve(), expected), "");
  }
  refuses(small, Eigen::VectorXd::Zero(7), "must have 3 entries");
  refuses(small, Eigen::Vector3d(std::numeric_limits<double>::infinity(), 0.0, 0.0), "finite");
  EXPECT_EQ(first_difference(small.solve(), to_small(expected)), "");
}

// The solver admits most velocities by bounds of its configuration and tests the rest as
// solve_impact does: near where the kinetic energy overflows (|q̇| about 1e154 on the bar), both
// accept and refuse the same velocities, with the same answers.
TEST(ImpactSolver, VelocitiesNearOverflowAreJudgedAsSolveImpactJudgesThem) {
  const ImpactProblem pb = to_dynamic(bar_first_impact(true));
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.9, 1.0);
  ImpactSolver solver(pb, law);
  SmallImpactSolver small(to_small(pb), law);
  int accepted = 0, refused = 0;
  for (double s : {1.0, 1e100, 1e149, 1e150, 1e151, 1e152, 1e153, 1e154, 1e155, 1e160, 1e200}) {
    ImpactProblem p = pb;
    p.qdot_A = Eigen::Vector3d(0.3 * s, -s, 0.1 * s);
    bool one_shot_refuses = false;
    ImpactResult expected;
    try {
      expected = solve_impact(p, law);
    } catch (const InvalidArgument&) {
      one_shot_refuses = true;
    }
    for (bool use_small : {false, true}) {
      bool prepared_refuses = false;
      try {
        if (use_small) {
          EXPECT_EQ(first_difference(to_dynamic(small.solve(p.qdot_A)), expected), "") << s;
        } else {
          EXPECT_EQ(first_difference(solver.solve(p.qdot_A), expected), "") << s;
        }
      } catch (const InvalidArgument& e) {
        prepared_refuses = true;
        EXPECT_EQ(e.name(), "qdot_A") << e.what();
      }
      EXPECT_EQ(prepared_refuses, one_shot_refuses) << "|qdot_A| = " << s;
    }
    (one_shot_refuses ? refused : accepted) += 1;
  }
  // Both sides of the boundary were tried, the bounds' own limit (1e150) among the accepted.
  EXPECT_GE(accepted, 6);
  EXPECT_GE(refused, 3);
}

TEST(ImpactSolver, BadConfigurationIsRefusedAndThePreviousOneKept) {
  const ImpactProblem pb = to_dynamic(bar_first_impact(true));
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.9, 1.0);
  ImpactProblem not_spd = pb;
  not_spd.M(2, 2) = -1.0;
  EXPECT_THROW(
      {
        try {
          ImpactSolver s(not_spd, law);
        } catch (const InvalidArgument& e) {
          EXPECT_EQ(e.name(), "M");
          throw;
        }
      },
      InvalidArgument);
  ImpactSolver solver(pb, law);
  auto refused_name = [&](auto&& f) {
    try {
      f();
    } catch (const InvalidArgument& e) {
      return e.name();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refused_name([&] { solver.update(not_spd.M, pb.W_N, pb.W_T); }), "M");
  EXPECT_EQ(refused_name([&] { solver.update(Eigen::MatrixXd::Identity(4, 4), pb.W_N, pb.W_T); }),
            "M");
  EXPECT_EQ(refused_name([&] { solver.update(pb.M, Eigen::MatrixXd::Zero(3, 2), pb.W_T); }), "W_N");
  EXPECT_EQ(refused_name([&] { solver.update_law(ImpactLaw::newton({0.5, 0.5})); }), "law.e");
  EXPECT_EQ(refused_name([&] { solver.update_law(ImpactLaw::newton(1.5)); }), "law.e");
  EXPECT_EQ(first_difference(solver.solve(), solve_impact(pb, law)), "");
}

}  // namespace
}  // namespace fremond
