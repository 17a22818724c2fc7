// `fremond simulate SCENE.json --out DIR` and `fremond simulate --preset paper-bar --law LAW --out
// DIR`: runs a scene (simulation/simulate.hpp), writes the trajectory (CSV) and the impact log
// (JSON), and prints a short summary.
//
// Exit status: 0 the run reached its end time (or --max-impacts); 1 input refused (the message
// names the key or option; nothing written); 2 the run stopped early because an impact or a
// persistent contact could not be solved, or a free flight's events could not be resolved within
// the event search's budget (the files are written up to there, and the summary says why); 3 the
// output could not be written; 128 + the signal (130 for Ctrl-C, 143 for SIGTERM) when interrupted:
// the run stops where it is and the files hold it up to there.
//
// Output files are complete or absent: each is written to a temporary file in DIR and renamed.
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "cli/commands.hpp"
#include "cli/output.hpp"
#include "fremond/core/error.hpp"
#include "fremond/io/scene_file.hpp"
#include "fremond/potentials/registry.hpp"
#include "fremond/scenes/presets.hpp"
#include "fremond/simulation/calibration.hpp"
#include "fremond/simulation/simulate.hpp"
#include "fremond/simulation/simulate_bodies.hpp"
#include "fremond/simulation/unresisted_slide.hpp"
#include "io/detail/json_number.hpp"

