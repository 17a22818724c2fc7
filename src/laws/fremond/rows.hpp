#pragma once
// Frémond's law row by row in contact space (docs/laws.md), shared by every Frémond solver and by
// law_residual: one residual for the law.
//
// With z = D_A + G P/2 (the mean velocity, paper eq. 21) each row j obeys −P_j ∈ ∂ψ_j(z_j):
//  - normal rows: ψ = φ_N + I_{[D_NA/2, ∞)}; the indicator is the reaction N_{R+}(D_NE) (eq. 16)
//    written on z since D_NE = 2 z_N − D_NA. In one dimension prox_{τψ} = max(prox_{τφ_N}, D_NA/2).
//  - tangential rows: ψ = φ_T (viscous, eq. 25), or b|·| with b = μ|P_N| (Coulomb on the mean
//    tangential velocity, quasi-variational: b depends on the answer).
// The inclusion is equivalent to the natural-map equation R_j = z_j − prox_{τ_j ψ_j}(z_j − τ_j P_j)
// = 0 for any τ_j > 0. We take τ_j = G_jj/2, the row's own compliance: for a decoupled row the
// map P ↦ z − τP is then constant and the equation is solved by one prox.
#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_space/contact_space.hpp"
#include "fremond/laws/impact_law.hpp"

namespace fremond::detail {

/// The prox step of a row with Delassus entry g, G_max the largest: g/2, or G_max/2 for a row that
/// moves no velocity (g ≤ 1e-14 G_max). Shared by the stopping test and the certificate.
inline double row_tau(double g, double g_max) {
  return g > 1e-14 * g_max ? 0.5 * g : (g_max > 0.0 ? 0.5 * g_max : 1.0);
}

/// The rounding floor at which the stopping test accepts a row:
/// min(16ε (|D_A,j| + ½Σ_k |G_jk P_k| + τ_j |P_j|), 1e-6 v_scale), with abs_GP = Σ_k |G_jk P_k|.
/// The cap: percussions so large that a row cannot be resolved better than that (P_N = −P_T =
/// 1e23 on W_T = W_N, residual 1.0) are no answer in double precision, whatever their rounding.
inline double row_rounding_floor(double D_A, double abs_GP, double tau, double P, double v_scale) {
  const double eps16 = 16.0 * std::numeric_limits<double>::epsilon();
  return std::min(eps16 * (std::fabs(D_A) + 0.5 * abs_GP + tau * std::fabs(P)), 1e-6 * v_scale);
}

template <int N, int C>
struct FremondRowsT {
  using CS = ContactSpaceT<N, C>;
  using Rows = typename CS::Rows;

  const CS* cs = nullptr;
  const FremondLaw* law = nullptr;
  Rows tau;     ///< prox step per row
  Rows weight;  ///< τ_max/τ_j ≥ 1: a row's residual R_j = τ_j·(percussion error), so the weight
                ///< measures every row's percussion error on the same scale
  bool coulomb = false;
  bool all_prox = true;  ///< every potential has a prox (else those rows use subgradients)
  /// Every potential is quadratic (a prox step is then linear): names the exact method's answer
  /// closed_form rather than scalar_newton.
  bool all_quadratic = true;
  /// Coulomb's tangential modes held fixed, one per active contact (the enumeration of modes):
  /// 0 sticks (z_T = 0, P_T free), +1 slides forwards (P_T = −μ|P_N|), −1 backwards
  /// (P_T = μ|P_N|). Each mode makes its rows smooth; nullptr: Coulomb's law itself.
  const signed char* fixed_modes = nullptr;
  /// With fixed_modes: the sign σ = ±1 of each contact's P_N held fixed as well, so that the bound
  /// μ|P_N| is the linear μσP_N. Newton on a sliding mode otherwise meets the kink of |P_N| at 0
  /// and can stop there (two contacts, one pulling with P_N = −0.76 and sliding); σ = −1 is the
  /// pull of Frémond's two-sided normal law (docs/laws.md).
  /// nullptr: the sign of P_N itself.
  const signed char* fixed_signs = nullptr;
  /// With fixed_modes: each contact's normal row held in one branch of its law too, 0 the law's
  /// own (the power law's prox, then the reaction's bound D_NE ≥ 0), 1 the power law alone (no
  /// reaction), 2 the reaction active (D_NE = 0, P_N free). Each branch is smooth where the law's
  /// own row has the kink of the bound, at which Newton can stop short of an answer (two contacts,
  /// one sliding with its reaction active: stopped at P_N = 2e-8 where the answer has P_N = 0.38).
  /// nullptr: 0.
  const signed char* fixed_normal = nullptr;
  /// The last prox of the normal potential of each normal row at the row's own step, with its
  /// argument (NaN: none yet): the reaction split asks prox(z − τP) < D_NA/2 of the answer, which
  /// the residual that certified it has just computed (a third of the viscous bar's prox calls).
  /// An exact memo: the same argument gives the same bits.
  mutable Rows last_x, last_y;

