#pragma once
/// @file A small result copied into a heap-stored one without new allocations where the sizes
/// match (the prepared solver's answer, solve after solve).
#include "fremond/solvers/impact_result.hpp"

namespace fremond::detail {

/// `to` becomes `from` in every member, as to_dynamic(from) would make it.
void copy_into(const SmallImpactResult& from, ImpactResult& to);

}  // namespace fremond::detail
