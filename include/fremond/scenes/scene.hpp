#pragma once
/// @file A planar rigid body against fixed half-planes: what the paper's scene (Fig. 1, the paper's
/// Fig. 1) needs, and no more.
///
/// Coordinates q = (x, y, θ): the centre of mass and the angle of the body frame. Gravity pulls
/// along −y. A contact is one (point, obstacle) pair; contact k is point k / obstacles, obstacle
/// k % obstacles, so the paper's bar on the ground has contact 0 at its end r = (−l, 0) (the lower
/// end at θ = π/4) and contact 1 at r = (+l, 0).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "fremond/laws/impact_law.hpp"

namespace fremond {

/// A point of the body, in the body frame, that can touch an obstacle; a positive radius makes it
/// a disk (a ball is one point at r = 0 with a radius).
struct ContactPoint {
  Eigen::Vector2d r = Eigen::Vector2d::Zero();  ///< position in the body frame (m).
  double radius = 0.0;                          ///< ≥ 0 (m).
};

/// Mass, centroidal inertia and contact points of a planar rigid body.
struct PlanarBody {
  double mass = 1.0;     ///< m > 0 (kg).
  double inertia = 1.0;  ///< J > 0, about the centre of mass (kg m²).
  std::vector<ContactPoint> points;

  /// M = diag(m, m, J).
  Eigen::Matrix3d mass_matrix() const;
};

/// The fixed half-plane {p : n·p ≥ offset}, free space on the side n points to (n is normalised
/// when the scene is validated). The ground y ≥ 0 is n = (0, 1), offset 0; a wall at x = 2 with
/// the body on its left is n = (−1, 0), offset −2.
struct HalfPlane {
  Eigen::Vector2d normal{0.0, 1.0};
  double offset = 0.0;  ///< (m)
};

/// Position and velocity q = (x, y, θ), q̇ = (ẋ, ẏ, θ̇).
struct PlanarState {
  Eigen::Vector3d q = Eigen::Vector3d::Zero();
  Eigen::Vector3d qdot = Eigen::Vector3d::Zero();
};

/// A body, its obstacles, gravity, the initial state and the impact law of every contact.
struct Scene {
  PlanarBody body;
  std::vector<HalfPlane> obstacles;
  double gravity = 9.81;  ///< g ≥ 0 along −y (m/s²).
  PlanarState initial;
  /// The law of every impact. Per-contact parameters (lists) have one value per contact, in the
  /// order of contact_count().
  ImpactLaw law;

  /// Number of (point, obstacle) pairs.
  int contact_count() const { return static_cast<int>(body.points.size() * obstacles.size()); }
  int point_of(int contact) const { return contact / static_cast<int>(obstacles.size()); }
  int obstacle_of(int contact) const { return contact % static_cast<int>(obstacles.size()); }

  /// Checks every value (mass, inertia > 0 and within a factor 1e24 of each other, so that every
  /// impact problem's M = diag(m, m, J) passes validate(); radii ≥ 0; non-zero normals; finite
  /// numbers, the initial energy and contact velocities included; at least one point and one
  /// obstacle; at most kMaxSceneContacts contacts; the law for contact_count() contacts) and
  /// normalises the obstacle normals. Throws InvalidArgument naming the field as the
  /// scene file spells it (`body.mass`, `obstacles[1].normal`, `initial.q`, `law.e`, ...).
  void validate();
};

namespace detail {
/// Throws InvalidArgument(name, reason + ...) unless M = diag(mass, mass, inertia) passes the
/// positive-definiteness test every impact problem is put to (laws/impact_problem.hpp): a scene
/// whose M fails it would be refused at its first impact, after its output had begun.
void require_usable_mass_matrix(const std::string& name, double mass, double inertia,
                                const std::string& reason);
/// Scene::validate's checks of one body, its keys named `<name>.mass`, `<name>.points[i].r`, ...
void validate_body(const std::string& name, const PlanarBody& body);
/// Scene::validate's checks of the half-planes (named `obstacles[i]...`); normalises the normals.
void validate_obstacles(std::vector<HalfPlane>& obstacles);
}  // namespace detail

/// The largest number of (point, obstacle) pairs a scene may have (the bounded storage of the
/// impact log).
inline constexpr int kMaxSceneContacts = 16;

/// Total energy ½ q̇ᵀMq̇ + m g y (the paper's Fig. 1).
double energy(const Scene& scene, const PlanarState& state);
/// Kinetic energy ½ q̇ᵀMq̇.
double kinetic_energy(const PlanarBody& body, const Eigen::Vector3d& qdot);

}  // namespace fremond
