// The run of a scene: event-driven flights and impacts, accumulations, Moreau–Jean (simulate.hpp).
#include "fremond/simulation/simulate.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>

#include "fremond/core/error.hpp"
#include "fremond/laws/impact_problem.hpp"
#include "fremond/scenes/kinematics.hpp"
#include "fremond/simulation/event_detection.hpp"
#include "fremond/simulation/free_flight.hpp"
#include "fremond/simulation/persistent_contact.hpp"
#include "fremond/solvers/solve_impact.hpp"
#include "simulation/detail/ulp.hpp"

namespace fremond {

namespace {

constexpr int kMaxC = kMaxSceneContacts;
using Mask = std::uint32_t;
constexpr double kInf = std::numeric_limits<double>::infinity();

bool uses_coulomb(const ImpactLaw& law) {
  return law.type == LawType::newton_coulomb || law.type == LawType::poisson_coulomb ||
         (law.type == LawType::fremond && law.tangential == TangentialLaw::coulomb);
}

bool is_uniform(const ImpactLaw& law) {
  return law.e.values.size() == 1 && law.mu.values.size() == 1 &&
         law.normal.potentials.size() <= 1 && law.tangential_potential.potentials.size() <= 1;
}

// The law of the contacts idx[0..n) of a law with per-contact parameters.
ImpactLaw restrict_law(const ImpactLaw& law, const int* idx, int n) {
  ImpactLaw r = law;
  const auto pick = [&](const PerContact& p, PerContact& out) {
    if (p.values.size() <= 1) return;
    out.values.clear();
    for (int i = 0; i < n; ++i) out.values.push_back(p[idx[i]]);
  };
  const auto pick_pot = [&](const PerContactPotential& p, PerContactPotential& out) {
    if (p.potentials.size() <= 1) return;
    out.potentials.clear();
    for (int i = 0; i < n; ++i) out.potentials.emplace_back(p[idx[i]].clone());
  };
  pick(law.e, r.e);
  pick(law.mu, r.mu);
  pick_pot(law.normal, r.normal);
  pick_pot(law.tangential_potential, r.tangential_potential);
  return r;
}

// The frames of a step's active contacts. ContactFrame zero-initialises its members; an array of
// them for every possible contact would be cleared at every step for nothing.
struct StepFrame {
  double gap;
  Eigen::Vector3d W_N, W_T;
  StepFrame& operator=(const ContactFrame& f) {
    gap = f.gap;
    W_N = f.W_N;
    W_T = f.W_T;
    return *this;
  }
};
using Frames = std::array<StepFrame, kMaxC>;

using detail::ulp;

class Run {
 public:
  Run(const Scene& scene, const SimulationOptions& options, SimulationObserver* observer)
      : sc_(scene), opt_(options), obs_(observer) {
    sc_.validate();
    opt_.validate();
    nc_ = sc_.contact_count();
    minv_ = {1.0 / sc_.body.mass, 1.0 / sc_.body.mass, 1.0 / sc_.body.inertia};
    pp_.minv = minv_;
    uniform_law_ = is_uniform(sc_.law);
    const bool coulomb = uses_coulomb(sc_.law);
    for (int k = 0; k < nc_; ++k) {
      point_[k] = &sc_.body.points[sc_.point_of(k)];
      plane_[k] = &sc_.obstacles[sc_.obstacle_of(k)];
      const ContactPoint& p = *point_[k];
      mu_[k] = coulomb ? sc_.law.mu[k] : 0.0;
      reach_[k] = p.r.norm() + p.radius;
      mode_[k] = ContactMode::stick;
    }
    t_ = 0.0;
    st_ = sc_.initial;
    validate_start(sc_, opt_);
  }

  SimulationResult go() {
    res_.energy_initial = e_prev_ = energy(sc_, st_);
    emit_sample(0.0, st_);
    next_sample_index_ = 1;
    phase_ = opt_.integrator == Integrator::moreau_jean ? Phase::moreau_jean : Phase::event_driven;
    while (!stop_ && t_ < opt_.t_end) {
      if (phase_ == Phase::event_driven)
        event_driven_phase();
      else
        moreau_jean_phase();
    }
    if (!stop_) {
      res_.status = SimulationStatus::completed;
      res_.message = "reached the end time";
    }
    if (last_sample_t_ != t_) emit_sample(t_, st_);
    if (obs_) obs_->on_progress(t_, opt_.t_end);
    res_.t = t_;
    res_.state = st_;
    res_.phase = phase_;
    res_.energy_final = energy(sc_, st_);
    return res_;
  }

