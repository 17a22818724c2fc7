#pragma once
// Private to the library: some of the measured impacts, set up once as a batch (in the small form
// when every one fits it), solved under one law after another: the fit's objective, the folds'
// held-out error, the predictions.
#include <span>
#include <vector>

#include "fremond/fit/measured_impact.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/solve_batch.hpp"

namespace fremond::detail {

class ImpactSet {
 public:
  /// The impacts all[idx[0]], all[idx[1]], ... (already validated); `all` must outlive the set.
  ImpactSet(std::span<const MeasuredImpact> all, std::vector<int> idx);
  /// Every impact of `all`.
  explicit ImpactSet(std::span<const MeasuredImpact> all);

  int size() const { return static_cast<int>(idx_.size()); }
  /// The measured components, summed over the set: the length of residuals().
  int measured() const { return measured_; }
  const std::vector<int>& indices() const { return idx_; }

  /// Solves the set under `law` and writes the weighted residuals (q̇_E,law − qdot_E)_j / sigma_j
  /// of the measured components, impact after impact, into r (resized to measured()); an impact
  /// whose solve gives no finite velocity has NaN residuals. Returns the count of such impacts.
  /// With qdot_E and status, also each impact's velocity after and solver status.
  int residuals(const ImpactLaw& law, const SolverOptions& options, const BatchOptions& batch,
                std::vector<double>& r, std::vector<VectorX>* qdot_E = nullptr,
                std::vector<SolverStatus>* status = nullptr) const;

 private:
  template <class Results>
  int compare(const Results& results, std::vector<double>& r, std::vector<VectorX>* qdot_E,
              std::vector<SolverStatus>* status) const;

  std::span<const MeasuredImpact> all_;
  std::vector<int> idx_;
  int measured_ = 0;
  bool small_ = true;
  std::vector<SmallImpactProblem> small_problems_;
  std::vector<ImpactProblem> problems_;
  mutable std::vector<SmallImpactResult> small_results_;
  mutable std::vector<ImpactResult> results_;
};

}  // namespace fremond::detail
