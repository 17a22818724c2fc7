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

/// Solves the mode of the Newton-type answer P (`off` as refine_answer builds it: target = e D_NA,
/// no fixed part) for q̇_E, then P. Returns false, with P and q untouched, unless the mode's
/// velocity equations are as many as the degrees of freedom the contacts touch, those dofs are
/// not coupled by M to the others, the equations are regular to working precision (reciprocal
/// condition number above 64ε), each closed row's percussion and each sticking row's slack in the
/// cone exceed what rounding can move them by, and the answer is finite.
template <int N, int C>
bool solve_mode_in_velocities(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                              const ImpactLaw& law, const ModeOffsets<N, C>& off,
                              typename ContactSpaceT<N, C>::Rows& P, VecT<N>& q) {
  using Rows = typename ContactSpaceT<N, C>::Rows;
  constexpr int kMax = ContactSpaceT<N, C>::kMaxRows;
  using Square = typename SmallLU<kMax>::Mat;
  using Vec = typename SmallLU<kMax>::Vec;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const int a = cs.active, r = cs.rows(), n = cs.dofs;
  if (r == 0) return false;
  // The dofs some row of the contacts touches. The others keep q̇_A exactly, provided M does not
  // couple them to the touched ones (two bodies in one problem: a group of contacts of one of
  // them, independent_groups.hpp). Where it does, the velocities would depend on M, whose
  // conditioning the answer would then carry, and the mode read from it might be one that holds
  // only to that (RegressionClassical.RoundingAllowanceDoesNotAcceptAWrongModeAsConverged).
  Eigen::Matrix<int, Eigen::Dynamic, 1, 0, N, 1> dof(n);
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
      if (pb.M(i, dof(k)) != 0.0 || pb.M(dof(k), i) != 0.0) return false;
  }
  const Mode<N, C> mode = read_mode(cs, law, off, P, accurate_row_velocities(pb, cs, P));
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

}  // namespace fremond::detail::classical
