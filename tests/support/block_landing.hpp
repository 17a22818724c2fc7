#pragma once
/// @file A block landing flat on both corners (tests/support: the shared problems).
#include "fremond/core/impact_problem.hpp"

namespace fremond::fixtures {

/// A block (m = 1, 0.4 × 0.2 m) landing flat on both lower corners, as a Moreau–Jean step met it:
/// under Frémond + Coulomb (p = 3, k = block_landing_flat_k, μ = 1) one corner slides backwards at
/// the edge of sticking while the other sticks.
inline ImpactProblem block_landing_flat() {
  ImpactProblem pb;
  pb.M = Eigen::Vector3d(1.0, 1.0, (0.16 + 0.04) / 12.0).asDiagonal();
  pb.W_N.resize(3, 2);
  pb.W_N << 0.0, 0.0, 1.0, 1.0, -0.20000086717102675, 0.19999913281393331;
  pb.W_T.resize(3, 2);
  pb.W_T << 1.0, 1.0, 0.0, 0.0, 0.099998265639146544, 0.10000173435333348;
  pb.qdot_A = Eigen::Vector3d(-2.3912283507627192, -3.2660445632676076, 0.0);
  return pb;
}
inline constexpr double block_landing_flat_k = 63.183050987687373;
}  // namespace fremond::fixtures
