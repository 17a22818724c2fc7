#pragma once
// An observer that keeps a run's impacts and samples, for the simulation tests.
#include <vector>

#include "fremond/simulation/simulate.hpp"

namespace fremond::testing {

struct SimulationLog : SimulationObserver {
  std::vector<ImpactRecord> impacts;
  std::vector<TrajectorySample> samples;
  void on_impact(const ImpactRecord& r) override { impacts.push_back(r); }
  void on_sample(const TrajectorySample& s) override { samples.push_back(s); }
};

}  // namespace fremond::testing
