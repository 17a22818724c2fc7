#pragma once
/// @file The storage the laws' chains keep from one solve to the next (docs/solvers.md).
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "solvers/nsgs/contact_rows.hpp"
#include "solvers/nsgs/sweeps.hpp"

namespace fremond::detail {

/// Room, not state: a solve writes everything it reads, so any solve may use any workspace. The
/// one-shot solve_impact makes one for its solve; the prepared solver keeps one, whose storage the
/// next solve of the same shape then reuses instead of allocating it again. Its parts are by the
/// stage that uses them.
struct ChainWorkspace {
  /// Whether the storage outlives the stage that made it (a caller that solves again); else the
  /// stage frees it when done, where a one-shot solve's heap blocks are best freed.
  bool persistent = false;
  /// Newton's law on many contacts (the classical chain's sweeps, classical.cpp): the contact
  /// space's rows grouped by contact, and the sweeps' and mode Newton's own storage.
  struct Sweeps {
    Layout layout;
    Eigen::VectorXd D_A, P;
    std::vector<double> e, mu;
    SweepWorkspace run;
  };
  /// Made by the first solve that runs the sweeps (an empty sparse matrix allocates already).
  std::optional<Sweeps> sweeps;
};

}  // namespace fremond::detail
