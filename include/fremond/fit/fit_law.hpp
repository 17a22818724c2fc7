#pragma once
/// @file Laws fitted to measured impacts and ranked by cross-validation (docs/measurements.md).
#include <span>
#include <vector>

#include "fremond/fit/fit_options.hpp"
#include "fremond/fit/fit_result.hpp"
#include "fremond/fit/law_family.hpp"
#include "fremond/fit/measured_impact.hpp"

namespace fremond {

/// The family's parameters that minimise Σ loss(r) over the weighted residuals r of every measured
/// component (predict.hpp): NLopt's GN_DIRECT_L over the parameters' box, then LN_BOBYQA from its
/// best point; each parameter's uncertainty; and, with options.folds, the held-out RMS of k-fold
/// cross-validation. Throws InvalidArgument for invalid options, impacts (`impacts[i]...`), or a
/// fixed or bounded parameter the family does not have. Deterministic for a given seed.
FitResult fit_law(std::span<const MeasuredImpact> impacts, LawFamily family,
                  const FitOptions& options = {});

/// fit_law for each family, ranked: the smallest held-out RMS first (the training RMS without
/// folds).
std::vector<FitResult> fit_laws(std::span<const MeasuredImpact> impacts,
                                const std::vector<LawFamily>& families,
                                const FitOptions& options = {});

}  // namespace fremond
