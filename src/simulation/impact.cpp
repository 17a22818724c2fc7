// An impact with the scene's law on some of its contacts: the problem posed in contact space,
// solved by solve_impact, logged, counted and audited.
#include <cmath>

#include "fremond/core/error.hpp"
#include "fremond/core/impact_problem.hpp"
#include "fremond/solvers/solve_impact.hpp"
#include "simulation/detail/impact_record.hpp"
#include "simulation/detail/reached_impact.hpp"
#include "simulation/detail/run.hpp"

namespace fremond::detail {

bool Run::impact(double t, PlanarState& s, const int* idx, int n, ImpactKind kind) {
  const ImpactLaw& law = laws_.of(idx, n);
  if (n <= kSmallContacts) {
    SmallImpactProblem pb;
    fill(pb, s, idx, n);
    return solve_and_record(t, s, idx, n, kind, pb, law);
  }
  ImpactProblem pb;
  fill(pb, s, idx, n);
  return solve_and_record(t, s, idx, n, kind, pb, law);
}

template <class Problem>
void Run::fill(Problem& pb, const PlanarState& s, const int* idx, int n) const {
  const double c = std::cos(s.q.z()), sn = std::sin(s.q.z());
  pb.M = sc_.body.mass_matrix();
  pb.W_N.resize(3, n);
  pb.W_T.resize(3, n);
  pb.w_N.setZero(n);
  pb.w_T.setZero(n);
  pb.qdot_A = s.qdot;
  for (int i = 0; i < n; ++i) {
    const ContactFrame f = frame(idx[i], s.q, c, sn);
    pb.W_N.col(i) = f.W_N;
    pb.W_T.col(i) = f.W_T;
  }
}

template <class Problem>
bool Run::solve_and_record(double t, PlanarState& s, const int* idx, int n, ImpactKind kind,
                           const Problem& pb, const ImpactLaw& law) {
  const auto r = detail::solve_reached_impact(pb, law, opt_.solver);
  if (!r) {
    finish(SimulationStatus::impact_failed, detail::kImpactOverflow);
    return false;
  }
  return record(t, s, idx, n, kind, *r);
}

template <class Result>
bool Run::record(double t, PlanarState& s, const int* idx, int n, ImpactKind kind,
                 const Result& r) {
  const double e_a = energy(sc_, s);
  PlanarState after = s;
  if (r.ok()) after.qdot = r.qdot_E.template head<3>();
  const double e_e = energy(sc_, after);
  const bool admissible = r.admissibility.admissible;
  if (obs_)
    obs_->on_impact(law_impact_record(log_index_, t, kind, idx, n, s, after.qdot, e_a, e_e, r));
  ++log_index_;
  if (!r.ok()) {
    finish(SimulationStatus::impact_failed, r.solver.message);
    return false;
  }
  ++res_.impacts;
  if (kind == ImpactKind::event) ++res_.event_impacts;
  if (!admissible) {
    if (res_.inadmissible_impacts++ == 0) res_.first_inadmissible_time = t;
  }
  audit_.record(e_e, !admissible);
  s = after;
  if (res_.impacts >= opt_.max_impacts) {
    finish(SimulationStatus::max_impacts, "stopped after the largest number of impacts allowed");
    return false;
  }
  return true;
}

}  // namespace fremond::detail
