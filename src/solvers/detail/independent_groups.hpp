#pragma once
/// @file Independent groups of contacts, each solved as a problem of its own.
///
/// Where G = Wᵀ M⁻¹ W has no entry between the rows of two sets of contacts (two bodies in one
/// problem, or contacts whose directions are M⁻¹-orthogonal), every law of docs/laws.md separates:
/// its equations read D_E = D_A + G P (z = D_A + G P/2 for Frémond's) row by row, and Poisson's
/// phases and Coulomb's bounds are per contact. Solved together, the stopping tests, the closed
/// forms' tolerances and Lemke's pivots are relative to the largest velocity of the whole problem,
/// and a group whose velocities are 1e9 times smaller is answered to that scale only: a body
/// approaching at 3.7e-10 m/s beside one at 1.5e5 gets P_N = 0 and keeps approaching (Newton +
/// Coulomb, its velocities wrong by 4 % of their size), yet "converged". Each group is therefore
/// solved on its own, with the contacts of the other groups lifted off (their D_NA made positive
/// through w_N, so that the contact indices, and the law's per-contact parameters, stay those of
/// the problem), and the percussions are gathered and written once for the whole problem.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "contact_space/contact_space.hpp"
#include "laws/detail/plugins.hpp"
#include "laws/detail/separating_contacts.hpp"
#include "solvers/detail/result_copy.hpp"

