#pragma once
/// @file Newton's and Poisson's restitution, each with or without Coulomb friction (docs/laws.md).
#include <array>
#include <span>
#include <string>
#include <string_view>

#include "fremond/laws/per_contact.hpp"

namespace fremond {

/// Newton's or Poisson's restitution on every contact, with Coulomb friction when `coulomb`.
/// The four laws are one family: one solver chain (contact modes, docs/solvers.md), one residual.
struct RestitutionLaw {
  enum class Kind {
    newton,   ///< D_NE + e D_NA ≥ 0 ⊥ P_N ≥ 0 (paper eqs. 5-6).
    poisson,  ///< compression then expansion with P_NE = e P_NC + ΔP.
  };
  Kind kind = Kind::newton;
  PerContact e{0.0};     ///< restitution in [0, 1].
  bool coulomb = false;  ///< Coulomb on (P_T, D_TE) (paper §4; per phase for Poisson).
  PerContact mu{0.0};    ///< friction coefficient ≥ 0, read when `coulomb`.

  /// The names of the problem file's `law.type`, as name() gives them.
  static constexpr std::array<std::string_view, 4> names{"newton", "poisson", "newton_coulomb",
                                                         "poisson_coulomb"};
  std::string_view name() const { return names[2 * coulomb + (kind == Kind::poisson)]; }

  /// Poisson's laws: a compression and an expansion phase (P_C, P_E).
  bool has_phases() const { return kind == Kind::poisson; }
  /// Tangential rows: the laws with Coulomb.
  bool has_friction() const { return coulomb; }
  bool uses_coulomb() const { return coulomb; }
  bool has_tangential_potential() const { return false; }
  /// Creates no energy by construction (the certificate's finding, not the solver's failure).
  /// No tangential percussion on a lasting slide of contact k at D_T: no friction, or μ = 0.
  bool leaves_slide_free(int k, double /*D_T*/) const { return !coulomb || mu[k] == 0.0; }
  static constexpr bool dissipative = false;

  /// Throws InvalidArgument naming `law.e`, `law.mu` (or `law.e[i]`): e in [0, 1], μ ≥ 0 and
  /// finite, one value or one per contact.
  void validate(int contacts) const;
  /// True when validate(contacts) would not throw (no message is built).
  bool quick_valid(int contacts) const;
  /// The longest of the per-contact lists (1 where every value is shared).
  std::size_t longest_list() const;
  /// E.g. "newton_coulomb(e=0.5, mu=[0.2, 0.3])".
  std::string describe() const;
  /// The law of the contacts idx[0..n).
  RestitutionLaw restricted(const int* idx, int n) const;
  /// The law as every contact obeys it (docs/laws.md), D_N their velocities before the impact:
  /// Newton's separating contacts without restitution; Poisson's obey both phases as they are.
  RestitutionLaw of_every_contact(std::span<const double> D_N) const;
};

}  // namespace fremond
