// The driver (docs/laws.md, docs/concepts.md): validate → the law's chain (its solve_chain) →
// admissibility.
#include "fremond/solvers/solve_impact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "admissibility/detail/admissibility.hpp"
#include "contact_space/contact_space.hpp"
#include "core/detail/impact_problem.hpp"
#include "fremond/admissibility/admissibility.hpp"
#include "laws/detail/plugins.hpp"
#include "laws/detail/separating_contacts.hpp"
#include "solvers/detail/chain_workspace.hpp"
#include "solvers/detail/independent_groups.hpp"
#include "solvers/detail/result_copy.hpp"
#include "solvers/detail/solve_stages.hpp"

namespace fremond {

namespace {
/// A chain that logs no attempt of its own (the classical laws') gets its answer's method as one.
template <int N, int C>
void log_answer_if_unlogged(ImpactResultT<N, C>& out) {
  if (out.solver.attempt_count == 0 && out.solver.status != SolverStatus::not_run)
    out.solver.record(out.solver.method, AttemptStart::none, out.solver.status,
                      out.solver.residual);
}

/// A dissipative law (Frémond's: (15), (17) and (19) hold for every exact solution whose
/// separating contacts carry no reaction: docs/concepts.md): an answer marked converged that its
/// certificate refuses is not resolved in double precision, whatever the law's residual
/// test said: it is kept and called stalled. The test accepts rows at their own rounding floor, and
/// where percussions are 1e8 times the velocities on cond(M) = 5e7 those floors let velocities 5e-9
/// off the exact ones through, with an energy gain (1e-8 of T_A) 5e6 times what ε·cond(M) allows.
/// The other laws are not held to it: Newton's and Poisson's with Coulomb create energy, which is
/// the certificate's finding, not the solver's failure.
template <int N, int C>
void refuse_inadmissible(const ImpactLaw& law, ImpactResultT<N, C>& out) {
  if (!law.dissipative() || out.solver.status != SolverStatus::converged ||
      out.admissibility.admissible)
    return;
  // A reaction that stops a separating contact works on its true mean velocity D_NA/2 > 0: total
  // (15) may then fail for the exact answer, which is the convention's finding, not a failure.
  if (detail::stops_a_separating_contact(out)) return;
  out.unique = false;
  // A law's data outside the domain where it dissipates, seen from the answer, is what the
  // certificate found, and no solver can do better.
  if (law.visit([&](const auto& l) { return detail::refuse_outside_domain(l, out); })) return;
  out.solver.status = SolverStatus::stalled;
  out.solver.message =
      "the answer passes the law's residual test, but its admissibility certificate refuses it "
      "(see admissibility.failed); the law dissipates by construction, so the answer is not "
      "resolved in double precision";
}
}  // namespace

template <int N, int C>
void detail::solve_on_contact_space(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                                    const SolverOptions& options, ContactSpaceT<N, C>& cs,
                                    ImpactResultT<N, C>& out, ChainWorkspace& ws) {
  // One contact, where its law has a lane for it (its plugin's solve_one_contact_lane): the
  // answer the chain's first stage would give, on scalars, without the chain around it.
  const bool lane = cs.contacts == 1 && law.visit([&](const auto& l) {
    return detail::solve_one_contact_lane(pb, cs, l, options, out);
  });
  if (!lane) {
    // Independent groups of contacts (two bodies in one problem) are solved each to its own
    // velocity scale (independent_groups.hpp); the test costs a look at G's off-diagonal entries,
    // and one contact does not even make the call (its frame holds three problems' storage).
    if (cs.active < 2 || !detail::solve_by_groups(pb, cs, law, options, out, ws))
      detail::solve_law_stage(pb, cs, law, options, out, ws);
    // Every contact takes part (separating_contacts.hpp): where the answer without the separating
    // ones drives one of them into its obstacle, or where the approaching contacts alone have no
    // answer, the impact is solved again on every contact, by independent groups there too.
    if (cs.active < cs.contacts && detail::needs_every_contact(pb, out, options)) {
      const ImpactLaw every = detail::law_of_every_contact(law, cs.D_N);
      build_contact_space(pb, detail::tangential_rows(law), cs, detail::HeldContacts::every);
      clear_result(out);
      if (!detail::solve_by_groups(pb, cs, law, options, out, ws, detail::HeldContacts::every))
        detail::solve_law_stage(pb, cs, every, options, out, ws);
    }
  }
  log_answer_if_unlogged(out);
  if (cs.contacts == 1) {
    // The certificate's steps on the contact's scalars: the same bits as over the whole result.
    out.admissibility = detail::check_one_contact(pb, law, out, options, cs);
  } else {
    // The percussions' rounding floors and G's largest entry serve only a law's own certificate
    // terms (Frémond's): the other laws' certificates do not read them.
    const bool own_terms =
        law.visit([](const auto& l) { return detail::has_certificate_terms(l); });
    VecT<C> percussion;
    const VecT<C> rounding = detail::velocity_rounding(cs, out, own_terms ? &percussion : nullptr);
    out.admissibility = detail::check_admissibility(pb, law, out, options, rounding,
                                                    own_terms ? detail::delassus_max(cs) : 0.0,
                                                    own_terms ? &percussion : nullptr);
  }
  refuse_inadmissible(law, out);
}

namespace {
/// The problem, the law and the options validated, and the contact space of the approaching
/// contacts built (M's positive-definiteness tested on its factor).
template <int N, int C>
detail::ContactSpaceT<N, C> validated_contact_space(const ImpactProblemT<N, C>& pb,
                                                    const ImpactLaw& law,
                                                    const SolverOptions& options) {
  detail::validate_shapes(pb);
  law.validate(pb.contacts());
  options.validate();
  detail::ContactSpaceT<N, C> cs;
  build_contact_space(pb, detail::tangential_rows(law), cs);
  detail::require_positive_definite(pb.M, cs.llt);  // validate()'s last test, on cs's factor
  return cs;
}
}  // namespace

template <int N, int C>
void detail::solve_impact_into(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                               const SolverOptions& options, ImpactResultT<N, C>& out) {
  ContactSpaceT<N, C> cs = validated_contact_space(pb, law, options);
  clear_result(out);
  ChainWorkspace ws;
  solve_on_contact_space(pb, law, options, cs, out, ws);
}

template <int N, int C>
ImpactResultT<N, C> detail::solve_impact_in_own_storage(const ImpactProblemT<N, C>& pb,
                                                        const ImpactLaw& law,
                                                        const SolverOptions& options) {
  ContactSpaceT<N, C> cs = validated_contact_space(pb, law, options);
  ImpactResultT<N, C> out;  // as default-constructed, as the stages want it
  ChainWorkspace ws;
  solve_on_contact_space(pb, law, options, cs, out, ws);
  return out;
}

template <int N, int C>
ImpactResultT<N, C> solve_impact(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                                 const SolverOptions& options) {
  if constexpr (N == Dynamic && C == Dynamic) {
    // A planar body with a few contacts handed over in heap storage: the same templates on the
    // stack sizes skip Eigen's dynamic-size dispatch and its temporaries (about 70 heap blocks a
    // solve on the bar), and the copies in and out cost less (the plate with one contact under
    // Newton: 1.17 µs → 0.57 µs). Shapes that do not fit, valid or not, stay in their own
    // storage, where validation names them.
    if (fits_small(pb))
      return to_dynamic(detail::solve_impact_in_own_storage(to_small(pb), law, options));
  }
  return detail::solve_impact_in_own_storage(pb, law, options);
}

template void detail::solve_on_contact_space(const ImpactProblemT<Dynamic, Dynamic>&,
                                             const ImpactLaw&, const SolverOptions&,
                                             ContactSpaceT<Dynamic, Dynamic>&,
                                             ImpactResultT<Dynamic, Dynamic>&, ChainWorkspace&);
template void detail::solve_on_contact_space(const ImpactProblemT<kSmallDofs, kSmallContacts>&,
                                             const ImpactLaw&, const SolverOptions&,
                                             ContactSpaceT<kSmallDofs, kSmallContacts>&,
                                             ImpactResultT<kSmallDofs, kSmallContacts>&,
                                             ChainWorkspace&);
template void detail::solve_impact_into(const ImpactProblemT<Dynamic, Dynamic>&, const ImpactLaw&,
                                        const SolverOptions&, ImpactResultT<Dynamic, Dynamic>&);
template void detail::solve_impact_into(const ImpactProblemT<kSmallDofs, kSmallContacts>&,
                                        const ImpactLaw&, const SolverOptions&,
                                        ImpactResultT<kSmallDofs, kSmallContacts>&);
template ImpactResultT<Dynamic, Dynamic> detail::solve_impact_in_own_storage(
    const ImpactProblemT<Dynamic, Dynamic>&, const ImpactLaw&, const SolverOptions&);
template ImpactResultT<kSmallDofs, kSmallContacts> detail::solve_impact_in_own_storage(
    const ImpactProblemT<kSmallDofs, kSmallContacts>&, const ImpactLaw&, const SolverOptions&);
template ImpactResultT<Dynamic, Dynamic> solve_impact(const ImpactProblemT<Dynamic, Dynamic>&,
                                                      const ImpactLaw&, const SolverOptions&);
template ImpactResultT<kSmallDofs, kSmallContacts> solve_impact(
    const ImpactProblemT<kSmallDofs, kSmallContacts>&, const ImpactLaw&, const SolverOptions&);

namespace {
/// solve_impact_all's work in the problem's storage.
template <int N, int C>
std::vector<ImpactResultT<N, C>> solve_all_in(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                                              const SolverOptions& options) {
  // Independent groups of contacts: the product of the groups' lists (independent_groups.hpp).
  std::vector<ImpactResultT<N, C>> all;
  if (!detail::solve_all_by_groups(pb, law, options, all))
    all = law.visit([&](const auto& l) {
      return detail::solve_every_answer(pb, l, options, detail::HeldContacts::approaching);
    });
  // Every contact takes part (separating_contacts.hpp): where an answer without the separating
  // contacts drives one of them into its obstacle, or where they have none, the list is made
  // again on every contact.
  VecT<C> D_N(pb.contacts());
  bool separating = false;
  for (int i = 0; i < pb.contacts(); ++i) {
    D_N(i) = detail::contact_velocity(pb.W_N.col(i), pb.qdot_A, pb.w_N.size() ? pb.w_N(i) : 0.0);
    separating = separating || D_N(i) > 0.0;
  }
  bool drives = separating && (all.empty() || (all.size() == 1 && detail::no_answer(all.front())));
  for (const auto& r : all) drives = drives || detail::drives_a_separating_contact(pb, r, options);
  if (drives) {
    const ImpactLaw every = detail::law_of_every_contact(law, D_N);
    all = every.visit([&](const auto& l) {
      return detail::solve_every_answer(pb, l, options, detail::HeldContacts::every);
    });
  }
  for (auto& r : all) {
    log_answer_if_unlogged(r);
    r.admissibility = check_admissibility(pb, law, r, options);
    refuse_inadmissible(law, r);
  }
  return all;
}
}  // namespace

std::vector<ImpactResult> solve_impact_all(const ImpactProblem& pb, const ImpactLaw& law,
                                           const SolverOptions& options) {
  validate(pb);
  law.validate(pb.contacts());
  options.validate();
  // In the storage solve_impact uses, so that a unique answer is solve_impact's to the last bit.
  if (!fits_small(pb)) return solve_all_in(pb, law, options);
  std::vector<ImpactResult> all;
  for (const SmallImpactResult& r : solve_all_in(to_small(pb), law, options))
    all.push_back(to_dynamic(r));
  return all;
}

}  // namespace fremond
