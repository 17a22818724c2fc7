// Newton's and Poisson's laws: their checks and their description (docs/laws.md).
#include "fremond/laws/restitution/restitution_law.hpp"

#include <algorithm>

#include "laws/detail/per_contact_checks.hpp"

namespace fremond {

// The common case (a valid law) is checked without building any message; validate()'s detailed
// pass, which names the offending key, runs only when something is wrong.
bool RestitutionLaw::quick_valid(int contacts) const {
  if (!detail::count_fits(e.values.size(), contacts)) return false;
  for (double v : e.values)
    if (!(v >= 0.0 && v <= 1.0)) return false;
  return !coulomb || detail::friction_fits(mu, contacts);
}

void RestitutionLaw::validate(int contacts) const {
  if (quick_valid(contacts)) return;
  detail::check_count("law.e", e.values.size(), contacts);
  for (std::size_t i = 0; i < e.values.size(); ++i)
    detail::require_in_unit_interval(detail::entry_name("law.e", e, i), e.values[i]);
  if (coulomb) detail::check_friction(mu, contacts);
}

std::size_t RestitutionLaw::longest_list() const {
  return std::max({e.values.size(), coulomb ? mu.values.size() : 1, std::size_t{1}});
}

std::string RestitutionLaw::describe() const {
  std::string out = std::string(name()) + "(e=" + detail::describe_list(e);
  if (coulomb) out += ", mu=" + detail::describe_list(mu);
  return out + ")";
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
  std::vector<double> each(D_N.size());
  for (std::size_t i = 0; i < D_N.size(); ++i)
    each[i] = D_N[i] > 0.0 ? 0.0 : e[static_cast<int>(i)];
  out.e = PerContact(std::move(each));
  return out;
}

}  // namespace fremond
