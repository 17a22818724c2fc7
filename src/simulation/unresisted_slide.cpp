// A slide the law does not resist (include/fremond/simulation/unresisted_slide.hpp).
#include "fremond/simulation/unresisted_slide.hpp"

#include <algorithm>
#include <cmath>

#include "fremond/scenes/kinematics.hpp"

namespace fremond {

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
    if (!scene.law.leaves_slide_free(k, D_T)) continue;
    if (!out || std::fabs(D_T) > std::fabs(out->speed)) out = UnresistedSlide{k, D_T};
  }
  return out;
}

}  // namespace fremond
