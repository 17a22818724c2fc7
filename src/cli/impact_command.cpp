// `fremond impact FILE|-` (docs/problem-file.md): reads one impact problem, solves it, prints the
// result as JSON.
//
// Exit status: 0 solved; 1 input refused (the message names the key; nothing on stdout); 2 the
// solver did not converge (the result is printed anyway, so the status can be seen); 3 the law has
// no solution for these data (docs/laws.md; the result is printed, with a message on stderr); 4 the
// result could not be written to standard output (message on stderr); 5 with --require-admissible,
// an inadmissible answer; 6 no answer within --time-limit (nothing on stdout).
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.hpp"
#include "cli/output.hpp"
#include "cli/watchdog.hpp"
#include "fremond/core/error.hpp"
#include "fremond/io/problem_file.hpp"
#include "fremond/io/siconos_file.hpp"
#include "fremond/potentials/registry.hpp"
#include "fremond/solvers/solve_impact.hpp"
#include "fremond/sparse/sparse_solver.hpp"

namespace fremond::cli {

namespace {

constexpr int kExitRefused = 1;
constexpr int kExitNotConverged = 2;
constexpr int kExitNoSolution = 3;
constexpr int kExitWriteFailed = 4;
constexpr int kExitInadmissible = 5;
constexpr int kExitTimeLimit = 6;

struct ImpactArguments {
  std::string file;
  bool all_solutions = false;
  std::string method = "automatic";
  double tolerance = SolverOptions{}.tolerance;
  bool tolerance_given = false;  // a Siconos file's default is SparseSolverOptions's
  bool pretty = false;
  bool require_admissible = false;
  double time_limit = 0.0;  // seconds; 0: none
};

// The input's name in messages.
std::string input_name(const std::string& file) {
  return file == "-" ? "<stdin>" : file;
}

std::string read_input(const std::string& file) {
  if (file == "-")
    return {std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw InvalidArgument(file, "is a directory, not a problem file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InvalidArgument(file, std::string("cannot open: ") + std::strerror(errno));
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InvalidArgument(file, "cannot read");
  return text;
}

// Options first: a bad option is refused before the input is read (stdin may be a pipe).
SolverOptions solver_options(const ImpactArguments& args) {
  SolverOptions options;
  try {
    options.method = solver_method_from_string(args.method);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument("--method", std::string(e.what()).substr(e.name().size() + 2));
  }
  options.tolerance = args.tolerance;
  if (!(args.time_limit >= 0.0) || !std::isfinite(args.time_limit))
    throw InvalidArgument("--time-limit",
                          "must be a finite number of seconds >= 0 (0: none), got " +
                              std::to_string(args.time_limit));
  std::string why;
  if (!options.is_valid(&why))
    throw InvalidArgument("--" + why.substr(0, why.find(':')), why.substr(why.find(':') + 2));
  return options;
}

// A result that cannot be written in full (disk full, closed pipe, size limit) is a failure: a
// caller reading only the exit status must not take a cut-off result for an answer.
void print(const std::string& json) {
  if (!write_stdout(json + "\n")) {
    std::fprintf(stderr, "fremond impact: error: cannot write the result to standard output: %s\n",
                 errno ? std::strerror(errno) : "write failed");
    exit_with(kExitWriteFailed);
  }
}

// An answer whose certificate fails is still the law's answer (Newton + Coulomb creates energy on
// the paper's bar): said on stderr, and an error only when asked for.
void report_inadmissible(const ImpactResult& r, const ImpactArguments& args) {
  if (r.admissibility.admissible || !r.ok()) return;
  const auto& a = r.admissibility;
  std::fprintf(
      stderr,
      "fremond impact: %s: the answer is not admissible: %s fails by %.6g%s "
      "(T_E - T_A = %.6g)\n",
      args.require_admissible ? "error" : "note", std::string(to_string(a.failed)).c_str(),
      a.violation,
      a.failed_contact >= 0 ? (" at contact " + std::to_string(a.failed_contact)).c_str() : "",
      r.energy_change);
  if (args.require_admissible) exit_with(kExitInadmissible);
}

// Exits like a JSON problem's solve: the result printed, then the status.
void finish(const ImpactResult& result, const ImpactArguments& args) {
  print(io::result_to_json(result, args.pretty ? 2 : -1));
  if (!result.ok()) {
    std::fprintf(stderr, "fremond impact: the solver did not converge (status %s: %s)\n",
                 std::string(to_string(result.solver.status)).c_str(),
                 std::string(result.solver.message).c_str());
    exit_with(kExitNotConverged);
  }
  report_inadmissible(result, args);
}

// The options of a sparse solve (docs/sparse.md), refusing what the sparse path does not have.
SparseSolverOptions sparse_options(const ImpactArguments& args, const char* what) {
  if (args.all_solutions)
    throw InvalidArgument("--all-solutions", std::string("is not available for ") + what +
                                                 ", solved sparse (one solution)");
  if (args.method != "automatic" && args.method != "nsgs")
    throw InvalidArgument(
        "--method",
        std::string(what) + " is solved sparse, by nsgs (or automatic), got " + args.method);
  SparseSolverOptions options;
  if (args.tolerance_given) options.tolerance = args.tolerance;
  return options;
}

// A Siconos friction-contact file (docs/sparse.md): solved sparse, by nonsmooth Gauss-Seidel.
void run_siconos(const std::string& text, const ImpactArguments& args) {
  io::SiconosProblem file;
  SparseSolverOptions options;
  try {
    options = sparse_options(args, "a Siconos file");
    try {
      file = io::parse_siconos_file(text);
    } catch (const InvalidArgument& e) {
      throw InvalidArgument(input_name(args.file) + ": " + e.name(),
                            std::string(e.what()).substr(e.name().size() + 2));
    }
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "fremond impact: error: %s\n", e.what());
    exit_with(kExitRefused);
  }
  const std::string size = std::to_string(file.contacts()) + " contacts (Siconos file)";
  std::optional<Watchdog> watchdog;
  watchdog.emplace("fremond impact", size, args.time_limit, kExitTimeLimit);
  const ImpactResult result = file.form == io::SiconosProblem::Form::local
                                  ? solve_contact_problem(file.contact, file.law(), options)
                                  : solve_impact(file.impact, file.law(), options);
  watchdog.reset();
  finish(result, args);
}

// Problem files from this many contacts on are solved sparse under Newton's law: Lemke's pivots
// on the dense G cost the cube of the contacts (230 contacts on 690 dofs: past 300 s; sparse:
// 1.4 ms).
constexpr int kSparseFromContacts = 64;

// A problem file solved by the sparse path (docs/sparse.md): under a law it solves, with method
// nsgs or automatic, on a file that writes its matrices sparse or has kSparseFromContacts contacts
// (fewer, written dense: solve_impact runs the same sweeps and certifies in q̇). A file written
// sparse is read sparse (kept sparse however large); `dense` is the file already read dense.
// False sends the file to the dense solvers.
bool run_sparse(const std::string& text, const io::ProblemFile* dense,
                const ImpactArguments& args) {
  const bool nsgs = args.method == "nsgs";
  if (args.all_solutions || (!nsgs && args.method != "automatic")) return false;
  io::SparseProblemFile file;
  SparseSolverOptions options;
  try {
    if (dense) {
      if (dense->problem.contacts() < kSparseFromContacts) return false;
      file.problem.M = dense->problem.M.sparseView(0.0, 0.0);
      file.problem.W_N = dense->problem.W_N.sparseView(0.0, 0.0);
      file.problem.W_T = dense->problem.W_T.sparseView(0.0, 0.0);
      file.problem.w_N = dense->problem.w_N;
      file.problem.w_T = dense->problem.w_T;
      file.problem.qdot_A = dense->problem.qdot_A;
      file.law = dense->law;
    } else {
      try {
        file = io::parse_sparse_problem_file(text, PotentialRegistry::with_builtins());
      } catch (const InvalidArgument& e) {
        throw InvalidArgument(input_name(args.file) + ": " + e.name(),
                              std::string(e.what()).substr(e.name().size() + 2));
      }
    }
    if (!solved_sparse(file.law)) return false;
    options = sparse_options(args, "a problem solved sparse");
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "fremond impact: error: %s\n", e.what());
    exit_with(kExitRefused);
  }
  const std::string size = std::to_string(file.problem.contacts()) + " contacts, sparse";
  std::optional<Watchdog> watchdog;
  watchdog.emplace("fremond impact", size, args.time_limit, kExitTimeLimit);
  const ImpactResult result = solve_impact(file.problem, file.law, options);
  watchdog.reset();
  finish(result, args);
  return true;
}

void run(const ImpactArguments& args) {
  io::ProblemFile file;
  SolverOptions options;
  try {
    options = solver_options(args);
    const std::string text = read_input(args.file);
    if (io::looks_like_siconos_file(text)) return run_siconos(text, args);
    if (io::writes_sparse_matrices(text) && run_sparse(text, nullptr, args)) return;
    try {
      file = io::parse_problem_file(text, PotentialRegistry::with_builtins());
    } catch (const InvalidArgument& e) {  // name the file, then the key
      throw InvalidArgument(input_name(args.file) + ": " + e.name(),
                            std::string(e.what()).substr(e.name().size() + 2));
    }
    if (run_sparse(text, &file, args)) return;
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "fremond impact: error: %s\n", e.what());
    exit_with(kExitRefused);
  }
  const int indent = args.pretty ? 2 : -1;
  const std::string size = std::to_string(file.problem.contacts()) + " contacts, " +
                           std::to_string(file.problem.dofs()) + " dofs, " + file.law.describe();
  std::optional<Watchdog> watchdog;
  watchdog.emplace("fremond impact", size, args.time_limit, kExitTimeLimit);

