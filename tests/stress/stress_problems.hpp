#pragma once
/// @file The random problems and laws of the stress runs (see stress_main.cpp for the list).
#include <Eigen/QR>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "fremond/fremond.hpp"
#include "support/fixtures.hpp"

namespace fremond::robust {

struct StressCase {
  ImpactProblem problem;
  ImpactLaw law;
  std::string shape;  ///< which generator made the problem (for the summary)
};

class Draw {
 public:
  explicit Draw(std::mt19937_64& rng) : rng_(rng) {}

  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  double decades(double lo, double hi) { return std::pow(10.0, uniform(lo, hi)); }

  // Parameters over their whole valid ranges, with the edge values exactly.
  double restitution() {
    const double u = uniform(0.0, 1.0);
    if (u < 0.2) return 0.0;
    if (u < 0.4) return 1.0;
    return uniform(0.0, 1.0);
  }
  double friction() {
    const double u = uniform(0.0, 1.0);
    if (u < 0.1) return 0.0;
    if (u < 0.2) return 1e8;  // μ → ∞
    return decades(-3.0, 3.0);
  }
  double exponent() {  // p, q in (1, ∞)
    const double u = uniform(0.0, 1.0);
    if (u < 0.2) return 2.0;
    if (u < 0.3) return 1.0 + decades(-6.0, -2.0);
    if (u < 0.4) return decades(1.0, 1.7);  // 10 to 50
    return uniform(1.05, 6.0);
  }
  double stiffness() { return chance(0.05) ? 0.0 : decades(-6.0, 6.0); }
  double dead_zone(double v) {  // r: 0, inside the velocities, or above every one
    const double u = uniform(0.0, 1.0);
    if (u < 0.2) return 0.0;
    if (u < 0.3) return 10.0 * v;
    return v * decades(-4.0, 0.0);
  }

  template <class F>
  PerContact per_contact(int c, F draw) {
    if (chance(0.5)) return PerContact(draw());
    std::vector<double> v(c);
    for (double& x : v) x = draw();
    return PerContact(std::move(v));
  }
  template <class F>
  PerContactPotential potentials(int c, F make) {
    PerContactPotential out;
    const int count = chance(0.5) ? 1 : c;
    for (int i = 0; i < count; ++i) out.potentials.emplace_back(make());
    return out;
  }

  /// M = Q diag(d) Qᵀ with condition up to `cond` and a mass scale over six decades.
  Eigen::MatrixXd mass_matrix(int n, double cond) {
    Eigen::MatrixXd A(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = uniform(-1.0, 1.0);
    const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(A).householderQ();
    Eigen::VectorXd d(n);
    const double scale = decades(-3.0, 3.0);
    for (int i = 0; i < n; ++i) d(i) = scale * std::pow(cond, n > 1 ? uniform(0.0, 1.0) : 0.0);
    if (n > 1) {  // reach the condition: the extremes at both ends
      d(0) = scale;
      d(n - 1) = scale * cond;
    }
    Eigen::MatrixXd M = Q * d.asDiagonal() * Q.transpose();
    return 0.5 * (M + M.transpose());
  }

  /// A random problem; n ≤ 6, c ≤ 4, with exact degeneracies now and then.
  ImpactProblem random_problem(bool tangential, std::string& shape) {
    const int n = integer(1, 6), c = integer(1, 4);
    const double cond = chance(0.3) ? decades(9.0, 12.0) : decades(0.0, 9.0);
    ImpactProblem pb;
    pb.M = mass_matrix(n, cond);
    pb.W_N.resize(n, c);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < c; ++j) pb.W_N(i, j) = uniform(-1.0, 1.0);
    if (tangential) {
      pb.W_T.resize(n, c);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < c; ++j) pb.W_T(i, j) = uniform(-1.0, 1.0);
    } else {
      pb.W_T.resize(n, 0);
    }
    shape = cond > 1e9 ? "random_cond>1e9" : "random";
    const double u = uniform(0.0, 1.0);
    if (u < 0.04 && c > 1) {  // a repeated contact row
      pb.W_N.col(c - 1) = pb.W_N.col(0);
      shape = "repeated_row";
    } else if (u < 0.08 && tangential) {  // tangent parallel to the normal
      pb.W_T.col(0) = pb.W_N.col(0);
      shape = "W_T_parallel_W_N";
    } else if (u < 0.10 && c > 1) {  // a contact that cannot move, touching (D_NA = 0)
      pb.W_N.col(c - 1).setZero();
      if (tangential) pb.W_T.col(c - 1).setZero();
      shape = "immobile_contact";
    } else if (u < 0.14) {  // a direction along one coordinate: sparse, decoupled rows
      pb.W_N.col(0).setZero();
      pb.W_N(integer(0, n - 1), 0) = 1.0;
      shape = "axis_direction";
    }
    const double v = decades(-12.0, 8.0);
    pb.qdot_A.resize(n);
    for (int i = 0; i < n; ++i) pb.qdot_A(i) = v * uniform(-1.0, 1.0);
    approach(pb, 0);
    if (c > 1 &&
        chance(0.1)) {  // a contact exactly touching: D_NA = 0 (as nearly as rounding allows)
      const Eigen::VectorXd w = pb.W_N.col(c - 1);
      if (w.squaredNorm() > 0) pb.qdot_A -= (w.dot(pb.qdot_A) / w.squaredNorm()) * w;
      approach(pb, 0);
      shape += "+touching";
    }
    if (chance(0.1)) {  // moving obstacles
      pb.w_N.resize(c);
      for (int j = 0; j < c; ++j) pb.w_N(j) = v * uniform(-1.0, 1.0);
      if (tangential) {
        pb.w_T.resize(c);
        for (int j = 0; j < c; ++j) pb.w_T(j) = v * uniform(-1.0, 1.0);
      }
      shape += "+moving_obstacles";
    }
    return pb;
  }