 private:
  // ---- bookkeeping -------------------------------------------------------------------------

  // Energy audit: every change of energy goes through here. A rise is recorded unless the law's
  // certificate allows it (an inadmissible impact, counted separately).
  void audit(double e_new, bool allowed) {
    if (!allowed) res_.max_energy_rise = std::max(res_.max_energy_rise, e_new - e_prev_);
    e_prev_ = e_new;
  }

  void emit_sample(double t, const PlanarState& s) {
    last_sample_t_ = t;
    if (!obs_) return;
    TrajectorySample smp;
    smp.t = t;
    smp.state = s;
    smp.energy = energy(sc_, s);
    smp.phase = phase_;
    obs_->on_sample(smp);
  }

  double grid(long i) const { return static_cast<double>(i) * opt_.sample_interval; }

  // Grid samples in (last, t_lim) — or (last, t_lim] when `inclusive` — from `state_at(t)`.
  template <class StateAt>
  void samples_until(double t_lim, bool inclusive, const StateAt& state_at) {
    if (!obs_) return;  // the grid only places samples, and nobody receives them
    while (true) {
      const double ts = grid(next_sample_index_);
      if (ts > opt_.t_end || ts > t_lim || (!inclusive && ts == t_lim)) break;
      emit_sample(ts, state_at(ts));
      ++next_sample_index_;
    }
  }

  // Progress for the observer, and its chance to stop the run; false when it asked to.
  bool progress() {
    if (!obs_) return true;
    if (t_ >= next_progress_) {
      obs_->on_progress(t_, opt_.t_end);
      while (next_progress_ <= t_) next_progress_ += 0.01 * opt_.t_end;
    }
    if (!obs_->stop_requested()) return true;
    finish(SimulationStatus::interrupted, "the observer asked the run to stop");
    return false;
  }

  void switch_phase(Phase to, std::string_view why) {
    if (obs_) obs_->on_phase(t_, phase_, to, why);
    phase_ = to;
    ++res_.phase_switches;
    n_times_ = 0;
  }

  void finish(SimulationStatus status, std::string_view message) {
    res_.status = status;
    res_.message = message;
    stop_ = true;
  }

  const ImpactLaw& law_for(const int* idx, int n) {
    if (uniform_law_) return sc_.law;
    Mask mask = 0;
    for (int i = 0; i < n; ++i) mask |= Mask{1} << idx[i];
    auto it = laws_.find(mask);
    if (it == laws_.end()) it = laws_.emplace(mask, restrict_law(sc_.law, idx, n)).first;
    return it->second;
  }

  ContactFrame frame(int k, const Eigen::Vector3d& q, double c, double s) const {
    return contact_frame(*point_[k], *plane_[k], q.head<2>(), c, s);
  }

  // ---- impacts -----------------------------------------------------------------------------

  template <class Problem>
  void fill(Problem& pb, const PlanarState& s, const int* idx, int n) const {
    const double c = std::cos(s.q.z()), sn = std::sin(s.q.z());
    pb.M = sc_.body.mass_matrix();
    pb.W_N.resize(3, n);
    pb.W_T.resize(3, n);
    pb.w_N.setZero(n);
    pb.w_T.setZero(n);
    pb.qdot_A = s.qdot;
    for (int i = 0; i < n; ++i) {
      const ContactFrame f = frame(idx[i], s.q, c, sn);
      pb.W_N.col(i) = f.W_N;
      pb.W_T.col(i) = f.W_T;
    }
  }

  // Solves the impact of contacts idx[0..n) at time t with the scene's law; s.qdot becomes q̇_E.
  // Returns false when the run must stop.
  bool impact(double t, PlanarState& s, const int* idx, int n, ImpactKind kind) {
    const ImpactLaw& law = law_for(idx, n);
    if (n <= kSmallContacts) {
      SmallImpactProblem pb;
      fill(pb, s, idx, n);
      return solve_and_record(t, s, idx, n, kind, pb, law);
    }
    ImpactProblem pb;
    fill(pb, s, idx, n);
    return solve_and_record(t, s, idx, n, kind, pb, law);
  }

