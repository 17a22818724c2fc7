// The sparse path (sparse/sparse_solver.hpp): against hand-derived answers, against the dense
// solvers on the same problems, and on Siconos's granular problems, where each contact's law is
// checked here from D_E = D_A + G P, independently of the solver's own residual.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "fremond/fremond.hpp"
#include "fremond/io/siconos_file.hpp"
#include "fremond/sparse/sparse_solver.hpp"
#include "support/disk_pile.hpp"
#include "support/test_problems.hpp"
#include "support/why.hpp"

namespace fremond {
namespace {

SparseMatrix sparse(const Eigen::MatrixXd& A) {
  return A.sparseView(0.0, 0.0);
}

SparseImpactProblem to_sparse(const ImpactProblem& pb) {
  SparseImpactProblem s;
  s.M = sparse(pb.M);
  s.W_N = sparse(pb.W_N);
  s.W_T = pb.has_tangential() ? sparse(pb.W_T) : SparseMatrix(pb.dofs(), 0);
  s.w_N = pb.w_N;
  s.w_T = pb.has_tangential() ? pb.w_T : Eigen::VectorXd();
  s.qdot_A = pb.qdot_A;
  return s;
}

// Three equal disks (m = 1, J = 0.1, radius 0.5) stacked on the ground, all falling at v = 2:
// q = (x, y, θ) per disk; contact 0 the ground under disk 0, contact k disk k−1 under disk k.
// Normal rows: y of the upper body minus y of the lower; tangent rows: x plus the rolling terms.
SparseImpactProblem falling_stack(double v, double spin = 0.0) {
  const int n = 9;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n), WN = Eigen::MatrixXd::Zero(n, 3),
                  WT = Eigen::MatrixXd::Zero(n, 3);
  for (int b = 0; b < 3; ++b) M.block(3 * b, 3 * b, 3, 3).diagonal() << 1.0, 1.0, 0.1;
  const double r = 0.5;
  WN(1, 0) = 1.0;  // ground under disk 0: its lowest point's velocity x − r θ̇
  WT(0, 0) = 1.0;
  WT(2, 0) = -r;
  for (int k = 1; k < 3; ++k) {
    const int lo = 3 * (k - 1), hi = 3 * k;
    WN(hi + 1, k) = 1.0;
    WN(lo + 1, k) = -1.0;
    WT(hi, k) = 1.0;  // slip of the upper disk's lowest point on the lower disk's highest
    WT(hi + 2, k) = -r;
    WT(lo, k) = -1.0;
    WT(lo + 2, k) = -r;
  }
  SparseImpactProblem pb;
  pb.M = sparse(M);
  pb.W_N = sparse(WN);
  pb.W_T = sparse(WT);
  pb.qdot_A = Eigen::VectorXd::Zero(n);
  for (int b = 0; b < 3; ++b) {
    pb.qdot_A(3 * b + 1) = -v;
    pb.qdot_A(3 * b + 2) = spin;
  }
  return pb;
}

// Falling together at v with e = 0, the stack stops as one: the ground takes 3 m v, the contact
// above it 2 m v, the top one m v; nothing slides, so no tangential percussion; T_E − T_A = −T_A.
TEST(SparseSolver, FallingStackStopsAsOneBody) {
  const SparseImpactProblem pb = falling_stack(2.0);
  const ImpactResult r = solve_impact(pb, ImpactLaw::newton_coulomb(0.0, 0.5));
  ASSERT_TRUE(r.ok()) << r.solver.message;
  const double expected[3] = {6.0, 4.0, 2.0};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(r.P_N(k), expected[k], 1e-9) << k;
    EXPECT_NEAR(r.P_T(k), 0.0, 1e-12) << k;
  }
  EXPECT_LE(r.qdot_E.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(r.energy_change, -6.0, 1e-9);
  EXPECT_NEAR(r.admissibility.kinetic_energy_A, 6.0, 1e-15);
  EXPECT_TRUE(r.admissibility.admissible);
}

// Newton's law with e = 1 on the same stack, frictionless: equal masses in a column exchange
// velocities (the 1-D chain: G = tridiag(−1, 2, −1) without the ground's end) — here every
// contact closes at once, and momentum with the ground's percussion and energy balance:
// M(q̇_E − q̇_A) = W P, T_E = T_A.
TEST(SparseSolver, ElasticStackKeepsEnergyAndBalancesMomentum) {
  SparseImpactProblem pb = falling_stack(1.0);
  pb.W_T.resize(pb.dofs(), 0);
  const ImpactResult r = solve_impact(pb, ImpactLaw::newton(1.0), {.tolerance = 1e-14});
  ASSERT_TRUE(r.ok()) << r.solver.message;
  const Eigen::VectorXd balance =
      Eigen::MatrixXd(pb.M) * (r.qdot_E - pb.qdot_A) - Eigen::MatrixXd(pb.W_N) * r.P_N;
  EXPECT_LE(balance.cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(r.energy_change, 0.0, 1e-12);
  // Every contact leaves as fast as it approached (D_NA = −1 at the ground, 0 between disks).
  EXPECT_NEAR(r.D_NE(0), 1.0, 1e-12);
}

// The same answers as the dense solvers on random problems (12 dofs, 3-5 contacts, Newton +
// Coulomb), wherever the dense answer is unique; G is then positive definite, so Gauss–Seidel
// converges to it.
TEST(SparseSolver, AgreesWithTheDenseSolvers) {
  int compared = 0;
  for (int index = 0; index < 120; ++index) {
    const int c = 3 + index % 3;
    const ImpactProblem dense = fixtures::random_problem_any(12, c, index, true);
    const ImpactLaw law = ImpactLaw::newton_coulomb(0.5, 0.3);
    const ImpactResult d = solve_impact(dense, law);
    if (!d.ok() || !d.unique) continue;
    const ImpactResult s = solve_impact(to_sparse(dense), law, {.tolerance = 1e-15});
    ASSERT_TRUE(s.ok()) << index << ": " << s.solver.message;
    const double scale = 1.0 + d.P_N.cwiseAbs().maxCoeff();
    EXPECT_LE((s.P_N - d.P_N).cwiseAbs().maxCoeff(), 1e-11 * scale) << index;
    EXPECT_LE((s.P_T - d.P_T).cwiseAbs().maxCoeff(), 1e-11 * scale) << index;
    EXPECT_LE((s.qdot_E - d.qdot_E).cwiseAbs().maxCoeff(), 1e-11 * scale) << index;
    EXPECT_NEAR(s.energy_change, d.energy_change, 1e-11 * scale * scale) << index;
    EXPECT_EQ(s.admissibility.admissible, d.admissibility.admissible) << index;
    ++compared;
  }
  EXPECT_GE(compared, 30);
}

// A warm start from the answer is already the answer: the first sweep finds it.
TEST(SparseSolver, WarmStartFromTheAnswerEndsAtOnce) {
  const SparseImpactProblem pb = falling_stack(2.0, 3.0);
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.2, 0.5);
  const ImpactResult cold = solve_impact(pb, law, {.tolerance = 1e-14});
  ASSERT_TRUE(cold.ok());
  const ImpactResult warm = solve_impact(pb, law, {.tolerance = 1e-14}, &cold);
  ASSERT_TRUE(warm.ok());
  // One sweep, and at most one Newton step where that sweep's rounding is above 1e-14.
  EXPECT_LE(warm.solver.iterations, 2);
  EXPECT_LE((warm.P_N - cold.P_N).cwiseAbs().maxCoeff(), 1e-13);
}

TEST(SparseSolver, OtherLawsAreUnsupportedAndSaySo) {
  const SparseImpactProblem pb = falling_stack(1.0);
  const ImpactResult r = solve_impact(pb, ImpactLaw::poisson_coulomb(0.5, 0.3));
  EXPECT_EQ(r.solver.status, SolverStatus::unsupported);
  EXPECT_NE(std::string(r.solver.message).find("Newton"), std::string::npos);
  // Poisson's law with e = 0 is Newton's.
  EXPECT_TRUE(solve_impact(pb, ImpactLaw::poisson_coulomb(0.0, 0.3)).ok());
}

TEST(SparseSolver, RefusesBadInputNamingIt) {
  auto name = [](auto&& f) { return testing::refused_name(f); };
  SparseImpactProblem pb = falling_stack(1.0);
  const ImpactLaw law = ImpactLaw::newton(0.0);
  EXPECT_EQ(name([&] { solve_impact(pb, law, {.tolerance = 0.5}); }), "tolerance");
  EXPECT_EQ(name([&] { solve_impact(pb, law, {.max_sweeps = 0}); }), "max_sweeps");
  SparseImpactProblem bad = pb;
  bad.M.coeffRef(2, 2) = -1.0;
  EXPECT_EQ(name([&] { solve_impact(bad, law); }), "M");
  bad = pb;
  bad.M.coeffRef(0, 1) = 0.5;
  EXPECT_EQ(name([&] { solve_impact(bad, law); }), "M");  // not symmetric
  bad = pb;
  bad.qdot_A(3) = std::nan("");
  EXPECT_EQ(name([&] { solve_impact(bad, law); }), "qdot_A");
  bad = pb;
  bad.W_T.resize(9, 2);
  EXPECT_EQ(name([&] { solve_impact(bad, law); }), "W_T");
  EXPECT_EQ(name([&] { solve_impact(pb, ImpactLaw::newton(PerContact({0.1, 0.2}))); }), "law.e");
  // A contact that no percussion moves (a zero normal column), and Delassus entries that overflow.
  Eigen::MatrixXd columns = Eigen::MatrixXd(pb.W_N);
  columns.col(1).setZero();
  bad = pb;
  bad.W_N = sparse(columns);
  EXPECT_EQ(name([&] { solve_impact(bad, law); }), "W_N");
  columns = Eigen::MatrixXd(pb.W_T) * 1e160;
  bad = pb;
  bad.W_T = sparse(columns);
  bad.qdot_A.setZero();
  EXPECT_EQ(name([&] { solve_impact(bad, ImpactLaw::newton_coulomb(0.0, 0.5)); }), "W_T");
  ContactProblem cp = contact_problem(pb);
  cp.D_A.conservativeResize(5);
  EXPECT_EQ(name([&] { solve_contact_problem(cp, law); }), "D_A");
  cp = contact_problem(pb);
  for (double bad_rounding : {-1e-6, 0.02, std::nan("")}) {
    cp.G_rounding = bad_rounding;
    EXPECT_EQ(name([&] { solve_contact_problem(cp, law); }), "G_rounding") << bad_rounding;
  }
  cp.G_rounding = 0.0;
  cp.D_A_rounding = 1.0;
  EXPECT_EQ(name([&] { solve_contact_problem(cp, law); }), "D_A_rounding");
}

// A Painlevé-like contact from fuzzing Siconos's reader (global form): W_N and W_T both along the
// first degree of freedom, μ = 5.1, and an obstacle's tangential velocity 3e11 times the normal
// one. The mode Newton once ended there with P_N = −0.64, "converged" at 1e-10 of that scale;
// every answer keeps P_N ≥ 0, and a converged one meets the law to its tolerance.
TEST(SparseSolver, NormalPercussionsStayNonNegative) {
  const io::SiconosProblem file = io::parse_siconos_file(
      "2\n1\n0\n2\n2\n2.7 0.5 0.5 1.0\n0\n2\n2\n4.0 0.0 0.8 0.0\n-2.\n30\n-5 333333333333\n5.1\n");
  ASSERT_EQ(file.form, io::SiconosProblem::Form::global);
  const ImpactResult r =
      solve_impact(file.impact, file.law(), {.tolerance = 1e-10, .max_sweeps = 2000});
  EXPECT_GE(r.P_N.minCoeff(), 0.0) << r.solver.message;
  if (r.ok()) {
    EXPECT_LE(contact_residual(contact_problem(file.impact), file.law(), r), 1e-10);
  }
}

// --- Siconos's granular problems -------------------------------------------------------------
// SiconosLarge: seconds in a Release build, minutes under the sanitizers (CI's sanitized share
// leaves them to scripts/check-long.sh).

io::SiconosProblem read_siconos(const std::string& name) {
  std::ifstream in(std::string(FREMOND_SICONOS_DATA) + "/" + name);
  std::stringstream text;
  text << in.rdbuf();
  return io::parse_siconos_file(text.str());
}

// The violation of Newton (e = 0) + Coulomb at contact i of (P, D = D_A + G P), in velocity
// units, computed here: P_N ≥ 0, D_NE ≥ 0, P_N D_NE = 0, |P_T| ≤ μ P_N, and P_T = −μ P_N sign(D_TE)
// where the contact slides. Percussions enter through the contact's own G_NN, G_TT.
double contact_violation(const ContactProblem& pb, const std::vector<double>& mu,
                         const Eigen::VectorXd& P, const Eigen::VectorXd& D, int i) {
  const double a = pb.G.coeff(2 * i, 2 * i), d = pb.G.coeff(2 * i + 1, 2 * i + 1);
  const double PN = P(2 * i), PT = P(2 * i + 1), DN = D(2 * i), DT = D(2 * i + 1);
  const double m = mu[static_cast<std::size_t>(i)];
  double worst = std::max({a * std::max(0.0, -PN), std::max(0.0, -DN),
                           std::min(a * std::fabs(PN), std::fabs(DN)),
                           d * std::max(0.0, std::fabs(PT) - m * PN)});
  // Sticking (|P_T| < μ P_N) needs D_TE = 0; sliding needs P_T against D_TE.
  const double slack = d * (m * PN - std::fabs(PT));
  worst = std::max(worst, std::min(slack, std::fabs(DT)));
  if (DT != 0.0)
    worst =
        std::max(worst, std::min(std::fabs(DT), d * std::fabs(PT + m * PN * (DT > 0 ? 1 : -1))));
  return worst;
}

Eigen::VectorXd percussion_rows(const ImpactResult& r) {
  Eigen::VectorXd P(2 * r.P_N.size());
  for (Eigen::Index i = 0; i < r.P_N.size(); ++i) {
    P(2 * i) = r.P_N(i);
    P(2 * i + 1) = r.P_T(i);
  }
  return P;
}

// The largest |D_A| of the approaching contacts: the scale of the velocities.
double velocity_scale(const ContactProblem& pb) {
  double v_scale = 0.0;
  for (int i = 0; i < pb.contacts(); ++i)
    if (pb.D_A(2 * i) <= 0.0)
      v_scale = std::max({v_scale, std::fabs(pb.D_A(2 * i)), std::fabs(pb.D_A(2 * i + 1))});
  return v_scale;
}

// The largest contact_violation over the contacts, relative to the velocity scale.
double law_violation(const ContactProblem& pb, const std::vector<double>& mu,
                     const ImpactResult& r) {
  const Eigen::VectorXd P = percussion_rows(r), D = pb.D_A + pb.G * P;
  double worst = 0.0;
  for (int i = 0; i < pb.contacts(); ++i)
    worst = std::max(worst, contact_violation(pb, mu, P, D, i));
  return worst / velocity_scale(pb);
}

// A 6 × 6 pile of disks (66 contacts, 132 rows on 108 degrees of freedom: G singular) falling on
// the ground: the sweeps slow down long before 1e-12, and the mode Newton that takes over meets
// the law to rounding. The velocities after are the sweeps' own answer's (1e-8 apart at their
// tolerance), and the law holds at every contact by the check written here.
TEST(SparseSolver, PileOfDisksMeetsTheLawToRounding) {
  const SparseImpactProblem pb = fixtures::disk_pile(6);
  const ContactProblem cp = contact_problem(pb);
  ASSERT_EQ(cp.contacts(), 66);
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.0, 0.5);
  const std::vector<double> mu(66, 0.5);
  const ImpactResult exact = solve_impact(pb, law, {.tolerance = 1e-13});
  ASSERT_TRUE(exact.ok()) << exact.solver.message;
  EXPECT_LE(exact.solver.residual, 1e-13);
  EXPECT_LE(law_violation(cp, mu, exact), 1e-12);
  const ImpactResult swept = solve_impact(pb, law, {.tolerance = 1e-10, .newton_polish = false});
  ASSERT_TRUE(swept.ok()) << swept.solver.message;
  EXPECT_LE(law_violation(cp, mu, swept), 1e-9);
  EXPECT_LE((exact.qdot_E - swept.qdot_E).lpNorm<Eigen::Infinity>(), 1e-8);
  // The pile stops on the ground: no disk moves down after the impact.
  for (int d = 0; d < 36; ++d) EXPECT_GE(exact.qdot_E(3 * d + 1), -1e-12) << "disk " << d;
  EXPECT_LE(exact.admissibility.penetration, 1e-12);
  EXPECT_LT(exact.energy_change, 0.0);
}