namespace fremond::cli {

namespace {

constexpr int kExitRefused = 1;
constexpr int kExitRunFailed = 2;
constexpr int kExitWriteFailed = 3;

using ojson = nlohmann::ordered_json;

struct SimulateArguments {
  std::string scene_file;
  std::string preset;
  std::string law;
  std::string out;
  std::string integrator;
  double t_end = std::nan("");
  double step = std::nan("");
  double sample_interval = std::nan("");
  long max_impacts = -1;
  long max_gap_evaluations = -1;
  long max_rows = 1000000;
  bool no_progress = false;
};

// The signal that asked the run to stop (SIGINT, SIGTERM), 0 while none did. A second one ends
// the process at once: the handler restores the default.
volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void stop_the_run(int sig) {
  g_stop_signal = sig;
  std::signal(sig, SIG_DFL);
}

[[noreturn]] void refuse(const std::string& what) {
  std::fprintf(stderr, "fremond simulate: error: %s\n", what.c_str());
  exit_with(kExitRefused);
}

// ---- the scene --------------------------------------------------------------------------------

struct Setup {
  Scene scene;
  std::optional<MultiBodyScene> bodies;  // a scene of several bodies instead of `scene`
  SimulationOptions options;
  std::string name;  // for the summary
  std::string note;  // said on standard error before the run, when not empty
};

// The presets of several bodies. Frémond's k_N gives the paper's e = 0.9 to two free balls of the
// preset meeting at the speed of its first impact (the normal law alone).
MultiBodyScene bodies_preset(const std::string& preset, PaperLaw law) {
  const bool fremond = law == PaperLaw::fremond_coulomb || law == PaperLaw::fremond_viscous;
  const auto k_N = [&](double mass, double radius, double speed) {
    if (!fremond) return 0.0;
    CradleParameters two;
    two.balls = 2;
    two.mass = mass;
    two.radius = radius;
    two.speed = speed;
    const MultiBodyScene pair = cradle_scene(two, ImpactLaw::newton(PaperConstants::e));
    const std::vector<int> contact{0};
    return calibrate_normal_stiffness(to_small(impact_problem(pair, pair.initial, contact)),
                                      PaperConstants::p, PaperConstants::e)
        .k_N;
  };
  if (preset == "cradle3" || preset == "cradle5") {
    CradleParameters c;
    c.balls = preset == "cradle3" ? 3 : 5;
    return cradle_scene(c, paper_law(law, k_N(c.mass, c.radius, c.speed)));
  }
  BallOnBallParameters b;
  const double v = std::sqrt(b.speed * b.speed + 2.0 * b.gravity * b.drop_height);
  return ball_on_ball_scene(b, paper_law(law, k_N(b.mass, b.radius, v)));
}

Setup preset_scene(const std::string& preset, const std::string& law_name) {
  if (law_name.empty())
    throw InvalidArgument("--law",
                          "required with --preset (one of: newton, newton_coulomb, "
                          "poisson_coulomb, fremond_coulomb, fremond_viscous)");
  PaperLaw law;
  try {
    law = paper_law_from_string(law_name);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument("--law", std::string(e.what()).substr(e.name().size() + 2));
  }
  const bool fremond = law == PaperLaw::fremond_coulomb || law == PaperLaw::fremond_viscous;
  // Frémond's k_N as docs/laws.md asks: e = 0.9 at the scene's own first impact, computed here.
  const auto with_law = [&](const auto& make, const auto& params) {
    const Scene probe = make(params, ImpactLaw::newton(PaperConstants::e));
    const double k_N =
        fremond ? first_impact_normal_stiffness(probe, PaperConstants::p, PaperConstants::e) : 0.0;
    return make(params, paper_law(law, k_N));
  };
  Setup s;
  s.name = preset + " (" + law_name + ")";
  if (preset == "paper-bar")
    s.scene = with_law(bar_scene, BarParameters{});
  else if (preset == "ball")
    s.scene = with_law(ball_scene, BallParameters{});
  else if (preset == "block")
    s.scene = with_law(block_scene, BlockParameters{});
  else if (preset == "cradle3" || preset == "cradle5" || preset == "ball-on-ball")
    s.bodies = bodies_preset(preset, law);
  else
    throw InvalidArgument("--preset", "unknown preset '" + preset +
                                          "' (one of: paper-bar, ball, block, cradle3, cradle5, "
                                          "ball-on-ball)");
  return s;
}

Setup load(const SimulateArguments& a) {
  Setup s;
  if (!a.scene_file.empty() && !a.preset.empty())
    throw InvalidArgument("--preset", "give a scene file or a preset, not both");
  if (a.scene_file.empty() && a.preset.empty())
    throw InvalidArgument("SCENE", "give a scene file, or --preset paper-bar --law LAW");
  if (!a.preset.empty()) {
    s = preset_scene(a.preset, a.law);
  } else {
    if (!a.law.empty())
      throw InvalidArgument("--law", "only with --preset: a scene file names its own law");
    std::error_code ec;
    if (std::filesystem::is_directory(a.scene_file, ec))
      throw InvalidArgument(a.scene_file, "is a directory, not a scene file");
    try {
      auto f = io::read_any_scene_file(a.scene_file, PotentialRegistry::with_builtins());
      if (auto* one = std::get_if<io::SceneFile>(&f)) {
        s.scene = std::move(one->scene);
        s.options = one->options;
      } else {
        auto& several = std::get<io::MultiBodySceneFile>(f);
        s.bodies = std::move(several.scene);
        s.options = several.options;
      }
    } catch (const InvalidArgument& e) {  // name the file, then the key
      if (e.name() == a.scene_file) throw;
      throw InvalidArgument(a.scene_file + ": " + e.name(),
                            std::string(e.what()).substr(e.name().size() + 2));
    }
    s.name = a.scene_file;
  }
  // Command-line options override the file's.
  SimulationOptions& o = s.options;
  if (!std::isnan(a.t_end)) o.t_end = a.t_end;
  if (!std::isnan(a.step)) o.step = a.step;
  if (!std::isnan(a.sample_interval)) o.sample_interval = a.sample_interval;
  if (a.max_impacts >= 0) o.max_impacts = a.max_impacts;
  if (a.max_gap_evaluations >= 0) o.max_gap_evaluations = a.max_gap_evaluations;
  if (!a.integrator.empty()) {
    try {
      o.integrator = integrator_from_string(a.integrator);
    } catch (const InvalidArgument& e) {
      throw InvalidArgument("--integrator", std::string(e.what()).substr(e.name().size() + 2));
    }
  }
  std::string why;
  if (!o.is_valid(&why)) {
    // Name the command-line option when it was one.
    const std::string key = why.substr(0, why.find(':'));
    const std::string reason = why.substr(why.find(':') + 2);
    if (key == "t_end" && !std::isnan(a.t_end)) throw InvalidArgument("--t-end", reason);
    if (key == "integrator.step" && !std::isnan(a.step)) throw InvalidArgument("--step", reason);
    if (key == "integrator.max_impacts" && a.max_impacts >= 0)
      throw InvalidArgument("--max-impacts", reason);
    if (key == "integrator.max_gap_evaluations" && a.max_gap_evaluations >= 0)
      throw InvalidArgument("--max-gap-evaluations", reason);
    if (key == "output.sample_interval" && !std::isnan(a.sample_interval))
      throw InvalidArgument("--sample-interval", reason);
    throw InvalidArgument(key, reason);
  }
  if (a.max_rows < 0)
    throw InvalidArgument("--max-rows",
                          "must be >= 0 (0: no limit), got " + std::to_string(a.max_rows));
  // A grid the user did not choose on the command line is made coarser rather than filling the
  // disk (3,000 s at 1 ms: 3 million rows, 358 MB).
  if (std::isnan(a.sample_interval) && a.max_rows > 0 &&
      o.t_end / o.sample_interval > static_cast<double>(a.max_rows)) {
    const double coarser = o.t_end / static_cast<double>(a.max_rows);
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "rows every %.6g s, not %.6g s, to keep trajectory.csv to %ld rows; "
                  "--sample-interval or --max-rows 0 keeps the finer grid",
                  coarser, o.sample_interval, a.max_rows);
    s.note = buf;
    o.sample_interval = coarser;
  }
  if (a.out.empty()) throw InvalidArgument("--out", "required: the directory to write into");
  return s;
}

// ---- recording the run ------------------------------------------------------------------------

using io::detail::json_number;

template <class V>
ojson numbers(const V& v, Eigen::Index n) {
  ojson a = ojson::array();
  for (Eigen::Index i = 0; i < n; ++i) a.push_back(json_number(v(i)));
  return a;
}

// How an impact's solve ended, as the impact log writes it.
ojson solver_json(const SolverReport& r) {
  ojson solver;
  solver["method"] = std::string(to_string(r.method));
  solver["status"] = std::string(to_string(r.status));
  solver["iterations"] = r.iterations;
  solver["residual"] = json_number(r.residual);
  solver["message"] = std::string(r.message);
  return solver;
}

ojson impact_json(const ImpactRecord& r) {
  const Eigen::Index n = r.contact_count;
  ojson j;
  j["index"] = r.index;
  j["t"] = json_number(r.t);
  j["kind"] = std::string(to_string(r.kind));
  ojson contacts = ojson::array();
  for (int i = 0; i < r.contact_count; ++i) contacts.push_back(r.contacts[i]);
  j["contacts"] = contacts;
  j["q"] = numbers(r.q, 3);
  j["qdot_A"] = numbers(r.qdot_A, 3);
  j["qdot_E"] = numbers(r.qdot_E, 3);
  j["P_N"] = numbers(r.P_N, n);
  j["P_T"] = numbers(r.P_T, n);
  j["D_NA"] = numbers(r.D_NA, n);
  j["D_NE"] = numbers(r.D_NE, n);
  j["D_TA"] = numbers(r.D_TA, n);
  j["D_TE"] = numbers(r.D_TE, n);
  j["energy_A"] = json_number(r.energy_A);
  j["energy_E"] = json_number(r.energy_E);
  j["admissible"] = r.admissible;
  j["failed"] = std::string(to_string(r.failed));
  j["failed_contact"] = r.failed_contact;
  j["violation"] = json_number(r.violation);
  j["unique"] = r.unique;
  j["solver"] = solver_json(r.solver);
  if (r.kind == ImpactKind::accumulation)
    j["accumulation_limit"] = json_number(r.accumulation_limit);
  return j;
}

// A progress bar on standard error, drawn only when it is a terminal and the run lasts; the clock
// here paces the drawing only, never the run.
class Recorder final : public SimulationObserver {
 public:
  explicit Recorder(bool progress) : progress_(progress && isatty(STDERR_FILENO)) {}
  ~Recorder() override { clear(); }

