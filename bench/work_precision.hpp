#pragma once
/// @file The work-precision sweep of Frémond's solvers (issue 6, item 2), shared by the program
/// bench/work_precision.cpp and by the test of the report (tests/unit/perf_report_test.cpp), which
/// runs a tiny version of it.
///
/// For every case of the suite (fremond_suite.hpp) and every method that applies, the sweep times
/// solve_impact and measures the actual error of its answer against the quad reference:
///  - the iterative methods (semismooth Newton, proximal iterations, and `automatic`, which picks
///    its own) over a range of `SolverOptions::tolerance`;
///  - NLopt over a range of `nlopt_tolerance` (which only decides its status: its own stopping test
///    is fixed), and over a range of evaluation budgets (`max_nlopt_evaluations`), which is what
///    traces its work against its precision;
///  - the exact methods (closed form, scalar Newton, mode enumeration) once: they take no
///    tolerance.
/// One CSV row per (method, case, tolerance, budget): see csv_header().
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "fremond_suite.hpp"

namespace fremond::bench::wp {

/// One point of the diagram.
struct Point {
  std::string method;   ///< the forced method (or "automatic")
  std::string problem;  ///< the case's problem and law
  std::string law;
  bool hard = false;
  double tolerance = 0.0;  ///< the requested tolerance (NLopt: nlopt_tolerance)
  int budget = 0;          ///< NLopt's evaluation budget; 0 elsewhere (the default budgets)
  double ns_per_solve = 0.0;
  double rel_error = 0.0;   ///< the largest over the case's problems (NaN: no reference)
  double residual = 0.0;    ///< the largest law residual the solver reported
  std::string status;       ///< the worst status over the case's problems
  std::string answered_by;  ///< the methods that produced the answers, e.g.
                            ///< "semismooth_newton*15|proximal*1"
  double iterations = 0;    ///< mean over the problems
  bool budget_hit = false;  ///< NLopt stopped on its evaluation budget on some problem
  int problems = 0;         ///< problems of the case solved (fewer when a solve was too slow)
  double cond_G = 0.0;      ///< the largest κ(G) over the case's problems (non-zero eigenvalues)
  double max_solve_seconds = 0.0;  ///< the slowest single solve (untimed pass)
};

struct Options {
  std::vector<double> tolerances{1e-2,  1e-3,  1e-4,  1e-6,  1e-8, 1e-10,
                                 1e-12, 1e-13, 1e-14, 1e-15, 1e-16};
  std::vector<double> nlopt_tolerances{1e-4, 1e-6, 1e-8, 1e-9, 1e-10, 1e-12};
  std::vector<int> nlopt_budgets{5, 10, 20, 50, 100, 200, 500, 1000, 5000};
  bool nlopt = true;
  double min_seconds = 0.02;  ///< timing: repeat the solves for at least this long, per repetition
  int repetitions = 3;        ///< timing: the fastest of this many repetitions
  /// A point whose single solve takes longer is timed by that one solve, and NLopt's series on
  /// the case stops there (its MMA path for Coulomb can run for minutes at the default budget).
  double max_solve_seconds = 0.25;
  int nlopt_coulomb_budget_cap = 500;  ///< see run()
};

/// Options for the test: three tolerances, short timings.
inline Options tiny_options() {
  Options o;
  o.tolerances = {1e-4, 1e-8, 1e-13};
  o.nlopt_tolerances = {1e-6, 1e-9};
  o.nlopt_budgets = {20, 200, 2000};
  o.min_seconds = 0.0005;
  o.repetitions = 1;
  return o;
}

/// ns per call of f() (each call solves `solves_per_call` problems): the fastest of `reps` runs of
/// at least `min_seconds` each.
template <class F>
double time_ns(F&& f, double min_seconds, int reps, int solves_per_call = 1) {
  using clock = std::chrono::steady_clock;
  f();  // warm up
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < std::max(reps, 1); ++r) {
    long calls = 0;
    const auto t0 = clock::now();
    double elapsed = 0.0;
    do {
      f();
      ++calls;
      elapsed = std::chrono::duration<double>(clock::now() - t0).count();
    } while (elapsed < min_seconds);
    best = std::min(best, 1e9 * elapsed / (static_cast<double>(calls) * solves_per_call));
  }
  return best;
}

inline int status_rank(SolverStatus s) {
  switch (s) {
    case SolverStatus::converged:
      return 0;
    case SolverStatus::max_iterations:
      return 1;
    case SolverStatus::stalled:
      return 2;
    case SolverStatus::no_solution:
      return 3;
    case SolverStatus::unsupported:
      return 4;
    case SolverStatus::failed:
      return 5;
    case SolverStatus::not_run:
      break;
  }
  return 6;
}

