#pragma once
// Shared by the fuzz targets: a failed invariant is a crash (libFuzzer keeps the input), and an
// exception other than InvalidArgument escaping the library is one too.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "fremond/fremond.hpp"
#include "stress/invariants.hpp"
#include "stress/known_issues.hpp"

namespace fremond::fuzz {

[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "\nINVARIANT BROKEN: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

/// A refusal must name what it refuses and say why.
inline void check_refusal(const InvalidArgument& e) {
  const std::string what = e.what();
  if (e.name().empty()) fail("InvalidArgument with an empty name: " + what);
  if (what.size() <= e.name().size() + 2) fail("InvalidArgument without a reason: " + what);
}

/// The known library issues (tests/stress/known_issues.txt, named by the environment variable
/// FREMOND_KNOWN_ISSUES, as scripts/fuzz.sh does): a broken invariant that is one of them is
/// reported to the maintainers already and does not stop the fuzzing.
inline std::vector<robust::KnownIssue>& known_issues() {
  static std::vector<robust::KnownIssue> known = [] {
    const char* path = std::getenv("FREMOND_KNOWN_ISSUES");
    if (!path || !*path) return std::vector<robust::KnownIssue>{};
    try {
      return robust::read_known_issues(path);
    } catch (const std::exception& e) {
      fail(e.what());
    }
  }();
  return known;
}

/// FREMOND_FUZZ_CLASSIFY=1: print the input's law family (known_issues.hpp) and solve nothing.
/// scripts/fuzz.sh sorts the inputs that timed out with it, without running them again.
inline bool classify_only(const ImpactLaw& law) {
  static const bool on = [] {
    const char* v = std::getenv("FREMOND_FUZZ_CLASSIFY");
    return v && *v && *v != '0';
  }();
  if (on) std::printf("law_family: %s\n", robust::law_family(law).c_str());
  return on;
}

template <int N, int C>
void check(const ImpactProblemT<N, C>& pb, const ImpactLaw& law, const SolverOptions& options,
           const ImpactResultT<N, C>& r, const char* where) {
  const std::string broken = robust::check_result(pb, law, options, r);
  if (broken.empty() || robust::match_known(known_issues(), robust::law_family(law), broken))
    return;
  fail(std::string(where) + ": " + broken + "\n  law: " + law.describe());
}

}  // namespace fremond::fuzz
