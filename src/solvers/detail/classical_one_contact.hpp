#pragma once
/// @file The first stage of the classical chain where it applies: Newton's law (eq. 5) or
/// Poisson's (its compression, then its expansion), with or without Coulomb's friction
/// (eqs. 7-8), on a problem of one contact that approaches, on a body whose M is diagonal (a bar,
/// a disc, a point mass in their principal axes). The closed forms of one_contact, the velocities
/// and the residual read at them, all on scalars: the contact modes' answer to the last bit,
/// without their lists, loops over contacts and dynamic-size vectors (docs/solvers.md).
#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_space/contact_space.hpp"
#include "core/detail/sized_vector.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/solver_options.hpp"
#include "laws/restitution/row_maps.hpp"
#include "solvers/detail/classical_phase.hpp"

namespace fremond::detail::classical {

/// Where the stage applies: the closed form allowed (automatic or closed_form), one contact in
/// the problem and it approaching (D_NA ≤ 0), M diagonal.
template <int N, int C>
bool one_approaching_contact(const ContactSpaceT<N, C>& cs, const SolverOptions& options) {
  return cs.contacts == 1 && cs.active == 1 && cs.D_N(0) <= 0.0 &&
         (options.method == SolverMethod::automatic ||
          options.method == SolverMethod::closed_form) &&
         cs.llt.matrix_is_diagonal();
}

/// q = q̇_A + M⁻¹W P for the contact's rows P (P[1] the tangential one, 0 without), as
/// velocity_after makes it, the same bits: the plain sum, or where its terms cancel (a sliding
/// contact whose normal and tangential torques nearly cancel) the force summed in twice the
/// precision. False where q is not finite. K: the dofs, where fixed.
template <int K, int N, int C>
bool one_contact_velocity_after(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                                const double (&P)[2], SizedVecT<K, N>& q) {
  const int rows = cs.tangential ? 2 : 1;
  if (!plain_velocity_sum<K>(
          pb, cs, rows, [&](int j) { return P[j]; }, q)) {
    typename ContactSpaceT<N, C>::Rows rows_P(rows);
    for (int j = 0; j < rows; ++j) rows_P(j) = P[j];
    VecT<N> refined;
    velocity_after(pb, cs, rows_P, refined);
    q = refined;
  }
  for (int i = 0; i < q.size(); ++i)
    if (!std::isfinite(q(i))) return false;
  return true;
}

/// Σ_i |W_i| u_i over W's column `col` (n entries), in order.
template <int K, int N>
double abs_dot(const double* col, const SizedVecT<K, N>& u) {
  double s = 0.0;
  for (int i = 0; i < u.size(); ++i) s += std::fabs(col[i]) * u(i);
  return s;
}

/// The answer of one_approaching_contact's problems, written into `out` (a cleared result) when
/// the contact modes would give it unchanged: one solution of the closed forms (G regular; for
/// Poisson one compression and one expansion) and a residual settled at its velocities
/// (residual_at_own_velocities). False, `out` untouched, otherwise: the contact modes then run as
/// they always do. Each number is computed as the general path computes it, in the same order, so
/// that the answers agree bit for bit.
///
/// K is the number of dofs where the stack-stored sizes fix it (with_size), Eigen::Dynamic
/// otherwise: the same loops, unrolled on the paper's planar bodies.
template <int K, int N, int C>
bool settle_one_contact_sized(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                              const RestitutionLaw& law, const SolverOptions& options,
                              ImpactResultT<N, C>& out) {
  const int rows = cs.tangential ? 2 : 1;
  const bool f = cs.tangential, tangential = pb.has_tangential(), poisson = law.has_phases();
  const double gnn = cs.G(0, 0), gnt = f ? cs.G(0, 1) : 0.0, gtt = f ? cs.G(1, 1) : 0.0;
  const double dna = cs.D_A(0), dta = f ? cs.D_A(1) : 0.0;
  const double e = law.e[0], mu = f ? law.mu[0] : 0.0;
  Tolerances tol;
  tol.v = 1e-9 * cs.v_scale;
  tol.p = tol.v / std::max({gnn, gtt, std::numeric_limits<double>::min()});
  // The law's phases by their closed forms (solve_law_one_contact): Newton's one, or Poisson's
  // compression and then its expansion from P_NE = e P_NC with the bound μ P_NE.
  const OneContact first =
      one_contact(gnn, gnt, gtt, poisson ? dna : (1 + e) * dna, dta, mu, 0.0, f, tol);
  if (first.degenerate || first.count != 1) return false;
  double P[2] = {first.x[0], f ? first.t[0] : 0.0}, P_C[2] = {0.0, 0.0};
  if (poisson) {
    const double xc = first.x[0], tc = first.t[0], s = e * xc;
    const double dnc = dna + gnn * xc + gnt * tc, dtc = dta + gnt * xc + gtt * tc;
    const OneContact second =
        one_contact(gnn, gnt, gtt, dnc + gnn * s, dtc + gnt * s, mu, mu * s, f, tol);
    if (second.degenerate || second.count != 1) return false;
    P_C[0] = xc;
    P_C[1] = f ? tc : 0.0;
    P[0] = xc + s + second.x[0];
    P[1] = f ? tc + second.t[0] : 0.0;
  }
  if (!std::isfinite(P[0]) || !std::isfinite(P[1]) || !std::isfinite(P_C[0]) ||
      !std::isfinite(P_C[1]))
    return false;

  // The velocities, the contact velocities after and T_E − T_A (write_classical_answer).
  SizedVecT<K, N> q, qC;
  if (!one_contact_velocity_after<K>(pb, cs, P, q)) return false;
  if (poisson && !one_contact_velocity_after<K>(pb, cs, P_C, qC)) return false;
  const double wn = pb.w_N.size() ? pb.w_N(0) : 0.0, wt = pb.w_T.size() ? pb.w_T(0) : 0.0;
  const double D_NE = contact_velocity(pb.W_N.col(0), q, wn);
  const double D_TE = tangential ? contact_velocity(pb.W_T.col(0), q, wt) : 0.0;
  const double D_NC = poisson ? contact_velocity(pb.W_N.col(0), qC, wn) : 0.0;
  const double D_TC = poisson && tangential ? contact_velocity(pb.W_T.col(0), qC, wt) : 0.0;
  const double energy = energy_change_at(pb, q, true);

  // The residual at these velocities (residual_at_own_velocities), within its share of the
  // tolerance; else the data's residual decides, on the general path.
  SizedVecT<K, N> u = velocity_terms<K>(cs, rows, [&](int j) { return P[j]; });
  if (poisson) u = u.cwiseMax(velocity_terms<K>(cs, rows, [&](int j) { return P_C[j]; }));
  const double floor = 2.0 * (rows + 2) * std::numeric_limits<double>::epsilon();
  const double dn = cs.D_N(0), dt = tangential ? cs.D_T(0) : 0.0;
  double terms = std::max(0.0, abs_dot<K, N>(pb.W_N.data(), u));
  if (tangential) terms = std::max(terms, abs_dot<K, N>(pb.W_T.data(), u));
  const double v_scale =
      std::max({std::numeric_limits<double>::min(), std::fabs(dn), std::fabs(dt)});
  const double gn = gnn > 0.0 ? gnn : 1.0, gt = f ? (gtt > 0.0 ? gtt : 1.0) : 1.0;
  const double worst =
      worst_row_map(poisson, tangential, e, law.has_friction() ? law.mu[0] : 0.0, dn, gn, gt,
                    {.D_NE = D_NE,
                     .D_TE = D_TE,
                     .P_N = P[0],
                     .P_T = P[1],
                     .D_NC = D_NC,
                     .D_TC = D_TC,
                     .P_NC = P_C[0],
                     .P_TC = P_C[1]});
  const double allowed = kOwnVelocityShare * options.tolerance * v_scale;
  if (!(floor * terms <= allowed) || !(worst <= allowed)) return false;
  const double residual = worst / v_scale;
  if (!std::isfinite(D_NE) || !std::isfinite(D_TE) || !std::isfinite(D_NC) ||
      !std::isfinite(D_TC) || !std::isfinite(energy) || !std::isfinite(residual))
    return false;

  out.qdot_E = q;
  out.P_N.resize(1);
  out.P_T.resize(1);
  out.P_N(0) = P[0];
  out.P_T(0) = P[1];
  // Entry by entry: Eigen's assignment of a run-time-size vector is a call and a loop.
  out.D_NA.resize(1);
  out.D_NA(0) = cs.D_N(0);
  out.D_NE.resize(1);
  out.D_NE(0) = D_NE;
  out.D_TA.resize(1);
  out.D_TA(0) = tangential ? cs.D_T(0) : 0.0;
  out.D_TE.resize(1);
  out.D_TE(0) = D_TE;
  out.takes_part.resize(1);
  out.takes_part(0) = dn <= 0.0 ? 1 : 0;
  out.energy_change = energy;
  out.has_phases = poisson;
  if (poisson) {
    out.P_NC.resize(1);
    out.P_TC.resize(1);
    out.P_NC(0) = P_C[0];
    out.P_TC(0) = P_C[1];
    out.qdot_C = qC;
    out.D_NC.resize(1);
    out.D_NC(0) = D_NC;
    out.D_TC.resize(1);
    out.D_TC(0) = D_TC;
  } else {
    out.qdot_C.resize(0);
  }
  // The report of a unique, exact answer (report_solution).
  out.unique = true;
  out.solutions_found = 1;
  out.solver.method = SolverMethod::closed_form;
  out.solver.criterion = StopCriterion::exact;
  out.solver.iterations = 0;
  out.solver.fallbacks = 0;
  out.solver.residual = residual;
  out.solver.message = "the unique solution";
  out.solver.status = SolverStatus::converged;
  return true;
}

/// settle_one_contact_sized on the problem's own number of dofs.
template <int N, int C>
bool settle_one_contact(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                        const RestitutionLaw& law, const SolverOptions& options,
                        ImpactResultT<N, C>& out) {
  return with_size<N>(cs.dofs, [&](auto size) {
    return settle_one_contact_sized<decltype(size)::value>(pb, cs, law, options, out);
  });
}

}  // namespace fremond::detail::classical