  void on_sample(const TrajectorySample& s) override {
    char line[512];
    const int n =
        std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", s.t,
                      s.state.q.x(), s.state.q.y(), s.state.q.z(), s.state.qdot.x(),
                      s.state.qdot.y(), s.state.qdot.z(), s.energy);
    csv_.append(line, static_cast<std::size_t>(n));
    ++rows_;
  }
  void on_impact(const ImpactRecord& r) override { impacts_.push_back(impact_json(r)); }
  void on_phase(double t, Phase from, Phase to, std::string_view why) override {
    ojson j;
    j["t"] = json_number(t);
    j["from"] = std::string(to_string(from));
    j["to"] = std::string(to_string(to));
    j["why"] = std::string(why);
    phases_.push_back(j);
  }
  bool stop_requested() override { return g_stop_signal != 0; }
  void on_progress(double t, double t_end) override {
    if (!progress_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - start_ < std::chrono::milliseconds(500) ||
        now - last_ < std::chrono::milliseconds(100))
      return;
    last_ = now;
    const int width = 40, done = static_cast<int>(width * t / t_end);
    std::fprintf(stderr, "\r[%.*s%*s] %5.1f%%  t = %.3f s", done,
                 "########################################", width - done, "", 100.0 * t / t_end,
                 t);
    std::fflush(stderr);
    drawn_ = true;
  }
  void clear() {
    if (drawn_) std::fprintf(stderr, "\r%*s\r", 70, "");
    drawn_ = false;
  }

