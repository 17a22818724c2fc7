// The preset scenes and the paper's laws (the paper's Fig. 1).
#include "fremond/scenes/presets.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "core/detail/validate.hpp"
#include "fremond/core/enum_names.hpp"
#include "fremond/core/error.hpp"
#include "fremond/potentials/deadzone_power.hpp"
#include "fremond/potentials/power.hpp"

namespace fremond {

namespace {
constexpr detail::EnumNames<PaperLaw, 6> kPaperLaws{
    {{PaperLaw::newton, "newton"},
     {PaperLaw::newton_coulomb, "newton_coulomb"},
     {PaperLaw::poisson_coulomb, "poisson_coulomb"},
     {PaperLaw::fremond_coulomb, "fremond_coulomb"},
     {PaperLaw::fremond_viscous, "fremond_viscous"},
     {PaperLaw::stronge_coulomb, "stronge_coulomb"}}};

// `dimensions` names what the inertia was computed from, for the one error they can cause.
Scene on_ground(PlanarBody body, double gravity, const PlanarState& initial, ImpactLaw law,
                const char* dimensions) {
  detail::require_usable_mass_matrix("body", body.mass, body.inertia,
                                     std::string(dimensions) + " give ");
  Scene s;
  s.body = std::move(body);
  s.obstacles = {HalfPlane{}};
  s.gravity = gravity;
  s.initial = initial;
  s.law = std::move(law);
  s.validate();
  return s;
}
}  // namespace

std::string_view to_string(PaperLaw l) {
  return detail::enum_to_string(kPaperLaws, l);
}
PaperLaw paper_law_from_string(std::string_view s) {
  return detail::enum_from_string(kPaperLaws, s, "law");
}

Scene bar_scene(const BarParameters& bar, ImpactLaw law) {
  PlanarBody body;
  const double l = bar.half_length;
  body.mass = bar.mass;
  body.inertia = bar.mass * l * l / 3.0;
  body.points = {ContactPoint{{-l, 0.0}, 0.0}, ContactPoint{{l, 0.0}, 0.0}};
  return on_ground(std::move(body), bar.gravity, bar.initial, std::move(law),
                   "the bar's mass and half_length");
}

Scene ball_scene(const BallParameters& ball, ImpactLaw law) {
  PlanarBody body;
  body.mass = ball.mass;
  body.inertia = 0.4 * ball.mass * ball.radius * ball.radius;
  body.points = {ContactPoint{{0.0, 0.0}, ball.radius}};
  return on_ground(std::move(body), ball.gravity, ball.initial, std::move(law),
                   "the ball's mass and radius");
}

Scene block_scene(const BlockParameters& block, ImpactLaw law) {
  PlanarBody body;
  const double w = 0.5 * block.width, h = 0.5 * block.height;
  body.mass = block.mass;
  body.inertia = block.mass * (block.width * block.width + block.height * block.height) / 12.0;
  body.points = {ContactPoint{{-w, -h}, 0.0}, ContactPoint{{w, -h}, 0.0}, ContactPoint{{w, h}, 0.0},
                 ContactPoint{{-w, h}, 0.0}};
  return on_ground(std::move(body), block.gravity, block.initial, std::move(law),
                   "the block's mass, width and height");
}

Scene ladder_scene(const LadderParameters& ladder, ImpactLaw law) {
  const double l = ladder.half_length, theta = ladder.angle;
  if (!(theta > 0.0 && theta < std::numbers::pi / 2))
    throw InvalidArgument("angle",
                          "must lie in (0, pi/2) rad, got " + detail::format_number(theta));
  PlanarBody body;
  body.mass = ladder.mass;
  body.inertia = ladder.mass * l * l / 3.0;
  body.points = {ContactPoint{{-l, 0.0}, 0.0}, ContactPoint{{l, 0.0}, 0.0}};
  const PlanarState initial{
      Eigen::Vector3d(ladder.wall - l * std::cos(theta), l * std::sin(theta), theta),
      ladder.velocity};
  detail::require_usable_mass_matrix("body", body.mass, body.inertia,
                                     "the ladder's mass and half_length give ");
  Scene s;
  s.body = std::move(body);
  s.obstacles = {HalfPlane{}, HalfPlane{Eigen::Vector2d(-1.0, 0.0), -ladder.wall}};
  s.gravity = ladder.gravity;
  s.initial = initial;
  s.law = std::move(law);
  s.validate();
  return s;
}

ImpactLaw paper_law(PaperLaw law, double k_N) {
  using C = PaperConstants;
  switch (law) {
    case PaperLaw::newton:
      return ImpactLaw::newton(C::e);
    case PaperLaw::newton_coulomb:
      return ImpactLaw::newton_coulomb(C::e, C::mu);
    case PaperLaw::poisson_coulomb:
      return ImpactLaw::poisson_coulomb(C::e, C::mu);
    case PaperLaw::fremond_coulomb:
      return ImpactLaw::fremond_coulomb(PowerPotential(k_N, C::p), C::mu);
    case PaperLaw::fremond_viscous:
      return ImpactLaw::fremond(PowerPotential(k_N, C::p),
                                DeadZonePowerPotential(C::k_T, C::q, C::r));
    case PaperLaw::stronge_coulomb: {
      StrongeLaw stronge;
      stronge.e = C::e;
      stronge.coulomb = true;
      stronge.mu = C::mu;
      return stronge;
    }
  }
  return ImpactLaw::newton(C::e);
}

namespace {
// A ball's body (the one of ball_scene), centred at the origin of its frame.
PlanarBody ball_body(double mass, double radius) {
  BallParameters p;
  p.mass = mass;
  p.radius = radius;
  detail::require_finite_above("mass", mass, 0.0);
  detail::require_finite_above("radius", radius, 0.0);
  return ball_scene(p, ImpactLaw::newton(0.0)).body;
}
}  // namespace

MultiBodyScene cradle_scene(const CradleParameters& cradle, ImpactLaw law) {
  const int n = cradle.balls;
  if (n < 2 || n * (n - 1) / 2 > kMaxMultiBodyContacts)
    throw InvalidArgument("balls", "must be at least 2 and give at most " +
                                       std::to_string(kMaxMultiBodyContacts) + " pairs, got " +
                                       std::to_string(n));
  detail::require_finite("speed", cradle.speed);
  MultiBodyScene s;
  s.bodies.assign(static_cast<std::size_t>(n), ball_body(cradle.mass, cradle.radius));
  s.gravity = 0.0;
  s.initial.q = Eigen::VectorXd::Zero(3 * n);
  s.initial.qdot = Eigen::VectorXd::Zero(3 * n);
  for (int i = 0; i < n; ++i) s.initial.q(3 * i) = 2.0 * cradle.radius * i;
  s.initial.qdot(0) = cradle.speed;
  s.law = std::move(law);
  s.validate();
  return s;
}

MultiBodyScene ball_on_ball_scene(const BallOnBallParameters& drop, ImpactLaw law) {
  detail::require_finite_at_least("drop_height", drop.drop_height, 0.0);
  detail::require_finite_at_least("speed", drop.speed, 0.0);
  MultiBodyScene s;
  s.bodies.assign(2, ball_body(drop.mass, drop.radius));
  s.obstacles = {HalfPlane{}};
  s.gravity = drop.gravity;
  const double r = drop.radius;
  s.initial.q = Eigen::VectorXd::Zero(6);
  s.initial.qdot = Eigen::VectorXd::Zero(6);
  s.initial.q(1) = r;
  s.initial.q(4) = 3.0 * r + drop.drop_height;
  s.initial.qdot(4) = 0.0 - drop.speed;  // +0 at rest, not −0
  s.law = std::move(law);
  s.validate();
  return s;
}

}  // namespace fremond
