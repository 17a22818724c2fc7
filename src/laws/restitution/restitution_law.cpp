// Newton's and Poisson's laws: their checks and their description (docs/laws.md).
#include "fremond/laws/restitution/restitution_law.hpp"

#include <algorithm>

#include "laws/detail/per_contact_checks.hpp"

namespace fremond {

// The common case (a valid law) is checked without building any message; validate()'s detailed
// pass, which names the offending key, runs only when something is wrong.
bool RestitutionLaw::quick_valid(int contacts) const {
  return detail::unit_interval_fits(e, contacts) &&
         (!coulomb || detail::friction_fits(mu, contacts));
}

void RestitutionLaw::validate(int contacts) const {
  if (quick_valid(contacts)) return;
  detail::check_unit_interval("law.e", e, contacts);
  if (coulomb) detail::check_friction(mu, contacts);
}

std::size_t RestitutionLaw::longest_list() const {
  return std::max({e.values.size(), coulomb ? mu.values.size() : 1, std::size_t{1}});
}

std::string RestitutionLaw::describe() const {
  return detail::describe_restitution(name(), e, coulomb, mu);
}

RestitutionLaw RestitutionLaw::restricted(const int* idx, int n) const {
  RestitutionLaw r = *this;
  r.e = e.restricted(idx, n);
  r.mu = mu.restricted(idx, n);
  return r;
}

RestitutionLaw RestitutionLaw::of_every_contact(std::span<const double> D_N) const {
  if (has_phases()) return *this;  // Poisson's: a separating contact obeys both phases as is
  RestitutionLaw out = *this;
  out.e = detail::without_separating(e, D_N);
  return out;
}

}  // namespace fremond
