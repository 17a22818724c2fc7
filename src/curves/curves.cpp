// The data of Figs. 8 and 9: sweeps of one point-mass impact under Frémond's law.
#include "fremond/curves/curves.hpp"

#include <cmath>
#include <string>

#include "core/detail/validate.hpp"
#include "fremond/core/enum_names.hpp"
#include "fremond/core/error.hpp"
#include "fremond/potentials/deadzone_power.hpp"
#include "fremond/potentials/power.hpp"
#include "fremond/solvers/solve_impact.hpp"

namespace fremond {

namespace {

constexpr detail::EnumNames<Scaling, 2> kScalings{
    {{Scaling::library, "library"}, {Scaling::paper, "paper"}}};

// docs/laws.md: the paper applies its potentials to D_E + D_A = 2z, so a paper constant c of a term
// |2z|^p equals ours times 2^(1−p) once the 1/p of the library's φ is matched by the paper's
// derivative k z|z|^(p−2) (eq. 22): k_paper = k·2^(1−p), k_T,paper = k_T·2^(1−q), and the dead zone
// |2z| ≤ r_paper is |z| ≤ r_paper/2.
double to_paper_stiffness(double k, double exponent) {
  return k * std::exp2(1.0 - exponent);
}
double to_library_stiffness(double k_paper, double exponent) {
  return k_paper * std::exp2(exponent - 1.0);
}

// The point-mass problem in the stack-stored form: the sweeps solve thousands of these.
SmallImpactProblem small_point_mass(double mass, double D_NA) {
  SmallImpactProblem pb;
  pb.M.setConstant(1, 1, mass);
  pb.W_N.setOnes(1, 1);
  pb.W_T.resize(1, 0);
  pb.w_N.setZero(1);
  pb.w_T.setZero(0);
  pb.qdot_A.setConstant(1, D_NA);
  return pb;
}

SmallImpactProblem small_point_mass(double mass, double D_NA, double D_TA) {
  SmallImpactProblem pb;
  pb.M.setZero(2, 2);
  pb.M(0, 0) = pb.M(1, 1) = mass;
  pb.W_N.resize(2, 1);
  pb.W_N << 0.0, 1.0;
  pb.W_T.resize(2, 1);
  pb.W_T << 1.0, 0.0;
  pb.w_N.setZero(1);
  pb.w_T.setZero(1);
  pb.qdot_A.resize(2);
  pb.qdot_A << D_TA, D_NA;
  return pb;
}

CurvePoint to_point(const SmallImpactResult& r) {
  CurvePoint pt;
  pt.D_NA = r.D_NA(0);
  pt.D_NE = r.D_NE(0);
  if (r.D_TA.size() > 0) {
    pt.D_TA = r.D_TA(0);
    pt.D_TE = r.D_TE(0);
  }
  pt.P_N = r.P_N(0);
  pt.P_N_reaction = r.P_N_reaction.size() > 0 ? r.P_N_reaction(0) : 0.0;
  pt.P_T = r.P_T.size() > 0 ? r.P_T(0) : 0.0;
  pt.energy_change = r.energy_change;
  pt.admissible = r.admissibility.admissible;
  pt.failed = r.admissibility.failed;
  pt.status = r.solver.status;
  return pt;
}

}  // namespace

std::string_view to_string(Scaling s) {
  return detail::enum_to_string(kScalings, s);
}
Scaling scaling_from_string(std::string_view s) {
  return detail::enum_from_string(kScalings, s, "scaling");
}

NormalCurveParameters NormalCurveParameters::in_library_scaling() const {
  NormalCurveParameters out = *this;
  if (scaling == Scaling::paper) out.k = to_library_stiffness(k, p);
  out.scaling = Scaling::library;
  return out;
}

NormalCurveParameters NormalCurveParameters::in_paper_scaling() const {
  NormalCurveParameters out = *this;
  if (scaling == Scaling::library) out.k = to_paper_stiffness(k, p);
  out.scaling = Scaling::paper;
  return out;
}

void NormalCurveParameters::validate() const {
  detail::require_finite_above("mass", mass, 0.0);
  detail::require_finite_at_least("k", k, 0.0);
  detail::require_finite_above("p", p, 1.0);
}

TangentialCurveParameters TangentialCurveParameters::paper_figure(Scaling scaling) {
  TangentialCurveParameters spec;  // the defaults are the paper's figure in the library's scaling
  return scaling == Scaling::library ? spec : spec.in_paper_scaling();
}

TangentialCurveParameters TangentialCurveParameters::in_library_scaling() const {
  TangentialCurveParameters out = *this;
  if (scaling == Scaling::paper) {
    out.k_N = to_library_stiffness(k_N, p);
    out.k_T = to_library_stiffness(k_T, q);
    out.r = 0.5 * r;
  }
  out.scaling = Scaling::library;
  return out;
}

TangentialCurveParameters TangentialCurveParameters::in_paper_scaling() const {
  TangentialCurveParameters out = *this;
  if (scaling == Scaling::library) {
    out.k_N = to_paper_stiffness(k_N, p);
    out.k_T = to_paper_stiffness(k_T, q);
    out.r = 2.0 * r;
  }
  out.scaling = Scaling::paper;
  return out;
}

void TangentialCurveParameters::validate() const {
  detail::require_finite_above("mass", mass, 0.0);
  detail::require_finite_at_least("k_N", k_N, 0.0);
  detail::require_finite_above("p", p, 1.0);
  detail::require_finite("D_NA", D_NA);
  if (!(D_NA <= 0.0))
    throw InvalidArgument("D_NA", "must be <= 0 (the mass moves towards the ground), got " +
                                      detail::format_number(D_NA));
  detail::require_finite_at_least("k_T", k_T, 0.0);
  detail::require_finite_above("q", q, 1.0);
  detail::require_finite_at_least("r", r, 0.0);
}

ImpactProblem point_mass_problem(double mass, double D_NA) {
  detail::require_finite_above("mass", mass, 0.0);
  detail::require_finite("D_NA", D_NA);
  return to_dynamic(small_point_mass(mass, D_NA));
}

ImpactProblem point_mass_problem(double mass, double D_NA, double D_TA) {
  detail::require_finite_above("mass", mass, 0.0);
  detail::require_finite("D_NA", D_NA);
  detail::require_finite("D_TA", D_TA);
  return to_dynamic(small_point_mass(mass, D_NA, D_TA));
}

ImpactLaw normal_curve_law(const NormalCurveParameters& parameters) {
  parameters.validate();
  const NormalCurveParameters s = parameters.in_library_scaling();
  return ImpactLaw::fremond(PowerPotential(s.k, s.p));
}

ImpactLaw tangential_curve_law(const TangentialCurveParameters& parameters) {
  parameters.validate();
  const TangentialCurveParameters s = parameters.in_library_scaling();
  return ImpactLaw::fremond(PowerPotential(s.k_N, s.p), DeadZonePowerPotential(s.k_T, s.q, s.r));
}

std::vector<CurvePoint> normal_restitution_curve(const NormalCurveParameters& parameters,
                                                 std::span<const double> speeds,
                                                 const SolverOptions& options) {
  const ImpactLaw law = normal_curve_law(parameters);
  options.validate();
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    const std::string name = "speeds[" + std::to_string(i) + "]";
    detail::require_finite_at_least(name, speeds[i], 0.0);
  }
  std::vector<CurvePoint> out;
  out.reserve(speeds.size());
  for (double speed : speeds)
    out.push_back(to_point(solve_impact(small_point_mass(parameters.mass, -speed), law, options)));
  return out;
}

