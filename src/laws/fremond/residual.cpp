// Frémond's residual (laws/residual.hpp): the natural map of every row of the law
// (fremond_rows.hpp) at the answer's percussions, in velocity units.
#include <algorithm>
#include <cmath>

#include "contact_space/contact_space.hpp"
#include "laws/detail/residuals.hpp"
#include "laws/detail/separating_contacts.hpp"
#include "laws/fremond/rows.hpp"

namespace fremond::detail {

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
  if (cs.active < cs.contacts) build_contact_space(pb, law.has_friction(), cs, HeldContacts::every);
  FremondRowsT<N, C> rows;
  rows.init(cs, every);
  typename FremondRowsT<N, C>::Rows P(cs.rows());
  for (int k = 0; k < cs.active; ++k) {
    P(k) = r.P_N(cs.index(k));
    if (cs.tangential) P(cs.active + k) = r.P_T(cs.index(k));
  }
  return rows.plain_residual(P) / cs.v_scale;
}

template double fremond_residual(const ImpactProblemT<Dynamic, Dynamic>&, const FremondLaw&,
                                 const ImpactResultT<Dynamic, Dynamic>&);
template double fremond_residual(const ImpactProblemT<kSmallDofs, kSmallContacts>&,
                                 const FremondLaw&,
                                 const ImpactResultT<kSmallDofs, kSmallContacts>&);

}  // namespace fremond::detail