  template <class Problem>
  bool solve_and_record(double t, PlanarState& s, const int* idx, int n, ImpactKind kind,
                        const Problem& pb, const ImpactLaw& law) {
    decltype(solve_impact(pb, law, opt_.solver)) r;
    // Scene::validate refuses what the first impact would refuse, but a state reached later can
    // still overflow what an impact computes (a fall under g = 1.5e308 m/s² reaches a speed whose
    // kinetic energy is not a double). That is the run's outcome, not bad input: the run stops
    // with a status and keeps what it has written.
    try {
      r = solve_impact(pb, law, opt_.solver);
    } catch (const InvalidArgument&) {
      finish(SimulationStatus::impact_failed,
             "an impact problem the run reached cannot be posed in double precision (a "
             "velocity or energy overflows)");
      return false;
    }
    return record(t, s, idx, n, kind, r);
  }

  template <class Result>
  bool record(double t, PlanarState& s, const int* idx, int n, ImpactKind kind, const Result& r) {
    const double e_a = energy(sc_, s);
    PlanarState after = s;
    if (r.ok()) after.qdot = r.qdot_E.template head<3>();
    const double e_e = energy(sc_, after);
    const bool admissible = r.admissibility.admissible;
    if (obs_) {
      ImpactRecord rec;
      rec.index = log_index_;
      rec.t = t;
      rec.kind = kind;
      rec.contact_count = n;
      for (int i = 0; i < n; ++i) rec.contacts[i] = idx[i];
      rec.q = s.q;
      rec.qdot_A = s.qdot;
      rec.qdot_E = after.qdot;
      rec.P_N = r.P_N;
      rec.P_T = r.P_T;
      rec.D_NA = r.D_NA;
      rec.D_NE = r.D_NE;
      rec.D_TA = r.D_TA;
      rec.D_TE = r.D_TE;
      rec.energy_A = e_a;
      rec.energy_E = e_e;
      rec.admissible = admissible;
      rec.failed = r.admissibility.failed;
      rec.failed_contact =
          r.admissibility.failed_contact >= 0 ? idx[r.admissibility.failed_contact] : -1;
      rec.violation = r.admissibility.violation;
      rec.unique = r.unique;
      rec.solver = r.solver;
      obs_->on_impact(rec);
    }
    ++log_index_;
    if (!r.ok()) {
      finish(SimulationStatus::impact_failed, r.solver.message);
      return false;
    }
    ++res_.impacts;
    if (kind == ImpactKind::event) ++res_.event_impacts;
    if (!admissible) {
      if (res_.inadmissible_impacts++ == 0) res_.first_inadmissible_time = t;
    }
    audit(e_e, !admissible);
    s = after;
    if (res_.impacts >= opt_.max_impacts) {
      finish(SimulationStatus::max_impacts, "stopped after the largest number of impacts allowed");
      return false;
    }
    return true;
  }

  // ---- event-driven phase ------------------------------------------------------------------

