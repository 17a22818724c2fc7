#pragma once
/// @file An impact law of docs/laws.md: one of the laws of law_list.hpp with its parameters.
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "fremond/laws/law_list.hpp"

namespace fremond {

/// The names of the problem file's `law.type`, every law of law_list.hpp in its order.
std::vector<std::string_view> law_names();
/// Throws InvalidArgument("law.type", ...) for a name no law of law_list.hpp has.
void check_law_name(std::string_view name);

/// An impact law: one of the laws of law_list.hpp (a std::variant: the solvers are templates on
/// the problem's sizes, so a law is dispatched once per solve at compile time, with no virtual
/// call and no heap). Build it with the named constructors, or from a law's value type.
class ImpactLaw {
 public:
  /// Newton's law with e = 0.
  ImpactLaw() = default;
  /// From any law of law_list.hpp, checked as the factories check it.
  template <class Law>
  requires(!std::is_same_v<std::remove_cvref_t<Law>, ImpactLaw> &&
           std::is_constructible_v<LawVariant, Law>)
      ImpactLaw(Law law)  // NOLINT: implicit by design
      : law_(std::move(law)) {
    check_values();
  }

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

  /// The law's value type and parameters.
  template <class Law>
  bool is() const {
    return std::holds_alternative<Law>(law_);
  }
  template <class Law>
  const Law* get_if() const {
    return std::get_if<Law>(&law_);
  }
  /// Throws InvalidArgument("law", ...) when the law is another one.
  template <class Law>
  const Law& get() const {
    if (const Law* l = get_if<Law>()) return *l;
    throw_not(Law::names[0]);
  }
  const LawVariant& variant() const { return law_; }
  template <class F>
  decltype(auto) visit(F&& f) const {
    return std::visit(std::forward<F>(f), law_);
  }

  // What the solvers, the residual, the certificate and the simulation ask of every law.

  /// The problem file's `law.type`, e.g. "newton_coulomb".
  std::string_view name() const {
    return visit([](const auto& l) { return l.name(); });
  }
  /// A compression and an expansion phase (P_C, P_E): Poisson's laws.
  bool has_phases() const {
    return visit([](const auto& l) { return l.has_phases(); });
  }
  /// Tangential rows in contact space.
  bool has_friction() const {
    return visit([](const auto& l) { return l.has_friction(); });
  }
  /// The tangential percussion bounded by μ|P_N| (μ given by mu()).
  bool uses_coulomb() const {
    return visit([](const auto& l) { return l.uses_coulomb(); });
  }
  /// A tangential pseudo-potential φ_T.
  bool has_tangential_potential() const {
    return visit([](const auto& l) { return l.has_tangential_potential(); });
  }
  /// No exact answer creates energy (an answer its certificate refuses is not resolved).
  bool dissipative() const {
    return visit([](const auto& l) { return l.dissipative; });
  }
  /// Coulomb's μ of contact k; 0 for a law without Coulomb.
  double mu(int k) const {
    return visit([k](const auto& l) { return l.uses_coulomb() ? l.mu[k] : 0.0; });
  }
  /// No tangential percussion on a lasting slide of contact k at D_T (the simulation's test of a
  /// slide nothing stops).
  bool leaves_slide_free(int k, double D_T) const {
    return visit([k, D_T](const auto& l) { return l.leaves_slide_free(k, D_T); });
  }
  /// Checks parameters and their counts against the number of contacts; throws InvalidArgument
  /// naming `law.e`, `law.mu`, `law.normal`, `law.tangential`.
  void validate(int contacts) const {
    visit([contacts](const auto& l) { l.validate(contacts); });
  }
  /// True when validate(contacts) would not throw (no message is built).
  bool quick_valid(int contacts) const {
    return visit([contacts](const auto& l) { return l.quick_valid(contacts); });
  }
  /// A one-line description, e.g. "fremond(normal=power(k=85.36, p=3), tangential=coulomb(mu=1))".
  std::string describe() const {
    return visit([](const auto& l) { return l.describe(); });
  }

 private:
  void check_values() const;
  [[noreturn]] void throw_not(std::string_view wanted) const;
  LawVariant law_;
};

}  // namespace fremond
