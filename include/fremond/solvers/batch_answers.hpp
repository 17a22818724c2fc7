#pragma once
/// @file A batch's answers as columns, one per impact (docs/solvers.md#batches): what a sweep or a
/// Monte Carlo run keeps of each solve, without its whole result.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "fremond/solvers/solver_status.hpp"

namespace fremond {

/// Column i (entry i) is impact i's: q̇_E, the percussions and the contact velocities after, as its
/// ImpactResult has them, and its energy change, residual, status, certificate verdict and
/// uniqueness. A result holds about 1 KB (its fixed-capacity vectors, attempts and certificate);
/// these columns hold 8 (n + 4c + 2) + 3 bytes an impact: ten million bar impacts keep in 1 GB
/// instead of 11 GB.
struct BatchAnswers {
  Eigen::MatrixXd qdot_E;                ///< n × N: the velocities after the impact
  Eigen::MatrixXd P_N;                   ///< c × N: normal percussions
  Eigen::MatrixXd P_T;                   ///< c × N: tangential percussions (zero without W_T)
  Eigen::MatrixXd D_NE;                  ///< c × N: normal contact velocities after the impact
  Eigen::MatrixXd D_TE;                  ///< c × N: tangential contact velocities after the impact
  Eigen::VectorXd energy_change;         ///< N: T_E − T_A
  Eigen::VectorXd residual;              ///< N: the law's scaled residual (solver.residual)
  std::vector<SolverStatus> status;      ///< N: solver.status
  std::vector<std::uint8_t> admissible;  ///< N: admissibility.admissible (1 or 0)
  std::vector<std::uint8_t> unique;      ///< N: unique (1 or 0)

  /// Room for `count` impacts of n degrees of freedom and c contacts (the storage kept where the
  /// sizes already match).
  void resize(Eigen::Index n, Eigen::Index c, Eigen::Index count) {
    qdot_E.resize(n, count);
    for (Eigen::MatrixXd* m : {&P_N, &P_T, &D_NE, &D_TE}) m->resize(c, count);
    energy_change.resize(count);
    residual.resize(count);
    status.resize(static_cast<std::size_t>(count));
    admissible.resize(static_cast<std::size_t>(count));
    unique.resize(static_cast<std::size_t>(count));
  }
  /// The number of impacts held.
  Eigen::Index size() const { return energy_change.size(); }
};

}  // namespace fremond
