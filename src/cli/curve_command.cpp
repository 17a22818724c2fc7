// `fremond curve normal|tangential`: the data of the paper's Figs. 8 and 9 as CSV, from the
// library's curves (include/fremond/curves/curves.hpp), in the library's scaling or the paper's
// (docs/laws.md).
//
// The CSV is one header row and one row per impact, with no comment lines, so that any CSV reader
// takes it as it is; the scaling and the parameters are columns of every row. Exit status: 0
// written; 1 a value refused (the message names the option, nothing is written); 2 some impact did
// not converge (the rows are written anyway, with their status).
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/output.hpp"
#include "fremond/core/error.hpp"
#include "fremond/curves/curves.hpp"

namespace fremond::cli {

namespace {

constexpr int kExitRefused = 1;
constexpr int kExitNotConverged = 2;

// What both curves share on the command line.
struct CommonArguments {
  std::string scaling = "library";
  double mass = 1.0;
  int points = 0;  // 0: the curve's default
  std::optional<double> max_speed;
  std::string out;  // empty: standard output
};

struct NormalArguments {
  CommonArguments common;
  std::vector<double> p{1.5, 2.0, 3.0, 4.0};
  std::optional<double> k;
};

struct TangentialArguments {
  CommonArguments common;
  std::optional<double> k_N, p, D_NA, k_T, q, r;
};

// The library names its parameters as the structs spell them; the user typed options.
InvalidArgument as_option(const InvalidArgument& e, const std::string& option) {
  return InvalidArgument(option, std::string(e.what()).substr(e.name().size() + 2));
}

Scaling parse_scaling(const std::string& text) {
  try {
    return scaling_from_string(text);
  } catch (const InvalidArgument& e) {
    throw as_option(e, "--scaling");
  }
}

std::vector<double> grid(double lo, double hi, int n) {
  std::vector<double> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v[i] = lo + (hi - lo) * static_cast<double>(i) / (n - 1);
  v.back() = hi;
  return v;
}

void check_common(const CommonArguments& a, int default_points, double default_max, int& points,
                  double& max_speed) {
  points = a.points == 0 ? default_points : a.points;
  if (points < 2 || points > 1000000)
    throw InvalidArgument("--points", "must lie in [2, 1000000], got " + std::to_string(points));
  max_speed = a.max_speed.value_or(default_max);
  if (!std::isfinite(max_speed) || !(max_speed > 0.0))
    throw InvalidArgument("--max-speed", "must be a finite number > 0, got " + number17(max_speed));
}

// Runs `body`, turning a refusal into exit status 1 with the message on stderr.
template <class F>
void refusing(const char* command, F&& body) {
  try {
    body();
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "fremond curve %s: error: %s\n", command, e.what());
    exit_with(kExitRefused);
  }
}

// Writes to --out (complete or absent: a temporary file and a rename) or to standard output;
// throws InvalidArgument naming what could not be written.
void write_output(const CommonArguments& a, const std::string& text, const std::string& what) {
  if (a.out.empty()) {
    if (!write_stdout(text))
      throw InvalidArgument("standard output", std::string("cannot write the curve: ") +
                                                   (errno ? std::strerror(errno) : "write failed"));
    return;
  }
  const std::filesystem::path out(a.out);
  const std::filesystem::path dir = out.has_parent_path() ? out.parent_path() : ".";
  try {
    write_atomically(dir, out.filename().string(), text);
  } catch (const InvalidArgument& e) {
    const std::string why = e.what();
    throw InvalidArgument(
        "--out", "cannot write '" + a.out + "'" + why.substr(why.find(": cannot write") + 14));
  }
  std::printf("wrote %s: %s\n", a.out.c_str(), what.c_str());
}

void run_normal(const NormalArguments& a) {
  std::ostringstream csv;
  std::string summary;
  bool all_converged = true;
  refusing("normal", [&] {
    const Scaling scaling = parse_scaling(a.common.scaling);
    int points = 0;
    double max_speed = 0.0;
    check_common(a.common, 101, 5.0, points, max_speed);
    if (a.p.empty()) throw InvalidArgument("--p", "needs at least one exponent");
    const std::vector<double> speeds = grid(0.0, max_speed, points);

    std::ostringstream rows;
    std::string constants;
    for (std::size_t i = 0; i < a.p.size(); ++i) {
      NormalCurveParameters par;
      par.mass = a.common.mass;
      par.p = a.p[i];
      par.scaling = scaling;
      // Without --k: the library's default k (4 in the library's scaling, ε = 1/3 at p = 2 by eq.
      // 24) for every p, written in the chosen scaling.
      if (a.k) {
        par.k = *a.k;
      } else {
        NormalCurveParameters spec;
        spec.p = par.p;
        par.k = scaling == Scaling::library ? spec.k : spec.in_paper_scaling().k;
      }
      std::vector<CurvePoint> curve;
      try {
        curve = normal_restitution_curve(par, speeds);
      } catch (const InvalidArgument& e) {
        if (e.name() == "mass") throw as_option(e, "--mass");
        if (e.name() == "k") throw as_option(e, "--k");
        if (e.name() == "p") throw as_option(e, "--p");
        throw;
      }
      const NormalCurveParameters s = par.in_library_scaling(), pp = par.in_paper_scaling();
      constants += "; p = " + brief(par.p) + ": k = " + brief(s.k) + " (library) = " + brief(pp.k) +
                   " (paper)";
      for (const CurvePoint& pt : curve) {
        all_converged = all_converged && pt.status == SolverStatus::converged;
        rows << to_string(scaling) << ',' << number17(par.p) << ',' << number17(par.k) << ','
             << number17(std::fabs(pt.D_NA)) << ',' << number17(pt.D_NA) << ',' << number17(pt.D_NE)
             << ',' << number17(pt.P_N) << ',' << number17(pt.P_N_reaction) << ','
             << number17(pt.energy_change) << ',' << (pt.admissible ? 1 : 0) << ','
             << to_string(pt.failed) << ',' << to_string(pt.status) << '\n';
      }
    }
    csv << "scaling,p,k,abs_D_NA,D_NA,D_NE,P_N,P_N_reaction,energy_change,admissible,failed,"
           "status\n"
        << rows.str();
    summary = "Fig. 8 data, " + std::to_string(a.p.size()) + " exponent(s) x " +
              std::to_string(points) + " speeds, " + std::string(to_string(scaling)) + " scaling" +
              constants;
    write_output(a.common, csv.str(), summary);
  });
  if (!all_converged) {
    std::fprintf(stderr, "fremond curve normal: some impacts did not converge (see 'status')\n");
    exit_with(kExitNotConverged);
  }
}

void run_tangential(const TangentialArguments& a) {
  bool all_converged = true;
  refusing("tangential", [&] {
    const Scaling scaling = parse_scaling(a.common.scaling);
    int points = 0;
    double max_speed = 0.0;
    check_common(a.common, 201, 1.0, points, max_speed);
    // Defaults: the paper's Fig. 9 (with the exponents given), written in the chosen scaling, so
    // that leaving a stiffness out means the same law in either scaling.
    TangentialCurveParameters spec = TangentialCurveParameters::paper_figure(Scaling::library);
    spec.mass = a.common.mass;
    if (a.p) spec.p = *a.p;
    if (a.q) spec.q = *a.q;
    TangentialCurveParameters par = scaling == Scaling::library ? spec : spec.in_paper_scaling();
    if (a.k_N) par.k_N = *a.k_N;
    if (a.D_NA) par.D_NA = *a.D_NA;
    if (a.k_T) par.k_T = *a.k_T;
    if (a.r) par.r = *a.r;
    std::vector<CurvePoint> curve;
    try {
      curve = tangential_curve(par, grid(-max_speed, max_speed, points));
    } catch (const InvalidArgument& e) {
      static const std::pair<const char*, const char*> kOptions[] = {
          {"mass", "--mass"}, {"k_N", "--k"}, {"p", "--p"}, {"D_NA", "--dna"},
          {"k_T", "--kt"},    {"q", "--q"},   {"r", "--r"}};
      for (const auto& [name, option] : kOptions)
        if (e.name() == name) throw as_option(e, option);
      throw;
    }
    const TangentialCurveParameters s = par.in_library_scaling(), pp = par.in_paper_scaling();
    std::ostringstream csv;
    const std::string constants = "k_T = " + brief(s.k_T) + ", q = " + brief(s.q) +
                                  ", r = " + brief(s.r) + ", k = " + brief(s.k_N) +
                                  " (library) = k_T " + brief(pp.k_T) + ", r " + brief(pp.r) +
                                  ", k " + brief(pp.k_N) + " (paper)";
    csv << "scaling,k_T,q,r,k,p,D_TA,D_TE,P_T,D_NA,D_NE,P_N,in_dead_zone,energy_change,admissible,"
           "failed,status\n";
    for (const CurvePoint& pt : curve) {
      all_converged = all_converged && pt.status == SolverStatus::converged;
      csv << to_string(scaling) << ',' << number17(par.k_T) << ',' << number17(par.q) << ','
          << number17(par.r) << ',' << number17(par.k_N) << ',' << number17(par.p) << ','
          << number17(pt.D_TA) << ',' << number17(pt.D_TE) << ',' << number17(pt.P_T) << ','
          << number17(pt.D_NA) << ',' << number17(pt.D_NE) << ',' << number17(pt.P_N) << ','
          << (pt.in_dead_zone ? 1 : 0) << ',' << number17(pt.energy_change) << ','
          << (pt.admissible ? 1 : 0) << ',' << to_string(pt.failed) << ',' << to_string(pt.status)
          << '\n';
    }
    write_output(a.common, csv.str(),
                 "Fig. 9 data, " + std::to_string(points) + " points, " +
                     std::string(to_string(scaling)) + " scaling; " + constants);
  });
  if (!all_converged) {
    std::fprintf(stderr,
                 "fremond curve tangential: some impacts did not converge (see 'status')\n");
    exit_with(kExitNotConverged);
  }
}

void add_common(CLI::App* cmd, CommonArguments& a, const char* points_help,
                const char* max_speed_help) {
  cmd->add_option("--scaling", a.scaling,
                  "Scaling of k, k_T, r: library (potentials of the mean velocity) or paper "
                  "(k_paper = k 2^(1-p), k_T,paper = k_T 2^(1-q), r_paper = 2 r; docs/laws.md)")
      ->capture_default_str();
  cmd->add_option("--mass", a.mass, "Mass of the point (kg), > 0")->capture_default_str();
  cmd->add_option("--points", a.points, points_help);
  cmd->add_option("--max-speed", a.max_speed, max_speed_help);
  cmd->add_option("--out", a.out, "Write the CSV to this file instead of standard output");
}

}  // namespace

