#pragma once
/// @file Independent groups of contacts, each solved as a problem of its own.
///
/// Where G = Wᵀ M⁻¹ W has no entry between the rows of two sets of contacts (two bodies in one
/// problem, or contacts whose directions are M⁻¹-orthogonal), every law of SPEC §2 separates: its
/// equations read D_E = D_A + G P (z = D_A + G P/2 for Frémond's) row by row, and Poisson's phases
/// and Coulomb's bounds are per contact. Solved together, the stopping tests, the closed forms'
/// tolerances and Lemke's pivots are relative to the largest velocity of the whole problem, and a
/// group whose velocities are 1e9 times smaller is answered to that scale only: a body approaching
/// at 3.7e-10 m/s beside one at 1.5e5 got P_N = 0 and kept approaching (Newton + Coulomb, its own
/// D_NE wrong by 4 % of its D_NA), "converged". Each group is therefore solved on its own, with the
/// contacts of the other groups lifted off (their D_NA made positive through w_N, so that the
/// contact indices, and the law's per-contact parameters, stay those of the problem), and the
/// percussions are gathered and written once for the whole problem.
#include <algorithm>
#include <cmath>
#include <limits>

#include "fremond.hpp"
#include "fremond/solvers/detail/classical.hpp"
#include "fremond/solvers/detail/contact_space.hpp"

namespace fremond::detail {

/// Labels the contacts that take part (cs's active order) by group: contacts k and l share a
/// group when an entry of G between a row of k and a row of l is not exactly zero. Returns the
/// number of groups; labels are 0, 1, … in order of first appearance.
template <int N, int C>
int independent_groups(const ContactSpaceT<N, C>& cs,
                       Eigen::Matrix<int, Eigen::Dynamic, 1, Eigen::ColMajor, C, 1>& group) {
  const int a = cs.active, r = cs.rows();
  group.resize(a);
  for (int k = 0; k < a; ++k) group(k) = k;
  auto root = [&](int k) {
    while (group(k) != k) k = group(k) = group(group(k));
    return k;
  };
  for (int j = 0; j < r; ++j)
    for (int l = j + 1; l < r; ++l)
      if (cs.G(j, l) != 0.0) {
        const int x = root(j < a ? j : j - a), y = root(l < a ? l : l - a);
        if (x != y) group(std::max(x, y)) = std::min(x, y);
      }
  // Roots are the smallest index of their group: relabel in order of first appearance.
  int count = 0;
  Eigen::Matrix<int, Eigen::Dynamic, 1, Eigen::ColMajor, C, 1> label(a);
  for (int k = 0; k < a; ++k) {
    const int x = root(k);
    label(k) = x == k ? count++ : label(x);
  }
  group = label;
  return count;
}

/// The law stage (SPEC §2) on one contact space: Frémond's chain or the classical laws.
template <int N, int C>
void solve_law_stage(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                     const ImpactLaw& law, const SolverOptions& options, ImpactResultT<N, C>& out) {
  if (law.type == LawType::fremond)
    solve_fremond(pb, cs, law, options, out);
  else
    solve_classical(pb, cs, law, options, out);
}

/// Solves the law group by group where cs's contacts fall into two or more independent groups;
/// false (nothing written) where they do not, or where a group ends without an answer to merge
/// (no_solution, unsupported: the whole problem is then solved as one, whose report says so).
template <int N, int C>
bool solve_by_groups(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                     const ImpactLaw& law, const SolverOptions& options, ImpactResultT<N, C>& out) {
  using Rows = typename ContactSpaceT<N, C>::Rows;
  if (cs.active < 2) return false;
  Eigen::Matrix<int, Eigen::Dynamic, 1, Eigen::ColMajor, C, 1> group;
  const int groups = independent_groups(cs, group);
  if (groups < 2) return false;
  const int a = cs.active, c = cs.contacts;
  const bool fremond = law.type == LawType::fremond;
  const bool tangential_rows = fremond ? law.tangential != TangentialLaw::none : law.has_friction();
  ImpactProblemT<N, C> sub = pb;
  if (sub.w_N.size() == 0) sub.w_N = VecT<C>::Zero(c);
  Rows P = Rows::Zero(cs.rows()), P_C = Rows::Zero(cs.rows());
  VecT<C> reaction = VecT<C>::Zero(c);
  SolverReport report;
  int hardest = -1;  // the group whose report is kept: the first not converged, else most work
  int iterations = 0, fallbacks = 0, solutions = 1;
  double residual = 0.0;
  bool rounding = false, unique = true, phases = false;
  ContactSpaceT<N, C> gcs;
  ImpactResultT<N, C> r;
  for (int g = 0; g < groups; ++g) {
    // The other groups' contacts lifted off: D_NA = −D_NA + v_scale > 0 (it was ≤ 0).
    for (int k = 0; k < a; ++k) {
      const int i = cs.index(k);
      const double w = pb.w_N.size() ? pb.w_N(i) : 0.0;
      sub.w_N(i) = group(k) == g ? w : w - 2.0 * cs.D_N(i) + cs.v_scale;
      if (!std::isfinite(sub.w_N(i))) return false;
    }
    build_contact_space(sub, tangential_rows, gcs);
    int members = 0;
    for (int k = 0; k < a; ++k) members += group(k) == g;
    if (gcs.active != members) return false;  // rounding moved a contact across D_NA = 0
    r = ImpactResultT<N, C>{};
    solve_law_stage(sub, gcs, law, options, r);
    const SolverStatus s = r.solver.status;
    if (s == SolverStatus::no_solution || s == SolverStatus::unsupported ||
        s == SolverStatus::not_run)
      return false;
    for (int k = 0; k < a; ++k) {
      if (group(k) != g) continue;
      const int i = cs.index(k);
      P(k) = r.P_N(i);
      if (cs.tangential) P(a + k) = r.P_T(i);
      if (r.P_N_reaction.size() == c) reaction(i) = r.P_N_reaction(i);
      if (r.has_phases) {
        P_C(k) = r.P_NC(i);
        if (cs.tangential) P_C(a + k) = r.P_TC(i);
      }
    }
    phases = phases || r.has_phases;
    const bool converged = s == SolverStatus::converged;
    const bool harder = hardest < 0 || (report.status == SolverStatus::converged &&
                                        (!converged || r.solver.iterations + r.solver.fallbacks >
                                                           report.iterations + report.fallbacks));
    if (harder) {
      report = r.solver;
      hardest = g;
    }
    iterations += r.solver.iterations;
    fallbacks = std::max(fallbacks, r.solver.fallbacks);
    if (!(r.solver.residual <= residual)) residual = r.solver.residual;  // NaN too
    rounding = rounding || (converged && r.solver.criterion == StopCriterion::rounding);
    unique = unique && r.unique;
    solutions = r.solutions_found > 0 ? std::min(solutions * r.solutions_found, 1 << 20) : 0;
  }
  ImpactResultT<N, C> merged;
  if (fremond) {
    scatter_solution(pb, cs, P, merged);
    merged.P_N_reaction = reaction;
  } else {
    write_classical_answer(pb, cs, law, P, P_C, merged);
    merged.has_phases = phases;
  }
  if (!(merged.qdot_E.allFinite() && std::isfinite(merged.energy_change))) return false;
  merged.solver = report;
  merged.solver.iterations = iterations;
  merged.solver.fallbacks = fallbacks;
  merged.solver.residual = residual;
  if (merged.solver.status == SolverStatus::converged && rounding)
    merged.solver.criterion = StopCriterion::rounding;
  merged.unique = unique;
  merged.solutions_found = solutions;
  out = merged;
  return true;
}

}  // namespace fremond::detail
