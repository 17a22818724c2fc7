#pragma once
/// @file The impact problem in contact space, on the contacts a solve holds (docs/concepts.md):
/// the approaching and touching ones (D_NA ≤ 0), or every contact.
///
/// Rows are ordered [normal rows of the active contacts, then their tangential rows]. G = Wᵀ M⁻¹ W
/// is formed from a Cholesky factor of M; it may be singular and is never inverted.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "core/detail/accurate_dot.hpp"
#include "core/detail/cholesky.hpp"
#include "core/detail/impact_problem.hpp"
#include "core/detail/refined_solve.hpp"
#include "core/detail/sized_vector.hpp"
#include "core/detail/small_dense.hpp"
#include "fremond/core/error.hpp"
#include "fremond/core/impact_problem.hpp"
#include "fremond/solvers/impact_result.hpp"

namespace fremond::detail {

/// A contact velocity Wᵀq̇ + w (docs/concepts.md) with an accurate dot product: a touching contact
/// (D_NA = 0 up to the data's last bits) takes part or not by the sign of a sum that cancels, and
/// the plain dot product can get that sign wrong (accurate_dot.hpp). Every place that decides or
/// reports D_A and D_E uses this one function, so that they agree to the last bit.
template <class Col, class Vec>
double contact_velocity(const Col& W_col, const Vec& qdot, double w) {
  return accurate_dot(W_col, qdot, w);
}

/// Which contacts a contact space holds. Every contact of a problem takes part in the impact; a
/// separating one (D_NA > 0) carries only the non-penetration reaction, so a solve first leaves
/// the separating ones out (their answer is P = 0 when nothing drives them into the obstacle) and
/// holds every contact only where one of them would penetrate (solve_impact.cpp).
enum class HeldContacts { approaching, every };

template <int MaxDofs, int MaxContacts>
struct ContactSpaceT {
  static constexpr int kMaxRows = times2(MaxContacts);
  using Rows = VecT<kMaxRows>;
  using RowMat = MatT<kMaxRows, kMaxRows>;
  using Jac = MatT<MaxDofs, kMaxRows>;
  using Index = Eigen::Matrix<int, Eigen::Dynamic, 1, Eigen::ColMajor, MaxContacts, 1>;

  int dofs = 0;
  int contacts = 0;  ///< all contacts of the problem
  int active = 0;    ///< contacts held: those with D_NA ≤ 0, or every one (HeldContacts::every)
  bool tangential = false;
  Index index;  ///< active → problem contact index
  Jac W;        ///< n × rows
  Jac MinvW;    ///< M⁻¹ W
  RowMat G;     ///< Delassus matrix of the active rows
  Rows D_A;     ///< contact velocities before, active rows
  /// D_NA and D_TA of every contact (D_T empty without W_T), computed once with
  /// contact_velocity() for the choice of active contacts and reused by the result.
  VecT<MaxContacts> D_N, D_T;
  double v_scale = 0.0;    ///< max |D_A| over the active rows, floored to the smallest normal
  CholeskyT<MaxDofs> llt;  ///< of M

  /// W_iᵀM⁻¹W_i of every contact's normal and tangential direction through llt, which the
  /// classical residual reads at every evaluation: computed once a build, on first use
  /// (self_delassus()), since a problem of 230 contacts on 1,000 dofs spent 78 % of its solve
  /// solving them again.
  mutable VecT<MaxContacts> self_N, self_T;
  mutable bool self_ready = false;
  /// cond(M) as estimated from llt, at least 1, computed once a build on first use: a prepared
  /// solver's every solve on one configuration reads the same number. -1 until then.
  mutable double kappa = -1.0;

  /// cond(M) (kappa, computed here on first use).
  double condition() const {
    if (kappa < 0.0) kappa = std::max(1.0, condition_estimate(llt));
    return kappa;
  }
  /// The relative rounding of G = WᵀM⁻¹W, formed by a solve with M's factor: 16ε cond(M). Every
  /// allowance made for G's rounding (the certificate's, the solvers') is this one number.
  double delassus_rounding() const {
    return 16 * std::numeric_limits<double>::epsilon() * condition();
  }

