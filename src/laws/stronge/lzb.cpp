#include "laws/stronge/lzb.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace fremond::detail {

namespace {

namespace odeint = boost::numeric::odeint;
using State = std::vector<double>;

// A contact's normal phase. Compression and expansion hold energy; a separated contact holds
// none and takes no percussion until its D_N turns negative again.
enum class Phase : unsigned char { separated, compression, expansion };

// The conditions that end a phase, located as events (kinds of Run::met_).
enum Kind : int {
  kCompressionEnds,  // compression, D_N > 0
  kRecompresses,     // expansion, D_N < 0: pushed back in by the others
  kEnergyGone,       // expansion, energy ≤ 0: the contact's impact ends
  kApproaches,       // separated, D_N < 0
  kSlipStops,        // slip in direction s, s D_T < 0
  kStickBreaks,      // stick, the percussion it needs leaves the cone
  kKinds
};

// Where all energies are 0 and several contacts approach, the first 1e-10 of the primary's
// percussion (in units of |D_N|/G_NN) is taken with the velocities frozen: δ_i = |D_Ni| t. Its
// error is of the order of that fraction squared; the integrator then takes over.
constexpr double kStartFraction = 1e-10;
// The primary contact changes when another holds more than this times its energy: the ratios
// dP_i/dP_p stay bounded, and the change (a restart of the integrator) is not made every step.
constexpr double kSwitchRatio = 2.0;
// A contact holds its energy E as its state above this fraction of the primary's, its
// compression δ below kHoldBelow (a hysteresis, as for the primary). δ starts a compression from
// E = 0 and ends one while the primary still pushes (dδ/dP_p = −D_N c/F_p is then regular); E
// ends one together with the primary (dE_i/dP_p = −D_N c F_i/F_p stays finite as both F → 0).
constexpr double kHoldAbove = 0.25;
constexpr double kHoldBelow = 0.125;
// Relative margin of the cone test: a stick holds while |λ| ≤ μ F_N (1 + margin).
constexpr double kConeMargin = 1e-9;
constexpr int kMaxEvents = 20000;
// A velocity condition holds once the velocity is past 0 by this much (the problem's velocities
// are of order 1): a phase that starts at D = 0 to rounding, a slip started from stick with D_T
// a rounding off the other way, does not end where it starts.
constexpr double kVelocityFloor = 1e-14;

// x^a for x ≥ 0, without pow for the exponents of the linear and Hertz laws (the integration
// spends most of its time here).
double power(double x, double a) {
  if (a == 1.0) return x;
  if (a == 0.5) return std::sqrt(x);
  if (a == 1.5) return x * std::sqrt(x);
  if (a == 2.0) return x * x;
  if (a == 2.5) return x * x * std::sqrt(x);
  return std::pow(x, a);
}

class Run {
 public:
  Run(const Eigen::Ref<const Eigen::MatrixXd>& G, const Eigen::Ref<const Eigen::VectorXd>& D_A,
      std::span<const LzbContact> contacts, const LzbOptions& options)
      : n_(static_cast<int>(contacts.size())),
        r_(static_cast<int>(G.rows())),
        friction_(r_ == 2 * n_),
        G_(G),
        D_A_(D_A),
        c_(contacts.begin(), contacts.end()),
        options_(options) {}

  LzbAnswer run();

  // The system for odeint: d/dτ of the state, τ the primary contact's percussion.
  void rhs(const State& x, State& dxdt) {
    evaluate(x);
    const double inv = F_(primary_) > 0.0 ? 1.0 / F_(primary_) : 0.0;
    for (int i = 0; i < n_; ++i) {
      const double dPN = rho_(i);
      const double vN = v_(i);
      dxdt[P(i)] = dPN;
      double dq = 0.0;
      if (phase_[i] != Phase::separated) {
        const double c = phase_[i] == Phase::compression ? 1.0 : 1.0 / (c_[i].e * c_[i].e);
        dq = holds_[i] ? -vN * c * dPN : -vN * c * inv;  // dE_i/dP_p, or dδ_i/dP_p
      }
      dxdt[Q(i)] = dq;
      dxdt[WC(i)] = phase_[i] == Phase::compression ? -vN * dPN : 0.0;
      dxdt[WR(i)] = phase_[i] == Phase::expansion ? vN * dPN : 0.0;
      double dPT = 0.0;
      if (friction_) {
        dPT = fT_(i);
        dxdt[P(n_ + i)] = dPT;
      }
      dxdt[DT(i)] = friction_ ? -v_(n_ + i) * dPT : 0.0;
    }
  }

