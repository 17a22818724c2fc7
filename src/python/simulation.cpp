// Simulation: simulate() with an observer that records every sample, impact and change of phase,
// handed to Python as NumPy arrays and a list of impact records.
#include <string>
#include <tuple>
#include <vector>

#include "fremond/simulation/simulate.hpp"
#include "fremond/simulation/simulation_options.hpp"
#include "fremond/simulation/unresisted_slide.hpp"
#include "python/bind_helpers.hpp"
#include "python/docstrings.hpp"

namespace fremond::python {

namespace {

// A recorded run. Storage only: every number comes from the library's observer hooks.
struct Simulation {
  SimulationResult result;
  std::vector<double> t, energy;
  std::vector<Eigen::Vector3d> q, qdot;
  std::vector<Phase> phase;
  std::vector<ImpactRecord> impacts;
  std::vector<std::tuple<double, Phase, Phase, std::string>> phase_changes;
};

class Recorder final : public SimulationObserver {
 public:
  explicit Recorder(Simulation& run) : run_(run) {}
  void on_sample(const TrajectorySample& s) override {
    run_.t.push_back(s.t);
    run_.q.push_back(s.state.q);
    run_.qdot.push_back(s.state.qdot);
    run_.energy.push_back(s.energy);
    run_.phase.push_back(s.phase);
  }
  void on_impact(const ImpactRecord& impact) override { run_.impacts.push_back(impact); }
  void on_phase(double t, Phase from, Phase to, std::string_view why) override {
    run_.phase_changes.emplace_back(t, from, to, std::string(why));
  }
  // Ctrl-C reaches a run that released the GIL: Python's signal handlers are run every 1,024
  // flights or steps (the GIL taken for that only), and a raised KeyboardInterrupt stops the run.
  bool stop_requested() override {
    if (interrupted_) return true;
    if (++calls_ % 1024 != 0) return false;
    py::gil_scoped_acquire gil;
    interrupted_ = PyErr_CheckSignals() != 0;
    return interrupted_;
  }
  bool interrupted() const { return interrupted_; }

