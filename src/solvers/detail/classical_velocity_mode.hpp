#pragma once
// A classical law's answer solved for its velocities and its percussions together, in one
// contact mode (docs/laws.md, eqs. 5-6 with Coulomb's stick and slip), without M⁻¹.
//
// The unknowns are q̇_E and the mode's free percussions p (the closed normal rows' P_N, the
// sticking rows' P_T; a sliding row's P_T = s μ P_N is carried by its normal column). The
// equations are the momentum balance M(q̇_E − q̇_A) = F p (F: W's columns, a closed normal row's
// plus s μ times its sliding tangential row's) and the mode's velocity rows: W_kᵀ q̇_E = −w_k −
// e_k D_NA,k on the closed normal rows, W_jᵀ q̇_E = −w_T,j on the sticking ones. A square system
// of n + m rows, solved for Δ = q̇_E − q̇_A (the momentum rows then exact), its rows and columns
// equilibrated (powers of two) before an LU with partial pivoting and a refinement with the
// residual in twice the precision.
//
// Why: the exact methods and the refinement (classical_refine.hpp) work on the percussions
// through G = WᵀM⁻¹W, and make the velocities from them through M⁻¹W. G carries cond(M): with
// cond(M) = 2e9 the best double percussions can miss D_NE = −e D_NA by 6e-7 of the velocity scale,
// and with cond(M) = 1e10 or more G can be singular beyond extended precision while this system,
// equilibrated, keeps a condition near 1e5. Here M is only multiplied. The law's residual
// (classical_residual) reads the velocities returned, since they balance the percussions to
// rounding.
//
// Poisson's phases are each such a mode, around a fixed part (ModeOffsets): the compression as
// Newton's with target 0, the expansion with P_N = (1 + e) P_NC + ΔP, P_T = P_TC + t and bound
// μ (P_N − P_NC), written from the compression's velocities and percussions (M(q̇_E − q̇_C) =
// W(P − P_C)): where the compression stops the body (q̇_C = 0, three rows on three dofs), the
// expansion of e = 0 then keeps q̇_C exactly, which M⁻¹W P_C made from q̇_A would miss by
// cond(M) ε.
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/detail/accurate_dot.hpp"
#include "laws/detail/residuals.hpp"
#include "solvers/detail/classical_refine.hpp"