 private:
  // The state: the percussions of every row, then per contact q (its energy E, or its
  // compression δ where holds_[i] is false: dδ/dP_p = −D_N/F_p is Lipschitz at E = 0 where
  // dE/dP_p ∝ E^(η/(η+1)) is not, and a contact starting from E = 0 would stay there), the
  // compression and restitution works and the friction work, all in the scaled problem's units.
  int P(int row) const { return row; }
  int Q(int i) const { return r_ + i; }
  int WC(int i) const { return r_ + n_ + i; }
  int WR(int i) const { return r_ + 2 * n_ + i; }
  int DT(int i) const { return r_ + 3 * n_ + i; }

  double energy(int i, const State& x) const {
    const double q = std::max(x[Q(i)], 0.0);
    if (holds_[i]) return q;
    const double eta = c_[i].eta;
    return K_(i) * power(q, eta + 1.0) / (eta + 1.0);
  }
  double compression_of_energy(int i, double E) const {
    const double eta = c_[i].eta;
    return power((eta + 1.0) * std::max(E, 0.0) / K_(i), 1.0 / (eta + 1.0));
  }
  double force(int i, const State& x) const {
    if (phase_[i] == Phase::separated) return 0.0;
    const double q = std::max(x[Q(i)], 0.0), eta = c_[i].eta;
    if (holds_[i])  // F = K^(1/(η+1)) ((η+1)E)^(η/(η+1))
      return K_root_(i) * power((eta + 1.0) * q, eta / (eta + 1.0));
    return K_(i) * power(q, eta);
  }

  // At state x: v_ (every row's velocity), F_ (normal forces), rho_ = F/F_p = dP_N/dP_p (1 for
  // the primary, also where F_p = 0) and fT_ = dP_T/dP_p (−μ s ρ while slipping, the stick
  // solve's λ while stuck).
  void evaluate(const State& x);
  // Condition k of contact i as a continuous margin, met where negative (kEnergyGone: where
  // ≤ 0), after evaluate(x); whether it is watched in the contact's present phases.
  double margin(int i, int k, const State& x) const;
  bool watched(int i, int k) const;
  static bool is_met(int k, double m) {
    if (k == kEnergyGone) return m <= 0.0;
    return k == kStickBreaks || k == kSlipStops ? m < 0.0 : m < -kVelocityFloor;
  }
  // met_[kKinds i + k]: whether condition k ends contact i's phase at x.
  bool conditions(const State& x);
  // The first τ in (t0, t1] where condition `which` is met, on the stepper's dense output.
  template <class Stepper>
  double locate(const Stepper& stepper, int which, double t0, double t1, State& xm);
  // The phase changes at an event, until no condition holds.
  bool apply_transitions(State& x);
  // Slip in the direction of D_T, or (D_T = 0, or `at_zero`) stick if the cone holds the
  // percussion it needs, else slip against it.
  void decide_tangent(int i, State& x, bool at_zero);
  void end_contact(int i, State& x);
  void start_slip(int i, double s);
  // A primary where there is none: the most energetic contact, or where all energies are 0 the
  // most approaching one, with the start of the others. False when no contact takes part.
  bool choose_primary(State& x);
  void start_from_rest(State& x);
  // Another primary where one holds kSwitchRatio times its energy, and each contact's state
  // (E or δ) by kHoldAbove and kHoldBelow; the step's scale factor, 0 if nothing changed.
  double rebalance(State& x);
  void hold_energy(int i, State& x, bool hold);
  LzbAnswer answer(const State& x, const char* message, bool converged) const;

