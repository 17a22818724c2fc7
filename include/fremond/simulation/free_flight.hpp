#pragma once
/// @file Exact free flight of a planar rigid body under gravity: a ballistic centre and a constant
/// rotation. Between impacts the state at any time is a closed form of the state at the start of
/// the flight, so the energy is constant to rounding however long the flight.
#include <cmath>

#include "fremond/scenes/kinematics.hpp"
#include "fremond/scenes/scene.hpp"

namespace fremond {

/// A flight from `start` at time t0 (the absolute time is only carried along; every formula uses
/// the elapsed time s = t − t0, so that late flights lose no precision).
struct FreeFlight {
  double t0 = 0.0;
  PlanarState start;
  double gravity = 0.0;

  /// The state after an elapsed time s ≥ 0: x = x₀ + ẋ₀s, y = y₀ + ẏ₀s − gs²/2, θ = θ₀ + θ̇₀s.
  PlanarState at_elapsed(double s) const {
    PlanarState out;
    out.q = {start.q.x() + start.qdot.x() * s,
             start.q.y() + start.qdot.y() * s - 0.5 * gravity * s * s,
             start.q.z() + start.qdot.z() * s};
    out.qdot = {start.qdot.x(), start.qdot.y() - gravity * s, start.qdot.z()};
    return out;
  }
};

/// The gap of one contact along a free flight, in closed form (s = t − t0, φ = θ₀ + ωs):
///   g(s) = α + βs + γs² + A cos φ + B sin φ,
/// with α = n·c₀ − offset − ρ, β = n·ċ₀, γ = −n_y g/2, A = n·r, B = n_y r_x − n_x r_y, so that
///   |g''| ≤ K = 2|γ| + ω²|r|  and  |g'''| ≤ L = |ω|³|r|,
/// the bounds that make the event search exhaustive (no root can hide between samples).
struct GapFunction {
  double alpha = 0.0, beta = 0.0, gamma = 0.0;
  double A = 0.0, B = 0.0, theta0 = 0.0, omega = 0.0;
  double K = 0.0;  ///< bound on |g''| over the whole flight (m/s²).
  double L = 0.0;  ///< bound on |g'''| over the whole flight (m/s³).

  /// The gap of `point` against `plane` (unit normal) along `flight`.
  static GapFunction make(const ContactPoint& point, const HalfPlane& plane,
                          const FreeFlight& flight) {
    const Eigen::Vector2d& n = plane.normal;
    const auto& q = flight.start.q;
    const auto& v = flight.start.qdot;
    GapFunction f;
    f.alpha = n.x() * q.x() + n.y() * q.y() - plane.offset - point.radius;
    f.beta = n.x() * v.x() + n.y() * v.y();
    f.gamma = -0.5 * n.y() * flight.gravity;
    f.A = n.x() * point.r.x() + n.y() * point.r.y();
    f.B = n.y() * point.r.x() - n.x() * point.r.y();
    f.theta0 = q.z();
    f.omega = v.z();
    const double R = std::hypot(f.A, f.B);
    const double w = std::fabs(f.omega);
    // A relative margin covers the rounding of the bounds themselves.
    constexpr double kMargin = 1.0 + 1e-12;
    f.K = (2.0 * std::fabs(f.gamma) + w * w * R) * kMargin;
    f.L = w * w * w * R * kMargin;
    return f;
  }

  /// g, g', g'' at elapsed time s.
  void eval(double s, double& g, double& gd, double& gdd) const {
    const double phi = theta0 + omega * s;
    const double c = std::cos(phi), sn = std::sin(phi);
    const double rot = A * c + B * sn;
    g = alpha + (beta + gamma * s) * s + rot;
    gd = beta + 2.0 * gamma * s + omega * (B * c - A * sn);
    gdd = 2.0 * gamma - omega * omega * rot;
  }
  double value(double s) const {
    double g, gd, gdd;
    eval(s, g, gd, gdd);
    return g;
  }
};

}  // namespace fremond
