// Scenes of several bodies (multibody.hpp): the contact frame of two disks against the velocities
// of their contact points worked out by hand and the derivative of the gap; Newton's cradle of 3
// and 5 balls and a ball dropped on a resting ball, under every law, against the answers derived
// by hand in ball_chain_test.cpp and against the 1-D problem of ball_chain (the scene adds y, θ
// and tangential rows, which G leaves uncoupled from the normal ones: W_N has x entries only in a
// cradle, W_T none), momentum balance, no penetration, and no energy created by the laws that
// dissipate by construction.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fremond/fremond.hpp"

namespace fremond {
namespace {

std::vector<ImpactLaw> every_scene_law() {
  StrongeLaw hertz;
  hertz.e = 1.0;
  hertz.eta = 1.5;
  StrongeLaw hertz_coulomb = hertz;
  hertz_coulomb.e = 0.9;
  hertz_coulomb.coulomb = true;
  hertz_coulomb.mu = 0.5;
  return {ImpactLaw::newton(1.0),
          ImpactLaw::newton(0.8),
          ImpactLaw::newton_coulomb(0.8, 0.5),
          ImpactLaw::poisson(1.0),
          ImpactLaw::poisson(0.8),
          ImpactLaw::poisson_coulomb(0.8, 0.5),
          ImpactLaw::fremond(PowerPotential(4.0, 3.0)),
          ImpactLaw::fremond_coulomb(PowerPotential(4.0, 3.0), 0.5),
          ImpactLaw(hertz),
          ImpactLaw(hertz_coulomb)};
}

double kinetic(const ImpactProblem& pb, const Eigen::VectorXd& v) {
  return 0.5 * v.dot(pb.M * v);
}

// How closely two posings of one impact agree: Stronge's distributing law integrates an ODE in
// the percussion to about 1e-12 relative, whose steps move with the rounding of G; the other
// laws' answers are closed forms or refined to the last bits.
double agreement(const ImpactLaw& law) {
  return law.is<StrongeLaw>() ? 1e-10 : 1e-12;
}

// The x velocities of the balls (every third entry of q̇).
Eigen::VectorXd along_x(const Eigen::VectorXd& qdot) {
  Eigen::VectorXd x(qdot.size() / 3);
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = qdot(3 * i);
  return x;
}

// Two bodies with off-centre disks, both turning: D_N must be the derivative of the gap, and
// D_T = t·(v_b − v_a) at the contact points, v = ċ + ω × (p − c), p on each rim along the line of
// centres (body b's at −ρ_b n from its disk's centre, body a's at +ρ_a n), t = (n_y, −n_x).
TEST(MultiBodyScene, DiskPairFrameIsTheContactPointsRelativeVelocity) {
  MultiBodyScene s;
  s.bodies.resize(2);
  s.bodies[0] = PlanarBody{2.0, 0.3, {ContactPoint{Eigen::Vector2d(0.2, -0.1), 0.15}}};
  s.bodies[1] = PlanarBody{1.0, 0.1, {ContactPoint{Eigen::Vector2d(-0.1, 0.3), 0.25}}};
  s.gravity = 0.0;
  s.initial.q = (Eigen::VectorXd(6) << 0.0, 0.0, 0.4, 0.5, 0.3, -0.7).finished();
  s.initial.qdot = (Eigen::VectorXd(6) << 0.3, -0.2, 1.1, -0.4, 0.6, 2.3).finished();
  s.law = ImpactLaw::newton(0.5);
  s.validate();
  ASSERT_EQ(s.contact_count(), 1);
  const BodyContact c = s.contacts()[0];
  EXPECT_EQ(c.body, 1);
  EXPECT_EQ(c.other_body, 0);

  const Eigen::VectorXd &q = s.initial.q, &v = s.initial.qdot;
  const auto centre = [&](int b, const Eigen::VectorXd& qq) {
    const double th = qq(3 * b + 2);
    const Eigen::Vector2d r = s.bodies[b].points[0].r;
    return Eigen::Vector2d(qq(3 * b) + std::cos(th) * r.x() - std::sin(th) * r.y(),
                           qq(3 * b + 1) + std::sin(th) * r.x() + std::cos(th) * r.y());
  };
  const Eigen::Vector2d ca = centre(0, q), cb = centre(1, q);
  const Eigen::Vector2d n = (cb - ca) / (cb - ca).norm(), t(n.y(), -n.x());
  const auto point_velocity = [&](int b, const Eigen::Vector2d& p) {
    const Eigen::Vector2d arm = p - q.segment<2>(3 * b);
    const double w = v(3 * b + 2);
    return Eigen::Vector2d(v(3 * b) - w * arm.y(), v(3 * b + 1) + w * arm.x());
  };
  const Eigen::Vector2d rel = point_velocity(1, cb - 0.25 * n) - point_velocity(0, ca + 0.15 * n);

  const ImpactProblem pb = impact_problem(s, s.initial, std::vector<int>{0});
  const PairFrame f = contact_frame(s, c, q);
  EXPECT_NEAR(f.gap, (cb - ca).norm() - 0.4, 1e-15);
  const double D_N = pb.W_N.col(0).dot(v), D_T = pb.W_T.col(0).dot(v);
  EXPECT_NEAR(D_N, n.dot(rel), 1e-14);
  EXPECT_NEAR(D_T, t.dot(rel), 1e-14);
  // The gap's central difference, O(h²) ≈ 1e-10 off.
  const double h = 1e-5;
  const double dgap =
      (contact_frame(s, c, q + h * v).gap - contact_frame(s, c, q - h * v).gap) / (2.0 * h);
  EXPECT_NEAR(D_N, dgap, 1e-9);
  // M is block-diagonal, diag(m, m, J) per body.
  EXPECT_EQ(pb.M.diagonal(), (Eigen::VectorXd(6) << 2.0, 2.0, 0.3, 1.0, 1.0, 0.1).finished());
  EXPECT_EQ((pb.M - Eigen::MatrixXd(pb.M.diagonal().asDiagonal())).norm(), 0.0);
}

// Three balls: Newton and Poisson at e = 1 give (−1/3, 2/3, 2/3) (ball_chain_test.cpp: G P =
// (2, 0), P = (4/3, 2/3)); five balls: (−3, 2, 2, 2, 2)/5 under Newton at e = 1.
TEST(MultiBodyScene, NewtonsCradleMatchesTheHandDerivedAnswers) {
  const MultiBodyScene three = cradle_scene(CradleParameters{}, ImpactLaw::newton(1.0));
  const std::vector<int> touching3 = touching_contacts(three, three.initial.q);
  ASSERT_EQ(touching3, (std::vector<int>{0, 2}));  // pairs (0,1), (1,2); (0,2) is 2ρ apart
  const ImpactProblem pb3 = impact_problem(three, three.initial, touching3);
  for (const ImpactLaw& law : {ImpactLaw::newton(1.0), ImpactLaw::poisson(1.0)}) {
    const ImpactResult r = solve_impact(pb3, law);
    ASSERT_TRUE(r.ok()) << law.name();
    const Eigen::VectorXd x = along_x(r.qdot_E);
    EXPECT_NEAR(x(0), -1.0 / 3, 1e-15) << law.name();
    EXPECT_NEAR(x(1), 2.0 / 3, 1e-15) << law.name();
    EXPECT_NEAR(x(2), 2.0 / 3, 1e-15) << law.name();
    EXPECT_NEAR(r.P_N(0), 4.0 / 3, 1e-15) << law.name();
    EXPECT_NEAR(r.P_N(1), 2.0 / 3, 1e-15) << law.name();
  }
  CradleParameters five_balls;
  five_balls.balls = 5;
  const MultiBodyScene five = cradle_scene(five_balls, ImpactLaw::newton(1.0));
  const std::vector<int> touching5 = touching_contacts(five, five.initial.q);
  ASSERT_EQ(touching5.size(), 4u);
  const ImpactResult r5 =
      solve_impact(impact_problem(five, five.initial, touching5), law_of(five, touching5));
  ASSERT_TRUE(r5.ok());
  const double expected[5] = {-0.6, 0.4, 0.4, 0.4, 0.4};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(r5.qdot_E(3 * i), expected[i], 1e-15) << i;
}

// Every law on the cradles: the answer of the 1-D problem ball_chain poses (its G is the scene's
// normal block, and Coulomb has nothing to act on: no tangential velocity, no coupling), the
// momentum kept (no external percussion), y and θ untouched, no penetration, and energy not
// created by the dissipative laws.
TEST(MultiBodyScene, NewtonsCradleUnderEveryLaw) {
  for (const int n : {3, 5}) {
    CradleParameters p;
    p.balls = n;
    std::vector<double> m(static_cast<std::size_t>(n), 1.0), v(static_cast<std::size_t>(n), 0.0);
    v[0] = 1.0;
    const ImpactProblem chain = ball_chain(m, v);
    for (const ImpactLaw& law : every_scene_law()) {
      const MultiBodyScene s = cradle_scene(p, law);
      const std::vector<int> idx = touching_contacts(s, s.initial.q);
      ASSERT_EQ(static_cast<int>(idx.size()), n - 1);
      const ImpactProblem pb = impact_problem(s, s.initial, idx);
      const ImpactResult r = solve_impact(pb, law_of(s, idx));
      const ImpactResult ref = solve_impact(chain, law);
      const std::string what = std::to_string(n) + " balls, " + law.describe();
      ASSERT_TRUE(r.ok()) << what << ": " << r.solver.message;
      ASSERT_TRUE(ref.ok()) << what;
      EXPECT_LE((along_x(r.qdot_E) - ref.qdot_E).lpNorm<Eigen::Infinity>(), agreement(law)) << what;
      EXPECT_LE((r.P_N - ref.P_N).lpNorm<Eigen::Infinity>(), agreement(law)) << what;
      const Eigen::Vector2d p_after = momentum(s, r.qdot_E);
      EXPECT_NEAR(p_after.x(), 1.0, 1e-12) << what;
      EXPECT_NEAR(p_after.y(), 0.0, 1e-12) << what;
      for (int i = 0; i < n; ++i) {
        EXPECT_NEAR(r.qdot_E(3 * i + 1), 0.0, 1e-12) << what;
        EXPECT_NEAR(r.qdot_E(3 * i + 2), 0.0, 1e-12) << what;
      }
      EXPECT_GE(r.D_NE.minCoeff(), -1e-12) << what;
      if (law.dissipative()) {
        EXPECT_LE(kinetic(pb, r.qdot_E), kinetic(pb, pb.qdot_A) * (1 + agreement(law))) << what;
      }
    }
  }
}

// A ball dropped at 1 m/s on one resting on the ground (drop_height 0): Newton at e = 1 leaves the
// lower ball at rest and sends the upper one back up at 1 m/s, P = 2 at both contacts
// (ball_chain_test.cpp). Every law: the answer of ball_chain's problem, the x momentum kept and
// the y momentum changed by the ground's percussion alone, no penetration, no energy created by
// the dissipative laws.
TEST(MultiBodyScene, BallDroppedOnARestingBallUnderEveryLaw) {
  BallOnBallParameters p;
  p.drop_height = 0.0;
  p.speed = 1.0;
  const MultiBodyScene hand = ball_on_ball_scene(p, ImpactLaw::newton(1.0));
  const std::vector<int> idx = touching_contacts(hand, hand.initial.q);
  ASSERT_EQ(idx, (std::vector<int>{0, 2}));  // ball 0 on the ground, the pair
  const ImpactProblem pb = impact_problem(hand, hand.initial, idx);
  const ImpactResult newton = solve_impact(pb, ImpactLaw::newton(1.0));
  ASSERT_TRUE(newton.ok());
  EXPECT_NEAR(newton.qdot_E(1), 0.0, 1e-15);
  EXPECT_NEAR(newton.qdot_E(4), 1.0, 1e-15);
  EXPECT_NEAR(newton.P_N(0), 2.0, 1e-15);
  EXPECT_NEAR(newton.P_N(1), 2.0, 1e-15);

  const std::vector<double> m{1.0, 1.0}, v{0.0, -1.0};
  const ImpactProblem chain = ball_chain(m, v, true);  // contacts: the pair, the ground
  for (const ImpactLaw& law : every_scene_law()) {
    const MultiBodyScene s = ball_on_ball_scene(p, law);
    const ImpactResult r = solve_impact(impact_problem(s, s.initial, idx), law_of(s, idx));
    const ImpactResult ref = solve_impact(chain, law);
    const std::string what = law.describe();
    ASSERT_TRUE(r.ok()) << what << ": " << r.solver.message;
    ASSERT_TRUE(ref.ok()) << what;
    EXPECT_NEAR(r.qdot_E(1), ref.qdot_E(0), agreement(law)) << what;
    EXPECT_NEAR(r.qdot_E(4), ref.qdot_E(1), agreement(law)) << what;
    EXPECT_NEAR(r.P_N(0), ref.P_N(1), agreement(law)) << what;
    EXPECT_NEAR(r.P_N(1), ref.P_N(0), agreement(law)) << what;
    const Eigen::Vector2d before = momentum(s, pb.qdot_A), after = momentum(s, r.qdot_E);
    const double ground_friction = r.P_T.size() > 0 ? r.P_T(0) : 0.0;
    EXPECT_NEAR(after.x() - before.x(), ground_friction, 1e-12) << what;
    EXPECT_NEAR(after.y() - before.y(), r.P_N(0), 1e-12) << what;
    EXPECT_GE(r.D_NE.minCoeff(), -1e-12) << what;
    if (law.dissipative()) {
      EXPECT_LE(kinetic(pb, r.qdot_E), kinetic(pb, pb.qdot_A) * (1 + agreement(law))) << what;
    }
  }
}

// The scene's energy and momentum against their definitions, on the dropped ball at rest: all
// potential, m g (y₀ + y₁).
TEST(MultiBodyScene, EnergyIsKineticPlusPotentialOfEveryBody) {
  BallOnBallParameters p;  // ρ = 0.1, drop 0.5: centres at 0.1 and 0.8
  const MultiBodyScene s = ball_on_ball_scene(p, ImpactLaw::newton(0.5));
  EXPECT_NEAR(energy(s, s.initial), 9.81 * (0.1 + 0.8), 1e-14);
  MultiBodyState moving = s.initial;
  moving.qdot(3) = 2.0;  // ball 1: ẋ = 2, ω = 10, J = 2/5 m ρ² = 0.004
  moving.qdot(5) = 10.0;
  EXPECT_NEAR(energy(s, moving), 9.81 * 0.9 + 0.5 * 4.0 + 0.5 * 0.004 * 100.0, 1e-14);
  EXPECT_EQ(momentum(s, moving.qdot), Eigen::Vector2d(2.0, 0.0));
}

std::string refusal(const MultiBodyScene& scene) {
  MultiBodyScene s = scene;
  try {
    s.validate();
  } catch (const InvalidArgument& e) {
    return e.name();
  }
  return "accepted";
}

TEST(MultiBodyScene, RefusesBadValuesNamingThem) {
  const MultiBodyScene good = cradle_scene(CradleParameters{}, ImpactLaw::newton(1.0));
  EXPECT_EQ(refusal(good), "accepted");
  MultiBodyScene s = good;
  s.bodies[1].mass = -1.0;
  EXPECT_EQ(refusal(s), "bodies[1].mass");
  s = good;
  s.bodies[2].points[0].radius = std::nan("");
  EXPECT_EQ(refusal(s), "bodies[2].points[0].radius");
  s = good;
  s.bodies[0].points.clear();
  EXPECT_EQ(refusal(s), "bodies[0].points");
  s = good;
  s.initial.q.resize(8);
  EXPECT_EQ(refusal(s), "initial.q");
  s = good;
  s.initial.qdot(4) = INFINITY;
  EXPECT_EQ(refusal(s), "initial.qdot[4]");
  s = good;
  s.initial.q.segment<2>(3) = s.initial.q.segment<2>(0);  // balls 0 and 1 at one centre
  EXPECT_EQ(refusal(s), "initial.q");
  s = good;
  s.law = ImpactLaw::newton(std::vector<double>{0.5, 0.5});  // three pairs
  EXPECT_EQ(refusal(s), "law.e");
  s = good;
  s.bodies.clear();
  EXPECT_EQ(refusal(s), "bodies");
  CradleParameters one;
  one.balls = 1;
  try {
    cradle_scene(one, ImpactLaw::newton(1.0));
    ADD_FAILURE() << "one ball accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "balls");
  }
  try {
    impact_problem(good, good.initial, std::vector<int>{3});
    ADD_FAILURE() << "contact 3 of 3 accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "contacts");
  }
}

}  // namespace
}  // namespace fremond
