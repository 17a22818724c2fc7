#pragma once
/// @file The first stage of the classical chain where it applies: Newton's law (eq. 5, with
/// Coulomb's eqs. 7-8) on a problem of one contact that approaches, on a body whose M is diagonal
/// (a bar, a disc, a point mass in their principal axes). The closed form of one_contact, its
/// velocities and its residual read at them, all on scalars: the contact modes' answer to the last
/// bit, without their lists, loops over contacts and dynamic-size vectors (docs/solvers.md).
#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_space/contact_space.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/solver_options.hpp"
#include "laws/restitution/row_maps.hpp"
#include "solvers/detail/classical_phase.hpp"

namespace fremond::detail::classical {

/// Where the stage applies: Newton's law (no phases), the closed form allowed (automatic or
/// closed_form), one contact in the problem and it approaching (D_NA ≤ 0), M diagonal.
template <int N, int C>
bool one_newton_contact(const ContactSpaceT<N, C>& cs, const RestitutionLaw& law,
                        const SolverOptions& options) {
  return !law.has_phases() && cs.contacts == 1 && cs.active == 1 && cs.D_N(0) <= 0.0 &&
         (options.method == SolverMethod::automatic ||
          options.method == SolverMethod::closed_form) &&
         cs.llt.matrix_is_diagonal();
}

/// The answer of one_newton_contact's problems, written into `out` (a cleared result) when the
/// contact modes would give it unchanged: one solution of the closed form (G regular), velocities
/// whose terms do not cancel (velocity_after's plain sum), and a residual settled at those
/// velocities (residual_at_own_velocities). False, `out` untouched, otherwise: the contact
/// modes then run as they always do. Each number is computed as the general path computes it, in
/// the same order, so that the answers agree bit for bit (tests/unit/classical_one_contact_test).
template <int N, int C>
bool settle_one_newton_contact(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                               const RestitutionLaw& law, const SolverOptions& options,
                               ImpactResultT<N, C>& out) {
  const int n = cs.dofs;
  const bool f = cs.tangential, tangential = pb.has_tangential();
  const double gnn = cs.G(0, 0), gnt = f ? cs.G(0, 1) : 0.0, gtt = f ? cs.G(1, 1) : 0.0;
  const double dna = cs.D_A(0), dta = f ? cs.D_A(1) : 0.0;
  const double e = law.e[0], mu = f ? law.mu[0] : 0.0;
  Tolerances tol;
  tol.v = 1e-9 * cs.v_scale;
  tol.p = tol.v / std::max({gnn, gtt, std::numeric_limits<double>::min()});
  const OneContact s = one_contact(gnn, gnt, gtt, (1 + e) * dna, dta, mu, 0.0, f, tol);
  if (s.degenerate || s.count != 1) return false;
  const double P[2] = {s.x[0], f ? s.t[0] : 0.0};
  if (!std::isfinite(P[0]) || !std::isfinite(P[1])) return false;
  const int rows = f ? 2 : 1;

  // q̇_E = q̇_A + M⁻¹W P, column by column, zero percussions skipped (velocity_after).
  VecT<N> q = pb.qdot_A;
  int moving = 0;
  for (int j = 0; j < rows; ++j) {
    if (P[j] == 0.0) continue;
    ++moving;
    for (int i = 0; i < n; ++i) q(i) += cs.MinvW(i, j) * P[j];
  }
  if (moving == 2) {  // where the terms cancel, velocity_after sums the force again, refined
    double terms = 0.0, change = 0.0;
    for (int i = 0; i < n; ++i) {
      double t = 0.0;
      for (int j = 0; j < rows; ++j)
        if (P[j] != 0.0) t += std::fabs(cs.MinvW(i, j) * P[j]);
      terms = std::max(terms, t);
      change = std::max(change, std::fabs(q(i) - pb.qdot_A(i)));
    }
    if (terms > 8.0 * change) return false;
  }
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(q(i))) return false;

  // The contact velocities after, and T_E − T_A (scatter_at_velocities).
  const double D_NE = contact_velocity(pb.W_N.col(0), q, pb.w_N.size() ? pb.w_N(0) : 0.0);
  const double D_TE =
      tangential ? contact_velocity(pb.W_T.col(0), q, pb.w_T.size() ? pb.w_T(0) : 0.0) : 0.0;
  const double energy = energy_change_at(pb, q, true);

  // The residual at these velocities (residual_at_own_velocities), within its share of the
  // tolerance; else the data's residual decides, on the general path.
  VecT<N> u = VecT<N>::Zero(n);
  for (int j = 0; j < rows; ++j)
    if (P[j] != 0.0) u += (cs.MinvW.col(j) * P[j]).cwiseAbs();
  const double floor = 2.0 * (rows + 2) * std::numeric_limits<double>::epsilon();
  const double dn = cs.D_N(0), dt = tangential ? cs.D_T(0) : 0.0;
  double terms = pb.W_N.col(0).cwiseAbs().dot(u);
  if (tangential) terms = std::max(terms, pb.W_T.col(0).cwiseAbs().dot(u));
  const double v_scale =
      std::max({std::numeric_limits<double>::min(), std::fabs(dn), std::fabs(dt)});
  const double gn = gnn > 0.0 ? gnn : 1.0, gt = f ? (gtt > 0.0 ? gtt : 1.0) : 1.0;
  double worst = std::max(0.0, std::fabs(complementarity(D_NE + e * dn, P[0], gn)));
  if (tangential)
    worst = std::max(
        worst, std::fabs(coulomb(P[1], D_TE, law.has_friction() ? law.mu[0] * P[0] : 0.0, gt)));
  const double allowed = kOwnVelocityShare * options.tolerance * v_scale;
  if (!(floor * terms <= allowed) || !(worst <= allowed)) return false;
  const double residual = worst / v_scale;
  if (!std::isfinite(D_NE) || !std::isfinite(D_TE) || !std::isfinite(energy) ||
      !std::isfinite(residual))
    return false;

  out.qdot_E = q;
  out.P_N.resize(1);
  out.P_T.resize(1);
  out.P_N(0) = P[0];
  out.P_T(0) = P[1];
  out.D_NA = cs.D_N;
  out.D_NE.resize(1);
  out.D_NE(0) = D_NE;
  if (tangential)
    out.D_TA = cs.D_T;
  else
    out.D_TA.setZero(1);
  out.D_TE.resize(1);
  out.D_TE(0) = D_TE;
  out.takes_part.resize(1);
  out.takes_part(0) = dn <= 0.0 ? 1 : 0;
  out.energy_change = energy;
  out.has_phases = false;
  out.qdot_C.resize(0);
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

}  // namespace fremond::detail::classical