  void event_driven_phase() {
    const double tau = opt_.simultaneity_tolerance;
    while (!stop_ && t_ < opt_.t_end) {
      if (!progress()) break;
      const FreeFlight flight{t_, st_, sc_.gravity};
      std::array<GapFunction, kMaxC> gap;
      std::array<bool, kMaxC> touching{};
      bool approaching = false, persistent = false;
      for (int k = 0; k < nc_; ++k) {
        gap[k] = GapFunction::make(*point_[k], *plane_[k], flight);
        double g, gd, gdd;
        gap[k].eval(0.0, g, gd, gdd);
        touching[k] = g <= opt_.gap_tolerance;
        if (!touching[k]) continue;
        if (gd < -opt_.velocity_tolerance)
          approaching = true;
        else if (gd <= opt_.velocity_tolerance && gdd < 0.0)
          persistent = true;  // at rest on the obstacle, and flight would push it in
      }
      if (approaching) {  // closed and closing now: an impact at this very instant
        std::array<int, kMaxC> idx;
        int n = 0;
        for (int k = 0; k < nc_; ++k)
          if (touching[k]) idx[n++] = k;
        emit_sample(t_, st_);
        if (!impact(t_, st_, idx.data(), n, ImpactKind::event)) return;
        emit_sample(t_, st_);
        if (after_event_impact()) return;
        continue;
      }
      if (persistent) {
        switch_phase(Phase::moreau_jean, "persistent contact");
        return;
      }

      // The first event of any contact; later contacts only need to look up to the best so far.
      const double horizon = opt_.t_end - t_;
      std::array<double, kMaxC> when;
      double best = kInf;
      for (int k = 0; k < nc_; ++k) {
        const EventSearchResult r = find_first_event(gap[k], std::min(horizon, best + tau),
                                                     touching[k], opt_.max_gap_evaluations);
        res_.gap_evaluations += r.evaluations;
        if (r.exhausted) {  // the state stays at the start of the flight: nothing is guessed
          finish(SimulationStatus::event_search_failed,
                 "the event search of a free flight spent integrator.max_gap_evaluations without "
                 "deciding where the next contact event is: the body turns too fast for its "
                 "events to be resolved");
          return;
        }
        when[k] = r.s;
        best = std::min(best, r.s);
      }
      const auto state_at = [&](double t) { return flight.at_elapsed(t - flight.t0); };
      if (best == kInf) {  // flies to the end
        samples_until(opt_.t_end, true, state_at);
        st_ = flight.at_elapsed(horizon);
        t_ = opt_.t_end;
        audit(energy(sc_, st_), false);
        return;
      }
      const double t_star = t_ + best;
      samples_until(t_star, false, state_at);
      st_ = flight.at_elapsed(best);
      t_ = t_star;
      audit(energy(sc_, st_), false);  // a flight conserves energy: rounding only

      std::array<int, kMaxC> idx;
      int n = 0;
      const double c = std::cos(st_.q.z()), s = std::sin(st_.q.z());
      for (int k = 0; k < nc_; ++k)
        if (when[k] <= best + tau || frame(k, st_.q, c, s).gap <= opt_.gap_tolerance) idx[n++] = k;
      emit_sample(t_, st_);
      if (!impact(t_, st_, idx.data(), n, ImpactKind::event)) return;
      emit_sample(t_, st_);
      if (after_event_impact()) return;
    }
  }

  // Accumulation test after an event impact; on an accumulation, closes it and switches to
  // Moreau–Jean (returns true).
  bool after_event_impact() {
    const int N = opt_.accumulation_impacts;
    if (n_times_ == static_cast<int>(times_.size())) {
      std::copy(times_.begin() + 1, times_.end(), times_.begin());
      --n_times_;
    }
    times_[n_times_++] = t_;
    if (n_times_ < N + 1) return false;
    const double* tt = times_.data() + n_times_ - (N + 1);
    bool geometric = true, stuck = true;
    for (int j = 0; j < N; ++j) {
      const double d = tt[j + 1] - tt[j];
      geometric = geometric && d <= opt_.accumulation_interval && (j == 0 || d < tt[j] - tt[j - 1]);
      stuck = stuck && d <= 16.0 * ulp(t_);
    }
    if (!geometric && !stuck) return false;
    double tail = 0.0;
    if (geometric) {
      const double last = tt[N] - tt[N - 1], prev = tt[N - 1] - tt[N - 2];
      const double r = last / prev;  // < 1: the intervals decrease strictly
      tail = std::min(last * r / (1.0 - r), opt_.t_end - t_);
    }
    close_accumulation(tail);
    if (!stop_ && phase_ == Phase::event_driven)
      switch_phase(Phase::moreau_jean, "accumulation of impacts");
    return true;
  }

