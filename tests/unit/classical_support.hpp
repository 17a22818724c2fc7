#pragma once
// Scenes and independent references for the tests of the classical laws (the paper's Fig. 1, paper
// Fig. 1).
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <numbers>

#include "fremond/fremond.hpp"
#include "support/fixtures.hpp"

namespace fremond::test {

inline constexpr double kM = 1.0, kL = 0.5, kJ = kM * kL * kL / 3, kG = 9.81;

/// The bar of the paper's Fig. 1 with its lower end on the ground at angle θ: W_N = (0, 1, −l cos
/// θ), W_T = (1, 0, l sin θ), M = diag(m, m, J).
inline ImpactProblem bar(double theta, const Eigen::Vector3d& qdot, bool friction = true) {
  return fixtures::bar(theta, qdot, false, kM, friction);
}

/// ẏ just before the first impact: free fall of the centre from y = 1 to l sin(π/4).
inline double first_impact_ydot() {
  return -std::sqrt(2 * kG * (1.0 - kL * std::sin(std::numbers::pi / 4)));
}

/// The paper's bar at its first impact: θ = π/4, q̇_A = (2, ẏ, 0).
inline ImpactProblem bar_first_impact(bool friction = true) {
  return bar(std::numbers::pi / 4, Eigen::Vector3d(2.0, first_impact_ydot(), 0.0), friction);
}

/// The bar lying flat (θ = 0), both ends on the ground: W_N = (0, 1, ∓l), W_T = (1, 0, 0) twice,
/// so the 4×4 G has rank 3.
inline ImpactProblem flat_bar(const Eigen::Vector3d& qdot, bool friction = true) {
  ImpactProblem p;
  p.M = Eigen::Vector3d(kM, kM, kJ).asDiagonal();
  p.W_N.resize(3, 2);
  p.W_N << 0, 0, 1, 1, -kL, kL;
  if (friction) {
    p.W_T.resize(3, 2);
    p.W_T << 1, 1, 0, 0, 0, 0;
  } else {
    p.W_T.resize(3, 0);
  }
  p.qdot_A = qdot;
  return p;
}

/// A point mass on the ground y = 0: G = I/m, no coupling between normal and tangential.
inline ImpactProblem point_mass(double vx, double vy, double m = 1.0, bool friction = true) {
  ImpactProblem p;
  p.M = Eigen::Matrix2d::Identity() * m;
  p.W_N = Eigen::Vector2d(0, 1);
  p.W_T = friction ? MatrixX(Eigen::Vector2d(1, 0)) : MatrixX(2, 0);
  p.qdot_A = Eigen::Vector2d(vx, vy);
  return p;
}

inline double kinetic(const ImpactProblem& p, const VectorX& qdot) {
  return 0.5 * qdot.dot(p.M * qdot);
}

/// q̇_E = q̇_A + M⁻¹(W_N P_N + W_T P_T), from the data (the impact equation, docs/concepts.md).
inline VectorX velocity_after(const ImpactProblem& p, const VectorX& PN, const VectorX& PT) {
  VectorX f = p.W_N * PN;
  if (p.has_tangential()) f += p.W_T * PT;
  return p.qdot_A + p.M.llt().solve(f);
}

}  // namespace fremond::test
