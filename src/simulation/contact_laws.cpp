// The scene's law restricted to the contacts of one impact (detail/contact_laws.hpp).
#include "simulation/detail/contact_laws.hpp"

namespace fremond::detail {

namespace {

bool is_uniform(const ImpactLaw& law) {
  return law.visit([](const auto& l) { return l.longest_list() == 1; });
}

// The law of the contacts idx[0..n) of a law with per-contact parameters.
ImpactLaw restrict_law(const ImpactLaw& law, const int* idx, int n) {
  return law.visit([&](const auto& l) { return ImpactLaw(l.restricted(idx, n)); });
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
