// The iterative solvers of Frémond's law in contact space: semismooth Newton with a line search,
// and accelerated proximal iterations. Both solve R(P) = z − prox_{τψ}(z − τP) = 0 (fremond_rows).
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/detail/small_full_piv_lu.hpp"
#include "core/detail/small_lu.hpp"
#include "solvers/detail/fremond.hpp"

namespace fremond::detail {

namespace {
constexpr double kEps = std::numeric_limits<double>::epsilon();
}

// Newton's step solves J ΔP = −R with J = (I − D) G/2 + D T (+ the Coulomb coupling ∂R_T/∂P_N),
// D = diag(∂prox/∂x) ∈ [0,1], T = diag(τ). J is singular where the law leaves P undetermined (a
// flat bar sticking with both ends: two identical rows); then a solution of J ΔP = −R from a
// full-pivoting LU where that system is consistent, else a Levenberg–Marquardt step (JᵀJ + λI)ΔP =
// −JᵀR with λ = ‖R‖ (Yamashita–Fukushima).
template <int N, int C>
MethodOutcome semismooth_newton(const FremondRowsT<N, C>& rows,
                                typename FremondRowsT<N, C>::Rows& P, const SolverOptions& opt) {
  using Rows = typename FremondRowsT<N, C>::Rows;
  using RowMat = typename ContactSpaceT<N, C>::RowMat;
  const auto& cs = *rows.cs;
  const int r = cs.rows();
  MethodOutcome o;
  Rows z(r), R(r), Pt(r), zt(r), Rt(r), dP(r), newton_dP(r);
  // The prox derivatives of the residual at P (d, dydb) and at the trial point (dt, dydbt): the
  // Jacobian is formed from those of the accepted point, not from r more prox calls (the flat bar
  // under the dead zone: 4 of the 12 prox calls of a step).
  const bool slopes = rows.all_prox;
  Rows d(r), dydb(r), dt(r), dydbt(r);
  auto evaluate = [&](const Rows& at, Rows& z_at, Rows& R_at, Rows& d_at, Rows& dydb_at) {
    return rows.residual(at, z_at, R_at, slopes ? &d_at : nullptr, slopes ? &dydb_at : nullptr);
  };
  RowMat J(r, r);
  SmallLU<ContactSpaceT<N, C>::kMaxRows> small_lu;  // used for the stack-stored sizes only
  // The same for the singular Newton systems (small_full_piv_lu.hpp); a placeholder size otherwise.
  SmallFullPivLU<N != Dynamic ? ContactSpaceT<N, C>::kMaxRows : 1> small_full_lu;
  double nr = evaluate(P, z, R, d, dydb);
  const double target = opt.tolerance * cs.v_scale;
  double nr_10_ago = nr;  // Newton that has not halved the residual in 10 steps is stuck at a
                          // kink (a stationary point of ‖R‖² that is not a solution): stop, so
                          // the driver falls back to the splitting, which cannot stall there.
  for (int it = 0;; ++it) {
    o.iterations = it;
    o.residual = nr;
    if (!std::isfinite(nr)) {
      o.status = SolverStatus::failed;
      o.message = "semismooth Newton: the residual is not finite";
      return o;
    }
    if (rows.converged(P, R, target)) {
      o.status = SolverStatus::converged;
      o.criterion = StopCriterion::residual;
      o.message = "semismooth Newton converged";
      return o;
    }
    if (it > 0 && it % 10 == 0) {
      if (nr > 0.5 * nr_10_ago) {
        o.status = SolverStatus::stalled;
        o.criterion = StopCriterion::step;
        o.message = "semismooth Newton: no progress in 10 iterations (a kink of the residual)";
        return o;
      }
      nr_10_ago = nr;
    }
    if (it >= opt.max_iterations) {
      o.status = SolverStatus::max_iterations;
      o.criterion = StopCriterion::iterations;
      o.message = "semismooth Newton: iteration budget exhausted";
      return o;
    }
    if (slopes)
      rows.jacobian_from_slopes(P, d, dydb, J);
    else
      rows.jacobian(z, P, J);
    // Directions in order: Newton (LU), then Levenberg–Marquardt with a damping that grows tenfold
    // each time the line search finds no decrease (towards steepest descent on θ = ½‖R‖²).
    const double theta0 = 0.5 * R.squaredNorm();
    double nrt = nr;
    bool accepted = false;
    // The Newton direction where J is well conditioned (rcond > 1e-12).
    bool have_newton = false;
    if constexpr (N != Dynamic) {
      small_lu.compute(J);
      if (small_lu.well_conditioned(1e-12)) {
        small_lu.solve(-R, newton_dP);
        have_newton = true;
      }
    } else {
      Eigen::PartialPivLU<RowMat> lu(J);
      if (lu.rcond() > 1e-12) {
        newton_dP = lu.solve(-R);
        have_newton = true;
      }
    }
    // J singular but J ΔP = −R consistent (two contacts sticking with one tangent: equal rows with
    // equal residuals): a solution from a rank-revealing LU is Newton's step on the rows J has, and
    // keeps its quadratic convergence. Levenberg–Marquardt, damped by ‖R‖ far from the answer,
    // crawls there (the plate touching with four contacts under Coulomb: 30 steps to a kink, then
    // the fallbacks, against 6 steps). An inconsistent system is left to Levenberg–Marquardt.
    if (!have_newton) {
      if constexpr (N != Dynamic) {
        small_full_lu.compute(J);
        small_full_lu.solve(-R, newton_dP);
      } else {
        const Eigen::FullPivLU<RowMat> full(J);
        newton_dP = full.solve(-R);
      }
      const double miss = (J * newton_dP + R).cwiseAbs().maxCoeff();
      have_newton = newton_dP.allFinite() && miss <= 1e-12 * R.cwiseAbs().maxCoeff();
    }
    // The Levenberg–Marquardt data, formed only when the Newton step is not taken.
    RowMat JtJ;
    Rows JtR;
    double lambda = 0.0;
    bool lm_ready = false;
    for (int attempt = 0; attempt < 12 && !accepted; ++attempt) {
      bool ok = false;
      if (attempt == 0 && have_newton) {
        dP = newton_dP;
        ok = dP.allFinite();
      }
      if (!ok) {
        if (!lm_ready) {
          JtJ.noalias() = J.transpose().lazyProduct(J);
          JtR.noalias() = J.transpose().lazyProduct(R);
          const double jscale =
              std::max(JtJ.diagonal().maxCoeff(), std::numeric_limits<double>::min());
          // λ relative to JᵀJ: ‖R‖/v_scale is dimensionless, so the damping does not depend on
          // the units of P and D (λ = ‖R‖ itself, a velocity beside JᵀJ in
          // velocity²/percussion², damped steps on rows with G_jj ~ 1e-6 a millionfold: Newton
          // crawled, halving its residual every 10 steps).
          lambda = jscale * std::max(nr / cs.v_scale, kEps);
          lm_ready = true;
        }
        RowMat A = JtJ;
        A.diagonal().array() += lambda;
        dP = A.llt().solve(-JtR);
        lambda *= 10.0;
        if (!dP.allFinite()) continue;
      }
      // Armijo backtracking on θ.
      double t = 1.0;
      for (int ls = 0; ls < 30; ++ls) {
        Pt = P + t * dP;
        nrt = evaluate(Pt, zt, Rt, dt, dydbt);
        if (0.5 * Rt.squaredNorm() <= (1.0 - 1e-4 * t) * theta0) {
          accepted = true;
          break;
        }
        t *= 0.5;
      }
    }
    if (!accepted) {
      o.status = SolverStatus::stalled;
      o.criterion = StopCriterion::step;
      o.message = "semismooth Newton: the line search found no decrease";
      return o;
    }
    P = Pt;
    z = zt;
    R = Rt;
    d.swap(dt);
    dydb.swap(dydbt);
    nr = nrt;
  }
}

// Proximal iterations by splitting: a projected Gauss–Seidel sweep over the rows, each row solved
// exactly by its own prox with the others fixed (the nonsmooth Gauss–Seidel of Moreau and Jean, as
// in Siconos's NSGS). With x_j = z_j − G_jj P_j/2 the row alone reads z_j = x_j + G_jj P_j/2, −P_j
// ∈ ∂ψ_j(z_j), so z_j = prox_{τ_j ψ_j}(x_j) with τ_j = G_jj/2 and P_j = (z_j − x_j)/τ_j. Normal
// rows come first in each sweep, so a Coulomb row sees the bound μ|P_N| of the same sweep. It needs
// only the prox, works with a singular G, and converges linearly where Newton may not (a poor
// start, kinks everywhere); its cost per sweep is O(rows²).
template <int N, int C>
MethodOutcome proximal_iterations(const FremondRowsT<N, C>& rows,
                                  typename FremondRowsT<N, C>::Rows& P, const SolverOptions& opt) {
  using Rows = typename FremondRowsT<N, C>::Rows;
  const auto& cs = *rows.cs;
  const int r = cs.rows();
  MethodOutcome o;
  Rows z(r), R(r);
  rows.mean_velocity(P, z);
  const double gmax = cs.G.diagonal().maxCoeff();
  const double target = opt.tolerance * cs.v_scale;
  double best = std::numeric_limits<double>::infinity();
  double checkpoint = 0.0;  // the residual 1000 sweeps ago
  int since_best = 0;
  for (int it = 1; it <= opt.max_proximal_iterations; ++it) {
    for (int j = 0; j < r; ++j) {
      const double g = cs.G(j, j);
      if (!(g > 1e-14 * gmax)) continue;  // a row that cannot move keeps its percussion
      rows.gauss_seidel_step(j, P, z);
    }
    const double nr = rows.residual(P, z, R);
    o.iterations = it;
    o.residual = nr;
    if (!std::isfinite(nr)) {
      o.status = SolverStatus::failed;
      o.message = "proximal iterations: the iterates diverged";
      return o;
    }
    if (rows.converged(P, R, target)) {
      o.status = SolverStatus::converged;
      o.criterion = StopCriterion::residual;
      o.message = "proximal iterations converged";
      return o;
    }
    // Too slow to finish: every 1000 sweeps, the linear rate ρ observed over them predicts the
    // sweeps still needed, log(target/‖R‖)/log ρ; when they exceed the budget, stop now rather
    // than spend it (seconds on a q ≈ 1 dead zone at ρ = 1 − 1e-4) to end above tolerance anyway.
    if (it % 1000 == 0) {
      if (checkpoint > 0.0 && nr > target && nr < checkpoint) {
        const double log_rate = std::log(nr / checkpoint) / 1000.0;  // < 0
        const double needed = std::log(target / nr) / log_rate;
        if (it + needed > opt.max_proximal_iterations) {
          o.status = SolverStatus::max_iterations;
          o.criterion = StopCriterion::iterations;
          o.message =
              "proximal iterations: at the observed linear rate the iteration budget "
              "cannot reach the tolerance";
          return o;
        }
      }
      checkpoint = nr;
    }
    // Stagnation: no new best residual for many sweeps (rounding reached, or a cycle).
    if (nr < 0.999 * best) {
      best = nr;
      since_best = 0;
    } else if (++since_best > 1000) {
      o.status = SolverStatus::stalled;
      o.criterion = StopCriterion::step;
      o.message = "proximal iterations: no progress in 1000 sweeps";
      return o;
    }
  }
  o.status = SolverStatus::max_iterations;
  o.criterion = StopCriterion::iterations;
  o.message = "proximal iterations: iteration budget exhausted";
  return o;
}

#define FREMOND_INSTANTIATE(N, C)                                                                  \
  template MethodOutcome semismooth_newton(const FremondRowsT<N, C>&, FremondRowsT<N, C>::Rows&,   \
                                           const SolverOptions&);                                  \
  template MethodOutcome proximal_iterations(const FremondRowsT<N, C>&, FremondRowsT<N, C>::Rows&, \
                                             const SolverOptions&);
FREMOND_INSTANTIATE(Dynamic, Dynamic)
FREMOND_INSTANTIATE(kSmallDofs, kSmallContacts)
#undef FREMOND_INSTANTIATE

}  // namespace fremond::detail
