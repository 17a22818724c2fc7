#pragma once
/// @file A small result copied into a heap-stored one without new allocations where the sizes
/// match (the prepared solver's answer, solve after solve), and a result cleared for the next
/// solve.
#include <memory>
#include <new>

#include "fremond/solvers/impact_result.hpp"

namespace fremond::detail {

/// `to` becomes `from` in every member, as to_dynamic(from) would make it.
void copy_into(const SmallImpactResult& from, ImpactResult& to);

/// `out` as a default-constructed result, for the next solve: destroyed and default-initialised in
/// place. Not `out = {}` (value-initialisation zeroes the whole 1 KB of the small form first, its
/// fixed-capacity vectors included) nor a fresh result moved in (a copy of every member).
template <int N, int C>
void clear_result(ImpactResultT<N, C>& out) {
  std::destroy_at(&out);
  ::new (static_cast<void*>(&out)) ImpactResultT<N, C>;
}

}  // namespace fremond::detail
