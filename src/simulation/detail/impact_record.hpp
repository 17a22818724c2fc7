#pragma once
// The entries of the impact log (ImpactRecord): an impact with the scene's law, and the closing of
// an accumulation.
#include <Eigen/Core>

#include "fremond/scenes/kinematics.hpp"
#include "fremond/simulation/simulate.hpp"

namespace fremond::detail {

/// An impact of `kind` with the scene's law on the contacts idx[0..n) at time t: the solver's
/// result r, from `before` to the velocity qdot_E, energies e_A and e_E. The result's per-contact
/// failure is renamed to its scene contact index.
template <class Result>
ImpactRecord law_impact_record(long index, double t, ImpactKind kind, const int* idx, int n,
                               const PlanarState& before, const Eigen::Vector3d& qdot_E, double e_A,
                               double e_E, const Result& r) {
  ImpactRecord rec;
  rec.index = index;
  rec.t = t;
  rec.kind = kind;
  rec.contact_count = n;
  for (int i = 0; i < n; ++i) rec.contacts[i] = idx[i];
  rec.q = before.q;
  rec.qdot_A = before.qdot;
  rec.qdot_E = qdot_E;
  rec.P_N = r.P_N;
  rec.P_T = r.P_T;
  rec.D_NA = r.D_NA;
  rec.D_NE = r.D_NE;
  rec.D_TA = r.D_TA;
  rec.D_TE = r.D_TE;
  rec.energy_A = e_A;
  rec.energy_E = e_E;
  rec.admissible = r.admissibility.admissible;
  rec.failed = r.admissibility.failed;
  rec.failed_contact =
      r.admissibility.failed_contact >= 0 ? idx[r.admissibility.failed_contact] : -1;
  rec.violation = r.admissibility.violation;
  rec.unique = r.unique;
  rec.solver = r.solver;
  return rec;
}

/// The closing of an accumulation at time t on the touching contacts idx[0..n) with frames
/// f[0..n): q̇ from `before` to qdot_E by the normal percussions −lambda, energies e_A and e_E.
/// Admissible when it does not raise the energy; `limit` is the accumulation time t∞.
template <class Multipliers>
ImpactRecord accumulation_record(long index, double t, const int* idx, const ContactFrame* f, int n,
                                 const PlanarState& before, const Eigen::Vector3d& qdot_E,
                                 const Multipliers& lambda, double e_A, double e_E, double limit) {
  ImpactRecord rec;
  rec.index = index;
  rec.t = t;
  rec.kind = ImpactKind::accumulation;
  rec.contact_count = n;
  rec.q = before.q;
  rec.qdot_A = before.qdot;
  rec.qdot_E = qdot_E;
  for (auto* v : {&rec.P_N, &rec.P_T, &rec.D_NA, &rec.D_NE, &rec.D_TA, &rec.D_TE}) v->resize(n);
  for (int i = 0; i < n; ++i) {
    rec.contacts[i] = idx[i];
    rec.P_N(i) = -lambda(i);
    rec.P_T(i) = 0.0;
    rec.D_NA(i) = f[i].W_N.dot(before.qdot);
    rec.D_NE(i) = f[i].W_N.dot(qdot_E);
    rec.D_TA(i) = f[i].W_T.dot(before.qdot);
    rec.D_TE(i) = f[i].W_T.dot(qdot_E);
  }
  rec.energy_A = e_A;
  rec.energy_E = e_E;
  rec.admissible = e_E <= e_A;
  rec.failed = rec.admissible ? Inequality::none : Inequality::total_15;
  rec.violation = rec.admissible ? 0.0 : e_E - e_A;
  rec.solver.method = SolverMethod::closed_form;
  rec.solver.status = SolverStatus::converged;
  rec.solver.criterion = StopCriterion::exact;
  rec.solver.message = "accumulation closed: normal velocities of the touching contacts set to 0";
  rec.solver.iterations = 0;
  rec.accumulation_limit = limit;
  return rec;
}

}  // namespace fremond::detail
