// The one residual of the classical laws (laws/residual.hpp), used by the solvers to report and by
// the tests to check: the natural map of each complementarity and of Coulomb's law, in velocity
// units, at the result's velocities where they balance its percussions, else at velocities
// recomputed from the percussions.
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_space/contact_space.hpp"
#include "core/detail/accurate_dot.hpp"
#include "core/detail/refined_solve.hpp"
#include "laws/detail/residuals.hpp"
#include "laws/restitution/row_maps.hpp"

namespace fremond::detail {

namespace {

/// Whether q satisfies M(q − q̇_A) = W_N P_N + W_T P_T to 16ε times the size of each row's terms
/// (Σ_j |M_kj|(|q_j| + |q̇_A,j|) + Σ_i |W_ki P_i|): the backward error of a momentum balance whose
/// every term is rounded once. Each row summed by Dot2 (accurate_dot.hpp), since its terms cancel
/// to the velocity change. For q̇_E with P, and Poisson's q̇_C with P_C.
template <int N, int C>
bool balances_percussions(const ImpactProblemT<N, C>& pb, const VecT<N>& q, const VecT<C>& PN,
                          const VecT<C>& PT) {
  const int n = pb.dofs(), c = pb.contacts();
  const bool tangential = pb.has_tangential();
  if (q.size() != n || !q.allFinite() || PN.size() != c || (tangential && PT.size() != c))
    return false;
  const int terms = n + (tangential ? 2 * c : c);
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, N == Dynamic ? Dynamic : N + times2(C), 1> row(terms),
      x(terms);
  for (int j = 0; j < n; ++j) x(j) = q(j) - pb.qdot_A(j);
  for (int i = 0; i < c; ++i) {
    x(n + i) = -PN(i);
    if (tangential) x(n + c + i) = -PT(i);
  }
  constexpr double eps16 = 16 * std::numeric_limits<double>::epsilon();
  for (int k = 0; k < n; ++k) {
    double size = 0.0;
    for (int j = 0; j < n; ++j) {
      row(j) = pb.M(k, j);
      size += std::fabs(pb.M(k, j)) * (std::fabs(q(j)) + std::fabs(pb.qdot_A(j)));
    }
    for (int i = 0; i < c; ++i) {
      row(n + i) = pb.W_N(k, i);
      size += std::fabs(pb.W_N(k, i) * PN(i));
      if (!tangential) continue;
      row(n + c + i) = pb.W_T(k, i);
      size += std::fabs(pb.W_T(k, i) * PT(i));
    }
    const double imbalance = accurate_dot(row, x);
    if (!std::isfinite(size) || !(std::fabs(imbalance) <= eps16 * size)) return false;
  }
  return true;
}

/// classical_residual with M's factor and every contact's W_iᵀM⁻¹W_i (self_delassus()) given.
template <int N, int C>
double residual_with(const ImpactProblemT<N, C>& pb, const RestitutionLaw& law,
                     const ImpactResultT<N, C>& r, const detail::CholeskyT<N>& llt,
                     const VecT<C>& self_N, const VecT<C>& self_T, double* beyond_rounding,
                     bool percussions_rounded, double percussion_cap) {
  const double inf = std::numeric_limits<double>::infinity();
  const int n = pb.dofs(), c = pb.contacts();
  const bool tangential = pb.has_tangential();
  const bool poisson = law.has_phases();
  const bool friction = law.has_friction();
  if (r.P_N.size() != c || r.P_T.size() != c) return inf;
  if (poisson && (!r.has_phases || r.P_NC.size() != c || r.P_TC.size() != c)) return inf;

  const bool diagonal = detail::is_diagonal(pb.M);
  auto wn = [&](int i) { return pb.w_N.size() ? pb.w_N(i) : 0.0; };
  auto wt = [&](int i) { return pb.w_T.size() ? pb.w_T(i) : 0.0; };
  // Velocities after the percussions (PN, PT), from the problem data only.
  auto velocity = [&](const VecT<C>& PN, const VecT<C>& PT) {
    // f = W_N P_N + W_T P_T, summed again in twice the precision where its terms cancel: with W_T
    // nearly parallel to W_N the percussions are 1e4 times the velocities they make, and the plain
    // sum carries ε·1e4 of noise into every velocity it yields.
    VecT<N> f(n);
    double terms = 0.0, largest = 0.0;
    for (int k = 0; k < n; ++k) {
      double sum = 0.0, size = 0.0;
      for (int i = 0; i < c; ++i) {
        const double x = pb.W_N(k, i) * PN(i), y = tangential ? pb.W_T(k, i) * PT(i) : 0.0;
        sum += x + y;
        size += std::fabs(x) + std::fabs(y);
      }
      f(k) = sum;
      terms = std::max(terms, size);
      largest = std::max(largest, std::fabs(sum));
    }
    if (terms > 8.0 * largest) {
      VecT<times2(C)> wk(tangential ? 2 * c : c), pk(tangential ? 2 * c : c);
      pk.head(c) = PN;
      if (tangential) pk.tail(c) = PT;
      for (int k = 0; k < n; ++k) {
        wk.head(c) = pb.W_N.row(k).transpose();
        if (tangential) wk.tail(c) = pb.W_T.row(k).transpose();
        f(k) = accurate_dot(wk, pk);
      }
    }
    // Refined where M is not diagonal: through the plain factor an ill-conditioned M (cond 3e10)
    // shows 1e-14 where the answer misses the law by 1e-6 (refined_solve.hpp).
    VecT<N> x = llt.solve(f);
    if (!diagonal) detail::refine_solve(pb.M, llt, f, x);
    VecT<N> q = pb.qdot_A;
    q += x;
    return q;
  };
  // Poisson's compression velocities, and the percussions' part of the floors: of P alone.
  VecT<N> qC(n);
  if (poisson) qC = velocity(r.P_NC, r.P_TC);
  // With percussions_rounded, Σ_k |G_jk||P_k| (G = WᵀM⁻¹W over every row of the problem): the
  // percussions are stored in double precision, each to ε|P_k|, and where W_T is nearly parallel
  // to W_N they are 1e4 times the velocities they make, so even correctly rounded percussions
  // move the velocities by ε Σ_k |G_jk||P_k|. That part of the floor is capped at 1e-10 of the
  // velocities, not 1e-6: with cond(G) = 2.5e11 (cond(M) > 1e9) the terms reach 1e-6 of the
  // velocities, and an answer in the wrong mode (a contact open whose true percussion is 5 % of
  // the others) met the law that closely, 8e-7 away from the quad reference.
  const int rows = tangential ? 2 * c : c;
  MatT<N, times2(C)> MinvW_all;
  VecT<times2(C)> P_abs;
  if (beyond_rounding && percussions_rounded) {
    MinvW_all.resize(n, rows);
    P_abs.resize(rows);
    MinvW_all.leftCols(c) = pb.W_N;
    P_abs.head(c) = r.P_N.cwiseAbs();
    if (poisson) P_abs.head(c) += r.P_NC.cwiseAbs();
    if (tangential) {
      MinvW_all.rightCols(c) = pb.W_T;
      P_abs.tail(c) = r.P_T.cwiseAbs();
      if (poisson) P_abs.tail(c) += r.P_TC.cwiseAbs();
    }
    llt.solve_lower_in_place(MinvW_all);
    llt.solve_upper_in_place(MinvW_all);
  }
  // The law at velocities qE and Poisson's qC (and the floors, into *beyond when asked).
  auto evaluate = [&](const VecT<N>& qE, const VecT<N>& q_C, double* beyond_rounding) {
    // |W_i|ᵀ(|q̇_A| + |q̇_E| + |q̇_C|): the size of the terms every velocity of contact i is summed
    // from. A grazing contact of a spinning body (D_NA = −6e-4 from terms of 1.2) is known only to
    // ε times that, far above ε|D_NA|.
    // Only where asked for: the stopping test asks only when the residual misses the tolerance.
    VecT<N> q_abs(n);
    if (beyond_rounding) {
      q_abs = pb.qdot_A.cwiseAbs() + qE.cwiseAbs();
      if (poisson) q_abs += q_C.cwiseAbs();
    }
    // Σ_k |W_jᵀ M⁻¹W_k| |P_k| for the direction W_j; zero percussions add nothing (also where their
    // column overflows).
    auto percussion_terms = [&](const auto& W_j) {
      double t = 0.0;
      if (!percussions_rounded) return t;
      for (int k = 0; k < rows; ++k)
        if (P_abs(k) != 0.0) t += std::fabs(W_j.dot(MinvW_all.col(k))) * P_abs(k);
      return t;
    };
    double v_scale = std::numeric_limits<double>::min(), worst = 0.0;
    VecT<C> contact_worst = VecT<C>::Zero(c), contact_floor = VecT<C>::Zero(c),
            percussion_floor = VecT<C>::Zero(c);
    for (int i = 0; i < c; ++i) {
      const double dna = contact_velocity(pb.W_N.col(i), pb.qdot_A, wn(i));
      const double dta = tangential ? contact_velocity(pb.W_T.col(i), pb.qdot_A, wt(i)) : 0.0;
      const double gn = self_N(i) > 0 ? self_N(i) : 1.0;
      const double gt = tangential && self_T(i) > 0 ? self_T(i) : 1.0;
      // The rounding floor of the contact's terms, as in Frémond's stopping test
      // (row_rounding_floor): 16ε times the size of the terms, capped at 1e-6 of the velocities
      // (the percussions' part at 1e-10, above).
      if (beyond_rounding) {
        double floor = std::fabs(wn(i)) + pb.W_N.col(i).cwiseAbs().dot(q_abs);
        double terms = percussion_terms(pb.W_N.col(i));
        if (tangential) {
          floor += std::fabs(wt(i)) + pb.W_T.col(i).cwiseAbs().dot(q_abs);
          terms += percussion_terms(pb.W_T.col(i));
        }
        floor *= 16.0 * std::numeric_limits<double>::epsilon();
        terms *= 16.0 * std::numeric_limits<double>::epsilon();
        contact_floor(i) = std::isfinite(floor) ? floor : 0.0;
        percussion_floor(i) = std::isfinite(terms) ? terms : 0.0;
      }
      auto keep = [&](double x) {
        const double a = std::isnan(x) ? inf : std::fabs(x);
        worst = std::max(worst, a);
        contact_worst(i) = std::max(contact_worst(i), a);
      };
      // A separating contact (D_NA > 0) obeys the law with its restitution on min(D_NA, 0) = 0
      // (docs/concepts.md): Newton's e D_NA drops out, Poisson's phases stay as they are.
      // Undriven, P = 0 meets it exactly. The velocity scale is the approaching contacts'.
      const bool separating = dna > 0.0;
      if (!separating) v_scale = std::max({v_scale, std::fabs(dna), std::fabs(dta)});
      const double e = separating && !poisson ? 0.0 : law.e[i];
      const double mu = friction ? law.mu[i] : 0.0;
      const double dne = contact_velocity(pb.W_N.col(i), qE, wn(i));
      const double dte = tangential ? contact_velocity(pb.W_T.col(i), qE, wt(i)) : 0.0;
      if (!poisson) {
        keep(complementarity(dne + e * dna, r.P_N(i), gn));  // eq. 5 as a complementarity
        if (tangential) keep(coulomb(r.P_T(i), dte, mu * r.P_N(i), gt));
        continue;
      }
      // Poisson: compression, then expansion with P_NE = e P_NC + ΔP (docs/laws.md).
      const double dnc = contact_velocity(pb.W_N.col(i), q_C, wn(i));
      const double dtc = tangential ? contact_velocity(pb.W_T.col(i), q_C, wt(i)) : 0.0;
      keep(complementarity(dnc, r.P_NC(i), gn));
      if (tangential) keep(coulomb(r.P_TC(i), dtc, mu * r.P_NC(i), gt));
      const double pne = r.P_N(i) - r.P_NC(i), pte = r.P_T(i) - r.P_TC(i);
      keep(complementarity(dne, pne - e * r.P_NC(i), gn));
      if (tangential) keep(coulomb(pte, dte, mu * pne, gt));
    }
    if (beyond_rounding) {
      double beyond = 0.0;
      for (int i = 0; i < c; ++i)
        if (!(contact_worst(i) <= std::min(contact_floor(i), 1e-6 * v_scale) +
                                      std::min(percussion_floor(i), percussion_cap * v_scale)))
          beyond = std::max(beyond, contact_worst(i));
      *beyond_rounding = beyond / v_scale;
    }
    return worst / v_scale;
  };
  // At the velocities the percussions make; and, where those miss the law beyond 64ε, at the
  // result's own q̇_E (and Poisson's q̇_C) where it balances its percussions, M(q̇_E − q̇_A) =
  // W_N P_N + W_T P_T, to the rounding of that equation's terms, the smaller of the two. P and q̇_E
  // are each the exact answer rounded where the contact mode was solved for both, M only
  // multiplied (classical_velocity_mode.hpp), and on an ill-conditioned M (cond 1e9) the
  // velocities made from the rounded P are then 1e-6 off the law that q̇_E meets to 1e-16.
  // Velocities that do not balance their percussions (or none) are not read: the result is judged
  // by its percussions there.
  const VecT<N> qE_P = velocity(r.P_N, r.P_T);
  double beyond_P = 0.0;
  const double at_P = evaluate(qE_P, qC, beyond_rounding ? &beyond_P : nullptr);
  double residual = at_P;
  if (!(at_P <= 64 * std::numeric_limits<double>::epsilon())) {
    const bool own_E = balances_percussions(pb, r.qdot_E, r.P_N, r.P_T);
    const bool own_C = poisson && balances_percussions(pb, r.qdot_C, r.P_NC, r.P_TC);
    if (own_E || own_C) {
      double beyond_E = 0.0;
      const double at_E = evaluate(own_E ? r.qdot_E : qE_P, own_C ? r.qdot_C : qC,
                                   beyond_rounding ? &beyond_E : nullptr);
      if (at_E < at_P) {
        residual = at_E;
        beyond_P = beyond_E;
      }
    }
  }
  if (beyond_rounding) *beyond_rounding = beyond_P;
  return residual;
}

}  // namespace

template <int N, int C>
double classical_residual(const ImpactProblemT<N, C>& pb, const RestitutionLaw& law,
                          const ImpactResultT<N, C>& r, double* beyond_rounding,
                          bool percussions_rounded, double percussion_cap) {
  const detail::CholeskyT<N> llt(pb.M);
  VecT<C> self_N, self_T;
  self_delassus(pb, llt, self_N, self_T);
  return residual_with(pb, law, r, llt, self_N, self_T, beyond_rounding, percussions_rounded,
                       percussion_cap);
}

template <int N, int C>
double classical_residual(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                          const RestitutionLaw& law, const ImpactResultT<N, C>& r,
                          double* beyond_rounding, bool percussions_rounded,
                          double percussion_cap) {
  self_delassus(pb, cs);
  return residual_with(pb, law, r, cs.llt, cs.self_N, cs.self_T, beyond_rounding,
                       percussions_rounded, percussion_cap);
}

template <int N, int C>
bool residual_at_own_velocities(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                                const RestitutionLaw& law,
                                const typename ContactSpaceT<N, C>::Rows& P,
                                const typename ContactSpaceT<N, C>::Rows& P_C,
                                const ImpactResultT<N, C>& r, double tolerance, double* value) {
  const int n = cs.dofs, c = cs.contacts, rows = cs.rows();
  const bool tangential = pb.has_tangential(), poisson = law.has_phases();
  if (!cs.llt.matrix_is_diagonal() || r.qdot_E.size() != n || r.D_NE.size() != c ||
      (tangential && r.D_TE.size() != c) || !r.qdot_E.allFinite())
    return false;
  if (poisson &&
      (!r.has_phases || P_C.size() != rows || r.qdot_C.size() != n || r.D_NC.size() != c ||
       (tangential && r.D_TC.size() != c) || !r.qdot_C.allFinite()))
    return false;
  // u = Σ_j |M⁻¹W_j P_j|: what q̇_E − q̇_A is summed from (Poisson: the larger of it and the same
  // sum for q̇_C); W's rows on it bound the rounding of every contact velocity after.
  VecT<N> u = velocity_terms(cs, rows, P);
  if (poisson) u = u.cwiseMax(velocity_terms(cs, rows, P_C));
  // Both velocities are sums of at most rows + c + 3 rounded terms of size `terms`.
  const double floor = 2.0 * (rows + 2) * std::numeric_limits<double>::epsilon();
  double v_scale = std::numeric_limits<double>::min(), worst = 0.0, terms = 0.0;
  for (int i = 0; i < c; ++i) {
    const double dna = cs.D_N(i), dta = tangential ? cs.D_T(i) : 0.0;
    terms = std::max(terms, pb.W_N.col(i).cwiseAbs().dot(u));
    if (tangential) terms = std::max(terms, pb.W_T.col(i).cwiseAbs().dot(u));
    const bool separating = dna > 0.0;
    if (!separating) v_scale = std::max({v_scale, std::fabs(dna), std::fabs(dta)});
    // Newton's e D_NA drops out on a separating contact; Poisson's phases stay as they are.
    const double e = separating && !poisson ? 0.0 : law.e[i];
    const double mu = law.has_friction() ? law.mu[i] : 0.0;
    const double PN = r.P_N(i), PT = tangential ? r.P_T(i) : 0.0;
    // The contact's own G_ii where it takes part; a separating one carries P = 0 and needs none.
    double gn = 1.0, gt = 1.0;
    for (int k = 0; k < cs.active; ++k)
      if (cs.index(k) == i) {
        gn = cs.G(k, k) > 0.0 ? cs.G(k, k) : 1.0;
        if (cs.tangential)
          gt = cs.G(cs.active + k, cs.active + k) > 0.0 ? cs.G(cs.active + k, cs.active + k) : 1.0;
      }
    ContactAnswer answer{
        .D_NE = r.D_NE(i), .D_TE = tangential ? r.D_TE(i) : 0.0, .P_N = PN, .P_T = PT};
    if (poisson) {
      answer.D_NC = r.D_NC(i);
      answer.D_TC = tangential ? r.D_TC(i) : 0.0;
      answer.P_NC = r.P_NC(i);
      answer.P_TC = tangential ? r.P_TC(i) : 0.0;
    }
    worst = std::max(worst, worst_row_map(poisson, tangential, e, mu, dna, gn, gt, answer));
  }
  // Each within 45 % of the tolerance: the data's residual, within their sum of this one (both
  // maps are 1-Lipschitz in the velocities), then stays within it.
  if (!(floor * terms <= kOwnVelocityShare * tolerance * v_scale) ||
      !(worst <= kOwnVelocityShare * tolerance * v_scale))
    return false;
  *value = worst / v_scale;
  return true;
}

#define FREMOND_INSTANTIATE(N, C)                                                                \
  template double classical_residual(const ImpactProblemT<N, C>&, const RestitutionLaw&,         \
                                     const ImpactResultT<N, C>&, double*, bool, double);         \
  template double classical_residual(const ImpactProblemT<N, C>&, const ContactSpaceT<N, C>&,    \
                                     const RestitutionLaw&, const ImpactResultT<N, C>&, double*, \
                                     bool, double);                                              \
  template bool residual_at_own_velocities(                                                      \
      const ImpactProblemT<N, C>&, const ContactSpaceT<N, C>&, const RestitutionLaw&,            \
      const typename ContactSpaceT<N, C>::Rows&, const typename ContactSpaceT<N, C>::Rows&,      \
      const ImpactResultT<N, C>&, double, double*);
FREMOND_INSTANTIATE(Dynamic, Dynamic)
FREMOND_INSTANTIATE(kSmallDofs, kSmallContacts)
#undef FREMOND_INSTANTIATE

}  // namespace fremond::detail
