// `fremond fit DATA --law NAMES`: law families fitted to measured impacts and ranked by their
// cross-validated error (docs/measurements.md#fit).
//
// The table (or with --json, a JSON array) lists the laws best first: parameters with their
// uncertainties, the training and held-out RMS in sigmas, NLopt's status and the evaluations.
// Exit status: 0 written; 1 a value or a file refused (the message names the option, or the row
// and key).
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/measured_input.hpp"
#include "cli/output.hpp"
#include "fremond/core/error.hpp"
#include "fremond/fit/fit_law.hpp"
#include "io/detail/json_number.hpp"

namespace fremond::cli {

namespace {

constexpr int kExitRefused = 1;

struct FitArguments {
  std::string file;
  std::vector<std::string> laws;
  std::string loss = "least_squares";
  double loss_scale = 1.0;
  std::string uncertainty = "gauss_newton";
  int bootstrap_samples = FitOptions{}.bootstrap_samples;
  bool absolute_sigma = false;
  int folds = FitOptions{}.folds;
  std::uint64_t seed = FitOptions{}.seed;
  int global_evaluations = FitOptions{}.global_evaluations;
  int local_evaluations = FitOptions{}.local_evaluations;
  std::vector<std::string> fix;
  std::vector<std::string> bounds;
  int threads = 0;
  bool json = false;
  std::string out;
};

// The library names its options as FitOptions spells them; the user typed these.
const std::pair<const char*, const char*> kOptionNames[] = {
    {"loss", "--loss"},
    {"loss_scale", "--loss-scale"},
    {"uncertainty", "--uncertainty"},
    {"bootstrap_samples", "--bootstrap-samples"},
    {"folds", "--folds"},
    {"global_evaluations", "--global-evaluations"},
    {"local_evaluations", "--local-evaluations"},
    {"threads", "--threads"}};

InvalidArgument as_option(const InvalidArgument& e) {
  const std::string reason = std::string(e.what()).substr(e.name().size() + 2);
  for (const auto& [name, option] : kOptionNames)
    if (e.name() == name) return InvalidArgument(option, reason);
  if (e.name().rfind("fixed.", 0) == 0) return InvalidArgument("--fix", e.what());
  if (e.name().rfind("bounds.", 0) == 0) return InvalidArgument("--bounds", e.what());
  return e;
}

FitOptions options_of(const FitArguments& a) {
  FitOptions o;
  try {
    o.loss = fit_loss_from_string(a.loss);
    o.uncertainty = fit_uncertainty_from_string(a.uncertainty);
  } catch (const InvalidArgument& e) {
    throw as_option(e);
  }
  o.loss_scale = a.loss_scale;
  o.bootstrap_samples = a.bootstrap_samples;
  o.absolute_sigma = a.absolute_sigma;
  o.folds = a.folds;
  o.seed = a.seed;
  o.global_evaluations = a.global_evaluations;
  o.local_evaluations = a.local_evaluations;
  o.fixed = named_values(a.fix, "--fix");
  for (const std::string& item : a.bounds) {
    // NAME=LOWER:UPPER
    const auto eq = item.find('='), colon = item.find(':', eq == std::string::npos ? 0 : eq);
    if (eq == std::string::npos || colon == std::string::npos)
      throw InvalidArgument("--bounds", "expects NAME=LOWER:UPPER, got '" + item + "'");
    const auto lo = named_values({item.substr(0, colon)}, "--bounds");
    const auto hi = named_values({item.substr(0, eq) + "=" + item.substr(colon + 1)}, "--bounds");
    o.bounds[lo.begin()->first] = {lo.begin()->second, hi.begin()->second};
  }
  o.batch.threads = a.threads;
  try {
    o.validate();
  } catch (const InvalidArgument& e) {
    throw as_option(e);
  }
  return o;
}

std::vector<LawFamily> families_of(const FitArguments& a) {
  std::vector<LawFamily> out;
  for (const std::string& name : a.laws) {
    if (name == "all") {
      for (const LawFamily f : law_families()) out.push_back(f);
      continue;
    }
    try {
      out.push_back(law_family_from_string(name));
    } catch (const InvalidArgument& e) {
      throw InvalidArgument("--law", std::string(e.what()).substr(e.name().size() + 2));
    }
  }
  return out;
}

using io::detail::json_number;

std::string as_json(const std::vector<FitResult>& results) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  int rank = 0;
  for (const FitResult& r : results) {
    nlohmann::ordered_json j;
    j["rank"] = ++rank;
    j["law"] = std::string(to_string(r.family));
    j["describe"] = r.law.describe();
    nlohmann::ordered_json values, sd;
    for (std::size_t i = 0; i < r.names.size(); ++i) {
      values[r.names[i]] = json_number(r.values(static_cast<Eigen::Index>(i)));
      sd[r.names[i]] = json_number(r.uncertainties(static_cast<Eigen::Index>(i)));
    }
    j["parameters"] = values.is_null() ? nlohmann::ordered_json::object() : values;
    j["uncertainties"] = sd.is_null() ? nlohmann::ordered_json::object() : sd;
    j["training_rms"] = json_number(r.training_rms);
    j["heldout_rms"] = json_number(r.heldout_rms);
    j["objective"] = json_number(r.objective);
    j["measured"] = r.measured;
    j["failed_solves"] = r.failed_solves;
    j["global_status"] = r.global_status;
    j["local_status"] = r.local_status;
    j["status"] = r.status;
    j["evaluations"] = r.evaluations;
    j["fold_evaluations"] = r.fold_evaluations;
    j["seconds"] = json_number(r.seconds);
    all.push_back(j);
  }
  return all.dump(2) + "\n";
}

std::string as_table(const std::vector<FitResult>& results, const FitOptions& o) {
  std::ostringstream t;
  char line[512];
  std::snprintf(line, sizeof line, "%-4s %-17s %-12s %-12s %-7s %s\n", "rank", "law", "train_rms",
                "heldout_rms", "evals", "parameters (± 1 sd)");
  t << line;
  int rank = 0;
  for (const FitResult& r : results) {
    std::string params;
    for (std::size_t i = 0; i < r.names.size(); ++i)
      params += (i ? ", " : "") + r.names[i] + " = " +
                brief(r.values(static_cast<Eigen::Index>(i))) + " ± " +
                brief(r.uncertainties(static_cast<Eigen::Index>(i)));
    // No held-out error without folds: a dash, not "nan".
    const std::string heldout = std::isfinite(r.heldout_rms) ? brief(r.heldout_rms) : "-";
    std::snprintf(line, sizeof line, "%-4d %-17s %-12s %-12s %-7d %s [%s]\n", ++rank,
                  std::string(to_string(r.family)).c_str(), brief(r.training_rms).c_str(),
                  heldout.c_str(), r.evaluations, params.c_str(), r.status.c_str());
    t << line;
  }
  t << "RMS in sigmas over " << (results.empty() ? 0 : results[0].measured)
    << " measured components; held-out: ";
  if (o.folds >= 2)
    t << o.folds << "-fold cross-validation, seed " << o.seed;
  else
    t << "none (--folds 0; ranked by training RMS)";
  t << "; uncertainties: " << to_string(o.uncertainty) << "\n";
  return t.str();
}

void run(const FitArguments& a) {
  try {
    const FitOptions o = options_of(a);
    const std::vector<LawFamily> families = families_of(a);
    const std::vector<MeasuredImpact> impacts = read_measured(a.file);
    const std::vector<FitResult> results = fit_laws(impacts, families, o);
    write_text(a.out, a.json ? as_json(results) : as_table(results, o));
    if (!a.out.empty()) std::printf("wrote %s\n", a.out.c_str());
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "fremond fit: error: %s\n", as_option(e).what());
    throw CLI::RuntimeError(kExitRefused);
  }
}

}  // namespace