  // Closes an accumulation (simulate.hpp): the touching contacts lose the small normal velocity of
  // their bounce, which the tail of impacts would damp to zero, by an M-orthogonal projection of
  // q̇ onto W_Nᵀq̇ = 0 — it can only lower the kinetic energy. Moreau–Jean then integrates the
  // tail from here, with the contacts closed: the other contacts, the rotation and friction go on
  // as in any persistent contact. `tail` is the extrapolated remaining time, t∞ − t, for the log.
  void close_accumulation(double tail) {
    using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxC, kMaxC>;
    const double c = std::cos(st_.q.z()), s = std::sin(st_.q.z());
    std::array<int, kMaxC> idx;
    std::array<ContactFrame, kMaxC> f;
    int n = 0;
    for (int k = 0; k < nc_; ++k) {
      f[n] = frame(k, st_.q, c, s);
      if (f[n].gap <= opt_.gap_tolerance) idx[n++] = k;
    }
    if (n == 0) return;
    Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxC> Wc(3, n);
    for (int i = 0; i < n; ++i) Wc.col(i) = f[i].W_N;
    const Small G = Wc.transpose() * minv_.asDiagonal() * Wc;
    // Minimum-norm multipliers: G is singular when the touching contacts are dependent.
    const Eigen::JacobiSVD<Small> svd(G, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const auto lambda = svd.solve((Wc.transpose() * st_.qdot).eval()).eval();
    PlanarState after = st_;
    after.qdot = st_.qdot - minv_.cwiseProduct(Wc * lambda);
    const double e_a = energy(sc_, st_), e_e = energy(sc_, after);
    if (obs_) {
      ImpactRecord rec;
      rec.index = log_index_;
      rec.t = t_;
      rec.kind = ImpactKind::accumulation;
      rec.contact_count = n;
      rec.q = st_.q;
      rec.qdot_A = st_.qdot;
      rec.qdot_E = after.qdot;
      for (auto* v : {&rec.P_N, &rec.P_T, &rec.D_NA, &rec.D_NE, &rec.D_TA, &rec.D_TE}) v->resize(n);
      for (int i = 0; i < n; ++i) {
        rec.contacts[i] = idx[i];
        rec.P_N(i) = -lambda(i);
        rec.P_T(i) = 0.0;
        rec.D_NA(i) = f[i].W_N.dot(st_.qdot);
        rec.D_NE(i) = f[i].W_N.dot(after.qdot);
        rec.D_TA(i) = f[i].W_T.dot(st_.qdot);
        rec.D_TE(i) = f[i].W_T.dot(after.qdot);
      }
      rec.energy_A = e_a;
      rec.energy_E = e_e;
      rec.admissible = e_e <= e_a;
      rec.failed = rec.admissible ? Inequality::none : Inequality::total_15;
      rec.violation = rec.admissible ? 0.0 : e_e - e_a;
      rec.solver.method = SolverMethod::closed_form;
      rec.solver.status = SolverStatus::converged;
      rec.solver.criterion = StopCriterion::exact;
      rec.solver.message =
          "accumulation closed: normal velocities of the touching contacts set to 0";
      rec.solver.iterations = 0;
      rec.accumulation_limit = t_ + tail;
      obs_->on_impact(rec);
    }
    ++log_index_;
    if (res_.accumulations++ == 0) res_.first_accumulation_time = t_ + tail;
    st_ = after;
    audit(e_e, false);
    emit_sample(t_, st_);
  }

  // ---- Moreau–Jean phase -------------------------------------------------------------------

  // The persistent-contact impulse (persistent_contact.hpp) on the active contacts f[0..na), from
  // velocity v to v_out = v + dv + M⁻¹(W_N P_N + W_T P_T), where dv is what gravity adds over the
  // step: (0, −g h, 0). Two uses:
  //  - h = 0 (`closing`): the plastic closing of approaching contacts (Signorini and Coulomb on
  //    the end velocity; P·z = P·D_E − ½PᵀGP ≤ 0), on the contacts not leaving, skipped when none
  //    approaches;
  //  - h > 0: the step against gravity on every active contact (solve_dissipative_step).
  // dv is formed once per phase (gravity_dv), not per call: adding a vector that was just stored
  // component by component makes the processor wait for the stores (a failed store forwarding),
  // which cost as much as the rest of the call. Returns false when the run must stop.
  bool persistent_impulse(const Frames& f, const int* active, int na, const Eigen::Vector3d& v,
                          bool closing, const Eigen::Vector3d& dv, Eigen::Vector3d& v_out) {
    int n = 0;
    bool approaching = false;
    std::array<bool, kMaxC> closed;
    for (int i = 0; i < na; ++i) {
      const double d = f[i].W_N.dot(v);
      closed[i] = !(closing && d > opt_.velocity_tolerance);  // leaving: not closed
      if (!closed[i]) continue;
      approaching = approaching || d < -opt_.velocity_tolerance;
      ++n;
    }
    if (n > PersistentContactProblem::kMax) {
      finish(SimulationStatus::contact_failed,
             "more than four contacts closed in one Moreau-Jean step");
      return false;
    }
    v_out = v + dv;
    if (n == 0 || (closing && !approaching)) return true;
    PersistentContactProblem& pp = pp_;  // reused: only contacts [0, n) are read
    std::array<int, PersistentContactProblem::kMax> idx;
    std::array<ContactMode, PersistentContactProblem::kMax> warm;
    n = 0;
    for (int i = 0; i < na; ++i) {
      if (!closed[i]) continue;
      pp.W_N[n] = f[i].W_N;
      pp.W_T[n] = f[i].W_T;
      pp.mu[n] = mu_[active[i]];
      warm[n] = mode_[active[i]];
      idx[n++] = active[i];
    }
    pp.contacts = n;
    pp.v_before = v;
    pp.v_free = v_out;
    if (closing) pp.normal = pp.friction = StepVelocity::end;
    const PersistentContactResult r = closing ? solve_persistent_contact(pp, warm.data())
                                              : solve_dissipative_step(pp, warm.data());
    if (!r.solved) {
      finish(SimulationStatus::contact_failed,
             "no contact mode satisfies the persistent-contact law (Painlevé-type case)");
      return false;
    }
    for (int i = 0; i < n; ++i) mode_[idx[i]] = r.mode[i];
    v_out = r.v;
    return true;
  }

  // What gravity adds to the velocity over a step h, (0, −g h, 0).
  Eigen::Vector3d gravity_dv(double h) const { return {0.0, -sc_.gravity * h, 0.0}; }

  void moreau_jean_phase() {
    const double t0 = t_, h = opt_.step, g = sc_.gravity;
    const Eigen::Vector3d gravity_step(0.0, -g, 0.0);
    const Eigen::Vector3d dv_zero = gravity_dv(0.0), dv_step = gravity_dv(h);
    long k = 0;
    int free_steps = 0;
    hit_step_.fill(-2);
    double cth = std::cos(st_.q.z()), sth = std::sin(st_.q.z());
    std::array<int, kMaxC> active, idx;
    while (!stop_ && t_ < opt_.t_end) {
      if (!progress()) break;
      // Full steps all use h itself (not a difference of rounded times), so that a step is one
      // fixed map of (q, v); only the last step is shortened to end at t_end.
      double t_next = t0 + static_cast<double>(k + 1) * h;
      if (t_next >= opt_.t_end || opt_.t_end - t_next < 1e-6 * h) t_next = opt_.t_end;
      const double hk = t_next == opt_.t_end ? opt_.t_end - t_ : h;
      const Eigen::Vector3d q = st_.q, v = st_.qdot;

      // 1. Active contacts: those that free flight would close within one full step h, by the
      //    Taylor expansion g + h g' + h² g''/2 of the gap (exact without rotation; the rotation
      //    adds at most L h³/6 with L = |ω|³|r|, far below any gap that matters). A full step
      //    also for a shortened last one: which contacts are active must not depend on where
      //    t_end falls. With R(θ)r: g' = n·ċ + ω (R(θ)r × n), g'' = −n_y g − ω² n·R(θ)r.
      Frames f;  // filled for the active contacts only
      int na = 0;
      const double w2 = v.z() * v.z();
      for (int j = 0; j < nc_; ++j) {
        const ContactPoint& p = *point_[j];
        const HalfPlane& o = *plane_[j];
        const Eigen::Vector2d& nn = o.normal;
        const Eigen::Vector2d Rr(cth * p.r.x() - sth * p.r.y(), sth * p.r.x() + cth * p.r.y());
        const double n_Rr = nn.dot(Rr);
        const double gap = nn.dot(q.head<2>()) + n_Rr - o.offset - p.radius;
        const double gd =
            nn.x() * v.x() + nn.y() * v.y() + v.z() * (Rr.x() * nn.y() - Rr.y() * nn.x());
        const double gdd = -nn.y() * g - w2 * n_Rr;
        if (gap + h * gd + 0.5 * h * h * gdd <= 0.0) {
          f[na] = contact_frame(p, o, q.head<2>(), cth, sth);
          active[na++] = j;
        }
      }

      Eigen::Vector3d v_e = v, v1;
      bool contact_step = na > 0;
      if (!contact_step) {
        v1 = v + hk * gravity_step;
        ++free_steps;
      } else {
        free_steps = 0;
        // 2. The law's impact, on the contacts that approach faster than one step of smooth
        //    forces could make them (slower ones are persistent contact, steps 3-4).
        //    The bound is twice what gravity and the rotation add to D_N in one step of free
        //    flight: a contact constrained by others (a bar pivoting on one end) accelerates
        //    faster than in free flight (1.5 g at the free end of a pivoting bar). A contact
        //    that had the law's impact in the previous step is not given another: a bounce that
        //    gravity undoes within one step is below the resolution of the step, and bouncing
        //    it again at every step would only chatter (and sink, through the midpoint rule).
        int n = 0;
        for (int i = 0; i < na; ++i) {
          const int j = active[i];
          if (f[i].W_N.dot(v) < -2.0 * hk * (g + w2 * reach_[j]) && hit_step_[j] != k - 1)
            idx[n++] = j;
        }
        for (int i = 0; i < n; ++i) hit_step_[idx[i]] = k;
        if (n > 0) {
          PlanarState s{q, v};
          if (!impact(t_, s, idx.data(), n, ImpactKind::time_step)) return;
          v_e = s.qdot;
        }
        // 3. Contacts still approaching (slowly, or driven in by the impact of step 2) close
        //    plastically at once: then no active contact sinks through the position update.
        if (!persistent_impulse(f, active.data(), na, v_e, true, dv_zero, v_e)) return;
        // 4. The persistent-contact impulse against gravity over the step.
        if (!persistent_impulse(f, active.data(), na, v_e, false,
                                hk == h ? dv_step : gravity_dv(hk), v1))
          return;
      }
      // 5. Midpoint positions.
      const Eigen::Vector3d q1 = q + (0.5 * hk) * (v_e + v1);
      const bool fixed_point =
          contact_step && q1 == q && v1 == v && v_e == v && t_next != opt_.t_end;
      st_.q = q1;
      st_.qdot = v1;
      t_ = t_next;
      ++k;
      ++res_.steps;
      cth = std::cos(q1.z());
      sth = std::sin(q1.z());
      audit(energy(sc_, st_), false);
      samples_until(t_, true, [&](double) { return st_; });
      if (fixed_point) {
        // The step maps (q, v) to itself, and it depends on nothing else (the warm modes are the
        // modes it found): every further full step repeats it. Jump to the last one.
        const long last = static_cast<long>(std::ceil((opt_.t_end - t0) / h)) - 1;
        if (last > k) {
          res_.steps += last - k;
          k = last;
          t_ = t0 + static_cast<double>(k) * h;
          samples_until(t_, true, [&](double) { return st_; });
        }
      }
      if (opt_.integrator == Integrator::event_driven &&
          free_steps >= opt_.return_after_free_steps) {
        switch_phase(Phase::event_driven, "free flight");
        return;
      }
    }
  }

  // ---- data --------------------------------------------------------------------------------
  Scene sc_;
  SimulationOptions opt_;
  SimulationObserver* obs_;
  int nc_ = 0;
  Eigen::Vector3d minv_;
  // The point and obstacle of each contact, looked up once: Scene::point_of and obstacle_of
  // divide, and the Moreau–Jean step asks for every contact at every step.
  std::array<const ContactPoint*, kMaxC> point_{};
  std::array<const HalfPlane*, kMaxC> plane_{};
  std::array<double, kMaxC> mu_{}, reach_{};
  std::array<ContactMode, kMaxC> mode_{};
  std::array<long, kMaxC> hit_step_{};  // Moreau–Jean step of each contact's last impact
  bool uniform_law_ = true;
  std::map<Mask, ImpactLaw> laws_;
  PersistentContactProblem pp_;  // the Moreau–Jean step's, kept to spare its set-up at every step

  double t_ = 0.0;
  PlanarState st_;
  Phase phase_ = Phase::event_driven;
  SimulationResult res_;
  bool stop_ = false;
  double e_prev_ = 0.0;
  long next_sample_index_ = 0;
  double last_sample_t_ = -1.0;
  double next_progress_ = 0.0;
  long log_index_ = 0;
  std::array<double, 64> times_{};
  int n_times_ = 0;
};

}  // namespace

void validate_start(const Scene& scene, const SimulationOptions& options) {
  const Eigen::Vector3d& q = scene.initial.q;
  for (int k = 0; k < scene.contact_count(); ++k) {
    const double gap = contact_frame(scene, k, q).gap;
    if (gap < -options.gap_tolerance)
      throw InvalidArgument("initial", "contact point " + std::to_string(scene.point_of(k)) +
                                           " starts " + std::to_string(-gap) +
                                           " m inside obstacle " +
                                           std::to_string(scene.obstacle_of(k)) +
                                           " (gap below -integrator.gap_tolerance); start the "
                                           "body on or above the obstacles");
  }
}

SimulationResult simulate(const Scene& scene, const SimulationOptions& options,
                          SimulationObserver* observer) {
  Run run(scene, options, observer);
  return run.go();
}

}  // namespace fremond
