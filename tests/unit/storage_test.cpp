// A heap-stored problem that fits the small form is solved in it (solve_impact.hpp): its answer
// must be the stack-stored answer in every member, whatever the law, the outcome (an energy gain,
// Poisson's phases, Frémond's reaction, several solutions, independent groups, no contact taking
// part) and the options; and a problem handed in either storage is refused with the same words.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "contact_space/contact_space.hpp"
#include "fremond/fremond.hpp"
#include "support/fixtures.hpp"

namespace fremond {
namespace {

using namespace fremond::fixtures;

/// The bar at θ = π/4 touching with D_NA = 0 and sliding back: for μ ≥ 5/3 both the open contact
/// and sticking solve Newton + Coulomb (classical_coulomb_test.cpp works it by hand).
SmallImpactProblem grazing_bar() {
  SmallImpactProblem p;
  const double l = 1.0, J = 1.0 / 3.0;  // unit mass and half-length: J = m l²/3
  p.M = SmallImpactProblem::Mat(Eigen::Vector3d(1.0, 1.0, J).asDiagonal());
  const double c = std::cos(std::numbers::pi / 4), s = std::sin(std::numbers::pi / 4);
  p.W_N = SmallImpactProblem::Jac(Eigen::Vector3d(0.0, 1.0, -l * c));
  p.W_T = SmallImpactProblem::Jac(Eigen::Vector3d(1.0, 0.0, l * s));
  p.qdot_A = Eigen::Vector3d(-1.0, 0.0, 0.0);
  return p;
}

/// A body whose only contact is already separating: nothing takes part.
SmallImpactProblem separating_point_mass() {
  SmallImpactProblem p = planar_point_mass(1.0, true);
  p.qdot_A(1) = 0.5;
  return p;
}

struct Case {
  std::string name;
  SmallImpactProblem problem;
  ImpactLaw law;
};

std::vector<Case> cases() {
  const auto [p3, viscous, coulomb] = bar_fremond_laws();
  // A normal law too weak to stop the bar by itself: the reaction does (docs/laws.md).
  const ImpactLaw reaction = ImpactLaw::fremond(PowerPotential(1e-3, 2.0));
  std::vector<Case> v{
      {"bar newton_coulomb (energy gain)", bar_first_impact(true),
       ImpactLaw::newton_coulomb(kRestitution, kFriction)},
      {"bar poisson_coulomb (phases)", bar_first_impact(true),
       ImpactLaw::poisson_coulomb(kRestitution, kFriction)},
      {"bar fremond viscous", bar_first_impact(true), viscous},
      {"bar fremond reaction", bar_first_impact(false), reaction},
      {"flat bar newton_coulomb", flat_bar_two_contacts(true),
       ImpactLaw::newton_coulomb(kRestitution, kFriction)},
      {"flat bar poisson", flat_bar_two_contacts(false), ImpactLaw::poisson(kRestitution)},
      {"flat bar fremond coulomb", flat_bar_two_contacts(true), coulomb},
      {"flat bar fremond p3", flat_bar_two_contacts(false), p3},
      {"two point masses newton_coulomb", two_point_masses(true),
       ImpactLaw::newton_coulomb(kRestitution, kFriction)},
      {"two point masses fremond coulomb", two_point_masses(true), coulomb},
      {"grazing bar newton_coulomb (two solutions)", grazing_bar(),
       ImpactLaw::newton_coulomb(0.5, 2.0)},
      {"separating point mass", separating_point_mass(), viscous}};
  for (int i = 0; i < 3; ++i) {
    v.push_back({"random " + std::to_string(i) + " poisson_coulomb", random_spd_problem(i, true),
                 ImpactLaw::poisson_coulomb(kRestitution, kFriction)});
    v.push_back({"random " + std::to_string(i) + " viscous", random_spd_problem(i, true), viscous});
  }
  return v;
}

template <class A, class B>
void expect_same_vector(const A& heap, const B& small, const char* what) {
  ASSERT_EQ(heap.size(), small.size()) << what;
  for (Eigen::Index i = 0; i < heap.size(); ++i)
    EXPECT_EQ(heap(i), small(i)) << what << "[" << i << "]";
}

void expect_same(const ImpactResult& h, const SmallImpactResult& s) {
  expect_same_vector(h.qdot_E, s.qdot_E, "qdot_E");
  expect_same_vector(h.P_N, s.P_N, "P_N");
  expect_same_vector(h.P_T, s.P_T, "P_T");
  expect_same_vector(h.D_NA, s.D_NA, "D_NA");
  expect_same_vector(h.D_TA, s.D_TA, "D_TA");
  expect_same_vector(h.D_NE, s.D_NE, "D_NE");
  expect_same_vector(h.D_TE, s.D_TE, "D_TE");
  expect_same_vector(h.P_N_reaction, s.P_N_reaction, "P_N_reaction");
  EXPECT_EQ(h.has_phases, s.has_phases);
  expect_same_vector(h.P_NC, s.P_NC, "P_NC");
  expect_same_vector(h.P_TC, s.P_TC, "P_TC");
  expect_same_vector(h.D_NC, s.D_NC, "D_NC");
  expect_same_vector(h.D_TC, s.D_TC, "D_TC");
  expect_same_vector(h.qdot_C, s.qdot_C, "qdot_C");
  expect_same_vector(h.takes_part, s.takes_part, "takes_part");
  EXPECT_EQ(h.energy_change, s.energy_change);
  EXPECT_EQ(h.unique, s.unique);
  EXPECT_EQ(h.solutions_found, s.solutions_found);
  const auto& a = h.admissibility;
  const auto& b = s.admissibility;
  EXPECT_EQ(a.kinetic_energy_A, b.kinetic_energy_A);
  EXPECT_EQ(a.energy_change, b.energy_change);
  EXPECT_EQ(a.total, b.total);
  expect_same_vector(a.per_contact, b.per_contact, "admissibility.per_contact");
  EXPECT_EQ(a.reaction, b.reaction);
  EXPECT_EQ(a.dissipation, b.dissipation);
  EXPECT_EQ(a.complementarity, b.complementarity);
  EXPECT_EQ(a.penetration, b.penetration);
  EXPECT_EQ(a.fenchel_young_gap, b.fenchel_young_gap);
  EXPECT_EQ(a.tolerance, b.tolerance);
  EXPECT_EQ(a.admissible, b.admissible);
  EXPECT_EQ(a.failed, b.failed);
  EXPECT_EQ(a.failed_contact, b.failed_contact);
  EXPECT_EQ(a.violation, b.violation);
  EXPECT_EQ(h.solver.method, s.solver.method);
  EXPECT_EQ(h.solver.status, s.solver.status);
  EXPECT_EQ(h.solver.criterion, s.solver.criterion);
  EXPECT_EQ(h.solver.message, s.solver.message);
  EXPECT_EQ(h.solver.iterations, s.solver.iterations);
  EXPECT_EQ(h.solver.residual, s.solver.residual);
  EXPECT_EQ(h.solver.native_code, s.solver.native_code);
  EXPECT_EQ(h.solver.fallbacks, s.solver.fallbacks);
}

/// The refusal's first word: the member it names.
template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const InvalidArgument& e) {
    return e.name();
  }
  return "(accepted)";
}