// A bed of 128 × 4 disks (1,020 contacts): the benchmarks' wide pile. Solved to 1e-8; the law holds
// at every contact by the check written here, the velocities are q̇_A + M⁻¹(W_N P_N + W_T P_T)
// (M = diag(1, 1, 1/8) a disk), and no disk of the bottom layer goes into the ground.
TEST(SparseSolver, WideBedOfDisksMeetsTheLaw) {
  const SparseImpactProblem pb = fixtures::disk_pile(128, 4);
  const ContactProblem cp = contact_problem(pb);
  ASSERT_EQ(cp.contacts(), 1020);
  const ImpactResult r = solve_impact(pb, ImpactLaw::newton_coulomb(0.0, 0.5), {.tolerance = 1e-8});
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_LE(law_violation(cp, std::vector<double>(1020, 0.5), r), 1e-8);
  const Eigen::VectorXd moved = pb.W_N * r.P_N + pb.W_T * r.P_T;
  for (int d = 0; d < 512; ++d) {
    const double inv_mass[3] = {1.0, 1.0, 8.0};
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(r.qdot_E(3 * d + k), pb.qdot_A(3 * d + k) + inv_mass[k] * moved(3 * d + k), 1e-12)
          << "disk " << d << ", coordinate " << k;
  }
  for (int d = 0; d < 128; ++d) EXPECT_GE(r.qdot_E(3 * d + 1), -1e-8) << "disk " << d;
}

