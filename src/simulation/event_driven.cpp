// The event-driven phase (simulate.hpp): exact free flights to the first contact event, the impact
// of every contact that closes then, until an accumulation or a persistent contact hands over to
// Moreau–Jean.
#include <algorithm>
#include <cmath>
#include <optional>

#include "fremond/simulation/free_flight.hpp"
#include "simulation/detail/run.hpp"

namespace fremond::detail {

void Run::event_driven_phase() {
  const double tau = opt_.simultaneity_tolerance;
  while (!stop_ && t_ < opt_.t_end) {
    if (!progress()) break;
    const FreeFlight flight{t_, st_, sc_.gravity};
    std::array<GapFunction, kMaxC> gap;
    std::array<bool, kMaxC> touching{};
    bool approaching = false, persistent = false;
    for (int k = 0; k < nc_; ++k) {
      gap[k] = GapFunction::make(*point_[k], *plane_[k], flight);
      double g, gd, gdd;
      gap[k].eval(0.0, g, gd, gdd);
      touching[k] = g <= opt_.gap_tolerance;
      if (!touching[k]) continue;
      if (gd < -opt_.velocity_tolerance)
        approaching = true;
      else if (gd <= opt_.velocity_tolerance && gdd < 0.0)
        persistent = true;  // at rest on the obstacle, and flight would push it in
    }
    if (approaching) {  // closed and closing now: an impact at this very instant
      std::array<int, kMaxC> idx;
      int n = 0;
      for (int k = 0; k < nc_; ++k)
        if (touching[k]) idx[n++] = k;
      sample(t_, st_);
      if (!impact(t_, st_, idx.data(), n, ImpactKind::event)) return;
      sample(t_, st_);
      if (after_event_impact()) return;
      continue;
    }
    if (persistent) {
      switch_phase(Phase::moreau_jean, "persistent contact");
      return;
    }

    const double horizon = opt_.t_end - t_;
    std::array<double, kMaxC> when;
    const std::optional<double> first = first_event(gap, touching, horizon, when);
    if (!first) return;
    const double best = *first;
    const auto state_at = [&](double t) { return flight.at_elapsed(t - flight.t0); };
    if (best == kInf) {  // flies to the end
      sampler_.until(opt_.t_end, true, phase_, state_at);
      st_ = flight.at_elapsed(horizon);
      t_ = opt_.t_end;
      audit_.record(energy(sc_, st_), false);
      return;
    }
    const double t_star = t_ + best;
    sampler_.until(t_star, false, phase_, state_at);
    st_ = flight.at_elapsed(best);
    t_ = t_star;
    audit_.record(energy(sc_, st_), false);  // a flight conserves energy: rounding only

    std::array<int, kMaxC> idx;
    int n = 0;
    const double c = std::cos(st_.q.z()), s = std::sin(st_.q.z());
    for (int k = 0; k < nc_; ++k)
      if (when[k] <= best + tau || frame(k, st_.q, c, s).gap <= opt_.gap_tolerance) idx[n++] = k;
    sample(t_, st_);
    if (!impact(t_, st_, idx.data(), n, ImpactKind::event)) return;
    sample(t_, st_);
    if (after_event_impact()) return;
  }
}

// The first contact event of the flight within `horizon` after its start (kInf: none), and each
// contact's own in when[k]; later contacts only need to look up to the best so far. Nothing when a
// search spent its budget: the run stops at the start of the flight, where nothing is guessed.
std::optional<double> Run::first_event(const std::array<GapFunction, kMaxC>& gap,
                                       const std::array<bool, kMaxC>& touching, double horizon,
                                       std::array<double, kMaxC>& when) {
  const double tau = opt_.simultaneity_tolerance;
  double best = kInf;
  for (int k = 0; k < nc_; ++k) {
    const EventSearchResult r = find_first_event(gap[k], std::min(horizon, best + tau), touching[k],
                                                 opt_.max_gap_evaluations);
    res_.gap_evaluations += r.evaluations;
    if (r.exhausted) {
      finish(SimulationStatus::event_search_failed,
             "the event search of a free flight spent integrator.max_gap_evaluations without "
             "deciding where the next contact event is: the body turns too fast for its "
             "events to be resolved");
      return std::nullopt;
    }
    when[k] = r.s;
    best = std::min(best, r.s);
  }
  return best;
}

// The accumulation test after an event impact; on an accumulation, closes it and switches to
// Moreau–Jean (returns true).
bool Run::after_event_impact() {
  const std::optional<double> tail = accumulation_.add(t_, opt_);
  if (!tail) return false;
  close_accumulation(*tail);
  if (!stop_ && phase_ == Phase::event_driven)
    switch_phase(Phase::moreau_jean, "accumulation of impacts");
  return true;
}

}  // namespace fremond::detail