  int rows() const { return tangential ? 2 * active : active; }
  int normal_row(int i) const { return i; }
  int tangential_row(int i) const { return active + i; }
};

namespace contact_space_detail {

/// M⁻¹W and G for a diagonal M = diag(m) (a body in principal axes: the bar, a point mass, the
/// plate): M⁻¹W is W_ij/m_i, one rounding per entry where L⁻ᵀL⁻¹W takes a square root's and two
/// divisions', and G_jk = Σ_i (W_ij/m_i) W_ik, each pair summed once (exactly symmetric). The
/// factor's square roots are then off the critical path (a third of the bar's contact space would
/// wait on them). Both paths and both storages use this one loop, so that a problem's G has the
/// same bits wherever it is stored: a singular G (two contacts on one dof) leaves the answer
/// sensitive to them at the rounding floor (different bits can move the velocities by 1e-7 of
/// their scale). `column[j]` is row j's column of W (n entries), `M` the mass matrix's column-major
/// data; N > 0 fixes n at compile time. Returns 0 unless an entry is ∞ or NaN (0·∞ = NaN).
template <int N, int MaxDofs, int MaxContacts>
double diagonal_inverse_and_delassus(const double* const* column, const double* M, int n, int r,
                                     ContactSpaceT<MaxDofs, MaxContacts>& cs) {
  if constexpr (N > 0) n = N;
  cs.MinvW.resize(n, r);
  cs.G.resize(r, r);
  double probe = 0.0;
  for (int j = 0; j < r; ++j) {
    double* const x = cs.MinvW.data() + static_cast<std::ptrdiff_t>(n) * j;
    for (int d = 0; d < n; ++d) {
      x[d] = column[j][d] / M[static_cast<std::ptrdiff_t>(d) * (n + 1)];
      probe += 0.0 * x[d];
    }
    for (int k = j; k < r; ++k) {
      double sum = 0.0;
      for (int d = 0; d < n; ++d) sum += x[d] * column[k][d];
      cs.G(j, k) = cs.G(k, j) = sum;
      probe += 0.0 * sum;
    }
  }
  return probe;
}

/// build_contact_space for a stack-stored problem with N dofs (known at compile time) and a
/// diagonal M, the planar and spatial bodies in principal axes and the point masses: the same
/// numbers, bit for bit, as the general path below (the same sums in the same order), with every
/// loop's trip count a constant. The general path spends most of a one-contact impact's contact
/// space on run-time sizes, resizes and copies: 1,260 instructions and 56 ns for the bar's two
/// rows, against 690 and 32 ns here.
/// Returns false where M is not diagonal, M's factor fails or an entry is not finite: the general
/// path then builds the contact space from the start and refuses what it refuses.
template <int N, int MaxDofs, int MaxContacts>
bool build_diagonal_of_size(const ImpactProblemT<MaxDofs, MaxContacts>& pb, bool with_tangential,
                            ContactSpaceT<MaxDofs, MaxContacts>& cs, HeldContacts held) {
  using Col = Eigen::Map<const Eigen::Matrix<double, N, 1>>;
  const bool has_t = pb.has_tangential();
  if (pb.M.cols() != N || pb.qdot_A.size() != N || pb.W_N.rows() != N ||
      (has_t && pb.W_T.rows() != N))
    return false;
  const double* const M = pb.M.data();  // column-major, N × N
  bool diagonal = true;
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i)
      if (i != j) diagonal &= M[i + N * j] == 0.0;  // a NaN is not zero, as in scan_diagonal
  if (!diagonal) return false;
  for (int d = 0; d < N; ++d)
    if (M[d + N * d] <= 0.0) return false;  // the factor's pivot test (a NaN passes it, as there)