// Anderson mixing of the sweeps (on by default beyond 64 contacts) changes the path, not what is
// solved: on a bed of 64 × 4 disks (508 contacts) and a pile of 12 × 12 (276), the mixed and the
// plain sweeps each meet the law at every contact, by the check written here. Without friction
// the velocities after are unique (the kinetic energy's minimiser), and the two agree to the
// tolerance; with μ = 0.5 the law may have other solutions, and on the bed the two methods find
// two of them (the disks' velocities 1e-3 apart, each meeting the law to 1e-10).
TEST(SparseSolver, MixedAndPlainSweepsMeetTheLaw) {
  for (const auto& [columns, layers] : {std::pair{64, 4}, std::pair{12, 12}}) {
    for (const double mu : {0.0, 0.5}) {
      SCOPED_TRACE(std::to_string(columns) + " x " + std::to_string(layers) + ", mu " +
                   std::to_string(mu));
      const SparseImpactProblem pb = fixtures::disk_pile(columns, layers);
      const ContactProblem cp = contact_problem(pb);
      const std::vector<double> mus(static_cast<std::size_t>(cp.contacts()), mu);
      const ImpactLaw law = ImpactLaw::newton_coulomb(0.0, mu);
      const ImpactResult mixed = solve_impact(pb, law, {.tolerance = 1e-10});
      const ImpactResult plain = solve_impact(pb, law, {.tolerance = 1e-10, .acceleration = false});
      ASSERT_TRUE(mixed.ok()) << mixed.solver.message;
      ASSERT_TRUE(plain.ok()) << plain.solver.message;
      EXPECT_LE(law_violation(cp, mus, mixed), 1e-10);
      EXPECT_LE(law_violation(cp, mus, plain), 1e-10);
      EXPECT_LE(mixed.admissibility.penetration, 1e-10);
      EXPECT_LT(mixed.energy_change, 0.0);
      if (mu == 0.0) {
        EXPECT_LE((mixed.qdot_E - plain.qdot_E).lpNorm<Eigen::Infinity>(), 1e-8);
        EXPECT_NEAR(mixed.energy_change, plain.energy_change,
                    1e-8 * std::fabs(plain.energy_change));
      }
    }
  }
}

