#pragma once
// What `fremond predict` and `fremond fit` share: the measured-impact file read from a path or
// standard input, lists of NAME=VALUE, the output written whole.
#include <map>
#include <string>
#include <vector>

#include "fremond/fit/measured_impact.hpp"

namespace fremond::cli {

/// The measured-impact file (docs/measurements.md) at `file`, or standard input for "-". Throws
/// InvalidArgument naming the file, or the row and key (`impacts[3].qdot_E: ...`).
std::vector<MeasuredImpact> read_measured(const std::string& file);

/// "e=0.9,mu=0.3" as {{"e", 0.9}, {"mu", 0.3}}; throws InvalidArgument naming `option`.
std::map<std::string, double> named_values(const std::vector<std::string>& items,
                                           const std::string& option);

/// `text` to `out` (complete or absent) or to standard output when `out` is empty; throws
/// InvalidArgument naming what could not be written.
void write_text(const std::string& out, const std::string& text);

}  // namespace fremond::cli
