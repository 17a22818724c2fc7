// The scene's law restricted to the contacts of one impact (detail/contact_laws.hpp).
#include "simulation/detail/contact_laws.hpp"

namespace fremond::detail {

namespace {

bool is_uniform(const ImpactLaw& law) {
  return law.e.values.size() == 1 && law.mu.values.size() == 1 &&
         law.normal.potentials.size() <= 1 && law.tangential_potential.potentials.size() <= 1;
}

// The law of the contacts idx[0..n) of a law with per-contact parameters.
ImpactLaw restrict_law(const ImpactLaw& law, const int* idx, int n) {
  ImpactLaw r = law;
  const auto pick = [&](const PerContact& p, PerContact& out) {
    if (p.values.size() <= 1) return;
    out.values.clear();
    for (int i = 0; i < n; ++i) out.values.push_back(p[idx[i]]);
  };
  const auto pick_pot = [&](const PerContactPotential& p, PerContactPotential& out) {
    if (p.potentials.size() <= 1) return;
    out.potentials.clear();
    for (int i = 0; i < n; ++i) out.potentials.emplace_back(p[idx[i]].clone());
  };
  pick(law.e, r.e);
  pick(law.mu, r.mu);
  pick_pot(law.normal, r.normal);
  pick_pot(law.tangential_potential, r.tangential_potential);
  return r;
}

}  // namespace

ContactLaws::ContactLaws(const ImpactLaw& law) : law_(&law), uniform_(is_uniform(law)) {}

const ImpactLaw& ContactLaws::of(const int* idx, int n) {
  if (uniform_) return *law_;
  Mask mask = 0;
  for (int i = 0; i < n; ++i) mask |= Mask{1} << idx[i];
  auto it = restricted_.find(mask);
  if (it == restricted_.end()) it = restricted_.emplace(mask, restrict_law(*law_, idx, n)).first;
  return it->second;
}

}  // namespace fremond::detail
