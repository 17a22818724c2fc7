#pragma once
// The energy audit of a run (SimulationResult::max_energy_rise): every change of the energy goes
// through record(), so the largest rise over any flight, step, accumulation or admissible impact is
// rounding only.
#include <algorithm>

namespace fremond::detail {

class EnergyAudit {
 public:
  void start(double energy) { e_prev_ = energy; }
  /// The energy is now `energy`. A rise counts unless `allowed`: the gain of an impact whose
  /// certificate failed is the law's, counted with the inadmissible impacts.
  void record(double energy, bool allowed) {
    if (!allowed) max_rise_ = std::max(max_rise_, energy - e_prev_);
    e_prev_ = energy;
  }
  double max_rise() const { return max_rise_; }

 private:
  double e_prev_ = 0.0;
  double max_rise_ = 0.0;
};

}  // namespace fremond::detail