// On an 8 × 8 pile (120 contacts) the mixed sweeps do not halve the residual within 128 sweeps:
// the log records that run as stalled, the plain sweeps start again from zero, and the answer
// meets the law as the plain solve's does.
TEST(SparseSolver, StalledMixingGivesWayToThePlainSweeps) {
  const SparseImpactProblem pb = fixtures::disk_pile(8);
  const ContactProblem cp = contact_problem(pb);
  ASSERT_EQ(cp.contacts(), 120);
  const ImpactResult r = solve_impact(pb, ImpactLaw::newton_coulomb(0.0, 0.5), {.tolerance = 1e-8});
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_LE(law_violation(cp, std::vector<double>(120, 0.5), r), 1e-8);
  int from_zero = 0;
  for (int k = 0; k < std::min(r.solver.attempt_count, SolverReport::kMaxAttempts); ++k) {
    const Attempt& a = r.solver.attempts[static_cast<std::size_t>(k)];
    if (a.method == SolverMethod::nsgs && a.start == AttemptStart::zero) {
      ++from_zero;
      if (from_zero == 1) {
        EXPECT_EQ(a.status, SolverStatus::stalled);
      }
    }
  }
  EXPECT_EQ(from_zero, 2);
}

// 667 grains at the start of the flow (q of order 1e-19): solved to 1e-8 of that scale.
TEST(SiconosProblems, GranularFlowOf667Contacts) {
  const auto file = read_siconos("fc2d_granularflowonwall_00667_00000.dat");
  ASSERT_EQ(file.contacts(), 667);
  const ImpactResult r = solve_contact_problem(file.contact, file.law(), {.tolerance = 1e-10});
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_LE(law_violation(file.contact, file.mu, r), 1e-9);
  EXPECT_LE(r.solver.residual, 1e-10);
}

