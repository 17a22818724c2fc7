// The law atlas: one contact of a planar body swept over θ, ψ and the spin ratio, under several
// laws and a list of μ or e, each point one solve_impact through solve_batch (docs/atlas.md).
#include "fremond/atlas/atlas.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>

#include "core/detail/validate.hpp"
#include "fremond/core/enum_names.hpp"
#include "fremond/core/error.hpp"
#include "fremond/laws/stronge/stronge_law.hpp"
#include "fremond/potentials/power.hpp"
#include "fremond/scenes/kinematics.hpp"
#include "fremond/simulation/calibration.hpp"
#include "fremond/solvers/solve_batch.hpp"

namespace fremond {

namespace {

constexpr detail::EnumNames<AtlasParameter, 2> kParameters{
    {{AtlasParameter::mu, "mu"}, {AtlasParameter::e, "e"}}};
constexpr detail::EnumNames<AtlasMode, 4> kModes{{{AtlasMode::stick, "stick"},
                                                  {AtlasMode::slide, "slide"},
                                                  {AtlasMode::reversal, "reversal"},
                                                  {AtlasMode::unknown, "unknown"}}};

constexpr int kMaxCells = 100000;
// Points solved per solve_batch call: small enough for the reused problems and results (2 kB a
// point) to stay in cache while they are read back, large enough that starting the threads
// costs little (about 1 ms of solving per block).
constexpr std::size_t kBlock = 1024;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string indexed(const char* name, std::size_t i) {
  return std::string(name) + "[" + std::to_string(i) + "]";
}

bool needs_fremond_k_N(const AtlasOptions& o) {
  return o.fremond_k_N == 0.0 && std::find(o.laws.begin(), o.laws.end(), "fremond") != o.laws.end();
}

// The law `name` with its parameters; the names were checked by validate().
ImpactLaw make_law(const std::string& name, double e, double mu, double k_N, double p) {
  if (name == "newton") return ImpactLaw::newton(e);
  if (name == "poisson") return ImpactLaw::poisson(e);
  if (name == "newton_coulomb") return ImpactLaw::newton_coulomb(e, mu);
  if (name == "poisson_coulomb") return ImpactLaw::poisson_coulomb(e, mu);
  if (name == "fremond") return ImpactLaw::fremond_coulomb(PowerPotential(k_N, p), mu);
  StrongeLaw stronge;
  stronge.e = e;
  stronge.coulomb = name == "stronge_coulomb";
  stronge.mu = mu;
  return stronge;
}

// The reading every law shares (AtlasMode): inside Coulomb's bound is a stick in the law's own
// variable; at it, the velocities say whether the slip goes on or turns back.
AtlasMode mode_of(double D_TA, double D_TE, double P_N, double P_T, double mu, double speed) {
  const double bound = mu * std::fabs(P_N);
  if (std::fabs(P_T) < (1.0 - kAtlasStickTolerance) * bound) return AtlasMode::stick;
  if (std::fabs(D_TE) <= kAtlasStickTolerance * speed) return AtlasMode::stick;
  return D_TA * D_TE < 0.0 ? AtlasMode::reversal : AtlasMode::slide;
}

std::int8_t solutions_of(const SmallImpactResult& r) {
  if (r.solver.status == SolverStatus::no_solution) return 0;
  if (r.solver.status != SolverStatus::converged) return -1;
  if (r.solutions_found > 0) return static_cast<std::int8_t>(std::min(r.solutions_found, 127));
  return r.unique ? 1 : 2;
}

// Cell centres of [lo, hi]: the ends (ψ = −π, 0: a grazing contact) are never solved.
std::vector<double> centres(double lo, double hi, int n) {
  std::vector<double> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = lo + (hi - lo) * (i + 0.5) / n;
  return v;
}

// The first impact of the scene from its initial state, for the defaults that come from it.
FirstImpact scene_first_impact(const Scene& scene, const char* option) {
  const FirstImpact first = first_impact(scene, 1e4);
  if (!first.resolved || !first.found || first.contact_count < 1)
    throw InvalidArgument(option, "cannot be taken from the scene's first impact: the scene " +
                                      std::string(first.resolved ? "never reaches an obstacle"
                                                                 : "turns too fast to find it") +
                                      "; give it");
  return first;
}

// The contact's frame at θ (its position does not matter: W_N, W_T depend on θ alone).
ContactFrame frame_at(const Scene& scene, int contact, double theta) {
  const ContactPoint& point = scene.body.points[static_cast<std::size_t>(scene.point_of(contact))];
  const HalfPlane& plane = scene.obstacles[static_cast<std::size_t>(scene.obstacle_of(contact))];
  return contact_frame(point, plane, Eigen::Vector2d::Zero(), std::cos(theta), std::sin(theta));
}

// q̇_A with contact velocities (D_TA, D_NA) and spin θ̇: the centre's velocity v from
// n·v = D_NA − θ̇ W_N,θ and t·v = D_TA − θ̇ W_T,θ.
Eigen::Vector3d velocity_before(const ContactFrame& f, const Eigen::Vector2d& n, double D_NA,
                                double D_TA, double omega) {
  const Eigen::Vector2d v =
      (D_NA - omega * f.W_N.z()) * n + (D_TA - omega * f.W_T.z()) * tangent_of(n);
  return {v.x(), v.y(), omega};
}

// One configuration's problem into `pb`, whose M and w are already set.
void set_problem(SmallImpactProblem& pb, const ContactFrame& f, const Eigen::Vector3d& qdot_A) {
  pb.W_N = f.W_N;
  pb.W_T = f.W_T;
  pb.qdot_A = qdot_A;
}

}  // namespace

std::string_view to_string(AtlasParameter p) {
  return detail::enum_to_string(kParameters, p);
}
AtlasParameter atlas_parameter_from_string(std::string_view s) {
  return detail::enum_from_string(kParameters, s, "parameter");
}
std::string_view to_string(AtlasMode m) {
  return detail::enum_to_string(kModes, m);
}
AtlasMode atlas_mode_from_string(std::string_view s) {
  return detail::enum_from_string(kModes, s, "mode");
}

void AtlasOptions::validate() const {
  if (laws.empty()) throw InvalidArgument("laws", "needs at least one law");
  const std::vector<std::string_view> known = law_names();
  for (std::size_t i = 0; i < laws.size(); ++i) {
    if (std::find(known.begin(), known.end(), laws[i]) == known.end()) {
      std::string list;
      for (auto n : known) list += (list.empty() ? "" : ", ") + std::string(n);
      throw InvalidArgument(indexed("laws", i),
                            "unknown law '" + laws[i] + "' (one of: " + list + ")");
    }
    if (std::find(laws.begin(), laws.begin() + static_cast<std::ptrdiff_t>(i), laws[i]) !=
        laws.begin() + static_cast<std::ptrdiff_t>(i))
      throw InvalidArgument(indexed("laws", i), "'" + laws[i] + "' is listed twice");
  }
  if (!reference.empty() && std::find(laws.begin(), laws.end(), reference) == laws.end())
    throw InvalidArgument("reference", "'" + reference + "' is not one of the laws");
  if (values.empty()) throw InvalidArgument("values", "needs at least one value");
  const bool calibrated = needs_fremond_k_N(*this);
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (parameter == AtlasParameter::mu) {
      detail::require_finite_at_least(indexed("values", i), values[i], 0.0);
    } else {
      detail::require_in_unit_interval(indexed("values", i), values[i]);
      if (calibrated && (values[i] == 0.0 || values[i] == 1.0))
        throw InvalidArgument(indexed("values", i),
                              "must lie in (0, 1) to calibrate Frémond's k_N (or give "
                              "fremond_k_N), got " +
                                  detail::format_number(values[i]));
    }
  }
  detail::require_in_unit_interval("e", e);
  if (calibrated && parameter == AtlasParameter::mu && (e == 0.0 || e == 1.0))
    throw InvalidArgument("e",
                          "must lie in (0, 1) to calibrate Frémond's k_N (or give "
                          "fremond_k_N), got " +
                              detail::format_number(e));
  detail::require_finite_at_least("mu", mu, 0.0);
  detail::require_finite_above("fremond_p", fremond_p, 1.0);
  detail::require_finite_at_least("fremond_k_N", fremond_k_N, 0.0);
  if (contact < -1)
    throw InvalidArgument("contact",
                          "must be -1 (the first impact's) or a contact index >= 0, "
                          "got " +
                              std::to_string(contact));
  for (auto [name, n] : {std::pair{"theta_count", theta_count}, {"psi_count", psi_count}})
    if (n < 1 || n > kMaxCells)
      throw InvalidArgument(
          name, "must lie in [1, " + std::to_string(kMaxCells) + "], got " + std::to_string(n));
  detail::require_finite("theta_min", theta_min);
  detail::require_finite("theta_max", theta_max);
  if (!(theta_max > theta_min))
    throw InvalidArgument("theta_max", "must be > theta_min (" + detail::format_number(theta_min) +
                                           "), got " + detail::format_number(theta_max));
  const double pi = std::numbers::pi;
  detail::require_finite("psi_min", psi_min);
  detail::require_finite("psi_max", psi_max);
  if (!(psi_min >= -pi))
    throw InvalidArgument("psi_min",
                          "must be >= -pi (the contact point approaches: D_NA <= 0), "
                          "got " +
                              detail::format_number(psi_min));
  if (!(psi_max <= 0.0))
    throw InvalidArgument("psi_max",
                          "must be <= 0 (the contact point approaches: D_NA <= 0), "
                          "got " +
                              detail::format_number(psi_max));
  if (!(psi_max > psi_min))
    throw InvalidArgument("psi_max", "must be > psi_min (" + detail::format_number(psi_min) +
                                         "), got " + detail::format_number(psi_max));
  if (spins.empty()) throw InvalidArgument("spins", "needs at least one spin ratio");
  for (std::size_t i = 0; i < spins.size(); ++i)
    detail::require_finite(indexed("spins", i), spins[i]);
  detail::require_finite_at_least("speed", speed, 0.0);
  if (threads < 0)
    throw InvalidArgument("threads",
                          "must be 0 (one per core) or at least 1, got " + std::to_string(threads));
  solver.validate();
}

