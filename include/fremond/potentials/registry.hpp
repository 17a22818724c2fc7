#pragma once
/// @file A registry of named potential kinds: how the problem file and the bindings make
/// potentials.
///
/// No global state: a registry is an ordinary object, passed to whatever reads problem files.
/// `PotentialRegistry::with_builtins()` holds power, deadzone_power, absolute_value,
/// indicator_nonnegative and indicator_nonpositive; users add their own kinds by name.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "fremond/potentials/potential.hpp"

namespace fremond {

/// The parameters of one potential of one contact, by name.
using PotentialParameters = std::map<std::string, double>;

/// How to make one kind of potential.
struct PotentialKind {
  /// Parameters that must be given.
  std::vector<std::string> required;
  /// Parameters that may be given, with their defaults.
  PotentialParameters optional;
  /// Makes the potential from a complete parameter set; may throw InvalidArgument naming a
  /// parameter.
  std::function<PotentialPtr(const PotentialParameters&)> make;
  /// One line for `--help`-style listings.
  std::string description;
};

class PotentialRegistry {
 public:
  /// An empty registry.
  PotentialRegistry() = default;
  /// A registry holding the built-in kinds.
  static PotentialRegistry with_builtins();

  /// Adds a kind; throws InvalidArgument if the name is empty, taken, or `make` is missing.
  void add(const std::string& name, PotentialKind kind);
  bool contains(const std::string& name) const { return kinds_.count(name) != 0; }
  /// Throws InvalidArgument("potential", "unknown potential 'x' (known: ...)").
  const PotentialKind& kind(const std::string& name) const;
  /// Makes a potential: refuses unknown and missing parameters, fills in defaults.
  /// `where` prefixes error messages (e.g. "law.normal").
  PotentialPtr make(const std::string& name, const PotentialParameters& params,
                    const std::string& where = "potential") const;
  std::vector<std::string> names() const;

 private:
  std::map<std::string, PotentialKind> kinds_;
};

}  // namespace fremond
