// Accumulations of impacts: detecting one and closing it (simulate.hpp, detail/accumulation.hpp).
#include "simulation/detail/accumulation.hpp"

#include <algorithm>

#include "simulation/detail/impact_record.hpp"
#include "simulation/detail/min_norm_solve.hpp"
#include "simulation/detail/run.hpp"
#include "simulation/detail/ulp.hpp"

namespace fremond::detail {

std::optional<double> AccumulationDetector::add(double t, const SimulationOptions& options) {
  const int N = options.accumulation_impacts;
  if (n_times_ == static_cast<int>(times_.size())) {
    std::copy(times_.begin() + 1, times_.end(), times_.begin());
    --n_times_;
  }
  times_[n_times_++] = t;
  if (n_times_ < N + 1) return std::nullopt;
  const double* tt = times_.data() + n_times_ - (N + 1);
  bool geometric = true, stuck = true;
  for (int j = 0; j < N; ++j) {
    const double d = tt[j + 1] - tt[j];
    geometric =
        geometric && d <= options.accumulation_interval && (j == 0 || d < tt[j] - tt[j - 1]);
    stuck = stuck && d <= 16.0 * ulp(t);
  }
  if (!geometric && !stuck) return std::nullopt;
  double tail = 0.0;
  if (geometric) {
    const double last = tt[N] - tt[N - 1], prev = tt[N - 1] - tt[N - 2];
    const double r = last / prev;  // < 1: the intervals decrease strictly
    tail = std::min(last * r / (1.0 - r), options.t_end - t);
  }
  return tail;
}

AccumulationClosing close_normal_velocities(const ContactNormals& W_N, const Eigen::Vector3d& minv,
                                            const Eigen::Vector3d& qdot) {
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxSceneContacts,
                              kMaxSceneContacts>;
  const Small G = W_N.transpose() * minv.asDiagonal() * W_N;
  const auto lambda = min_norm_solve(G, (W_N.transpose() * qdot).eval());
  return {lambda, qdot - minv.cwiseProduct(W_N * lambda)};
}

// Closes an accumulation: the touching contacts lose the small normal velocity of their bounce,
// which the tail of impacts would damp to zero. Moreau–Jean then integrates the tail from here,
// with the contacts closed: the other contacts, the rotation and friction go on as in any
// persistent contact. `tail` is the extrapolated remaining time t∞ − t, for the log.
void Run::close_accumulation(double tail) {
  const double c = std::cos(st_.q.z()), s = std::sin(st_.q.z());
  std::array<int, kMaxC> idx;
  std::array<ContactFrame, kMaxC> f;
  int n = 0;
  for (int k = 0; k < nc_; ++k) {
    f[n] = frame(k, st_.q, c, s);
    if (f[n].gap <= opt_.gap_tolerance) idx[n++] = k;
  }
  if (n == 0) return;
  ContactNormals Wc(3, n);
  for (int i = 0; i < n; ++i) Wc.col(i) = f[i].W_N;
  const AccumulationClosing closing = close_normal_velocities(Wc, minv_, st_.qdot);
  PlanarState after = st_;
  after.qdot = closing.qdot;
  const double e_a = energy(sc_, st_), e_e = energy(sc_, after);
  if (obs_)
    obs_->on_impact(accumulation_record(log_index_, t_, idx.data(), f.data(), n, st_, after.qdot,
                                        closing.lambda, e_a, e_e, t_ + tail));
  ++log_index_;
  if (res_.accumulations++ == 0) res_.first_accumulation_time = t_ + tail;
  st_ = after;
  audit_.record(e_e, false);
  sample(t_, st_);
}

}  // namespace fremond::detail
