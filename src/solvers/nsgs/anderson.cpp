// Anderson mixing (anderson.hpp).
#include "solvers/nsgs/anderson.hpp"

#include <algorithm>
#include <cmath>

namespace fremond::detail {

void AndersonMixing::mix(const Eigen::VectorXd& x, Eigen::VectorXd& g) {
  const Eigen::Index n = g.size();
  f_ = g - x;
  const double norm = f_.norm();
  if (!std::isfinite(norm)) {
    reset();
    return;
  }
  if (dF_.rows() != n || dF_.cols() != depth_) {
    dF_.resize(n, depth_);
    dG_.resize(n, depth_);
    gram_.resize(depth_, depth_);
    reset();
  }
  if (has_last_ && norm > 2.0 * last_norm_) {
    count_ = head_ = 0;
  } else if (has_last_) {
    const int h = head_;
    dF_.col(h) = f_ - f_last_;
    dG_.col(h) = g - g_last_;
    head_ = (head_ + 1) % depth_;
    count_ = std::min(count_ + 1, depth_);
    for (int k = 0; k < count_; ++k) gram_(h, k) = gram_(k, h) = dF_.col(h).dot(dF_.col(k));
  }
  f_last_.swap(f_);  // f_last_ holds this call's residual from here on
  g_last_ = g;
  last_norm_ = norm;
  has_last_ = true;
  if (count_ == 0) return;
  // Regularised normal equations: the differences are often nearly dependent.
  const int m = count_;
  system_ = gram_.topLeftCorner(m, m);
  system_.diagonal().array() += 1e-12 * system_.diagonal().maxCoeff() + 1e-300;
  rhs_.noalias() = dF_.leftCols(m).transpose() * f_last_;
  ldlt_.compute(system_);
  gamma_ = ldlt_.solve(rhs_);
  if (!gamma_.allFinite()) {
    count_ = head_ = 0;
    return;
  }
  g.noalias() -= dG_.leftCols(m) * gamma_;
}

}  // namespace fremond::detail
