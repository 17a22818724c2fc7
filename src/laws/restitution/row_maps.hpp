#pragma once
/// @file The natural maps of one contact's rows under the classical laws (docs/solvers.md):
/// the complementarity of the normal row and Coulomb's law on the tangential one, in velocity
/// units, and what bounds the rounding of an answer's own velocities. The law's residual
/// (residual.cpp) and the one-contact stage of its chain read the same functions, so that they
/// agree to the last bit.
#include <algorithm>
#include <cmath>

#include "contact_space/contact_space.hpp"

namespace fremond::detail {

/// g·x with 0 exactly where x is: g = W_iᵀM⁻¹W_i overflows for |W| near 1e308, and 0·∞ would
/// make an exact zero a NaN residual.
inline double scaled(double g, double x) {
  return x == 0.0 ? 0.0 : g * x;
}

/// min(w, g·x): zero exactly when 0 ≤ x ⊥ w ≥ 0 (g converts a percussion to a velocity).
inline double complementarity(double w, double x, double g) {
  return std::min(w, scaled(g, x));
}

/// Coulomb's natural map on (t, v) with bound b: g·(t − clamp(t − v/g, −b, b)); zero exactly when
/// |t| ≤ b, v = 0 where |t| < b, t = −b sign(v) where v ≠ 0. A negative bound is clipped (the
/// normal residual reports the negative percussion).
inline double coulomb(double t, double v, double b, double g) {
  b = std::max(0.0, b);
  return scaled(g, t - std::clamp(t - v / g, -b, b));
}

/// One contact's rows at an answer: its velocities after (Poisson's: also at the end of
/// compression) and its percussions (total, and Poisson's compression part).
struct ContactAnswer {
  double D_NE = 0.0, D_TE = 0.0, P_N = 0.0, P_T = 0.0;
  double D_NC = 0.0, D_TC = 0.0, P_NC = 0.0, P_TC = 0.0;
};

/// The largest |natural map| of one contact's rows (Newton: eq. 5 as a complementarity, then
/// Coulomb; Poisson: compression, then the expansion with P_NE = e P_NC + ΔP), in velocity units.
/// `e` acts on `dna` (Newton's) or on P_NC (Poisson's); `mu` bounds the tangential percussion (0
/// without friction); gn, gt the contact's own Delassus entries.
inline double worst_row_map(bool poisson, bool tangential, double e, double mu, double dna,
                            double gn, double gt, const ContactAnswer& k) {
  double worst = 0.0;
  if (!poisson) {
    worst = std::max(worst, std::fabs(complementarity(k.D_NE + e * dna, k.P_N, gn)));
    if (tangential) worst = std::max(worst, std::fabs(coulomb(k.P_T, k.D_TE, mu * k.P_N, gt)));
    return worst;
  }
  worst = std::max(worst, std::fabs(complementarity(k.D_NC, k.P_NC, gn)));
  if (tangential) worst = std::max(worst, std::fabs(coulomb(k.P_TC, k.D_TC, mu * k.P_NC, gt)));
  const double pne = k.P_N - k.P_NC, pte = k.P_T - k.P_TC;
  worst = std::max(worst, std::fabs(complementarity(k.D_NE, pne - e * k.P_NC, gn)));
  if (tangential) worst = std::max(worst, std::fabs(coulomb(pte, k.D_TE, mu * pne, gt)));
  return worst;
}

/// u = Σ_j |M⁻¹W_j P_j| over the first `rows` rows of cs with a percussion (p(j) row j's):
/// what q̇ − q̇_A is summed from, so that W's rows on u bound the rounding of the contact
/// velocities at q̇ (residual_at_own_velocities). Entry by entry, rows in order.
/// K: the dofs where fixed (sized_vector.hpp).
template <int K = Eigen::Dynamic, int N, int C, class Percussion>
SizedVecT<K, N> velocity_terms(const ContactSpaceT<N, C>& cs, int rows, const Percussion& p) {
  const int n = sized<K>(cs.dofs);
  SizedVecT<K, N> u = SizedVecT<K, N>::Zero(n);
  for (int j = 0; j < rows; ++j) {
    const double pj = p(j);
    if (pj != 0.0)
      for (int i = 0; i < n; ++i) u(i) += std::fabs(cs.MinvW(i, j) * pj);
  }
  return u;
}

/// The share of the tolerance that the residual at an answer's own velocities, and those
/// velocities' rounding, may each take for the law's residual from the data to stay within it
/// (both maps are 1-Lipschitz in the velocities): residual_at_own_velocities.
inline constexpr double kOwnVelocityShare = 0.45;

}  // namespace fremond::detail
