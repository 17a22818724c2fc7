#include "fremond/laws/residual.hpp"

#include <limits>
#include <string>
#include <utility>

#include "fremond/core/error.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "laws/detail/plugins.hpp"

namespace fremond {

template <int N, int C>
double law_residual(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                    const ImpactResultT<N, C>& r) {
  // The residual indexes P_N and P_T by contact: a result of another problem (or a
  // default-constructed one) is no answer to this one. Refuse it, saying which sizes differ, for
  // every law alike.
  const auto c = static_cast<Eigen::Index>(pb.contacts());
  for (const auto& [name, size] : {std::pair{"P_N", r.P_N.size()}, std::pair{"P_T", r.P_T.size()}})
    if (size != c)
      throw InvalidArgument("result", std::string(name) + " has " + std::to_string(size) +
                                          " entries, the problem has " + std::to_string(c) +
                                          " contacts");
  if constexpr (N == Dynamic && C == Dynamic) {
    // In the storage solve_impact uses for this problem, so that the result's own residual reads
    // the same to the last bit (solve_impact.cpp).
    if (fits_small(pb) && fits_small(r)) return law_residual(to_small(pb), law, to_small(r));
  }
  return law.visit([&](const auto& l) { return detail::residual_of(pb, l, r); });
}

template double law_residual(const ImpactProblemT<kSmallDofs, kSmallContacts>&, const ImpactLaw&,
                             const ImpactResultT<kSmallDofs, kSmallContacts>&);
template double law_residual(const ImpactProblemT<Dynamic, Dynamic>&, const ImpactLaw&,
                             const ImpactResultT<Dynamic, Dynamic>&);

}  // namespace fremond
