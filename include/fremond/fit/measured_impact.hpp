#pragma once
/// @file One measured impact (docs/measurements.md): an impact problem and the velocity measured
/// after it, possibly only some of its components, each with its uncertainty.
#include <span>
#include <vector>

#include "fremond/core/impact_problem.hpp"
#include "fremond/core/types.hpp"

namespace fremond {

/// An impact problem and what was measured after it. A law is judged on it by the weighted
/// residuals (q̇_E,law − qdot_E)_j / sigma_j over the measured components j (mask_j true).
struct MeasuredImpact {
  ImpactProblem problem;   ///< the impact: M, W_N, W_T, w_N, w_T, qdot_A (validate(problem) holds).
  VectorX qdot_E;          ///< n, the velocity measured after; entries not measured are ignored.
  std::vector<bool> mask;  ///< n, which components of qdot_E were measured (all, unless told).
  VectorX sigma;           ///< n, the uncertainty of each measured component (> 0; 1 by default).

  /// How many components were measured.
  int measured() const;
};

/// Checks the problem (validate), the sizes of qdot_E, mask and sigma against its n degrees of
/// freedom, that at least one component is measured, and that every measured qdot_E is finite and
/// every measured sigma finite and > 0. Throws InvalidArgument naming the member (`M`, `qdot_E[2]`,
/// `sigma[0]`, `mask`) and the reason.
void validate(const MeasuredImpact& impact);

/// validate() of each, the refusal named `impacts[i].<member>`; an empty list is refused as
/// `impacts`.
void validate(std::span<const MeasuredImpact> impacts);

/// A measured impact with every component measured, sigma = 1.
MeasuredImpact measured_impact(ImpactProblem problem, VectorX qdot_E);

}  // namespace fremond
