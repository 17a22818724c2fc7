// `fremond atlas`: the law atlas of a scene (include/fremond/atlas/atlas.hpp, docs/atlas.md) as CSV
// and NPZ files, each complete or absent.
//
// Every value is checked before the sweep starts, the output folders too, so that a refusal never
// comes after minutes of solving. Exit status: 0 written (points that did not converge are in the
// files with their status, and counted on standard output); 1 a value refused or a file that
// could not be written (the message names the option; nothing is written).
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "cli/commands.hpp"
#include "cli/output.hpp"
#include "fremond/admissibility/admissibility_report.hpp"
#include "fremond/atlas/atlas.hpp"
#include "fremond/core/error.hpp"
#include "fremond/io/atlas_file.hpp"
#include "fremond/io/scene_file.hpp"
#include "fremond/scenes/presets.hpp"
#include "fremond/solvers/solver_status.hpp"

namespace fremond::cli {

namespace {

constexpr int kExitRefused = 1;
// Sweeps with at least this many points say how far they are on standard error.
constexpr std::size_t kProgressFrom = 100000;

struct AtlasArguments {
  std::string preset = "paper-bar";
  std::string scene_file;
  std::vector<std::string> laws{"newton_coulomb", "poisson_coulomb", "fremond", "stronge_coulomb"};
  std::string reference;
  std::vector<double> mu{1.0}, e{0.9};
  double k_N = 0.0, p = 3.0;
  int contact = -1;
  double speed = 0.0;
  std::vector<double> spins{0.0};
  std::string grid = "200x200";
  std::vector<double> theta, psi;
  int threads = 0;
  std::string csv, npz;
  bool no_progress = false;
};

// The library names the options as AtlasOptions spells them; the user typed flags.
InvalidArgument as_flag(const InvalidArgument& e, bool sweeps_e) {
  static const std::pair<const char*, const char*> kFlags[] = {
      {"laws", "--laws"},       {"reference", "--reference"}, {"e", "--e"},
      {"mu", "--mu"},           {"fremond_p", "--p"},         {"fremond_k_N", "--k-n"},
      {"contact", "--contact"}, {"theta_count", "--grid"},    {"psi_count", "--grid"},
      {"theta_min", "--theta"}, {"theta_max", "--theta"},     {"psi_min", "--psi"},
      {"psi_max", "--psi"},     {"spins", "--spin"},          {"speed", "--speed"},
      {"threads", "--threads"}, {"values", nullptr}};
  const std::string name = e.name().substr(0, e.name().find('['));
  const std::string reason = std::string(e.what()).substr(e.name().size() + 2);
  for (const auto& [key, flag] : kFlags)
    if (name == key) return InvalidArgument(flag ? flag : (sweeps_e ? "--e" : "--mu"), reason);
  return e;
}

// "200x300" (θ × ψ) or "200" (both).
void parse_grid(const std::string& text, int& nt, int& np) {
  const auto cells = [&](const std::string& part) {
    std::size_t used = 0;
    long v = 0;
    try {
      v = std::stol(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != part.size() || part.empty() || v < 1 || v > 100000)
      throw InvalidArgument("--grid",
                            "needs N or NxM with cell counts in [1, 100000], got '" + text + "'");
    return static_cast<int>(v);
  };
  const std::size_t x = text.find('x');
  nt = cells(text.substr(0, x));
  np = x == std::string::npos ? nt : cells(text.substr(x + 1));
}

Scene load_scene(const AtlasArguments& a) {
  if (!a.scene_file.empty())
    return io::read_scene_file(a.scene_file, PotentialRegistry::with_builtins()).scene;
  // The scene's own law is not used: the atlas names its laws.
  const ImpactLaw law = ImpactLaw::newton(PaperConstants::e);
  if (a.preset == "paper-bar") return bar_scene(BarParameters{}, law);
  if (a.preset == "ball") return ball_scene(BallParameters{}, law);
  if (a.preset == "block") return block_scene(BlockParameters{}, law);
  throw InvalidArgument("--preset",
                        "unknown preset '" + a.preset + "' (one of: paper-bar, ball, block)");
}

// A file's folder must exist before the sweep: the files are written after it.
void check_writable(const std::string& path, const char* flag) {
  const std::filesystem::path p(path);
  const std::filesystem::path dir = p.has_parent_path() ? p.parent_path() : ".";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw InvalidArgument(flag,
                          "cannot write '" + path + "': no such folder '" + dir.string() + "'");
  if (p.filename().empty() || std::filesystem::is_directory(p, ec))
    throw InvalidArgument(flag, "cannot write '" + path + "': it names a folder");
}

void write_file(const std::string& path, const std::string& bytes, const char* flag) {
  const std::filesystem::path p(path);
  try {
    write_atomically(p.has_parent_path() ? p.parent_path() : ".", p.filename().string(), bytes);
  } catch (const InvalidArgument& e) {
    const std::string why = e.what();
    throw InvalidArgument(
        flag, "cannot write '" + path + "'" + why.substr(why.find(": cannot write") + 14));
  }
}

// Progress on standard error: a line redrawn on a terminal, else a line every tenth.
class Progress {
 public:
  explicit Progress(bool on) : on_(on), terminal_(::isatty(STDERR_FILENO) == 1) {}
  void operator()(std::size_t done, std::size_t total) {
    if (!on_) return;
    const int tenth = static_cast<int>(10 * done / total);
    if (terminal_) {
      std::fprintf(stderr, "\rfremond atlas: %zu / %zu points (%d%%)", done, total,
                   static_cast<int>(100 * done / total));
      if (done == total) std::fputc('\n', stderr);
    } else if (tenth > last_) {
      std::fprintf(stderr, "fremond atlas: %zu / %zu points (%d%%)\n", done, total, 10 * tenth);
      last_ = tenth;
    }
    std::fflush(stderr);
  }

 private:
  bool on_, terminal_;
  int last_ = 0;
};

void run(const AtlasArguments& a) {
  try {
    if (a.csv.empty() && a.npz.empty())
      throw InvalidArgument("--csv", "give --csv FILE and/or --npz FILE: the atlas goes there");
    if (a.mu.size() > 1 && a.e.size() > 1)
      throw InvalidArgument("--e", "sweep μ or e, not both: give one of --mu, --e a single value");
    if (a.mu.empty()) throw InvalidArgument("--mu", "needs a value");
    if (a.e.empty()) throw InvalidArgument("--e", "needs a value");
    const bool sweeps_e = a.e.size() > 1;
    AtlasOptions o;
    o.laws = a.laws;
    o.reference = a.reference;
    o.parameter = sweeps_e ? AtlasParameter::e : AtlasParameter::mu;
    o.values = sweeps_e ? a.e : a.mu;
    o.e = a.e.front();
    o.mu = a.mu.front();
    o.fremond_k_N = a.k_N;
    o.fremond_p = a.p;
    o.contact = a.contact;
    o.speed = a.speed;
    o.spins = a.spins;
    o.threads = a.threads;
    parse_grid(a.grid, o.theta_count, o.psi_count);
    for (auto [range, lo, hi, flag] : {std::tuple{&a.theta, &o.theta_min, &o.theta_max, "--theta"},
                                       std::tuple{&a.psi, &o.psi_min, &o.psi_max, "--psi"}}) {
      if (range->empty()) continue;
      if (range->size() != 2)
        throw InvalidArgument(
            flag, "needs MIN,MAX (radians), got " + std::to_string(range->size()) + " values");
      *lo = (*range)[0];
      *hi = (*range)[1];
    }
    try {
      o.validate();
    } catch (const InvalidArgument& e) {
      throw as_flag(e, sweeps_e);
    }
    if (!a.csv.empty()) check_writable(a.csv, "--csv");
    if (!a.npz.empty()) check_writable(a.npz, "--npz");
    const Scene scene = load_scene(a);

    const std::size_t points = o.laws.size() * o.values.size() * o.spins.size() *
                               static_cast<std::size_t>(o.theta_count) *
                               static_cast<std::size_t>(o.psi_count);
    auto progress = std::make_shared<Progress>(!a.no_progress && points >= kProgressFrom);
    o.progress = [progress](std::size_t done, std::size_t total) { (*progress)(done, total); };
    const auto t0 = std::chrono::steady_clock::now();
    AtlasResult r;
    try {
      r = law_atlas(scene, o);
    } catch (const InvalidArgument& e) {
      throw as_flag(e, sweeps_e);
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    // Both files or neither: the second's failure removes the first.
    if (!a.npz.empty()) write_file(a.npz, io::atlas_npz(r), "--npz");
    if (!a.csv.empty()) {
      try {
        write_file(a.csv, io::atlas_csv(r), "--csv");
      } catch (const InvalidArgument&) {
        if (!a.npz.empty()) std::filesystem::remove(a.npz);
        throw;
      }
    }

    std::string summary;
    std::size_t unconverged = 0;
    const std::size_t per_law = r.values.size() * r.configurations();
    for (std::size_t l = 0; l < r.laws.size(); ++l) {
      std::size_t created = 0, solved = 0;
      for (std::size_t p = l * per_law; p < (l + 1) * per_law; ++p) {
        if (static_cast<SolverStatus>(r.status[p]) != SolverStatus::converged) {
          ++unconverged;
          continue;
        }
        ++solved;
        created += r.failed[p] == static_cast<std::uint8_t>(Inequality::total_15);
      }
      char buf[160];
      std::snprintf(
          buf, sizeof buf, "  %s creates energy on %.2f%% of its solved points\n",
          r.laws[l].c_str(),
          solved ? 100.0 * static_cast<double>(created) / static_cast<double>(solved) : 0.0);
      summary += buf;
    }
    std::printf(
        "wrote %s%s%s: %zu laws x %zu %s x %zu spins x %zux%zu configurations (%zu points) "
        "in %.2f s, contact %d at %.6g m/s\n%s",
        a.npz.c_str(), (!a.npz.empty() && !a.csv.empty()) ? " and " : "", a.csv.c_str(),
        r.laws.size(), r.values.size(), std::string(to_string(r.parameter)).c_str(), r.spins.size(),
        r.theta.size(), r.psi.size(), r.points(), seconds, r.contact, r.speed, summary.c_str());
    if (unconverged > 0)
      std::printf("  %zu points did not converge (their status is in the files)\n", unconverged);
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "fremond atlas: error: %s\n", e.what());
    exit_with(kExitRefused);
  }
}

}  // namespace

void add_atlas_command(CLI::App& app) {
  auto a = std::make_shared<AtlasArguments>();
  auto* cmd = app.add_subcommand(
      "atlas", "Map where each law creates energy over a scene's impact configurations (CSV, NPZ)");
  cmd->footer(
      "Exit status: 0 written; 1 a value refused or a file that could not be written (the "
      "message names the option; nothing is written). docs/atlas.md describes the columns.");
  auto* preset = cmd->add_option("--preset", a->preset, "Scene: paper-bar, ball or block")
                     ->capture_default_str();
  cmd->add_option("--scene", a->scene_file, "A scene file instead of a preset (its law unused)")
      ->excludes(preset);
  cmd->add_option("--laws", a->laws,
                  "Laws, comma-separated: newton, poisson, newton_coulomb, poisson_coulomb, "
                  "fremond (power law + Coulomb on the mean velocity), stronge, stronge_coulomb")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--reference", a->reference,
                  "The law the others' distance is measured from (default: the first)");
  cmd->add_option("--mu", a->mu, "Coulomb's mu, >= 0; a list sweeps it (comma-separated)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--e", a->e, "Restitution e in [0, 1]; a list sweeps it (comma-separated)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--k-n", a->k_N,
                  "Fremond's normal stiffness k_N >= 0; 0 calibrates it to e at the scene's first "
                  "impact, as the paper's")
      ->capture_default_str();
  cmd->add_option("--p", a->p, "Fremond's normal exponent p > 1")->capture_default_str();
  cmd->add_option("--contact", a->contact,
                  "The scene's contact; -1: the first contact of its first impact")
      ->capture_default_str();
  cmd->add_option("--speed", a->speed,
                  "Contact speed |(D_TA, D_NA)| > 0 (m/s); 0: the contact's at the first impact")
      ->capture_default_str();
  cmd->add_option("--spin", a->spins,
                  "Spin ratios s = thetadot r_g / speed (comma-separated; several: a third axis)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--grid", a->grid, "Cells along theta x psi: NxM, or N for both, each <= 100000")
      ->capture_default_str();
  cmd->add_option("--theta", a->theta, "MIN,MAX of the body's angle (rad; default 0,pi/2)")
      ->delimiter(',');
  cmd->add_option("--psi", a->psi,
                  "MIN,MAX of the contact velocity's direction, within [-pi, 0] (rad; default "
                  "-pi,0)")
      ->delimiter(',');
  cmd->add_option("--threads", a->threads, "Threads, >= 0 (0: one per core)")
      ->capture_default_str();
  cmd->add_option("--csv", a->csv, "Write one row per point to this CSV file");
  cmd->add_option("--npz", a->npz, "Write the arrays to this NumPy .npz file");
  cmd->add_flag("--no-progress", a->no_progress,
                "No progress on standard error (shown for sweeps of 100000 points or more)");
  cmd->callback([a] { run(*a); });
}

}  // namespace fremond::cli
