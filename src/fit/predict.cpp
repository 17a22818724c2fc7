#include "fremond/fit/predict.hpp"

#include <cmath>
#include <string>

#include "fit/detail/impact_set.hpp"
#include "fremond/core/error.hpp"

namespace fremond {

Prediction predict(std::span<const MeasuredImpact> impacts, const ImpactLaw& law,
                   const SolverOptions& options, const BatchOptions& batch) {
  validate(impacts);
  const detail::ImpactSet set(impacts);
  Prediction out;
  std::vector<double> r;
  out.failed = set.residuals(law, options, batch, r, &out.qdot_E, &out.status);
  out.measured = set.measured();
  // Spread the residuals back over each impact's components, NaN where nothing was measured.
  double sum = 0.0;
  int counted = 0;
  std::size_t at = 0;
  out.residuals.resize(impacts.size());
  for (std::size_t k = 0; k < impacts.size(); ++k) {
    const MeasuredImpact& m = impacts[k];
    VectorX& res = out.residuals[k];
    res = VectorX::Constant(m.qdot_E.size(), std::nan(""));
    for (std::size_t j = 0; j < m.mask.size(); ++j) {
      if (!m.mask[j]) continue;
      const double x = r[at++];
      res(static_cast<Eigen::Index>(j)) = x;
      if (std::isfinite(x)) {
        sum += x * x;
        ++counted;
      }
    }
  }
  out.rms = counted > 0 ? std::sqrt(sum / counted) : std::nan("");
  return out;
}

}  // namespace fremond
