// The run of a scene (simulate.hpp): set-up, the alternation of the event-driven and Moreau–Jean
// phases, and the end of the run. The phases are in event_driven.cpp and moreau_jean.cpp.
#include "fremond/simulation/simulate.hpp"

#include "fremond/core/error.hpp"
#include "simulation/detail/run.hpp"

namespace fremond {

namespace detail {

Run::Run(const Scene& scene, const SimulationOptions& options, SimulationObserver* observer)
    : sc_(scene), opt_(options), obs_(observer), sampler_(sc_, opt_, observer) {
  sc_.validate();
  opt_.validate();
  nc_ = sc_.contact_count();
  minv_ = {1.0 / sc_.body.mass, 1.0 / sc_.body.mass, 1.0 / sc_.body.inertia};
  pp_.minv = minv_;
  laws_ = ContactLaws(sc_.law);
  for (int k = 0; k < nc_; ++k) {
    point_[k] = &sc_.body.points[sc_.point_of(k)];
    plane_[k] = &sc_.obstacles[sc_.obstacle_of(k)];
    const ContactPoint& p = *point_[k];
    mu_[k] = sc_.law.mu(k);  // 0 without Coulomb
    reach_[k] = p.r.norm() + p.radius;
    mode_[k] = ContactMode::stick;
  }
  t_ = 0.0;
  st_ = sc_.initial;
  validate_start(sc_, opt_);
}

SimulationResult Run::go() {
  const double e0 = energy(sc_, st_);
  res_.energy_initial = e0;
  audit_.start(e0);
  sample(0.0, st_);
  sampler_.set_next_index(1);
  phase_ = opt_.integrator == Integrator::moreau_jean ? Phase::moreau_jean : Phase::event_driven;
  while (!stop_ && t_ < opt_.t_end) {
    if (phase_ == Phase::event_driven)
      event_driven_phase();
    else
      moreau_jean_phase();
  }
  if (!stop_) {
    res_.status = SimulationStatus::completed;
    res_.message = "reached the end time";
  }
  if (sampler_.last_t() != t_) sample(t_, st_);
  if (obs_) obs_->on_progress(t_, opt_.t_end);
  res_.t = t_;
  res_.state = st_;
  res_.phase = phase_;
  res_.energy_final = energy(sc_, st_);
  res_.max_energy_rise = audit_.max_rise();
  return res_;
}

void Run::switch_phase(Phase to, std::string_view why) {
  if (obs_) obs_->on_phase(t_, phase_, to, why);
  phase_ = to;
  ++res_.phase_switches;
  accumulation_.reset();
}

}  // namespace detail

void validate_start(const Scene& scene, const SimulationOptions& options) {
  const Eigen::Vector3d& q = scene.initial.q;
  for (int k = 0; k < scene.contact_count(); ++k) {
    const double gap = contact_frame(scene, k, q).gap;
    if (gap < -options.gap_tolerance)
      throw InvalidArgument("initial", "contact point " + std::to_string(scene.point_of(k)) +
                                           " starts " + std::to_string(-gap) +
                                           " m inside obstacle " +
                                           std::to_string(scene.obstacle_of(k)) +
                                           " (gap below -integrator.gap_tolerance); start the "
                                           "body on or above the obstacles");
  }
}

SimulationResult simulate(const Scene& scene, const SimulationOptions& options,
                          SimulationObserver* observer) {
  detail::Run run(scene, options, observer);
  return run.go();
}

}  // namespace fremond