  int n_, r_;
  bool friction_;
  Eigen::MatrixXd G_;  // scaled to G / g
  Eigen::VectorXd D_A_;
  std::vector<LzbContact> c_;
  LzbOptions options_;
  double v_s_ = 1.0, P_s_ = 1.0;  // units of velocity and percussion
  Eigen::VectorXd K_, K_root_;    // stiffnesses in the scaled units, K^(1/(η+1))
  std::vector<Phase> phase_;
  std::vector<double> slip_;          // slip direction ±1, 0 while stuck
  std::vector<unsigned char> holds_;  // q is E (true) or δ (false)
  // A slip stops where s D_T falls below this: kVelocityFloor below where it started, or below 0
  // (a slip started at D_T = 0 to rounding, a little the other way, does not stop at once).
  std::vector<double> slip_floor_;
  int primary_ = -1;
  double drift_ = 0.0;  // largest invariant drift found at a contact's end
  int steps_ = 0, events_ = 0;
  Eigen::VectorXd v_, F_, rho_, fT_, lambda_;
  std::vector<int> stuck_;
  std::vector<unsigned char> met_;
};

void Run::evaluate(const State& x) {
  // v = D_A + G P, by columns: a few rows, where Eigen's general product costs its dispatch.
  v_ = D_A_;
  for (int j = 0; j < r_; ++j) {
    const double Pj = x[P(j)];
    if (Pj == 0.0) continue;
    const double* g = G_.data() + static_cast<std::ptrdiff_t>(j) * r_;
    for (int k = 0; k < r_; ++k) v_(k) += g[k] * Pj;
  }
  for (int i = 0; i < n_; ++i) F_(i) = force(i, x);
  const double Fp = F_(primary_ < 0 ? 0 : primary_);
  for (int i = 0; i < n_; ++i) rho_(i) = Fp > 0.0 ? F_(i) / Fp : 0.0;
  if (primary_ >= 0) rho_(primary_) = 1.0;
  if (!friction_) return;
  stuck_.clear();
  for (int i = 0; i < n_; ++i) {
    fT_(i) = 0.0;
    lambda_(i) = 0.0;
    if (phase_[i] == Phase::separated || c_[i].mu == 0.0) continue;
    if (slip_[i] != 0.0)
      fT_(i) = -c_[i].mu * slip_[i] * rho_(i);
    else
      stuck_.push_back(i);
  }
  if (stuck_.empty()) return;
  // The stuck contacts keep dD_T = 0: G_TS,TS λ = −(G_TS,N F + G_TS,T f_T of the others).
  const int m = static_cast<int>(stuck_.size());
  Eigen::MatrixXd A(m, m);
  Eigen::VectorXd b(m);
  for (int a = 0; a < m; ++a) {
    const int ra = n_ + stuck_[a];
    double s = G_.row(ra).head(n_).dot(rho_);
    for (int j = 0; j < n_; ++j) s += G_(ra, n_ + j) * fT_(j);  // stuck ones are 0 in fT_ yet
    b(a) = -s;
    for (int c = 0; c < m; ++c) A(a, c) = G_(ra, n_ + stuck_[c]);
  }
  Eigen::VectorXd lam = A.ldlt().solve(b);
  if (!lam.allFinite()) lam = A.completeOrthogonalDecomposition().solve(b);
  for (int a = 0; a < m; ++a) {
    lambda_(stuck_[a]) = lam(a);
    fT_(stuck_[a]) = lam(a);
  }
}

double Run::margin(int i, int k, const State& x) const {
  switch (k) {
    case kCompressionEnds:
      return -v_(i);
    case kRecompresses:
    case kApproaches:
      return v_(i);
    case kEnergyGone:
      return x[Q(i)];
    case kSlipStops:
      return slip_[i] * v_(n_ + i) - slip_floor_[i];
    default:
      return c_[i].mu * rho_(i) * (1.0 + kConeMargin) - std::fabs(lambda_(i));
  }
}

bool Run::watched(int i, int k) const {
  switch (k) {
    case kCompressionEnds:
      return phase_[i] == Phase::compression;
    case kRecompresses:
    case kEnergyGone:
      return phase_[i] == Phase::expansion;
    case kApproaches:
      return phase_[i] == Phase::separated;
    default:
      return friction_ && phase_[i] != Phase::separated && c_[i].mu > 0.0 &&
             (k == kSlipStops) == (slip_[i] != 0.0);
  }
}

bool Run::conditions(const State& x) {
  evaluate(x);
  bool any = false;
  for (int i = 0; i < n_; ++i)
    for (int k = 0; k < kKinds; ++k) {
      const bool m = watched(i, k) && is_met(k, margin(i, k, x));
      met_[static_cast<std::size_t>(kKinds * i + k)] = m;
      any = any || m;
    }
  return any;
}

void Run::end_contact(int i, State& x) {
  // Its energy from the works integrated beside δ: E = W_c − W_r/e² should be 0 here.
  const double e2 = c_[i].e * c_[i].e;
  if (e2 > 0.0) drift_ = std::max(drift_, std::fabs(e2 * x[WC(i)] - x[WR(i)]));
  x[Q(i)] = 0.0;
  phase_[i] = Phase::separated;
  holds_[i] = 0;
  if (i == primary_) primary_ = -1;
}

void Run::decide_tangent(int i, State& x, bool at_zero) {
  if (!friction_ || c_[i].mu == 0.0) return;
  const double vT = v_(n_ + i);
  if (!at_zero && vT != 0.0) {
    start_slip(i, vT > 0.0 ? 1.0 : -1.0);
    return;
  }
  slip_[i] = 0.0;
  evaluate(x);
  const double lam = lambda_(i);
  if (std::fabs(lam) <= c_[i].mu * rho_(i) * (1.0 + kConeMargin)) return;
  // The cone cannot hold it: it slides the way that is consistent, s dD_T > 0 under the friction
  // −μ s ρ (the way it is driven, −sign λ, for one contact; with others the first that is).
  const double driven = lam > 0.0 ? -1.0 : 1.0;
  for (double s : {driven, -driven}) {
    slip_[i] = s;
    evaluate(x);
    double dvT = 0.0;
    for (int j = 0; j < n_; ++j) dvT += G_(n_ + i, j) * rho_(j) + G_(n_ + i, n_ + j) * fT_(j);
    if (s * dvT > 0.0) return start_slip(i, s);
  }
  start_slip(i, driven);
}

void Run::start_slip(int i, double s) {
  slip_[i] = s;
  slip_floor_[i] = std::min(0.0, s * v_(n_ + i)) - kVelocityFloor;
}

bool Run::apply_transitions(State& x) {
  for (int round = 0; round < 4 * n_ + 4; ++round) {
    if (!conditions(x)) return true;
    const std::vector<unsigned char> met = met_;
    for (int i = 0; i < n_; ++i) {
      const unsigned char* m = &met[static_cast<std::size_t>(kKinds * i)];
      if (m[kCompressionEnds]) {
        // e* = 0 gives nothing back: the contact ends where its compression does.
        if (c_[i].e == 0.0 || x[Q(i)] <= 0.0)
          end_contact(i, x);
        else
          phase_[i] = Phase::expansion;
      } else if (m[kRecompresses]) {
        phase_[i] = Phase::compression;
      } else if (m[kEnergyGone]) {
        end_contact(i, x);
      } else if (m[kApproaches]) {
        phase_[i] = Phase::compression;
        x[Q(i)] = 0.0;
        decide_tangent(i, x, false);
      }
      if (phase_[i] == Phase::separated) continue;
      if (m[kSlipStops]) decide_tangent(i, x, true);
      if (m[kStickBreaks]) {
        evaluate(x);  // λ as the changes above left it
        start_slip(i, lambda_(i) > 0.0 ? -1.0 : 1.0);
      }
    }
  }
  return !conditions(x);
}

void Run::start_from_rest(State& x) {
  // Every energy is 0: the contacts that approach start together, the primary the one that
  // approaches fastest (Liu, Zhao & Brogliato). Over the first kStartFraction of its percussion
  // the velocities barely change: δ_i = |D_Ni| t, P_i = K_i |D_Ni|^η_i t^(η_i+1)/(η_i+1).
  const int p = primary_;
  const double vp = -v_(p);
  const double dP = kStartFraction * vp / std::max(G_(p, p), std::numeric_limits<double>::min());
  const double ep = c_[p].eta;
  const double t = std::pow((ep + 1.0) * dP / (K_(p) * std::pow(vp, ep)), 1.0 / (ep + 1.0));
  std::vector<double> dPN(static_cast<std::size_t>(n_), 0.0);
  for (int i = 0; i < n_; ++i) {
    if (phase_[i] != Phase::compression || !(v_(i) < 0.0)) continue;
    const double vi = -v_(i), eta = c_[i].eta;
    dPN[static_cast<std::size_t>(i)] =
        i == p ? dP : K_(i) * std::pow(vi, eta) * std::pow(t, eta + 1.0) / (eta + 1.0);
    x[Q(i)] = i == p ? vi * dP : vi * t;
  }
  // The tangential modes at the start's forces, and the same ratio of tangential to normal.
  for (int i = 0; i < n_; ++i)
    if (phase_[i] == Phase::compression) decide_tangent(i, x, false);
  evaluate(x);
  for (int i = 0; i < n_; ++i) {
    const double d = dPN[static_cast<std::size_t>(i)];
    if (d == 0.0) continue;
    x[WC(i)] += -v_(i) * d;
    if (friction_ && rho_(i) > 0.0) {
      const double dT = fT_(i) / rho_(i) * d;
      x[DT(i)] += -v_(n_ + i) * dT;
      x[P(n_ + i)] += dT;
    }
  }
  for (int i = 0; i < n_; ++i) x[P(i)] += dPN[static_cast<std::size_t>(i)];
}

bool Run::choose_primary(State& x) {
  int best = -1;
  double best_E = 0.0;
  for (int i = 0; i < n_; ++i) {
    if (phase_[i] == Phase::separated) continue;
    const double E = energy(i, x);
    if (E > best_E) best = i, best_E = E;
  }
  if (best >= 0) {
    primary_ = best;
    hold_energy(best, x, true);
    rebalance(x);
    return true;
  }
  // No energy anywhere: the contacts that approach now start; the others are apart.
  evaluate(x);
  int fastest = -1;
  int approaching = 0;
  for (int i = 0; i < n_; ++i) {
    x[Q(i)] = 0.0;
    holds_[i] = 0;
    if (v_(i) < 0.0) {
      phase_[i] = Phase::compression;
      ++approaching;
      if (fastest < 0 || v_(i) < v_(fastest)) fastest = i;
    } else {
      phase_[i] = Phase::separated;
    }
  }
  if (fastest < 0) return false;
  primary_ = fastest;
  holds_[fastest] = 1;
  if (approaching > 1) {
    start_from_rest(x);
    rebalance(x);
  } else {
    // One contact approaches: it drives from E = 0, where dE/dP = −D_N is regular. Contacts at
    // D_N = 0 start their compression with it (a chain at rest behind the struck ball).
    for (int i = 0; i < n_; ++i)
      if (i != fastest && v_(i) == 0.0) phase_[i] = Phase::compression;
    for (int i = 0; i < n_; ++i)
      if (phase_[i] == Phase::compression) decide_tangent(i, x, false);
  }
  return true;
}

void Run::hold_energy(int i, State& x, bool hold) {
  if (static_cast<bool>(holds_[i]) == hold) return;
  const double E = energy(i, x);
  holds_[i] = hold;
  x[Q(i)] = hold ? E : compression_of_energy(i, E);
}

double Run::rebalance(State& x) {
  const int p = primary_;
  double Ep = energy(p, x);
  const double Fp = force(p, x);
  int best = p;
  double best_E = kSwitchRatio * Ep;
  for (int i = 0; i < n_; ++i) {
    if (i == p || phase_[i] == Phase::separated) continue;
    const double E = energy(i, x);
    if (E > best_E) best = i, best_E = E;
  }
  bool changed = best != p;
  primary_ = best;
  hold_energy(best, x, true);
  Ep = energy(best, x);
  for (int i = 0; i < n_; ++i) {
    if (i == best || phase_[i] == Phase::separated) continue;
    const double E = energy(i, x);
    const bool hold = holds_[i] ? E >= kHoldBelow * Ep : E > kHoldAbove * Ep;
    changed = changed || hold != static_cast<bool>(holds_[i]);
    hold_energy(i, x, hold);
  }
  if (!changed) return 0.0;
  const double Fb = force(best, x);
  return Fp > 0.0 && Fb > 0.0 ? Fb / Fp : 1.0;
}

LzbAnswer Run::answer(const State& x, const char* message, bool converged) const {
  LzbAnswer out;
  out.message = message;
  out.converged = converged;
  out.steps = steps_;
  out.events = events_;
  Eigen::VectorXd Pall(r_);
  for (int k = 0; k < r_; ++k) Pall(k) = x[P(k)] * P_s_;
  out.P_N = Pall.head(n_);
  out.P_T = friction_ ? Eigen::VectorXd(Pall.tail(n_)) : Eigen::VectorXd::Zero(n_);
  out.D_E = D_A_ * v_s_ + (G_ * Pall) * (v_s_ / P_s_);
  const double unit = v_s_ * P_s_;  // of energy
  out.work_compression.resize(n_);
  out.dissipated_normal.resize(n_);
  out.dissipated_tangential.resize(n_);
  double work = 0.0;
  for (int i = 0; i < n_; ++i) {
    out.work_compression(i) = -x[WC(i)] * unit;
    out.dissipated_normal(i) = (x[WC(i)] - x[WR(i)]) * unit;
    out.dissipated_tangential(i) = x[DT(i)] * unit;
    work += x[WR(i)] - x[WC(i)] - x[DT(i)];
  }
  out.energy_change = work * unit;
  // The invariants' drift, as a velocity relative to v_s: energies over the summed percussion.
  const Eigen::Map<const Eigen::VectorXd> Ps(x.data(), r_);
  const double exact_work = D_A_.dot(Ps) + 0.5 * Ps.dot(G_ * Ps);
  const double p_sum = std::max(Ps.cwiseAbs().sum(), std::numeric_limits<double>::min());
  out.error_estimate =
      std::max(options_.tolerance, std::max(drift_, std::fabs(exact_work - work)) / p_sum);
  return out;
}

template <class Stepper>
double Run::locate(const Stepper& stepper, int which, double t0, double t1, State& xm) {
  // Regula falsi with Illinois' halving on the margin, bisection where it stalls; the answer is
  // the bracket's end where the condition holds, so that the phase changes there.
  const int i = which / kKinds, k = which % kKinds;
  auto at = [&](double t) {
    stepper.calc_state(t, xm);
    evaluate(xm);
    return margin(i, k, xm);
  };
  double lo = t0, hi = t1, m_lo = at(lo), m_hi = at(hi);
  int side = 0;
  for (int it = 0; it < 100 && hi - lo > 4e-16 * std::max(std::fabs(hi), 1.0); ++it) {
    double t = m_lo != m_hi ? hi - m_hi * (hi - lo) / (m_hi - m_lo) : lo + 0.5 * (hi - lo);
    if (!(t > lo && t < hi) || it % 8 == 7) t = lo + 0.5 * (hi - lo);
    const double m = at(t);
    if (is_met(k, m)) {
      hi = t, m_hi = m;
      if (side == -1) m_lo *= 0.5;
      side = -1;
    } else {
      lo = t, m_lo = m;
      if (side == 1) m_hi *= 0.5;
      side = 1;
    }
  }
  return hi;
}

LzbAnswer Run::run() {
  // Scaled problem: velocities in units of v_s = max |D_A|, percussions in units of v_s / g with
  // g the largest diagonal entry of G. Time is not a variable of the answer: a common unit T of
  // time makes every force a common factor, taken so that the largest scaled stiffness is 1.
  v_s_ = D_A_.size() ? D_A_.cwiseAbs().maxCoeff() : 0.0;
  const double g = G_.size() ? G_.diagonal().maxCoeff() : 0.0;
  State x(static_cast<std::size_t>(r_ + 4 * n_), 0.0);
  if (!(v_s_ > 0.0) || !(g > 0.0) || !std::isfinite(v_s_) || !std::isfinite(g)) {
    v_s_ = std::isfinite(v_s_) && v_s_ > 0.0 ? v_s_ : 1.0;
    P_s_ = 1.0;
    if (!(D_A_.head(n_).array() >= 0.0).all())
      return answer(x, "G or D_A is zero or not finite", false);
    return answer(x, "no contact approaches: no percussion", true);
  }
  P_s_ = v_s_ / g;
  G_ /= g;
  D_A_ /= v_s_;
  // K̂_i = K_i v_s^η_i T^(η_i+1) / P_s (docs: the force in units of P_s/T, δ in units of v_s T).
  K_.resize(n_);
  K_root_.resize(n_);
  double logT = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n_; ++i) {
    const double eta = c_[i].eta;
    logT = std::min(
        logT, (std::log(P_s_) - std::log(c_[i].stiffness) - eta * std::log(v_s_)) / (eta + 1.0));
  }
  for (int i = 0; i < n_; ++i) {
    const double eta = c_[i].eta;
    K_(i) = std::exp(std::log(c_[i].stiffness) + eta * std::log(v_s_) + (eta + 1.0) * logT -
                     std::log(P_s_));
    K_root_(i) = std::pow(K_(i), 1.0 / (eta + 1.0));
  }
  phase_.assign(static_cast<std::size_t>(n_), Phase::separated);
  slip_.assign(static_cast<std::size_t>(n_), 0.0);
  slip_floor_.assign(static_cast<std::size_t>(n_), -kVelocityFloor);
  holds_.assign(static_cast<std::size_t>(n_), 0);
  v_.resize(r_);
  F_.setZero(n_);
  rho_.setZero(n_);
  fT_.setZero(n_);
  lambda_.setZero(n_);
  met_.assign(static_cast<std::size_t>(kKinds * n_), 0);

