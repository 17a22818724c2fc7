// Newton on the velocity-space problem of Frémond's law (docs/laws.md), for contacts whose rows
// outnumber the degrees of freedom:
//
//   minimise  F(u) = uᵀ M u + Σ_j φ_j(z_j),   z = D_A + Wᵀ u,   u = v − q̇_A = M⁻¹ W P / 2,
//
// a strongly convex function of n unknowns. Its gradient 2Mu + W φ'(z) vanishes exactly where
// P = −φ'(z) solves the law with no reaction, and its generalized Hessian 2M + W diag(φ'') Wᵀ is
// symmetric positive definite, however many rows there are.
//
// Why: in contact space the law has one unknown per row, and with more rows than degrees of
// freedom G = WᵀM⁻¹W is singular. Semismooth Newton's matrix there, J = (I − D) G/2 + D T, is then
// singular up to the diagonal D T, which a stiff potential makes small: on the plate lying flat on
// 32 contacts (3 dofs, p = 3) Newton stalls at a kink of ‖R‖ and the splitting needs thousands of
// sweeps (milliseconds), where velocity space takes 12 steps of 3 × 3 (tens of µs).
//
// φ'' is not part of a potential's interface; its prox derivative gives it: at x = z + τ φ'(z) the
// prox returns z, and its derivative there is 1/(1 + τ φ''(z)). A derivative 0 (a kink: p < 2 at
// z = 0, the edge of a dead zone with q < 2) is an infinite curvature, capped. The law's reaction
// (D_NE ≥ 0) and Coulomb's bound are not part of F: an answer that needs a reaction fails the
// law's own stopping test, and the driver goes on with the contact-space methods.
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "solvers/detail/fremond.hpp"

