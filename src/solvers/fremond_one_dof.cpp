// Frémond's law without Coulomb on one degree of freedom, exactly: docs/laws.md's velocity-space
// problem is then a scalar one,
//
//   minimise  F(u) = M u² + Σ_j ψ_j(D_A,j + a_j u),   u = v − q̇_A,   q̇_E = q̇_A + 2u,
//
// with a_j = W_j (1 × 1 columns), ψ_j = φ_j on tangential rows and φ_N + I_{[D_NA/2, ∞)} on normal
// rows (the reaction, eq. 16). F is strongly convex, so ∂F(u) = 2Mu + Σ_j a_j ∂ψ_j(z_j) is a
// strictly monotone set-valued map and its zero is found to the last bit by bisection on the
// sign of that interval, with no G, no prox and no step size.
//
// Why: in contact space one dof under several rows makes G of rank one, and a steep potential
// makes percussions 1e11 times the velocities whose terms of G P cancel (one contact on a moving
// obstacle, a dead zone of k = 1.3e5, q = 3.5 far outside its width): Newton, the splitting and
// NLopt can all stall there, with velocities of the wrong sign. The velocities are what this solve
// gets right whatever the percussions' scale; the percussions follow from them row by row.
#include <algorithm>
#include <cmath>
#include <limits>

#include "solvers/detail/fremond.hpp"

namespace fremond::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The sum of a·∂ψ_j over rows, in u; empty (lo > hi) where a potential's subdifferential is.
struct Slope {
  double lo = 0.0, hi = 0.0;
  bool empty = false;
};

}  // namespace

