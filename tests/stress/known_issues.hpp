#pragma once
/// @file Known library issues, shared by the stress runs and the fuzz targets: failures that are
/// reported to the library's maintainers (each with a reproducer and a disabled regression test in
/// tests/unit/regression_*_test.cpp) and must not stop the other checks meanwhile.
///
/// The file (tests/stress/known_issues.txt) has one issue a line, `law | regex | note`, where law
/// is one of law_family()'s names or `*`, and the regex (ECMAScript) is searched in the sentence
/// of the broken invariant (invariants.hpp). Blank lines and lines starting with # are comments.
/// Delete a line once its issue is fixed: the stress run says when a known issue is no longer seen.
#include <fstream>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "fremond/laws/impact_law.hpp"

namespace fremond::robust {

/// The stress runs' name of a law: newton, poisson, newton_coulomb, poisson_coulomb, fremond
/// (normal law only), fremond_viscous (a tangential potential), fremond_coulomb.
inline std::string law_family(const ImpactLaw& law) {
  if (!law.is<FremondLaw>()) return std::string(law.name());
  switch (law.get<FremondLaw>().tangential) {
    case TangentialLaw::none:
      return "fremond";
    case TangentialLaw::potential:
      return "fremond_viscous";
    case TangentialLaw::coulomb:
      return "fremond_coulomb";
  }
  return "fremond";
}

struct KnownIssue {
  std::string law;
  std::string text;
  std::regex pattern;
  std::string note;
  long seen = 0;
};

/// Reads the file; throws std::runtime_error for a line that is not `law | regex | note`.
inline std::vector<KnownIssue> read_known_issues(const std::string& path) {
  std::vector<KnownIssue> out;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read the known issues " + path);
  auto trim = [](const std::string& s) {
    const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  std::string line;
  while (std::getline(in, line)) {
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const auto p1 = line.find(" | ");
    const auto p2 = p1 == std::string::npos ? p1 : line.find(" | ", p1 + 3);
    if (p2 == std::string::npos)
      throw std::runtime_error(path + ": not 'law | regex | note': " + line);
    KnownIssue k;
    k.law = trim(line.substr(0, p1));
    k.text = trim(line.substr(p1 + 3, p2 - p1 - 3));
    k.pattern = std::regex(k.text);
    k.note = trim(line.substr(p2 + 3));
    out.push_back(std::move(k));
  }
  return out;
}

/// The known issue that `what` (a broken invariant of a law of family `law`) is, or null.
inline KnownIssue* match_known(std::vector<KnownIssue>& known, const std::string& law,
                               const std::string& what) {
  for (KnownIssue& k : known)
    if ((k.law == "*" || k.law == law) && std::regex_search(what, k.pattern)) return &k;
  return nullptr;
}

}  // namespace fremond::robust
