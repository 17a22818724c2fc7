// The performance report's work-precision data (bench/work_precision.hpp), on a tiny version of the
// sweep: the CSV it writes is well-formed, and every method reaches its requested tolerance on the
// suite (bench/fremond_suite.hpp), measured against the quad reference.
//
// "Reaches its requested tolerance": the tolerance bounds the law's residual (relative to the
// largest contact velocity before the impact), and the error measured is that of q̇_E in the
// kinetic-energy norm relative to q̇_A. The two agree up to the problem's conditioning, so a point
// marked converged must have
//     error ≤ C · max(tolerance, 16 ε κ(G), 1e-15)
// with C = 10 for the exact and Newton-type methods, and C = 100 for the proximal iterations,
// which converge linearly with a rate ρ and stop on the residual, an underestimate of the error
// by up to 1/(1 − ρ). NLopt's tolerance is nlopt_tolerance. A point that is not converged must say
// so in its status; at the default tolerance every method converges on every case except those
// listed in kMayNotConverge, each with its reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../bench/work_precision.hpp"

namespace fremond {
namespace {

using namespace fremond::bench;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream is(line);
  while (std::getline(is, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

bool parse_double(const std::string& s, double& v) {
  if (s == "nan") {
    v = std::nan("");
    return true;
  }
  if (s == "inf") {
    v = std::numeric_limits<double>::infinity();
    return true;
  }
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size();
}

/// 16 ε κ(G) of the case's worst problem.
double conditioning_floor(const FremondCase& c) {
  return 16 * std::numeric_limits<double>::epsilon() * wp::condition_of_G(c);
}

/// (problem, law, method) that may stay unconverged at the default tolerance, and why. "may": if
/// the library gets better they converge and the test still passes.
const std::map<std::string, std::string>& may_not_converge() {
  static const std::map<std::string, std::string> m{
      {"hard_mass_ratio_1e6 fremond_viscous proximal",
       "Gauss-Seidel on a Delassus matrix with κ ≈ 1e7 converges at a rate 1 − 1e-7 a sweep"},
      {"random_n6_c3 fremond_p3_coulomb semismooth_newton",
       "stalls at a kink on one of the 16 problems (automatic falls back to the proximal "
       "iterations)"},
      {"random_n6_c3 fremond_p3_coulomb proximal",
       "no progress in 1000 sweeps on one of the 16 problems (Coulomb's bound moves with P_N)"},
  };
  return m;
}

TEST(PerfReport, WorkPrecisionCsvIsWellFormedAndMethodsReachTheirTolerance) {
  SuiteOptions so;
  so.random_problems = 16;
  const std::vector<FremondCase> cases = fremond_suite(so);
  wp::Options o = wp::tiny_options();
  const std::vector<wp::Point> points = wp::run(cases, o);

  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "fremond_perf_report_test";
  std::filesystem::create_directories(dir);
  const std::filesystem::path csv = dir / "work_precision.csv";
  {
    std::ofstream f(csv);
    wp::write_csv(f, points);
  }

  // Well-formed: the header, then one row of kCsvColumns cells per point, each cell parsing.
  std::ifstream f(csv);
  std::string line;
  ASSERT_TRUE(std::getline(f, line));
  EXPECT_EQ(line, wp::csv_header());
  const std::set<std::string> statuses{"converged", "max_iterations", "stalled", "no_solution",
                                       "failed"};
  const std::set<std::string> methods{
      "automatic",         "closed_form", "scalar_newton", "mode_enumeration",
      "semismooth_newton", "proximal",    "nlopt"};
  std::map<std::string, const FremondCase*> by_name;
  for (const FremondCase& c : cases) by_name[c.problem + " " + c.law_name] = &c;
  std::map<std::string, double> floors;
  std::set<std::string> seen;
  int rows = 0;
  while (std::getline(f, line)) {
    ++rows;
    const auto cell = split(line);
    ASSERT_EQ(static_cast<int>(cell.size()), wp::kCsvColumns) << line;
    const std::string& method = cell[0];
    const std::string name = cell[1] + " " + cell[2];
    EXPECT_TRUE(methods.count(method)) << line;
    ASSERT_TRUE(by_name.count(name)) << line;
    EXPECT_TRUE(cell[3] == "0" || cell[3] == "1") << line;
    double tol, budget, ns, err, res, iters, hit, nprob;
    ASSERT_TRUE(parse_double(cell[4], tol) && tol > 0 && tol <= 1e-2) << line;
    ASSERT_TRUE(parse_double(cell[5], budget) && budget >= 0 && budget == std::floor(budget))
        << line;
    ASSERT_TRUE(parse_double(cell[6], ns) && std::isfinite(ns) && ns > 0) << line;
    ASSERT_TRUE(parse_double(cell[7], err)) << line;
    ASSERT_TRUE(parse_double(cell[8], res) && res >= 0) << line;
    EXPECT_TRUE(statuses.count(cell[9])) << line;
    EXPECT_FALSE(cell[10].empty()) << line;
    ASSERT_TRUE(parse_double(cell[11], iters) && iters >= 0) << line;
    ASSERT_TRUE(parse_double(cell[12], hit) && (hit == 0 || hit == 1)) << line;
    ASSERT_TRUE(parse_double(cell[13], nprob) && nprob >= 1) << line;
    double cond;
    ASSERT_TRUE(parse_double(cell[14], cond) && cond >= 1) << line;
    const FremondCase& c = *by_name[name];
    const bool has_reference = c.reference[0].ok;
    EXPECT_EQ(std::isnan(err), !has_reference) << line;
    seen.insert(name + " " + method);

    // The requested tolerance, where the point converged.
    if (cell[9] != "converged" || !has_reference) continue;
    if (!floors.count(name)) floors[name] = conditioning_floor(c);
    const double C = method == "proximal" ? 100.0 : 10.0;
    const double bound = C * std::max({tol, floors[name], 1e-15});
    EXPECT_LE(err, bound) << method << " on " << name << " at tolerance " << tol << " (budget "
                          << budget << "): error " << err;
  }
  EXPECT_EQ(rows, static_cast<int>(points.size()));
  std::printf("  %d work-precision points over %zu cases\n", rows, cases.size());

  // Coverage: every case has its automatic, semismooth Newton, proximal and NLopt points, and the
  // exact methods where they apply.
  for (const FremondCase& c : cases) {
    const std::string name = c.problem + " " + c.law_name;
    for (const char* m : {"automatic", "semismooth_newton", "proximal", "nlopt"})
      EXPECT_TRUE(seen.count(name + " " + m)) << name << " has no " << m << " point";
  }

  // At the default tolerance every method converges on every case, but for the listed ones.
  const double t0 = SolverOptions{}.tolerance;
  for (const wp::Point& p : points) {
    if (p.method == "nlopt" || p.tolerance != t0) continue;
    const std::string key = p.problem + " " + p.law + " " + p.method;
    if (p.status != "converged") {
      EXPECT_TRUE(may_not_converge().count(key))
          << key << " did not converge at the default tolerance: " << p.status;
    }
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace fremond