template <int N, int C>
bool solve_one_dof(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows,
                   typename FremondRowsT<N, C>::Rows& P, double& u_out) {
  const auto& cs = *rows.cs;
  const int r = cs.rows(), a = cs.active;
  if (cs.dofs != 1 || r == 0 || rows.coulomb) return false;
  auto potential = [&](int j) -> const Potential& {
    return rows.is_normal(j) ? rows.law->normal[rows.contact(j)]
                             : rows.law->tangential_potential[rows.contact(j)];
  };
  for (int j = 0; j < r; ++j)
    if (!potential(j).capabilities().subdifferential) return false;
  const double m = pb.M(0, 0);
  // The domain of the reactions: a_j u ≥ −D_NA,j/2 on each normal row (D_NE ≥ 0).
  double u_lo = -kInf, u_hi = kInf;
  for (int j = 0; j < a; ++j) {
    const double aj = cs.W(0, j), bound = -0.5 * cs.D_A(j);
    if (aj > 0.0)
      u_lo = std::max(u_lo, bound / aj);
    else if (aj < 0.0)
      u_hi = std::min(u_hi, bound / aj);
    else if (bound > 0.0)
      return false;  // a row no velocity moves, penetrating: no answer (solve_fremond says so)
  }
  if (!(u_lo <= u_hi)) return false;
  // ∂F(u) without the normal cones of the reactions (they act at the domain's ends only).
  auto slope = [&](double u) {
    Slope s;
    s.lo = s.hi = 2.0 * m * u;
    for (int j = 0; j < r; ++j) {
      const double aj = cs.W(0, j);
      if (aj == 0.0) continue;
      const Interval d = potential(j).subdifferential(cs.D_A(j) + aj * u);
      if (d.is_empty()) {
        s.empty = true;
        return s;
      }
      s.lo += aj > 0.0 ? aj * d.lo : aj * d.hi;
      s.hi += aj > 0.0 ? aj * d.hi : aj * d.lo;
    }
    if (std::isnan(s.lo) || std::isnan(s.hi)) s.empty = true;
    return s;
  };
  double u = 0.0;
  bool found = false;
  // At an end of the domain the reaction's normal cone adds (−∞, 0] (left end) or [0, ∞) (right
  // end) to ∂F: the end is the answer where what is left can reach zero from there.
  if (std::isfinite(u_lo)) {
    const Slope s = slope(u_lo);
    if (s.empty) return false;
    if (s.hi >= 0.0) u = u_lo, found = true;
  }
  if (!found && std::isfinite(u_hi)) {
    const Slope s = slope(u_hi);
    if (s.empty) return false;
    if (s.lo <= 0.0) u = u_hi, found = true;
  }
  if (!found) {
    // A bracket [left, right] with ∂F(left) < 0 < ∂F(right), grown geometrically from the
    // velocity scale; ∂F → ±∞ at ±∞ (the term 2Mu), so it ends within the range of doubles.
    const double scale = std::max({std::fabs(pb.qdot_A(0)), cs.v_scale, 1e-300});
    double left = u_lo, right = u_hi;
    const double start = std::clamp(0.0, u_lo, u_hi);
    const Slope s0 = slope(start);
    if (s0.empty) return false;
    if (s0.lo <= 0.0 && s0.hi >= 0.0) {
      u = start;
      found = true;
    } else if (s0.lo > 0.0) {  // the root lies left of start
      right = start;
      if (!std::isfinite(left))
        for (double step = scale;; step *= 2.0) {
          left = start - step;
          const Slope s = slope(left);
          if (s.empty) return false;
          if (s.hi < 0.0) break;
          if (s.lo <= 0.0) {  // 0 ∈ ∂F(left): the root itself
            u = left;
            found = true;
            break;
          }
          if (!std::isfinite(step) || !std::isfinite(left)) return false;
          right = left;
        }
    } else {  // s0.hi < 0: the root lies right of start
      left = start;
      if (!std::isfinite(right))
        for (double step = scale;; step *= 2.0) {
          right = start + step;
          const Slope s = slope(right);
          if (s.empty) return false;
          if (s.lo > 0.0) break;
          if (s.hi >= 0.0) {  // 0 ∈ ∂F(right): the root itself
            u = right;
            found = true;
            break;
          }
          if (!std::isfinite(step) || !std::isfinite(right)) return false;
          left = right;
        }
    }
    // Bisection to the last bit: the interval always holds the root (slope < 0 left of it,
    // > 0 right of it, or 0 ∈ ∂F at a probe: the root itself).
    for (int it = 0; !found && it < 4400; ++it) {
      const double mid = 0.5 * left + 0.5 * right;
      if (!(mid > left && mid < right)) {
        // Adjacent doubles: the one where ∂F is nearer to containing zero.
        const Slope sl = slope(left), sr = slope(right);
        u = (sl.empty || (!sr.empty && -sl.hi > sr.lo)) ? right : left;
        found = true;
        break;
      }
      const Slope s = slope(mid);
      if (s.empty) return false;
      if (s.lo > 0.0)
        right = mid;
      else if (s.hi < 0.0)
        left = mid;
      else
        u = mid, found = true;
    }
  }
  if (!found || !std::isfinite(u)) return false;

  // The percussions: each row's P_j ∈ −∂ψ_j(z_j), with Σ_j a_j P_j = 2Mu (momentum,
  // docs/concepts.md: M(q̇_E − q̇_A) = W P). Where that leaves a choice (set-valued rows: a reaction,
  // a kink), the least-norm one, P_j = clamp(λ a_j) into its interval, λ found by bisection (the
  // sum is nondecreasing in λ).
  using Rows = typename FremondRowsT<N, C>::Rows;
  Rows lo(r), hi(r);
  for (int j = 0; j < r; ++j) {
    const double aj = cs.W(0, j), z = cs.D_A(j) + aj * u;
    const Interval d = potential(j).subdifferential(z);
    if (d.is_empty()) return false;
    lo(j) = -d.hi;
    hi(j) = -d.lo;
    // A reaction at its bound (D_NE = 0: this row's end of the domain is the answer) pushes with
    // any P ≥ the power law's: −∂ψ = [−φ'(z), ∞).
    if (rows.is_normal(j) && aj != 0.0) {
      const double own = -0.5 * cs.D_A(j) / aj;
      if (std::fabs(u - own) <= 4 * std::numeric_limits<double>::epsilon() * std::fabs(own))
        hi(j) = kInf;
    }
  }
  const double target = 2.0 * m * u;
  auto split = [&](double lambda, Rows& Q) {
    double s = 0.0;
    for (int j = 0; j < r; ++j) {
      Q(j) = std::clamp(lambda * cs.W(0, j), lo(j), hi(j));
      s += cs.W(0, j) * Q(j);
    }
    return s;
  };
  Rows Q(r);
  const double lscale = std::max(1.0, std::fabs(target));
  double l_lo = -lscale, l_hi = lscale;
  for (int it = 0; it < 2100 && split(l_lo, Q) > target; ++it) l_lo *= 2.0;
  for (int it = 0; it < 2100 && split(l_hi, Q) < target; ++it) l_hi *= 2.0;
  if (!std::isfinite(l_lo) || !std::isfinite(l_hi)) return false;
  for (int it = 0; it < 4400; ++it) {
    const double mid = 0.5 * l_lo + 0.5 * l_hi;
    if (!(mid > l_lo && mid < l_hi)) break;
    (split(mid, Q) < target ? l_lo : l_hi) = mid;
  }
  const double s_lo = split(l_lo, Q);
  Rows Qh(r);
  const double s_hi = split(l_hi, Qh);
  if (std::fabs(s_hi - target) < std::fabs(s_lo - target)) Q = Qh;
  if (!Q.allFinite()) return false;
  P = Q + Rows::Zero(r);  // + 0: a row clamped to −0.0 (−∂φ(0) = {−0}) reads 0
  u_out = u;
  return true;
}

#define FREMOND_INSTANTIATE_ONE_DOF(N, C)                                             \
  template bool solve_one_dof(const ImpactProblemT<N, C>&, const FremondRowsT<N, C>&, \
                              typename FremondRowsT<N, C>::Rows&, double&);
FREMOND_INSTANTIATE_ONE_DOF(Dynamic, Dynamic)
FREMOND_INSTANTIATE_ONE_DOF(kSmallDofs, kSmallContacts)

}  // namespace fremond::detail