// 2,020 grains: the file keeps 6 significant digits of G, which leaves it indefinite (its smallest
// eigenvalue −3.9e-3 beside its largest 1.7e4); the sweeps stall near 1.7e-6 of the velocities.
// There every contact meets the law to within what those digits leave undetermined of its
// velocities, 5e-6 Σ|G_jk P_k| row by row (checked here contact by contact, by the check above):
// converged as far as the data go, criterion `data`. The same numbers taken as exact stall.
TEST(SiconosLarge, GranularFlowOf2020ContactsIsSolvedAsFarAsItsDigitsGo) {
  const auto file = read_siconos("fc2d_granularflowonwall_02020_00213.dat");
  const ContactProblem& pb = file.contact;
  EXPECT_EQ(pb.G_rounding, 5e-6);
  EXPECT_EQ(pb.D_A_rounding, 5e-25);
  const ImpactResult r = solve_contact_problem(pb, file.law(), {.tolerance = 1e-8});
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_EQ(r.solver.criterion, StopCriterion::data);
  EXPECT_GT(r.solver.residual, 1e-8);
  EXPECT_TRUE(r.admissibility.admissible) << to_string(r.admissibility.failed);
  const Eigen::VectorXd P = percussion_rows(r), D = pb.D_A + pb.G * P;
  const Eigen::VectorXd size = SparseMatrix(pb.G.cwiseAbs()) * P.cwiseAbs();
  const double v_scale = velocity_scale(pb);
  int beyond_double = 0;
  for (int i = 0; i < pb.contacts(); ++i) {
    const double known =
        pb.G_rounding * std::max(size(2 * i), size(2 * i + 1)) +
        pb.D_A_rounding * std::max(std::fabs(pb.D_A(2 * i)), std::fabs(pb.D_A(2 * i + 1)));
    const double violation = contact_violation(pb, file.mu, P, D, i);
    EXPECT_LE(violation, known + 1e-8 * v_scale) << "contact " << i;
    if (violation > 1e-8 * v_scale) ++beyond_double;
  }
  EXPECT_GT(beyond_double, 0);  // the digits, not double precision, bound the answer

  ContactProblem exact = pb;
  exact.G_rounding = exact.D_A_rounding = 0.0;
  const ImpactResult s = solve_contact_problem(exact, file.law(), {.tolerance = 1e-8});
  EXPECT_EQ(s.solver.status, SolverStatus::stalled) << s.solver.message;
  EXPECT_EQ((s.P_N - r.P_N).cwiseAbs().maxCoeff(), 0.0);  // the same sweeps, another verdict
}