namespace fremond::detail::classical {

/// The largest size of a mode's system in (q̇_E, p): n dofs and at most as many velocity rows.
template <int N>
inline constexpr int kMaxModeSystem = N == Eigen::Dynamic ? Eigen::Dynamic : 2 * N;

/// The velocity rows of a mode whose percussions are unknowns of its system (1), or kept at a given
/// increment (0: rows dependent on the others, solve_mode_with_velocities).
template <int N, int C>
using RowFlags = Eigen::Matrix<int, Eigen::Dynamic, 1, 0, ContactSpaceT<N, C>::kMaxRows, 1>;

/// w of contact space row j's contact (w_N for a normal row, w_T for a tangential one).
template <int N, int C>
double row_offset(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs, int j) {
  const int a = cs.active;
  const int i = cs.index(j < a ? j : j - a);
  const auto& w = j < a ? pb.w_N : pb.w_T;
  return w.size() ? w(i) : 0.0;
}

/// The least-squares coefficients of the rows flagged in `which` on the m basic rows `rows`
/// (column j: W_j ≈ Σ_k c_k W_rows(k)), and whether each is that combination within 1e-8 of |W_j|
/// (`spanned`): the dependences kept_rows_hold and percussions_can_move read.
template <int N, int C>
using BasisCoefficients =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, N, ContactSpaceT<N, C>::kMaxRows>;

template <int N, int C>
void basis_coefficients(const ContactSpaceT<N, C>& cs, const RowFlags<N, C>& rows, int m,
                        const RowFlags<N, C>& which, BasisCoefficients<N, C>& coef,
                        RowFlags<N, C>& spanned) {
  const int r = cs.rows(), n = cs.dofs;
  using Basis = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, N, N>;  // m ≤ n
  Basis B(n, m);
  for (int k = 0; k < m; ++k) B.col(k) = cs.W.col(rows(k));
  const Eigen::HouseholderQR<Basis> qr(B);
  coef.setZero(m, r);
  spanned.setZero(r);
  for (int j = 0; j < r; ++j) {
    if (!which(j)) continue;
    const VecT<N> wj = cs.W.col(j);
    coef.col(j) = qr.solve(wj);
    spanned(j) = (B * coef.col(j) - wj).norm() <= 1e-8 * wj.norm();
  }
}

/// Whether the velocity rows of `mode` kept at a given increment (flagged 0 in `basic`) hold at the
/// answer (P, q̇_E) solved on the m basic ones `rows`: each meets its velocity row to 16ε of its
/// own terms and of the basic rows' it is a combination of (`coef`, basis_coefficients), plus what
/// the solve's rounding moves q̇_E by (`q_moved`, entrywise), a closed one's increment is not
/// negative and a sticking one's lies in its cone μ (P_N − cB).
template <int N, int C>
bool kept_rows_hold(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                    const RestitutionLaw& law, const ModeOffsets<N, C>& off, const Mode<N, C>& mode,
                    const RowFlags<N, C>& basic, const RowFlags<N, C>& rows, int m,
                    const BasisCoefficients<N, C>& coef,
                    const typename ContactSpaceT<N, C>::Rows& P, const VecT<N>& qE,
                    const VecT<N>& q0, const VecT<N>& q_moved) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const int a = cs.active, r = cs.rows();
  auto target = [&](int j) { return j < a ? off.target(j) : 0.0; };
  auto terms = [&](int j) {
    return std::fabs(row_offset(pb, cs, j)) + std::fabs(target(j)) +
           cs.W.col(j).cwiseAbs().dot(qE.cwiseAbs() + q0.cwiseAbs());
  };
  for (int j = 0; j < r; ++j) {
    if (mode.kind(j) != 0 || basic(j) != 0) continue;
    double bound = terms(j);
    for (int k = 0; k < m; ++k) bound += std::fabs(coef(k, j)) * terms(rows(k));
    const double miss = contact_velocity(cs.W.col(j), qE, row_offset(pb, cs, j)) + target(j);
    if (!(std::fabs(miss) <= 16 * eps * bound + cs.W.col(j).cwiseAbs().dot(q_moved))) return false;
    if (j < a) {
      if (!(P(j) >= off.cN(j))) return false;
    } else {
      const int k = j - a;
      if (!(std::fabs(P(j) - off.cT(k)) <= Mode<N, C>::mu(cs, law, k) * (P(k) - off.cB(k))))
        return false;
    }
  }
  return true;
}

/// Whether the percussions of an answer solved on the m basic rows `rows` can move without moving
/// any velocity or leaving the law, to first order: along δ = ±(e_j − Σ c_k e_k) for a row j of
/// `loose` (a kept velocity row, or a free row the answer holds on its boundary: an open normal
/// at zero increment whose velocity meets its target to rounding, a sliding row at zero velocity,
/// whose percussion may then move into the cone) that is a combination of the basic rows
/// (`coef`, `spanned`: basis_coefficients). The basic rows are inside their constraints beyond
/// rounding (solve_mode_on_basis), so only rows on the boundary of theirs (`edge`: zero
/// increments, percussions on the cone's edge) can stop a move. A sliding row that is not loose
/// ties its percussion to its normal's, so that a move along W's dependence alone would change the
/// momentum: the caller claims no move then.
template <int N, int C>
bool percussions_can_move(const ContactSpaceT<N, C>& cs, const RestitutionLaw& law,
                          const ModeOffsets<N, C>& off, const RowFlags<N, C>& rows, int m,
                          const RowFlags<N, C>& loose, const RowFlags<N, C>& edge,
                          const BasisCoefficients<N, C>& coef, const RowFlags<N, C>& spanned,
                          const typename ContactSpaceT<N, C>::Rows& P) {
  using Rows = typename ContactSpaceT<N, C>::Rows;
  const int a = cs.active, r = cs.rows();
  for (int j = 0; j < r; ++j) {
    if (!loose(j) || !spanned(j)) continue;
    for (const double s : {1.0, -1.0}) {
      Rows d = Rows::Zero(r);
      d(j) = s;
      for (int k = 0; k < m; ++k) d(rows(k)) -= s * coef(k, j);
      bool feasible = true;
      for (int i = 0; i < r && feasible; ++i) {
        if (!edge(i)) continue;
        if (i < a) {
          feasible = d(i) >= 0.0;  // a zero increment may only grow
        } else {  // |t| = μ (P_N − cB): |t + δt| ≤ μ (P_N + δP_N − cB) to first order
          const int k = i - a;
          const double t = P(i) - off.cT(k), mu = Mode<N, C>::mu(cs, law, k);
          feasible =
              t != 0.0 ? (t > 0.0 ? d(i) : -d(i)) <= mu * d(k) : std::fabs(d(i)) <= mu * d(k);
        }
      }
      if (feasible) return true;
    }
  }
  return false;
}