TEST(Storage, HeapStoredSmallProblemGetsTheStackStoredAnswerInEveryMember) {
  bool saw_gain = false, saw_phases = false, saw_reaction = false, saw_several = false,
       saw_none_taking_part = false;
  for (const Case& c : cases()) {
    const ImpactProblem heap = to_dynamic(c.problem);
    for (const bool unique : {false, true}) {
      SCOPED_TRACE(c.name + (unique ? ", check_uniqueness" : ""));
      SolverOptions opt;
      opt.check_uniqueness = unique;
      const ImpactResult h = solve_impact(heap, c.law, opt);
      const SmallImpactResult s = solve_impact(c.problem, c.law, opt);
      expect_same(h, s);
      EXPECT_TRUE(h.ok()) << to_string(h.solver.status);
      saw_gain |= h.admissibility.energy_change > 0.0 && !h.admissibility.admissible;
      saw_phases |= h.has_phases;
      saw_reaction |= h.P_N_reaction.size() > 0 && h.P_N_reaction.maxCoeff() > 0.0;
      saw_several |= !h.unique;
      saw_none_taking_part |= h.takes_part.sum() == 0;
    }
  }
  // The cases reach every member's interesting values, so a member left uncopied shows.
  EXPECT_TRUE(saw_gain);
  EXPECT_TRUE(saw_phases);
  EXPECT_TRUE(saw_reaction);
  EXPECT_TRUE(saw_several);
  EXPECT_TRUE(saw_none_taking_part);
}

// law_residual and check_admissibility of a heap-stored small problem read it in the small form
// too: the same numbers as on the stack-stored problem and result, to the last bit.
TEST(Storage, ResidualAndCertificateOfAHeapStoredResultAreTheStackStoredOnes) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const ImpactProblem heap = to_dynamic(c.problem);
    ImpactResult h = solve_impact(heap, c.law);
    SmallImpactResult s = solve_impact(c.problem, c.law);
    EXPECT_EQ(law_residual(heap, c.law, h), law_residual(c.problem, c.law, s));
    h.admissibility = check_admissibility(heap, c.law, h);
    s.admissibility = check_admissibility(c.problem, c.law, s);
    expect_same(h, s);
    // The result moved back to the small form is the stack-stored result.
    const SmallImpactResult back = to_small(h);
    expect_same(h, back);
  }
}

