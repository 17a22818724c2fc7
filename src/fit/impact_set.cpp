#include "fit/detail/impact_set.hpp"

#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace fremond::detail {

ImpactSet::ImpactSet(std::span<const MeasuredImpact> all, std::vector<int> idx)
    : all_(all), idx_(std::move(idx)) {
  for (const int i : idx_) {
    measured_ += all_[static_cast<std::size_t>(i)].measured();
    small_ = small_ && fits_small(all_[static_cast<std::size_t>(i)].problem);
  }
  // The small form holds no heap memory: a batch of them solves without allocating.
  for (const int i : idx_) {
    const ImpactProblem& pb = all_[static_cast<std::size_t>(i)].problem;
    if (small_)
      small_problems_.push_back(to_small(pb));
    else
      problems_.push_back(pb);
  }
  if (small_)
    small_results_.resize(idx_.size());
  else
    results_.resize(idx_.size());
}

ImpactSet::ImpactSet(std::span<const MeasuredImpact> all)
    : ImpactSet(all, [&all] {
        std::vector<int> idx(all.size());
        std::iota(idx.begin(), idx.end(), 0);
        return idx;
      }()) {}

template <class Results>
int ImpactSet::compare(const Results& results, std::vector<double>& r, std::vector<VectorX>* qdot_E,
                       std::vector<SolverStatus>* status) const {
  r.resize(static_cast<std::size_t>(measured_));
  if (qdot_E) qdot_E->resize(idx_.size());
  if (status) status->resize(idx_.size());
  int failed = 0;
  std::size_t at = 0;
  for (std::size_t k = 0; k < idx_.size(); ++k) {
    const MeasuredImpact& m = all_[static_cast<std::size_t>(idx_[k])];
    const auto& v = results[k].qdot_E;
    bool finite = v.size() == m.qdot_E.size();
    for (Eigen::Index j = 0; finite && j < v.size(); ++j) finite = std::isfinite(v(j));
    failed += finite ? 0 : 1;
    for (std::size_t j = 0; j < m.mask.size(); ++j) {
      if (!m.mask[j]) continue;
      const auto i = static_cast<Eigen::Index>(j);
      r[at++] =
          finite ? (v(i) - m.qdot_E(i)) / m.sigma(i) : std::numeric_limits<double>::quiet_NaN();
    }
    if (qdot_E) {
      if (finite)
        (*qdot_E)[k] = v;
      else
        (*qdot_E)[k] = VectorX::Constant(m.qdot_E.size(), std::numeric_limits<double>::quiet_NaN());
    }
    if (status) (*status)[k] = results[k].solver.status;
  }
  return failed;
}

int ImpactSet::residuals(const ImpactLaw& law, const SolverOptions& options,
                         const BatchOptions& batch, std::vector<double>& r,
                         std::vector<VectorX>* qdot_E, std::vector<SolverStatus>* status) const {
  if (small_) {
    solve_batch(std::span<const SmallImpactProblem>(small_problems_), law,
                std::span<SmallImpactResult>(small_results_), options, batch);
    return compare(small_results_, r, qdot_E, status);
  }
  solve_batch(std::span<const ImpactProblem>(problems_), law, std::span<ImpactResult>(results_),
              options, batch);
  return compare(results_, r, qdot_E, status);
}

}  // namespace fremond::detail
