#pragma once
// The rows of the trajectory: samples on the grid of options.sample_interval, at t = 0 and t_end,
// and just before and after every impact (SimulationObserver::on_sample).
#include "fremond/scenes/scene.hpp"
#include "fremond/simulation/simulate.hpp"
#include "fremond/simulation/simulation_options.hpp"

namespace fremond::detail {

class Sampler {
 public:
  Sampler(const Scene& scene, const SimulationOptions& options, SimulationObserver* observer)
      : scene_(scene), interval_(options.sample_interval), t_end_(options.t_end), obs_(observer) {}

  /// A sample of state `s` at time t, in `phase`.
  void emit(double t, const PlanarState& s, Phase phase);
  /// The time of the last sample emitted (−1 before the first).
  double last_t() const { return last_t_; }
  /// The grid's samples from now on start at index `i` (time i × sample_interval).
  void set_next_index(long i) { next_index_ = i; }

  /// Grid samples in (last, t_lim) — or (last, t_lim] when `inclusive` — from `state_at(t)`.
  template <class StateAt>
  void until(double t_lim, bool inclusive, Phase phase, const StateAt& state_at) {
    if (!obs_) return;  // the grid only places samples, and nobody receives them
    while (true) {
      const double ts = grid(next_index_);
      if (ts > t_end_ || ts > t_lim || (!inclusive && ts == t_lim)) break;
      emit(ts, state_at(ts), phase);
      ++next_index_;
    }
  }

 private:
  double grid(long i) const { return static_cast<double>(i) * interval_; }

  const Scene& scene_;
  double interval_, t_end_;
  SimulationObserver* obs_;
  long next_index_ = 0;
  double last_t_ = -1.0;
};

}  // namespace fremond::detail
