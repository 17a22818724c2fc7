#pragma once
/// @file Ready-made scenes: the paper's bar (the paper's Fig. 1), a ball and a rectangular block,
/// each on the ground y = 0, and the laws the paper compares.
#include <string_view>

#include "fremond/scenes/multibody.hpp"
#include "fremond/scenes/scene.hpp"

namespace fremond {

/// A uniform bar of length 2l, its two ends as contact points (r = (∓l, 0)), J = m l²/3 (the
/// paper's Fig. 1). Defaults: the paper's bar and initial state (§3): x = 0, ẋ = 2, y = 1, ẏ = 0, θ
/// = π/4, θ̇ = 0.
struct BarParameters {
  double mass = 1.0;         ///< kg
  double half_length = 0.5;  ///< l (m); the paper does not give it, docs/laws.md fixes 0.5.
  double gravity = 9.81;     ///< m/s²
  PlanarState initial{Eigen::Vector3d(0.0, 1.0, 0.78539816339744830962),
                      Eigen::Vector3d(2.0, 0.0, 0.0)};
};
Scene bar_scene(const BarParameters& bar, ImpactLaw law);

/// A ball (a solid sphere moving in the plane, J = 2 m ρ²/5): one point at the centre with radius
/// ρ. Defaults: dropped at rest from a height of 1 m (its lowest point), not spinning.
struct BallParameters {
  double mass = 1.0;      ///< kg
  double radius = 0.1;    ///< ρ (m)
  double gravity = 9.81;  ///< m/s²
  PlanarState initial{Eigen::Vector3d(0.0, 1.1, 0.0), Eigen::Vector3d::Zero()};
};
Scene ball_scene(const BallParameters& ball, ImpactLaw law);

/// A uniform rectangular block w × h, J = m (w² + h²)/12, its four corners as contact points
/// (in the order (−w/2, −h/2), (w/2, −h/2), (w/2, h/2), (−w/2, h/2)).
/// Defaults: dropped from 0.5 m, tilted by 0.3 rad, sliding at 1 m/s.
struct BlockParameters {
  double mass = 1.0;      ///< kg
  double width = 0.4;     ///< m
  double height = 0.2;    ///< m
  double gravity = 9.81;  ///< m/s²
  PlanarState initial{Eigen::Vector3d(0.0, 0.5, 0.3), Eigen::Vector3d(1.0, 0.0, 0.0)};
};
Scene block_scene(const BlockParameters& block, ImpactLaw law);

/// A uniform bar of length 2l leaning at angle θ from the ground against a wall on its right: its
/// lower end (r = (−l, 0)) on the ground y = 0, its upper end (r = (+l, 0)) against the wall x =
/// `wall`, both touching at the initial state. Obstacles [ground, wall], so contact 0 is the lower
/// end on the ground and contact 3 the upper end against the wall (scene.hpp). Defaults: θ = 0.2,
/// both ends approaching at 1 m/s, q̇ = (1, −1, 0): the two-contact impact on which Poisson's law
/// with Coulomb friction on the ground creates energy (docs/atlas.md), as no single contact can.
struct LadderParameters {
  double mass = 1.0;                         ///< kg
  double half_length = 0.5;                  ///< l (m)
  double angle = 0.2;                        ///< θ in (0, π/2) (rad)
  double wall = 1.0;                         ///< the wall's x (m)
  double gravity = 9.81;                     ///< m/s²
  Eigen::Vector3d velocity{1.0, -1.0, 0.0};  ///< q̇ at the initial state
};
/// Throws InvalidArgument naming `angle` outside (0, π/2), or a field the scene refuses.
Scene ladder_scene(const LadderParameters& ladder, ImpactLaw law);

/// Newton's cradle: `balls` equal balls (solid spheres, J = 2 m ρ²/5) in a row along x, touching,
/// centres at x = 2ρi, y = 0, the first (ball 0) striking the others at `speed` along +x. The
/// strings hold the balls against gravity and take no part in the impact: g = 0 and no obstacle,
/// so the contacts are the pairs of balls (i < j, multibody.hpp's order) and the impact at t = 0
/// is that of ball_chain(masses, velocity).
struct CradleParameters {
  int balls = 3;        ///< ≥ 2
  double mass = 1.0;    ///< kg
  double radius = 0.1;  ///< ρ (m)
  double speed = 1.0;   ///< the struck ball's velocity (m/s)
};
/// Throws InvalidArgument naming `balls` (< 2, or more pairs than kMaxMultiBodyContacts) or a
/// field the scene refuses.
MultiBodyScene cradle_scene(const CradleParameters& cradle, ImpactLaw law);

/// A ball dropped on an equal ball resting on the ground y = 0 (solid spheres, J = 2 m ρ²/5):
/// ball 0 at rest on the ground (centre y = ρ), ball 1 above it, its lowest point `drop_height`
/// above ball 0's top, falling at `speed` (m/s, ≥ 0, downwards). Contacts: ball 0 on the ground,
/// ball 1 on the ground, the pair (multibody.hpp's order). With drop_height = 0 the impact is at
/// t = 0 and is that of ball_chain({m, m}, {0, −speed}, ground).
struct BallOnBallParameters {
  double mass = 1.0;         ///< kg
  double radius = 0.1;       ///< ρ (m)
  double drop_height = 0.5;  ///< m, ≥ 0
  double speed = 0.0;        ///< m/s, ≥ 0
  double gravity = 9.81;     ///< m/s²
};
MultiBodyScene ball_on_ball_scene(const BallOnBallParameters& drop, ImpactLaw law);

/// The five laws of the paper (the paper's Fig. 1), by their command-line names.
enum class PaperLaw {
  newton,           ///< Newton, e = 0.9, frictionless (§3, Figs. 2-3).
  newton_coulomb,   ///< Newton + Coulomb, e = 0.9, μ = 1 (§4, Figs. 4-5).
  poisson_coulomb,  ///< Poisson + Coulomb, e = 0.9, μ = 1 (§4, Figs. 6-7).
  fremond_coulomb,  ///< Frémond p = 3 + Coulomb on the mean velocity, μ = 1 (§5, Figs. 10-11).
  fremond_viscous,  ///< Frémond p = 3 + viscous dead zone k_T = 1.5, q = 2, r = 0.2 in the
                    ///< library's scaling (the paper's k_T = 0.75, r = 0.4; §5.4, Figs. 12-13).
  stronge_coulomb,  ///< Stronge's energetic e* = 0.9 + Coulomb μ = 1 (not in the paper: the
                    ///< classical energy-consistent answer, docs/stronge.md).
};
std::string_view to_string(PaperLaw l);
/// Throws InvalidArgument("law", ...) naming the accepted values.
PaperLaw paper_law_from_string(std::string_view s);

/// The paper's constants (the paper's Fig. 1).
struct PaperConstants {
  static constexpr double e = 0.9;
  static constexpr double mu = 1.0;
  static constexpr double p = 3.0;    ///< Frémond's normal exponent.
  static constexpr double k_T = 1.5;  ///< viscous dead zone, the library's scaling (paper: 0.75).
  static constexpr double q = 2.0;
  static constexpr double r = 0.2;  ///< the library's scaling (paper: 0.4).
};

/// The paper's law with its parameters; `k_N` is Frémond's normal stiffness (unused by the
/// classical laws). The simulation module computes k_N as docs/laws.md asks (paper_bar_scene()).
ImpactLaw paper_law(PaperLaw law, double k_N);

}  // namespace fremond
