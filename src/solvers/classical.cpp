// Placeholder until the classical laws land: every classical solve reports `unsupported`.
#include "fremond/solvers/detail/classical.hpp"

#include <limits>

namespace fremond::detail {

template <int N, int C>
void solve_classical(const ImpactProblemT<N, C>&, const ContactSpaceT<N, C>&, const ImpactLaw&,
                     const SolverOptions&, ImpactResultT<N, C>& out) {
  out.solver.status = SolverStatus::unsupported;
  out.solver.message = "classical laws are not implemented yet";
}

std::vector<ImpactResult> solve_classical_all(const ImpactProblem&, const ImpactLaw&,
                                              const SolverOptions&) {
  return {};
}

template <int N, int C>
double classical_residual(const ImpactProblemT<N, C>&, const ImpactLaw&, const ImpactResultT<N, C>&) {
  return std::numeric_limits<double>::quiet_NaN();
}

#define FREMOND_INSTANTIATE(N, C)                                                                  \
  template void solve_classical(const ImpactProblemT<N, C>&, const ContactSpaceT<N, C>&,          \
                                const ImpactLaw&, const SolverOptions&, ImpactResultT<N, C>&);    \
  template double classical_residual(const ImpactProblemT<N, C>&, const ImpactLaw&,               \
                                     const ImpactResultT<N, C>&);
FREMOND_INSTANTIATE(Dynamic, Dynamic)
FREMOND_INSTANTIATE(kSmallDofs, kSmallContacts)
#undef FREMOND_INSTANTIATE

}  // namespace fremond::detail
