#pragma once
// A Newton-type answer whose contact mode fixes the velocities, solved for the velocities first
// (SPEC §2, eqs. 5-6 with Coulomb's stick and slip).
//
// Where the mode holds as many velocity equations (closed normal rows, sticking tangential rows)
// as the body has degrees of freedom, and they are independent, they alone give q̇_E:
// W_kᵀ q̇_E = −w_k − e_k D_NA,k on the closed rows, W_jᵀ q̇_E = −w_T,j on the sticking ones. M
// plays no part. The percussions then follow from the momentum balance M(q̇_E − q̇_A) = W P, with
// the mode's percussion relations (open rows: none; sliding rows: P_T = s μ P_N).
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
/// no fixed part) for q̇_E, then P. Returns false, with P and q untouched, unless the mode has
/// exactly as many independent velocity equations as degrees of freedom (each LU's reciprocal
/// condition number above 64ε) and the answer is finite.
template <int N, int C>
bool solve_mode_in_velocities(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                              const ImpactLaw& law, const ModeOffsets<N, C>& off,
                              typename ContactSpaceT<N, C>::Rows& P, VecT<N>& q) {
  using Rows = typename ContactSpaceT<N, C>::Rows;
  constexpr int kMax = ContactSpaceT<N, C>::kMaxRows;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const int a = cs.active, r = cs.rows(), n = cs.dofs;
  if (r < n) return false;
  const Mode<N, C> mode = read_mode(cs, law, off, P, accurate_row_velocities(pb, cs, P));
  // The velocity rows, in order; `column(j)` is row j's unknown percussion, −1 for the others.
  Eigen::Matrix<int, Eigen::Dynamic, 1, 0, kMax, 1> rows(r), column(r);
  int m = 0;
  for (int j = 0; j < r; ++j) {
    column(j) = mode.kind(j) == 0 ? m : -1;
    if (mode.kind(j) == 0) rows(m++) = j;
  }
  if (m != n) return false;
  auto offset = [&](int j) {  // w of row j's contact
    const int i = cs.index(j < a ? j : j - a);
    const auto& w = j < a ? pb.w_N : pb.w_T;
    return w.size() ? w(i) : 0.0;
  };
  // Wᵀ q̇_E = b on the velocity rows, refined once with the residual in twice the precision.
  typename SmallLU<kMax>::Mat A(n, n);
  typename SmallLU<kMax>::Vec b(n), x(n), res(n), d(n);
  for (int k = 0; k < n; ++k) {
    const int j = rows(k);
    A.row(k) = cs.W.col(j).transpose();
    b(k) = -offset(j) - (j < a ? off.target(j) : 0.0);
  }
  SmallLU<kMax> lu;
  lu.compute(A);
  if (lu.singular() || !(lu.rcond() > 64 * eps)) return false;
  lu.solve(b, x);
  for (int k = 0; k < n; ++k) res(k) = -accurate_dot(A.row(k), x.head(n), -b(k));
  lu.solve(res, d);
  x += d;
  // M(q̇_E − q̇_A) = W P with P = T p: a closed normal row's column is W_N,k plus s μ W_T,k of its
  // sliding tangential row; a sticking row's is W_T,j. Open rows and rows held at zero add nothing.
  VecT<N> dq = x.head(n) - pb.qdot_A;
  Rows slide_of = Rows::Zero(r);  // s μ on a closed normal row whose tangential row slides
  if (cs.tangential)
    for (int k = 0; k < a; ++k)
      if (mode.slide(a + k) != 0.0) slide_of(k) = mode.slide(a + k) * Mode<N, C>::mu(cs, law, k);
  typename SmallLU<kMax>::Mat F(n, n);
  for (int k = 0; k < n; ++k) {
    const int j = rows(k);
    F.col(k) = cs.W.col(j);
    if (j < a && slide_of(j) != 0.0) F.col(k) += slide_of(j) * cs.W.col(a + j);
  }
  for (int k = 0; k < n; ++k) b(k) = accurate_dot(pb.M.row(k), dq);
  lu.compute(F);
  if (lu.singular() || !(lu.rcond() > 64 * eps)) return false;
  typename SmallLU<kMax>::Vec p(n);
  lu.solve(b, p);
  for (int k = 0; k < n; ++k) res(k) = -accurate_dot(F.row(k), p.head(n), -b(k));
  lu.solve(res, d);
  p += d;
  Rows out = Rows::Zero(r);
  for (int j = 0; j < r; ++j)
    if (column(j) >= 0) out(j) = p(column(j));
  for (int k = 0; k < a && cs.tangential; ++k)
    if (slide_of(k) != 0.0) out(a + k) = slide_of(k) * out(k);
  if (!x.allFinite() || !out.allFinite()) return false;
  P = out;
  q = x.head(n);
  return true;
}

}  // namespace fremond::detail::classical