  const int c = pb.contacts();
  cs.dofs = N;
  cs.contacts = c;
  cs.tangential = with_tangential && has_t;
  cs.index.resize(c);
  cs.D_N.resize(c);
  cs.D_T.resize(has_t ? c : 0);
  const Col q(pb.qdot_A.data());
  int a = 0;
  for (int i = 0; i < c; ++i) {
    cs.D_N(i) = contact_velocity(Col(pb.W_N.data() + N * i), q, pb.w_N.size() ? pb.w_N(i) : 0.0);
    if (has_t)
      cs.D_T(i) = contact_velocity(Col(pb.W_T.data() + N * i), q, pb.w_T.size() ? pb.w_T(i) : 0.0);
    if (held == HeldContacts::every || cs.D_N(i) <= 0.0) cs.index(a++) = i;
  }
  cs.active = a;
  cs.index.conservativeResize(a);
  const int r = cs.rows();
  // Each row's column, read from the problem: the products below load what was stored long
  // before, not the entries of cs.W just stored one by one (a load that waits on them stalls).
  const double* column[ContactSpaceT<MaxDofs, MaxContacts>::kMaxRows];
  cs.D_A.resize(r);
  for (int k = 0; k < a; ++k) {
    const int i = cs.index(k);
    column[k] = pb.W_N.data() + N * i;
    cs.D_A(k) = cs.D_N(i);
    if (cs.tangential) {
      column[a + k] = pb.W_T.data() + N * i;
      cs.D_A(a + k) = cs.D_T(i);
    }
  }
  cs.W.resize(N, r);
  for (int j = 0; j < r; ++j)
    for (int d = 0; d < N; ++d) cs.W(d, j) = column[j][d];
  if (!(diagonal_inverse_and_delassus<N>(column, M, N, r, cs) == 0.0))
    return false;  // an overflow: the general path names the row
  cs.v_scale = r ? cs.D_A.cwiseAbs().maxCoeff() : 0.0;
  if (!(cs.v_scale > std::numeric_limits<double>::min()))
    cs.v_scale = std::numeric_limits<double>::min();
  // Last: its square roots are needed by no entry above (they would hold up the divisions).
  cs.llt.compute_diagonal(pb.M);
  return true;
}

/// build_diagonal_of_size for the sizes 1, 2, 3 and 6 that fit MaxDofs; false for the others.
template <int MaxDofs, int MaxContacts>
bool build_diagonal(const ImpactProblemT<MaxDofs, MaxContacts>& pb, bool with_tangential,
                    ContactSpaceT<MaxDofs, MaxContacts>& cs,
                    HeldContacts held = HeldContacts::approaching) {
  auto fits = [&](auto size) {
    constexpr int N = decltype(size)::value;
    if constexpr (N <= MaxDofs)
      return pb.dofs() == N && build_diagonal_of_size<N>(pb, with_tangential, cs, held);
    else
      return false;
  };
  // The point masses (1, 2 dofs), the planar rigid bodies (3) and the spatial ones (6).
  return fits(std::integral_constant<int, 3>{}) || fits(std::integral_constant<int, 2>{}) ||
         fits(std::integral_constant<int, 1>{}) || fits(std::integral_constant<int, 6>{});
}

/// Each contact's |Y_i|² from Y = L⁻¹[W_N W_T] (c normal columns, then the tangential ones where
/// `tangential`): its W_iᵀM⁻¹W_i, into N and T.
template <class Y, class Vec>
void column_squares(const Y& y, int c, bool tangential, Vec& N, Vec& T) {
  N.resize(c);
  T.resize(tangential ? c : 0);
  for (int i = 0; i < c; ++i) {
    N(i) = y.col(i).squaredNorm();
    if (tangential) T(i) = y.col(c + i).squaredNorm();
  }
}

}  // namespace contact_space_detail