  void init(const CS& space, const FremondLaw& l) {
    cs = &space;
    law = &l;
    coulomb = l.uses_coulomb() && space.tangential;
    // One pass over the law's potentials, the contacts that take no part included: what the law
    // can do does not depend on which contacts touch.
    all_prox = all_quadratic = true;
    auto take = [&](const Potential& p) {
      const PotentialCapabilities cap = p.capabilities();
      all_prox = all_prox && cap.prox;
      all_quadratic = all_quadratic && cap.quadratic;
    };
    for (const auto& p : l.normal.potentials) take(*p);
    if (l.has_tangential_potential())
      for (const auto& p : l.tangential_potential.potentials) take(*p);
    const int r = space.rows();
    tau.resize(r);
    double gmax = 0.0;
    for (int j = 0; j < r; ++j) gmax = std::max(gmax, space.G(j, j));
    // τ_j from G twice, first for the largest, then for τ and the weights together: the weights
    // from τ just stored entry by entry would be reloaded two at a time, a store-forwarding stall
    // of 2 % of the bar's whole law stage.
    double tmax = r ? 0.0 : 1.0;
    for (int j = 0; j < r; ++j) tmax = std::max(tmax, row_tau(space.G(j, j), gmax));
    weight.resize(r);
    for (int j = 0; j < r; ++j) {
      const double t = row_tau(space.G(j, j), gmax);
      tau(j) = t;
      weight(j) = tmax / t;
    }
    last_x.resize(space.active);
    last_y.resize(space.active);
    for (int k = 0; k < space.active; ++k) last_x(k) = std::numeric_limits<double>::quiet_NaN();
  }

  /// prox_{τ_k φ_N}(x) of normal row k at its own step, without the reaction's bound: from the
  /// memo where x is its argument.
  double normal_prox(int k, double x) const {
    if (x == last_x(k)) return last_y(k);
    return law->normal[contact(k)].prox(x, tau(k));
  }

  int active() const { return cs->active; }
  bool is_normal(int j) const { return j < cs->active; }
  int contact(int j) const { return cs->index(is_normal(j) ? j : j - cs->active); }
  /// Lower bound of a normal row: z_N ≥ D_NA/2 ⇔ D_NE ≥ 0.
  double lower_bound(int j) const { return 0.5 * cs->D_A(j); }

  /// prox_{τ_j ψ_j}(x) with the row's own step τ_j; see prox_with_step.
  double prox(int j, double x, double b, double* d = nullptr, double* dydb = nullptr) const {
    return prox_with_step(j, x, b, tau(j), d, dydb);
  }

  /// prox_{t ψ_j}(x); `d` receives ∂y/∂x, `dydb` (Coulomb rows) ∂y/∂b; b is μ|P_N| for Coulomb.
  double prox_with_step(int j, double x, double b, double t, double* d = nullptr,
                        double* dydb = nullptr) const {
    if (dydb) *dydb = 0.0;
    if (!std::isfinite(x) || !std::isfinite(b)) {  // a diverging iterate: report, never throw
      if (d) *d = 0.0;
      return std::numeric_limits<double>::quiet_NaN();
    }
    if (is_normal(j)) {
      const int branch = fixed_normal ? fixed_normal[j] : 0;
      if (branch == 2) {
        if (d) *d = 0.0;
        return lower_bound(j);
      }
      const double y = law->normal[contact(j)].prox(x, t, d);
      if (t == tau(j)) {
        last_x(j) = x;
        last_y(j) = y;
      }
      if (branch == 1) return y;
      const double lb = lower_bound(j);
      if (y < lb) {
        if (d) *d = 0.0;
        return lb;
      }
      return y;
    }
    if (coulomb && fixed_modes) {  // prox of the mode's own potential: {0}, or ±b·z linear
      const int sign = fixed_modes[j - cs->active];
      if (d) *d = sign == 0 ? 0.0 : 1.0;
      if (sign == 0) return 0.0;
      if (dydb) *dydb = -t * sign;
      return x - sign * t * b;
    }
    if (coulomb) {
      const double th = t * b;  // soft thresholding at τb
      if (std::fabs(x) <= th) {
        if (d) *d = 0.0;
        return 0.0;
      }
      if (d) *d = 1.0;
      if (dydb) *dydb = -t * (x > 0.0 ? 1.0 : -1.0);
      return x - std::copysign(th, x);
    }
    return law->tangential_potential[contact(j)].prox(x, t, d);
  }