/// Solves every problem of the case once with `opt` (untimed) and fills the accuracy columns;
/// false when the method does not apply (status unsupported).
inline bool measure(const FremondCase& c, const SolverOptions& opt, Point& pt,
                    double max_solve_seconds = std::numeric_limits<double>::infinity()) {
  SolverStatus worst = SolverStatus::converged;
  double err = 0.0, res = 0.0, iters = 0.0;
  std::size_t k_done = c.problems.size();
  bool any_reference = false;
  int by[16] = {};
  pt.budget_hit = false;
  pt.max_solve_seconds = 0.0;
  for (std::size_t k = 0; k < c.problems.size(); ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const SmallImpactResult r = solve_impact(c.problems[k], c.law, opt);
    pt.max_solve_seconds =
        std::max(pt.max_solve_seconds,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (r.solver.status == SolverStatus::unsupported) return false;
    if (r.solver.method == SolverMethod::nlopt &&
        r.solver.native_code == 5 /* NLOPT_MAXEVAL_REACHED */)
      pt.budget_hit = true;
    if (status_rank(r.solver.status) > status_rank(worst)) worst = r.solver.status;
    by[static_cast<int>(r.solver.method)]++;
    res = std::max(res, std::isfinite(r.solver.residual) ? r.solver.residual
                                                         : std::numeric_limits<double>::infinity());
    iters += r.solver.iterations;
    const double e = relative_error(c.problems[k], c.reference[k], r.qdot_E);
    if (!std::isnan(e)) {
      any_reference = true;
      err = std::max(err, e);
    }
    if (pt.max_solve_seconds > max_solve_seconds) {  // too slow to go on: the problems so far
      k_done = k + 1;
      break;
    }
  }
  pt.problems = static_cast<int>(k_done);
  pt.answered_by.clear();
  for (int m = 0; m < 16; ++m)
    if (by[m] > 0) {
      if (!pt.answered_by.empty()) pt.answered_by += "|";
      pt.answered_by += std::string(to_string(static_cast<SolverMethod>(m)));
      if (by[m] != static_cast<int>(k_done))
        pt.answered_by.append("*").append(std::to_string(by[m]));
    }
  pt.status = std::string(to_string(worst));
  pt.rel_error = any_reference ? err : std::nan("");
  pt.residual = res;
  pt.iterations = iters / static_cast<double>(k_done);
  return true;
}

inline double time_case(const FremondCase& c, const SolverOptions& opt, const Options& o) {
  std::size_t k = 0;
  const std::size_t n = c.problems.size();
  return time_ns(
      [&] {
        const SmallImpactResult r = solve_impact(c.problems[k], c.law, opt);
        k = (k + 1) % n;
        asm volatile("" : : "r"(r.qdot_E.data()) : "memory");
      },
      o.min_seconds, o.repetitions);
}

/// The largest condition number of the case's Delassus matrices, over their non-zero eigenvalues
/// (the rows the law uses: normal, and tangential where it has a tangential law). The attainable
/// error of a contact-space method is about ε κ(G).
inline double condition_of_G(const FremondCase& c) {
  double worst = 1.0;
  for (const SmallImpactProblem& p : c.problems) {
    const bool t = c.spec.tangential != FremondLawSpec::Tangential::none && p.has_tangential();
    const int r = p.contacts() * (t ? 2 : 1);
    Eigen::MatrixXd W(p.dofs(), r);
    for (int i = 0; i < p.contacts(); ++i) {
      W.col(t ? 2 * i : i) = p.W_N.col(i);
      if (t) W.col(2 * i + 1) = p.W_T.col(i);
    }
    const Eigen::MatrixXd M = p.M;
    const Eigen::MatrixXd G = W.transpose() * M.ldlt().solve(W);
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(G).eigenvalues();
    double lpos = ev.maxCoeff();
    for (int i = 0; i < ev.size(); ++i)
      if (ev(i) > 1e-12 * ev.maxCoeff()) lpos = std::min(lpos, ev(i));
    worst = std::max(worst, ev.maxCoeff() / lpos);
  }
  return worst;
}

inline SolverOptions options_for(SolverMethod m, double tol) {
  SolverOptions s;
  s.method = m;
  s.tolerance = tol;
  return s;
}

/// The whole sweep over `cases`; `progress`, if given, receives one line per point.
inline std::vector<Point> run(const std::vector<FremondCase>& cases, const Options& o,
                              std::ostream* progress = nullptr) {
  std::vector<Point> out;
  Point last;
  double cond = 1.0;
  auto add = [&](const FremondCase& c, SolverMethod m, const SolverOptions& opt, double tol,
                 int budget) {
    Point pt;
    pt.method = std::string(to_string(m));
    pt.problem = c.problem;
    pt.law = c.law_name;
    pt.hard = c.hard;
    pt.cond_G = cond;
    pt.tolerance = tol;
    pt.budget = budget;
    if (!measure(c, opt, pt, o.max_solve_seconds)) return false;
    pt.ns_per_solve = pt.max_solve_seconds > o.max_solve_seconds ? 1e9 * pt.max_solve_seconds
                                                                 : time_case(c, opt, o);
    last = pt;
    if (progress)
      *progress << c.problem << " " << c.law_name << " " << pt.method << " tol=" << tol
                << " budget=" << budget << ": " << pt.ns_per_solve << " ns, error " << pt.rel_error
                << ", " << pt.status << "\n"
                << std::flush;
    out.push_back(pt);
    return true;
  };
  for (const FremondCase& c : cases) {
    cond = condition_of_G(c);
    const double t0 = SolverOptions{}.tolerance;
    for (SolverMethod m :
         {SolverMethod::closed_form, SolverMethod::scalar_newton, SolverMethod::mode_enumeration})
      add(c, m, options_for(m, t0), t0, 0);
    for (SolverMethod m :
         {SolverMethod::automatic, SolverMethod::semismooth_newton, SolverMethod::proximal})
      for (double tol : o.tolerances)
        if (!add(c, m, options_for(m, tol), tol, 0)) break;
    if (!o.nlopt) continue;
    // NLopt: budgets in increasing order until it stops on its own criterion (a larger budget then
    // gives the same answer) or a solve gets too slow; then, if it stopped on its own, its
    // tolerance sweep at the default budget.
    // Its MMA path (Coulomb) on three contacts takes tens of seconds for a few thousand
    // evaluations: budgets there stop at o.nlopt_coulomb_budget_cap.
    const bool slow_nlopt =
        c.spec.tangential == FremondLawSpec::Tangential::coulomb && c.problems[0].contacts() > 2;
    bool natural_stop = false;
    for (int budget : o.nlopt_budgets) {
      if (slow_nlopt && budget > o.nlopt_coulomb_budget_cap) break;
      SolverOptions s;
      s.method = SolverMethod::nlopt;
      s.max_nlopt_evaluations = budget;
      if (!add(c, SolverMethod::nlopt, s, s.nlopt_tolerance, budget)) break;
      if (last.max_solve_seconds > o.max_solve_seconds) break;
      if (!last.budget_hit) {
        natural_stop = true;
        break;
      }
    }
    if (!natural_stop) {
      if (progress)
        *progress << c.problem << " " << c.law_name
                  << " nlopt: no run at the default budget (it did not stop on its own within "
                  << "the budgets tried, or a solve took over " << o.max_solve_seconds << " s)\n";
      continue;
    }
    for (double tol : o.nlopt_tolerances) {
      SolverOptions s;
      s.method = SolverMethod::nlopt;
      s.tolerance = std::min(s.tolerance, tol);
      s.nlopt_tolerance = tol;
      if (!add(c, SolverMethod::nlopt, s, tol, 0)) break;
    }
  }
  return out;
}

inline const char* csv_header() {
  return "method,problem,law,hard,tolerance,budget,ns_per_solve,rel_error,residual,status,"
         "answered_by,iterations,budget_hit,problems,cond_G";
}
inline constexpr int kCsvColumns = 15;

inline void write_csv(std::ostream& os, const std::vector<Point>& points) {
  os << csv_header() << "\n";
  std::ostringstream line;
  for (const Point& p : points) {
    line.str("");
    line << std::setprecision(6);
    line << p.method << "," << p.problem << "," << p.law << "," << (p.hard ? 1 : 0) << ","
         << p.tolerance << "," << p.budget << "," << p.ns_per_solve << ",";
    line << std::setprecision(4) << p.rel_error << "," << p.residual << ",";
    line << p.status << "," << p.answered_by << "," << std::setprecision(6) << p.iterations << ","
         << (p.budget_hit ? 1 : 0) << "," << p.problems << "," << std::setprecision(3) << p.cond_G;
    os << line.str() << "\n";
  }
}

}  // namespace fremond::bench::wp
