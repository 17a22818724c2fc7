#include "fremond/laws/impact_law.hpp"

#include <algorithm>
#include <cmath>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"

namespace fremond {

namespace {
// A law is refused where it is made: its values (e in [0, 1], μ ≥ 0, potentials present) for
// as many contacts as its longest list; the count against a problem waits for validate(contacts).
ImpactLaw checked(ImpactLaw l) {
  const std::size_t n = std::max({l.e.values.size(), l.mu.values.size(), l.normal.potentials.size(),
                                  l.tangential_potential.potentials.size(), std::size_t{1}});
  l.validate(static_cast<int>(n));
  return l;
}

ImpactLaw classical(LawType type, PerContact e, PerContact mu) {
  ImpactLaw l;
  l.type = type;
  l.e = std::move(e);
  l.mu = std::move(mu);
  return checked(std::move(l));
}

ImpactLaw fremond_with(TangentialLaw tangential, PerContactPotential normal,
                       PerContactPotential tangential_potential, PerContact mu) {
  ImpactLaw l;
  l.type = LawType::fremond;
  l.tangential = tangential;
  l.normal = std::move(normal);
  l.tangential_potential = std::move(tangential_potential);
  l.mu = std::move(mu);
  return checked(std::move(l));
}
}  // namespace

ImpactLaw ImpactLaw::newton(PerContact e) {
  return classical(LawType::newton, std::move(e), {});
}
ImpactLaw ImpactLaw::poisson(PerContact e) {
  return classical(LawType::poisson, std::move(e), {});
}
ImpactLaw ImpactLaw::newton_coulomb(PerContact e, PerContact mu) {
  return classical(LawType::newton_coulomb, std::move(e), std::move(mu));
}
ImpactLaw ImpactLaw::poisson_coulomb(PerContact e, PerContact mu) {
  return classical(LawType::poisson_coulomb, std::move(e), std::move(mu));
}
ImpactLaw ImpactLaw::fremond(PerContactPotential normal) {
  return fremond_with(TangentialLaw::none, std::move(normal), {}, {});
}
ImpactLaw ImpactLaw::fremond(PerContactPotential normal, PerContactPotential tangential) {
  return fremond_with(TangentialLaw::potential, std::move(normal), std::move(tangential), {});
}
ImpactLaw ImpactLaw::fremond_coulomb(PerContactPotential normal, PerContact mu) {
  return fremond_with(TangentialLaw::coulomb, std::move(normal), {}, std::move(mu));
}

bool ImpactLaw::has_friction() const {
  return is_fremond() ? tangential != TangentialLaw::none
                      : type == LawType::newton_coulomb || type == LawType::poisson_coulomb;
}

namespace {
void check_count(const char* name, std::size_t size, int contacts) {
  if (size == 1 || static_cast<int>(size) == contacts) return;
  throw InvalidArgument(name, "needs one value or one per contact (" + std::to_string(contacts) +
                                  "), got " + std::to_string(size));
}
}  // namespace

// The common case (a valid law) is checked without building any message; the detailed pass below,
// which names the offending key, runs only when something is wrong.
bool ImpactLaw::quick_valid(int contacts) const {
  auto count_ok = [&](std::size_t n) { return n == 1 || static_cast<int>(n) == contacts; };
  if (!is_fremond()) {
    if (!count_ok(e.values.size())) return false;
    for (double v : e.values)
      if (!(v >= 0.0 && v <= 1.0)) return false;
  }
  if (uses_coulomb()) {
    if (!count_ok(mu.values.size())) return false;
    for (double v : mu.values)
      if (!(v >= 0.0 && std::isfinite(v))) return false;
  }
  if (is_fremond()) {
    if (normal.empty() || !count_ok(normal.potentials.size())) return false;
    for (const auto& p : normal.potentials)
      if (!p) return false;
    if (has_tangential_potential()) {
      if (tangential_potential.empty() || !count_ok(tangential_potential.potentials.size()))
        return false;
      for (const auto& p : tangential_potential.potentials)
        if (!p) return false;
    }
  }
  return true;
}

void ImpactLaw::validate(int contacts) const {
  if (quick_valid(contacts)) return;
  if (!is_fremond()) {
    check_count("law.e", e.values.size(), contacts);
    for (std::size_t i = 0; i < e.values.size(); ++i)
      detail::require_in_unit_interval(
          e.values.size() == 1 ? "law.e" : "law.e[" + std::to_string(i) + "]", e.values[i]);
  }
  if (uses_coulomb()) {
    check_count("law.mu", mu.values.size(), contacts);
    for (std::size_t i = 0; i < mu.values.size(); ++i)
      detail::require_finite_at_least(
          mu.values.size() == 1 ? "law.mu" : "law.mu[" + std::to_string(i) + "]", mu.values[i],
          0.0);
  }
  if (is_fremond()) {
    if (normal.empty())
      throw InvalidArgument("law.normal", "Frémond's law needs a normal potential");
    check_count("law.normal", normal.potentials.size(), contacts);
    for (const auto& p : normal.potentials)
      if (!p) throw InvalidArgument("law.normal", "a potential is missing (null)");
    if (has_tangential_potential()) {
      if (tangential_potential.empty())
        throw InvalidArgument("law.tangential", "the tangential law needs a potential");
      check_count("law.tangential", tangential_potential.potentials.size(), contacts);
      for (const auto& p : tangential_potential.potentials)
        if (!p) throw InvalidArgument("law.tangential", "a potential is missing (null)");
    }
  }
}

std::string ImpactLaw::describe() const {
  auto list = [](const PerContact& v) {
    std::string s;
    for (double x : v.values) s += (s.empty() ? "" : ", ") + detail::format_number(x);
    return v.values.size() == 1 ? s : "[" + s + "]";
  };
  auto pots = [](const PerContactPotential& v) {
    std::string s;
    for (const auto& p : v.potentials) s += (s.empty() ? "" : ", ") + p->describe();
    return v.potentials.size() == 1 ? s : "[" + s + "]";
  };
  std::string out(to_string(type));
  switch (type) {
    case LawType::newton:
    case LawType::poisson:
      return out + "(e=" + list(e) + ")";
    case LawType::newton_coulomb:
    case LawType::poisson_coulomb:
      return out + "(e=" + list(e) + ", mu=" + list(mu) + ")";
    case LawType::fremond:
      out += "(normal=" + pots(normal);
      if (tangential == TangentialLaw::potential)
        out += ", tangential=" + pots(tangential_potential);
      if (tangential == TangentialLaw::coulomb) out += ", tangential=coulomb(mu=" + list(mu) + ")";
      return out + ")";
  }
  return out;
}

}  // namespace fremond