/// Solves contact mode `mode` around the fixed part and target of `off` for q̇ and the percussions
/// of its velocity rows flagged in `basic`; the others keep the increment `fixed` (x on a closed
/// normal row, t on a sticking one) and must meet their velocity row to the rounding of the rows
/// they depend on. Returns false, with P and q untouched, unless the basic rows are at most n, the
/// system is regular to working precision (reciprocal condition number of the equilibrated system
/// above 64ε), each basic closed row's percussion and each basic sticking row's slack in the cone
/// exceed what rounding can move them by, each kept sticking row lies in its cone, the rows the
/// mode leaves free (open normals, sliding tangents) meet the law to their rounding, and the answer
/// is finite. `continuum` (when accepted): the percussions can move along a dependence of the rows
/// the answer holds without leaving the law (percussions_can_move): they form a continuum about
/// the answer, the velocities not.
template <int N, int C>
bool solve_mode_on_basis(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                         const RestitutionLaw& law, const ModeOffsets<N, C>& off,
                         const Mode<N, C>& mode, const RowFlags<N, C>& basic,
                         const typename ContactSpaceT<N, C>::Rows& fixed,
                         typename ContactSpaceT<N, C>::Rows& P, VecT<N>& q, const VecT<N>* q_from,
                         const typename ContactSpaceT<N, C>::Rows* P_from, bool& continuum) {
  using Rows = typename ContactSpaceT<N, C>::Rows;
  constexpr int kMaxRows = ContactSpaceT<N, C>::kMaxRows;
  constexpr int S = kMaxModeSystem<N>;
  using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, S, S>;
  using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, S, 1>;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const int a = cs.active, r = cs.rows(), n = cs.dofs;
  // The velocity rows, in order; `column(j)` is row j's unknown percussion, −1 for the others.
  Eigen::Matrix<int, Eigen::Dynamic, 1, 0, kMaxRows, 1> rows(r), column(r);
  int m = 0;
  bool kept = false;  // a velocity row at a given increment
  for (int j = 0; j < r; ++j) {
    kept = kept || (mode.kind(j) == 0 && basic(j) == 0);
    const bool unknown = mode.kind(j) == 0 && basic(j) != 0;
    column(j) = unknown ? m : -1;
    if (unknown) {
      if (m == n) return false;  // more velocity rows than dofs: singular
      rows(m++) = j;
    }
  }
  auto offset = [&](int j) { return row_offset(pb, cs, j); };
  // P = P0 + T p: the fixed part P0 of the offsets (cN on every normal row; cT, plus s μ (cN − cB)
  // where the row slides, on every tangential one), and p the velocity rows' increments (x on a
  // closed normal row, with s μ x on its sliding tangential row; t on a sticking row).
  Rows slide_of = Rows::Zero(r);  // s μ on a normal row whose tangential row slides
  Rows P0(r);
  for (int k = 0; k < a; ++k) {
    P0(k) = off.cN(k);
    if (!cs.tangential) continue;
    slide_of(k) = mode.slide(a + k) * Mode<N, C>::mu(cs, law, k);
    P0(a + k) = off.cT(k) + (slide_of(k) != 0.0 ? slide_of(k) * (off.cN(k) - off.cB(k)) : 0.0);
  }
  // The kept rows' increments join the fixed part (a closed normal row's with its sliding
  // tangential row's share).
  for (int j = 0; j < r; ++j) {
    if (mode.kind(j) != 0 || basic(j) != 0) continue;
    P0(j) += fixed(j);
    if (j < a && slide_of(j) != 0.0) P0(a + j) += slide_of(j) * fixed(j);
  }
  const VecT<N>& q0 = q_from ? *q_from : pb.qdot_A;
  Rows dP(r);  // P0 − P_0
  for (int j = 0; j < r; ++j) dP(j) = P0(j) - (P_from ? (*P_from)(j) : 0.0);
  // K y = rhs, y = (Δ, p) with Δ = q̇ − q̇_0: [M, −F; Aᵀ, 0], rhs = (W (P0 − P_0), b − Aᵀq̇_0),
  // from the velocities q̇_0 = q_from made by the percussions P_0 = P_from (q̇_A and 0 unless
  // given: Poisson's expansion starts from its compression). In Δ the momentum rows are exact
  // where P0 = P_0 (Newton's laws; M q̇_A rounded would be an error of ε|M q̇_A|, which cond(M)
  // brings into the velocities; and Poisson's open rows at e = 0), and the velocity rows'
  // right-hand sides are contact velocities computed to their last bit (accurate_dot).
  const int s = n + m;
  Mat K = Mat::Zero(s, s);
  Vec rhs(s);
  K.topLeftCorner(n, n) = pb.M;
  for (int k = 0; k < m; ++k) {
    const int j = rows(k);
    for (int l = 0; l < n; ++l) {
      K(l, n + k) =
          -(cs.W(l, j) + (j < a && slide_of(j) != 0.0 ? slide_of(j) * cs.W(l, a + j) : 0.0));
      K(n + k, l) = cs.W(l, j);
    }
    rhs(n + k) = -(accurate_dot(cs.W.col(j), q0, offset(j)) + (j < a ? off.target(j) : 0.0));
  }
  for (int i = 0; i < n; ++i) rhs(i) = accurate_dot(cs.W.row(i), dP);
  if (!K.allFinite() || !rhs.allFinite()) return false;
  // Equilibrated by powers of two (exact): rows, then columns, to unit largest entries, a few
  // passes (Ruiz). The momentum rows are of M's size and the velocity rows of W's, the percussions
  // of M times velocities: 1e11 apart at cond(M) = 2e11.
  Vec dr = Vec::Ones(s), dc = Vec::Ones(s);
  auto power = [](double x) { return std::ldexp(1.0, -std::ilogb(x) / 2); };  // ~ 1/sqrt(x)
  for (int pass = 0; pass < 6; ++pass) {
    for (int i = 0; i < s; ++i) {
      double big = 0.0;
      for (int l = 0; l < s; ++l) big = std::max(big, std::fabs(dr(i) * K(i, l) * dc(l)));
      if (!(big > 0.0)) return false;  // a zero row: singular
      dr(i) *= power(big);
    }
    for (int l = 0; l < s; ++l) {
      double big = 0.0;
      for (int i = 0; i < s; ++i) big = std::max(big, std::fabs(dr(i) * K(i, l) * dc(l)));
      if (!(big > 0.0)) return false;
      dc(l) *= power(big);
    }
  }
  const Mat Ke = dr.asDiagonal() * K * dc.asDiagonal();
  const Eigen::PartialPivLU<Mat> lu(Ke);
  const Mat inv = lu.inverse();  // exact rcond below, and the rounding bound
  if (!inv.allFinite()) return false;
  const double rcond =
      1.0 / (Ke.cwiseAbs().colwise().sum().maxCoeff() * inv.cwiseAbs().colwise().sum().maxCoeff());
  if (!(rcond > 64 * eps)) return false;
  // y = Dc Ke⁻¹ Dr rhs, refined twice with the residual in twice the precision.
  Vec y = dc.asDiagonal() * lu.solve((dr.asDiagonal() * rhs).eval()), res(s);
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < s; ++i) res(i) = -accurate_dot(K.row(i), y, -rhs(i));
    y += dc.asDiagonal() * lu.solve((dr.asDiagonal() * res).eval());
  }
  // The mode must be the data's, not rounding's: each equation is known to 16ε of its terms,
  // which moves y by up to |K⁻¹| = Dc |Ke⁻¹| Dr times that. Where M is ill-conditioned and the
  // velocity change lies along its soft directions, that can exceed p itself; a closed row whose
  // percussion, or a sticking row whose slack in the cone, is within it is not accepted.
  Vec known(s);
  for (int i = 0; i < s; ++i) {
    double size = std::fabs(rhs(i));
    for (int l = 0; l < s; ++l) size += std::fabs(K(i, l) * y(l));
    if (i < n) size += cs.W.row(i).cwiseAbs().dot(dP.cwiseAbs());
    known(i) = 16 * eps * size;
  }
  const Vec moved = dc.asDiagonal() * (inv.cwiseAbs() * (dr.asDiagonal() * known).eval());
  for (int k = 0; k < m; ++k) {
    const int j = rows(k);
    if (j < a) {
      if (!(y(n + k) > moved(n + k))) return false;  // closed, beyond doubt
    } else {  // sticking, inside the cone μ (P_N − cB) beyond doubt
      const int kn = column(j - a), kc = j - a;
      const double x = kn >= 0 ? y(n + kn) - moved(n + kn) : 0.0;
      const double mu = Mode<N, C>::mu(cs, law, kc);
      if (!(std::fabs(y(n + k)) + moved(n + k) < mu * (P0(kc) - off.cB(kc) + x))) return false;
    }
  }
  if (!y.allFinite()) return false;
  // The rows the mode leaves free must meet the law to their rounding (16ε of their terms): an
  // open row D_NE + e D_NA ≥ 0, a sliding row's D_TE against its percussion. The answer's own
  // mode read wrongly (an open contact whose true percussion is 5 % of the others, cond(M) = 3e10)
  // would otherwise pass the law's residual within the allowance for rounded percussions
  // (RegressionClassical.RoundingAllowanceDoesNotAcceptAWrongModeAsConverged).
  const VecT<N> qE = q0 + y.head(n);
  // A velocity is known to the rounding of its own terms and to what the equations' rounding moves
  // q̇_E by (moved's head): a body stopping in both phases has q̇_C and q̇_E of 1e-20 made by
  // percussions 1e4 times as large in M's units, so a floor from the velocities alone (1e-35) would
  // refuse an open row at D_NE = −1.5e-20 that is only rounding.
  const VecT<N> q_moved = moved.head(n);
  if (!q_moved.allFinite()) return false;  // a floor of ∞ would accept any mode
  RowFlags<N, C> loose = RowFlags<N, C>::Zero(r), edge = RowFlags<N, C>::Zero(r);
  for (int j = 0; j < r; ++j) {
    const bool normal = j < a;
    if (normal ? mode.kind(j) != 1 : mode.slide(j) == 0.0) continue;
    const double D = contact_velocity(cs.W.col(j), qE, offset(j));
    const double floor =
        16 * eps *
            (std::fabs(offset(j)) + cs.W.col(j).cwiseAbs().dot(qE.cwiseAbs() + q0.cwiseAbs())) +
        cs.W.col(j).cwiseAbs().dot(q_moved);
    if (!(normal ? D + off.target(j) >= -floor : -mode.slide(j) * D >= -floor)) return false;
    // On the boundary of both its velocity and its percussion (an open row at zero increment
    // whose velocity meets its target, a sliding row at zero velocity): loose.
    loose(j) = edge(j) = std::fabs(normal ? D + off.target(j) : D) <= floor;
  }
  Rows out(r);
  for (int j = 0; j < r; ++j) out(j) = P0(j) + (column(j) >= 0 ? y(n + column(j)) : 0.0);
  for (int k = 0; k < a && cs.tangential; ++k)
    if (slide_of(k) != 0.0 && column(k) >= 0) out(a + k) += slide_of(k) * y(n + column(k));
  if (!out.allFinite()) return false;
  for (int j = 0; j < r; ++j) {  // the kept rows are loose too
    if (mode.kind(j) != 0 || basic(j) != 0) continue;
    loose(j) = 1;
    if (j < a) {
      edge(j) = out(j) == off.cN(j);
    } else {
      const int k = j - a;
      edge(j) = std::fabs(out(j) - off.cT(k)) == Mode<N, C>::mu(cs, law, k) * (out(k) - off.cB(k));
    }
  }
  continuum = false;
  if (loose.any()) {
    BasisCoefficients<N, C> coef;
    RowFlags<N, C> spanned;
    basis_coefficients(cs, rows, m, loose, coef, spanned);
    if (kept && !kept_rows_hold(pb, cs, law, off, mode, basic, rows, m, coef, out, qE, q0, q_moved))
      return false;
    bool ties = false;  // a sliding row not loose, whose normal's percussion may move
    for (int k = 0; k < a && cs.tangential; ++k)
      ties = ties || (slide_of(k) != 0.0 && !loose(a + k) && (mode.kind(k) == 0 || loose(k)));
    continuum =
        !ties && percussions_can_move(cs, law, off, rows, m, loose, edge, coef, spanned, out);
  }
  P = out;
  q = qE;
  return true;
}

