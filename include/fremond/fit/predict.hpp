#pragma once
/// @file A law's predictions beside the measurements (docs/measurements.md#predict).
#include <span>
#include <vector>

#include "fremond/core/types.hpp"
#include "fremond/fit/fit_options.hpp"
#include "fremond/fit/measured_impact.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/solve_batch.hpp"
#include "fremond/solvers/solver_options.hpp"
#include "fremond/solvers/solver_status.hpp"

namespace fremond {

/// What a law predicts for each measured impact and how far it is from the measurement.
struct Prediction {
  std::vector<VectorX> qdot_E;       ///< per impact: the law's velocity after the impact.
  std::vector<VectorX> residuals;    ///< per impact: (q̇_E,law − qdot_E)_j / sigma_j, NaN where
                                     ///< not measured.
  std::vector<SolverStatus> status;  ///< per impact: how its solve ended.
  /// The root mean square of the weighted residuals over every measured component: 1 means the
  /// law misses by one sigma on average.
  double rms = 0.0;
  int measured = 0;  ///< the number of measured components.
  /// Impacts whose solve gave no finite velocity; their residuals are NaN and stay out of rms.
  int failed = 0;
};

/// Solves every impact under `law` (solve_batch) and compares with what was measured. Throws
/// InvalidArgument naming `impacts[i]...` for an invalid impact, or the law's key when it does not
/// fit an impact's contacts.
Prediction predict(std::span<const MeasuredImpact> impacts, const ImpactLaw& law,
                   const SolverOptions& options = fit_solver_options(),
                   const BatchOptions& batch = {});

}  // namespace fremond