void add_fit_command(CLI::App& app) {
  auto a = std::make_shared<FitArguments>();
  auto* cmd = app.add_subcommand(
      "fit", "Fit law families to measured impacts and rank them by cross-validated error");
  cmd->add_option("DATA", a->file, "The measured-impact file (JSON), or - for standard input")
      ->required();
  cmd->add_option("--law", a->laws,
                  "Law families, comma-separated, or 'all': newton, poisson, newton_coulomb, "
                  "poisson_coulomb, stronge, stronge_coulomb, fremond, fremond_coulomb, "
                  "fremond_deadzone")
      ->delimiter(',')
      ->required();
  cmd->add_option("--loss", a->loss, "least_squares, huber or soft_l1")->capture_default_str();
  cmd->add_option("--loss-scale", a->loss_scale, "Where Huber and soft-L1 turn linear, in sigmas")
      ->capture_default_str();
  cmd->add_option("--uncertainty", a->uncertainty, "gauss_newton or bootstrap")
      ->capture_default_str();
  cmd->add_option("--bootstrap-samples", a->bootstrap_samples, "Resamples of the bootstrap")
      ->capture_default_str();
  cmd->add_flag("--absolute-sigma", a->absolute_sigma,
                "Trust the sigmas as the true uncertainties (Gauss-Newton without rescaling)");
  cmd->add_option("--folds", a->folds, "k of k-fold cross-validation; 0: none")
      ->capture_default_str();
  cmd->add_option("--seed", a->seed, "Seed of the folds and the bootstrap")->capture_default_str();
  cmd->add_option("--global-evaluations", a->global_evaluations,
                  "Evaluations of the global stage (GN_DIRECT_L); 0 skips it")
      ->capture_default_str();
  cmd->add_option("--local-evaluations", a->local_evaluations,
                  "Evaluations of the local polish (LN_BOBYQA)")
      ->capture_default_str();
  cmd->add_option("--fix", a->fix, "Hold parameters, e.g. p=2,q=2 (comma-separated)")
      ->delimiter(',');
  cmd->add_option("--bounds", a->bounds, "Search intervals, e.g. mu=0:0.5 (comma-separated)")
      ->delimiter(',');
  cmd->add_option("--threads", a->threads, "Worker threads: 0 for one per core")
      ->capture_default_str();
  cmd->add_flag("--json", a->json, "Write the results as a JSON array instead of a table");
  cmd->add_option("--out", a->out, "Write to this file instead of standard output");
  cmd->footer(
      "Exit status: 0 written; 1 a value or a file refused (the message names the option, or "
      "the row and key).");
  cmd->callback([a] { run(*a); });
}

}  // namespace fremond::cli
