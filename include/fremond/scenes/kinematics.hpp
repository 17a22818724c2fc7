#pragma once
/// @file Contact kinematics of a planar rigid body against a half-plane (the paper's Fig. 1).
///
/// For a point at body-frame r (radius ρ) and a half-plane with unit normal n and tangent
/// t = (n_y, −n_x) (t = (1, 0) on the ground), the material contact point is a = R(θ) r − ρ n
/// from the centre of mass, and
///   gap  g   = n·(c + R(θ) r) − offset − ρ,
///   W_N      = (n_x, n_y, (a × n)_z),   D_N = W_Nᵀ q̇ = ġ,
///   W_T      = (t_x, t_y, (a × t)_z),   D_T = W_Tᵀ q̇.
/// For the paper's bar at θ = π/4 the lower end a = (−l cos θ, −l sin θ) gives
/// W_N = (0, 1, −l cos θ) and W_T = (1, 0, l sin θ), as in the paper's Fig. 1.
#include <Eigen/Core>

#include "fremond/scenes/scene.hpp"

namespace fremond {

/// The gap and the contact directions of one contact at one configuration.
struct ContactFrame {
  double gap = 0.0;                               ///< signed distance (m), < 0 in penetration.
  Eigen::Vector3d W_N = Eigen::Vector3d::Zero();  ///< normal direction in q̇-space.
  Eigen::Vector3d W_T = Eigen::Vector3d::Zero();  ///< tangential direction in q̇-space.
};

/// The tangent of a half-plane, t = (n_y, −n_x).
inline Eigen::Vector2d tangent_of(const Eigen::Vector2d& n) {
  return {n.y(), -n.x()};
}

/// Contact frame of `point` against `plane` with the body at centre c and angle θ given by its
/// cosine and sine (so that one sin/cos serves every contact). `plane.normal` must be a unit
/// vector.
inline ContactFrame contact_frame(const ContactPoint& point, const HalfPlane& plane,
                                  const Eigen::Vector2d& c, double cos_theta, double sin_theta) {
  const Eigen::Vector2d& n = plane.normal;
  const Eigen::Vector2d t = tangent_of(n);
  const Eigen::Vector2d Rr{cos_theta * point.r.x() - sin_theta * point.r.y(),
                           sin_theta * point.r.x() + cos_theta * point.r.y()};
  const Eigen::Vector2d a = Rr - point.radius * n;
  ContactFrame f;
  f.gap = n.dot(c + Rr) - plane.offset - point.radius;
  f.W_N = {n.x(), n.y(), a.x() * n.y() - a.y() * n.x()};
  f.W_T = {t.x(), t.y(), a.x() * t.y() - a.y() * t.x()};
  return f;
}

/// Contact frame of contact k of a validated scene at configuration q.
ContactFrame contact_frame(const Scene& scene, int contact, const Eigen::Vector3d& q);

}  // namespace fremond
