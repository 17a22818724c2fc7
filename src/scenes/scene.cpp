// Scene checks and the energy of the paper's Fig. 1.
#include "fremond/scenes/scene.hpp"

#include <cmath>
#include <string>

#include "core/detail/impact_problem.hpp"
#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"
#include "fremond/core/impact_problem.hpp"
#include "fremond/core/types.hpp"
#include "fremond/scenes/kinematics.hpp"

namespace fremond {

using detail::format_number;
using detail::require_finite;
using detail::require_finite_above;
using detail::require_finite_at_least;

Eigen::Matrix3d PlanarBody::mass_matrix() const {
  return Eigen::Vector3d(mass, mass, inertia).asDiagonal();
}

namespace {
std::string at(const char* list, std::size_t i, const char* field) {
  return std::string(list) + "[" + std::to_string(i) + "]." + field;
}
void require_finite_vector(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    require_finite(name + "[" + std::to_string(i) + "]", v(i));
}
}  // namespace

void detail::require_usable_mass_matrix(const std::string& name, double mass, double inertia,
                                        const std::string& reason) {
  // The very test of validate(ImpactProblem), on the M every impact of this body will have.
  const MatT<kSmallDofs, kSmallDofs> M = Eigen::Vector3d(mass, mass, inertia).asDiagonal();
  try {
    detail::require_positive_definite(M, CholeskyT<kSmallDofs>(M));
  } catch (const InvalidArgument&) {
    throw InvalidArgument(name, reason + "mass " + format_number(mass) + " and inertia " +
                                    format_number(inertia) +
                                    ", too far apart for double precision: M = diag(m, m, J) "
                                    "is not positive definite to rounding (J/m must lie within "
                                    "1e-24 and 1e24); express the body in other units");
  }
}

void detail::validate_body(const std::string& name, const PlanarBody& body) {
  require_finite_above(name + ".mass", body.mass, 0.0);
  require_finite_above(name + ".inertia", body.inertia, 0.0);
  detail::require_usable_mass_matrix(name + ".inertia", body.mass, body.inertia, "");
  const std::string points = name + ".points";
  if (body.points.empty()) throw InvalidArgument(points, "needs at least one point");
  for (std::size_t i = 0; i < body.points.size(); ++i) {
    require_finite_vector(at(points.c_str(), i, "r"), body.points[i].r);
    require_finite_at_least(at(points.c_str(), i, "radius"), body.points[i].radius, 0.0);
  }
}

void detail::validate_obstacles(std::vector<HalfPlane>& obstacles) {
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    require_finite_vector(at("obstacles", i, "normal"), obstacles[i].normal);
    require_finite(at("obstacles", i, "offset"), obstacles[i].offset);
    const double norm = obstacles[i].normal.norm();
    if (!(norm > 0.0)) throw InvalidArgument(at("obstacles", i, "normal"), "must not be zero");
    obstacles[i].normal /= norm;
  }
}

void Scene::validate() {
  detail::validate_body("body", body);
  if (obstacles.empty()) throw InvalidArgument("obstacles", "needs at least one obstacle");
  detail::validate_obstacles(obstacles);
  if (contact_count() > kMaxSceneContacts)
    throw InvalidArgument("body.points", "points × obstacles must be at most " +
                                             std::to_string(kMaxSceneContacts) + ", got " +
                                             std::to_string(contact_count()));
  require_finite_at_least("gravity", gravity, 0.0);
  require_finite_vector("initial.q", initial.q);
  require_finite_vector("initial.qdot", initial.qdot);
  // Finite data can still overflow what every impact computes (the paper's energy, the contact
  // velocities D = W^T q̇): refuse here what the first impact would refuse.
  if (!std::isfinite(energy(*this, initial)))
    throw InvalidArgument("initial",
                          "the energy 1/2 qdot^T M qdot + m g y overflows double "
                          "precision (max |qdot| = " +
                              format_number(initial.qdot.cwiseAbs().maxCoeff()) + ", y = " +
                              format_number(initial.q.y()) + "); express the scene in other units");
  for (int k = 0; k < contact_count(); ++k) {
    const ContactFrame f = contact_frame(*this, k, initial.q);
    if (!std::isfinite(f.gap) || !std::isfinite(f.W_N.dot(initial.qdot)) ||
        !std::isfinite(f.W_T.dot(initial.qdot)))
      throw InvalidArgument("initial", "contact " + std::to_string(k) +
                                           ": its gap or velocity overflows double precision at "
                                           "the initial state; express the scene in other units");
  }
  law.validate(contact_count());
}

double kinetic_energy(const PlanarBody& body, const Eigen::Vector3d& v) {
  return 0.5 * (body.mass * (v.x() * v.x() + v.y() * v.y()) + body.inertia * v.z() * v.z());
}

double energy(const Scene& scene, const PlanarState& s) {
  return kinetic_energy(scene.body, s.qdot) + scene.body.mass * scene.gravity * s.q.y();
}

ContactFrame contact_frame(const Scene& scene, int contact, const Eigen::Vector3d& q) {
  return contact_frame(scene.body.points[scene.point_of(contact)],
                       scene.obstacles[scene.obstacle_of(contact)], q.head<2>(), std::cos(q.z()),
                       std::sin(q.z()));
}

}  // namespace fremond
