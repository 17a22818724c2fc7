// Options of a run: ranges, and the names of the simulation's enumerations.
#include "fremond/simulation/simulation_options.hpp"

#include <cmath>

#include "core/detail/validate.hpp"
#include "fremond/core/enum_names.hpp"
#include "fremond/core/error.hpp"
#include "fremond/simulation/simulate.hpp"

namespace fremond {

namespace {
using detail::EnumNames;
constexpr EnumNames<Integrator, 2> kIntegrators{
    {{Integrator::event_driven, "event_driven"}, {Integrator::moreau_jean, "moreau_jean"}}};
constexpr EnumNames<Phase, 2> kPhases{
    {{Phase::event_driven, "event_driven"}, {Phase::moreau_jean, "moreau_jean"}}};
constexpr EnumNames<SimulationStatus, 7> kStatus{
    {{SimulationStatus::not_run, "not_run"},
     {SimulationStatus::completed, "completed"},
     {SimulationStatus::max_impacts, "max_impacts"},
     {SimulationStatus::impact_failed, "impact_failed"},
     {SimulationStatus::contact_failed, "contact_failed"},
     {SimulationStatus::event_search_failed, "event_search_failed"},
     {SimulationStatus::interrupted, "interrupted"}}};
constexpr EnumNames<ImpactKind, 3> kKinds{{{ImpactKind::event, "event"},
                                           {ImpactKind::time_step, "time_step"},
                                           {ImpactKind::accumulation, "accumulation"}}};
}  // namespace

std::string_view to_string(Integrator i) {
  return detail::enum_to_string(kIntegrators, i);
}
Integrator integrator_from_string(std::string_view s) {
  return detail::enum_from_string(kIntegrators, s, "integrator.method");
}
std::string_view to_string(Phase p) {
  return detail::enum_to_string(kPhases, p);
}
Phase phase_from_string(std::string_view s) {
  return detail::enum_from_string(kPhases, s, "phase");
}
std::string_view to_string(SimulationStatus s) {
  return detail::enum_to_string(kStatus, s);
}
SimulationStatus simulation_status_from_string(std::string_view s) {
  return detail::enum_from_string(kStatus, s, "simulation status");
}
std::string_view to_string(ImpactKind k) {
  return detail::enum_to_string(kKinds, k);
}
ImpactKind impact_kind_from_string(std::string_view s) {
  return detail::enum_from_string(kKinds, s, "impact kind");
}

namespace {
// The first option out of range, as {name, reason}; name empty when all are valid.
std::pair<std::string, std::string> first_invalid(const SimulationOptions& o) {
  using detail::format_number;
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!positive(o.t_end))
    return {"t_end", "must be a finite number > 0, got " + format_number(o.t_end)};
  if (!positive(o.step) || !(o.step <= o.t_end))
    return {"integrator.step", "must be in (0, t_end], got " + format_number(o.step)};
  if (o.max_impacts < 1)
    return {"integrator.max_impacts", "must be >= 1, got " + std::to_string(o.max_impacts)};
  if (!non_negative(o.simultaneity_tolerance))
    return {"integrator.simultaneity_tolerance",
            "must be a finite number >= 0, got " + format_number(o.simultaneity_tolerance)};
  if (o.max_gap_evaluations < 100)
    return {"integrator.max_gap_evaluations",
            "must be >= 100, got " + std::to_string(o.max_gap_evaluations)};
  if (!non_negative(o.gap_tolerance))
    return {"integrator.gap_tolerance",
            "must be a finite number >= 0, got " + format_number(o.gap_tolerance)};
  if (!non_negative(o.velocity_tolerance))
    return {"integrator.velocity_tolerance",
            "must be a finite number >= 0, got " + format_number(o.velocity_tolerance)};
  if (!positive(o.accumulation_interval))
    return {"integrator.accumulation_interval",
            "must be a finite number > 0, got " + format_number(o.accumulation_interval)};
  if (o.accumulation_impacts < 2 || o.accumulation_impacts > 32)
    return {"integrator.accumulation_impacts",
            "must be in [2, 32], got " + std::to_string(o.accumulation_impacts)};
  if (o.return_after_free_steps < 1)
    return {"integrator.return_after_free_steps",
            "must be >= 1, got " + std::to_string(o.return_after_free_steps)};
  if (!positive(o.sample_interval))
    return {"output.sample_interval",
            "must be a finite number > 0, got " + format_number(o.sample_interval)};
  std::string why;
  if (!o.solver.is_valid(&why)) return {"solver", why};
  return {};
}
}  // namespace

bool SimulationOptions::is_valid(std::string* why) const {
  const auto [name, reason] = first_invalid(*this);
  if (name.empty()) return true;
  if (why) *why = name + ": " + reason;
  return false;
}

void SimulationOptions::validate() const {
  const auto [name, reason] = first_invalid(*this);
  if (!name.empty()) throw InvalidArgument(name, reason);
}

}  // namespace fremond