  const std::string& csv() const { return csv_; }
  long rows() const { return rows_; }
  const ojson& impacts() const { return impacts_; }
  const ojson& phases() const { return phases_; }

 private:
  bool progress_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_;
  std::string csv_ = "t,x,y,theta,xdot,ydot,thetadot,energy\n";
  long rows_ = 0;
  ojson impacts_ = ojson::array();
  ojson phases_ = ojson::array();
};

// ---- writing ----------------------------------------------------------------------------------

ojson summary_json(const Setup& s, const SimulationResult& r,
                   const std::optional<UnresistedSlide>& slide) {
  ojson j;
  j["scene"] = s.name;
  j["law"] = s.scene.law.describe();
  j["integrator"] = std::string(to_string(s.options.integrator));
  j["t_end"] = json_number(s.options.t_end);
  j["step"] = json_number(s.options.step);
  j["status"] = std::string(to_string(r.status));
  j["message"] = std::string(r.message);
  j["t"] = json_number(r.t);
  j["q"] = numbers(r.state.q, 3);
  j["qdot"] = numbers(r.state.qdot, 3);
  j["phase"] = std::string(to_string(r.phase));
  j["energy_initial"] = json_number(r.energy_initial);
  j["energy_final"] = json_number(r.energy_final);
  j["max_energy_rise"] = json_number(r.max_energy_rise);
  j["impacts"] = r.impacts;
  j["event_impacts"] = r.event_impacts;
  j["inadmissible_impacts"] = r.inadmissible_impacts;
  j["first_inadmissible_time"] = json_number(r.first_inadmissible_time);
  j["accumulations"] = r.accumulations;
  j["first_accumulation_time"] = json_number(r.first_accumulation_time);
  j["moreau_jean_steps"] = r.steps;
  j["phase_switches"] = r.phase_switches;
  if (slide) {
    ojson sl;
    sl["contact"] = slide->contact;
    sl["D_T"] = json_number(slide->speed);
    j["unresisted_slide"] = sl;
  } else {
    j["unresisted_slide"] = nullptr;
  }
  return j;
}

