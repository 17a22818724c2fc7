#include "fremond/laws/residual.hpp"

#include <limits>

#include "fremond/solvers/detail/classical.hpp"
#include "../solvers/detail/fremond.hpp"

namespace fremond {

template <int N, int C>
double law_residual(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                    const ImpactResultT<N, C>& r) {
  if (law.type != LawType::fremond) return detail::classical_residual(pb, law, r);
  return detail::fremond_residual(pb, law, r);
}

template double law_residual(const ImpactProblemT<Dynamic, Dynamic>&, const ImpactLaw&,
                             const ImpactResultT<Dynamic, Dynamic>&);
template double law_residual(const ImpactProblemT<kSmallDofs, kSmallContacts>&, const ImpactLaw&,
                             const ImpactResultT<kSmallDofs, kSmallContacts>&);

}  // namespace fremond
