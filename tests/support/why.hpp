#pragma once
// What a failed assertion on a result prints: how the solve ended and the solver's explanation.
// Tests assert on the answer; the message is for the reader of a failure only.
#include <string>

#include "fremond/core/error.hpp"
#include "fremond/solvers/impact_result.hpp"

namespace fremond::testing {

template <class Result>
std::string why(const Result& r) {
  return std::string(to_string(r.solver.status)) + " (" +
         std::string(to_string(r.solver.criterion)) + "): " + std::string(r.solver.message);
}

/// The name (key, option, member) an InvalidArgument thrown by f() gives, or "accepted".
template <class F>
std::string refused_name(F&& f) {
  try {
    f();
  } catch (const InvalidArgument& e) {
    return e.name();
  }
  return "accepted";
}

}  // namespace fremond::testing
