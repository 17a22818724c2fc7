#pragma once
/// @file The impact laws of docs/laws.md: Newton, Poisson (each with or without Coulomb) and
/// Frémond.
#include <string>
#include <string_view>
#include <vector>

#include "fremond/potentials/potential.hpp"

namespace fremond {

/// The law family; names as in the problem file (`law.type`).
enum class LawType {
  newton,           ///< D_NE + e D_NA ≥ 0 ⊥ P_N ≥ 0; P_T = 0 (paper eqs. 5-6).
  poisson,          ///< compression then expansion with P_NE = e P_NC + ΔP; P_T = 0.
  newton_coulomb,   ///< Newton + Coulomb on (P_T, D_TE) (paper §4).
  poisson_coulomb,  ///< Poisson + Coulomb per phase (Pfeiffer & Glocker 1996).
  fremond,          ///< −P ∈ ∂φ(z) + reaction, z the mean velocity (paper §5).
};
std::string_view to_string(LawType t);
/// Throws InvalidArgument("law.type", ...) for an unknown name.
LawType law_type_from_string(std::string_view s);

/// Frémond's tangential law.
enum class TangentialLaw {
  none,       ///< no tangential percussion.
  potential,  ///< −P_T ∈ ∂φ_T(z_T), e.g. the viscous dead zone (eq. 25).
  coulomb,    ///< Coulomb on (P_T, z_T) with bound μ|P_N| (quasi-variational, docs/laws.md).
};
std::string_view to_string(TangentialLaw t);
TangentialLaw tangential_law_from_string(std::string_view s);

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
};

/// An impact law with its parameters. Build it with the named constructors.
struct ImpactLaw {
  LawType type = LawType::newton;
  PerContact e{0.0};   ///< restitution in [0, 1] (Newton, Poisson).
  PerContact mu{0.0};  ///< friction coefficient ≥ 0 (the Coulomb laws, Frémond + Coulomb).
  PerContactPotential normal;  ///< Frémond: φ_N (the reaction is added by the law).
  TangentialLaw tangential = TangentialLaw::none;  ///< Frémond's tangential law.
  PerContactPotential tangential_potential;        ///< Frémond with TangentialLaw::potential.

  /// Each factory refuses its values where the law is made (InvalidArgument naming law.e, law.mu,
  /// law.normal or law.tangential): e in [0, 1], μ ≥ 0 and finite, potentials present, lists of
  /// one value or of one common length. The count against a problem's contacts is validate()'s.
  static ImpactLaw newton(PerContact e);
  static ImpactLaw poisson(PerContact e);
  static ImpactLaw newton_coulomb(PerContact e, PerContact mu);
  static ImpactLaw poisson_coulomb(PerContact e, PerContact mu);
  /// Frémond, normal law only.
  static ImpactLaw fremond(PerContactPotential normal);
  /// Frémond with a tangential potential (e.g. the viscous dead zone).
  static ImpactLaw fremond(PerContactPotential normal, PerContactPotential tangential);
  /// Frémond with Coulomb friction on the mean tangential velocity.
  static ImpactLaw fremond_coulomb(PerContactPotential normal, PerContact mu);

  // What the solvers, the residual, the certificate and the simulation ask of a law, answered
  // here once instead of by switching on `type` where they need it.

  /// Frémond's laws: pseudo-potentials of the mean velocity, dissipative by construction.
  bool is_fremond() const { return type == LawType::fremond; }
  /// Poisson's laws: a compression and an expansion phase (P_C, P_E).
  bool has_phases() const { return type == LawType::poisson || type == LawType::poisson_coulomb; }
  /// Laws with tangential rows: the classical laws with Coulomb, Frémond's with a tangential law.
  bool has_friction() const;
  /// Laws whose tangential percussion is bounded by μ|P_N| (reads `mu`).
  bool uses_coulomb() const {
    return type == LawType::newton_coulomb || type == LawType::poisson_coulomb ||
           (type == LawType::fremond && tangential == TangentialLaw::coulomb);
  }
  /// Frémond with a tangential pseudo-potential φ_T (reads `tangential_potential`).
  bool has_tangential_potential() const {
    return type == LawType::fremond && tangential == TangentialLaw::potential;
  }
  /// Checks parameters and their counts against the number of contacts; throws InvalidArgument
  /// naming `law.e`, `law.mu`, `law.normal`, `law.tangential`.
  void validate(int contacts) const;
  /// True when validate(contacts) would not throw (no message is built).
  bool quick_valid(int contacts) const;
  /// A one-line description, e.g. "fremond(normal=power(k=85.36, p=3), tangential=coulomb(mu=1))".
  std::string describe() const;
};

}  // namespace fremond
