#pragma once
/// @file Contacts that separate before the impact (D_NA > 0). Every contact of a problem takes part
/// in the impact (docs/concepts.md): a separating one obeys its law with the restitution acting on
/// min(D_NA, 0) = 0, so it carries only the non-penetration reaction 0 ≤ P_N ⊥ D_NE ≥ 0 (Newton's
/// laws: e = 0; Poisson's: both phases as they are; Frémond's: no φ_N, and no tangential
/// potential), with Coulomb's cone under its usual bound. Undriven, it leaves with D_NE = D_NA and
/// P = 0, which is why a solve first leaves the separating contacts out and holds them only where
/// the others' percussions would drive one into its obstacle.
#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_space/contact_space.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/potentials/power.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/solver_options.hpp"
#include "fremond/solvers/solver_status.hpp"

namespace fremond::detail {

/// True when a separating contact of the answer `r` carries a percussion: the impact was solved
/// on every contact, and the reaction that stops it works on D_NA/2 > 0 (docs/concepts.md).
template <int N, int C>
bool stops_a_separating_contact(const ImpactResultT<N, C>& r) {
  for (Eigen::Index i = 0; i < r.D_NA.size() && i < r.P_N.size(); ++i)
    if (r.D_NA(i) > 0.0 && (r.P_N(i) != 0.0 || (r.P_T.size() > i && r.P_T(i) != 0.0))) return true;
  return false;
}

/// `law` as every contact obeys it, D_N their velocities before the impact: each law says how its
/// separating contacts obey it (its of_every_contact); the same law where none separates.
template <class Law, class Vec>
Law law_of_every_contact(const Law& law, const Vec& D_N) {
  return law.of_every_contact({D_N.data(), static_cast<std::size_t>(D_N.size())});
}
template <class Vec>
ImpactLaw law_of_every_contact(const ImpactLaw& law, const Vec& D_N) {
  return law.visit([&](const auto& l) { return ImpactLaw(law_of_every_contact(l, D_N)); });
}

/// True when the answer `r`, solved without the separating contacts, drives one of them into its
/// obstacle (D_NE < 0, or Poisson's D_NC < 0) beyond what its velocity is known to: the solver's
/// tolerance on the size of the terms that velocity is summed from, |W_N,i|ᵀ(|q̇_A| + |q̇|) +
/// |w_N,i|. Each contact is held to its own terms, so that a body moving a billion times slower
/// than another in the same problem is judged on its own scale (independent groups). `rounding`,
/// where given, is a relative allowance of its own on the same terms.
template <int N, int C>
bool drives_a_separating_contact(const ImpactProblemT<N, C>& pb, const ImpactResultT<N, C>& r,
                                 const SolverOptions& options, double rounding = 0.0) {
  const double eps = std::numeric_limits<double>::epsilon();
  const double tol = 2.0 * std::max({8.0 * eps, options.tolerance, rounding});
  auto driven = [&](int i, const VecT<N>& q, double d) {
    if (!(d < 0.0)) return false;
    double terms = pb.w_N.size() ? std::fabs(pb.w_N(i)) : 0.0;
    for (int k = 0; k < pb.dofs(); ++k)
      terms += std::fabs(pb.W_N(k, i)) * (std::fabs(pb.qdot_A(k)) + std::fabs(q(k)));
    return -d > tol * terms;
  };
  for (int i = 0; i < pb.contacts(); ++i) {
    if (!(r.D_NA.size() > i && r.D_NA(i) > 0.0)) continue;
    if (r.D_NE.size() > i && r.qdot_E.size() == pb.dofs() && driven(i, r.qdot_E, r.D_NE(i)))
      return true;
    if (r.has_phases && r.D_NC.size() > i && r.qdot_C.size() == pb.dofs() &&
        driven(i, r.qdot_C, r.D_NC(i)))
      return true;
  }
  return false;
}

/// No answer to judge: the law has none on the contacts held, or the chain found none. A
/// separating contact's reaction, with Coulomb's friction, can make one where the approaching
/// contacts alone have none (a jam: its friction drives it shut).
template <int N, int C>
bool no_answer(const ImpactResultT<N, C>& r) {
  return r.solver.status == SolverStatus::no_solution || r.solver.status == SolverStatus::failed;
}

/// True when an impact solved on its approaching contacts must be solved again on every contact:
/// that answer is none, or it drives a separating contact into its obstacle.
template <int N, int C>
bool needs_every_contact(const ImpactProblemT<N, C>& pb, const ImpactResultT<N, C>& r,
                         const SolverOptions& options) {
  return no_answer(r) || drives_a_separating_contact(pb, r, options);
}

}  // namespace fremond::detail
