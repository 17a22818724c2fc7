// Work-precision of Frémond's solvers and of the simulation (issue 6, items 2 and 3), written as
// CSV:
//
//   work_precision [--out DIR] [--quick] [--impacts-only | --simulation-only]
//
//  - DIR/work_precision.csv: per method, case and tolerance (NLopt: also per evaluation budget),
//    the time per solve and the actual error against the quad reference (work_precision.hpp);
//  - DIR/simulation_work_precision.csv: Moreau-Jean on the paper's bar against the step size, its
//    energy and trajectory errors relative to the event-driven run of the same law, and its cost
//    per simulated second; with Siconos, Siconos's Moreau-Jean on the same scene at the same steps.
//
// --quick runs fewer tolerances and shorter timings (a smoke run, not for the report).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "fremond/scenes/presets.hpp"
#include "fremond/simulation/calibration.hpp"
#include "fremond/simulation/simulate.hpp"
#include "work_precision.hpp"
#ifdef FREMOND_HAVE_SICONOS
#include "siconos_peers.hpp"
#endif

namespace {

using namespace fremond;
using namespace fremond::bench;

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Records the trajectory on the sample grid (multiples of the sample interval), and the state
/// just after the first impact.
class Recorder : public SimulationObserver {
 public:
  explicit Recorder(double dt) : dt_(dt) {}
  void on_sample(const TrajectorySample& s) override {
    const double k = std::round(s.t / dt_);
    if (std::fabs(s.t - k * dt_) > 1e-9 * dt_) return;  // impact samples are off the grid
    const auto i = static_cast<std::size_t>(k);
    if (i >= q.size()) {
      q.resize(i + 1, Eigen::Vector3d::Constant(std::nan("")));
      energy.resize(i + 1, std::nan(""));
    }
    q[i] = s.state.q;
    energy[i] = s.energy;
  }
  void on_impact(const ImpactRecord& r) override {
    if (impacts++ == 0) first_impact_qdot_E = r.qdot_E;
  }
  std::vector<Eigen::Vector3d> q;
  std::vector<double> energy;
  Eigen::Vector3d first_impact_qdot_E = Eigen::Vector3d::Constant(std::nan(""));
  long impacts = 0;

 private:
  double dt_;
};

struct SimRow {
  std::string code, law;
  double step = 0.0;
  long steps = 0, impacts = 0;
  double cpu_s = 0.0;  ///< CPU time of one run
  double ns_per_step = std::nan("");
  double ns_per_simulated_second = 0.0;
  double energy_error = std::nan("");        ///< max |E − E_ref| on the grid / E(0)
  double energy_final_error = std::nan("");  ///< |E(T) − E_ref(T)| / E(0)
  double trajectory_error = std::nan("");  ///< max over the grid of |q − q_ref|∞ (θ times l), m
  double early_trajectory_error = std::nan("");  ///< the same up to t_early
  double final_state_error = std::nan("");       ///< |q(T) − q_ref(T)|∞ (θ times l), m
  std::string status;
};

void write_sim_csv(const std::string& path, const std::vector<SimRow>& rows) {
  std::ofstream f(path);
  f << "code,law,step,steps,impacts,cpu_seconds,ns_per_step,ns_per_simulated_second,energy_error,"
       "energy_final_error,trajectory_error,early_trajectory_error,final_state_error,status\n";
  f << std::setprecision(6);
  for (const SimRow& r : rows)
    f << r.code << "," << r.law << "," << r.step << "," << r.steps << "," << r.impacts << ","
      << r.cpu_s << "," << r.ns_per_step << "," << r.ns_per_simulated_second << ","
      << r.energy_error << "," << r.energy_final_error << "," << r.trajectory_error << ","
      << r.early_trajectory_error << "," << r.final_state_error << "," << r.status << "\n";
}

double q_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double l = kHalfLength;
  return std::max({std::fabs(a(0) - b(0)), std::fabs(a(1) - b(1)), l * std::fabs(a(2) - b(2))});
}