void add_curve_command(CLI::App& app) {
  auto* curve = app.add_subcommand(
      "curve", "Write the data of the paper's Figs. 8 (normal) and 9 (tangential) as CSV");
  curve->require_subcommand(1);
  curve->footer(
      "Exit status: 0 written; 1 a value refused (the message names the option); 2 some impact "
      "did not converge (rows written anyway, with their status).");

  auto na = std::make_shared<NormalArguments>();
  auto* normal = curve->add_subcommand(
      "normal", "Fig. 8: D_NE against |D_NA| for several p (point mass, normal law alone)");
  normal->add_option("--p", na->p, "Exponents p > 1 of phi_N = k|z|^p/p (comma-separated)")
      ->delimiter(',')
      ->capture_default_str();
  normal->add_option("--k", na->k,
                     "Stiffness k >= 0 in the chosen scaling (default: 4 in the library's scaling, "
                     "i.e. restitution 1/3 for p = 2 by eq. 24)");
  add_common(normal, na->common, "Speeds per exponent, in [2, 1000000] (default 101)",
             "Largest |D_NA| (m/s), > 0; the speeds run from 0 (default 5)");
  normal->callback([na] { run_normal(*na); });

  auto ta = std::make_shared<TangentialArguments>();
  auto* tangential = curve->add_subcommand(
      "tangential", "Fig. 9: D_TE against D_TA, viscous dead zone (point mass, normal law fixed)");
  tangential->add_option(
      "--kt", ta->k_T,
      "Tangential stiffness k_T >= 0 (default: the paper's 0.75, the library's 1.5)");
  tangential->add_option("--q", ta->q, "Tangential exponent q > 1 (default 2)");
  tangential->add_option(
      "--r", ta->r, "Dead-zone half-width r >= 0 (default: the paper's 0.4, the library's 0.2)");
  tangential->add_option("--k", ta->k_N,
                         "Normal stiffness k >= 0 (default: 4 in the library's scaling)");
  tangential->add_option("--p", ta->p, "Normal exponent p > 1 (default 2)");
  tangential->add_option("--dna", ta->D_NA,
                         "Normal velocity before the impact D_NA <= 0 (m/s, default -1)");
  add_common(tangential, ta->common, "Points on the curve, in [2, 1000000] (default 201)",
             "Largest |D_TA| (m/s), > 0; D_TA runs from -max to +max (default 1)");
  tangential->callback([ta] { run_tangential(*ta); });
}

}  // namespace fremond::cli
