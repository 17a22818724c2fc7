// `fremond predict DATA --law LAW`: what a law predicts for each measured impact, beside what was
// measured (docs/measurements.md#predict), as CSV.
//
// One header row and one row per measured component (impact, component, measured, predicted,
// sigma, residual, the impact's RMS, the solver's status), no comment lines, so that any CSV
// reader takes it as it is; the overall RMS goes to standard error. Exit status: 0 written; 1 a
// value or a file refused (the message names the option, or the row and key); 2 some impact did
// not converge (the rows are written anyway, with their status).
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/measured_input.hpp"
#include "cli/output.hpp"
#include "fremond/core/error.hpp"
#include "fremond/fit/law_family.hpp"
#include "fremond/fit/predict.hpp"
#include "fremond/io/problem_file.hpp"

namespace fremond::cli {

namespace {

constexpr int kExitRefused = 1;
constexpr int kExitNotConverged = 2;

struct PredictArguments {
  std::string file;
  std::string law;
  std::vector<std::string> params;
  std::string out;
  int threads = 0;
};

// --law is a law's JSON object (docs/problem-file.md, `law`) or a family's name with --params.
ImpactLaw law_of(const PredictArguments& a, int contacts) {
  const auto first = a.law.find_first_not_of(" \t\n");
  if (first != std::string::npos && a.law[first] == '{') {
    if (!a.params.empty())
      throw InvalidArgument("--params", "goes with a law's name; the JSON law holds its values");
    try {
      return io::parse_law(a.law, contacts, PotentialRegistry::with_builtins());
    } catch (const InvalidArgument& e) {
      throw InvalidArgument("--law", e.what());
    }
  }
  LawFamily family;
  try {
    family = law_family_from_string(a.law);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument("--law", std::string(e.what()).substr(e.name().size() + 2));
  }
  const auto values = named_values(a.params, "--params");
  try {
    return make_law(family, values);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument("--params", e.what());
  }
}

std::string csv_number(double v) {
  return std::isfinite(v) ? number17(v) : "";
}

void run(const PredictArguments& a) {
  bool all_converged = true;
  try {
    if (a.threads < 0)
      throw InvalidArgument(
          "--threads", "must be 0 (one per core) or at least 1, got " + std::to_string(a.threads));
    const std::vector<MeasuredImpact> impacts = read_measured(a.file);
    const ImpactLaw law = law_of(a, impacts.front().problem.contacts());
    BatchOptions batch;
    batch.threads = a.threads;
    const Prediction p = predict(impacts, law, fit_solver_options(), batch);
    std::ostringstream csv;
    csv << "impact,component,measured,predicted,sigma,residual,impact_rms,status\n";
    for (std::size_t i = 0; i < impacts.size(); ++i) {
      const MeasuredImpact& m = impacts[i];
      all_converged = all_converged && p.status[i] == SolverStatus::converged;
      double ss = 0.0;
      int count = 0;
      for (Eigen::Index j = 0; j < p.residuals[i].size(); ++j)
        if (std::isfinite(p.residuals[i](j))) ss += p.residuals[i](j) * p.residuals[i](j), ++count;
      const double impact_rms = count ? std::sqrt(ss / count) : std::nan("");
      for (std::size_t j = 0; j < m.mask.size(); ++j) {
        if (!m.mask[j]) continue;
        const auto k = static_cast<Eigen::Index>(j);
        csv << i << ',' << j << ',' << csv_number(m.qdot_E(k)) << ',' << csv_number(p.qdot_E[i](k))
            << ',' << csv_number(m.sigma(k)) << ',' << csv_number(p.residuals[i](k)) << ','
            << csv_number(impact_rms) << ',' << to_string(p.status[i]) << '\n';
      }
    }
    write_text(a.out, csv.str());
    std::fprintf(stderr,
                 "fremond predict: %s: RMS %.6g sigma over %d measured components of %zu "
                 "impacts%s%s\n",
                 law.describe().c_str(), p.rms, p.measured, impacts.size(),
                 p.failed ? ", failed solves: " : "",
                 p.failed ? std::to_string(p.failed).c_str() : "");
    if (!a.out.empty()) std::printf("wrote %s\n", a.out.c_str());
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "fremond predict: error: %s\n", e.what());
    throw CLI::RuntimeError(kExitRefused);
  }
  if (!all_converged) {
    std::fprintf(stderr, "fremond predict: some impacts did not converge (see 'status')\n");
    throw CLI::RuntimeError(kExitNotConverged);
  }
}

}  // namespace

void add_predict_command(CLI::App& app) {
  auto a = std::make_shared<PredictArguments>();
  auto* cmd = app.add_subcommand(
      "predict", "Each measured impact solved under a law: predicted beside measured, as CSV");
  cmd->add_option("DATA", a->file, "The measured-impact file (JSON), or - for standard input")
      ->required();
  cmd->add_option("--law", a->law,
                  "A law family's name (newton, poisson, newton_coulomb, poisson_coulomb, "
                  "stronge, stronge_coulomb, fremond, fremond_coulomb, fremond_deadzone) with "
                  "--params, or a law's JSON object as in the problem file")
      ->required();
  cmd->add_option("--params", a->params, "The family's parameters, e.g. e=0.9,mu=0.3")
      ->delimiter(',');
  cmd->add_option("--out", a->out, "Write the CSV to this file instead of standard output");
  cmd->add_option("--threads", a->threads, "Worker threads: 0 for one per core")
      ->capture_default_str();
  cmd->footer(
      "Exit status: 0 written; 1 a value or a file refused (the message names the option, or "
      "the row and key); 2 some impact did not converge (rows written anyway, with their "
      "status).");
  cmd->callback([a] { run(*a); });
}

}  // namespace fremond::cli
