// One approaching contact on a diagonal M under Newton's or Poisson's law, with or without
// Coulomb's friction: the answer and its certificate come from scalars (the lane of one contact,
// on loops of the body's own size where it is 1, 2, 3 or 6 dofs). The certificate the public
// check_admissibility computes over the whole result must read the same to the last bit, the
// answer must meet its law, and the heap-stored and stack-stored forms must agree. Every other
// answer on one contact (Frémond's and Stronge's laws, a full M, a leaving contact) is certified
// from the same scalars, with the law's own terms: the same comparison holds for them.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "fremond/fremond.hpp"

namespace fremond {
namespace {

/// A body of n dofs with a diagonal M (masses over three decades) or, where `full`, M = AᵀA + I
/// with A's entries in (−1, 1); one contact of unit-scale directions, approaching; w_N, w_T
/// nonzero where `moving` (a moving obstacle).
ImpactProblem one_contact(std::mt19937_64& rng, int n, bool tangential, bool moving,
                          bool full = false) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ImpactProblem pb;
  pb.M = MatrixX::Zero(n, n);
  for (int i = 0; i < n; ++i) pb.M(i, i) = std::pow(10.0, 1.5 * (u(rng) + 1.0));
  if (full) {
    MatrixX A(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = u(rng);
    pb.M = A.transpose() * A + MatrixX::Identity(n, n);
  }
  pb.W_N.resize(n, 1);
  for (int i = 0; i < n; ++i) pb.W_N(i, 0) = u(rng);
  if (tangential) {
    pb.W_T.resize(n, 1);
    for (int i = 0; i < n; ++i) pb.W_T(i, 0) = u(rng);
  }
  pb.qdot_A.resize(n);
  for (int i = 0; i < n; ++i) pb.qdot_A(i) = u(rng);
  if (moving) {
    pb.w_N = VectorX::Constant(1, 0.1 * u(rng));
    if (tangential) pb.w_T = VectorX::Constant(1, 0.3 * u(rng));
  }
  const double dn = pb.W_N.col(0).dot(pb.qdot_A) + (moving ? pb.w_N(0) : 0.0);
  if (dn > 0.0) pb.qdot_A -= (2.0 * dn / pb.W_N.col(0).squaredNorm()) * pb.W_N.col(0);
  return pb;
}

void expect_same_bits(const AdmissibilityReportT<Dynamic>& a,
                      const AdmissibilityReportT<Dynamic>& b, const std::string& what) {
  using R = AdmissibilityReportT<Dynamic>;
  for (double R::*m : {&R::kinetic_energy_A, &R::energy_change, &R::total, &R::reaction,
                       &R::dissipation, &R::penetration, &R::tolerance, &R::violation})
    EXPECT_EQ(a.*m, b.*m) << what;
  EXPECT_EQ(a.per_contact, b.per_contact) << what;
  EXPECT_EQ(a.admissible, b.admissible) << what;
  EXPECT_EQ(a.failed, b.failed) << what;
  EXPECT_EQ(a.failed_contact, b.failed_contact) << what;
}

/// Options that solve to 1e-14 and certify with no relative allowance where `tight`: the
/// velocities' rounding (16ε(|D_A| + κ(M) Σ|G||P| + |W|ᵀ|q̇_E|)) rather than the tolerances then
/// sets the certificate's own tolerance.
SolverOptions options_for(bool tight) {
  SolverOptions options;
  if (tight) {
    options.tolerance = 1e-14;
    options.admissibility_tolerance = 0.0;
  }
  return options;
}

/// solve_impact's answer, its certificate compared with check_admissibility's over the whole
/// result, bit for bit; with the obstacle at rest (not `moving`), T_E − T_A from the velocities
/// against the work −P·z of eq. (9) from the percussions.
ImpactResult solved_and_compared(const ImpactProblem& pb, const ImpactLaw& law,
                                 const SolverOptions& options, bool moving,
                                 const std::string& what) {
  const ImpactResult r = solve_impact(pb, law, options);
  EXPECT_TRUE(r.ok()) << what << ": " << r.solver.message;
  expect_same_bits(r.admissibility, check_admissibility(pb, law, r, options), what);
  const double work = -r.admissibility.total;
  if (!moving) {
    EXPECT_NEAR(r.energy_change, work, 1e-12 * (r.admissibility.kinetic_energy_A + std::fabs(work)))
        << what;
  }
  return r;
}

TEST(OneContactLane, ItsCertificateIsTheWholeResultsToTheLastBit) {
  std::mt19937_64 rng(20261207);
  int answered = 0, created_energy = 0, admissible = 0;
  for (const ImpactLaw& law : {ImpactLaw::newton(0.9), ImpactLaw::newton_coulomb(0.9, 1.0),
                               ImpactLaw::newton_coulomb(0.0, 0.2), ImpactLaw::poisson(0.5),
                               ImpactLaw::poisson_coulomb(0.5, 0.3)}) {
    for (int n : {1, 2, 3, 4, 6, 9}) {  // fixed-size loops for 1, 2, 3, 6; 4 and 9 dynamic
      for (int k = 0; k < 12; ++k) {
        const bool tangential = law.has_friction() || k % 3 == 0, moving = k % 4 == 1;
        if (n == 1 && tangential) continue;  // one dof: W_T along W_N, where Coulomb can jam
        const ImpactProblem pb = one_contact(rng, n, tangential, moving);
        const std::string what =
            std::string(law.name()) + " n=" + std::to_string(n) + " #" + std::to_string(k);
        const SolverOptions options = options_for(k % 2 == 0);  // every other case tight
        const ImpactResult r = solved_and_compared(pb, law, options, moving, what);
        if (!r.ok()) continue;
        EXPECT_LE(law_residual(pb, law, r), options.tolerance) << what;
        if (n <= kSmallDofs) {  // the stack-stored form: the same bits
          const SmallImpactResult s = solve_impact(to_small(pb), law, options);
          EXPECT_EQ(s.qdot_E, r.qdot_E) << what;
          EXPECT_EQ(s.admissibility.total, r.admissibility.total) << what;
          EXPECT_EQ(s.solver.residual, r.solver.residual) << what;
        }
        answered += r.solver.method == SolverMethod::closed_form;
        created_energy += r.energy_change > r.admissibility.tolerance;
        admissible += r.admissibility.admissible;
      }
    }
  }
  // The cases reach both verdicts (Newton + Coulomb creates energy on some) and the closed form
  // answers most of them: the comparison above is of the lane, not of the chain alone.
  EXPECT_GE(answered, 250);
  EXPECT_GE(created_energy, 3);
  EXPECT_GE(admissible, 200);
}

StrongeLaw stronge(double e, double eta) {
  StrongeLaw s;
  s.e = e;
  s.eta = eta;
  return s;
}

TEST(OneContactCertificate, EveryLawsIsTheWholeResultsToTheLastBit) {
  std::mt19937_64 rng(20261208);
  int reactions = 0, own_terms = 0;
  const std::vector<ImpactLaw> laws = {
      ImpactLaw::fremond_coulomb(PowerPotential(85.36, 3.0), 1.0),
      ImpactLaw::fremond_coulomb(PowerPotential(2.0, 1.5), 0.3),
      ImpactLaw::fremond(PowerPotential(6.0, 2.0)),
      ImpactLaw::fremond(PowerPotential(85.36, 3.0), DeadZonePowerPotential(1.5, 2.0, 0.2)),
      ImpactLaw::newton_coulomb(0.5, 0.4),  // on a full M: the chain, not the lane
      ImpactLaw(stronge(0.8, 1.5))};
  for (const ImpactLaw& law : laws) {
    for (int n : {1, 2, 3, 5, 6}) {
      for (int k = 0; k < 12; ++k) {
        const bool tangential = (law.has_friction() || law.has_tangential_potential()) && n > 1,
                   moving = k % 4 == 1;
        if (law.has_tangential_potential() && !tangential) continue;
        ImpactProblem pb = one_contact(rng, n, tangential, moving, k % 2 == 1);
        // A tangential row that barely moves the body (G_TT 1e-8 of G_NN): its percussion is
        // pinned down only to the stopping test's floor over τ = G_TT/2.
        if (k % 4 == 3 && tangential) pb.W_T *= 1e-4;
        if (k % 6 == 5) pb.qdot_A = -pb.qdot_A;  // the contact leaves: no percussion
        const std::string what =
            std::string(law.name()) + " n=" + std::to_string(n) + " #" + std::to_string(k);
        const ImpactResult r =
            solved_and_compared(pb, law, options_for(k % 3 == 2 || k % 4 == 3), moving, what);
        if (law.is<FremondLaw>()) {
          // Frémond's law dissipates: the certificate holds.
          EXPECT_TRUE(r.admissibility.admissible) << what;
          own_terms += r.admissibility.dissipation != 0.0 || r.admissibility.reaction != 0.0;
          reactions += r.P_N_reaction.size() == 1 && r.P_N_reaction(0) > 0.0;
        }
      }
    }
  }
  EXPECT_GE(reactions, 10);  // answers whose reaction acts (eq. 16)
  EXPECT_GE(own_terms, 10);
}

}  // namespace
}  // namespace fremond