std::vector<CurvePoint> tangential_curve(const TangentialCurveParameters& parameters,
                                         std::span<const double> D_TA,
                                         const SolverOptions& options) {
  const ImpactLaw law = tangential_curve_law(parameters);
  options.validate();
  for (std::size_t i = 0; i < D_TA.size(); ++i)
    detail::require_finite("D_TA[" + std::to_string(i) + "]", D_TA[i]);
  const double r = parameters.in_library_scaling().r;
  std::vector<CurvePoint> out;
  out.reserve(D_TA.size());
  for (double v : D_TA) {
    CurvePoint pt =
        to_point(solve_impact(small_point_mass(parameters.mass, parameters.D_NA, v), law, options));
    // With P_T = 0 the mean tangential velocity is D_TA itself, so |D_TA| ≤ r is exactly the
    // input for which eq. (25) gives no tangential percussion (the law's solution is unique).
    pt.in_dead_zone = std::fabs(v) <= r;
    out.push_back(pt);
  }
  return out;
}

double equivalent_restitution(const NormalCurveParameters& parameters) {
  parameters.validate();
  if (parameters.p != 2.0)
    throw InvalidArgument(
        "p", "eq. (24) holds for p = 2 only, got " + detail::format_number(parameters.p));
  // m(D_E − D_A) = −k (D_A + D_E)/2 gives D_E = −(k − 2m)/(k + 2m) D_A.
  const double k = parameters.in_library_scaling().k;
  return (k - 2.0 * parameters.mass) / (k + 2.0 * parameters.mass);
}

}  // namespace fremond
