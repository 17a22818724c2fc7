// Frémond's laws: their checks and their description (docs/laws.md).
#include "fremond/laws/fremond/fremond_law.hpp"

#include <algorithm>

#include "fremond/core/enum_names.hpp"
#include "fremond/potentials/power.hpp"
#include "laws/detail/per_contact_checks.hpp"

namespace fremond {

namespace {
constexpr detail::EnumNames<TangentialLaw, 3> kTangential{{{TangentialLaw::none, "none"},
                                                           {TangentialLaw::potential, "potential"},
                                                           {TangentialLaw::coulomb, "coulomb"}}};

bool potentials_fit(const PerContactPotential& p, int contacts) {
  if (p.empty() || !detail::count_fits(p.potentials.size(), contacts)) return false;
  for (const auto& q : p.potentials)
    if (!q) return false;
  return true;
}

void check_potentials(const char* name, const PerContactPotential& p, int contacts) {
  detail::check_count(name, p.potentials.size(), contacts);
  for (const auto& q : p.potentials)
    if (!q) throw InvalidArgument(name, "a potential is missing (null)");
}

std::string describe_potentials(const PerContactPotential& v) {
  std::string s;
  for (const auto& p : v.potentials) s += (s.empty() ? "" : ", ") + p->describe();
  return v.potentials.size() == 1 ? s : "[" + s + "]";
}
}  // namespace

std::string_view to_string(TangentialLaw t) {
  return detail::enum_to_string(kTangential, t);
}
TangentialLaw tangential_law_from_string(std::string_view s) {
  return detail::enum_from_string(kTangential, s, "tangential law");
}

bool FremondLaw::leaves_slide_free(int k, double D_T) const {
  if (has_tangential_potential()) return tangential_potential[k].subdifferential(D_T).contains(0.0);
  return !uses_coulomb() || mu[k] == 0.0;
}

bool FremondLaw::quick_valid(int contacts) const {
  if (uses_coulomb() && !detail::friction_fits(mu, contacts)) return false;
  if (!potentials_fit(normal, contacts)) return false;
  return !has_tangential_potential() || potentials_fit(tangential_potential, contacts);
}

void FremondLaw::validate(int contacts) const {
  if (quick_valid(contacts)) return;
  if (uses_coulomb()) detail::check_friction(mu, contacts);
  if (normal.empty()) throw InvalidArgument("law.normal", "Frémond's law needs a normal potential");
  check_potentials("law.normal", normal, contacts);
  if (has_tangential_potential()) {
    if (tangential_potential.empty())
      throw InvalidArgument("law.tangential", "the tangential law needs a potential");
    check_potentials("law.tangential", tangential_potential, contacts);
  }
}

std::size_t FremondLaw::longest_list() const {
  return std::max({normal.potentials.size(), uses_coulomb() ? mu.values.size() : 1,
                   tangential_potential.potentials.size(), std::size_t{1}});
}

std::string FremondLaw::describe() const {
  std::string out = std::string(name()) + "(normal=" + describe_potentials(normal);
  if (has_tangential_potential())
    out += ", tangential=" + describe_potentials(tangential_potential);
  if (uses_coulomb()) out += ", tangential=coulomb(mu=" + detail::describe_list(mu) + ")";
  return out + ")";
}

FremondLaw FremondLaw::restricted(const int* idx, int n) const {
  FremondLaw r = *this;
  r.normal = normal.restricted(idx, n);
  r.tangential_potential = tangential_potential.restricted(idx, n);
  r.mu = mu.restricted(idx, n);
  return r;
}

FremondLaw FremondLaw::of_every_contact(std::span<const double> D_N) const {
  const PowerPotential none(0.0, 2.0);  // φ = 0: the reaction alone
  FremondLaw out = *this;
  PerContactPotential n, t;
  for (std::size_t i = 0; i < D_N.size(); ++i) {
    const int k = static_cast<int>(i);
    n.potentials.emplace_back(D_N[i] > 0.0 ? none.clone() : normal[k].clone());
    if (has_tangential_potential())
      t.potentials.emplace_back(D_N[i] > 0.0 ? none.clone() : tangential_potential[k].clone());
  }
  out.normal = std::move(n);
  if (has_tangential_potential()) out.tangential_potential = std::move(t);
  return out;
}

}  // namespace fremond
