#pragma once
/// @file Why a run ends sliding: a slide the scene's law does not resist.
#include <optional>

#include "fremond/simulation/simulate.hpp"

namespace fremond {

/// A contact where the run ends touching and sliding while the law puts no tangential percussion on
/// that slide: nothing in the model will stop it. Frémond's viscous dead zone does that to every
/// slide with |D_T| ≤ r (docs/laws.md), as does a law without friction.
struct UnresistedSlide {
  int contact = -1;    ///< scene contact index.
  double speed = 0.0;  ///< D_T (m/s) at the end of the run.
};

/// The slide of `result`'s final state that `scene`'s law does not resist, on the contact sliding
/// fastest, if any: a contact touching its obstacle (within options.gap_tolerance, or in the
/// Moreau–Jean phase within h² g, what one step of gravity closes), at rest along the
/// normal (|D_N| ≤ options.velocity_tolerance), sliding faster than that, with 0 ∈ ∂φ_T(D_T)
/// (Frémond's tangential potential), μ = 0, or no friction at all.
std::optional<UnresistedSlide> unresisted_slide(const Scene& scene,
                                                const SimulationOptions& options,
                                                const SimulationResult& result);

}  // namespace fremond