  /// The Coulomb bound of tangential row j from the normal percussions P.
  double bound(int j, const Rows& P) const {
    if (!coulomb || is_normal(j)) return 0.0;
    const double pn = P(j - cs->active);
    return law->mu[contact(j)] * (fixed_signs ? fixed_signs[j - cs->active] * pn : std::fabs(pn));
  }

  /// ∂bound/∂P_N of tangential row j (Newton's Jacobian): μ times the sign of P_N, or σ.
  double bound_slope(int j, const Rows& P) const {
    const int k = j - cs->active;
    return law->mu[contact(j)] * (fixed_signs ? fixed_signs[k] : (P(k) >= 0.0 ? 1.0 : -1.0));
  }

  /// The generalized Jacobian of R(P) = z − prox(z − τP) at P, z = D_A + G P/2 its mean
  /// velocity: J = (I − D) G/2 + D T, with D = diag(∂prox/∂x) ∈ [0, 1] and T = diag(τ), plus the
  /// Coulomb coupling ∂R_T/∂P_N of a sliding row (its bound μ|P_N|). Semismooth Newton's matrix,
  /// and the refinement's.
  template <class RowMat>
  void jacobian(const Rows& z, const Rows& P, RowMat& J) const {
    const int r = cs->rows();
    Rows d = Rows::Zero(r), dydb = Rows::Zero(r);
    for (int j = 0; j < r; ++j) prox(j, z(j) - tau(j) * P(j), bound(j, P), &d(j), &dydb(j));
    jacobian_from_slopes(P, d, dydb, J);
  }

  /// The same J from the prox derivatives d = ∂prox/∂x and dydb = ∂prox/∂b of every row at P, as
  /// residual() gives them: Newton takes them from the residual it evaluated at its
  /// point, instead of one more prox per row for the Jacobian.
  template <class RowMat>
  void jacobian_from_slopes(const Rows& P, const Rows& d, const Rows& dydb, RowMat& J) const {
    const int r = cs->rows(), a = cs->active;
    J.resize(r, r);
    for (int j = 0; j < r; ++j) {
      const double dj = d(j);
      const double c = 0.5 * (1.0 - dj);
      for (int k = 0; k < r; ++k) J(j, k) = c * cs->G(j, k);
      J(j, j) += dj * tau(j);
      // j − a: the normal row of the same contact.
      if (dydb(j) != 0.0) J(j, j - a) -= dydb(j) * bound_slope(j, P);
    }
  }

  /// Row j solved exactly with the others held (one nonsmooth Gauss–Seidel step): with
  /// x = z_j − G_jj P_j/2, z_j = prox(x) and P_j = (z_j − x)/τ_j. P_j and z move by the change,
  /// which is returned. The splitting's sweep, the final sweep after Newton and the tangential
  /// sweeps of the split of undetermined normal percussions.
  double gauss_seidel_step(int j, Rows& P, Rows& z) const {
    const double g = cs->G(j, j);
    const double x = z(j) - 0.5 * g * P(j);
    const double dP = (prox(j, x, bound(j, P)) - x) / tau(j) - P(j);
    if (dP != 0.0) {
      P(j) += dP;
      z.noalias() += (0.5 * dP) * cs->G.col(j);
    }
    return dP;
  }

  /// z = D_A + G P / 2. A hand loop for the stack-stored sizes (≤ 8 rows), where Eigen's
  /// dynamic-size matrix-vector product costs more in dispatch than in arithmetic.
  void mean_velocity(const Rows& P, Rows& z) const {
    if constexpr (N != Dynamic) {
      // Fused (z = D_A + ½ G P in one pass, no temporary): it runs at every Newton step.
      const int r = cs->rows();
      z.resize(r);
      for (int j = 0; j < r; ++j) {
        double s = 0.0;
        for (int k = 0; k < r; ++k) s += cs->G(j, k) * P(k);
        z(j) = cs->D_A(j) + 0.5 * s;
      }
    } else {
      z.noalias() = cs->D_A + 0.5 * (cs->G * P);
    }
  }

