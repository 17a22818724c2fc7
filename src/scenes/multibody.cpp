// Scenes of several bodies (multibody.hpp): their contacts, frames and impact problems.
#include "fremond/scenes/multibody.hpp"

#include <cmath>
#include <string>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"
#include "fremond/scenes/kinematics.hpp"

namespace fremond {

using detail::format_number;

namespace {

std::string body_name(std::size_t i) {
  return "bodies[" + std::to_string(i) + "]";
}

void require_size(const char* name, const Eigen::VectorXd& v, int n) {
  if (v.size() != n)
    throw InvalidArgument(name, "must have 3 entries per body (x, y, theta of each), " +
                                    std::to_string(n) + " in all, got " + std::to_string(v.size()));
}

// The centre and angle of body i at q.
struct Placement {
  Eigen::Vector2d c;
  double cos_theta, sin_theta;
};
Placement placement(const Eigen::Ref<const Eigen::VectorXd>& q, int body) {
  const double theta = q(3 * body + 2);
  return {q.segment<2>(3 * body), std::cos(theta), std::sin(theta)};
}

Eigen::Vector2d rotated(const Placement& p, const Eigen::Vector2d& r) {
  return {p.cos_theta * r.x() - p.sin_theta * r.y(), p.sin_theta * r.x() + p.cos_theta * r.y()};
}

}  // namespace

std::vector<BodyContact> MultiBodyScene::contacts() const {
  std::vector<BodyContact> out;
  const int nb = static_cast<int>(bodies.size());
  for (int b = 0; b < nb; ++b)
    for (int i = 0; i < static_cast<int>(bodies[b].points.size()); ++i)
      for (int o = 0; o < static_cast<int>(obstacles.size()); ++o) out.push_back({b, i, o, -1, -1});
  for (int a = 0; a < nb; ++a)
    for (int b = a + 1; b < nb; ++b)
      for (int i = 0; i < static_cast<int>(bodies[a].points.size()); ++i)
        for (int j = 0; j < static_cast<int>(bodies[b].points.size()); ++j)
          if (bodies[a].points[i].radius > 0.0 && bodies[b].points[j].radius > 0.0)
            out.push_back({b, j, -1, a, i});
  return out;
}

void MultiBodyScene::validate() {
  if (bodies.empty()) throw InvalidArgument("bodies", "needs at least one body");
  for (std::size_t i = 0; i < bodies.size(); ++i) detail::validate_body(body_name(i), bodies[i]);
  detail::validate_obstacles(obstacles);
  detail::require_finite_at_least("gravity", gravity, 0.0);
  require_size("initial.q", initial.q, dofs());
  require_size("initial.qdot", initial.qdot, dofs());
  for (int i = 0; i < dofs(); ++i) {
    detail::require_finite("initial.q[" + std::to_string(i) + "]", initial.q(i));
    detail::require_finite("initial.qdot[" + std::to_string(i) + "]", initial.qdot(i));
  }
  const std::vector<BodyContact> all = contacts();
  if (all.empty())
    throw InvalidArgument("bodies",
                          "the scene has no contact: give an obstacle, or disks "
                          "(points with a radius > 0) on two bodies");
  if (static_cast<int>(all.size()) > kMaxMultiBodyContacts)
    throw InvalidArgument("bodies", "the scene has " + std::to_string(all.size()) +
                                        " contacts (points x obstacles and pairs of disks), at "
                                        "most " +
                                        std::to_string(kMaxMultiBodyContacts) + " are allowed");
  if (!std::isfinite(energy(*this, initial)))
    throw InvalidArgument("initial",
                          "the energy 1/2 qdot^T M qdot + m g y overflows double "
                          "precision; express the scene in other units");
  for (std::size_t k = 0; k < all.size(); ++k) {
    const BodyContact& c = all[k];
    if (c.is_pair()) {
      const Placement pa = placement(initial.q, c.other_body), pb = placement(initial.q, c.body);
      const Eigen::Vector2d d = pb.c + rotated(pb, bodies[c.body].points[c.point].r) -
                                (pa.c + rotated(pa, bodies[c.other_body].points[c.other_point].r));
      if (!(d.norm() > 0.0))
        throw InvalidArgument("initial.q", "the disks of contact " + std::to_string(k) + " (" +
                                               body_name(c.other_body) + " and " +
                                               body_name(c.body) +
                                               ") have one centre: their normal is undefined");
    }
    const PairFrame f = contact_frame(*this, c, initial.q);
    const double D = f.W_N_b.dot(initial.qdot.segment<3>(3 * c.body)) +
                     (c.is_pair() ? f.W_N_a.dot(initial.qdot.segment<3>(3 * c.other_body)) : 0.0);
    if (!std::isfinite(f.gap) || !std::isfinite(D))
      throw InvalidArgument("initial", "contact " + std::to_string(k) +
                                           ": its gap or velocity overflows double precision at "
                                           "the initial state; express the scene in other units");
  }
  law.validate(static_cast<int>(all.size()));
}

PairFrame contact_frame(const MultiBodyScene& scene, const BodyContact& c,
                        const Eigen::Ref<const Eigen::VectorXd>& q) {
  const ContactPoint& pb = scene.bodies[c.body].points[c.point];
  const Placement b = placement(q, c.body);
  PairFrame out;
  if (!c.is_pair()) {
    const ContactFrame f =
        contact_frame(pb, scene.obstacles[c.obstacle], b.c, b.cos_theta, b.sin_theta);
    out.gap = f.gap;
    out.W_N_b = f.W_N;
    out.W_T_b = f.W_T;
    return out;
  }
  // Each body sees the other's disk as a half-plane through its rim, normal to the line of
  // centres: body b the one of normal n, body a the one of normal −n (kinematics.hpp).
  const ContactPoint& pa = scene.bodies[c.other_body].points[c.other_point];
  const Placement a = placement(q, c.other_body);
  const Eigen::Vector2d ca = a.c + rotated(a, pa.r), cb = b.c + rotated(b, pb.r);
  const Eigen::Vector2d n = (cb - ca).normalized();
  const ContactFrame fb =
      contact_frame(pb, HalfPlane{n, n.dot(ca) + pa.radius}, b.c, b.cos_theta, b.sin_theta);
  const ContactFrame fa =
      contact_frame(pa, HalfPlane{-n, -n.dot(cb) + pb.radius}, a.c, a.cos_theta, a.sin_theta);
  out.gap = fb.gap;
  out.W_N_b = fb.W_N;
  out.W_T_b = fb.W_T;
  out.W_N_a = fa.W_N;
  out.W_T_a = fa.W_T;  // fa's tangent is that of −n, −t: D_T = t·(v_b − v_a)
  return out;
}

std::vector<int> touching_contacts(const MultiBodyScene& scene,
                                   const Eigen::Ref<const Eigen::VectorXd>& q, double tolerance) {
  std::vector<int> out;
  const std::vector<BodyContact> all = scene.contacts();
  for (int k = 0; k < static_cast<int>(all.size()); ++k)
    if (contact_frame(scene, all[k], q).gap <= tolerance) out.push_back(k);
  return out;
}

ImpactProblem impact_problem(const MultiBodyScene& scene, const MultiBodyState& state,
                             std::span<const int> which) {
  const int n = scene.dofs();
  require_size("state.q", state.q, n);
  require_size("state.qdot", state.qdot, n);
  const std::vector<BodyContact> all = scene.contacts();
  const int c = static_cast<int>(which.size());
  ImpactProblem pb;
  pb.M = MatrixX::Zero(n, n);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    pb.M.block<3, 3>(3 * i, 3 * i) = scene.bodies[i].mass_matrix();
  pb.W_N = MatrixX::Zero(n, c);
  pb.W_T = MatrixX::Zero(n, c);
  pb.qdot_A = state.qdot;
  for (int i = 0; i < c; ++i) {
    const int k = which[i];
    if (k < 0 || k >= static_cast<int>(all.size()))
      throw InvalidArgument("contacts", "contact " + std::to_string(k) + " is not one of the " +
                                            std::to_string(all.size()) + " of the scene");
    const BodyContact& ct = all[k];
    const PairFrame f = contact_frame(scene, ct, state.q);
    pb.W_N.block<3, 1>(3 * ct.body, i) = f.W_N_b;
    pb.W_T.block<3, 1>(3 * ct.body, i) = f.W_T_b;
    if (ct.is_pair()) {
      pb.W_N.block<3, 1>(3 * ct.other_body, i) = f.W_N_a;
      pb.W_T.block<3, 1>(3 * ct.other_body, i) = f.W_T_a;
    }
  }
  return pb;
}

ImpactLaw law_of(const MultiBodyScene& scene, std::span<const int> which) {
  return scene.law.visit([&](const auto& l) {
    return ImpactLaw(l.restricted(which.data(), static_cast<int>(which.size())));
  });
}

double energy(const MultiBodyScene& scene, const MultiBodyState& s) {
  double e = 0.0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    e += kinetic_energy(scene.bodies[i], s.qdot.segment<3>(3 * i)) +
         scene.bodies[i].mass * scene.gravity * s.q(3 * i + 1);
  return e;
}

Eigen::Vector2d momentum(const MultiBodyScene& scene,
                         const Eigen::Ref<const Eigen::VectorXd>& qdot) {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    p += scene.bodies[i].mass * qdot.segment<2>(3 * i);
  return p;
}

}  // namespace fremond