/// Solves contact mode `mode` around the fixed part and target of `off` (as refine_answer builds
/// them: Newton's, or either of Poisson's phases) for q̇ and the percussions together
/// (solve_mode_on_basis): on all its velocity rows where they are at most n; else, or where that
/// system is singular because the rows are dependent, on a basis of them (column-pivoted QR of
/// their unit directions; a row within 1e-8 of the span of those before it is dependent), the
/// others keeping the increments of `P_guess` (the answer being solved again; zero without one).
/// Both contacts of a three-dof body closed and sticking make four rows: q̇_E is fixed by three of
/// them, the percussions form a line, and the answer's point of it is kept (through G, with
/// cond(M) = 7e8, its velocities can miss the law by 2e-4 of their scale). Returns false, with P
/// and q untouched, where neither is accepted.
/// `continuum`, where given: set when accepted, as solve_mode_on_basis says (the percussions a
/// continuum about the answer, the velocities unique).
template <int N, int C>
bool solve_mode_with_velocities(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                                const RestitutionLaw& law, const ModeOffsets<N, C>& off,
                                const Mode<N, C>& mode, typename ContactSpaceT<N, C>::Rows& P,
                                VecT<N>& q, const VecT<N>* q_from = nullptr,
                                const typename ContactSpaceT<N, C>::Rows* P_from = nullptr,
                                const typename ContactSpaceT<N, C>::Rows* P_guess = nullptr,
                                bool* continuum = nullptr) {
  using Rows = typename ContactSpaceT<N, C>::Rows;
  const int a = cs.active, r = cs.rows(), n = cs.dofs;
  RowFlags<N, C> basic(r), rows(r);
  int m = 0;
  for (int j = 0; j < r; ++j) {
    basic(j) = mode.kind(j) == 0 ? 1 : 0;
    if (basic(j)) rows(m++) = j;
  }
  Rows fixed = Rows::Zero(r);
  bool moves = false;
  auto accepted = [&] {
    if (continuum) *continuum = moves;
    return true;
  };
  if (m <= n &&
      solve_mode_on_basis(pb, cs, law, off, mode, basic, fixed, P, q, q_from, P_from, moves))
    return accepted();
  if (m < 2) return false;
  using Directions =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, N, ContactSpaceT<N, C>::kMaxRows>;
  Directions A(n, m);
  for (int k = 0; k < m; ++k) {
    const double norm = cs.W.col(rows(k)).norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) return false;
    A.col(k) = cs.W.col(rows(k)) / norm;
  }
  Eigen::ColPivHouseholderQR<Directions> qr(A);
  qr.setThreshold(1e-8);
  const int rank = static_cast<int>(qr.rank());
  if (rank == m) return false;  // independent rows: the full system's verdict stands
  // The basis on `chosen` (the positions in `rows` of its rank rows); the others at the guess.
  auto try_basis = [&](const RowFlags<N, C>& chosen) {
    basic.setZero();
    for (int k = 0; k < rank; ++k) basic(rows(chosen(k))) = 1;
    fixed.setZero();
    for (int k = 0; k < m && P_guess; ++k) {
      const int j = rows(k);
      if (basic(j)) continue;
      const double guess = (*P_guess)(j);
      fixed(j) = j < a ? std::max(0.0, guess - off.cN(j)) : guess - off.cT(j - a);
    }
    return solve_mode_on_basis(pb, cs, law, off, mode, basic, fixed, P, q, q_from, P_from, moves);
  };
  RowFlags<N, C> chosen(rank);
  for (int k = 0; k < rank; ++k) chosen(k) = static_cast<int>(qr.colsPermutation().indices()(k));
  if (try_basis(chosen)) return accepted();
  // Refused (the best-conditioned basis leaves a kept row outside its cone at the guess, e.g. a
  // body stopping in both phases, eight rows at zero velocity on three dofs): every other basis of
  // rank rows, in lexicographic order, up to 12 rows, for an answer being solved again only (the
  // all-modes fallback already multiplies modes).
  if (!P_guess || m > 12) return false;
  const RowFlags<N, C> first = chosen;
  for (int k = 0; k < rank; ++k) chosen(k) = k;
  while (true) {
    bool same = true;
    for (int k = 0; k < rank && same; ++k) {
      bool in = false;
      for (int l = 0; l < rank; ++l) in = in || first(l) == chosen(k);
      same = in;
    }
    if (!same && try_basis(chosen)) return accepted();
    int k = rank - 1;  // the next combination of rank positions out of m
    while (k >= 0 && chosen(k) == m - rank + k) --k;
    if (k < 0) return false;
    ++chosen(k);
    for (int l = k + 1; l < rank; ++l) chosen(l) = chosen(l - 1) + 1;
  }
}

