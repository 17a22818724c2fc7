#include "fremond/solvers/solver_options.hpp"

#include <cmath>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"

namespace fremond {

bool SolverOptions::is_valid(std::string* why) const {
  auto fail = [&](const std::string& s) {
    if (why) *why = s;
    return false;
  };
  using detail::format_number;
  if (!(tolerance >= 1e-16 && tolerance <= 1e-2))
    return fail("tolerance: must lie in [1e-16, 1e-2], got " + format_number(tolerance));
  if (!(nlopt_tolerance >= 1e-16 && nlopt_tolerance <= 1e-2))
    return fail("nlopt_tolerance: must lie in [1e-16, 1e-2], got " +
                format_number(nlopt_tolerance));
  if (max_iterations < 1)
    return fail("max_iterations: must be >= 1, got " + std::to_string(max_iterations));
  if (max_proximal_iterations < 1)
    return fail("max_proximal_iterations: must be >= 1, got " +
                std::to_string(max_proximal_iterations));
  if (max_nlopt_evaluations < 1)
    return fail("max_nlopt_evaluations: must be >= 1, got " +
                std::to_string(max_nlopt_evaluations));
  if (!(admissibility_tolerance >= 0.0 && admissibility_tolerance < 1.0))
    return fail("admissibility_tolerance: must lie in [0, 1), got " +
                format_number(admissibility_tolerance));
  return true;
}

void SolverOptions::validate() const {
  std::string why;
  if (!is_valid(&why)) {
    const auto colon = why.find(':');
    throw InvalidArgument(why.substr(0, colon), why.substr(colon + 2));
  }
}

}  // namespace fremond
