// fit_law and predict (docs/measurements.md) against data made by a known law: the paper's bar at
// several angles, speeds and incidences, each impact solved under the law with known parameters,
// then measured with seeded Gaussian noise. The fit must find the parameters again (to 1e-6
// without noise, within a few of its own standard deviations with noise), and cross-validation
// must rank the law that made the data first.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "fremond/core/error.hpp"
#include "fremond/fit/fit_law.hpp"
#include "fremond/fit/predict.hpp"
#include "fremond/solvers/solve_impact.hpp"
#include "support/fixtures.hpp"

namespace fremond {
namespace {

using fixtures::bar;

// The true values of each family's parameters.
std::map<std::string, double> truth(LawFamily f) {
  switch (f) {
    case LawFamily::newton_coulomb:
      return {{"e", 0.6}, {"mu", 0.3}};
    case LawFamily::poisson_coulomb:
      return {{"e", 0.7}, {"mu", 0.25}};
    case LawFamily::stronge_coulomb:
      return {{"e", 0.8}, {"mu", 0.2}};
    case LawFamily::fremond:
      return {{"k", 12.0}, {"p", 2.5}};
    case LawFamily::fremond_coulomb:
      return {{"k", 9.0}, {"p", 2.5}, {"mu", 0.3}};
    case LawFamily::fremond_deadzone:
      return {{"k", 15.0}, {"p", 1.8}, {"k_T", 0.8}};
    default:
      return {};
  }
}

// The bar (m = 1, l = 0.5) at angles 20°..70°, hitting at 1, 2.5 and 4 m/s with incidences
// 0°..60° from the normal, measured with Gaussian noise of standard deviation `noise` (sigma says
// so); without noise sigma is 0.01 all the same, so that the RMS reads in the same units.
std::vector<MeasuredImpact> synthetic(LawFamily family, double noise, std::uint64_t seed = 7,
                                      bool friction = true) {
  const ImpactLaw law = make_law(family, truth(family));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<MeasuredImpact> out;
  for (const double theta_deg : {20.0, 35.0, 50.0, 70.0})
    for (const double v : {1.0, 2.5, 4.0})
      for (const double alpha_deg : {0.0, 20.0, 40.0, 60.0}) {
        const double a = alpha_deg * std::numbers::pi / 180.0;
        ImpactProblem pb =
            bar(theta_deg * std::numbers::pi / 180.0,
                Eigen::Vector3d(v * std::sin(a), -v * std::cos(a), 0.3 * v), false, 1.0, friction);
        pb.w_N = VectorX::Zero(1);
        if (friction) pb.w_T = VectorX::Zero(1);
        const ImpactResult r = solve_impact(pb, law, fit_solver_options());
        EXPECT_EQ(r.solver.status, SolverStatus::converged);
        VectorX measured = r.qdot_E;
        for (Eigen::Index j = 0; j < measured.size(); ++j) measured(j) += noise * gauss(rng);
        MeasuredImpact m = measured_impact(pb, measured);
        m.sigma.setConstant(noise > 0.0 ? noise : 0.01);
        out.push_back(m);
      }
  return out;
}

FitOptions quick(int folds = 0) {
  FitOptions o;
  o.global_evaluations = 150;
  o.folds = folds;
  return o;
}

void expect_recovers(const FitResult& r, LawFamily family, double tolerance_in_sd,
                     double noise_free_tolerance) {
  const auto t = truth(family);
  ASSERT_EQ(r.names.size(), t.size());
  for (std::size_t i = 0; i < r.names.size(); ++i) {
    const double want = t.at(r.names[i]);
    const double got = r.values(static_cast<Eigen::Index>(i));
    const double sd = r.uncertainties(static_cast<Eigen::Index>(i));
    if (tolerance_in_sd > 0.0) {
      EXPECT_TRUE(std::isfinite(sd) && sd > 0.0) << r.names[i] << " sd " << sd;
      EXPECT_LE(std::fabs(got - want), tolerance_in_sd * sd)
          << to_string(family) << ' ' << r.names[i] << " = " << got << " ± " << sd << ", true "
          << want;
    } else {
      EXPECT_NEAR(got, want, noise_free_tolerance * std::max(1.0, std::fabs(want)))
          << to_string(family) << ' ' << r.names[i] << ", status " << r.status;
    }
  }
}

class FitFamily : public ::testing::TestWithParam<LawFamily> {};

TEST_P(FitFamily, NoiseFreeDataGiveTheParametersTo1e6) {
  const LawFamily family = GetParam();
  const auto data = synthetic(family, 0.0, 7, family != LawFamily::fremond);
  const FitResult r = fit_law(data, family, quick());
  expect_recovers(r, family, 0.0, 1e-6);
  EXPECT_LT(r.training_rms, 1e-5);
  EXPECT_EQ(r.failed_solves, 0);
  EXPECT_GT(r.evaluations, 0);
}

TEST_P(FitFamily, NoisyDataGiveTheParametersWithinTheirUncertainty) {
  const LawFamily family = GetParam();
  const auto data = synthetic(family, 0.01, 11, family != LawFamily::fremond);
  const FitResult r = fit_law(data, family, quick());
  expect_recovers(r, family, 4.0, 0.0);
  // The noise is what sigma says: the residuals are about one sigma each.
  EXPECT_GT(r.training_rms, 0.7);
  EXPECT_LT(r.training_rms, 1.3);
}

INSTANTIATE_TEST_SUITE_P(Laws, FitFamily,
                         ::testing::Values(LawFamily::newton_coulomb, LawFamily::poisson_coulomb,
                                           LawFamily::stronge_coulomb, LawFamily::fremond,
                                           LawFamily::fremond_coulomb, LawFamily::fremond_deadzone),
                         [](const auto& info) { return std::string(to_string(info.param)); });

TEST(FitLaws, CrossValidationRanksTheLawThatMadeTheDataFirst) {
  const std::vector<LawFamily> candidates{LawFamily::newton_coulomb, LawFamily::poisson_coulomb,
                                          LawFamily::stronge_coulomb, LawFamily::fremond_coulomb};
  for (const LawFamily truth_family : candidates) {
    const auto data = synthetic(truth_family, 0.01, 3);
    const auto ranked = fit_laws(data, candidates, quick(5));
    ASSERT_EQ(ranked.size(), candidates.size());
    EXPECT_EQ(ranked.front().family, truth_family)
        << "data of " << to_string(truth_family) << ": first " << to_string(ranked[0].family)
        << " held-out " << ranked[0].heldout_rms << ", then " << to_string(ranked[1].family) << " "
        << ranked[1].heldout_rms;
    for (const FitResult& r : ranked) EXPECT_TRUE(std::isfinite(r.heldout_rms));
  }
}

TEST(FitLaws, SeededRunsAreIdentical) {
  const auto data = synthetic(LawFamily::newton_coulomb, 0.01, 5);
  FitOptions o = quick(3);
  o.uncertainty = FitUncertainty::bootstrap;
  o.bootstrap_samples = 5;
  const FitResult a = fit_law(data, LawFamily::newton_coulomb, o);
  const FitResult b = fit_law(data, LawFamily::newton_coulomb, o);
  EXPECT_EQ(a.values, b.values);
  EXPECT_EQ(a.uncertainties, b.uncertainties);
  EXPECT_EQ(a.heldout_rms, b.heldout_rms);
  EXPECT_TRUE(std::isfinite(a.uncertainties(0)) && a.uncertainties(0) > 0.0);
}

// The two estimates of the uncertainty agree on a smooth problem with Gaussian noise: the spread
// of refits on resampled impacts is the curvature's standard deviation, within sampling error.
TEST(FitLaws, BootstrapAndGaussNewtonAgree) {
  const auto data = synthetic(LawFamily::stronge_coulomb, 0.01, 13);
  FitOptions o = quick();
  const FitResult gn = fit_law(data, LawFamily::stronge_coulomb, o);
  o.uncertainty = FitUncertainty::bootstrap;
  o.bootstrap_samples = 40;
  const FitResult bs = fit_law(data, LawFamily::stronge_coulomb, o);
  EXPECT_EQ(gn.values, bs.values);  // the same fit; only the uncertainty differs
  for (Eigen::Index i = 0; i < gn.values.size(); ++i) {
    EXPECT_GT(bs.uncertainties(i), gn.uncertainties(i) / 2.5) << gn.names[i];
    EXPECT_LT(bs.uncertainties(i), gn.uncertainties(i) * 2.5) << gn.names[i];
  }
  EXPECT_GT(bs.fold_evaluations, 40);
}

TEST(FitLaws, RobustLossesDownweighOutliers) {
  auto data = synthetic(LawFamily::newton_coulomb, 0.01, 9);
  for (std::size_t i = 0; i < data.size(); i += 12) data[i].qdot_E(1) += 1.0;  // 100 sigmas off
  FitOptions o = quick();
  o.loss = FitLoss::soft_l1;
  const FitResult robust = fit_law(data, LawFamily::newton_coulomb, o);
  EXPECT_NEAR(robust.values(0), 0.6, 0.01);
  o.loss = FitLoss::huber;
  EXPECT_NEAR(fit_law(data, LawFamily::newton_coulomb, o).values(0), 0.6, 0.01);
  const FitResult plain = fit_law(data, LawFamily::newton_coulomb, quick());
  EXPECT_GT(std::fabs(plain.values(0) - 0.6), std::fabs(robust.values(0) - 0.6));
}

TEST(FitLaws, HeldParametersAndBounds) {
  const auto data = synthetic(LawFamily::fremond_coulomb, 0.0);
  FitOptions o = quick();
  o.fixed["p"] = 2.5;
  const FitResult r = fit_law(data, LawFamily::fremond_coulomb, o);
  ASSERT_EQ(r.names, (std::vector<std::string>{"k", "mu"}));
  EXPECT_NEAR(r.values(0), 9.0, 1e-6 * 9.0);
  o.fixed.clear();
  o.bounds["mu"] = {0.0, 0.1};  // the truth (0.3) outside: the fit stops at the bound
  const FitResult b = fit_law(data, LawFamily::fremond_coulomb, o);
  EXPECT_LE(b.values(2), 0.1);
  EXPECT_GT(b.values(2), 0.099);
}

TEST(FitLaws, RefusalsNameTheOption) {
  const auto data = synthetic(LawFamily::newton_coulomb, 0.0);
  const auto refusal = [&](FitOptions o, LawFamily f = LawFamily::newton_coulomb) -> std::string {
    try {
      fit_law(data, f, o);
    } catch (const InvalidArgument& e) {
      return e.name();
    }
    return "";
  };
  FitOptions o;
  o.folds = 1;
  EXPECT_EQ(refusal(o), "folds");
  o.folds = 1000;
  EXPECT_EQ(refusal(o), "folds");
  o = {};
  o.loss_scale = 0.0;
  EXPECT_EQ(refusal(o), "loss_scale");
  o = {};
  o.fixed["k"] = 1.0;
  EXPECT_EQ(refusal(o), "fixed.k");
  o = {};
  o.bounds["e"] = {0.5, 2.0};
  EXPECT_EQ(refusal(o), "bounds.e");
  o = {};
  o.fixed["e"] = 1.5;
  EXPECT_EQ(refusal(o), "law.e");
  auto bad = data;
  bad[4].sigma(1) = -1.0;
  try {
    fit_law(bad, LawFamily::newton, {});
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "impacts[4].sigma[1]");
  }
}

TEST(Predict, ResidualsAndRms) {
  const auto data = synthetic(LawFamily::stronge_coulomb, 0.0);
  const Prediction exact =
      predict(data, make_law(LawFamily::stronge_coulomb, truth(LawFamily::stronge_coulomb)));
  EXPECT_EQ(exact.measured, static_cast<int>(3 * data.size()));
  EXPECT_LT(exact.rms, 1e-9);
  EXPECT_EQ(exact.failed, 0);
  // Half a sigma off on one component of every impact, measured alone: RMS 0.5.
  auto shifted = data;
  for (MeasuredImpact& m : shifted) {
    m.mask = {false, true, false};
    m.qdot_E(1) -= 0.5 * m.sigma(1);
  }
  const Prediction p =
      predict(shifted, make_law(LawFamily::stronge_coulomb, truth(LawFamily::stronge_coulomb)));
  EXPECT_NEAR(p.rms, 0.5, 1e-9);
  EXPECT_TRUE(std::isnan(p.residuals[0](0)));
  EXPECT_NEAR(p.residuals[0](1), 0.5, 1e-9);
  EXPECT_NEAR(p.qdot_E[0](1), data[0].qdot_E(1), 1e-12);
}

}  // namespace
}  // namespace fremond
