// The classical residual read at an answer's own velocities (docs/solvers.md: on a diagonal M a
// solve judges its answer there, no solve by M) against the same residual from the data
// (law_residual's: velocities recomputed from the percussions). Fed answers that are off by a
// known amount, both must read the same miss, under Newton's law and both phases of Poisson's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "contact_space/contact_space.hpp"
#include "laws/detail/residuals.hpp"
#include "solvers/detail/classical.hpp"
#include "unit/classical_support.hpp"

namespace fremond {
namespace {

TEST(OwnVelocityResidual, ReadsWhatTheDataReadOfAnAnswerOffByAKnownAmount) {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> off(-1e-3, 1e-3), unit(0.0, 1.0);
  int compared = 0, missing = 0;
  for (int k = 0; k < 300; ++k) {
    const double theta = -1.4 + 2.8 * unit(rng);
    const Eigen::Vector3d qdot(4.0 * unit(rng) - 2.0, -1.0 - unit(rng), 2.0 * unit(rng) - 1.0);
    const ImpactProblem pb = k % 6 == 0 ? test::flat_bar(qdot) : test::bar(theta, qdot);
    const double e = unit(rng), mu = 0.8 * unit(rng);
    const RestitutionLaw law =
        (k % 2 ? ImpactLaw::poisson_coulomb(e, mu) : ImpactLaw::newton_coulomb(e, mu))
            .get<RestitutionLaw>();
    detail::ContactSpaceT<Dynamic, Dynamic> cs;
    detail::build_contact_space(pb, true, cs);
    if (cs.active == 0) continue;
    // Any percussions of the right size, the law met or not: each row moved by up to 1e-3.
    const int rows = cs.rows();
    Eigen::VectorXd P(rows), P_C(law.has_phases() ? rows : 0);
    for (int j = 0; j < rows; ++j) P(j) = (j < cs.active ? 1.0 : 0.2) + off(rng);
    for (int j = 0; j < P_C.size(); ++j) P_C(j) = (j < cs.active ? 0.6 : 0.1) + off(rng);
    ImpactResult r;
    detail::write_classical_answer(pb, cs, law, P, P_C, r);
    double own = 0.0;
    // A tolerance above any miss: the test at the own velocities accepts, and reports what it read.
    ASSERT_TRUE(detail::residual_at_own_velocities(pb, cs, law, P, P_C, r, 1e9, &own)) << k;
    const double data = detail::classical_residual(pb, cs, law, r);
    EXPECT_NEAR(own, data, 1e-13 * std::max(1.0, data)) << "k " << k;
    missing += data > 1e-6;
    ++compared;
  }
  EXPECT_GT(compared, 250);
  EXPECT_GT(missing, 200);  // the answers fed were off the law, and both readings said so
}

}  // namespace
}  // namespace fremond