namespace fremond::detail {

/// Labels the contacts that take part (cs's active order) by group: contacts k and l share a
/// group when an entry of G between a row of k and a row of l is not exactly zero. Returns the
/// number of groups; labels are 0, 1, … in order of first appearance.
template <int N, int C, class Labels>
int independent_groups(const ContactSpaceT<N, C>& cs, Labels& group) {
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
  Labels label(a);
  for (int k = 0; k < a; ++k) {
    const int x = root(k);
    label(k) = x == k ? count++ : label(x);
  }
  group = label;
  return count;
}

/// True when every contact that takes part is coupled by G to the first one (one group, the
/// common case of one rigid body), decided without labelling anything.
template <int N, int C>
bool coupled_to_first(const ContactSpaceT<N, C>& cs) {
  const int a = cs.active;
  for (int k = 1; k < a; ++k) {
    bool coupled = cs.G(0, k) != 0.0;
    if (cs.tangential)
      coupled = coupled || cs.G(0, a + k) != 0.0 || cs.G(a, k) != 0.0 || cs.G(a, a + k) != 0.0;
    if (!coupled) return false;
  }
  return true;
}

/// The law stage (docs/laws.md) on one contact space: the law's own solver chain, its storage
/// taken from `ws`.
template <int N, int C>
void solve_law_stage(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                     const ImpactLaw& law, const SolverOptions& options, ImpactResultT<N, C>& out,
                     ChainWorkspace& ws) {
  law.visit([&](const auto& l) { solve_chain(pb, cs, l, options, out, ws); });
}

/// Whether the law has tangential rows in contact space (Frémond's with any tangential law, the
/// classical laws with Coulomb), as solve_impact builds it.
inline bool tangential_rows(const ImpactLaw& law) {
  return law.has_friction();
}

/// `sub` = the problem with the contacts of every group but g lifted off: D_NA = −D_NA + v_scale
/// > 0 (it was ≤ 0) through w_N, so that g's contacts alone take part and every contact keeps its
/// index (and its parameters in the law); `gcs` its contact space. False where the lifted w_N
/// overflows, or where rounding moved a contact across D_NA = 0 (gcs then lacks or has one more).
///
/// With `held` = every (the impact solved again on every contact: separating_contacts.hpp), `cs`
/// holds every contact, and so does `gcs`: the other groups' contacts, held too, are moved to
/// D_NA = s and D_TA = 0 (up to their rounding) through w_N and w_T, s the largest |D_A| of g's own
/// rows. Separating from the group and independent of it, they take no percussion, and the group
/// keeps its own velocity scale. False also where one of them does not separate, or where its
/// rounding alone would set the scale (gcs.v_scale beyond 2s).
template <int N, int C, class Group>
bool group_problem(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                   const ImpactLaw& law, const Group& group, int g, ImpactProblemT<N, C>& sub,
                   ContactSpaceT<N, C>& gcs, HeldContacts held = HeldContacts::approaching) {
  if (sub.w_N.size() == 0) sub.w_N = VecT<C>::Zero(cs.contacts);
  if (held == HeldContacts::every) {
    const bool has_t = pb.has_tangential();
    if (has_t && sub.w_T.size() == 0) sub.w_T = VecT<C>::Zero(cs.contacts);
    double s = 0.0;
    for (int k = 0; k < cs.active; ++k)
      if (group(k) == g)
        s = std::max(
            {s, std::fabs(cs.D_N(cs.index(k))), has_t ? std::fabs(cs.D_T(cs.index(k))) : 0.0});
    if (!(s > 0.0)) return false;
    for (int k = 0; k < cs.active; ++k) {
      const int i = cs.index(k);
      const double wN = pb.w_N.size() ? pb.w_N(i) : 0.0;
      const double wT = pb.w_T.size() ? pb.w_T(i) : 0.0;
      const bool own = group(k) == g;
      sub.w_N(i) = own ? wN : wN - cs.D_N(i) + s;
      if (has_t) sub.w_T(i) = own ? wT : wT - cs.D_T(i);
      if (!std::isfinite(sub.w_N(i)) || (has_t && !std::isfinite(sub.w_T(i)))) return false;
    }
    build_contact_space_like(sub, tangential_rows(law), cs, gcs, HeldContacts::every);
    for (int k = 0; k < cs.active; ++k)
      if (group(k) != g && !(gcs.D_N(cs.index(k)) > 0.0)) return false;
    return gcs.active == cs.active && gcs.v_scale <= 2.0 * s;
  }
  int members = 0;
  for (int k = 0; k < cs.active; ++k) {
    const int i = cs.index(k);
    const double w = pb.w_N.size() ? pb.w_N(i) : 0.0;
    members += group(k) == g;
    sub.w_N(i) = group(k) == g ? w : w - 2.0 * cs.D_N(i) + cs.v_scale;
    if (!std::isfinite(sub.w_N(i))) return false;
  }
  build_contact_space_like(sub, tangential_rows(law), cs, gcs);
  return gcs.active == members;
}

/// Gathers the groups' answers (each a result of the whole problem's size, its own contacts filled)
/// into one result of the whole problem.
template <int N, int C>
class GroupMerge {
 public:
  using Rows = typename ContactSpaceT<N, C>::Rows;

  GroupMerge(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs)
      : pb_(pb),
        cs_(cs),
        P_(Rows::Zero(cs.rows())),
        P_C_(Rows::Zero(cs.rows())),
        dq_(VecT<N>::Zero(cs.dofs)),
        dqC_(VecT<N>::Zero(cs.dofs)),
        reaction_(VecT<C>::Zero(cs.contacts)) {}

