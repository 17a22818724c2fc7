#include "fremond/scenes/ball_chain.hpp"

#include <cmath>
#include <string>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"

namespace fremond {

ImpactProblem ball_chain(std::span<const double> masses, std::span<const double> velocity,
                         bool ground) {
  const int n = static_cast<int>(masses.size());
  if (n < 1 || (n < 2 && !ground))
    throw InvalidArgument("masses",
                          "needs two balls, or one on the ground; got " + std::to_string(n));
  for (int i = 0; i < n; ++i)
    if (!(std::isfinite(masses[i]) && masses[i] > 0.0))
      throw InvalidArgument("masses[" + std::to_string(i) + "]",
                            "must be finite and > 0, got " + detail::format_number(masses[i]));
  if (static_cast<int>(velocity.size()) != n)
    throw InvalidArgument("velocity", "must have one entry per ball (" + std::to_string(n) +
                                          "), got " + std::to_string(velocity.size()));
  const int c = n - 1 + (ground ? 1 : 0);
  ImpactProblem pb;
  pb.M = MatrixX::Zero(n, n);
  pb.W_N = MatrixX::Zero(n, c);
  pb.qdot_A = VectorX(n);
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(velocity[i]))
      throw InvalidArgument("velocity[" + std::to_string(i) + "]",
                            "must be finite, got " + detail::format_number(velocity[i]));
    pb.M(i, i) = masses[i];
    pb.qdot_A(i) = velocity[i];
  }
  for (int k = 0; k + 1 < n; ++k) {
    pb.W_N(k, k) = -1.0;
    pb.W_N(k + 1, k) = 1.0;
  }
  if (ground) pb.W_N(0, c - 1) = 1.0;
  pb.W_T = MatrixX::Zero(n, 0);
  return pb;
}

}  // namespace fremond
