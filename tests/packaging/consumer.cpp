// An outside project: one point-mass impact with Frémond's p = 2 law, checked against eq. (24).
#include <cmath>
#include <cstdio>

#include <fremond/fremond.hpp>

int main() {
  fremond::ImpactProblem pb;
  pb.M = Eigen::MatrixXd::Identity(1, 1);
  pb.W_N = Eigen::MatrixXd::Ones(1, 1);
  pb.qdot_A = Eigen::VectorXd::Constant(1, -2.0);
  const double k = 6.0, m = 1.0;
  const auto law = fremond::ImpactLaw::fremond(fremond::PowerPotential(k, 2.0));
  const auto r = fremond::solve_impact(pb, law);
  const double eps = (k - 2 * m) / (k + 2 * m);
  const bool ok =
      r.ok() && std::fabs(r.qdot_E(0) - 2.0 * eps) < 1e-12 && r.admissibility.admissible;
  std::printf("qdot_E = %.17g (expected %.17g) %s\n", r.qdot_E(0), 2.0 * eps, ok ? "ok" : "WRONG");
  return ok ? 0 : 1;
}
