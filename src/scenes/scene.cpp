// Scene checks and the energy of SPEC §5.
#include "fremond/scenes/scene.hpp"

#include <cmath>
#include <string>

#include "fremond/core/error.hpp"
#include "fremond/potentials/detail/validate.hpp"
#include "fremond/scenes/kinematics.hpp"

namespace fremond {

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

void Scene::validate() {
  require_finite_above("body.mass", body.mass, 0.0);
  require_finite_above("body.inertia", body.inertia, 0.0);
  if (body.points.empty()) throw InvalidArgument("body.points", "needs at least one point");
  for (std::size_t i = 0; i < body.points.size(); ++i) {
    require_finite_vector(at("body.points", i, "r"), body.points[i].r);
    require_finite_at_least(at("body.points", i, "radius"), body.points[i].radius, 0.0);
  }
  if (obstacles.empty()) throw InvalidArgument("obstacles", "needs at least one obstacle");
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    require_finite_vector(at("obstacles", i, "normal"), obstacles[i].normal);
    require_finite(at("obstacles", i, "offset"), obstacles[i].offset);
    const double norm = obstacles[i].normal.norm();
    if (!(norm > 0.0)) throw InvalidArgument(at("obstacles", i, "normal"), "must not be zero");
    obstacles[i].normal /= norm;
  }
  if (contact_count() > kMaxSceneContacts)
    throw InvalidArgument("body.points", "points × obstacles must be at most " +
                                             std::to_string(kMaxSceneContacts) + ", got " +
                                             std::to_string(contact_count()));
  require_finite_at_least("gravity", gravity, 0.0);
  require_finite_vector("initial.q", initial.q);
  require_finite_vector("initial.qdot", initial.qdot);
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