  /// Takes group g's answer r for its contacts (group(k) == g) and its solver report.
  template <class Group>
  void add(const Group& group, int g, const ImpactResultT<N, C>& r) {
    const int a = cs_.active, c = cs_.contacts;
    for (int k = 0; k < a; ++k) {
      if (group(k) != g) continue;
      const int i = cs_.index(k);
      P_(k) = r.P_N(i);
      if (cs_.tangential) P_(a + k) = r.P_T(i);
      if (r.P_N_reaction.size() == c) reaction_(i) = r.P_N_reaction(i);
      if (r.has_phases) {
        P_C_(k) = r.P_NC(i);
        if (cs_.tangential) P_C_(a + k) = r.P_TC(i);
      }
    }
    dq_ += r.qdot_E - pb_.qdot_A;
    if (r.has_phases) dqC_ += r.qdot_C - pb_.qdot_A;
    // The report kept is the first group's not converged, else the one that worked most.
    const bool converged = r.solver.status == SolverStatus::converged;
    if (!have_ || (report_.status == SolverStatus::converged &&
                   (!converged || r.solver.iterations + r.solver.fallbacks >
                                      report_.iterations + report_.fallbacks)))
      report_ = r.solver;
    have_ = true;
    iterations_ += r.solver.iterations;
    fallbacks_ = std::max(fallbacks_, r.solver.fallbacks);
    if (!(r.solver.residual <= residual_)) residual_ = r.solver.residual;  // NaN too
    rounding_ = rounding_ || (converged && r.solver.criterion == StopCriterion::rounding);
    unique_ = unique_ && r.unique;
    solutions_ = r.solutions_found > 0 ? std::min(solutions_ * r.solutions_found, 1 << 20) : 0;
  }

  /// Writes the whole answer into `out`, as the law writes an answer merged from its groups
  /// (its write_merged_answer), and the report of the groups. False, with `out` untouched, where
  /// the velocities or the energy are not finite.
  bool write(const ImpactLaw& law, ImpactResultT<N, C>& out) const {
    ImpactResultT<N, C> merged;
    law.visit([&](const auto& l) {
      write_merged_answer(pb_, cs_, l, P_, P_C_, reaction_, dq_, dqC_, merged);
    });
    if (!(merged.qdot_E.allFinite() && std::isfinite(merged.energy_change))) return false;
    merged.solver = report_;
    merged.solver.iterations = iterations_;
    merged.solver.fallbacks = fallbacks_;
    merged.solver.residual = residual_;
    if (merged.solver.status == SolverStatus::converged && rounding_)
      merged.solver.criterion = StopCriterion::rounding;
    merged.unique = unique_;
    merged.solutions_found = solutions_;
    out = merged;
    return true;
  }

