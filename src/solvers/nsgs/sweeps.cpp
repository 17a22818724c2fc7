// Nonsmooth Gauss–Seidel with the mode Newton after it (sweeps.hpp, docs/sparse.md).
#include "solvers/nsgs/sweeps.hpp"

#include <cmath>
#include <limits>
#include <utility>

namespace fremond::detail {

namespace {
// Stalled: this many sweeps without a 1 % gain of the residual. Piles of disks plateau for
// thousands of sweeps before converging (703 contacts: 30,000 sweeps).
constexpr int kStallSweeps = 8192;
// Steps of one run of the mode Newton (mode_newton.hpp); a run that has the modes right ends in
// a few.
constexpr int kModeNewtonSteps = 12;
// A rigid body on a few contacts: the Newton steps factor its n x n velocities' system, about the
// cost of a few sweeps, and from 8 sweeps on they end the plates' solves (8 to 32 contacts: 8-15 %
// fewer instructions than the first measure at 16). Elsewhere that early run fails more often
// than it ends (random bodies of 12-30 dofs: 10-20 % more).
constexpr int kEarlyMeasure = 8;
// Anderson mixing is dropped after this many sweeps without halving the residual: where it
// helps (beds, piles of a few hundred contacts: 2-10 times fewer sweeps) it gains that much at
// every measure; where the contacts' modes keep changing (tall piles with friction) it stalls,
// and the sweeps it made (128 to 400 on the problems of docs/sparse.md) are lost.
constexpr int kMixingPatience = 128;
}  // namespace

SweepOutcome solve_by_sweeps(const Layout& L, const Eigen::VectorXd& D_A, Eigen::VectorXd& P,
                             const SweepOptions& options, AttemptStart first, SolverReport& log,
                             SweepWorkspace& ws) {
  const double target = options.tolerance * L.v_scale;
  // Within tolerance, or each contact within the rounding of its rows.
  auto meets = [target](const Measure& x) { return x.residual <= target || x.excess <= target; };
  Measure& m = ws.measure;  // valid once `measured`
  bool measured = false;
  Eigen::VectorXd& velocities = ws.velocities;
  int sweeps = 0, newton_steps = 0, checks = 0, last_newton = 0, best_at = 0;
  double best = std::numeric_limits<double>::infinity();
  // The residual costs a sweep: measured every 64 sweeps, every 16 on a few contacts, where a
  // sweep is cheap beside the Newton run it may start.
  const bool few = L.contacts <= 64;
  const int every = few ? 16 : 64;
  // The first Newton run: at the first measure on a few contacts, whose factorisation costs a few
  // sweeps; at the second on more, where easy problems end in the sweeps before it.
  const int first_run = few ? 1 : 2;
  const bool early = few && L.has_velocity_factors();
  bool by_newton = false;
  AttemptStart from = first;
  // Each pair of sweeps (forward, backward) is the map P ↦ g(P) that Anderson mixing accelerates.
  bool mixing = options.acceleration && !few;
  double mixing_best = std::numeric_limits<double>::infinity();
  int mixing_best_at = 0;
  if (mixing) {
    ws.start = P;
    ws.mixing.reset();
  }
  // The mixed run recorded as stalled at `residual`; the plain sweeps from the start, as if they
  // were the first.
  auto drop_mixing = [&](double residual) {
    log.record(SolverMethod::nsgs, from, SolverStatus::stalled, residual / L.v_scale);
    mixing = false;
    P = ws.start;
    from = first;
    best = std::numeric_limits<double>::infinity();
    best_at = sweeps;
    checks = last_newton = 0;  // the Newton runs at the same measures as a plain solve's
  };
  SweepOutcome out;
  out.message = "the sweep budget (max_sweeps) ran out with the residual above tolerance";
  auto converge = [&](bool newton) {
    by_newton = newton;
    out.status = SolverStatus::converged;
    out.criterion = m.residual <= target ? StopCriterion::residual : StopCriterion::rounding;
    out.message = m.residual <= target
                      ? "the residual is within tolerance"
                      : "each contact's residual is within the rounding of its velocities";
  };
  // A sweep's largest velocity change bounds what the next can still move; the residual is
  // measured when that change is small, and every `every` sweeps to see a stall.
  while (sweeps < options.max_sweeps) {
    if (mixing && sweeps % 2 == 0) ws.input = P;
    // Forward, then backward: a blow crosses a pile in one sweep either way.
    const double change = sweep(L, D_A, P, sweeps % 2 == 1, velocities);
    ++sweeps;
    // P ↦ the mix, after the residual is measured at the pair's own output.
    auto next_input = [&] {
      if (mixing && sweeps % 2 == 0) ws.mixing.mix(ws.input, P);
    };
    if (!std::isfinite(change) && mixing) {
      drop_mixing(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    if (!std::isfinite(change)) {
      out.status = SolverStatus::failed;
      out.criterion = StopCriterion::none;
      out.message = "the sweeps produced non-finite percussions";
      break;
    }
    if (change > target && sweeps % every != 0 && !(early && sweeps == kEarlyMeasure)) {
      next_input();
      continue;
    }
    measure(L, D_A, P, m);
    measured = true;
    if (meets(m)) {
      converge(false);
      break;
    }
    // From `first_run` on, the mode Newton tries to finish from the sweeps' point, at measures
    // ever further apart (doubling) so that it costs a fraction of the sweeps: its steps do not
    // grow with the pile, the sweeps do. A run that does not converge is dropped, and the sweeps
    // go on from their own point.
    ++checks;
    if (options.newton_polish && checks >= first_run && checks >= 2 * last_newton) {
      last_newton = checks;
      log.record(SolverMethod::nsgs, from, SolverStatus::stalled, m.residual / L.v_scale);
      from = AttemptStart::sweeps_end;
      Eigen::VectorXd& trial = ws.trial;
      Measure& trial_m = ws.trial_measure;
      trial = P;
      trial_m = m;
      const auto o = mode_newton(L, D_A, trial, trial_m, target, kModeNewtonSteps, ws.newton);
      newton_steps += o.steps;
      // Normal percussions stay ≥ 0, as the sweeps keep them: a run's negative one (a wrong mode
      // within the tolerance) is set to 0 and the residual measured again.
      bool converged = o.converged;
      if (converged) {
        bool clipped = false;
        for (int i = 0; i < L.contacts; ++i)
          if (trial(L.step * i) < 0.0) {
            trial(L.step * i) = 0.0;
            clipped = true;
          }
        if (clipped) {
          measure(L, D_A, trial, trial_m);
          converged = meets(trial_m);
        }
      }
      log.record(SolverMethod::semismooth_newton, AttemptStart::sweeps_end,
                 converged ? SolverStatus::converged : SolverStatus::stalled,
                 trial_m.residual / L.v_scale);
      if (converged) {
        P.swap(trial);
        std::swap(m, trial_m);
        converge(true);
        break;
      }
    }
    if (mixing) {
      if (m.residual < 0.5 * mixing_best) {
        mixing_best = m.residual;
        mixing_best_at = sweeps;
      } else if (sweeps - mixing_best_at >= kMixingPatience) {
        drop_mixing(m.residual);
        continue;
      }
    }
    next_input();
    if (m.residual < 0.99 * best) {
      best = m.residual;
      best_at = sweeps;
    } else if (sweeps - best_at >= kStallSweeps) {
      // Stalled within what the data's own digits leave undetermined: as exact as the data.
      if (L.has_data_rounding() && m.data_excess <= target) {
        out.status = SolverStatus::converged;
        out.criterion = StopCriterion::data;
        out.message =
            "each contact's residual is within the rounding of the problem's numbers as given "
            "(G_rounding, D_A_rounding); the sweeps no longer reduce it";
        break;
      }
      out.status = SolverStatus::stalled;
      out.criterion = StopCriterion::step;
      out.message = "the sweeps no longer reduce the residual";
      break;
    }
  }
  if (!measured || out.status == SolverStatus::max_iterations) measure(L, D_A, P, m);
  out.iterations = sweeps + newton_steps;
  out.method = by_newton ? SolverMethod::semismooth_newton : SolverMethod::nsgs;
  if (!by_newton) log.record(SolverMethod::nsgs, from, out.status, m.residual / L.v_scale);
  return out;
}

}  // namespace fremond::detail