/// build_contact_space's general path, for every size and mass matrix (build_contact_space takes
/// the fixed-size one where it applies; the tests hold the two to the same bits).
///
/// With M = L Lᵀ and Y = L⁻¹ W: G = WᵀM⁻¹W = YᵀY (a Gram matrix: symmetric and positive
/// semidefinite by construction, also in floating point up to rounding of each entry) and
/// M⁻¹W = L⁻ᵀ Y. Where M is not diagonal and that solve is off by more than rounding (cond(M)·ε),
/// M⁻¹W is refined and G recomputed from it. `factor`, where given, is pb.M's already.
template <int MaxDofs, int MaxContacts>
void build_contact_space_general(const ImpactProblemT<MaxDofs, MaxContacts>& pb,
                                 bool with_tangential, ContactSpaceT<MaxDofs, MaxContacts>& cs,
                                 HeldContacts held = HeldContacts::approaching,
                                 const CholeskyT<MaxDofs>* factor = nullptr) {
  constexpr bool small = MaxDofs != Dynamic;
  const int n = pb.dofs(), c = pb.contacts();
  cs.dofs = n;
  cs.contacts = c;
  cs.tangential = with_tangential && pb.has_tangential();
  if (factor)
    cs.llt = *factor;
  else
    cs.llt.compute(pb.M);
  cs.index.resize(c);
  cs.D_N.resize(c);
  cs.D_T.resize(pb.has_tangential() ? c : 0);
  int a = 0;
  for (int i = 0; i < c; ++i) {
    cs.D_N(i) = contact_velocity(pb.W_N.col(i), pb.qdot_A, pb.w_N.size() ? pb.w_N(i) : 0.0);
    if (pb.has_tangential())
      cs.D_T(i) = contact_velocity(pb.W_T.col(i), pb.qdot_A, pb.w_T.size() ? pb.w_T(i) : 0.0);
    if (held == HeldContacts::every || cs.D_N(i) <= 0.0) cs.index(a++) = i;
  }
  cs.active = a;
  cs.index.conservativeResize(a);
  const int r = cs.rows();
  cs.W.resize(n, r);
  cs.D_A.resize(r);
  for (int k = 0; k < a; ++k) {
    const int i = cs.index(k);
    cs.W.col(k) = pb.W_N.col(i);
    cs.D_A(k) = cs.D_N(i);
    if (cs.tangential) {
      cs.W.col(a + k) = pb.W_T.col(i);
      cs.D_A(a + k) = cs.D_T(i);
    }
  }
  // No row (no contact takes part): nothing to solve. Eigen's triangular solve of a matrix with
  // no column binds a reference to its null data (undefined behaviour, UBSan stops there).
  if (r > 0) {
    if (cs.llt.matrix_is_diagonal()) {
      // A non-positive m_i (M not SPD) leaves a non-finite or negative entry, refused below as
      // the factor's failure is.
      const double* column[small ? ContactSpaceT<MaxDofs, MaxContacts>::kMaxRows : 1];
      std::vector<const double*> heap_column;
      const double** columns = column;
      if constexpr (!small) {
        heap_column.resize(static_cast<std::size_t>(r));
        columns = heap_column.data();
      }
      for (int j = 0; j < r; ++j) columns[j] = cs.W.data() + static_cast<std::ptrdiff_t>(n) * j;
      contact_space_detail::diagonal_inverse_and_delassus<0>(columns, pb.M.data(), n, r, cs);
    } else {
      cs.MinvW = cs.W;  // Y = L⁻¹W, then M⁻¹W = L⁻ᵀY
      cs.llt.solve_lower_in_place(cs.MinvW);
      // Every contact held, with its tangential rows: W is [W_N W_T] and Y holds self_delassus()'s
      // solve, to the last bit.
      if (a == c && cs.tangential == pb.has_tangential()) {
        contact_space_detail::column_squares(cs.MinvW, c, cs.tangential, cs.self_N, cs.self_T);
        cs.self_ready = true;
      }
      if constexpr (small) {
        small_dense::gram(cs.MinvW, cs.G);
      } else {
        cs.G.noalias() = cs.MinvW.transpose() * cs.MinvW;
        cs.G = 0.5 * (cs.G + cs.G.transpose()).eval();
      }
      cs.llt.solve_upper_in_place(cs.MinvW);
    }
    // An ill-conditioned M: M⁻¹W and G to the working precision (refined_solve.hpp). G is then
    // WᵀX from twice-precise sums, symmetrised; a diagonal M needs none.
    if (!cs.llt.matrix_is_diagonal() && refine_solve(pb.M, cs.llt, cs.W, cs.MinvW)) {
      for (int j = 0; j < r; ++j) {
        cs.G(j, j) = std::max(0.0, accurate_dot(cs.W.col(j), cs.MinvW.col(j)));
        for (int k = j + 1; k < r; ++k)
          cs.G(j, k) = cs.G(k, j) = 0.5 * (accurate_dot(cs.W.col(j), cs.MinvW.col(k)) +
                                           accurate_dot(cs.W.col(k), cs.MinvW.col(j)));
      }
    }
    // G = Wᵀ M⁻¹ W of a contact that takes part must be a number: |W|²/|M| beyond 1e308 leaves no
    // percussion representable (P ~ D_A / G), and a factorisation of a matrix holding ∞ is
    // undefined (Eigen's SVD reads out of bounds). The data are finite, their scale is not.
    // The row blamed is one whose own entry or column overflows: a huge W_T makes the normal
    // row's coupling W_Nᵀ M⁻¹ W_T overflow too, and a scan of whole columns named W_N for it
    // (problem-file fuzzing: W_T = 3.5e307 against M = 0.038). Only where no row's own terms
    // overflow is an off-diagonal entry the cause.
    int culprit = -1;
    for (int k = 0; k < r && culprit < 0; ++k)
      if (!(std::isfinite(cs.G(k, k)) && cs.MinvW.col(k).allFinite())) culprit = k;
    for (int k = 0; k < r && culprit < 0; ++k)
      if (!cs.G.col(k).allFinite()) culprit = k;
    if (culprit >= 0) {
      const int k = culprit;
      require_positive_definite(pb.M, cs.llt);  // a singular M is the cause, if it is not SPD
      const bool normal = k < a;
      throw InvalidArgument(normal ? "W_N" : "W_T",
                            "contact " + std::to_string(cs.index(normal ? k : k - a)) +
                                ": the Delassus entry W^T M^-1 W overflows double precision "
                                "(|W|^2 / |M| beyond 1e308); express the problem in other units");
    }
  } else {
    cs.MinvW.resize(n, 0);
    cs.G.resize(0, 0);
  }
  cs.v_scale = r ? cs.D_A.cwiseAbs().maxCoeff() : 0.0;
  if (!(cs.v_scale > std::numeric_limits<double>::min()))
    cs.v_scale = std::numeric_limits<double>::min();
}

