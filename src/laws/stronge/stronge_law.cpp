// Stronge's law: its checks and its description (docs/stronge.md).
#include "fremond/laws/stronge/stronge_law.hpp"

#include <algorithm>

#include "laws/detail/per_contact_checks.hpp"

namespace fremond {

bool StrongeLaw::quick_valid(int contacts) const {
  return detail::unit_interval_fits(e, contacts) &&
         (!coulomb || detail::friction_fits(mu, contacts));
}

void StrongeLaw::validate(int contacts) const {
  if (quick_valid(contacts)) return;
  detail::check_unit_interval("law.e", e, contacts);
  if (coulomb) detail::check_friction(mu, contacts);
}

std::size_t StrongeLaw::longest_list() const {
  return std::max({e.values.size(), coulomb ? mu.values.size() : 1, std::size_t{1}});
}

std::string StrongeLaw::describe() const {
  return detail::describe_restitution(name(), e, coulomb, mu);
}

StrongeLaw StrongeLaw::restricted(const int* idx, int n) const {
  StrongeLaw r = *this;
  r.e = e.restricted(idx, n);
  r.mu = mu.restricted(idx, n);
  return r;
}

StrongeLaw StrongeLaw::of_every_contact(std::span<const double> D_N) const {
  StrongeLaw out = *this;
  out.e = detail::without_separating(e, D_N);
  return out;
}

}  // namespace fremond
