// The event-driven run of a scene of several bodies (simulate_bodies.hpp).
#include "fremond/simulation/simulate_bodies.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fremond/core/error.hpp"
#include "fremond/simulation/event_detection.hpp"
#include "fremond/simulation/free_flight.hpp"
#include "fremond/solvers/solve_impact.hpp"
#include "simulation/detail/accumulation.hpp"
#include "simulation/detail/reached_impact.hpp"

namespace fremond {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The squared distance of two disk centres minus (ρ_a + ρ_b)², along flights where their
// separation is d(s) = d₀ + w s + ½ a s²: h(s) = c₀ + c₁s + c₂s² + c₃s³ + c₄s⁴, h' = 2|d| D_N.
struct PairGap {
  double c[5] = {0, 0, 0, 0, 0};
  double value(double s) const { return (((c[4] * s + c[3]) * s + c[2]) * s + c[1]) * s + c[0]; }
  double slope(double s) const {
    return ((4.0 * c[4] * s + 3.0 * c[3]) * s + 2.0 * c[2]) * s + c[1];
  }
  static PairGap make(const Eigen::Vector2d& d0, const Eigen::Vector2d& w, const Eigen::Vector2d& a,
                      double reach) {
    PairGap p;
    p.c[0] = d0.squaredNorm() - reach * reach;
    p.c[1] = 2.0 * d0.dot(w);
    p.c[2] = w.squaredNorm() + d0.dot(a);
    p.c[3] = w.dot(a);
    p.c[4] = 0.25 * a.squaredNorm();
    return p;
  }
  // Every real root, polished by Newton's method to the last bits.
  std::vector<double> real_roots() const {
    std::vector<double> out;
    if (c[4] != 0.0) {
      Eigen::Matrix4d companion = Eigen::Matrix4d::Zero();
      companion.diagonal(-1).setOnes();
      for (int i = 0; i < 4; ++i) companion(i, 3) = -c[i] / c[4];
      const Eigen::Vector4cd ev = companion.eigenvalues();
      for (int i = 0; i < 4; ++i)
        if (std::fabs(ev(i).imag()) <= 1e-6 * std::max(1.0, std::fabs(ev(i).real())))
          out.push_back(ev(i).real());
    } else if (c[2] != 0.0) {  // no relative acceleration: c₃ = 0 too
      const double disc = c[1] * c[1] - 4.0 * c[2] * c[0];
      if (disc >= 0.0) {
        const double q = -0.5 * (c[1] + std::copysign(std::sqrt(disc), c[1]));
        out.push_back(q / c[2]);
        if (q != 0.0) out.push_back(c[0] / q);
      }
    }
    for (double& s : out)
      for (int it = 0; it < 4; ++it) {
        const double d = slope(s);
        if (d == 0.0) break;
        s -= value(s) / d;
      }
    std::sort(out.begin(), out.end());
    return out;
  }
};

class BodiesRun {
 public:
  BodiesRun(const MultiBodyScene& scene, const SimulationOptions& options,
            MultiBodyObserver* observer)
      : sc_(scene), opt_(options), obs_(observer) {
    sc_.validate();
    opt_.validate();
    if (opt_.integrator != Integrator::event_driven)
      throw InvalidArgument("integrator.method",
                            "a scene of several bodies is simulated event-driven only");
    contacts_ = sc_.contacts();
    for (const BodyContact& c : contacts_) {
      if (!c.is_pair()) continue;
      for (const auto& [b, p] :
           {std::pair{c.body, c.point}, std::pair{c.other_body, c.other_point}})
        if (sc_.bodies[b].points[p].r != Eigen::Vector2d::Zero())
          throw InvalidArgument(
              "bodies[" + std::to_string(b) + "].points[" + std::to_string(p) + "].r",
              "a disk that can touch another body's disk must be at its "
              "body's centre, r = [0, 0], to be simulated (its events are "
              "found from the distance of the centres)");
    }
    validate_start(sc_, opt_);
    st_ = sc_.initial;
    held_.assign(sc_.bodies.size(), false);
  }

