#include "fremond/fit/measured_impact.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"

namespace fremond {

int MeasuredImpact::measured() const {
  int count = 0;
  for (const bool m : mask) count += m ? 1 : 0;
  return count;
}

void validate(const MeasuredImpact& impact) {
  validate(impact.problem);
  const auto n = static_cast<std::size_t>(impact.problem.dofs());
  const auto has = [n](std::size_t size, const char* what, const char* name) {
    if (size != n)
      throw InvalidArgument(name, std::string("must have ") + std::to_string(n) + " entries (" +
                                      what + "), got " + std::to_string(size));
  };
  has(static_cast<std::size_t>(impact.qdot_E.size()), "one per degree of freedom, like qdot_A",
      "qdot_E");
  has(impact.mask.size(), "one per component of qdot_E", "mask");
  has(static_cast<std::size_t>(impact.sigma.size()), "one per component of qdot_E", "sigma");
  if (impact.measured() == 0)
    throw InvalidArgument("mask", "measures no component: the impact says nothing about a law");
  for (std::size_t j = 0; j < n; ++j) {
    if (!impact.mask[j]) continue;  // not measured: its values are not read
    const auto i = static_cast<Eigen::Index>(j);
    // Built by appending: GCC 12 warns (-Wrestrict, falsely) on "[" + std::to_string(j).
    std::string at = "[";
    at += std::to_string(j);
    at += ']';
    if (!std::isfinite(impact.qdot_E(i)))
      throw InvalidArgument("qdot_E" + at, "a measured component must be a finite number, got " +
                                               detail::format_number(impact.qdot_E(i)));
    if (!std::isfinite(impact.sigma(i)) || !(impact.sigma(i) > 0.0))
      throw InvalidArgument("sigma" + at, "must be a finite number > 0, got " +
                                              detail::format_number(impact.sigma(i)));
  }
}

void validate(std::span<const MeasuredImpact> impacts) {
  if (impacts.empty()) throw InvalidArgument("impacts", "holds no impact");
  for (std::size_t i = 0; i < impacts.size(); ++i) {
    try {
      validate(impacts[i]);
    } catch (const InvalidArgument& e) {
      const std::string what = e.what();
      throw InvalidArgument("impacts[" + std::to_string(i) + "]." + e.name(),
                            what.substr(e.name().size() + 2));
    }
  }
}

MeasuredImpact measured_impact(ImpactProblem problem, VectorX qdot_E) {
  MeasuredImpact m;
  const auto n = static_cast<std::size_t>(problem.dofs());
  m.problem = std::move(problem);
  m.qdot_E = std::move(qdot_E);
  m.mask.assign(n, true);
  m.sigma = VectorX::Ones(static_cast<Eigen::Index>(n));
  return m;
}

}  // namespace fremond