/// Builds the contact space; `with_tangential` adds the tangential rows (when W_T has columns),
/// `held` says which contacts it holds. A stack-stored problem of 1, 2, 3 or 6 dofs with a
/// diagonal M takes the fixed-size path (contact_space_detail::build_diagonal), every other one
/// the general path.
template <int MaxDofs, int MaxContacts>
void build_contact_space(const ImpactProblemT<MaxDofs, MaxContacts>& pb, bool with_tangential,
                         ContactSpaceT<MaxDofs, MaxContacts>& cs,
                         HeldContacts held = HeldContacts::approaching) {
  cs.self_ready = false;
  cs.kappa = -1.0;
  if constexpr (MaxDofs != Dynamic)
    if (contact_space_detail::build_diagonal(pb, with_tangential, cs, held)) return;
  build_contact_space_general(pb, with_tangential, cs, held);
}

/// Every contact's own Delassus entries (self_delassus()) of `from` given to `to`, where `from`
/// has them and `to` not: two contact spaces of one configuration (M, W_N, W_T).
template <int MaxDofs, int MaxContacts>
void share_self_delassus(const ContactSpaceT<MaxDofs, MaxContacts>& from,
                         const ContactSpaceT<MaxDofs, MaxContacts>& to) {
  if (!from.self_ready || to.self_ready) return;
  to.self_N = from.self_N;
  to.self_T = from.self_T;
  to.self_ready = true;
}

/// build_contact_space for a problem with the configuration (M, W_N, W_T) of the one `of` was
/// built from, w or q̇_A aside: M's factor is taken from `of`, and every contact's own Delassus
/// entries where `of` has them (the same numbers, to the last bit).
template <int MaxDofs, int MaxContacts>
void build_contact_space_like(const ImpactProblemT<MaxDofs, MaxContacts>& pb, bool with_tangential,
                              const ContactSpaceT<MaxDofs, MaxContacts>& of,
                              ContactSpaceT<MaxDofs, MaxContacts>& cs,
                              HeldContacts held = HeldContacts::approaching) {
  cs.self_ready = false;
  cs.kappa = of.kappa;
  if constexpr (MaxDofs != Dynamic)
    if (contact_space_detail::build_diagonal(pb, with_tangential, cs, held)) return;
  build_contact_space_general(pb, with_tangential, cs, held, &of.llt);
  share_self_delassus(of, cs);
}