  MultiBodyResult go() {
    res_.energy_initial = energy(sc_, st_);
    sample(0.0, st_);
    next_sample_index_ = 1;
    while (!stop_ && t_ < opt_.t_end) step();
    if (!stop_) finish(SimulationStatus::completed, "reached the end time");
    if (last_sample_t_ != t_) sample(t_, st_);
    res_.t = t_;
    res_.state = st_;
    res_.energy_final = energy(sc_, st_);
    return res_;
  }

 private:
  void finish(SimulationStatus s, std::string_view why) {
    res_.status = s;
    res_.message = why;
    stop_ = true;
  }
  void sample(double t, const MultiBodyState& s) {
    last_sample_t_ = t;
    if (obs_) obs_->on_sample({t, s, energy(sc_, s)});
  }
  void audit(double before, double after) {
    res_.max_energy_rise = std::max(res_.max_energy_rise, after - before);
  }
  int nb() const { return static_cast<int>(sc_.bodies.size()); }
  double contact_velocity(const BodyContact& c, const PairFrame& f,
                          const Eigen::VectorXd& v) const {
    double d = f.W_N_b.dot(v.segment<3>(3 * c.body));
    if (c.is_pair()) d += f.W_N_a.dot(v.segment<3>(3 * c.other_body));
    return d;
  }
  // The flight of body i from the present state; a held body stays where it is.
  FreeFlight flight_of(int i) const {
    PlanarState s;
    s.q = st_.q.segment<3>(3 * i);
    s.qdot = held_[i] ? Eigen::Vector3d::Zero() : Eigen::Vector3d(st_.qdot.segment<3>(3 * i));
    return {t_, s, held_[i] ? 0.0 : sc_.gravity};
  }
  Eigen::Vector2d acceleration_of(int i) const { return {0.0, held_[i] ? 0.0 : -sc_.gravity}; }

  void step() {
    if (obs_ && obs_->stop_requested()) {
      finish(SimulationStatus::interrupted, "the observer asked the run to stop");
      return;
    }
    const int nc = static_cast<int>(contacts_.size());
    std::vector<PairFrame> f(nc);
    std::vector<bool> touching(nc);
    std::vector<int> idx;
    bool approaching = false;
    for (int k = 0; k < nc; ++k) {
      f[k] = contact_frame(sc_, contacts_[k], st_.q);
      touching[k] = f[k].gap <= opt_.gap_tolerance;
      if (!touching[k]) continue;
      idx.push_back(k);
      approaching =
          approaching || contact_velocity(contacts_[k], f[k], st_.qdot) < -opt_.velocity_tolerance;
    }
    if (approaching) {  // closed and closing now
      event_impact(idx);
      return;
    }
    if (!hold_bodies_at_rest(idx)) return;
    if (lasting_contact_of_a_moving_body(f, touching)) return;
    fly(touching);
  }

  // Holds the bodies at rest that one plastic contact step against gravity leaves at rest.
  bool hold_bodies_at_rest(const std::vector<int>& touching) {
    std::fill(held_.begin(), held_.end(), false);
    if (touching.empty() || sc_.gravity == 0.0) return true;
    MultiBodyState pushed = st_;
    for (int i = 0; i < nb(); ++i) pushed.qdot(3 * i + 1) -= opt_.step * sc_.gravity;
    const ImpactProblem pb = impact_problem(sc_, pushed, touching);
    std::vector<double> mu;
    for (int k : touching) mu.push_back(sc_.law.mu(k));
    const ImpactLaw plastic =
        sc_.law.uses_coulomb() ? ImpactLaw::newton_coulomb(0.0, mu) : ImpactLaw::newton(0.0);
    ImpactResult r;
    try {
      r = solve_impact(pb, plastic, opt_.solver);
    } catch (const InvalidArgument&) {
      r.solver.status = SolverStatus::failed;
    }
    if (!r.ok()) {
      finish(SimulationStatus::contact_failed,
             "the contact step that tells the bodies at rest from the others has no answer");
      return false;
    }
    const double tol = opt_.velocity_tolerance;
    for (int i = 0; i < nb(); ++i) {
      const bool at_rest = st_.qdot.segment<3>(3 * i).lpNorm<Eigen::Infinity>() <= tol;
      const bool stays = r.qdot_E.segment<3>(3 * i).lpNorm<Eigen::Infinity>() <= tol;
      if (at_rest && stays) {
        held_[i] = true;
        st_.qdot.segment<3>(3 * i).setZero();
      }
    }
    return true;
  }

