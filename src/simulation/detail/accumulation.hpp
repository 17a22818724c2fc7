#pragma once
// Accumulations of impacts (simulate.hpp): telling one from the times of the event impacts, and
// closing it by taking the small normal velocity of the touching contacts' last bounce away.
#include <Eigen/Core>
#include <array>
#include <optional>

#include "fremond/scenes/scene.hpp"
#include "fremond/simulation/simulation_options.hpp"

namespace fremond::detail {

/// The times of the event impacts since the last change of phase.
class AccumulationDetector {
 public:
  void reset() { n_times_ = 0; }
  /// Records an event impact at time t. When it ends an accumulation — the last
  /// options.accumulation_impacts intervals between impacts each shorter than the one before and
  /// than options.accumulation_interval, or all within rounding of t — returns the extrapolated
  /// remaining time t∞ − t of the geometric tail (0 for impacts stuck at one time), at most up to
  /// t_end.
  std::optional<double> add(double t, const SimulationOptions& options);

 private:
  std::array<double, 64> times_{};
  int n_times_ = 0;
};

using ContactNormals =
    Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxSceneContacts>;  ///< W_N, column per contact
using ContactMultipliers = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxSceneContacts, 1>;

/// The M-orthogonal projection of q̇ onto W_Nᵀq̇ = 0: q̇ − M⁻¹W_N λ with the minimum-norm λ of
/// (W_Nᵀ M⁻¹ W_N) λ = W_Nᵀq̇ (the touching contacts may be dependent). It can only lower the
/// kinetic energy.
struct AccumulationClosing {
  ContactMultipliers lambda;
  Eigen::Vector3d qdot;
};
AccumulationClosing close_normal_velocities(const ContactNormals& W_N, const Eigen::Vector3d& minv,
                                            const Eigen::Vector3d& qdot);

}  // namespace fremond::detail
