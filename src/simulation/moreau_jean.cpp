// The Moreau–Jean phase (simulate.hpp, steps 1-5), until options.return_after_free_steps free
// steps in a row hand back to the event-driven phase.
#include <cmath>

#include "simulation/detail/run.hpp"

namespace fremond::detail {

// Step 1: the contacts that free flight would close within one full step h, by the Taylor
// expansion g + h g' + h² g''/2 of the gap (exact without rotation; the rotation adds at most
// L h³/6 with L = |ω|³|r|, far below any gap that matters). With R(θ)r: g' = n·ċ + ω (R(θ)r × n),
// g'' = −n_y g − ω² n·R(θ)r. Fills their frames f and scene indices `active`; returns their count.
int Run::active_contacts(const Eigen::Vector3d& q, const Eigen::Vector3d& v, double h, double cth,
                         double sth, Frames& f, int* active) const {
  const double g = sc_.gravity;
  int na = 0;
  const double w2 = v.z() * v.z();
  for (int j = 0; j < nc_; ++j) {
    const ContactPoint& p = *point_[j];
    const HalfPlane& o = *plane_[j];
    const Eigen::Vector2d& nn = o.normal;
    const Eigen::Vector2d Rr(cth * p.r.x() - sth * p.r.y(), sth * p.r.x() + cth * p.r.y());
    const double n_Rr = nn.dot(Rr);
    const double gap = nn.dot(q.head<2>()) + n_Rr - o.offset - p.radius;
    const double gd = nn.x() * v.x() + nn.y() * v.y() + v.z() * (Rr.x() * nn.y() - Rr.y() * nn.x());
    const double gdd = -nn.y() * g - w2 * n_Rr;
    if (gap + h * gd + 0.5 * h * h * gdd <= 0.0) {
      f[na] = contact_frame(p, o, q.head<2>(), cth, sth);
      active[na++] = j;
    }
  }
  return na;
}

// Step 2: the active contacts f[0..na) that get the law's impact in step k (length hk), into idx;
// returns their count. Those that approach faster than one step of smooth forces could make them;
// slower ones are persistent contact (steps 3-4). The bound is twice what gravity and the rotation
// add to D_N in one step of free flight: a contact constrained by others (a bar pivoting on one
// end) accelerates faster than in free flight (1.5 g at the free end of a pivoting bar). A contact
// that had the law's impact in the previous step is not given another: a bounce that gravity
// undoes within one step is below the resolution of the step, and bouncing it again at every step
// would only chatter (and sink, through the midpoint rule).
int Run::law_impact_contacts(const Frames& f, const int* active, int na, const Eigen::Vector3d& v,
                             double hk, long k, int* idx) {
  const double g = sc_.gravity, w2 = v.z() * v.z();
  int n = 0;
  for (int i = 0; i < na; ++i) {
    const int j = active[i];
    if (f[i].W_N.dot(v) < -2.0 * hk * (g + w2 * reach_[j]) && hit_step_[j] != k - 1) idx[n++] = j;
  }
  for (int i = 0; i < n; ++i) hit_step_[idx[i]] = k;
  return n;
}

// The persistent-contact impulse (persistent_contact.hpp) on the active contacts f[0..na), from
// velocity v to v_out = v + dv + M⁻¹(W_N P_N + W_T P_T), where dv is what gravity adds over the
// step: (0, −g h, 0). Two uses:
//  - h = 0 (`closing`): the plastic closing of approaching contacts (Signorini and Coulomb on
//    the end velocity; P·z = P·D_E − ½PᵀGP ≤ 0), on the contacts not leaving, skipped when none
//    approaches;
//  - h > 0: the step against gravity on every active contact (solve_dissipative_step).
// dv is formed once per phase by the caller: a vector added right after being stored component by
// component stalls on the stores. Returns false when the run must stop.
bool Run::persistent_impulse(const Frames& f, const int* active, int na, const Eigen::Vector3d& v,
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
  const PersistentContactResult r =
      closing ? solve_persistent_contact(pp, warm.data()) : solve_dissipative_step(pp, warm.data());
  if (!r.solved) {
    finish(SimulationStatus::contact_failed,
           "no contact mode satisfies the persistent-contact law (Painlevé-type case)");
    return false;
  }
  for (int i = 0; i < n; ++i) mode_[idx[i]] = r.mode[i];
  v_out = r.v;
  return true;
}

void Run::moreau_jean_phase() {
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

    // 1. Active contacts, over a full step also for a shortened last one: which contacts are
    //    active must not depend on where t_end falls.
    Frames f;  // filled for the active contacts only
    const int na = active_contacts(q, v, h, cth, sth, f, active.data());

    Eigen::Vector3d v_e = v, v1;
    bool contact_step = na > 0;
    if (!contact_step) {
      v1 = v + hk * gravity_step;
      ++free_steps;
    } else {
      free_steps = 0;
      // 2. The law's impact, on the contacts approaching too fast for persistent contact.
      const int n = law_impact_contacts(f, active.data(), na, v, hk, k, idx.data());
      if (n > 0) {
        PlanarState s{q, v};
        if (!impact(t_, s, idx.data(), n, ImpactKind::time_step)) return;
        v_e = s.qdot;
      }
      // 3. Contacts still approaching (slowly, or driven in by the impact of step 2) close
      //    plastically at once: then no active contact sinks through the position update.
      if (!persistent_impulse(f, active.data(), na, v_e, true, dv_zero, v_e)) return;
      // 4. The persistent-contact impulse against gravity over the step.
      if (!persistent_impulse(f, active.data(), na, v_e, false, hk == h ? dv_step : gravity_dv(hk),
                              v1))
        return;
    }
    // 5. Midpoint positions.
    const Eigen::Vector3d q1 = q + (0.5 * hk) * (v_e + v1);
    const bool fixed_point = contact_step && q1 == q && v1 == v && v_e == v && t_next != opt_.t_end;
    st_.q = q1;
    st_.qdot = v1;
    t_ = t_next;
    ++k;
    ++res_.steps;
    cth = std::cos(q1.z());
    sth = std::sin(q1.z());
    audit_.record(energy(sc_, st_), false);
    sampler_.until(t_, true, phase_, [&](double) { return st_; });
    if (fixed_point) {
      // The step maps (q, v) to itself, and it depends on nothing else (the warm modes are the
      // modes it found): every further full step repeats it. Jump to the last one.
      const long last = static_cast<long>(std::ceil((opt_.t_end - t0) / h)) - 1;
      if (last > k) {
        res_.steps += last - k;
        k = last;
        t_ = t0 + static_cast<double>(k) * h;
        sampler_.until(t_, true, phase_, [&](double) { return st_; });
      }
    }
    if (opt_.integrator == Integrator::event_driven && free_steps >= opt_.return_after_free_steps) {
      switch_phase(Phase::event_driven, "free flight");
      return;
    }
  }
}

}  // namespace fremond::detail
