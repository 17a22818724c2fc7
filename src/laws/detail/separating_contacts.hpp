#pragma once
/// @file Contacts that separate before the impact (D_NA > 0). Every contact of a problem takes part
/// in the impact (docs/concepts.md): a separating one obeys its law with the restitution acting on
/// min(D_NA, 0) = 0, so it carries only the non-penetration reaction 0 ≤ P_N ⊥ D_NE ≥ 0 (Newton's
/// laws: e = 0; Poisson's: both phases as they are; Frémond's: no φ_N, and no tangential
/// potential), with Coulomb's cone under its usual bound. Undriven, it leaves with D_NE = D_NA and
/// P = 0, which is why a solve first leaves the separating contacts out and holds them only where
/// the others' percussions would drive one into its obstacle.
#include <cmath>
#include <limits>

#include "contact_space/contact_space.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/potentials/power.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond::detail {

/// True when a separating contact of the answer `r` carries a percussion: the impact was solved
/// on every contact, and the reaction that stops it works on D_NA/2 > 0 (docs/concepts.md).
template <int N, int C>
bool stops_a_separating_contact(const ImpactResultT<N, C>& r) {
  for (Eigen::Index i = 0; i < r.D_NA.size() && i < r.P_N.size(); ++i)
    if (r.D_NA(i) > 0.0 && (r.P_N(i) != 0.0 || (r.P_T.size() > i && r.P_T(i) != 0.0))) return true;
  return false;
}

/// `law` as the contacts obey it, D_N their velocities before the impact: the separating ones
/// without restitution and without potentials (the file's comment); the same law where none
/// separates.
template <class Vec>
ImpactLaw law_of_every_contact(const ImpactLaw& law, const Vec& D_N) {
  const int c = static_cast<int>(D_N.size());
  ImpactLaw out = law;
  if (law.is_fremond()) {
    const PowerPotential none(0.0, 2.0);  // φ = 0: the reaction alone
    PerContactPotential normal, tangential;
    for (int i = 0; i < c; ++i) {
      normal.potentials.emplace_back(D_N(i) > 0.0 ? none.clone() : law.normal[i].clone());
      if (law.has_tangential_potential())
        tangential.potentials.emplace_back(D_N(i) > 0.0 ? none.clone()
                                                        : law.tangential_potential[i].clone());
    }
    out.normal = std::move(normal);
    if (law.has_tangential_potential()) out.tangential_potential = std::move(tangential);
  } else if (!law.has_phases()) {  // Poisson's: a separating contact obeys both phases as is
    std::vector<double> e(static_cast<std::size_t>(c));
    for (int i = 0; i < c; ++i) e[static_cast<std::size_t>(i)] = D_N(i) > 0.0 ? 0.0 : law.e[i];
    out.e = PerContact(std::move(e));
  }
  return out;
}

/// True when the answer `r`, solved without the separating contacts, drives one of them into its
/// obstacle (D_NE < 0, or Poisson's D_NC < 0) beyond what its velocity is known to: the solver's
/// tolerance on the size of the terms that velocity is summed from, |W_N,i|ᵀ(|q̇_A| + |q̇|) +
/// |w_N,i|. Each contact is held to its own terms, so that a body moving a billion times slower
/// than another in the same problem is judged on its own scale (independent groups).
template <int N, int C>
bool drives_a_separating_contact(const ImpactProblemT<N, C>& pb, const ImpactResultT<N, C>& r,
                                 const SolverOptions& options) {
  const double eps = std::numeric_limits<double>::epsilon();
  const double tol = 2.0 * std::max(8.0 * eps, options.tolerance);
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

}  // namespace fremond::detail
