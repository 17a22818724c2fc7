#pragma once
/// @file What a fit found (docs/measurements.md#fit).
#include <string>
#include <vector>

#include "fremond/core/types.hpp"
#include "fremond/fit/law_family.hpp"
#include "fremond/laws/impact_law.hpp"

namespace fremond {

struct FitResult {
  LawFamily family = LawFamily::newton;
  ImpactLaw law;                   ///< the family's law at the fitted values (held ones included).
  std::vector<std::string> names;  ///< the fitted parameters, in order.
  VectorX values;                  ///< their fitted values.
  /// One standard deviation of each (FitOptions::uncertainty); +∞ for a parameter the data do not
  /// determine (a zero direction of JᵀJ, e.g. μ where no impact slides).
  VectorX uncertainties;
  double objective = 0.0;     ///< Σ loss(r) at the optimum.
  double training_rms = 0.0;  ///< √(Σr²/m) over the m measured components, in sigmas.
  /// The same over each fold's held-out impacts, fitted on the others (NaN without folds).
  double heldout_rms = 0.0;
  int measured = 0;          ///< m, the measured components.
  int failed_solves = 0;     ///< impacts whose solve gave no velocity at the optimum.
  int global_status = 0;     ///< NLopt's nlopt_result of the global stage (0: not run).
  int local_status = 0;      ///< NLopt's nlopt_result of the local polish.
  std::string status;        ///< local_status by name, e.g. "XTOL_REACHED".
  int evaluations = 0;       ///< objective evaluations of the fit on every impact (not the folds').
  int fold_evaluations = 0;  ///< the folds' and the bootstrap's evaluations.
  double seconds = 0.0;      ///< the wall time of the whole fit, folds included.
};

}  // namespace fremond