  /// The paper's bar (fixtures.hpp) near the degenerate angles, one or both ends, of mass m.
  ImpactProblem bar(bool tangential, std::string& shape) {
    const double m = decades(-3.0, 3.0);
    double theta;
    const double u = uniform(0.0, 1.0);
    if (u < 0.35) {
      theta = decades(-12.0, -1.0);  // θ → 0
      shape = "bar_theta_to_0";
    } else if (u < 0.7) {
      theta = std::numbers::pi / 2 - decades(-12.0, -1.0);  // θ → π/2
      shape = "bar_theta_to_pi/2";
    } else if (u < 0.8) {
      theta = chance(0.5) ? 0.0 : std::numbers::pi / 2;
      shape = "bar_theta_exact";
    } else {
      theta = uniform(0.0, std::numbers::pi / 2);
      shape = "bar";
    }
    const int c = chance(0.5) ? 2 : 1;
    if (c == 2) shape += "_both_ends";
    ImpactProblem pb = fixtures::bar(theta, Eigen::Vector3d::Zero(), c == 2, m, tangential);
    const double v = decades(-12.0, 8.0);
    pb.qdot_A =
        Eigen::Vector3d(v * uniform(-2.0, 2.0), -v * uniform(0.0, 1.0), v * uniform(-3.0, 3.0));
    approach(pb, 0);
    return pb;
  }

  /// Point masses (decoupled contacts): the exact one-contact methods.
  ImpactProblem point(bool tangential, std::string& shape) {
    shape = "point_mass";
    const double m = decades(-3.0, 3.0), v = decades(-12.0, 8.0);
    ImpactProblem pb;
    const int n = tangential ? 2 : 1;
    pb.M = m * Eigen::MatrixXd::Identity(n, n);
    pb.W_N = Eigen::MatrixXd::Zero(n, 1);
    pb.W_N(n - 1, 0) = 1.0;
    pb.W_T = Eigen::MatrixXd::Zero(n, tangential ? 1 : 0);
    if (tangential) pb.W_T(0, 0) = 1.0;
    pb.qdot_A = Eigen::VectorXd(n);
    pb.qdot_A(n - 1) = -v * uniform(0.0, 1.0);
    if (tangential) pb.qdot_A(0) = v * uniform(-3.0, 3.0) * (chance(0.1) ? 0.0 : 1.0);
    return pb;
  }

  ImpactLaw law(const std::string& name, int c, double v) {
    if (name == "newton") return ImpactLaw::newton(per_contact(c, [&] { return restitution(); }));
    if (name == "poisson") return ImpactLaw::poisson(per_contact(c, [&] { return restitution(); }));
    if (name == "newton_coulomb")
      return ImpactLaw::newton_coulomb(per_contact(c, [&] { return restitution(); }),
                                       per_contact(c, [&] { return friction(); }));
    if (name == "poisson_coulomb")
      return ImpactLaw::poisson_coulomb(per_contact(c, [&] { return restitution(); }),
                                        per_contact(c, [&] { return friction(); }));
    auto normal =
        potentials(c, [&] { return std::make_unique<PowerPotential>(stiffness(), exponent()); });
    if (name == "fremond") return ImpactLaw::fremond(std::move(normal));
    if (name == "fremond_viscous")
      return ImpactLaw::fremond(
          std::move(normal), potentials(c, [&]() -> PotentialPtr {
            const double u = uniform(0.0, 1.0);
            if (u < 0.1) return std::make_unique<AbsoluteValuePotential>(v * decades(-3.0, 3.0));
            if (u < 0.15)
              return DeadZonePowerPotential(stiffness(), exponent(), dead_zone(v)) +
                     AbsoluteValuePotential(v * decades(-3.0, 1.0));
            return std::make_unique<DeadZonePowerPotential>(stiffness(), exponent(), dead_zone(v));
          }));
    return ImpactLaw::fremond_coulomb(std::move(normal),
                                      per_contact(c, [&] { return friction(); }));
  }

 private:
  // Makes contact j approach (D_NA < 0) by reflecting q̇_A in the plane of its direction.
  static void approach(ImpactProblem& pb, int j) {
    const Eigen::VectorXd w = pb.W_N.col(j);
    const double dn = w.dot(pb.qdot_A);
    if (dn > 0.0 && w.squaredNorm() > 0.0) pb.qdot_A -= (2.0 * dn / w.squaredNorm()) * w;
  }

  std::mt19937_64& rng_;
};

/// One case for the law `name` (stress_main.cpp's list).
inline StressCase draw_case(std::mt19937_64& rng, const std::string& name) {
  Draw d(rng);
  StressCase sc;
  const bool tangential = name != "newton" && name != "poisson" && name != "fremond"
                              ? true
                              : d.chance(0.3);  // frictionless laws ignore W_T: give it anyway
  const double u = d.uniform(0.0, 1.0);
  if (u < 0.6)
    sc.problem = d.random_problem(tangential, sc.shape);
  else if (u < 0.85)
    sc.problem = d.bar(tangential, sc.shape);
  else
    sc.problem = d.point(tangential, sc.shape);
  double v = 0.0;
  for (int i = 0; i < sc.problem.qdot_A.size(); ++i)
    v = std::max(v, std::fabs(sc.problem.qdot_A(i)));
  sc.law = d.law(name, sc.problem.contacts(), v > 0 ? v : 1.0);
  return sc;
}

}  // namespace fremond::robust