/// Runs the simulation sweep for one of the paper's laws; Siconos's Moreau-Jean is added for
/// Newton + Coulomb, the law it implements (NewtonImpactFrictionNSL).
void simulation_sweep(PaperLaw law, const std::vector<double>& steps, double t_end, double t_early,
                      double min_seconds, std::vector<SimRow>& rows) {
  const Scene scene = paper_bar_scene(law);
  const double dt = 1e-3;
  SimulationOptions base;
  base.t_end = t_end;
  base.sample_interval = dt;
  // The reference: event-driven.
  Recorder ref(dt);
  SimulationOptions eo = base;
  eo.integrator = Integrator::event_driven;
  const SimulationResult er = simulate(scene, eo, &ref);
  const double E0 = er.energy_initial;
  auto timed_run = [&](const SimulationOptions& o, SimulationResult& res) {
    double total = 0.0;
    int runs = 0;
    double best = 1e300;
    do {
      const double t0 = cpu_seconds();
      res = simulate(scene, o);
      const double t = cpu_seconds() - t0;
      best = std::min(best, t);
      total += t;
      ++runs;
    } while (total < min_seconds && runs < 1000);
    return best;
  };
  {
    SimRow r;
    r.code = "fremond_event_driven";
    r.law = std::string(to_string(law));
    SimulationResult res;
    r.cpu_s = timed_run(eo, res);
    r.steps = res.steps;
    r.impacts = res.impacts;
    r.ns_per_simulated_second = 1e9 * r.cpu_s / t_end;
    r.energy_error = r.energy_final_error = r.trajectory_error = r.early_trajectory_error =
        r.final_state_error = 0.0;
    r.status = std::string(to_string(res.status));
    rows.push_back(r);
  }
  for (const double h : steps) {
    SimulationOptions mo = base;
    mo.integrator = Integrator::moreau_jean;
    mo.step = h;
    Recorder rec(dt);
    const SimulationResult mr = simulate(scene, mo, &rec);
    SimRow r;
    r.code = "fremond_moreau_jean";
    r.law = std::string(to_string(law));
    r.step = h;
    SimulationResult res;
    r.cpu_s = timed_run(mo, res);
    r.steps = mr.steps;
    r.impacts = mr.impacts;
    r.ns_per_step = mr.steps ? 1e9 * r.cpu_s / static_cast<double>(mr.steps) : std::nan("");
    r.ns_per_simulated_second = 1e9 * r.cpu_s / t_end;
    double ee = 0.0, te = 0.0, tee = 0.0;
    const std::size_t n = std::min(rec.q.size(), ref.q.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (std::isnan(rec.energy[i]) || std::isnan(ref.energy[i])) continue;
      ee = std::max(ee, std::fabs(rec.energy[i] - ref.energy[i]) / E0);
      const double d = q_distance(rec.q[i], ref.q[i]);
      te = std::max(te, d);
      if (static_cast<double>(i) * dt <= t_early) tee = std::max(tee, d);
    }
    r.energy_error = ee;
    r.energy_final_error = std::fabs(mr.energy_final - er.energy_final) / E0;
    r.trajectory_error = te;
    r.early_trajectory_error = tee;
    r.final_state_error = q_distance(mr.state.q, er.state.q);
    r.status = std::string(to_string(mr.status));
    rows.push_back(r);
  }
#ifdef FREMOND_HAVE_SICONOS
  if (law == PaperLaw::newton_coulomb) {
    for (const double h : steps) {
      siconos::MoreauJeanSettings s;
      s.h = h;
      s.duration = t_end;
      double best = 1e300, total = 0.0;
      siconos::MoreauJeanRun run;
      int runs = 0;
      do {
        run = siconos::simulate_bar_moreau_jean(s);
        best = std::min(best, run.cpu_seconds);
        total += run.cpu_seconds;
        ++runs;
      } while (total < min_seconds && runs < 100);
      SimRow r;
      r.code = "siconos_moreau_jean";
      r.law = std::string(to_string(law));
      r.step = h;
      r.steps = run.steps;
      r.impacts = static_cast<long>(run.impact_times.size());
      r.cpu_s = best;
      r.ns_per_step = run.steps ? 1e9 * best / run.steps : std::nan("");
      r.ns_per_simulated_second = 1e9 * best / t_end;
      r.energy_final_error = std::fabs(run.energy_final - er.energy_final) / E0;
      if (run.q_final.size() == 3)
        r.final_state_error =
            q_distance(Eigen::Vector3d(run.q_final[0], run.q_final[1], run.q_final[2]), er.state.q);
      r.status = "completed";
      rows.push_back(r);
    }
  }
#endif
}

}  // namespace

int main(int argc, char** argv) {
  std::string out = "out/perf";
  bool quick = false, impacts = true, simulation = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--out" && i + 1 < argc) {
      out = argv[++i];
    } else if (a == "--quick") {
      quick = true;
    } else if (a == "--impacts-only") {
      simulation = false;
    } else if (a == "--simulation-only") {
      impacts = false;
    } else {
      std::cerr
          << "usage: work_precision [--out DIR] [--quick] [--impacts-only | --simulation-only]\n";
      return 2;
    }
  }
  std::filesystem::create_directories(out);
  if (impacts) {
    std::cerr << "work-precision: building the suite and its quad reference\n";
    const auto cases = fremond_suite();
    wp::Options o = quick ? wp::tiny_options() : wp::Options{};
    const auto points = wp::run(cases, o, &std::cerr);
    std::ofstream f(out + "/work_precision.csv");
    wp::write_csv(f, points);
    std::cerr << "wrote " << out << "/work_precision.csv (" << points.size() << " points)\n";
  }
  if (simulation) {
    std::vector<SimRow> rows;
    const std::vector<double> steps =
        quick ? std::vector<double>{1e-2, 1e-3}
              : std::vector<double>{1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5};
    const double min_s = quick ? 0.0 : 0.2;
    for (PaperLaw law :
         {PaperLaw::newton_coulomb, PaperLaw::fremond_coulomb, PaperLaw::fremond_viscous}) {
      std::cerr << "simulation work-precision: " << to_string(law) << "\n";
      simulation_sweep(law, steps, 3.0, 0.5, min_s, rows);
    }
    write_sim_csv(out + "/simulation_work_precision.csv", rows);
    std::cerr << "wrote " << out << "/simulation_work_precision.csv\n";
  }
  return 0;
}
