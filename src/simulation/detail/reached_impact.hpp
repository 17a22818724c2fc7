#pragma once
// The impact of a state a run reached, solved by either run (one body, several bodies).
#include <optional>
#include <string_view>

#include "fremond/core/error.hpp"
#include "fremond/solvers/solve_impact.hpp"

namespace fremond::detail {

/// What a run says when it stops on such an impact.
inline constexpr std::string_view kImpactOverflow =
    "an impact problem the run reached cannot be posed in double precision (a velocity or "
    "energy overflows)";

/// solve_impact, or nothing where the problem cannot be posed. The scene's checks refuse what the
/// first impact would refuse, but a state reached later can still overflow what an impact computes
/// (a fall under g = 1.5e308 m/s² reaches a speed whose kinetic energy is not a double): that is
/// the run's outcome, not bad input, and the run stops with a status, keeping what it has written.
template <class Problem>
auto solve_reached_impact(const Problem& pb, const ImpactLaw& law, const SolverOptions& options)
    -> std::optional<decltype(solve_impact(pb, law, options))> {
  try {
    return solve_impact(pb, law, options);
  } catch (const InvalidArgument&) {
    return std::nullopt;
  }
}

}  // namespace fremond::detail