/// A new q̇_A on the configuration `cs` was built from (M, W and w unchanged since): every
/// contact's D_N, D_T and, where the contacts held are the ones `cs` holds, D_A and v_scale, the
/// only parts of a contact space that follow the velocity. True then, with cs as
/// build_contact_space would leave it, to the last bit (G, M⁻¹W, the factor and the contacts' own
/// Delassus entries are kept); false, with cs to be built again, where another set of contacts
/// is held.
template <int MaxDofs, int MaxContacts>
bool update_velocities(const ImpactProblemT<MaxDofs, MaxContacts>& pb,
                       ContactSpaceT<MaxDofs, MaxContacts>& cs,
                       HeldContacts held = HeldContacts::approaching) {
  const int c = pb.contacts();
  if (cs.contacts != c || cs.dofs != pb.dofs() || cs.D_N.size() != c) return false;
  const bool has_t = pb.has_tangential();
  int a = 0;
  bool same = true;
  for (int i = 0; i < c; ++i) {
    cs.D_N(i) = contact_velocity(pb.W_N.col(i), pb.qdot_A, pb.w_N.size() ? pb.w_N(i) : 0.0);
    if (has_t)
      cs.D_T(i) = contact_velocity(pb.W_T.col(i), pb.qdot_A, pb.w_T.size() ? pb.w_T(i) : 0.0);
    if (held == HeldContacts::every || cs.D_N(i) <= 0.0) {
      same = same && a < cs.active && cs.index(a) == i;
      ++a;
    }
  }
  if (!same || a != cs.active) return false;
  for (int k = 0; k < a; ++k) {
    const int i = cs.index(k);
    cs.D_A(k) = cs.D_N(i);
    if (cs.tangential) cs.D_A(a + k) = cs.D_T(i);
  }
  const int r = cs.rows();
  cs.v_scale = r ? cs.D_A.cwiseAbs().maxCoeff() : 0.0;
  if (!(cs.v_scale > std::numeric_limits<double>::min()))
    cs.v_scale = std::numeric_limits<double>::min();
  return true;
}

/// W_iᵀM⁻¹W_i of every contact i of `pb` (normal into N, tangential into T: empty without W_T),
/// each as |L⁻¹W_i|² with M = L Lᵀ (one triangular solve of [W_N W_T], and never negative): the
/// classical residual's scales. A contact space that holds every contact with its tangential rows
/// solves the same columns in the same order, and takes them from its own solve
/// (build_contact_space_general).
template <int MaxDofs, int MaxContacts>
void self_delassus(const ImpactProblemT<MaxDofs, MaxContacts>& pb, const CholeskyT<MaxDofs>& llt,
                   VecT<MaxContacts>& N, VecT<MaxContacts>& T) {
  const int c = pb.contacts(), rows = pb.has_tangential() ? 2 * c : c;
  MatT<MaxDofs, times2(MaxContacts)> Y(pb.dofs(), rows);
  if (c > 0) {
    Y.leftCols(c) = pb.W_N;
    if (pb.has_tangential()) Y.rightCols(c) = pb.W_T;
    llt.solve_lower_in_place(Y);
  }
  contact_space_detail::column_squares(Y, c, pb.has_tangential(), N, T);
}

/// self_delassus() of the problem `cs` was built from, through cs's factor of M, computed on first
/// use after a build.
template <int MaxDofs, int MaxContacts>
void self_delassus(const ImpactProblemT<MaxDofs, MaxContacts>& pb,
                   const ContactSpaceT<MaxDofs, MaxContacts>& cs) {
  if (cs.self_ready) return;
  self_delassus(pb, cs.llt, cs.self_N, cs.self_T);
  cs.self_ready = true;
}