namespace fremond::detail {

namespace {

// The potential of row j: the normal law's, or the tangential one's (a law without Coulomb).
template <int N, int C>
const Potential& row_potential(const FremondRowsT<N, C>& rows, int j) {
  return rows.is_normal(j) ? rows.law->normal[rows.contact(j)]
                           : rows.law->tangential_potential[rows.contact(j)];
}

}  // namespace

template <int N, int C>
MethodOutcome velocity_space_newton(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows,
                                    typename FremondRowsT<N, C>::Rows& P,
                                    const SolverOptions& opt) {
  using Rows = typename FremondRowsT<N, C>::Rows;
  using Vec = VecT<N>;
  using Mat = MatT<N, N>;
  const auto& cs = *rows.cs;
  const int n = cs.dofs, r = cs.rows();
  MethodOutcome o;
  if (rows.coulomb || !rows.all_prox || r == 0) {
    o.status = SolverStatus::unsupported;
    o.message = "velocity-space Newton: Coulomb's bound, or a potential without a prox";
    return o;
  }
  const double target = opt.tolerance * cs.v_scale;
  // The law's curvature cap: a prox derivative below 1e-12 is read as 1e-12 (φ'' ≤ 1e12/τ).
  constexpr double kMinDerivative = 1e-12;
  // A fast path, with the contact-space methods behind it: the answers it reaches take fewer than
  // 30 steps; past that it is spending time on an answer that needs a reaction, or on extreme
  // data (p near 1, k from 1e-6 to 1e6).
  constexpr int kMaxIterations = 30;
  Rows z(r), s(r), h(r), zc(r), R(r), zt(r), st(r), zx(r), sx(r);
  Vec u(n), g(n), du(n), ut(n), ux(n);
  Mat H(n, n);
  // The start: u from the P given (u = M⁻¹ W P / 2) or u = 0 (no percussion), whichever has the
  // lower F. The decoupled guess, each row as if it held the body alone, overshoots by about the
  // number of rows that share a direction: on the plate with 32 contacts F is 1e6 times its value
  // at u = 0, which costs Newton 10 steps to come back.
  u = 0.5 * (cs.MinvW * P);
  // F at u, with z and φ'(z) into zz and ss; +∞ where a value is not finite.
  auto evaluate = [&](const Vec& uu, Rows& zz, Rows& ss) {
    zz.noalias() = cs.D_A + cs.W.transpose() * uu;
    double f = uu.dot(pb.M * uu);
    for (int j = 0; j < r; ++j) {
      const Potential& phi = row_potential(rows, j);
      f += phi.value(zz(j));
      ss(j) = phi.subgradient(zz(j));
    }
    return std::isfinite(f) && ss.allFinite() ? f : std::numeric_limits<double>::infinity();
  };
  double f = u.allFinite() ? evaluate(u, z, s) : std::numeric_limits<double>::infinity();
  {
    ut.setZero(n);
    const double f0 = evaluate(ut, zt, st);
    if (!(f <= f0)) {
      u = ut;
      z = zt;
      s = st;
      f = f0;
    }
  }
  // The first answer that passes the stopping test gets one more step (`polish`), kept if it
  // passes too: the test accepts 1e-13 of the velocities, and Newton's next step, quadratic
  // there, leaves rounding. Without it a flat bar dropped on both ends spins at 3e-14 of its speed
  // where contact space's Newton keeps it at 1e-15 (SimulationBar.AFlatDropHits…).
  bool polishing = false;
  Rows P_done;
  double residual_done = 0.0;
  int iterations_done = 0;
  auto done = [&]() {
    o.status = SolverStatus::converged;
    o.criterion = StopCriterion::residual;
    o.message =
        "semismooth Newton in velocity space converged (more contact rows than degrees of "
        "freedom)";
    if (polishing) {
      P = P_done;
      o.residual = residual_done;
      o.iterations = iterations_done;
    }
    return o;
  };
  // A failure ends the method, except after an answer passed the test: that answer stands.
  auto stop = [&](SolverStatus status, StopCriterion criterion, const char* message) {
    if (polishing) return done();
    o.status = status;
    o.criterion = criterion;
    o.message = message;
    return o;
  };
  double decrement = std::numeric_limits<double>::infinity();  // −slope of the last step
  for (int it = 0;; ++it) {
    o.iterations = it;
    if (!std::isfinite(f))
      return stop(SolverStatus::failed, StopCriterion::none,
                  "velocity-space Newton: the objective is not finite");
    // The law's own stopping test, on the percussions the velocities give: O(rows²) and a prox
    // per row, so only once Newton's decrement is small (at 1e-8 of F the next step is at
    // rounding), and on the start.
    P = -s;
    bool passes = false;
    if (it == 0 || polishing || decrement <= 1e-8 * f) {
      o.residual = rows.residual(P, zc, R);
      passes = rows.converged(P, R, target);
    }
    if (polishing) {
      if (passes) polishing = false;  // the polished answer stands
      return done();
    }
    if (passes) {
      polishing = true;
      P_done = P;
      residual_done = o.residual;
      iterations_done = it;
    }
    if (it >= std::min(opt.max_iterations, kMaxIterations))
      return stop(SolverStatus::max_iterations, StopCriterion::iterations,
                  "velocity-space Newton: iteration budget exhausted");
    // Gradient and generalized Hessian.
    g.noalias() = 2.0 * (pb.M * u) + cs.W * s;
    for (int j = 0; j < r; ++j) {
      const double tau = rows.tau(j);
      const Potential& phi = row_potential(rows, j);
      double d = 1.0;
      phi.prox(z(j) + tau * s(j), tau, &d);
      // A steep row (τφ'' beyond 1e12: the dead zone with k = 1e6 on a rotor of inertia 1e-6, τ =
      // G_jj/2 = 1.5e6) gives a derivative below the cap, and the capped φ'' is 7.5 times too
      // small: Newton creeps instead of converging. Read again with the step τd, at which τdφ'' ≈ 1
      // and the derivative is about ½, far from the cap. Only a kink (d = 0) keeps the cap.
      if (d > 0.0 && d < kMinDerivative) {
        const double t = tau * d;
        double d2 = 1.0;
        phi.prox(z(j) + t * s(j), t, &d2);
        if (d2 > kMinDerivative && d2 < 1.0) {
          h(j) = (1.0 - d2) / (d2 * t);
          continue;
        }
      }
      d = std::clamp(d, kMinDerivative, 1.0);
      h(j) = (1.0 - d) / (d * tau);
    }
    H = 2.0 * pb.M;
    for (int j = 0; j < r; ++j)
      if (h(j) != 0.0) H.noalias() += h(j) * cs.W.col(j) * cs.W.col(j).transpose();
    const Eigen::LLT<Mat> chol(H);
    if (chol.info() != Eigen::Success)
      return stop(SolverStatus::failed, StopCriterion::none,
                  "velocity-space Newton: the Hessian is not positive definite");
    du = chol.solve(-g);
    const double slope = g.dot(du);  // < 0: H is positive definite
    decrement = -slope;
    if (!du.allFinite() || !(slope < 0.0))
      return stop(SolverStatus::stalled, StopCriterion::step,
                  "velocity-space Newton: no descent direction (rounding)");
    // The unconstrained minimum reached (Newton's decrement at 1e-12 of F) with a contact
    // penetrating (D_NE < 0 beyond 1e-10 of the velocity scale): the answer needs a reaction,
    // which F does not hold, and the contact-space methods take over.
    if (-slope <= 1e-12 * f)
      for (int j = 0; j < cs.active; ++j)
        if (z(j) - rows.lower_bound(j) < -0.5e-10 * cs.v_scale)
          return stop(SolverStatus::stalled, StopCriterion::step,
                      "velocity-space Newton: the answer needs a reaction (D_NE < 0 without one)");
    // Armijo backtracking on F, which is convex: the full step is taken near the answer. There
    // the decrease F can show, ½|slope|, falls below the rounding of F itself (its terms are all
    // non-negative: about ε F), and the test would compare noise; the step is then judged by the
    // gradient's norm instead, which Newton's step reduces quadratically.
    const bool below_rounding =
        polishing || -slope <= 1e3 * std::numeric_limits<double>::epsilon() * f;
    // The gradient in M⁻¹'s norm |L⁻¹g| (M = LLᵀ), the dual of u's: in the Euclidean norm a light
    // rotor's component (M_θθ = 1e-6 of the translations') counts 1e6 times too little, and the
    // translations' rounding floor hid a rotation still far from converged.
    auto dual_norm = [&](Vec gg) {
      cs.llt.solve_lower_in_place(gg);
      return gg.norm();
    };
    const double gnorm = below_rounding ? dual_norm(g) : 0.0;
    double t = 1.0, ft = 0.0;
    bool accepted = false;
    for (int ls = 0; ls < 40; ++ls) {
      ut = u + t * du;
      ft = evaluate(ut, zt, st);
      if (below_rounding ? std::isfinite(ft) && dual_norm(2.0 * (pb.M * ut) + cs.W * st) < gnorm
                         : ft <= f + 1e-4 * t * slope) {
        accepted = true;
        break;
      }
      t *= 0.5;
    }
    if (!accepted)
      return stop(SolverStatus::stalled, StopCriterion::step,
                  "velocity-space Newton: the line search found no decrease (rounding)");
    // A full step far from the answer on a steep power row (p = 10: Newton shrinks z only by
    // (p − 2)/(p − 1) = 8/9 a step, 130 steps from z = 2.5e6) is extended while F keeps falling:
    // along the line F is convex, so the longest of the doubled steps that still lowers F is the
    // nearest of them to the minimum on the line. Only where the step gained more than Newton's
    // quadratic model foresees (½|slope|; a power row far out gains 0.58 to 0.64 of |slope| for
    // p from 3 to 50): near the answer F is quadratic to rounding, and the step is not retried.
    if (t == 1.0 && !below_rounding && f - ft > 0.55 * -slope) {
      for (double tx = 2.0; tx <= 1024.0; tx *= 2.0) {
        ux = u + tx * du;
        const double fx = evaluate(ux, zx, sx);
        if (!(fx < ft)) break;
        ut = ux;
        zt = zx;
        st = sx;
        ft = fx;
        t = tx;
      }
    }
    u = ut;
    z = zt;
    s = st;
    f = ft;
  }
}

#define FREMOND_INSTANTIATE(N, C)                                           \
  template MethodOutcome velocity_space_newton(const ImpactProblemT<N, C>&, \
                                               const FremondRowsT<N, C>&,   \
                                               FremondRowsT<N, C>::Rows&, const SolverOptions&);
FREMOND_INSTANTIATE(Dynamic, Dynamic)
FREMOND_INSTANTIATE(kSmallDofs, kSmallContacts)
#undef FREMOND_INSTANTIATE

}  // namespace fremond::detail