SmallImpactProblem atlas_problem(const Scene& scene, int contact, double theta, double psi,
                                 double spin, double speed) {
  if (contact < 0 || contact >= scene.contact_count())
    throw InvalidArgument("contact", "must lie in [0, " + std::to_string(scene.contact_count()) +
                                         "), got " + std::to_string(contact));
  detail::require_finite_above("speed", speed, 0.0);
  detail::require_finite("theta", theta);
  detail::require_finite("psi", psi);
  detail::require_finite("spin", spin);
  const ContactFrame f = frame_at(scene, contact, theta);
  const double omega = spin * speed / std::sqrt(scene.body.inertia / scene.body.mass);
  const HalfPlane& plane = scene.obstacles[static_cast<std::size_t>(scene.obstacle_of(contact))];
  SmallImpactProblem pb;
  pb.M = scene.body.mass_matrix();
  pb.w_N.setZero(1);
  pb.w_T.setZero(1);
  set_problem(
      pb, f, velocity_before(f, plane.normal, speed * std::sin(psi), speed * std::cos(psi), omega));
  return pb;
}

AtlasResult law_atlas(const Scene& scene, const AtlasOptions& options) {
  options.validate();
  AtlasResult r;
  r.laws = options.laws;
  r.reference = options.reference.empty() ? options.laws.front() : options.reference;
  r.parameter = options.parameter;
  r.values = options.values;
  // The swept one's fixed value is not used: NaN says so.
  r.e = options.parameter == AtlasParameter::e ? kNaN : options.e;
  r.mu = options.parameter == AtlasParameter::mu ? kNaN : options.mu;
  r.fremond_p = options.fremond_p;
  r.spins = options.spins;
  r.theta = centres(options.theta_min, options.theta_max, options.theta_count);
  r.psi = centres(options.psi_min, options.psi_max, options.psi_count);
  r.radius_of_gyration = std::sqrt(scene.body.inertia / scene.body.mass);

  // The defaults that come from the scene's first impact: its contact and that contact's speed.
  r.contact = options.contact;
  r.speed = options.speed;
  // A contact given is checked before anything reads its frame.
  auto require_contact = [&] {
    if (r.contact >= scene.contact_count())
      throw InvalidArgument("contact", "must lie in [0, " + std::to_string(scene.contact_count()) +
                                           "), got " + std::to_string(r.contact));
  };
  require_contact();
  if (r.contact < 0 || r.speed == 0.0) {
    const FirstImpact first = scene_first_impact(scene, r.contact < 0 ? "contact" : "speed");
    if (r.contact < 0) r.contact = first.contacts[0];
    require_contact();
    if (r.speed == 0.0) {
      const ContactFrame f = contact_frame(scene, r.contact, first.state.q);
      r.speed = std::hypot(f.W_N.dot(first.state.qdot), f.W_T.dot(first.state.qdot));
    }
  }

  // Frémond's k_N per value: given, or calibrated to e at the scene's first impact (the paper's).
  const bool sweeps_e = options.parameter == AtlasParameter::e;
  const bool has_fremond = std::find(r.laws.begin(), r.laws.end(), "fremond") != r.laws.end();
  r.fremond_k_N.assign(r.values.size(), kNaN);
  if (has_fremond) {
    for (std::size_t v = 0; v < r.values.size(); ++v) {
      if (options.fremond_k_N > 0.0 || (v > 0 && !sweeps_e)) {
        r.fremond_k_N[v] = options.fremond_k_N > 0.0 ? options.fremond_k_N : r.fremond_k_N[0];
        continue;
      }
      try {
        r.fremond_k_N[v] = first_impact_normal_stiffness(scene, options.fremond_p,
                                                         sweeps_e ? r.values[v] : options.e);
      } catch (const InvalidArgument& e) {
        throw InvalidArgument("fremond_k_N",
                              std::string("cannot be calibrated (") + e.what() + "); give it");
      }
    }
  }

  // The configurations: the frame per θ, the velocity before per (spin, θ, ψ). Problems are built
  // block by block into a reused buffer: all of them at once would be 880 bytes a point.
  const std::size_t nc = r.configurations();
  std::vector<ContactFrame> frames(r.theta.size());
  for (std::size_t i = 0; i < r.theta.size(); ++i)
    frames[i] = frame_at(scene, r.contact, r.theta[i]);
  const Eigen::Vector2d normal =
      scene.obstacles[static_cast<std::size_t>(scene.obstacle_of(r.contact))].normal;
  const Eigen::Matrix3d M = scene.body.mass_matrix();
  r.D_NA.resize(nc);
  r.D_TA.resize(nc);
  r.qdot_A.resize(3 * nc);
  r.kinetic_energy.resize(nc);
  for (std::size_t s = 0; s < r.spins.size(); ++s)
    for (std::size_t i = 0; i < r.theta.size(); ++i)
      for (std::size_t j = 0; j < r.psi.size(); ++j) {
        const std::size_t c = r.config(s, i, j);
        const double omega = r.spins[s] * r.speed / r.radius_of_gyration;
        const Eigen::Vector3d qdot = velocity_before(
            frames[i], normal, r.speed * std::sin(r.psi[j]), r.speed * std::cos(r.psi[j]), omega);
        Eigen::Map<Eigen::Vector3d>(&r.qdot_A[3 * c]) = qdot;
        r.D_NA[c] = frames[i].W_N.dot(qdot);
        r.D_TA[c] = frames[i].W_T.dot(qdot);
        r.kinetic_energy[c] = 0.5 * qdot.dot(M * qdot);
      }
  std::vector<SmallImpactProblem> problems(std::min(kBlock, nc));
  for (SmallImpactProblem& pb : problems) {
    pb.M = M;
    pb.w_N.setZero(1);
    pb.w_T.setZero(1);
  }

  const std::size_t np = r.points();
  for (auto* a : {&r.energy_ratio, &r.distance, &r.P_N, &r.P_T, &r.D_NE, &r.D_TE}) a->resize(np);
  r.qdot_E.resize(3 * np);
  for (auto* a : {&r.admissible, &r.failed, &r.status, &r.mode}) a->resize(np);
  r.solutions.resize(np);

  BatchOptions batch;
  batch.threads = options.threads;
  std::vector<SmallImpactResult> results(std::min(kBlock, nc));
  std::size_t done = 0;
  for (std::size_t l = 0; l < r.laws.size(); ++l)
    for (std::size_t v = 0; v < r.values.size(); ++v) {
      const double e = sweeps_e ? r.values[v] : r.e, mu = sweeps_e ? r.mu : r.values[v];
      const ImpactLaw law = make_law(r.laws[l], e, mu, r.fremond_k_N[v], r.fremond_p);
      for (std::size_t begin = 0; begin < nc; begin += kBlock) {
        const std::size_t count = std::min(kBlock, nc - begin);
        for (std::size_t k = 0; k < count; ++k) {
          const std::size_t c = begin + k, th = (c / r.psi.size()) % r.theta.size();
          set_problem(problems[k], frames[th], Eigen::Map<const Eigen::Vector3d>(&r.qdot_A[3 * c]));
        }
        const std::span<SmallImpactResult> out(results.data(), count);
        solve_batch(std::span<const SmallImpactProblem>(problems.data(), count), law, out,
                    options.solver, batch);
        for (std::size_t k = 0; k < count; ++k) {
          const SmallImpactResult& res = out[k];
          const std::size_t c = begin + k, p = (l * r.values.size() + v) * nc + c;
          const bool ok = res.solver.status == SolverStatus::converged;
          r.status[p] = static_cast<std::uint8_t>(res.solver.status);
          r.admissible[p] = res.admissibility.admissible ? 1 : 0;
          r.failed[p] = static_cast<std::uint8_t>(res.admissibility.failed);
          r.solutions[p] = solutions_of(res);
          r.energy_ratio[p] = ok ? res.energy_change / r.kinetic_energy[c] : kNaN;
          r.P_N[p] = ok ? res.P_N(0) : kNaN;
          r.P_T[p] = ok ? res.P_T(0) : kNaN;
          r.D_NE[p] = ok ? res.D_NE(0) : kNaN;
          r.D_TE[p] = ok ? res.D_TE(0) : kNaN;
          for (int d = 0; d < 3; ++d)
            r.qdot_E[3 * p + static_cast<std::size_t>(d)] = ok ? res.qdot_E(d) : kNaN;
          r.mode[p] = static_cast<std::uint8_t>(
              ok ? mode_of(r.D_TA[c], res.D_TE(0), res.P_N(0), res.P_T(0), law.mu(0), r.speed)
                 : AtlasMode::unknown);
        }
        done += count;
        if (options.progress) options.progress(done, np);
      }
    }

  // Each law's distance from the reference, in the norm of kinetic energy.
  const std::size_t ref = static_cast<std::size_t>(
      std::find(r.laws.begin(), r.laws.end(), r.reference) - r.laws.begin());
  for (std::size_t l = 0; l < r.laws.size(); ++l)
    for (std::size_t v = 0; v < r.values.size(); ++v)
      for (std::size_t c = 0; c < nc; ++c) {
        const std::size_t p = (l * r.values.size() + v) * nc + c;
        const std::size_t q = (ref * r.values.size() + v) * nc + c;
        const Eigen::Vector3d d(r.qdot_E[3 * p] - r.qdot_E[3 * q],
                                r.qdot_E[3 * p + 1] - r.qdot_E[3 * q + 1],
                                r.qdot_E[3 * p + 2] - r.qdot_E[3 * q + 2]);
        r.distance[p] = std::sqrt(d.dot(M * d) / (2.0 * r.kinetic_energy[c]));
      }
  return r;
}

}  // namespace fremond
