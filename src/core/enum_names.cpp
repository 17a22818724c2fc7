// Names of every public enum, as used by the problem file, the command line and the bindings.
#include "fremond/core/enum_names.hpp"

#include "fremond/admissibility/admissibility_report.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/solver_status.hpp"

namespace fremond {

namespace {
using detail::EnumNames;
constexpr EnumNames<AttemptStart, 9> kStarts{
    {{AttemptStart::none, "none"},
     {AttemptStart::decoupled_guess, "decoupled_guess"},
     {AttemptStart::zero, "zero"},
     {AttemptStart::newton_end, "newton_end"},
     {AttemptStart::splitting_end, "splitting_end"},
     {AttemptStart::nlopt_end, "nlopt_end"},
     {AttemptStart::velocity_newton_end, "velocity_newton_end"},
     {AttemptStart::normal_rows, "normal_rows"},
     {AttemptStart::sweeps_end, "sweeps_end"}}};
constexpr EnumNames<SolverStatus, 7> kStatus{{{SolverStatus::not_run, "not_run"},
                                              {SolverStatus::converged, "converged"},
                                              {SolverStatus::max_iterations, "max_iterations"},
                                              {SolverStatus::stalled, "stalled"},
                                              {SolverStatus::no_solution, "no_solution"},
                                              {SolverStatus::failed, "failed"},
                                              {SolverStatus::unsupported, "unsupported"}}};
constexpr EnumNames<SolverMethod, 11> kMethods{
    {{SolverMethod::automatic, "automatic"},
     {SolverMethod::trivial, "trivial"},
     {SolverMethod::closed_form, "closed_form"},
     {SolverMethod::scalar_newton, "scalar_newton"},
     {SolverMethod::mode_enumeration, "mode_enumeration"},
     {SolverMethod::lemke, "lemke"},
     {SolverMethod::semismooth_newton, "semismooth_newton"},
     {SolverMethod::proximal, "proximal"},
     {SolverMethod::nlopt, "nlopt"},
     {SolverMethod::impulse_integration, "impulse_integration"},
     {SolverMethod::nsgs, "nsgs"}}};
constexpr EnumNames<StopCriterion, 8> kCriteria{{{StopCriterion::none, "none"},
                                                 {StopCriterion::exact, "exact"},
                                                 {StopCriterion::residual, "residual"},
                                                 {StopCriterion::step, "step"},
                                                 {StopCriterion::iterations, "iterations"},
                                                 {StopCriterion::nlopt, "nlopt"},
                                                 {StopCriterion::rounding, "rounding"},
                                                 {StopCriterion::data, "data"}}};
constexpr EnumNames<Inequality, 8> kInequalities{
    {{Inequality::none, "none"},
     {Inequality::total_15, "total_15"},
     {Inequality::per_contact_15, "per_contact_15"},
     {Inequality::reaction_17, "reaction_17"},
     {Inequality::dissipation_19, "dissipation_19"},
     {Inequality::complementarity_16, "complementarity_16"},
     {Inequality::fenchel_young, "fenchel_young"},
     {Inequality::non_penetration, "non_penetration"}}};
}  // namespace

std::string_view to_string(SolverStatus s) {
  return detail::enum_to_string(kStatus, s);
}
SolverStatus solver_status_from_string(std::string_view s) {
  return detail::enum_from_string(kStatus, s, "solver status");
}
std::string_view to_string(SolverMethod m) {
  return detail::enum_to_string(kMethods, m);
}
SolverMethod solver_method_from_string(std::string_view s) {
  return detail::enum_from_string(kMethods, s, "method");
}
std::string_view to_string(StopCriterion c) {
  return detail::enum_to_string(kCriteria, c);
}
StopCriterion stop_criterion_from_string(std::string_view s) {
  return detail::enum_from_string(kCriteria, s, "stop criterion");
}
std::string_view to_string(AttemptStart a) {
  return detail::enum_to_string(kStarts, a);
}
AttemptStart attempt_start_from_string(std::string_view s) {
  return detail::enum_from_string(kStarts, s, "attempt start");
}
std::string_view to_string(Inequality i) {
  return detail::enum_to_string(kInequalities, i);
}
Inequality inequality_from_string(std::string_view s) {
  return detail::enum_from_string(kInequalities, s, "inequality");
}

}  // namespace fremond
