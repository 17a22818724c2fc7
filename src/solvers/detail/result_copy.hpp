#pragma once
/// @file A small result copied into a heap-stored one without new allocations where the sizes
/// match (the prepared solver's answer, solve after solve), and a result cleared for the next
/// solve.
#include <utility>

#include "fremond/solvers/impact_result.hpp"

namespace fremond::detail {

/// `to` becomes `from` in every member, as to_dynamic(from) would make it.
void copy_into(const SmallImpactResult& from, ImpactResult& to);

/// `out` as a default-constructed result, for the next solve. Not `out = {}`: a value-initialised
/// aggregate is zeroed whole first, its fixed-capacity vectors included (1 KB in the small form,
/// 130 instructions of every prepared one-contact solve).
template <int N, int C>
void clear_result(ImpactResultT<N, C>& out) {
  ImpactResultT<N, C> fresh;
  out = std::move(fresh);
}

}  // namespace fremond::detail