 private:
  Simulation& run_;
  long calls_ = 0;
  bool interrupted_ = false;
};

py::array_t<double> rows3(const std::vector<Eigen::Vector3d>& v) {
  py::array_t<double> out({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int j = 0; j < 3; ++j) a(static_cast<py::ssize_t>(i), j) = v[i](j);
  return out;
}

// The contacts of one impact: the first contact_count entries.
VectorX head(const ImpactRecord::CVec& v, int n) {
  return v.size() >= n ? VectorX(v.head(n)) : VectorX(v);
}

}  // namespace

void bind_simulation(py::module_& m) {
  py::class_<SimulationOptions> opt(m, "SimulationOptions", doc::kSimulationOptions);
  def_keyword_init<SimulationOptions>(opt);
  opt.def_readwrite("integrator", &SimulationOptions::integrator)
      .def_readwrite("t_end", &SimulationOptions::t_end)
      .def_readwrite("step", &SimulationOptions::step)
      .def_readwrite("max_impacts", &SimulationOptions::max_impacts)
      .def_readwrite("max_gap_evaluations", &SimulationOptions::max_gap_evaluations)
      .def_readwrite("simultaneity_tolerance", &SimulationOptions::simultaneity_tolerance)
      .def_readwrite("gap_tolerance", &SimulationOptions::gap_tolerance)
      .def_readwrite("velocity_tolerance", &SimulationOptions::velocity_tolerance)
      .def_readwrite("accumulation_interval", &SimulationOptions::accumulation_interval)
      .def_readwrite("accumulation_impacts", &SimulationOptions::accumulation_impacts)
      .def_readwrite("return_after_free_steps", &SimulationOptions::return_after_free_steps)
      .def_readwrite("sample_interval", &SimulationOptions::sample_interval)
      .def_readwrite("solver", &SimulationOptions::solver)
      .def("is_valid", [](const SimulationOptions& o) { return o.is_valid(); })
      .def("validate", &SimulationOptions::validate)
      .def("__repr__", [](const SimulationOptions& o) {
        return repr_of(o, "SimulationOptions",
                       {"integrator", "t_end", "step", "max_impacts", "sample_interval"});
      });

  py::class_<ImpactRecord>(m, "ImpactRecord", doc::kImpactRecord)
      .def_readonly("index", &ImpactRecord::index)
      .def_readonly("t", &ImpactRecord::t)
      .def_readonly("kind", &ImpactRecord::kind)
      .def_property_readonly("contacts",
                             [](const ImpactRecord& r) {
                               return std::vector<int>(r.contacts.begin(),
                                                       r.contacts.begin() + r.contact_count);
                             })
      .def_readonly("q", &ImpactRecord::q)
      .def_readonly("qdot_A", &ImpactRecord::qdot_A)
      .def_readonly("qdot_E", &ImpactRecord::qdot_E)
      .def_property_readonly("P_N",
                             [](const ImpactRecord& r) { return head(r.P_N, r.contact_count); })
      .def_property_readonly("P_T",
                             [](const ImpactRecord& r) { return head(r.P_T, r.contact_count); })
      .def_property_readonly("D_NA",
                             [](const ImpactRecord& r) { return head(r.D_NA, r.contact_count); })
      .def_property_readonly("D_NE",
                             [](const ImpactRecord& r) { return head(r.D_NE, r.contact_count); })
      .def_property_readonly("D_TA",
                             [](const ImpactRecord& r) { return head(r.D_TA, r.contact_count); })
      .def_property_readonly("D_TE",
                             [](const ImpactRecord& r) { return head(r.D_TE, r.contact_count); })
      .def_readonly("energy_A", &ImpactRecord::energy_A)
      .def_readonly("energy_E", &ImpactRecord::energy_E)
      .def_readonly("admissible", &ImpactRecord::admissible)
      .def_readonly("failed", &ImpactRecord::failed)
      .def_readonly("failed_contact", &ImpactRecord::failed_contact)
      .def_readonly("violation", &ImpactRecord::violation)
      .def_readonly("unique", &ImpactRecord::unique)
      .def_readonly("solver", &ImpactRecord::solver)
      .def_readonly("accumulation_limit", &ImpactRecord::accumulation_limit)
      .def("__repr__", [](const ImpactRecord& r) {
        return repr_of(
            r, "ImpactRecord",
            {"index", "t", "kind", "contacts", "energy_A", "energy_E", "admissible", "failed"});
      });

  py::class_<SimulationResult>(m, "SimulationResult", doc::kSimulationResult)
      .def_readonly("status", &SimulationResult::status)
      .def_property_readonly("message",
                             [](const SimulationResult& r) { return std::string(r.message); })
      .def_readonly("t", &SimulationResult::t)
      .def_readonly("state", &SimulationResult::state)
      .def_readonly("phase", &SimulationResult::phase)
      .def_readonly("energy_initial", &SimulationResult::energy_initial)
      .def_readonly("energy_final", &SimulationResult::energy_final)
      .def_readonly("impacts", &SimulationResult::impacts)
      .def_readonly("event_impacts", &SimulationResult::event_impacts)
      .def_readonly("inadmissible_impacts", &SimulationResult::inadmissible_impacts)
      .def_readonly("first_inadmissible_time", &SimulationResult::first_inadmissible_time)
      .def_readonly("accumulations", &SimulationResult::accumulations)
      .def_readonly("first_accumulation_time", &SimulationResult::first_accumulation_time)
      .def_readonly("steps", &SimulationResult::steps)
      .def_readonly("phase_switches", &SimulationResult::phase_switches)
      .def_readonly("max_energy_rise", &SimulationResult::max_energy_rise)
      .def_readonly("gap_evaluations", &SimulationResult::gap_evaluations)
      .def("ok", &SimulationResult::ok)
      .def("__repr__", [](const SimulationResult& r) {
        return repr_of(
            r, "SimulationResult",
            {"status", "t", "impacts", "inadmissible_impacts", "energy_initial", "energy_final"});
      });

  py::class_<Simulation>(m, "Simulation", doc::kSimulation)
      .def_readonly("result", &Simulation::result)
      .def_property_readonly(
          "t", [](const Simulation& s) { return py::array_t<double>(s.t.size(), s.t.data()); })
      .def_property_readonly(
          "energy",
          [](const Simulation& s) { return py::array_t<double>(s.energy.size(), s.energy.data()); })
      .def_property_readonly("q", [](const Simulation& s) { return rows3(s.q); })
      .def_property_readonly("qdot", [](const Simulation& s) { return rows3(s.qdot); })
      .def_readonly("phase", &Simulation::phase)
      .def_readonly("impacts", &Simulation::impacts)
      .def_readonly("phase_changes", &Simulation::phase_changes)
      .def("__repr__", [](const Simulation& s) {
        return "<fremond Simulation " + std::to_string(s.t.size()) + " samples, " +
               std::to_string(s.impacts.size()) + " log entries, status " +
               std::string(to_string(s.result.status)) + ">";
      });

  m.def(
      "simulate",
      [](const Scene& scene, const SimulationOptions& options) {
        Simulation run;
        Recorder recorder(run);
        {
          py::gil_scoped_release released;
          run.result = simulate(scene, options, &recorder);
        }
        if (recorder.interrupted()) throw py::error_already_set();  // the KeyboardInterrupt
        return run;
      },
      py::arg("scene"), py::arg("options") = SimulationOptions{}, doc::kSimulate);

  py::class_<UnresistedSlide>(m, "UnresistedSlide",
                              "A contact sliding at the end of a run where the law puts no "
                              "tangential percussion on that slide.")
      .def_readonly("contact", &UnresistedSlide::contact)
      .def_readonly("speed", &UnresistedSlide::speed)
      .def("__repr__", [](const UnresistedSlide& u) {
        return "UnresistedSlide(contact=" + std::to_string(u.contact) +
               ", speed=" + std::to_string(u.speed) + ")";
      });
  m.def(
      "unresisted_slide",
      [](const Scene& scene, const SimulationOptions& options, const SimulationResult& result) {
        return unresisted_slide(scene, options, result);
      },
      py::arg("scene"), py::arg("options"), py::arg("result"),
      "The slide the law does not resist at the end of a run (None if there is none): a contact "
      "touching, at rest along the normal and sliding where 0 is in the subdifferential of the "
      "tangential potential at D_T (the viscous dead zone |D_T| <= r), or mu = 0, or no "
      "friction.");
}

}  // namespace fremond::python