  // A touching contact at rest that the flights would push in, on a body not held: stops the run.
  bool lasting_contact_of_a_moving_body(const std::vector<PairFrame>& f,
                                        const std::vector<bool>& touching) {
    for (int k = 0; k < static_cast<int>(contacts_.size()); ++k) {
      const BodyContact& c = contacts_[k];
      if (!touching[k] || (held_[c.body] && (!c.is_pair() || held_[c.other_body]))) continue;
      if (std::fabs(contact_velocity(c, f[k], st_.qdot)) > opt_.velocity_tolerance) continue;
      double gdd;
      if (!c.is_pair()) {
        const GapFunction gap = GapFunction::make(sc_.bodies[c.body].points[c.point],
                                                  sc_.obstacles[c.obstacle], flight_of(c.body));
        double g, gd;
        gap.eval(0.0, g, gd, gdd);
      } else {
        const Eigen::Vector2d d = st_.q.segment<2>(3 * c.body) - st_.q.segment<2>(3 * c.other_body);
        const Eigen::Vector2d w =
            flight_of(c.body).start.qdot.head<2>() - flight_of(c.other_body).start.qdot.head<2>();
        const Eigen::Vector2d n = d.normalized();
        gdd = n.dot(acceleration_of(c.body) - acceleration_of(c.other_body)) +
              (w.squaredNorm() - n.dot(w) * n.dot(w)) / d.norm();
      }
      if (gdd < 0.0) {
        finish(SimulationStatus::contact_failed,
               "a moving body in lasting contact (rolling, sliding, or resting on a moving "
               "body): a scene of several bodies is simulated event-driven only");
        return true;
      }
    }
    return false;
  }

  // The first event of a pair of disks within s_max (kInf: none).
  double pair_event(const BodyContact& c, bool touching, double s_max) const {
    const Eigen::Vector2d d0 = st_.q.segment<2>(3 * c.body) - st_.q.segment<2>(3 * c.other_body);
    const Eigen::Vector2d w =
        flight_of(c.body).start.qdot.head<2>() - flight_of(c.other_body).start.qdot.head<2>();
    const Eigen::Vector2d a = acceleration_of(c.body) - acceleration_of(c.other_body);
    const double reach = sc_.bodies[c.body].points[c.point].radius +
                         sc_.bodies[c.other_body].points[c.other_point].radius;
    const PairGap h = PairGap::make(d0, w, a, reach);
    for (const double s : h.real_roots()) {
      if (s < 0.0 || s > s_max) continue;
      // Closing through the root: h' = 2|d| D_N < 0. Just after an impact (touching) a root at
      // the start is the contact leaving, unless it still approaches beyond the tolerance.
      const double D_N = h.slope(s) / (2.0 * reach);
      if (D_N < (touching ? -opt_.velocity_tolerance : 0.0)) return s;
    }
    return kInf;
  }

