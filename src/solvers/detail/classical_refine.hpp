#pragma once
// Iterative refinement of a classical law's answer in the contact mode it found (docs/laws.md).
//
// The exact methods solve each mode's linear equations with G = WᵀM⁻¹W as formed in double
// precision, so their percussions are off by about cond(G)·ε relative. Where W_T is nearly parallel
// to W_N (cond(G) = 1e6 on a moderate two-dof body) the percussions are 1e4 times the velocities
// they produce, and that error reaches the velocities: a sticking contact can keep D_TE = 7e-12
// beside D_A = 0.17, which the law's residual rightly calls "stalled". Refinement removes it the
// classical way (Higham, "Accuracy and Stability of Numerical Algorithms", §12.1): the mode's
// equations are evaluated at the velocities of the answer computed in twice the precision (force W
// P by Dot2, the solve with M refined), and the correction solves the same equations with the
// double-precision G. Each step gains a factor cond(G)·ε.
//
// The mode is read from the answer: a normal row is closed where its percussion (beyond the fixed
// part) is positive, else held at that part; a tangential row sticks where its percussion is
// inside the bound, slides where it is on it, and is held at zero where the bound is zero.
// Poisson refines its compression, then its expansion with the compression held. The caller keeps
// the refined answer only when the law's own residual (classical_residual) says it is better.
#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_space/contact_space.hpp"
#include "core/detail/small_lu.hpp"
#include "fremond/core/impact_problem.hpp"
#include "fremond/laws/impact_law.hpp"
#include "laws/detail/residuals.hpp"

