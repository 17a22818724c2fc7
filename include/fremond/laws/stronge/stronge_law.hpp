#pragma once
/// @file Stronge's energetic restitution, with or without Coulomb friction (docs/stronge.md).
#include <array>
#include <span>
#include <string>
#include <string_view>

#include "fremond/laws/per_contact.hpp"

namespace fremond {

/// Stronge's law: the impact integrated in the normal percussion (Darboux-Keller) with Coulomb
/// friction, compression ending where D_N = 0 and restitution where the normal work of restitution
/// is e² times that of compression. One contact, or contacts that do not interact, in closed form;
/// coupled contacts by the distributing law of Liu, Zhao and Brogliato, which shares the
/// percussion among them by their compliances (`eta`, `stiffness`). Dissipative by construction.
struct StrongeLaw {
  PerContact e{0.0};     ///< Stronge's energetic coefficient e* in [0, 1].
  bool coulomb = false;  ///< Coulomb's law during the impact (slip, stick, reversal).
  PerContact mu{0.0};    ///< friction coefficient ≥ 0, read when `coulomb`.
  /// Compliance exponent η > 0 of each contact (force K δ^η: 1 linear, 1.5 Hertz), read by the
  /// distributing law on coupled contacts only.
  PerContact eta{1.0};
  /// Relative stiffness K > 0 of each contact, read by the distributing law on coupled contacts
  /// only: with one η for all, only the ratios matter.
  PerContact stiffness{1.0};

  static constexpr std::array<std::string_view, 2> names{"stronge", "stronge_coulomb"};
  std::string_view name() const { return names[coulomb]; }

  bool has_phases() const { return false; }
  bool has_friction() const { return coulomb; }
  bool uses_coulomb() const { return coulomb; }
  bool has_tangential_potential() const { return false; }
  /// No tangential percussion on a lasting slide of contact k at D_T: no friction, or μ = 0.
  bool leaves_slide_free(int k, double /*D_T*/) const { return !coulomb || mu[k] == 0.0; }
  static constexpr bool dissipative = true;
  /// On coupled contacts the distributing law passes energy from one contact to another (a blow
  /// runs along a chain of balls at rest): the certificate holds the law to the energy
  /// inequality in total, not contact by contact.
  static constexpr bool shares_energy_between_contacts = true;

  /// Throws InvalidArgument naming `law.e`, `law.mu`, `law.eta` or `law.stiffness`: e in [0, 1],
  /// μ ≥ 0 and finite, η and K > 0 and finite, one value or one per contact.
  void validate(int contacts) const;
  bool quick_valid(int contacts) const;
  std::size_t longest_list() const;
  /// E.g. "stronge_coulomb(e=0.9, mu=0.3)", with eta and stiffness where they are not 1.
  std::string describe() const;
  StrongeLaw restricted(const int* idx, int n) const;
  /// Separating contacts without restitution (their reaction alone: docs/concepts.md).
  StrongeLaw of_every_contact(std::span<const double> D_N) const;
};

}  // namespace fremond
