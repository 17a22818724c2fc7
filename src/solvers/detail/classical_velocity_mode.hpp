#pragma once
// A Newton-type answer whose contact mode fixes the velocities, solved for the velocities first
// (SPEC §2, eqs. 5-6 with Coulomb's stick and slip).
//
// The mode's velocity equations (closed normal rows, sticking tangential rows) fix q̇_E on their
// directions: W_kᵀ q̇_E = −w_k − e_k D_NA,k on the closed rows, W_jᵀ q̇_E = −w_T,j on the sticking
// ones. Where they are as many as the degrees of freedom the contacts touch (and M does not couple
// those to the others, which keep q̇_A: a second body in the problem), they fix q̇_E, and M plays
// no part. The percussions then follow from the momentum balance M(q̇_E − q̇_A) = W P, with the
// mode's percussion relations (open rows: none; sliding rows: P_T = s μ P_N).
//
// Why: the exact methods and the refinement (classical_refine.hpp) work on the percussions, and
// the velocities are made from them through M⁻¹W. On an ill-conditioned M the last bit of each
// percussion moves the velocities by far more than their own last bit: two contacts closed on a
// two-dof body with cond(M) = 2e9 (stress, Newton, seed 41 #48) missed D_NE = −e D_NA by 6e-7 of
// the velocity scale, at the best double percussions, and ended `stalled`. Solved here, both
// equations hold to 1e-16 and the percussions are the exact ones rounded; the law's residual
// (classical_residual) reads the velocities returned, since they balance the percussions to
// rounding.
//
// Not for Poisson: its expansion starts from the compression's velocities, which are made from
// percussions again.
#include <cmath>
#include <limits>

#include "classical_refine.hpp"
#include "fremond/solvers/detail/accurate_dot.hpp"
#include "small_lu.hpp"