  const double tol = std::max(options_.tolerance, 1e-14);
  auto stepper = odeint::make_dense_output(tol, tol, 0.1, odeint::runge_kutta_dopri5<State>());
  auto system = [this](const State& s, State& d, double /*tau*/) { rhs(s, d); };
  double tau = 0.0, dtau = 1e-3;
  State xm(x.size());
  int rounds = 0;  // restarts: events, changes of primary
  try {
    while (true) {
      if (++rounds > kMaxEvents)
        return answer(x, "too many phase changes (contacts chattering between phases)", false);
      if (!apply_transitions(x)) return answer(x, "the contacts' phases do not settle", false);
      if (primary_ < 0) {
        if (!choose_primary(x)) break;  // every contact apart, none approaching: the impact ends
        continue;                       // the new phases' transitions, then the integration
      }
      stepper.initialize(x, tau, dtau);
      bool restart = false;
      while (!restart) {
        if (++steps_ > options_.max_steps)
          return answer(x, "the integration took more steps than allowed", false);
        const auto [t0, t1] = stepper.do_step(system);
        const State& x1 = stepper.current_state();
        for (double value : x1)
          if (!std::isfinite(value)) return answer(x, "the integration diverged", false);
        if (!conditions(x1)) {
          x = x1;
          tau = t1;
          dtau = stepper.current_time_step();
          const double scale = rebalance(x);
          if (scale != 0.0) {
            dtau *= scale;
            restart = true;
          }
          continue;
        }
        // Locate the first event by bisection on the dense output, to the last bits of τ.
        const std::vector<unsigned char> met1 = met_;
        double first = t1;
        for (std::size_t k = 0; k < met1.size(); ++k) {
          if (!met1[k]) continue;
          if (first < t1) {  // met by an earlier event's time?
            stepper.calc_state(first, xm);
            evaluate(xm);
            if (!is_met(static_cast<int>(k) % kKinds,
                        margin(static_cast<int>(k) / kKinds, static_cast<int>(k) % kKinds, xm)))
              continue;
          }
          first = locate(stepper, static_cast<int>(k), t0, first, xm);
        }
        ++events_;
        stepper.calc_state(first, x);
        tau = first;
        dtau = std::max(stepper.current_time_step(), 1e-3 * (t1 - t0));
        restart = true;
      }
    }
  } catch (const std::exception&) {  // odeint's step size control gave up
    return answer(x, "the integration's step size control failed", false);
  }
  // Every contact is apart; none may still approach.
  evaluate(x);
  return answer(x, "every contact compressed and gave back its energy", true);
}

}  // namespace

LzbAnswer lzb_impact(const Eigen::Ref<const Eigen::MatrixXd>& G,
                     const Eigen::Ref<const Eigen::VectorXd>& D_A,
                     std::span<const LzbContact> contacts, const LzbOptions& options) {
  const int n = static_cast<int>(contacts.size());
  if (n == 0 || G.rows() != G.cols() || (G.rows() != n && G.rows() != 2 * n) ||
      D_A.size() != G.rows()) {
    LzbAnswer out;
    out.message = "G must be n x n or 2n x 2n and D_A hold one entry per row";
    return out;
  }
  Run run(G, D_A, contacts, options);
  return run.run();
}

}  // namespace fremond::detail