 private:
  const ImpactProblemT<N, C>& pb_;
  const ContactSpaceT<N, C>& cs_;
  Rows P_, P_C_;
  VecT<N> dq_, dqC_;  ///< the sum of the groups' velocity changes (dqC_: Poisson's compression)
  VecT<C> reaction_;
  SolverReport report_;
  bool have_ = false, rounding_ = false, unique_ = true;
  int iterations_ = 0, fallbacks_ = 0, solutions_ = 1;
  double residual_ = 0.0;
};

template <int C>
using GroupLabels = Eigen::Matrix<int, Eigen::Dynamic, 1, Eigen::ColMajor, C, 1>;

/// solve_by_groups' work once there are two groups or more: each solved alone, then merged. Out
/// of line: its frame holds three problems' storage, which a problem that does not split (the
/// common case) should not pay for (240 instructions a solve on the flat bar).
template <int N, int C>
[[gnu::noinline]] bool solve_each_group(const ImpactProblemT<N, C>& pb,
                                        const ContactSpaceT<N, C>& cs, const ImpactLaw& law,
                                        const SolverOptions& options, const GroupLabels<C>& group,
                                        int groups, HeldContacts held, ImpactResultT<N, C>& out,
                                        ChainWorkspace& ws) {
  const bool every = held == HeldContacts::every;
  ImpactProblemT<N, C> sub = pb;
  ContactSpaceT<N, C> gcs, approaching;
  ImpactResultT<N, C> r;
  GroupMerge<N, C> merge(pb, cs);
  for (int g = 0; g < groups; ++g) {
    if (!group_problem(pb, cs, law, group, g, sub, gcs, held)) return false;
    clear_result(r);
    if (!every) {
      solve_law_stage(sub, gcs, law, options, r, ws);
    } else {
      // As the group's own problem is solved (solve_impact.cpp): on its approaching contacts
      // first, and on every contact where that answer drives one of its separating contacts or
      // where there is none, under the law its separating contacts and the lifted ones obey.
      build_contact_space_like(sub, tangential_rows(law), cs, approaching);
      solve_law_stage(sub, approaching, law, options, r, ws);
      if (needs_every_contact(sub, r, options)) {
        clear_result(r);
        solve_law_stage(sub, gcs, law_of_every_contact(law, gcs.D_N), options, r, ws);
      }
    }
    share_self_delassus(gcs, cs);  // once a group's residual has them, for the next groups
    const SolverStatus s = r.solver.status;
    if (s == SolverStatus::no_solution || s == SolverStatus::unsupported ||
        s == SolverStatus::not_run)
      return false;
    merge.add(group, g, r);
  }
  // Not `every ? law_of_every_contact(...) : law`, whose prvalue would copy `law` (its heap lists).
  if (!every) return merge.write(law, out);
  return merge.write(law_of_every_contact(law, cs.D_N), out);
}

/// Solves the law group by group where cs's contacts fall into two or more independent groups;
/// false (nothing written) where they do not, or where a group ends without an answer to merge
/// (no_solution, unsupported: the whole problem is then solved as one, whose report says so).
/// `held`: the contacts cs holds (with every, `law` is still the problem's: each group is solved
/// under the law of its every contact, law_of_every_contact).
template <int N, int C>
bool solve_by_groups(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                     const ImpactLaw& law, const SolverOptions& options, ImpactResultT<N, C>& out,
                     ChainWorkspace& ws, HeldContacts held = HeldContacts::approaching) {
  if (cs.active < 2 || coupled_to_first(cs)) return false;
  GroupLabels<C> group;
  const int groups = independent_groups(cs, group);
  return groups >= 2 && solve_each_group(pb, cs, law, options, group, groups, held, out, ws);
}

/// solve_impact_all by groups: every solution is one of each group's, so the list is the product
/// of the groups' lists (most dissipative first, as each law's own list). False (nothing written)
/// where the contacts form one group, where a group's list is empty or holds an answer that is not
/// converged (the whole problem's list then says so), or where the product exceeds 256.
template <int N, int C>
bool solve_all_by_groups(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                         const SolverOptions& options, std::vector<ImpactResultT<N, C>>& all) {
  ContactSpaceT<N, C> cs;
  build_contact_space(pb, tangential_rows(law), cs);
  if (cs.active < 2 || coupled_to_first(cs)) return false;
  GroupLabels<C> group;
  const int groups = independent_groups(cs, group);
  if (groups < 2) return false;
  ImpactProblemT<N, C> sub = pb;
  ContactSpaceT<N, C> gcs;
  std::vector<std::vector<ImpactResultT<N, C>>> lists(groups);
  long total = 1;
  for (int g = 0; g < groups; ++g) {
    if (!group_problem(pb, cs, law, group, g, sub, gcs)) return false;
    lists[g] = law.visit([&](const auto& l) {
      return solve_every_answer(sub, l, options, HeldContacts::approaching);
    });
    if (lists[g].empty()) return false;
    for (const ImpactResultT<N, C>& r : lists[g])
      if (r.solver.status != SolverStatus::converged) return false;
    total *= static_cast<long>(lists[g].size());
    if (total > 256) return false;
  }
  std::vector<ImpactResultT<N, C>> found;
  std::vector<std::size_t> pick(groups, 0);
  while (true) {
    GroupMerge<N, C> merge(pb, cs);
    for (int g = 0; g < groups; ++g) merge.add(group, g, lists[g][pick[g]]);
    ImpactResultT<N, C>& r = found.emplace_back();
    if (!merge.write(law, r)) return false;
    r.unique = r.unique && total == 1;
    r.solutions_found = static_cast<int>(total);
    int g = 0;
    while (g < groups && ++pick[g] == lists[g].size()) pick[g++] = 0;
    if (g == groups) break;
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const ImpactResultT<N, C>& x, const ImpactResultT<N, C>& y) {
                     return x.energy_change < y.energy_change;
                   });
  all = std::move(found);
  return true;
}

}  // namespace fremond::detail
