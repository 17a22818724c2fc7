// First impact of a scene and the calibration of Frémond's k_N (docs/laws.md).
#include "fremond/simulation/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"
#include "fremond/potentials/power.hpp"
#include "fremond/scenes/kinematics.hpp"
#include "fremond/simulation/event_detection.hpp"
#include "fremond/solvers/solve_impact.hpp"

namespace fremond {

FirstImpact first_impact(const Scene& scene_in, double t_max, double simultaneity_tolerance) {
  Scene scene = scene_in;
  scene.validate();
  const FreeFlight flight{0.0, scene.initial, scene.gravity};
  const int nc = scene.contact_count();
  std::array<double, kMaxSceneContacts> when{};
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < nc; ++k) {
    const GapFunction g = GapFunction::make(scene.body.points[scene.point_of(k)],
                                            scene.obstacles[scene.obstacle_of(k)], flight);
    const EventSearchResult r =
        find_first_event(g, std::min(t_max, best + simultaneity_tolerance), false);
    if (r.exhausted) {
      FirstImpact out;
      out.resolved = false;
      return out;
    }
    when[k] = r.s;
    best = std::min(best, when[k]);
  }
  FirstImpact out;
  if (!std::isfinite(best)) return out;
  out.found = true;
  out.t = best;
  out.state = flight.at_elapsed(best);
  for (int k = 0; k < nc; ++k)
    if (when[k] <= best + simultaneity_tolerance) out.contacts[out.contact_count++] = k;
  return out;
}

SmallImpactProblem impact_problem(const Scene& scene, const PlanarState& state, const int* contacts,
                                  int n) {
  if (n < 0 || n > kSmallContacts)
    throw InvalidArgument("contacts", "must number 0 to " + std::to_string(kSmallContacts));
  SmallImpactProblem pb;
  pb.M = scene.body.mass_matrix();
  pb.W_N.resize(3, n);
  pb.W_T.resize(3, n);
  pb.w_N.setZero(n);
  pb.w_T.setZero(n);
  pb.qdot_A = state.qdot;
  for (int i = 0; i < n; ++i) {
    const ContactFrame f = contact_frame(scene, contacts[i], state.q);
    pb.W_N.col(i) = f.W_N;
    pb.W_T.col(i) = f.W_T;
  }
  return pb;
}

StiffnessCalibration calibrate_normal_stiffness(const SmallImpactProblem& problem_in, double p,
                                                double restitution, int contact,
                                                const SolverOptions& options) {
  detail::require_finite_above("p", p, 1.0);
  detail::require_finite("restitution", restitution);
  if (!(restitution > 0.0 && restitution < 1.0))
    throw InvalidArgument("restitution",
                          "must lie in (0, 1), got " + detail::format_number(restitution));
  if (contact < 0 || contact >= problem_in.contacts())
    throw InvalidArgument("contact", "no contact " + std::to_string(contact));
  SmallImpactProblem problem = problem_in;
  problem.W_T.resize(problem.dofs(), 0);  // the normal law alone (docs/laws.md)
  problem.w_T.resize(0);
  const double w = problem.w_N.size() ? problem.w_N(contact) : 0.0;
  const double d_na = problem.W_N.col(contact).dot(problem.qdot_A) + w;
  if (!(d_na < 0.0)) throw InvalidArgument("contact", "does not approach (D_NA >= 0)");

  StiffnessCalibration out;
  // f(u) = restitution at k = e^u, minus the target; increasing in u.
  const auto f = [&](double u) {
    ++out.solves;
    const auto r =
        solve_impact(problem, ImpactLaw::fremond(PowerPotential(std::exp(u), p)), options);
    if (!r.ok()) return std::numeric_limits<double>::quiet_NaN();
    return -r.D_NE(contact) / d_na - restitution;
  };
  // Bracket in decades around k = 1.
  double a = 0.0, fa = f(a);
  if (!std::isfinite(fa)) return out;
  double b = a, fb = fa;
  const double step = std::log(10.0) * (fa < 0.0 ? 1.0 : -1.0);
  for (int i = 0; i < 40 && std::isfinite(fb) && (fb < 0.0) == (fa < 0.0); ++i) {
    a = b;
    fa = fb;
    b += step;
    fb = f(b);
  }
  if (!std::isfinite(fb) || (fb < 0.0) == (fa < 0.0)) return out;

  // Brent's method (Brent 1973, ch. 4) on [a, b].
  double c = a, fc = fa, d = b - a, e = d;
  for (int it = 0; it < 200; ++it) {
    if ((fb > 0.0) == (fc > 0.0)) {
      c = a;
      fc = fa;
      d = e = b - a;
    }
    if (std::fabs(fc) < std::fabs(fb)) {
      a = b;
      b = c;
      c = a;
      fa = fb;
      fb = fc;
      fc = fa;
    }
    const double tol = 2.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::fabs(b));
    const double m = 0.5 * (c - b);
    if (std::fabs(m) <= tol || fb == 0.0) {
      out.converged = true;
      break;
    }
    if (std::fabs(e) >= tol && std::fabs(fa) > std::fabs(fb)) {
      double s = fb / fa, pp, qq;
      if (a == c) {
        pp = 2.0 * m * s;
        qq = 1.0 - s;
      } else {
        const double q0 = fa / fc, r = fb / fc;
        pp = s * (2.0 * m * q0 * (q0 - r) - (b - a) * (r - 1.0));
        qq = (q0 - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (pp > 0.0) qq = -qq;
      pp = std::fabs(pp);
      if (2.0 * pp < std::min(3.0 * m * qq - std::fabs(tol * qq), std::fabs(e * qq))) {
        e = d;
        d = pp / qq;
      } else {
        d = m;
        e = m;
      }
    } else {
      d = m;
      e = m;
    }
    a = b;
    fa = fb;
    b += std::fabs(d) > tol ? d : (m > 0.0 ? tol : -tol);
    fb = f(b);
    if (!std::isfinite(fb)) return out;
  }
  out.k_N = std::exp(b);
  out.restitution = fb + restitution;
  return out;
}

double first_impact_normal_stiffness(const Scene& scene, double p, double restitution) {
  const FirstImpact first = first_impact(scene, 1e4);
  if (!first.resolved)
    throw InvalidArgument("scene",
                          "turns too fast for the event search to find its first contact event");
  if (!first.found) throw InvalidArgument("scene", "never reaches an obstacle");
  const int n = std::min(first.contact_count, kSmallContacts);
  const SmallImpactProblem pb = impact_problem(scene, first.state, first.contacts.data(), n);
  const StiffnessCalibration cal = calibrate_normal_stiffness(pb, p, restitution, 0);
  if (!cal.converged)
    throw InvalidArgument("k_N", "the calibration of Frémond's normal stiffness did not converge");
  return cal.k_N;
}

double paper_bar_normal_stiffness(const BarParameters& bar) {
  return first_impact_normal_stiffness(bar_scene(bar, ImpactLaw::newton(PaperConstants::e)),
                                       PaperConstants::p, PaperConstants::e);
}

Scene paper_bar_scene(PaperLaw law, const BarParameters& bar) {
  const bool fremond = law == PaperLaw::fremond_coulomb || law == PaperLaw::fremond_viscous;
  return bar_scene(bar, paper_law(law, fremond ? paper_bar_normal_stiffness(bar) : 0.0));
}

}  // namespace fremond