// 7,002 grains, the same digits: solved to 1e-8 all the same.
TEST(SiconosLarge, GranularFlowOf7002Contacts) {
  const auto file = read_siconos("fc2d_granularflowonwall_07002_00801.dat");
  const ImpactResult r = solve_contact_problem(file.contact, file.law(), {.tolerance = 1e-8});
  ASSERT_TRUE(r.ok()) << r.solver.message;
  EXPECT_LE(r.solver.residual, 1e-8);
  EXPECT_LE(law_violation(file.contact, file.mu, r), 1e-8);
}

// The global problems (M, H, q, b): the sparse path and the dense solvers (Lemke on 900 degrees
// of freedom) agree.
TEST(SiconosLarge, GlobalProblemAgreesWithTheDenseSolvers) {
  const auto file = read_siconos("gfc2d_granularflowonwall_00069_00350.dat");
  ASSERT_EQ(file.form, io::SiconosProblem::Form::global);
  ASSERT_EQ(file.contacts(), 69);
  const SparseImpactProblem& s = file.impact;
  const ImpactResult sparse_answer = solve_impact(s, file.law(), {.tolerance = 1e-14});
  ASSERT_TRUE(sparse_answer.ok()) << sparse_answer.solver.message;
  ImpactProblem d;
  d.M = Eigen::MatrixXd(s.M);
  d.W_N = Eigen::MatrixXd(s.W_N);
  d.W_T = Eigen::MatrixXd(s.W_T);
  d.w_N = s.w_N;
  d.w_T = s.w_T;
  d.qdot_A = s.qdot_A;
  SolverOptions o;
  o.check_uniqueness = false;
  o.method = SolverMethod::lemke;
  const ImpactResult dense_answer = solve_impact(d, file.law(), o);
  ASSERT_TRUE(dense_answer.ok()) << dense_answer.solver.message;
  const double scale = dense_answer.P_N.cwiseAbs().maxCoeff();
  EXPECT_LE((sparse_answer.P_N - dense_answer.P_N).cwiseAbs().maxCoeff(), 1e-9 * scale);
  EXPECT_LE((sparse_answer.qdot_E - dense_answer.qdot_E).cwiseAbs().maxCoeff(),
            1e-9 * dense_answer.qdot_E.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace fremond
