#include "fremond/laws/residual.hpp"

#include <limits>
#include <string>
#include <utility>

#include "fremond/core/error.hpp"
#include "fremond/solvers/detail/classical.hpp"
#include "../solvers/detail/fremond.hpp"

namespace fremond {

template <int N, int C>
double law_residual(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                    const ImpactResultT<N, C>& r) {
  if (law.type != LawType::fremond) return detail::classical_residual(pb, law, r);
  // Frémond's residual indexes P_N and P_T by contact: a result of another problem (or a
  // default-constructed one) would be read past its end. Refuse it, saying which sizes differ. The
  // classical residual checks the same sizes itself and answers +inf (a result that is no answer).
  const auto c = static_cast<Eigen::Index>(pb.contacts());
  for (const auto& [name, size] : {std::pair{"P_N", r.P_N.size()}, std::pair{"P_T", r.P_T.size()}})
    if (size != c)
      throw InvalidArgument("result", std::string(name) + " has " + std::to_string(size) +
                                          " entries, the problem has " + std::to_string(c) +
                                          " contacts");
  return detail::fremond_residual(pb, law, r);
}

template double law_residual(const ImpactProblemT<Dynamic, Dynamic>&, const ImpactLaw&,
                             const ImpactResultT<Dynamic, Dynamic>&);
template double law_residual(const ImpactProblemT<kSmallDofs, kSmallContacts>&, const ImpactLaw&,
                             const ImpactResultT<kSmallDofs, kSmallContacts>&);

}  // namespace fremond