void print_summary(const Setup& s, const SimulationResult& r,
                   const std::optional<UnresistedSlide>& slide, const std::filesystem::path& dir,
                   const Recorder& rec) {
  const auto& q = r.state.q;
  const auto& v = r.state.qdot;
  std::printf("scene:        %s\n", s.name.c_str());
  std::printf("law:          %s\n", s.scene.law.describe().c_str());
  std::printf("integrator:   %s (Moreau-Jean step %g s), t_end %g s\n",
              std::string(to_string(s.options.integrator)).c_str(), s.options.step,
              s.options.t_end);
  std::printf("status:       %s (%s) at t = %.9g s\n", std::string(to_string(r.status)).c_str(),
              std::string(r.message).c_str(), r.t);
  std::printf("impacts:      %ld (%ld event-driven, %ld in Moreau-Jean steps)\n", r.impacts,
              r.event_impacts, r.impacts - r.event_impacts);
  if (r.inadmissible_impacts > 0)
    std::printf(
        "inadmissible: %ld impacts fail the admissibility certificate (first at t = %.9g s)\n",
        r.inadmissible_impacts, r.first_inadmissible_time);
  else
    std::printf("inadmissible: none\n");
  if (r.accumulations > 0)
    std::printf("accumulation: %d (first limit t = %.12g s)\n", r.accumulations,
                r.first_accumulation_time);
  else
    std::printf("accumulation: none\n");
  std::printf("steps:        %ld Moreau-Jean steps, %d phase switches\n", r.steps,
              r.phase_switches);
  std::printf("energy:       %.12g J -> %.12g J (largest rise outside flagged impacts %.3g J)\n",
              r.energy_initial, r.energy_final, r.max_energy_rise);
  std::printf("final state:  q = (%.9g, %.9g, %.9g), qdot = (%.9g, %.9g, %.9g)\n", q.x(), q.y(),
              q.z(), v.x(), v.y(), v.z());
  if (slide)
    std::printf(
        "sliding:      contact %d slides at D_T = %.6g m/s at the end, and the law puts no "
        "tangential percussion on that slide (a viscous dead zone |D_T| <= r, or no friction): "
        "nothing in the model stops it (docs/laws.md)\n",
        slide->contact, slide->speed);
  std::printf("wrote:        %s (%ld rows), %s (%zu impacts), %s\n",
              (dir / "trajectory.csv").c_str(), rec.rows(), (dir / "impacts.json").c_str(),
              rec.impacts().size(), (dir / "summary.json").c_str());
  std::fflush(stdout);
}

// ---- a scene of several bodies -------------------------------------------------------------

ojson bodies_impact_json(const MultiBodyImpact& r) {
  const Eigen::Index n = r.P_N.size();
  ojson j;
  j["index"] = r.index;
  j["t"] = json_number(r.t);
  j["kind"] = std::string(to_string(r.kind));
  j["contacts"] = r.contacts;
  j["q"] = numbers(r.q, r.q.size());
  j["qdot_A"] = numbers(r.qdot_A, r.qdot_A.size());
  j["qdot_E"] = numbers(r.qdot_E, r.qdot_E.size());
  j["P_N"] = numbers(r.P_N, n);
  j["P_T"] = numbers(r.P_T, n);
  j["D_NA"] = numbers(r.D_NA, n);
  j["D_NE"] = numbers(r.D_NE, n);
  j["energy_A"] = json_number(r.energy_A);
  j["energy_E"] = json_number(r.energy_E);
  j["admissible"] = r.admissible;
  j["solver"] = solver_json(r.solver);
  return j;
}

// trajectory.csv: t, then x_i, y_i, theta_i, xdot_i, ydot_i, thetadot_i of each body i, energy.
class BodiesRecorder final : public MultiBodyObserver {
 public:
  explicit BodiesRecorder(int bodies) {
    csv_ = "t";
    for (int i = 0; i < bodies; ++i)
      for (const char* c : {"x", "y", "theta", "xdot", "ydot", "thetadot"})
        csv_.append(",").append(c).append(std::to_string(i));
    csv_.append(",energy\n");
  }
  void on_sample(const MultiBodySample& s) override {
    char cell[32];
    const auto add = [&](double v) {  // ",v"
      const int n = std::snprintf(cell, sizeof cell, ",%.17g", v);
      csv_.append(cell, static_cast<std::size_t>(n));
    };
    const int n = std::snprintf(cell, sizeof cell, "%.17g", s.t);
    csv_.append(cell, static_cast<std::size_t>(n));
    for (Eigen::Index i = 0; i < s.state.q.size() / 3; ++i) {
      for (int c = 0; c < 3; ++c) add(s.state.q(3 * i + c));
      for (int c = 0; c < 3; ++c) add(s.state.qdot(3 * i + c));
    }
    add(s.energy);
    csv_ += '\n';
    ++rows_;
  }
  void on_impact(const MultiBodyImpact& r) override { impacts_.push_back(bodies_impact_json(r)); }
  bool stop_requested() override { return g_stop_signal != 0; }

