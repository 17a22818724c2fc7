// Stronge's law: its checks and its description (docs/stronge.md).
#include "fremond/laws/stronge/stronge_law.hpp"

#include <algorithm>
#include <cmath>

#include "laws/detail/per_contact_checks.hpp"

namespace fremond {

namespace {

// η and K of the distributing law: positive and finite, one value or one per contact.
bool positive_fits(const PerContact& v, int contacts) {
  if (!detail::count_fits(v.values.size(), contacts)) return false;
  for (double x : v.values)
    if (!(x > 0.0 && std::isfinite(x))) return false;
  return true;
}
void check_positive(const char* name, const PerContact& v, int contacts) {
  detail::check_count(name, v.values.size(), contacts);
  for (std::size_t i = 0; i < v.values.size(); ++i)
    detail::require_finite_above(detail::entry_name(name, v, i), v.values[i], 0.0);
}
bool all_one(const PerContact& v) {
  return std::all_of(v.values.begin(), v.values.end(), [](double x) { return x == 1.0; });
}

}  // namespace

bool StrongeLaw::quick_valid(int contacts) const {
  return detail::unit_interval_fits(e, contacts) &&
         (!coulomb || detail::friction_fits(mu, contacts)) && positive_fits(eta, contacts) &&
         positive_fits(stiffness, contacts);
}

void StrongeLaw::validate(int contacts) const {
  if (quick_valid(contacts)) return;
  detail::check_unit_interval("law.e", e, contacts);
  if (coulomb) detail::check_friction(mu, contacts);
  check_positive("law.eta", eta, contacts);
  check_positive("law.stiffness", stiffness, contacts);
}

std::size_t StrongeLaw::longest_list() const {
  return std::max({e.values.size(), coulomb ? mu.values.size() : 1, eta.values.size(),
                   stiffness.values.size(), std::size_t{1}});
}

std::string StrongeLaw::describe() const {
  std::string out = detail::describe_restitution(name(), e, coulomb, mu);
  // The distributing law's values where they are not the default, so that a one-contact law
  // reads as before.
  if (!all_one(eta)) out.insert(out.size() - 1, ", eta=" + detail::describe_list(eta));
  if (!all_one(stiffness))
    out.insert(out.size() - 1, ", stiffness=" + detail::describe_list(stiffness));
  return out;
}

StrongeLaw StrongeLaw::restricted(const int* idx, int n) const {
  StrongeLaw r = *this;
  r.e = e.restricted(idx, n);
  r.mu = mu.restricted(idx, n);
  r.eta = eta.restricted(idx, n);
  r.stiffness = stiffness.restricted(idx, n);
  return r;
}

StrongeLaw StrongeLaw::of_every_contact(std::span<const double> D_N) const {
  StrongeLaw out = *this;
  out.e = detail::without_separating(e, D_N);
  return out;
}

}  // namespace fremond
