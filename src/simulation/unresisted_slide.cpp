// A slide the law does not resist (include/fremond/simulation/unresisted_slide.hpp).
#include "fremond/simulation/unresisted_slide.hpp"

#include <algorithm>
#include <cmath>

#include "fremond/scenes/kinematics.hpp"

namespace fremond {

namespace {
// True where the law of contact k puts no tangential percussion on a slide at D_T.
bool resists_no_slide(const ImpactLaw& law, int k, double D_T) {
  // A tangential potential: the slide's mean velocity is D_T itself (before = after), so no
  // percussion where 0 ∈ ∂φ_T(D_T). Otherwise Coulomb's with μ = 0, or no friction at all.
  if (const FremondLaw* f = law.get_if<FremondLaw>(); f && f->has_tangential_potential())
    return f->tangential_potential[k].subdifferential(D_T).contains(0.0);
  return !law.has_friction() || law.mu(k) == 0.0;
}
}  // namespace

std::optional<UnresistedSlide> unresisted_slide(const Scene& scene,
                                                const SimulationOptions& options,
                                                const SimulationResult& result) {
  std::optional<UnresistedSlide> out;
  const Eigen::Vector3d& q = result.state.q;
  const Eigen::Vector3d& v = result.state.qdot;
  if (!q.allFinite() || !v.allFinite()) return out;
  // Touching: within the gap tolerance, or, in Moreau–Jean's phase, within what one step of
  // gravity closes (h² g/2: its contacts are active when the predicted gap reaches 0).
  const double touching = std::max(
      options.gap_tolerance,
      result.phase == Phase::moreau_jean ? options.step * options.step * scene.gravity : 0.0);
  for (int k = 0; k < scene.contact_count(); ++k) {
    const ContactFrame f = contact_frame(scene, k, q);
    const double D_N = f.W_N.dot(v), D_T = f.W_T.dot(v);
    if (std::fabs(f.gap) > touching || std::fabs(D_N) > options.velocity_tolerance ||
        std::fabs(D_T) <= options.velocity_tolerance)
      continue;
    if (!resists_no_slide(scene.law, k, D_T)) continue;
    if (!out || std::fabs(D_T) > std::fabs(out->speed)) out = UnresistedSlide{k, D_T};
  }
  return out;
}

}  // namespace fremond
