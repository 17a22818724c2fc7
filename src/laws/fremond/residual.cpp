// Frémond's residual (laws/residual.hpp): the natural map of every row of the law
// (fremond_rows.hpp) at the answer's percussions, in velocity units.
#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_space/contact_space.hpp"
#include "fremond/core/error.hpp"
#include "laws/detail/residuals.hpp"
#include "laws/detail/separating_contacts.hpp"
#include "laws/fremond/rows.hpp"

namespace fremond::detail {

namespace {

/// The answer's percussions on the rows of `cs`, in its row order.
template <int N, int C>
typename FremondRowsT<N, C>::Rows held_percussions(const ContactSpaceT<N, C>& cs,
                                                   const ImpactResultT<N, C>& r) {
  typename FremondRowsT<N, C>::Rows P(cs.rows());
  for (int k = 0; k < cs.active; ++k) {
    P(k) = r.P_N(cs.index(k));
    if (cs.tangential) P(cs.active + k) = r.P_T(cs.index(k));
  }
  return P;
}

/// ‖R‖∞ over the rows of `cs`, in velocity units (unscaled).
template <int N, int C>
double held_rows_residual(const ContactSpaceT<N, C>& cs, const FremondLaw& every,
                          const ImpactResultT<N, C>& r) {
  FremondRowsT<N, C> rows;
  rows.init(cs, every);
  return rows.plain_residual(held_percussions(cs, r));
}

template <int N, int C>
double residual_of_held(const ContactSpaceT<N, C>& cs, const FremondLaw& every,
                        const ImpactResultT<N, C>& r) {
  return held_rows_residual(cs, every, r) / cs.v_scale;
}

/// The residual where the contact space of every contact cannot be formed, `cs` holding the
/// approaching ones. A separating contact without percussion obeys the reaction alone exactly
/// when it does not penetrate: its rows' residual is max(0, −D_NE)/2 (normal; the mean velocity
/// less the bound D_NA/2) and 0 (tangential), with D_NE from the velocities the approaching
/// contacts' percussions make. One carrying a percussion cannot be judged in double precision:
/// infinity. The scale is the one every contact would give: the largest |D_A| of all of them.
template <int N, int C>
double unloaded_separating_residual(const ImpactProblemT<N, C>& pb, const ContactSpaceT<N, C>& cs,
                                    const FremondLaw& every, const ImpactResultT<N, C>& r) {
  double scale = cs.v_scale;
  for (int i = 0; i < cs.contacts; ++i) {
    if (!(cs.D_N(i) > 0.0)) continue;
    if (r.P_N(i) != 0.0 || r.P_T(i) != 0.0) return std::numeric_limits<double>::infinity();
    scale = std::max(scale, cs.D_N(i));
    if (cs.tangential) scale = std::max(scale, std::fabs(cs.D_T(i)));
  }
  double worst = held_rows_residual(cs, every, r);
  VecT<N> q;
  velocity_after(pb, cs, held_percussions(cs, r), q);
  for (int i = 0; i < cs.contacts; ++i) {
    if (!(cs.D_N(i) > 0.0)) continue;
    const double D_NE = contact_velocity(pb.W_N.col(i), q, pb.w_N.size() ? pb.w_N(i) : 0.0);
    worst = std::max(worst, std::isnan(D_NE) ? std::numeric_limits<double>::infinity()
                                             : std::max(0.0, -0.5 * D_NE));
  }
  return worst / scale;
}

}  // namespace

template <int N, int C>
double fremond_residual(const ImpactProblemT<N, C>& pb, const FremondLaw& law,
                        const ImpactResultT<N, C>& r) {
  ContactSpaceT<N, C> cs;
  build_contact_space(pb, law.has_friction(), cs);
  if (cs.active == 0) {  // every contact separates: undriven, each keeps P = 0
    double off_trivial = 0.0;
    for (int i = 0; i < cs.contacts; ++i)
      off_trivial = std::max({off_trivial, std::fabs(r.P_N(i)), std::fabs(r.P_T(i))});
    return off_trivial;
  }
  // Every contact obeys the law, the separating ones with the reaction alone
  // (separating_contacts.hpp); where none separates that is the law as it is.
  const FremondLaw every = law_of_every_contact(law, cs.D_N);
  if (cs.active == cs.contacts) return residual_of_held(cs, every, r);
  ContactSpaceT<N, C> all;
  try {
    build_contact_space(pb, law.has_friction(), all, HeldContacts::every);
  } catch (const InvalidArgument&) {
    // A separating contact's Delassus entries overflow: M and the approaching contacts built
    // above, so the cause is that contact, and no percussion on it is representable.
    return unloaded_separating_residual(pb, cs, every, r);
  }
  return residual_of_held(all, every, r);
}

template double fremond_residual(const ImpactProblemT<Dynamic, Dynamic>&, const FremondLaw&,
                                 const ImpactResultT<Dynamic, Dynamic>&);
template double fremond_residual(const ImpactProblemT<kSmallDofs, kSmallContacts>&,
                                 const FremondLaw&,
                                 const ImpactResultT<kSmallDofs, kSmallContacts>&);

}  // namespace fremond::detail