  /// R = z − prox(z − τP); returns the weighted norm max_j weight_j |R_j|. With `d` and `dydb`
  /// (only where every potential has a prox), every row's prox derivatives at P as well, for
  /// jacobian_from_slopes: the same prox calls, so the same R to the last bit.
  double residual(const Rows& P, Rows& z, Rows& R, Rows* d = nullptr, Rows* dydb = nullptr) const {
    mean_velocity(P, z);
    return residual_at(P, z, R, d, dydb);
  }

  /// R and its weighted norm as residual(), with the mean velocity z given (the refinement takes
  /// it from the velocities themselves).
  double residual_at(const Rows& P, const Rows& z, Rows& R, Rows* d = nullptr,
                     Rows* dydb = nullptr) const {
    const int r = cs->rows();
    R.resize(r);
    if (d) {
      d->setZero(r);
      dydb->setZero(r);
    }
    double m = 0.0;
    for (int j = 0; j < r; ++j) {
      R(j) = d ? z(j) - prox(j, z(j) - tau(j) * P(j), bound(j, P), &(*d)(j), &(*dydb)(j))
               : row_residual(j, z(j), P);
      if (!std::isfinite(R(j))) return std::numeric_limits<double>::infinity();
      m = std::max(m, weight(j) * std::fabs(R(j)));
    }
    return m;
  }

  bool row_has_prox(int j) const {
    if (is_normal(j)) return law->normal[contact(j)].capabilities().prox;
    if (coulomb) return true;
    return law->tangential_potential[contact(j)].capabilities().prox;
  }

  /// Σ_k |G_jk P_k|: the size of the terms of row j's mean velocity D_A + G P/2 beyond D_A.
  double abs_GP(int j, const Rows& P) const {
    double s = 0.0;
    for (int k = 0; k < cs->rows(); ++k) s += std::fabs(cs->G(j, k) * P(k));
    return s;
  }

  /// Row j's rounding floor at P (row_rounding_floor), which the stopping test accepts.
  double rounding_floor(int j, const Rows& P) const {
    return row_rounding_floor(cs->D_A(j), abs_GP(j, P), tau(j), P(j), cs->v_scale);
  }

  /// The stopping test of every solver: each row within the target or at its own rounding floor,
  ///   weight_j |R_j| ≤ target  or  |R_j| ≤ min(16ε (|D_A,j| + ½Σ_k |G_jk P_k| + τ_j |P_j|),
  ///                                              1e-6 v_scale)   (row_rounding_floor),
  /// with R from the last call of residual().
  bool converged(const Rows& P, const Rows& R, double target) const {
    const int r = cs->rows();
    for (int j = 0; j < r; ++j) {
      const double a = std::fabs(R(j));
      if (weight(j) * a <= target) continue;
      const double floor = rounding_floor(j, P);
      if (!(a <= floor)) return false;
    }
    return true;
  }

  /// ‖R‖∞ without weights, in velocity units: what law_residual reports (scaled by v_scale).
  double plain_residual(const Rows& P) const {
    Rows z, R;
    if (!std::isfinite(residual(P, z, R))) return std::numeric_limits<double>::infinity();
    return cs->rows() ? R.cwiseAbs().maxCoeff() : 0.0;
  }

  /// One row of R. Where the potential has no prox (value and subgradient only), the equivalent
  /// smooth-case residual: τ(P_j + φ'(z_j)) on a free row, and the min-function
  /// min(τ P_reac, z_N − D_NA/2) with P_reac = P_N + φ'(z_N) on a normal row (eq. 16).
  double row_residual(int j, double zj, const Rows& P) const {
    if (all_prox || row_has_prox(j)) return zj - prox(j, zj - tau(j) * P(j), bound(j, P));
    if (is_normal(j)) {
      const double s = P(j) + law->normal[contact(j)].subgradient(zj);
      return std::min(tau(j) * s, zj - lower_bound(j));
    }
    return tau(j) * (P(j) + law->tangential_potential[contact(j)].subgradient(zj));
  }
};

}  // namespace fremond::detail