/// Which contacts `cs` holds, to build the contact space of the same problem again: a space that
/// holds all of them holds every contact (the approaching ones are then all of them anyway).
template <int MaxDofs, int MaxContacts>
HeldContacts held_by(const ContactSpaceT<MaxDofs, MaxContacts>& cs) {
  return cs.active < cs.contacts ? HeldContacts::approaching : HeldContacts::every;
}

/// velocity_after's plain sum over the first `rows` rows, percussion(j) each: q = q̇_A + M⁻¹W P
/// column by column, zero percussions skipped. True where it stands: fewer than two columns, or
/// terms that do not cancel (in each entry Σ|M⁻¹W_ij P_j| ≤ 8 |q_i − q̇_A,i|, at worst). K: the
/// dofs where fixed (with_size): the same loops, unrolled, the same bits.
template <int K, int MaxDofs, int MaxContacts, class Percussion, class Velocity>
bool plain_velocity_sum(const ImpactProblemT<MaxDofs, MaxContacts>& pb,
                        const ContactSpaceT<MaxDofs, MaxContacts>& cs, int rows,
                        const Percussion& percussion, Velocity& q) {
  const int n = sized<K>(cs.dofs);
  q.resize(n);
  for (int i = 0; i < n; ++i) q(i) = pb.qdot_A(i);
  int moving = 0;  // percussions that are not zero
  for (int j = 0; j < rows; ++j) {
    const double p = percussion(j);
    if (p == 0.0) continue;
    ++moving;
    for (int i = 0; i < n; ++i) q(i) += cs.MinvW(i, j) * p;
  }
  if (moving < 2) return true;  // one term per entry: nothing cancels
  double terms = 0.0, change = 0.0;
  for (int i = 0; i < n; ++i) {
    double t = 0.0;
    for (int j = 0; j < rows; ++j) {
      const double p = percussion(j);
      if (p != 0.0) t += std::fabs(cs.MinvW(i, j) * p);
    }
    terms = std::max(terms, t);
    change = std::max(change, std::fabs(q(i) - pb.qdot_A(i)));
  }
  return !(terms > 8.0 * change);
}

/// The velocity q = q̇_A + M⁻¹W P after the active-row percussions P (size rows()).
///
/// Column by column from M⁻¹W, skipping zero percussions: with |W| near 1e308 a column of M⁻¹W
/// overflows, and 0·∞ would turn the exact "no percussion" answer into NaN. Where the columns'
/// terms cancel (W_T nearly parallel to W_N: percussions 1e4 times the velocity change they make),
/// or where `accurate` asks, the force W P is summed in twice the precision and solved with M
/// (refined): the plain sum would carry ε times the terms, 1e-12 of the velocities, into the
/// answer.
template <int MaxDofs, int MaxContacts>
void velocity_after(const ImpactProblemT<MaxDofs, MaxContacts>& pb,
                    const ContactSpaceT<MaxDofs, MaxContacts>& cs,
                    const typename ContactSpaceT<MaxDofs, MaxContacts>::Rows& P, VecT<MaxDofs>& q,
                    bool accurate = false) {
  const int n = cs.dofs;
  const bool stands = with_size<MaxDofs>(n, [&](auto size) {
    return plain_velocity_sum<decltype(size)::value>(
        pb, cs, cs.rows(), [&](int j) { return P(j); }, q);
  });
  if (stands && !accurate) return;
  VecT<MaxDofs> f(n);
  accurate_residual(cs.W, P, VecT<MaxDofs>::Zero(n), f);  // 0 − W P
  f = -f;
  VecT<MaxDofs> x = cs.llt.solve(f);
  if (!cs.llt.matrix_is_diagonal()) refine_solve(pb.M, cs.llt, f, x);
  if (x.allFinite()) q = pb.qdot_A + x;
}

