#pragma once
/// @file The families of laws a fit searches (docs/measurements.md): each a law of law_list.hpp
/// with the parameters a fit varies and those it holds.
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "fremond/laws/impact_law.hpp"

namespace fremond {

/// A law with its parameters left open. The parameters a fit varies, in order:
enum class LawFamily {
  newton,            ///< e
  poisson,           ///< e
  newton_coulomb,    ///< e, mu
  poisson_coulomb,   ///< e, mu
  stronge,           ///< e (Stronge's energetic e*)
  stronge_coulomb,   ///< e, mu
  fremond,           ///< k, p of the normal power law φ_N = k|z|^p/p, no tangential law
  fremond_coulomb,   ///< k, p, mu (Coulomb on the mean tangential velocity)
  fremond_deadzone,  ///< k, p, k_T of φ_T = (k_T/q) max(0, |y| − r)^q; q = 2 and r = 0 are held
                     ///< unless FitOptions::fixed gives them
};

/// Every family in the order above.
const std::vector<LawFamily>& law_families();
/// "newton_coulomb", "fremond_deadzone", ...
std::string_view to_string(LawFamily family);
/// Throws InvalidArgument("law", ...) naming the text and the known families.
LawFamily law_family_from_string(std::string_view name);

/// The parameters a fit of the family varies, in the order of the enum's comments.
std::vector<std::string> fitted_parameters(LawFamily family);
/// The parameters the family holds at a value unless told otherwise (fremond_deadzone: q = 2,
/// r = 0), with those values.
std::map<std::string, double> held_parameters(LawFamily family);

/// The family's law at the named values: every fitted parameter must be given; held ones default
/// to held_parameters(). Throws InvalidArgument naming a missing or unknown parameter, or the
/// law's own refusal (e.g. `law.e: must lie in [0, 1]`).
ImpactLaw make_law(LawFamily family, const std::map<std::string, double>& values);

}  // namespace fremond
