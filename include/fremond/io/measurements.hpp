#pragma once
/// @file The measured-impact file (docs/measurements.md): a JSON array of impacts, each an impact
/// problem without a law and the velocity measured after it.
///
/// Keys of each impact: `M`, `W_N`, `qdot_A`, `qdot_E` required; `W_T`, `w_N`, `w_T`, `mask`,
/// `sigma` optional, read as the impact-problem file reads them (docs/problem-file.md). `qdot_E`
/// holds n numbers, `null` where a component was not measured; `mask` (n booleans) says which
/// were measured (without it: the entries that are not null); `sigma` is one number for every
/// component or n of them (default 1). A row that is not a valid measured impact is refused with
/// its index and key named: `impacts[3].qdot_E[1]: ...`.
#include <iosfwd>
#include <string_view>
#include <vector>

#include "fremond/fit/measured_impact.hpp"

namespace fremond::io {

/// Reads the measured-impact file from its text. Throws InvalidArgument naming the key as
/// `impacts[i].key` (or `impacts` for the document itself: not JSON, not an array, empty).
std::vector<MeasuredImpact> parse_measurements(std::string_view json_text);

/// The same, reading the whole stream first.
std::vector<MeasuredImpact> read_measurements(std::istream& in);

}  // namespace fremond::io
