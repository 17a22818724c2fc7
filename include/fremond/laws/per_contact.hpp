#pragma once
/// @file A law's parameters per contact: one value (or potential) for every contact, or one each.
#include <initializer_list>
#include <utility>
#include <vector>

#include "fremond/potentials/potential.hpp"

namespace fremond {

/// A per-contact coefficient: one value for every contact, or one value per contact.
struct PerContact {
  std::vector<double> values;
  PerContact() : values{0.0} {}
  PerContact(double v) : values{v} {}                          // NOLINT: implicit by design
  PerContact(std::vector<double> v) : values(std::move(v)) {}  // NOLINT
  PerContact(std::initializer_list<double> v) : values(v) {}
  double operator[](int i) const { return values.size() == 1 ? values[0] : values[i]; }
  bool fits(int contacts) const {
    return values.size() == 1 || static_cast<int>(values.size()) == contacts;
  }
  /// The values of the contacts idx[0..n) (the same list where it holds one value).
  PerContact restricted(const int* idx, int n) const {
    if (values.size() <= 1) return *this;
    PerContact out(std::vector<double>{});
    for (int i = 0; i < n; ++i) out.values.push_back((*this)[idx[i]]);
    return out;
  }
};

/// Per-contact potentials: one shared potential or one per contact.
struct PerContactPotential {
  std::vector<detail::PotentialHandle> potentials;
  PerContactPotential() = default;
  PerContactPotential(const Potential& p) { potentials.emplace_back(p.clone()); }  // NOLINT
  PerContactPotential(PotentialPtr p) { potentials.emplace_back(std::move(p)); }   // NOLINT
  const Potential& operator[](int i) const {
    return potentials.size() == 1 ? *potentials[0] : *potentials[i];
  }
  bool empty() const { return potentials.empty(); }
  bool fits(int contacts) const {
    return potentials.size() == 1 || static_cast<int>(potentials.size()) == contacts;
  }
  /// The potentials of the contacts idx[0..n) (the same list where it holds one).
  PerContactPotential restricted(const int* idx, int n) const {
    if (potentials.size() <= 1) return *this;
    PerContactPotential out;
    for (int i = 0; i < n; ++i) out.potentials.emplace_back((*this)[idx[i]].clone());
    return out;
  }
};

}  // namespace fremond