/// T_E − T_A = ½(q̇_E − q̇_A)ᵀ M (q̇_E + q̇_A) = P·z (eq. 9), computed from the velocities q̇_E.
/// No percussion changes nothing: zero exactly, also where M(q̇_E + q̇_A) overflows (0·∞).
/// `diagonal`: M is known to be diagonal (CholeskyT::matrix_is_diagonal).
/// `qE` is a VecT<MaxDofs> or, for the stack-stored sizes, a vector of the dofs' fixed size.
template <int MaxDofs, int MaxContacts, class Velocity>
double energy_change_at(const ImpactProblemT<MaxDofs, MaxContacts>& pb, const Velocity& qE,
                        bool diagonal = false) {
  const int n = sized<Velocity::SizeAtCompileTime>(pb.dofs());
  bool moved = false;
  for (int i = 0; i < n && !moved; ++i) moved = qE(i) != pb.qdot_A(i);
  if (!moved) return 0.0;
  if constexpr (MaxDofs != Dynamic) {
    if (diagonal) {
      // The loop below with its exact zeros left out: from +0, adding the products 0·x (±0) leaves
      // +0 or the one nonzero term, so each row's sum is 0.0 + M_ii(q̇_E,i + q̇_A,i), the same bits.
      // Only where a product is not finite would 0·∞ have made it NaN: that case takes the loop.
      double e = 0.0;
      for (int i = 0; i < n; ++i)
        e += (qE(i) - pb.qdot_A(i)) * (0.0 + pb.M(i, i) * (qE(i) + pb.qdot_A(i)));
      if (std::isfinite(e)) return 0.5 * e;
    }
    double e = 0.0;  // fused: no temporary
    for (int i = 0; i < n; ++i) {
      double Ms = 0.0;
      for (int j = 0; j < n; ++j) Ms += pb.M(i, j) * (qE(j) + pb.qdot_A(j));
      e += (qE(i) - pb.qdot_A(i)) * Ms;
    }
    return 0.5 * e;
  } else {
    const auto dq = (qE - pb.qdot_A).eval();
    return 0.5 * dq.dot(pb.M * (qE + pb.qdot_A));
  }
}

/// Fills the percussions, contact velocities and energy change of `out` from the active-row
/// percussions P (size rows()) and the velocities already in out.qdot_E. Contacts that do not take
/// part get zero percussion.
template <int MaxDofs, int MaxContacts>
void scatter_at_velocities(const ImpactProblemT<MaxDofs, MaxContacts>& pb,
                           const ContactSpaceT<MaxDofs, MaxContacts>& cs,
                           const typename ContactSpaceT<MaxDofs, MaxContacts>::Rows& P,
                           ImpactResultT<MaxDofs, MaxContacts>& out) {
  const int c = cs.contacts;
  out.P_N.setZero(c);
  out.P_T.setZero(c);
  for (int k = 0; k < cs.active; ++k) {
    out.P_N(cs.index(k)) = P(k);
    if (cs.tangential) out.P_T(cs.index(k)) = P(cs.active + k);
  }
  out.D_NA = cs.D_N;
  out.D_NE.resize(c);
  out.D_TE.setZero(c);
  if (pb.has_tangential())
    out.D_TA = cs.D_T;
  else
    out.D_TA.setZero(c);
  out.takes_part.resize(c);
  for (int i = 0; i < c; ++i) {
    out.D_NE(i) = contact_velocity(pb.W_N.col(i), out.qdot_E, pb.w_N.size() ? pb.w_N(i) : 0.0);
    out.takes_part(i) = out.D_NA(i) <= 0.0 ? 1 : 0;
    if (pb.has_tangential())
      out.D_TE(i) = contact_velocity(pb.W_T.col(i), out.qdot_E, pb.w_T.size() ? pb.w_T(i) : 0.0);
  }
  out.energy_change = energy_change_at(pb, out.qdot_E, cs.llt.matrix_is_diagonal());
}

/// Fills the velocities, percussions and energy change of `out` from the active-row percussions P
/// (size rows()). Contacts that do not take part get zero percussion.
template <int MaxDofs, int MaxContacts>
void scatter_solution(const ImpactProblemT<MaxDofs, MaxContacts>& pb,
                      const ContactSpaceT<MaxDofs, MaxContacts>& cs,
                      const typename ContactSpaceT<MaxDofs, MaxContacts>::Rows& P,
                      ImpactResultT<MaxDofs, MaxContacts>& out) {
  velocity_after(pb, cs, P, out.qdot_E);
  scatter_at_velocities(pb, cs, P, out);
}

}  // namespace fremond::detail