/// Solves the mode of the answer P (`off` as refine_answer builds it) for q̇ and P together
/// (solve_mode_with_velocities). Returns false, with P and q untouched, where that does not accept
/// the answer.
template <int N, int C>
bool solve_mode_in_velocities(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                              const RestitutionLaw& law, const ModeOffsets<N, C>& off,
                              typename ContactSpaceT<N, C>::Rows& P, VecT<N>& q,
                              const VecT<N>* q_from = nullptr,
                              const typename ContactSpaceT<N, C>::Rows* P_from = nullptr,
                              bool* continuum = nullptr) {
  if (cs.rows() == 0) return false;
  const Mode<N, C> mode = read_mode(cs, law, off, P, accurate_row_velocities(pb, cs, P));
  const typename ContactSpaceT<N, C>::Rows guess = P;
  return solve_mode_with_velocities(pb, cs, law, off, mode, P, q, q_from, P_from, &guess,
                                    continuum);
}

/// Calls visit(mode) for every contact mode of up to 4 active contacts around `off`: each normal
/// row open or closed; each tangential row, where its bound μ (P_N − cB) can be positive (μ > 0,
/// and the normal closed or cN > cB: Poisson's expansion keeps μ e P_NC on an open row),
/// sticking or sliding either way, else t = 0. Nothing where there are more than 4.
template <int N, int C, class Visit>
void for_each_mode(const ContactSpaceT<N, C>& cs, const RestitutionLaw& law,
                   const ModeOffsets<N, C>& off, Visit&& visit) {
  const int a = cs.active, r = cs.rows();
  if (r == 0 || a > 4) return;
  auto frictional = [&](int k, bool closed) {  // 3 tangential kinds, else 1 (t = 0)
    return cs.tangential && Mode<N, C>::mu(cs, law, k) > 0.0 && (closed || off.cN(k) > off.cB(k))
               ? 3
               : 1;
  };
  int choices[4], combinations = 1;
  for (int k = 0; k < a; ++k) {
    choices[k] = frictional(k, false) + frictional(k, true);
    combinations *= choices[k];
  }
  Mode<N, C> mode;
  mode.kind.resize(r);
  mode.slide.resize(r);
  for (int code = 0; code < combinations; ++code) {
    mode.slide.setZero();
    for (int k = 0, rest = code; k < a; rest /= choices[k], ++k) {
      const int choice = rest % choices[k], open_kinds = frictional(k, false);
      const bool closed = choice >= open_kinds;
      mode.kind(k) = closed ? 0 : 1;  // closed: D_N + target = 0; open: P_N = cN
      if (!cs.tangential) continue;
      const int t = closed ? choice - open_kinds : choice;
      if (frictional(k, closed) == 1) {
        mode.kind(a + k) = 1;  // t = 0
      } else if (t == 0) {
        mode.kind(a + k) = 0;  // stick: D_T = 0
      } else {
        mode.kind(a + k) = 1;  // slide: t = s μ (P_N − cB)
        mode.slide(a + k) = t == 1 ? 1.0 : -1.0;
      }
    }
    visit(static_cast<const Mode<N, C>&>(mode));
  }
}