  void fly(const std::vector<bool>& touching) {
    const double tau = opt_.simultaneity_tolerance, horizon = opt_.t_end - t_;
    const int nc = static_cast<int>(contacts_.size());
    std::vector<double> when(nc, kInf);
    double best = kInf;
    for (int k = 0; k < nc; ++k) {
      const BodyContact& c = contacts_[k];
      if (held_[c.body] && (!c.is_pair() || held_[c.other_body])) continue;
      const double s_max = std::min(horizon, best + tau);
      if (c.is_pair()) {
        when[k] = pair_event(c, touching[k], s_max);
      } else {
        const GapFunction gap = GapFunction::make(sc_.bodies[c.body].points[c.point],
                                                  sc_.obstacles[c.obstacle], flight_of(c.body));
        const EventSearchResult r =
            find_first_event(gap, s_max, touching[k], opt_.max_gap_evaluations);
        if (r.exhausted) {
          finish(SimulationStatus::event_search_failed,
                 "the event search of a free flight spent integrator.max_gap_evaluations "
                 "without deciding where the next contact event is");
          return;
        }
        when[k] = r.s;
      }
      best = std::min(best, when[k]);
    }
    const double e_before = energy(sc_, st_);
    const double t0 = t_;
    std::vector<FreeFlight> flights;
    for (int i = 0; i < nb(); ++i) flights.push_back(flight_of(i));
    const auto state_at = [&](double s) {
      MultiBodyState out = st_;
      for (int i = 0; i < nb(); ++i) {
        const PlanarState p = flights[i].at_elapsed(s);
        out.q.segment<3>(3 * i) = p.q;
        out.qdot.segment<3>(3 * i) = p.qdot;
      }
      return out;
    };
    const double s_end = best == kInf ? horizon : best;
    for (;;) {  // the grid's samples within the flight (its end is sampled by the caller)
      const double ts = static_cast<double>(next_sample_index_) * opt_.sample_interval;
      if (!(ts < t0 + s_end)) break;
      sample(ts, state_at(ts - t0));
      ++next_sample_index_;
    }
    st_ = state_at(s_end);
    t_ = best == kInf ? opt_.t_end : t0 + best;
    audit(e_before, energy(sc_, st_));
    if (best == kInf) return;
    std::vector<int> idx;
    for (int k = 0; k < nc; ++k)
      if (when[k] <= best + tau ||
          contact_frame(sc_, contacts_[k], st_.q).gap <= opt_.gap_tolerance)
        idx.push_back(k);
    event_impact(idx);
  }

  void event_impact(const std::vector<int>& idx) {
    sample(t_, st_);
    if (!impact(idx)) return;
    sample(t_, st_);
    if (!accumulation_.add(t_, opt_)) return;
    accumulation_.reset();
    close_accumulation();
  }

  // Closes an accumulation as simulate.hpp does: the touching contacts lose the small normal
  // velocity of their last bounce, by the M-orthogonal projection of q̇ onto W_Nᵀq̇ = 0 (the
  // minimum-norm percussion where contacts are dependent), which can only lower the kinetic
  // energy; the bodies at rest are then held.
  void close_accumulation() {
    std::vector<int> idx;
    for (int k = 0; k < static_cast<int>(contacts_.size()); ++k)
      if (contact_frame(sc_, contacts_[k], st_.q).gap <= opt_.gap_tolerance) idx.push_back(k);
    if (idx.empty()) return;
    const ImpactProblem pb = impact_problem(sc_, st_, idx);
    const Eigen::VectorXd minv = pb.M.diagonal().cwiseInverse();
    const Eigen::MatrixXd G = pb.W_N.transpose() * minv.asDiagonal() * pb.W_N;
    const Eigen::VectorXd lambda =
        G.completeOrthogonalDecomposition().solve(pb.W_N.transpose() * st_.qdot);
    MultiBodyState after = st_;
    after.qdot = st_.qdot - minv.cwiseProduct(pb.W_N * lambda);
    const double e_a = energy(sc_, st_), e_e = energy(sc_, after);
    if (obs_) {
      MultiBodyImpact rec = record_of(ImpactKind::accumulation, idx, after, e_a, e_e);
      rec.P_N = -lambda;
      rec.P_T = Eigen::VectorXd::Zero(lambda.size());
      rec.D_NA = pb.W_N.transpose() * st_.qdot;
      rec.D_NE = pb.W_N.transpose() * after.qdot;
      rec.solver.method = SolverMethod::closed_form;
      rec.solver.status = SolverStatus::converged;
      rec.solver.message = "accumulation closed";
      obs_->on_impact(rec);
    }
    ++log_index_;
    ++res_.accumulations;
    audit(e_a, e_e);
    st_ = after;
    sample(t_, st_);
  }

