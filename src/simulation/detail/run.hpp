#pragma once
// One run of simulate() (simulate.hpp): its state and its parts, one file each —
//  - simulate.cpp: set-up, the alternation of phases, the end of the run;
//  - event_driven.cpp: exact flights to the next contact event, and the impact there;
//  - impact.cpp: an impact with the scene's law (posed, solved, logged);
//  - accumulation.cpp: telling and closing an accumulation of impacts;
//  - moreau_jean.cpp: the Moreau–Jean step;
//  - sampling.cpp, energy_audit.hpp, impact_record.hpp: the rows, the energy audit, the log;
//  - contact_laws.cpp: the scene's law restricted to the contacts of an impact.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>

#include "fremond/scenes/kinematics.hpp"
#include "fremond/simulation/event_detection.hpp"
#include "fremond/simulation/persistent_contact.hpp"
#include "fremond/simulation/simulate.hpp"
#include "simulation/detail/accumulation.hpp"
#include "simulation/detail/contact_laws.hpp"
#include "simulation/detail/energy_audit.hpp"
#include "simulation/detail/sampling.hpp"

namespace fremond::detail {

class Run {
 public:
  /// Validates copies of the scene and the options (throws InvalidArgument).
  Run(const Scene& scene, const SimulationOptions& options, SimulationObserver* observer);
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  SimulationResult go();

 private:
  static constexpr int kMaxC = kMaxSceneContacts;
  static constexpr double kInf = std::numeric_limits<double>::infinity();

  // The frames of a step's active contacts. ContactFrame zero-initialises its members; an array of
  // them for every possible contact would be cleared at every step for nothing.
  struct StepFrame {
    double gap;
    Eigen::Vector3d W_N, W_T;
    StepFrame& operator=(const ContactFrame& f) {
      gap = f.gap;
      W_N = f.W_N;
      W_T = f.W_T;
      return *this;
    }
  };
  using Frames = std::array<StepFrame, kMaxC>;

  // ---- the run (simulate.cpp and here) ----
  // Progress for the observer, and its chance to stop the run; false when it asked to.
  bool progress() {
    if (!obs_) return true;
    if (t_ >= next_progress_) {
      obs_->on_progress(t_, opt_.t_end);
      while (next_progress_ <= t_) next_progress_ += 0.01 * opt_.t_end;
    }
    if (!obs_->stop_requested()) return true;
    finish(SimulationStatus::interrupted, "the observer asked the run to stop");
    return false;
  }
  void switch_phase(Phase to, std::string_view why);
  void finish(SimulationStatus status, std::string_view message) {
    res_.status = status;
    res_.message = message;
    stop_ = true;
  }
  void sample(double t, const PlanarState& s) { sampler_.emit(t, s, phase_); }
  ContactFrame frame(int k, const Eigen::Vector3d& q, double c, double s) const {
    return contact_frame(*point_[k], *plane_[k], q.head<2>(), c, s);
  }

  // ---- impacts with the scene's law (impact.cpp) ----
  // Solves the impact of contacts idx[0..n) at time t; s.qdot becomes q̇_E. False: the run stops.
  bool impact(double t, PlanarState& s, const int* idx, int n, ImpactKind kind);
  template <class Problem>
  void fill(Problem& pb, const PlanarState& s, const int* idx, int n) const;
  template <class Problem>
  bool solve_and_record(double t, PlanarState& s, const int* idx, int n, ImpactKind kind,
                        const Problem& pb, const ImpactLaw& law);
  template <class Result>
  bool record(double t, PlanarState& s, const int* idx, int n, ImpactKind kind, const Result& r);

  // ---- event-driven phase (event_driven.cpp) ----
  void event_driven_phase();
  std::optional<double> first_event(const std::array<GapFunction, kMaxC>& gap,
                                    const std::array<bool, kMaxC>& touching, double horizon,
                                    std::array<double, kMaxC>& when);
  bool after_event_impact();

  // ---- accumulations (accumulation.cpp) ----
  void close_accumulation(double tail);

  // ---- Moreau–Jean phase (moreau_jean.cpp) ----
  void moreau_jean_phase();
  int active_contacts(const Eigen::Vector3d& q, const Eigen::Vector3d& v, double h, double cth,
                      double sth, Frames& f, int* active) const;
  int law_impact_contacts(const Frames& f, const int* active, int na, const Eigen::Vector3d& v,
                          double hk, long k, int* idx);
  bool persistent_impulse(const Frames& f, const int* active, int na, const Eigen::Vector3d& v,
                          bool closing, const Eigen::Vector3d& dv, Eigen::Vector3d& v_out);
  // What gravity adds to the velocity over a step h, (0, −g h, 0).
  Eigen::Vector3d gravity_dv(double h) const { return {0.0, -sc_.gravity * h, 0.0}; }

  // ---- data ----
  Scene sc_;
  SimulationOptions opt_;
  SimulationObserver* obs_;
  Sampler sampler_;
  EnergyAudit audit_;
  AccumulationDetector accumulation_;
  ContactLaws laws_;
  int nc_ = 0;
  Eigen::Vector3d minv_;
  // The point and obstacle of each contact, looked up once: Scene::point_of and obstacle_of
  // divide, and the Moreau–Jean step asks for every contact at every step.
  std::array<const ContactPoint*, kMaxC> point_{};
  std::array<const HalfPlane*, kMaxC> plane_{};
  std::array<double, kMaxC> mu_{}, reach_{};
  std::array<ContactMode, kMaxC> mode_{};
  std::array<long, kMaxC> hit_step_{};  // Moreau–Jean step of each contact's last impact
  PersistentContactProblem pp_;  // the Moreau–Jean step's, kept to spare its set-up at every step

  double t_ = 0.0;
  PlanarState st_;
  Phase phase_ = Phase::event_driven;
  SimulationResult res_;
  bool stop_ = false;
  double next_progress_ = 0.0;
  long log_index_ = 0;
};

}  // namespace fremond::detail
