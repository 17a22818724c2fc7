#pragma once
/// @file How a law is fitted to measured impacts (docs/measurements.md#fit).
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>

#include "fremond/solvers/solve_batch.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond {

/// The solver options a fit and a prediction use unless told otherwise: the defaults, without
/// the search for other solutions (check_uniqueness), which a fit does not read.
SolverOptions fit_solver_options();

/// The loss of each weighted residual r (in sigmas); the fit minimises their sum.
enum class FitLoss {
  least_squares,  ///< r²: the measurements' errors Gaussian with the given sigma.
  huber,          ///< r² for |r| ≤ s, 2s|r| − s² beyond: outliers weigh linearly.
  soft_l1,        ///< 2s²(√(1 + (r/s)²) − 1): a smooth Huber.
};
std::string_view to_string(FitLoss loss);
/// Throws InvalidArgument("loss", ...) naming the text and the known losses.
FitLoss fit_loss_from_string(std::string_view name);

/// How each parameter's uncertainty is estimated.
enum class FitUncertainty {
  /// The Gauss-Newton covariance s²(JᵀJ)⁻¹ from the finite-difference Jacobian J of the weighted
  /// residuals at the optimum; s² the residuals' reduced chi-square (or 1 with absolute_sigma).
  gauss_newton,
  /// The spread (standard deviation) of the parameters refitted on resampled impacts (drawn with
  /// replacement, seeded), each fit polished from the optimum.
  bootstrap,
};
std::string_view to_string(FitUncertainty u);
FitUncertainty fit_uncertainty_from_string(std::string_view name);

struct FitOptions {
  FitLoss loss = FitLoss::least_squares;
  double loss_scale = 1.0;  ///< s of Huber and soft-L1, in sigmas; > 0.
  /// Evaluations of the global stage (NLopt GN_DIRECT_L over the parameters' box); 0 skips it
  /// (the local stage then starts from the middle of the box, or from `start`).
  int global_evaluations = 300;
  /// Evaluations of the local polish (NLopt LN_BOBYQA) from the global stage's best point, ≥ 1.
  int local_evaluations = 2000;
  /// The polish stops when a step changes every parameter by less than this, relative; > 0.
  double xtol_rel = 1e-12;
  FitUncertainty uncertainty = FitUncertainty::gauss_newton;
  /// Gauss-Newton: s² = 1, i.e. the sigmas are trusted as the measurements' true uncertainties.
  /// Otherwise the covariance is scaled by the reduced chi-square Σr²/(m − d) of the fit.
  bool absolute_sigma = false;
  int bootstrap_samples = 50;  ///< resamples for FitUncertainty::bootstrap, ≥ 2.
  /// k-fold cross-validation: 0 skips it, else 2 ≤ folds ≤ the number of impacts.
  int folds = 5;
  std::uint64_t seed = 1;  ///< the folds' shuffle and the bootstrap's draws.
  /// Parameters held at a value: a fitted one (then not searched) or a held one (fremond_deadzone's
  /// q, r). A name the family does not have is refused by fit_law.
  std::map<std::string, double> fixed;
  /// A fitted parameter's search interval [lower, upper] instead of its default (docs).
  std::map<std::string, std::pair<double, double>> bounds;
  SolverOptions solver = fit_solver_options();
  BatchOptions batch;

  /// Throws InvalidArgument naming the option (`loss_scale`, `folds`, ...) and the reason.
  void validate() const;
};

}  // namespace fremond
