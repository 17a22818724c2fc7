// `fremond impact FILE|-` (SPEC §7): reads one impact problem, solves it, prints the result as
// JSON.
//
// Exit status: 0 solved; 1 input refused (the message names the key; nothing on stdout); 2 the
// solver did not converge (the result is printed anyway, so the status can be seen); 3 the law has
// no solution for these data (SPEC §2; the result is printed, with a message on stderr); 4 the
// result could not be written to standard output (message on stderr).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>

#include "commands.hpp"
#include "fremond/core/error.hpp"
#include "fremond/io/problem_file.hpp"
#include "fremond/potentials/registry.hpp"
#include "fremond/solvers/solve_impact.hpp"
#include "output.hpp"

namespace fremond::cli {

namespace {

constexpr int kExitRefused = 1;
constexpr int kExitNotConverged = 2;
constexpr int kExitNoSolution = 3;
constexpr int kExitWriteFailed = 4;

struct ImpactArguments {
  std::string file;
  bool all_solutions = false;
  std::string method = "automatic";
  double tolerance = SolverOptions{}.tolerance;
  bool pretty = false;
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
  std::string why;
  if (!options.is_valid(&why))
    throw InvalidArgument("--" + why.substr(0, why.find(':')), why.substr(why.find(':') + 2));
  return options;
}

[[noreturn]] void exit_with(int code) {
  throw CLI::RuntimeError(code);
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

void run(const ImpactArguments& args) {
  io::ProblemFile file;
  SolverOptions options;
  try {
    options = solver_options(args);
    const std::string text = read_input(args.file);
    try {
      file = io::parse_problem_file(text, PotentialRegistry::with_builtins());
    } catch (const InvalidArgument& e) {  // name the file, then the key
      throw InvalidArgument(input_name(args.file) + ": " + e.name(),
                            std::string(e.what()).substr(e.name().size() + 2));
    }
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "fremond impact: error: %s\n", e.what());
    exit_with(kExitRefused);
  }
  const int indent = args.pretty ? 2 : -1;

  if (args.all_solutions) {
    const auto all = solve_impact_all(file.problem, file.law, options);
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
    return;
  }

  const auto result = solve_impact(file.problem, file.law, options);
  print(io::result_to_json(result, indent));
  if (result.solver.status == SolverStatus::no_solution) {
    std::fprintf(stderr, "fremond impact: the law has no solution for these data (%s)\n",
                 std::string(result.solver.message).c_str());
    exit_with(kExitNoSolution);
  }
  if (!result.ok()) {
    std::fprintf(stderr, "fremond impact: the solver did not converge (status %s: %s)\n",
                 std::string(to_string(result.solver.status)).c_str(),
                 std::string(result.solver.message).c_str());
    exit_with(kExitNotConverged);
  }
}

}  // namespace

void add_impact_command(CLI::App& app) {
  auto args = std::make_shared<ImpactArguments>();
  auto* cmd = app.add_subcommand("impact",
                                 "Solve one impact problem (SPEC §7) and print the result as JSON");
  cmd->add_option("FILE", args->file, "The impact-problem file (JSON), or - for standard input")
      ->required();
  cmd->add_flag("--all-solutions", args->all_solutions,
                "Print every solution found: {\"count\": N, \"solutions\": [...]}");
  cmd->add_option("--method", args->method,
                  "Solver method: automatic, trivial, closed_form, scalar_newton, "
                  "mode_enumeration, lemke, semismooth_newton, proximal, nlopt")
      ->capture_default_str();
  cmd->add_option("--tolerance", args->tolerance,
                  "Relative tolerance on the law's residual, in [1e-16, 1e-2]")
      ->capture_default_str();
  cmd->add_flag("--pretty", args->pretty, "Indent the JSON output");
  cmd->footer(
      "Exit status: 0 solved; 1 input refused (message on stderr naming the key, nothing on "
      "stdout); 2 the solver did not converge (the result is printed anyway, with its status); "
      "3 the law has no solution for these data (the result is printed, message on stderr); "
      "4 the result could not be written.");
  cmd->callback([args] { run(*args); });
}

}  // namespace fremond::cli
