#pragma once
/// @file The power potential behind a Potential, where it is one: the laws' scalar forms for
/// k|z|^p/p (Frémond + Coulomb's one-contact modes) read its k and p.
#include <typeinfo>

#include "fremond/potentials/power.hpp"

namespace fremond::detail {

/// `phi` as a PowerPotential, or nullptr. PowerPotential is final, so one comparison of types
/// decides, where dynamic_cast walks the class hierarchy (some 90 instructions a call).
inline const PowerPotential* as_power(const Potential& phi) {
  return typeid(phi) == typeid(PowerPotential) ? static_cast<const PowerPotential*>(&phi) : nullptr;
}

}  // namespace fremond::detail
