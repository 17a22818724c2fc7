#pragma once
/// @file A public checker for a user's potential: the invariants every pseudo-potential must
/// satisfy before it is trusted inside an impact law (Ceres's manifold checker, for potentials).
#include <string>
#include <vector>

#include "fremond/potentials/potential.hpp"

namespace fremond {

struct ConformanceOptions {
  /// Sample points are drawn in [−range, range] (and on a log scale down to range·1e-6).
  double range = 10.0;
  /// Number of random sample points (a fixed seed: the check is reproducible).
  int samples = 400;
  /// Prox steps τ tried.
  std::vector<double> taus{1e-3, 0.1, 1.0, 10.0};
  /// Relative tolerance of every equality check.
  double tolerance = 1e-9;
  unsigned seed = 12345;
};

/// What was checked and what failed (each failure is a sentence with the numbers).
struct ConformanceReport {
  bool ok = true;
  std::vector<std::string> failures;
  int checks = 0;
  double max_fenchel_young_gap_at_prox = 0.0;  ///< should be ~0
  double max_moreau_error = 0.0;  ///< |prox_{φ*/τ}(x/τ) − (x − prox_{τφ}(x))/τ|, scaled
  double max_prox_optimality = 0.0;  ///< dist((x − y)/τ, ∂φ(y)), scaled
  std::string summary() const;
};

/// Checks: φ(0) = 0 and φ ≥ 0; convexity along random chords; the subgradient inequality; the prox
/// optimality (x − y)/τ ∈ ∂φ(y); firm non-expansiveness of the prox; the prox derivative in [0, 1]
/// and consistent with finite differences; and, where the conjugate is known, Fenchel–Young ≥ 0
/// everywhere, = 0 at prox points, and the Moreau identity x = prox_{τφ}(x) + τ prox_{φ*/τ}(x/τ)
/// (the conjugate's prox found by a derivative-free search, independent of the potential's prox).
ConformanceReport check_potential(const Potential& potential,
                                  const ConformanceOptions& options = {});

}  // namespace fremond