  const std::string& csv() const { return csv_; }
  long rows() const { return rows_; }
  const ojson& impacts() const { return impacts_; }

 private:
  std::string csv_;
  long rows_ = 0;
  ojson impacts_ = ojson::array();
};

void write_run(const std::filesystem::path& dir, const std::string& csv, const ojson& impact_list,
               const ojson& summary) {
  write_atomically(dir, "trajectory.csv", csv);
  // One impact a line: a list that reads as a table and still parses as JSON.
  std::string impacts = "[";
  for (std::size_t i = 0; i < impact_list.size(); ++i)
    impacts += (i ? ",\n " : "\n ") + impact_list[i].dump();
  impacts += impact_list.empty() ? "]\n" : "\n]\n";
  write_atomically(dir, "impacts.json", impacts);
  write_atomically(dir, "summary.json", summary.dump(1) + "\n");
}

// Exits as run() does for the status of a finished run.
void exit_for(SimulationStatus status, double t, std::string_view message) {
  if (status == SimulationStatus::interrupted) {
    std::fprintf(stderr,
                 "fremond simulate: interrupted at t = %.9g s; the files hold the run up to "
                 "there\n",
                 t);
    exit_with(128 + static_cast<int>(g_stop_signal));
  }
  if (status != SimulationStatus::completed && status != SimulationStatus::max_impacts) {
    std::fprintf(stderr, "fremond simulate: the run stopped at t = %.9g s: %s (%s)\n", t,
                 std::string(to_string(status)).c_str(), std::string(message).c_str());
    exit_with(kExitRunFailed);
  }
}

void run_bodies(const Setup& setup, const std::filesystem::path& dir) {
  const MultiBodyScene& scene = *setup.bodies;
  BodiesRecorder rec(static_cast<int>(scene.bodies.size()));
  MultiBodyResult r;
  try {
    r = simulate(scene, setup.options, &rec);
  } catch (const InvalidArgument& e) {
    refuse(e.what());
  }
  ojson j;
  j["scene"] = setup.name;
  j["bodies"] = scene.bodies.size();
  j["law"] = scene.law.describe();
  j["integrator"] = std::string(to_string(setup.options.integrator));
  j["t_end"] = json_number(setup.options.t_end);
  j["status"] = std::string(to_string(r.status));
  j["message"] = std::string(r.message);
  j["t"] = json_number(r.t);
  j["q"] = numbers(r.state.q, r.state.q.size());
  j["qdot"] = numbers(r.state.qdot, r.state.qdot.size());
  j["energy_initial"] = json_number(r.energy_initial);
  j["energy_final"] = json_number(r.energy_final);
  j["max_energy_rise"] = json_number(r.max_energy_rise);
  j["impacts"] = r.impacts;
  j["inadmissible_impacts"] = r.inadmissible_impacts;
  j["accumulations"] = r.accumulations;
  try {
    write_run(dir, rec.csv(), rec.impacts(), j);
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "fremond simulate: error: %s\n", e.what());
    exit_with(kExitWriteFailed);
  }
  std::printf("scene:        %s (%zu bodies)\n", setup.name.c_str(), scene.bodies.size());
  std::printf("law:          %s\n", scene.law.describe().c_str());
  std::printf("status:       %s (%s) at t = %.9g s\n", std::string(to_string(r.status)).c_str(),
              std::string(r.message).c_str(), r.t);
  std::printf("impacts:      %ld (%ld fail the admissibility certificate), %d accumulations\n",
              r.impacts, r.inadmissible_impacts, r.accumulations);
  std::printf("energy:       %.12g J -> %.12g J (largest rise outside flagged impacts %.3g J)\n",
              r.energy_initial, r.energy_final, r.max_energy_rise);
  std::printf("wrote:        %s (%ld rows), %s (%zu impacts), %s\n",
              (dir / "trajectory.csv").c_str(), rec.rows(), (dir / "impacts.json").c_str(),
              rec.impacts().size(), (dir / "summary.json").c_str());
  std::fflush(stdout);
  exit_for(r.status, r.t, r.message);
}