namespace fremond::detail::classical {

/// The degrees of freedom some row of the contacts touches, into `dof` (their count returned), or
/// -1 where M couples one of them to an untouched one. The others keep q̇_A exactly, provided M does
/// not couple them to the touched ones (two bodies in one problem: a group of contacts of one of
/// them, independent_groups.hpp). Where it does, the velocities would depend on M, whose
/// conditioning the answer would then carry, and the mode read from it might be one that holds
/// only to that (RegressionClassical.RoundingAllowanceDoesNotAcceptAWrongModeAsConverged).
template <int N, int C>
int touched_dofs(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                 Eigen::Matrix<int, Eigen::Dynamic, 1, 0, N, 1>& dof) {
  const int n = cs.dofs, r = cs.rows();
  dof.resize(n);
  int t = 0;
  for (int i = 0; i < n; ++i) {
    bool touched = false;
    for (int j = 0; j < r && !touched; ++j) touched = cs.W(i, j) != 0.0;
    if (touched) dof(t++) = i;
  }
  for (int i = 0, u = 0; i < n; ++i) {
    if (u < t && dof(u) == i) {
      ++u;
      continue;
    }
    for (int k = 0; k < t; ++k)
      if (pb.M(i, dof(k)) != 0.0 || pb.M(dof(k), i) != 0.0) return -1;
  }
  return t;
}

/// Solves contact mode `mode` (`off` as refine_answer builds it: target = e D_NA, no fixed part)
/// for q̇_E, then P, on the t touched dofs `dof` (touched_dofs). Returns false, with P and q
/// untouched, unless the mode's velocity equations are as many as those dofs, the equations are
/// regular to working precision (reciprocal condition number above 64ε), each closed row's
/// percussion and each sticking row's slack in the cone exceed what rounding can move them by,
/// and the answer is finite. The rows the mode does not fix (open normals, sliding tangents) are
/// not checked here.
template <int N, int C>
bool solve_velocity_mode(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                         const ImpactLaw& law, const ModeOffsets<N, C>& off, const Mode<N, C>& mode,
                         const Eigen::Matrix<int, Eigen::Dynamic, 1, 0, N, 1>& dof, int t,
                         typename ContactSpaceT<N, C>::Rows& P, VecT<N>& q) {
  using Rows = typename ContactSpaceT<N, C>::Rows;
  constexpr int kMax = ContactSpaceT<N, C>::kMaxRows;
  using Square = typename SmallLU<kMax>::Mat;
  using Vec = typename SmallLU<kMax>::Vec;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const int a = cs.active, r = cs.rows();
  // The velocity rows, in order; `column(j)` is row j's unknown percussion, −1 for the others.
  Eigen::Matrix<int, Eigen::Dynamic, 1, 0, kMax, 1> rows(r), column(r);
  int m = 0;
  for (int j = 0; j < r; ++j) {
    column(j) = mode.kind(j) == 0 ? m : -1;
    if (mode.kind(j) == 0) rows(m++) = j;
  }
  if (m != t) return false;
  auto offset = [&](int j) {  // w of row j's contact
    const int i = cs.index(j < a ? j : j - a);
    const auto& w = j < a ? pb.w_N : pb.w_T;
    return w.size() ? w(i) : 0.0;
  };
  // Wᵀ q̇_E = b on the velocity rows (touched dofs).
  Square A(t, t);
  Vec b(t), x(t), res(t), d(t);
  for (int k = 0; k < t; ++k) {
    const int j = rows(k);
    for (int l = 0; l < t; ++l) A(k, l) = cs.W(dof(l), j);
    b(k) = -offset(j) - (j < a ? off.target(j) : 0.0);
  }
  // K y = rhs by LU (left in `lu`), refined once with the residual in twice the precision; false
  // where K is singular to working precision.
  SmallLU<kMax> lu;
  auto solve_refined = [&](const Square& K, const Vec& rhs, Vec& y) {
    lu.compute(K);
    if (!lu.well_conditioned(64 * eps)) return false;
    lu.solve(rhs, y);
    for (int k = 0; k < t; ++k) res(k) = -accurate_dot(K.row(k), y, -rhs(k));
    lu.solve(res, d);
    y += d;
    return true;
  };
  if (!solve_refined(A, b, x)) return false;
  // M(q̇_E − q̇_A) = F p with P = T p: a closed normal row's column is W_N,k plus s μ W_T,k of its
  // sliding tangential row; a sticking row's is W_T,j. Open rows and rows held at zero add nothing.
  Rows slide_of = Rows::Zero(r);  // s μ on a closed normal row whose tangential row slides
  if (cs.tangential)
    for (int k = 0; k < a; ++k)
      if (mode.slide(a + k) != 0.0) slide_of(k) = mode.slide(a + k) * Mode<N, C>::mu(cs, law, k);
  Square F(t, t), Mt(t, t);
  for (int k = 0; k < t; ++k) {
    const int j = rows(k);
    for (int l = 0; l < t; ++l) {
      F(l, k) =
          cs.W(dof(l), j) + (j < a && slide_of(j) != 0.0 ? slide_of(j) * cs.W(dof(l), a + j) : 0.0);
      Mt(k, l) = pb.M(dof(k), dof(l));
    }
  }
  Vec dq(t), p(t);
  for (int k = 0; k < t; ++k) dq(k) = x(k) - pb.qdot_A(dof(k));
  for (int k = 0; k < t; ++k) b(k) = accurate_dot(Mt.row(k), dq);
  if (!solve_refined(F, b, p)) return false;
  // The mode must be the data's, not rounding's: M(q̇_E − q̇_A) is known to 16ε Σ|M|(|q̇_E| +
  // |q̇_A|) per row, which moves p by up to |F⁻¹| times that. Where M is ill-conditioned and the
  // velocity change lies along its soft directions, that can exceed p itself; a closed row whose
  // percussion, or a sticking row whose slack in the cone, is within it is not accepted.
  Vec known(t), unit(t), col(t), moved = Vec::Zero(t);
  for (int k = 0; k < t; ++k) {
    double size = 0.0;
    for (int l = 0; l < t; ++l)
      size += std::fabs(Mt(k, l)) * (std::fabs(x(l)) + std::fabs(pb.qdot_A(dof(l))));
    known(k) = 16 * eps * size + 4 * eps * std::fabs(b(k));
  }
  for (int l = 0; l < t; ++l) {  // |F⁻¹| known, column by column of F⁻¹
    unit.setZero();
    unit(l) = 1.0;
    lu.solve(unit, col);
    moved += col.cwiseAbs() * known(l);
  }
  for (int k = 0; k < t; ++k) {
    const int j = rows(k);
    if (j < a) {
      if (!(p(k) > moved(k))) return false;  // closed, beyond doubt
    } else if (column(j - a) >= 0) {         // sticking, inside the cone beyond doubt
      const int kn = column(j - a);
      const double mu = Mode<N, C>::mu(cs, law, j - a);
      if (!(std::fabs(p(k)) + moved(k) < mu * (p(kn) - moved(kn)))) return false;
    } else {
      return false;  // sticking on an open contact: not a mode of the law
    }
  }
  Rows out = Rows::Zero(r);
  for (int j = 0; j < r; ++j)
    if (column(j) >= 0) out(j) = p(column(j));
  for (int k = 0; k < a && cs.tangential; ++k)
    if (slide_of(k) != 0.0) out(a + k) = slide_of(k) * out(k);
  if (!x.allFinite() || !out.allFinite()) return false;
  P = out;
  q = pb.qdot_A;
  for (int k = 0; k < t; ++k) q(dof(k)) = x(k);
  return true;
}

/// Solves the mode of the Newton-type answer P (`off` as refine_answer builds it: target = e D_NA,
/// no fixed part) for q̇_E, then P. Returns false, with P and q untouched, unless the mode's
/// velocity equations are as many as the degrees of freedom the contacts touch, those dofs are
/// not coupled by M to the others, and solve_velocity_mode accepts the answer.
template <int N, int C>
bool solve_mode_in_velocities(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                              const ImpactLaw& law, const ModeOffsets<N, C>& off,
                              typename ContactSpaceT<N, C>::Rows& P, VecT<N>& q) {
  if (cs.rows() == 0) return false;
  Eigen::Matrix<int, Eigen::Dynamic, 1, 0, N, 1> dof;
  const int t = touched_dofs(pb, cs, dof);
  if (t < 0) return false;
  const Mode<N, C> mode = read_mode(cs, law, off, P, accurate_row_velocities(pb, cs, P));
  return solve_velocity_mode(pb, cs, law, off, mode, dof, t, P, q);
}

/// Newton's laws where no contact mode solves the law in contact space, not even with G in
/// extended precision: every mode of up to 4 active contacts (each open, or closed and sticking,
/// or closed and sliding either way; closed with P_T = 0 where μ = 0) whose velocity equations fix
/// the touched dofs, solved for the velocities first (solve_velocity_mode), M only multiplied.
/// G = WᵀM⁻¹W inherits cond(M) where those velocities do not: one contact of a two-dof body with
/// cond(M) = 1.3e10 and W_T 2e-4 from parallel to W_N has G singular to 3e-19 of its entries,
/// below even extended precision, while the exact answer sticks with velocities fixed by W alone
/// and percussions 1e19 times them (stress newton_coulomb #27360 of seed 7). A mode is kept when
/// the rows it leaves free meet the law to their rounding (16ε of their terms): an open row
/// D_NE + e D_NA ≥ 0, a sliding row's D_TE against its percussion. Of those kept, the most
/// dissipative (T_E − T_A from the velocities). Returns the number of modes kept; P and q hold
/// the answer when it is not zero.
template <int N, int C>
int solve_modes_in_velocities(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                              const ImpactLaw& law, const ModeOffsets<N, C>& off,
                              typename ContactSpaceT<N, C>::Rows& P, VecT<N>& q) {
  using Rows = typename ContactSpaceT<N, C>::Rows;
  constexpr double eps16 = 16 * std::numeric_limits<double>::epsilon();
  const int a = cs.active, r = cs.rows(), n = cs.dofs;
  if (r == 0 || a > 4) return 0;
  Eigen::Matrix<int, Eigen::Dynamic, 1, 0, N, 1> dof;
  const int t = touched_dofs(pb, cs, dof);
  if (t <= 0) return 0;
  const int kinds = cs.tangential ? 4 : 2;  // open, stick (closed), slide +, slide −
  int combinations = 1;
  for (int k = 0; k < a; ++k) combinations *= kinds;
  Mode<N, C> mode;
  mode.kind.resize(r);
  mode.slide.resize(r);
  auto offset = [&](int j) {  // w of row j's contact
    const int i = cs.index(j < a ? j : j - a);
    const auto& w = j < a ? pb.w_N : pb.w_T;
    return w.size() ? w(i) : 0.0;
  };
  int kept = 0;
  double best_energy = 0.0;
  for (int code = 0; code < combinations; ++code) {
    mode.slide.setZero();
    int fixed = 0;
    bool repeated = false;  // μ = 0: the sliding kinds repeat the closed one
    for (int k = 0, rest = code; k < a; ++k, rest /= kinds) {
      const int kind = rest % kinds;
      mode.kind(k) = kind == 0 ? 1 : 0;  // open: P_N = 0; else D_NE = −e D_NA
      if (kind != 0) ++fixed;
      if (!cs.tangential) continue;
      const bool friction = Mode<N, C>::mu(cs, law, k) > 0.0;
      if (kind == 1 && friction) {
        mode.kind(a + k) = 0;  // stick: D_TE = 0
        ++fixed;
      } else {
        mode.kind(a + k) = 1;  // t = s μ P_N, or t = 0 (open, or μ = 0)
        if (kind >= 2 && friction) mode.slide(a + k) = kind == 2 ? 1.0 : -1.0;
      }
      repeated = repeated || (!friction && kind >= 2);
    }
    if (repeated || fixed != t) continue;
    Rows Pm = Rows::Zero(r);
    VecT<N> qm;
    if (!solve_velocity_mode(pb, cs, law, off, mode, dof, t, Pm, qm)) continue;
    bool holds = true;
    for (int j = 0; j < r && holds; ++j) {
      const bool normal = j < a;
      if (normal ? mode.kind(j) != 1 : mode.slide(j) == 0.0) continue;
      const double D = contact_velocity(cs.W.col(j), qm, offset(j));
      const double floor =
          eps16 *
          (std::fabs(offset(j)) + cs.W.col(j).cwiseAbs().dot(qm.cwiseAbs() + pb.qdot_A.cwiseAbs()));
      holds = normal ? D + off.target(j) >= -floor : -mode.slide(j) * D >= -floor;
    }
    if (!holds) continue;
    double energy = 0.0;  // T_E − T_A = ½(q̇_E − q̇_A)ᵀM(q̇_E + q̇_A), eq. 9
    for (int i = 0; i < n; ++i) {
      double Ms = 0.0;
      for (int l = 0; l < n; ++l) Ms += pb.M(i, l) * (qm(l) + pb.qdot_A(l));
      energy += 0.5 * (qm(i) - pb.qdot_A(i)) * Ms;
    }
    if (kept == 0 || energy < best_energy) {
      best_energy = energy;
      P = Pm;
      q = qm;
    }
    ++kept;
  }
  return kept;
}

}  // namespace fremond::detail::classical
