#pragma once
/// @file Several planar rigid bodies against fixed half-planes and against each other: the scenes
/// where multiple-impact laws differ (Newton's cradle, a ball dropped on a resting ball).
///
/// A separate type from Scene (one body, scene.hpp), which the paper's results use unchanged; the
/// body, its points and the half-planes are the same types. Coordinates q = (x₀, y₀, θ₀, x₁, y₁,
/// θ₁, ...): three per body, in the order of `bodies`. Contacts, in this order (contact_count()):
///  1. every (body, point, obstacle), body first, then point, then obstacle: as Scene's, body by
///     body;
///  2. every pair of disks (points of radius > 0) of two bodies a < b, by a, then b, then a's
///     point, then b's point.
/// A disk pair is an obstacle contact seen from body b, with a moving obstacle: the normal n is the
/// unit vector from a's disk centre to b's, the tangent t = (n_y, −n_x) as for a half-plane
/// (kinematics.hpp), so that D_N = n·(v_b − v_a) and D_T = t·(v_b − v_a) at the contact point
/// (> 0: separating), and W's column has body b's entries of an obstacle contact with normal n,
/// and body a's with the signs reversed (a's contact point is on a's rim, at +ρ_a n).
#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include "fremond/core/impact_problem.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/scenes/scene.hpp"

namespace fremond {

/// The largest number of contacts a scene of several bodies may have (pairs of disks grow as the
/// square of the disks).
inline constexpr int kMaxMultiBodyContacts = 64;

/// One contact of a MultiBodyScene: body `body`'s point `point` against obstacle `obstacle`
/// (other_body < 0), or against point `other_point` of body `other_body` (< body, so that the
/// normal points from the other body to `body`).
struct BodyContact {
  int body = 0;
  int point = 0;
  int obstacle = -1;    ///< the half-plane, or −1 for a disk pair.
  int other_body = -1;  ///< the other body of a disk pair, or −1.
  int other_point = -1;
  bool is_pair() const { return other_body >= 0; }
};

/// Positions and velocities of every body, three entries each.
struct MultiBodyState {
  Eigen::VectorXd q, qdot;
};

/// Bodies, obstacles, gravity, the initial state and the impact law of every contact.
struct MultiBodyScene {
  std::vector<PlanarBody> bodies;
  std::vector<HalfPlane> obstacles;  ///< may be empty.
  double gravity = 9.81;             ///< g ≥ 0 along −y (m/s²).
  MultiBodyState initial;
  /// The law of every impact; per-contact parameters have one value per contact, in the order of
  /// contacts().
  ImpactLaw law;

  int dofs() const { return 3 * static_cast<int>(bodies.size()); }
  /// The contacts in the order of the file comment; recomputed from bodies and obstacles.
  std::vector<BodyContact> contacts() const;
  int contact_count() const { return static_cast<int>(contacts().size()); }

  /// Checks every value as Scene::validate does, named as the scene file spells them
  /// (`bodies[1].mass`, `bodies[0].points[2].radius`, `obstacles[0].normal`, `initial.q`,
  /// `law.e`, ...): at least one body, each with a point; initial q, q̇ of 3 entries per body; at
  /// least one contact and at most kMaxMultiBodyContacts; no two disks of a pair at one centre at
  /// the initial state (their normal is undefined). Normalises the obstacle normals.
  void validate();
};

/// The gap and the two bodies' parts of W_N, W_T of one contact (body a = the other body of a
/// disk pair, zero for an obstacle contact).
struct PairFrame {
  double gap = 0.0;  ///< (m), < 0 in penetration.
  Eigen::Vector3d W_N_b = Eigen::Vector3d::Zero(), W_T_b = Eigen::Vector3d::Zero();
  Eigen::Vector3d W_N_a = Eigen::Vector3d::Zero(), W_T_a = Eigen::Vector3d::Zero();
};

/// The frame of `contact` at configuration q (3 entries per body) of a validated scene.
PairFrame contact_frame(const MultiBodyScene& scene, const BodyContact& contact,
                        const Eigen::Ref<const Eigen::VectorXd>& q);

/// The indices (into contacts()) of the contacts whose gap at q is at most `tolerance`.
std::vector<int> touching_contacts(const MultiBodyScene& scene,
                                   const Eigen::Ref<const Eigen::VectorXd>& q,
                                   double tolerance = 1e-9);

/// The impact problem of the contacts `which` (indices into contacts()) at `state`:
/// M = blockdiag(diag(m, m, J)) of every body, W_N and W_T with one column per contact built from
/// both of its bodies, q̇_A = state.qdot. Throws InvalidArgument naming `contacts` for an index
/// out of range and `state` for sizes that do not match the scene.
ImpactProblem impact_problem(const MultiBodyScene& scene, const MultiBodyState& state,
                             std::span<const int> which);
/// The scene's law restricted to the contacts `which`, in their order.
ImpactLaw law_of(const MultiBodyScene& scene, std::span<const int> which);

/// Total energy Σ ½ q̇ᵢᵀMᵢq̇ᵢ + mᵢ g yᵢ.
double energy(const MultiBodyScene& scene, const MultiBodyState& state);
/// Σ mᵢ q̇ᵢ: the linear momentum (x, y).
Eigen::Vector2d momentum(const MultiBodyScene& scene,
                         const Eigen::Ref<const Eigen::VectorXd>& qdot);

}  // namespace fremond