namespace fremond::detail::classical {

/// The contact-space velocities D = Wᵀ(q̇_A + M⁻¹W P) + w of the rows that take part, as accurate
/// as the velocity q̇_E can be stored: the force W P in twice the precision (its terms cancel where
/// the percussions are large), M⁻¹ refined, each D by Dot2.
template <int N, int C>
typename ContactSpaceT<N, C>::Rows accurate_row_velocities(
    const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
    const typename ContactSpaceT<N, C>::Rows& P) {
  VecT<N> q;
  velocity_after(pb, cs, P, q, true);
  typename ContactSpaceT<N, C>::Rows D(cs.rows());
  for (int k = 0; k < cs.active; ++k) {
    const int i = cs.index(k);
    D(k) = contact_velocity(cs.W.col(k), q, pb.w_N.size() ? pb.w_N(i) : 0.0);
    if (cs.tangential)
      D(cs.active + k) =
          contact_velocity(cs.W.col(cs.active + k), q, pb.w_T.size() ? pb.w_T(i) : 0.0);
  }
  return D;
}

/// One phase's mode equations around a fixed part: normal row k closed (x_k = P_N,k − cN_k > 0,
/// D_N,k + target_k = 0) or open (P_N,k = cN_k); tangential row, t_k = P_T,k − cT_k with bound
/// β_k = μ_k (P_N,k − cB_k): zero bound → t_k = 0, sticking → D_T,k = 0, sliding → t_k = s β_k.
/// Newton: cN = cT = cB = 0, target = e D_NA. Poisson compression: the same with target 0;
/// expansion: cN = (1 + e) P_NC, cT = P_TC, cB = P_NC, target 0.
template <int N, int C>
struct ModeOffsets {
  using Rows = typename ContactSpaceT<N, C>::Rows;
  Rows cN, cT, cB, target;  ///< cN, cB, target: active contacts; cT: active contacts
};

/// Poisson's expansion around the compression P_C (docs/laws.md): P_NE = e P_NC + ΔP with bound
/// μ P_NE, so P_N = (1 + e) P_NC + ΔP and P_T = P_TC + t with |t| ≤ μ (P_N − P_NC); target 0.
template <int N, int C>
void hold_compression(const ContactSpaceT<N, C>& cs, const RestitutionLaw& law,
                      const typename ContactSpaceT<N, C>::Rows& P_C, ModeOffsets<N, C>& off) {
  const int a = cs.active;
  off.target.setZero(a);
  for (int k = 0; k < a; ++k) {
    const double e = law.e[cs.index(k)];
    off.cN(k) = (1.0 + e) * P_C(k);
    off.cB(k) = P_C(k);
    if (cs.tangential) off.cT(k) = P_C(a + k);
  }
}

/// How a refinement ended: the mode's equations singular to working precision (G singular: the
/// percussions are not unique and the minimum-norm choice must stay; P untouched), corrections
/// that stopped shrinking before reaching rounding, or P the mode's exact solution to rounding.
enum class Refinement { singular, stalled, converged };

/// A contact mode read from an answer: which equation each row holds (0 = its velocity, 1 = a
/// percussion relation) and, for a sliding tangential row, the sign s of t = s β.
template <int N, int C>
struct Mode {
  static constexpr int kMax = ContactSpaceT<N, C>::kMaxRows;
  Eigen::Matrix<int, Eigen::Dynamic, 1, 0, kMax, 1> kind;
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMax, 1> slide;  ///< 0 except on sliding rows
  /// μ of the contact of active contact k (0 without friction).
  static double mu(const ContactSpaceT<N, C>& cs, const RestitutionLaw& law, int k) {
    return cs.tangential && law.has_friction() ? law.mu[cs.index(k)] : 0.0;
  }
};

/// The mode of the answer P, whose row velocities are D (accurate_row_velocities). Each row's mode
/// is the one its answer satisfies more clearly, in velocity units: closed where G_kk x_k exceeds
/// |w_k| (x = 1e-17 left by rounding beside w = 2e-3 is an open row), sticking where the bound's
/// slack G_jj (β − |t|) exceeds |v_j|.
template <int N, int C>
Mode<N, C> read_mode(const ContactSpaceT<N, C>& cs, const RestitutionLaw& law,
                     const ModeOffsets<N, C>& off, const typename ContactSpaceT<N, C>::Rows& P,
                     const typename ContactSpaceT<N, C>::Rows& D) {
  const int a = cs.active, r = cs.rows();
  Mode<N, C> mode;
  mode.kind.resize(r);
  mode.slide.setZero(r);
  for (int k = 0; k < a; ++k) {
    mode.kind(k) = cs.G(k, k) * (P(k) - off.cN(k)) > std::fabs(D(k) + off.target(k)) ? 0 : 1;
    if (!cs.tangential) continue;
    const int j = a + k;
    const double bound = Mode<N, C>::mu(cs, law, k) * (P(k) - off.cB(k)), t = P(j) - off.cT(k);
    if (!(bound > 0.0)) {
      mode.kind(j) = 1;  // t = 0
    } else if (cs.G(j, j) * (bound - std::fabs(t)) > std::fabs(D(j))) {
      mode.kind(j) = 0;  // stick
    } else {
      mode.kind(j) = 1;  // slide: t − s μ (P_N − cB) = 0
      mode.slide(j) = t > 0.0 ? 1.0 : -1.0;
    }
  }
  return mode;
}

/// Refines P in place (up to `steps` corrections).
template <int N, int C>
Refinement refine_mode(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                       const RestitutionLaw& law, const ModeOffsets<N, C>& off,
                       typename ContactSpaceT<N, C>::Rows& P, int steps = 4) {
  using Rows = typename ContactSpaceT<N, C>::Rows;
  constexpr int kMax = ContactSpaceT<N, C>::kMaxRows;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const int a = cs.active, r = cs.rows();
  if (r == 0) return Refinement::singular;
  Rows D = accurate_row_velocities(pb, cs, P);
  const Mode<N, C> mode = read_mode(cs, law, off, P, D);
  const auto& kind = mode.kind;
  const auto& slide = mode.slide;
  typename SmallLU<kMax>::Mat K = SmallLU<kMax>::Mat::Zero(r, r);
  for (int j = 0; j < r; ++j) {
    if (kind(j) == 0) {
      K.row(j) = cs.G.row(j);
      continue;
    }
    K(j, j) = 1.0;
    if (slide(j) != 0.0) K(j, j - a) = -slide(j) * Mode<N, C>::mu(cs, law, j - a);
  }
  SmallLU<kMax> lu;
  lu.compute(K);
  if (!lu.well_conditioned(64 * eps)) return Refinement::singular;
  const Rows start = P;
  Rows res(r), d(r);
  double previous = std::numeric_limits<double>::infinity();
  Refinement outcome = Refinement::stalled;
  for (int step = 0; step < steps; ++step) {
    if (step > 0) D = accurate_row_velocities(pb, cs, P);
    for (int k = 0; k < a; ++k) {
      res(k) = kind(k) == 0 ? -(D(k) + off.target(k)) : off.cN(k) - P(k);
      if (!cs.tangential) continue;
      const int j = a + k;
      const double mu = Mode<N, C>::mu(cs, law, k);
      if (kind(j) == 0)
        res(j) = -D(j);
      else
        res(j) = -((P(j) - off.cT(k)) - slide(j) * mu * (P(k) - off.cB(k)));
    }
    lu.solve(res, d);
    const double size = P.cwiseAbs().maxCoeff(), correction = d.cwiseAbs().maxCoeff();
    if (correction <= 4 * eps * size) {  // rounding: P solves its mode to working precision
      outcome = Refinement::converged;
      break;
    }
    if (!std::isfinite(correction) || !(correction < 0.5 * previous)) break;
    P += d;
    previous = correction;
  }
  if (!P.allFinite()) {
    P = start;
    return Refinement::stalled;
  }
  return outcome;
}

}  // namespace fremond::detail::classical
