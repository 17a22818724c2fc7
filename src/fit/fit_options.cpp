#include "fremond/fit/fit_options.hpp"

#include <array>
#include <cmath>
#include <string>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"

namespace fremond {

namespace {

template <class E, std::size_t N>
E from_names(std::string_view text, const std::array<std::string_view, N>& names, const char* key) {
  for (std::size_t i = 0; i < N; ++i)
    if (names[i] == text) return static_cast<E>(i);
  std::string known;
  for (const auto n : names) known += (known.empty() ? "" : ", ") + std::string(n);
  throw InvalidArgument(key, "unknown value '" + std::string(text) + "' (known: " + known + ")");
}

constexpr std::array<std::string_view, 3> kLosses{"least_squares", "huber", "soft_l1"};
constexpr std::array<std::string_view, 2> kUncertainties{"gauss_newton", "bootstrap"};

}  // namespace

SolverOptions fit_solver_options() {
  SolverOptions o;
  o.check_uniqueness = false;  // a fit reads q̇_E only; the search for other answers costs solves
  return o;
}

std::string_view to_string(FitLoss loss) {
  return kLosses[static_cast<std::size_t>(loss)];
}
FitLoss fit_loss_from_string(std::string_view name) {
  return from_names<FitLoss>(name, kLosses, "loss");
}
std::string_view to_string(FitUncertainty u) {
  return kUncertainties[static_cast<std::size_t>(u)];
}
FitUncertainty fit_uncertainty_from_string(std::string_view name) {
  return from_names<FitUncertainty>(name, kUncertainties, "uncertainty");
}

void FitOptions::validate() const {
  using detail::format_number;
  if (!std::isfinite(loss_scale) || !(loss_scale > 0.0))
    throw InvalidArgument("loss_scale",
                          "must be a finite number > 0, got " + format_number(loss_scale));
  if (global_evaluations < 0)
    throw InvalidArgument("global_evaluations", "must be >= 0 (0 skips the global stage), got " +
                                                    std::to_string(global_evaluations));
  if (local_evaluations < 1)
    throw InvalidArgument("local_evaluations",
                          "must be >= 1, got " + std::to_string(local_evaluations));
  if (!std::isfinite(xtol_rel) || !(xtol_rel > 0.0))
    throw InvalidArgument("xtol_rel",
                          "must be a finite number > 0, got " + format_number(xtol_rel));
  if (uncertainty == FitUncertainty::bootstrap && bootstrap_samples < 2)
    throw InvalidArgument("bootstrap_samples",
                          "must be >= 2 for a spread, got " + std::to_string(bootstrap_samples));
  if (folds < 0 || folds == 1)
    throw InvalidArgument("folds",
                          "must be 0 (no cross-validation) or >= 2, got " + std::to_string(folds));
  for (const auto& [name, value] : fixed)
    if (!std::isfinite(value))
      throw InvalidArgument("fixed." + name,
                            "must be a finite number, got " + format_number(value));
  for (const auto& [name, b] : bounds)
    if (!std::isfinite(b.first) || !std::isfinite(b.second) || !(b.first < b.second))
      throw InvalidArgument("bounds." + name, "must be finite with lower < upper, got [" +
                                                  format_number(b.first) + ", " +
                                                  format_number(b.second) + "]");
  solver.validate();
  batch.validate();
}

}  // namespace fremond
