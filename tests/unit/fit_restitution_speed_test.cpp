// Restitution against speed: a ball dropped from several heights onto the ground, its rebound
// measured, as a drop rig measures it. Frémond's normal law φ_N = k|z|^p/p with p ≠ 2 gives a
// restitution that changes with the speed (docs/laws.md: p > 2 rises with it), which Newton's
// constant e cannot follow. Fitted on the rebounds, Frémond's (k, p) are found again, its e(v)
// follows the law that made the data at every speed, and cross-validation ranks it above Newton's.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "fremond/fit/fit_law.hpp"
#include "fremond/fit/predict.hpp"
#include "fremond/solvers/solve_impact.hpp"

namespace fremond {
namespace {

constexpr double kBallMass = 0.2, kGravity = 9.81;
const std::vector<double> kHeights{0.02, 0.05, 0.1, 0.2, 0.4, 0.7, 1.0, 1.5, 2.0, 3.0};

// The ball's vertical motion alone: q = y, M = m, W_N = 1; it hits the ground at √(2 g h).
ImpactProblem drop(double height) {
  ImpactProblem pb;
  pb.M = MatrixX::Constant(1, 1, kBallMass);
  pb.W_N = MatrixX::Constant(1, 1, 1.0);
  pb.qdot_A = VectorX::Constant(1, -std::sqrt(2 * kGravity * height));
  return pb;
}

double restitution(const ImpactLaw& law, double height) {
  const ImpactProblem pb = drop(height);
  const ImpactResult r = solve_impact(pb, law, fit_solver_options());
  EXPECT_TRUE(r.ok());
  return -r.qdot_E(0) / pb.qdot_A(0);
}

// Rebound speeds of drops from every height (each thrice), with Gaussian noise of 0.5 % of the
// impact speed: what a rebound height read to 1 % gives.
std::vector<MeasuredImpact> drops(const ImpactLaw& law, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<MeasuredImpact> out;
  for (const double h : kHeights)
    for (int repeat = 0; repeat < 3; ++repeat) {
      const ImpactProblem pb = drop(h);
      const double sigma = 0.005 * std::fabs(pb.qdot_A(0));
      VectorX rebound = solve_impact(pb, law, fit_solver_options()).qdot_E;
      rebound(0) += sigma * gauss(rng);
      MeasuredImpact m = measured_impact(pb, rebound);
      m.sigma.setConstant(sigma);
      out.push_back(m);
    }
  return out;
}

TEST(FitRestitutionSpeed, FremondRecoversItsRestitutionCurveWhereNewtonCannot) {
  const double k = 0.8, p = 3.0;
  const ImpactLaw truth = make_law(LawFamily::fremond, {{"k", k}, {"p", p}});
  // The data span a real change of restitution with speed.
  const double e_slow = restitution(truth, kHeights.front()),
               e_fast = restitution(truth, kHeights.back());
  ASSERT_GT(e_fast - e_slow, 0.2) << e_slow << " " << e_fast;

  const std::vector<MeasuredImpact> data = drops(truth, 3);
  FitOptions options;
  options.folds = 5;
  const std::vector<FitResult> ranked =
      fit_laws(data, {LawFamily::newton, LawFamily::fremond}, options);
  ASSERT_EQ(ranked.size(), 2u);
  EXPECT_EQ(ranked[0].family, LawFamily::fremond);
  EXPECT_LT(ranked[0].heldout_rms, 2.0);  // about one sigma: the noise
  EXPECT_GT(ranked[1].heldout_rms, 5.0);  // a constant e misses the curve by many sigmas
  const FitResult& fit = ranked[0];
  ASSERT_EQ(fit.names[1], "p");
  EXPECT_NEAR(fit.values(1), p, 4 * fit.uncertainties(1));
  EXPECT_LT(fit.uncertainties(1), 0.1 * p);
  // e(v) of the fitted law against the true one, at every height and between them.
  for (double h = kHeights.front(); h <= kHeights.back(); h *= 1.3)
    EXPECT_NEAR(restitution(fit.law, h), restitution(truth, h), 0.01) << "h = " << h;
  // Newton's best constant e lies between the slow and the fast restitutions.
  const double e_newton = ranked[1].values(0);
  EXPECT_GT(e_newton, e_slow);
  EXPECT_LT(e_newton, e_fast);
}

}  // namespace
}  // namespace fremond