  if (args.all_solutions) {
    const auto all = solve_impact_all(file.problem, file.law, options);
    watchdog.reset();
    print(io::solutions_to_json(all, indent));
    if (all.empty()) {
      std::fprintf(stderr, "fremond impact: the law has no solution for these data (%s)\n",
                   file.law.describe().c_str());
      exit_with(kExitNoSolution);
    }
    for (const auto& r : all)
      if (!r.ok()) {
        std::fprintf(stderr, "fremond impact: a solution did not converge (status %s: %s)\n",
                     std::string(to_string(r.solver.status)).c_str(),
                     std::string(r.solver.message).c_str());
        exit_with(kExitNotConverged);
      }
    for (const auto& r : all) report_inadmissible(r, args);
    return;
  }

  const auto result = solve_impact(file.problem, file.law, options);
  watchdog.reset();
  if (result.solver.status == SolverStatus::no_solution) {
    print(io::result_to_json(result, indent));
    std::fprintf(stderr, "fremond impact: the law has no solution for these data (%s)\n",
                 std::string(result.solver.message).c_str());
    exit_with(kExitNoSolution);
  }
  finish(result, args);
}

}  // namespace

void add_impact_command(CLI::App& app) {
  auto args = std::make_shared<ImpactArguments>();
  auto* cmd = app.add_subcommand(
      "impact", "Solve one impact problem (docs/problem-file.md) and print the result as JSON");
  cmd->add_option("FILE", args->file,
                  "The impact-problem file (JSON), a Siconos 2-D friction-contact file "
                  "(docs/sparse.md), or - for standard input")
      ->required();
  cmd->add_flag("--all-solutions", args->all_solutions,
                "Print every solution found: {\"count\": N, \"solutions\": [...]}");
  cmd->add_option("--method", args->method,
                  "Solver method: automatic, trivial, closed_form, scalar_newton, "
                  "mode_enumeration, lemke, semismooth_newton, proximal, nlopt, "
                  "impulse_integration, nsgs (Newton's law; a Siconos file's only method)")
      ->capture_default_str();
  cmd->add_option("--tolerance", args->tolerance,
                  "Relative tolerance on the law's residual, in [1e-16, 1e-2] (a Siconos file: "
                  "1e-10 unless given)")
      ->capture_default_str()
      ->each([args](const std::string&) { args->tolerance_given = true; });
  cmd->add_flag("--pretty", args->pretty, "Indent the JSON output");
  cmd->add_option("--time-limit", args->time_limit,
                  "Seconds the solve may take (0: no limit); past it, exit status 6 and nothing "
                  "on stdout. A note on stderr says the solve is still running after 1, 2, 4, "
                  "... s");
  cmd->add_flag("--require-admissible", args->require_admissible,
                "Exit with status 5 when the answer fails its admissibility certificate "
                "(inequalities 15-19; the result is printed anyway)");
  cmd->footer(
      "Exit status: 0 solved; 1 input refused (message on stderr naming the key, nothing on "
      "stdout); 2 the solver did not converge (the result is printed anyway, with its status); "
      "3 the law has no solution for these data (the result is printed, message on stderr); "
      "4 the result could not be written; 5 with --require-admissible, the answer is not "
      "admissible "
      "(a note on stderr says which inequality fails, with or without the flag); 6 no answer "
      "within --time-limit (nothing on stdout).");
  cmd->callback([args] { run(*args); });
}

}  // namespace fremond::cli