void run(const SimulateArguments& args) {
  Setup setup;
  std::filesystem::path dir;
  try {
    setup = load(args);
    dir = args.out;
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (!std::filesystem::is_directory(dir, ec))
      throw InvalidArgument("--out", "cannot create the directory '" + args.out + "'");
  } catch (const InvalidArgument& e) {
    refuse(e.what());
  }

  if (!setup.note.empty()) std::fprintf(stderr, "fremond simulate: note: %s\n", setup.note.c_str());
  std::signal(SIGINT, stop_the_run);
  std::signal(SIGTERM, stop_the_run);
  if (setup.bodies) {
    run_bodies(setup, dir);
    return;
  }
  Recorder rec(!args.no_progress);
  SimulationResult result;
  try {
    result = simulate(setup.scene, setup.options, &rec);
  } catch (const InvalidArgument& e) {
    rec.clear();
    refuse(e.what());
  }
  rec.clear();
  const std::optional<UnresistedSlide> slide = unresisted_slide(setup.scene, setup.options, result);

  try {
    ojson summary = summary_json(setup, result, slide);
    summary["phases"] = rec.phases();
    write_run(dir, rec.csv(), rec.impacts(), summary);
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "fremond simulate: error: %s\n", e.what());
    exit_with(kExitWriteFailed);
  }
  print_summary(setup, result, slide, dir, rec);
  exit_for(result.status, result.t, result.message);
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto args = std::make_shared<SimulateArguments>();
  auto* cmd = app.add_subcommand(
      "simulate",
      "Simulate a scene (a planar rigid body, or several, against half-planes and each other): "
      "trajectory, every impact, accumulations");
  cmd->add_option("SCENE", args->scene_file, "The scene file (JSON)");
  cmd->add_option("--preset", args->preset,
                  "A ready-made scene: paper-bar (the paper's Fig. 1), ball, block; of several "
                  "bodies: cradle3, cradle5 (Newton's cradle), ball-on-ball (a ball dropped on a "
                  "resting ball)");
  cmd->add_option("--law", args->law,
                  "With --preset: newton, newton_coulomb, poisson_coulomb, fremond_coulomb, "
                  "fremond_viscous, stronge_coulomb, with the paper's parameters (the paper's "
                  "Fig. 1)");
  cmd->add_option("--out", args->out,
                  "The directory to write trajectory.csv, impacts.json and "
                  "summary.json into (created if needed)");
  cmd->add_option("--t-end", args->t_end, "End time (s)");
  cmd->add_option("--max-impacts", args->max_impacts, "Stop after this many impacts");
  cmd->add_option("--max-gap-evaluations", args->max_gap_evaluations,
                  "Budget of one free flight's event search (gap evaluations per contact, >= 100)");
  cmd->add_option("--integrator", args->integrator, "event_driven (default) or moreau_jean");
  cmd->add_option("--step", args->step, "Moreau-Jean step (s)");
  cmd->add_option("--sample-interval", args->sample_interval,
                  "Interval of the trajectory rows (s); impacts add rows just before and after");
  cmd->add_option("--max-rows", args->max_rows,
                  "Without --sample-interval, make the rows coarser than the scene's interval "
                  "where t_end would need more than this many (0: no limit)")
      ->capture_default_str();
  cmd->add_flag("--no-progress", args->no_progress, "No progress bar on standard error");
  cmd->footer(
      "Exit status: 0 the run reached its end time (or --max-impacts); 1 input refused (message "
      "on stderr naming the key or option, nothing written); 2 the run stopped early (files "
      "written up to there, reason on stderr); 3 the output could not be written; 130 (Ctrl-C) or "
      "143 (SIGTERM) interrupted, the files written up to there. Files are complete or absent.");
  cmd->callback([args] { run(*args); });
}

}  // namespace fremond::cli
