// The rows of the trajectory (detail/sampling.hpp).
#include "simulation/detail/sampling.hpp"

namespace fremond::detail {

void Sampler::emit(double t, const PlanarState& s, Phase phase) {
  last_t_ = t;
  if (!obs_) return;
  TrajectorySample smp;
  smp.t = t;
  smp.state = s;
  smp.energy = energy(scene_, s);
  smp.phase = phase;
  obs_->on_sample(smp);
}

}  // namespace fremond::detail