/// The classical laws where no contact mode solves the law in contact space, not even with G in
/// extended precision: every mode (for_each_mode; Poisson's: every expansion mode around every
/// compression mode accepted) solved for the velocities and the percussions together
/// (solve_mode_with_velocities), M only multiplied. G = WᵀM⁻¹W inherits cond(M) where that system
/// does not: with cond(M) = 1e10 and W_T nearly parallel to W_N, G can be singular to 3e-19 of its
/// entries, below even extended precision, while the exact answer sticks with percussions 1e19
/// times its velocities. Of the answers accepted, the most dissipative (T_E − T_A from the
/// velocities). `off` is Newton's (newton_offsets); Poisson's phases are built from it. Returns the
/// number of answers accepted; P, q and Poisson's P_C, q_C hold the one kept when it is not zero.
template <int N, int C>
int solve_modes_in_velocities(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                              const RestitutionLaw& law, bool poisson, const ModeOffsets<N, C>& off,
                              typename ContactSpaceT<N, C>::Rows& P,
                              typename ContactSpaceT<N, C>::Rows& P_C, VecT<N>& q, VecT<N>& q_C) {
  using Rows = typename ContactSpaceT<N, C>::Rows;
  int kept = 0;
  double best_energy = 0.0;
  auto keep = [&](const Rows& Pm, const Rows& PCm, const VecT<N>& qm, const VecT<N>& qCm) {
    const double energy = energy_change_at(pb, qm);
    if (kept == 0 || energy < best_energy) {
      best_energy = energy;
      P = Pm;
      P_C = PCm;
      q = qm;
      q_C = qCm;
    }
    ++kept;
  };
  Rows Pm, PCm;
  VecT<N> qm, qC;
  if (!poisson) {
    for_each_mode(cs, law, off, [&](const Mode<N, C>& mode) {
      if (solve_mode_with_velocities(pb, cs, law, off, mode, Pm, qm)) keep(Pm, Rows(), qm, qm);
    });
    return kept;
  }
  ModeOffsets<N, C> compression = off;
  compression.target.setZero();
  for_each_mode(cs, law, compression, [&](const Mode<N, C>& mc) {
    if (!solve_mode_with_velocities(pb, cs, law, compression, mc, PCm, qC)) return;
    ModeOffsets<N, C> expansion = compression;
    hold_compression(cs, law, PCm, expansion);
    for_each_mode(cs, law, expansion, [&](const Mode<N, C>& me) {
      if (solve_mode_with_velocities(pb, cs, law, expansion, me, Pm, qm, &qC, &PCm))
        keep(Pm, PCm, qm, qC);
    });
  });
  return kept;
}

}  // namespace fremond::detail::classical