// A result larger than the small form is refused by to_small, naming it.
TEST(Storage, ToSmallRefusesAResultThatDoesNotFit) {
  ImpactResult r = to_dynamic(solve_impact(bar_first_impact(true), ImpactLaw::newton(0.5)));
  EXPECT_TRUE(fits_small(r));
  r.qdot_E = Eigen::VectorXd::Zero(kSmallDofs + 1);
  EXPECT_FALSE(fits_small(r));
  EXPECT_EQ(refusal([&] { (void)to_small(r); }), "result");
  r = to_dynamic(solve_impact(bar_first_impact(true), ImpactLaw::newton(0.5)));
  r.admissibility.per_contact = Eigen::VectorXd::Zero(kSmallContacts + 1);
  EXPECT_FALSE(fits_small(r));
}

// solve_impact_all solves in the storage solve_impact uses: where the answer is unique, the list's
// one answer is solve_impact's to the last bit (with `fremond impact` and `--all-solutions` print
// the same numbers); where it is not, solve_impact's answer is one of the list.
TEST(Storage, SolveImpactAllGivesSolveImpactsAnswerToTheLastBit) {
  int unique = 0, several = 0;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const ImpactProblem heap = to_dynamic(c.problem);
    const ImpactResult one = solve_impact(heap, c.law);
    const std::vector<ImpactResult> all = solve_impact_all(heap, c.law);
    ASSERT_FALSE(all.empty());
    const auto same = [&](const ImpactResult& r) {
      return r.qdot_E == one.qdot_E && r.P_N == one.P_N && r.P_T == one.P_T &&
             r.energy_change == one.energy_change;
    };
    if (all.size() == 1) {
      ++unique;
      EXPECT_TRUE(same(all[0]));
      EXPECT_EQ(all[0].solver.status, one.solver.status);
    } else {
      ++several;
      EXPECT_TRUE(std::any_of(all.begin(), all.end(), same));
    }
  }
  EXPECT_GE(unique, 15);
  EXPECT_GE(several, 1);
}

// A heap-stored problem that fits the small form is validated there, with the same words as in
// its own storage; one whose shapes do not fit is refused in its own storage.
TEST(Storage, RefusalsNameTheSameMemberInEitherStorage) {
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.5, 1.0);
  std::vector<ImpactProblem> bad(5, to_dynamic(bar_first_impact(true)));
  bad[0].qdot_A(1) = std::numeric_limits<double>::quiet_NaN();
  bad[1].M(0, 1) = 0.5;  // not symmetric
  bad[2].W_T.resize(3, 0);
  bad[2].w_T = Eigen::VectorXd::Zero(1);  // a tangential term without a tangential row
  bad[3].M = -bad[3].M;                   // not positive definite
  bad[4].W_N = Eigen::MatrixXd::Ones(kSmallDofs + 1, 1);  // does not fit: its own storage
  for (std::size_t i = 0; i < bad.size(); ++i) {
    SCOPED_TRACE(i);
    const std::string heap = refusal([&] { (void)solve_impact(bad[i], law); });
    EXPECT_NE(heap, "(accepted)");
    EXPECT_EQ(heap, refusal([&] { (void)detail::solve_impact_in_own_storage(bad[i], law); }));
  }
}

}  // namespace
}  // namespace fremond

namespace fremond {
namespace {

// T_E − T_A on a diagonal M skips the loop's products with M's zeros (contact_space.hpp): the same
// bits as the full sums, signed zeros included, and where a velocity is not finite (0·∞ = NaN in
// the full sums) the full sums' value.
TEST(Storage, EnergyChangeOnADiagonalMassIsTheFullSumsToTheLastBit) {
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double specials[] = {0.0, -0.0, 1e-310, -1e300, 1e300};
  auto same_bits = [](double a, double b) {
    return (std::isnan(a) && std::isnan(b)) || (a == b && std::signbit(a) == std::signbit(b));
  };
  int nonzero = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = 1 + trial % 6;
    SmallImpactProblem pb;
    pb.M = SmallImpactProblem::Mat::Zero(n, n);
    for (int i = 0; i < n; ++i) pb.M(i, i) = std::pow(10.0, 6.0 * u(gen));
    pb.qdot_A.resize(n);
    VecT<kSmallDofs> qE(n);
    for (int i = 0; i < n; ++i) {
      pb.qdot_A(i) = u(gen);
      qE(i) = trial % 3 == 0 ? -pb.qdot_A(i) : u(gen);
      if (trial % 7 == 0) qE(i) = specials[(trial / 7 + i) % 5];
      if (trial % 13 == 0 && i % 2 == 0) pb.qdot_A(i) = qE(i) = -0.0;
    }
    if (trial % 11 == 0) qE(trial % n) = std::numeric_limits<double>::infinity();
    const double fast = detail::energy_change_at(pb, qE, true);
    const double full = detail::energy_change_at(pb, qE, false);
    EXPECT_TRUE(same_bits(fast, full)) << "trial " << trial << ": " << fast << " vs " << full;
    nonzero += fast != 0.0;
  }
  EXPECT_GT(nonzero, 2000);  // the comparison is not only of zeros
}

}  // namespace
}  // namespace fremond