  // The log's record of an impact of contacts idx at the current state, to `after`, with the
  // energies before and after: what an event and the closing of an accumulation share.
  MultiBodyImpact record_of(ImpactKind kind, const std::vector<int>& idx,
                            const MultiBodyState& after, double e_a, double e_e) const {
    MultiBodyImpact rec;
    rec.index = log_index_;
    rec.t = t_;
    rec.kind = kind;
    rec.contacts = idx;
    rec.q = st_.q;
    rec.qdot_A = st_.qdot;
    rec.qdot_E = after.qdot;
    rec.energy_A = e_a;
    rec.energy_E = e_e;
    return rec;
  }

  // Solves the impact of contacts idx with the scene's law; false when the run stops.
  bool impact(const std::vector<int>& idx) {
    const ImpactProblem pb = impact_problem(sc_, st_, idx);
    const ImpactLaw law = law_of(sc_, idx);
    const std::optional<ImpactResult> solved = detail::solve_reached_impact(pb, law, opt_.solver);
    if (!solved) {
      finish(SimulationStatus::impact_failed, detail::kImpactOverflow);
      return false;
    }
    const ImpactResult& r = *solved;
    MultiBodyState after = st_;
    if (r.ok()) after.qdot = r.qdot_E;
    const double e_a = energy(sc_, st_), e_e = energy(sc_, after);
    if (obs_) {
      MultiBodyImpact rec = record_of(ImpactKind::event, idx, after, e_a, e_e);
      rec.P_N = r.P_N;
      rec.P_T = r.P_T;
      if (rec.P_T.size() == 0) rec.P_T.setZero(r.P_N.size());
      rec.D_NA = r.D_NA;
      rec.D_NE = r.D_NE;
      rec.admissible = r.admissibility.admissible;
      rec.solver = r.solver;
      obs_->on_impact(rec);
    }
    ++log_index_;
    if (!r.ok()) {
      finish(SimulationStatus::impact_failed, r.solver.message);
      return false;
    }
    ++res_.impacts;
    if (!r.admissibility.admissible)
      ++res_.inadmissible_impacts;
    else
      audit(e_a, e_e);
    st_ = after;
    if (res_.impacts >= opt_.max_impacts) {
      finish(SimulationStatus::max_impacts, "stopped after the largest number of impacts allowed");
      return false;
    }
    return true;
  }

  MultiBodyScene sc_;
  SimulationOptions opt_;
  MultiBodyObserver* obs_;
  std::vector<BodyContact> contacts_;
  std::vector<bool> held_;
  detail::AccumulationDetector accumulation_;
  MultiBodyResult res_;
  MultiBodyState st_;
  double t_ = 0.0, last_sample_t_ = -1.0;
  long next_sample_index_ = 0, log_index_ = 0;
  bool stop_ = false;
};

}  // namespace

void validate_start(const MultiBodyScene& scene, const SimulationOptions& options) {
  const std::vector<BodyContact> all = scene.contacts();
  for (int k = 0; k < static_cast<int>(all.size()); ++k) {
    const double gap = contact_frame(scene, all[k], scene.initial.q).gap;
    if (gap < -options.gap_tolerance)
      throw InvalidArgument("initial", "contact " + std::to_string(k) + " starts " +
                                           std::to_string(-gap) +
                                           " m in penetration (gap below "
                                           "-integrator.gap_tolerance); start the bodies apart "
                                           "or touching");
  }
}

MultiBodyResult simulate(const MultiBodyScene& scene, const SimulationOptions& options,
                         MultiBodyObserver* observer) {
  BodiesRun run(scene, options, observer);
  return run.go();
}

}  // namespace fremond
