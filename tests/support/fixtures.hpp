#pragma once
/// @file The problems shared by the tests, the stress runs and the benchmarks, defined once: the
/// paper's bar (its Fig. 1) at any angle and at its first impact, the bar lying flat on both ends,
/// the plate on many contacts, point masses, random problems of a fixed seed; and the bar's Frémond
/// laws. The benchmarks time these
/// very numbers (bench/problems.hpp adds their closed-form answers and the random problems).
///
/// Conventions are docs/concepts.md: `D = Wᵀ q̇ + w`, `G = Wᵀ M⁻¹ W`, P_N ≥ 0 pushes the bodies
/// apart.
#include <cmath>
#include <cstdint>
#include <numbers>

#include <Eigen/Dense>
#include <fremond/fremond.hpp>

namespace fremond::fixtures {

// ---------------------------------------------------------------------------------------------
// The scene of the paper's Fig. 1.

inline constexpr double kMass = 1.0;                                       ///< m, kg.
inline constexpr double kHalfLength = 0.5;                                 ///< l, m.
inline constexpr double kInertia = kMass * kHalfLength * kHalfLength / 3;  ///< J = m l²/3.
inline constexpr double kGravity = 9.81;                                   ///< g, m/s².
inline constexpr double kRestitution = 0.9;                                ///< Newton's e (§3).
inline constexpr double kFriction = 1.0;                                   ///< μ (§4).
inline constexpr double kTheta0 = std::numbers::pi / 4;                    ///< θ at t = 0.
inline constexpr double kY0 = 1.0;                                         ///< y at t = 0.
inline constexpr double kXdot0 = 2.0;                                      ///< ẋ at t = 0.

/// M = diag(m, m, J) for q = (x, y, θ).
inline SmallImpactProblem::Mat bar_mass() {
  SmallImpactProblem::Mat M = SmallImpactProblem::Mat::Zero(3, 3);
  M(0, 0) = kMass;
  M(1, 1) = kMass;
  M(2, 2) = kInertia;
  return M;
}

/// Normal and tangential directions of the bar's end s = ±1, at (x + s l cos θ, y + s l sin θ):
/// W_N = (0, 1, s l cos θ), W_T = (1, 0, −s l sin θ). For s = −1, θ = π/4 these are the paper's.
inline Eigen::Vector3d bar_end_normal(double s, double theta) {
  return {0.0, 1.0, s * kHalfLength * std::cos(theta)};
}
inline Eigen::Vector3d bar_end_tangent(double s, double theta) {
  return {1.0, 0.0, -s * kHalfLength * std::sin(theta)};
}

/// The bar at angle θ with its lower end (s = −1) on the ground, and with `both_ends` its upper end
/// (s = +1) too, in that order; mass m, J = m l²/3; without `tangential` W_T has no column.
inline ImpactProblem bar(double theta, const Eigen::Vector3d& qdot, bool both_ends = false,
                         double m = kMass, bool tangential = true) {
  const double l = kHalfLength;
  ImpactProblem pb;
  pb.M = MatrixX::Zero(3, 3);
  pb.M.diagonal() << m, m, m * l * l / 3.0;
  const int c = both_ends ? 2 : 1;
  pb.W_N.resize(3, c);
  pb.W_T.resize(3, tangential ? c : 0);
  for (int i = 0; i < c; ++i) {
    const double s = (i == 0) ? -1.0 : 1.0;
    pb.W_N.col(i) << 0.0, 1.0, s * l * std::cos(theta);
    if (tangential) pb.W_T.col(i) << 1.0, 0.0, -s * l * std::sin(theta);
  }
  pb.qdot_A = qdot;
  return pb;
}

/// The bar at its first impact from the paper's initial state, heap-stored: a free fall from y = 1
/// until the lower end touches (centre at l sin θ), ẋ = 2, θ̇ = 0, ẏ = −√(2 g (1 − l sin θ)).
inline ImpactProblem paper_bar_first_impact() {
  const double th = kTheta0;
  const double drop = kY0 - kHalfLength * std::sin(th);
  return bar(th, Eigen::Vector3d(kXdot0, -std::sqrt(2.0 * kGravity * drop), 0.0));
}

/// A point mass m hitting the ground with normal velocity v < 0: q = y, or with `tangential`
/// q = (x, y) and tangential velocity vt.
inline ImpactProblem point_mass(double m, double v, double vt = 0.0, bool tangential = false) {
  ImpactProblem pb;
  const int n = tangential ? 2 : 1;
  pb.M = m * MatrixX::Identity(n, n);
  pb.W_N = MatrixX::Zero(n, 1);
  pb.W_N(n - 1, 0) = 1.0;
  if (tangential) {
    pb.W_T = MatrixX::Zero(n, 1);
    pb.W_T(0, 0) = 1.0;
    pb.qdot_A = Eigen::Vector2d(vt, v);
  } else {
    pb.qdot_A = VectorX::Constant(1, v);
  }
  return pb;
}

/// Time of the first impact from the initial state of the paper's Fig. 1: the bar falls without
/// turning (θ̇ = 0, no torque) until its lower end, at height y − l sin θ, reaches the ground.
inline double bar_first_impact_time() {
  return std::sqrt(2.0 * (kY0 - kHalfLength * std::sin(kTheta0)) / kGravity);
}

/// The bar at its first impact (the paper's Fig. 1): one contact, the lower end (s = −1) at θ =
/// π/4, with q̇_A = (2, −g t₁, 0), so D_NA = −g t₁ ≈ −3.5613 and D_TA = 2. Without friction W_T has
/// no column.
inline SmallImpactProblem bar_first_impact(bool with_friction = true) {
  SmallImpactProblem p;
  p.M = bar_mass();
  p.W_N = bar_end_normal(-1.0, kTheta0);
  p.W_T = with_friction ? SmallImpactProblem::Jac(bar_end_tangent(-1.0, kTheta0))
                        : SmallImpactProblem::Jac(3, 0);
  p.w_N = SmallImpactProblem::CVec::Zero(1);
  p.w_T = SmallImpactProblem::CVec::Zero(with_friction ? 1 : 0);
  p.qdot_A = Eigen::Vector3d(kXdot0, -kGravity * bar_first_impact_time(), 0.0);
  return p;
}

/// The bar lying flat (θ = 0) and hitting the ground with both ends: q̇_A = (2, −3, 1), so
/// D_NA = (−2.5, −3.5) and D_TA = (2, 2). Two contacts and three degrees of freedom: G_NN =
/// [[4, −2], [−2, 4]] is regular, but the 4×4 G with the friction rows has rank 3 (both tangents
/// are (1, 0, 0)), so under Coulomb the split of P_T between the ends is not unique.
inline SmallImpactProblem flat_bar_two_contacts(bool with_friction = true) {
  SmallImpactProblem p;
  p.M = bar_mass();
  p.W_N.resize(3, 2);
  p.W_N << bar_end_normal(1.0, 0.0), bar_end_normal(-1.0, 0.0);
  if (with_friction) {
    p.W_T.resize(3, 2);
    p.W_T << bar_end_tangent(1.0, 0.0), bar_end_tangent(-1.0, 0.0);
  } else {
    p.W_T.resize(3, 0);
  }
  p.w_N = SmallImpactProblem::CVec::Zero(2);
  p.w_T = SmallImpactProblem::CVec::Zero(with_friction ? 2 : 0);
  p.qdot_A = Eigen::Vector3d(kXdot0, -3.0, 1.0);
  return p;
}

/// A point mass m in the plane, q = (x, y), on the ground y = 0, with q̇_A = (2, −1): D_NA = −1,
/// D_TA = 2 and G = I/m. Under Newton + Coulomb at e = 0.9, μ = 1 (m = 1) it slides.
inline SmallImpactProblem planar_point_mass(double m = 1.0, bool with_friction = true) {
  SmallImpactProblem p;
  p.M = SmallImpactProblem::Mat::Identity(2, 2) * m;
  p.W_N = Eigen::Vector2d(0.0, 1.0);
  p.W_T = with_friction ? SmallImpactProblem::Jac(Eigen::Vector2d(1.0, 0.0))
                        : SmallImpactProblem::Jac(2, 0);
  p.w_N = SmallImpactProblem::CVec::Zero(1);
  p.w_T = SmallImpactProblem::CVec::Zero(with_friction ? 1 : 0);
  p.qdot_A = Eigen::Vector2d(2.0, -1.0);
  return p;
}

/// A flat plate (the bar, lying at θ = 0) touching the ground at c points spread evenly over its
/// length, all approaching: q̇_A = (2, −3, 1) gives D_NA,i = −3 + x_i ∈ [−3.5, −2.5]. Three
/// degrees of freedom, so G is singular from c = 4 on (c = 2 with the friction rows). Dynamic.
inline ImpactProblem plate_many_contacts(int c, bool with_friction) {
  ImpactProblem p;
  p.M = Eigen::MatrixXd(bar_mass());
  p.W_N.resize(3, c);
  p.W_T.resize(3, with_friction ? c : 0);
  for (int i = 0; i < c; ++i) {
    const double x = c == 1 ? -kHalfLength : -kHalfLength + 2.0 * kHalfLength * i / (c - 1);
    p.W_N.col(i) << 0.0, 1.0, x;
    if (with_friction) p.W_T.col(i) << 1.0, 0.0, 0.0;
  }
  p.w_N = Eigen::VectorXd::Zero(c);
  p.w_T = Eigen::VectorXd::Zero(with_friction ? c : 0);
  p.qdot_A = Eigen::Vector3d(kXdot0, -3.0, 1.0);
  return p;
}

/// Two point masses in one problem, q = (x₁, y₁, x₂, y₂), one contact each, with q̇_A = (2, −3,
/// 1e-9, −2e-9): G couples nothing, so the contacts form two independent groups, 1e9 apart in
/// speed.
inline SmallImpactProblem two_point_masses(bool with_friction = true) {
  SmallImpactProblem p;
  p.M = SmallImpactProblem::Mat::Identity(4, 4);
  p.W_N = SmallImpactProblem::Jac::Zero(4, 2);
  p.W_N(1, 0) = p.W_N(3, 1) = 1.0;
  p.W_T = SmallImpactProblem::Jac::Zero(4, with_friction ? 2 : 0);
  if (with_friction) p.W_T(0, 0) = p.W_T(2, 1) = 1.0;
  p.qdot_A = SmallImpactProblem::Vec(4);
  p.qdot_A << 2.0, -3.0, 1e-9, -2e-9;
  return p;
}

/// SplitMix64: a generator whose numbers are the same with every standard library (the standard
/// distributions are not), so the random problems are the same everywhere.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(next() >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_;
};

inline constexpr std::uint64_t kRandomSeed = 20240611;  ///< the fixed seed of the random problems.
inline constexpr int kRandomProblems = 16;              ///< how many the benchmarks cycle through.

/// Random problem `index` (0 ≤ index) with n degrees of freedom and c contacts, heap-stored:
/// M = A Aᵀ/n + I/2 (eigenvalues from 0.5), W_N, W_T, q̇_A with entries uniform in [−1, 1); each
/// W_N column is flipped if needed so that every contact takes part (D_NA < 0).
inline ImpactProblem random_problem_any(int n, int c, int index, bool with_friction) {
  SplitMix64 rng(kRandomSeed + 0x1000ULL * static_cast<std::uint64_t>(index) +
                 (n == 6 && c == 3 ? 0ULL : 0x9E37ULL * static_cast<std::uint64_t>(n * 64 + c)));
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = rng.uniform(-1.0, 1.0);
  ImpactProblem p;
  p.M = A * A.transpose() / n + 0.5 * Eigen::MatrixXd::Identity(n, n);
  p.W_N.resize(n, c);
  Eigen::MatrixXd WT(n, c);
  for (int j = 0; j < c; ++j)
    for (int i = 0; i < n; ++i) {
      p.W_N(i, j) = rng.uniform(-1.0, 1.0);
      WT(i, j) = rng.uniform(-1.0, 1.0);
    }
  p.qdot_A.resize(n);
  for (int i = 0; i < n; ++i) p.qdot_A(i) = rng.uniform(-1.0, 1.0);
  for (int j = 0; j < c; ++j)
    if (p.W_N.col(j).dot(p.qdot_A) > 0) p.W_N.col(j) *= -1.0;
  p.W_T = with_friction ? WT : Eigen::MatrixXd(n, 0);
  p.w_N = Eigen::VectorXd::Zero(c);
  p.w_T = Eigen::VectorXd::Zero(with_friction ? c : 0);
  return p;
}

/// random_problem_any with n = 6 degrees of freedom and 3 contacts, in the small form.
inline SmallImpactProblem random_spd_problem(int index, bool with_friction = true) {
  return to_small(random_problem_any(6, 3, index, with_friction));
}

// ---------------------------------------------------------------------------------------------
// Derived quantities and answers in closed form.

/// The contact-space data of a problem (docs/concepts.md), rows ordered contact by contact as (N,
/// T): G = Wᵀ M⁻¹ W with W = [W_N,1, W_T,1, W_N,2, W_T,2, ...] (frictionless: only the N rows), and
/// D_A = Wᵀ q̇_A + w. This is Siconos's ordering of a friction-contact problem.
struct ContactSpace {
  Eigen::MatrixXd W;    ///< n × rows.
  Eigen::MatrixXd G;    ///< rows × rows.
  Eigen::VectorXd D_A;  ///< rows.
  int contacts = 0;
  int rows_per_contact = 1;  ///< 2 with friction, else 1.
};

inline ContactSpace contact_space(const SmallImpactProblem& p) {
  ContactSpace cs;
  cs.contacts = p.contacts();
  cs.rows_per_contact = p.has_tangential() ? 2 : 1;
  const int n = p.dofs(), r = cs.rows_per_contact;
  cs.W.resize(n, r * cs.contacts);
  cs.D_A.resize(r * cs.contacts);
  for (int i = 0; i < cs.contacts; ++i) {
    cs.W.col(r * i) = p.W_N.col(i);
    cs.D_A(r * i) = p.W_N.col(i).dot(p.qdot_A) + (p.w_N.size() ? p.w_N(i) : 0.0);
    if (r == 2) {
      cs.W.col(r * i + 1) = p.W_T.col(i);
      cs.D_A(r * i + 1) = p.W_T.col(i).dot(p.qdot_A) + (p.w_T.size() ? p.w_T(i) : 0.0);
    }
  }
  const Eigen::MatrixXd M = p.M;
  cs.G = cs.W.transpose() * M.ldlt().solve(cs.W);
  return cs;
}

/// q̇_E = q̇_A + M⁻¹ W P for percussions P in the row order of contact_space().
inline Eigen::VectorXd velocity_after(const SmallImpactProblem& p, const ContactSpace& cs,
                                      const Eigen::VectorXd& P) {
  const Eigen::MatrixXd M = p.M;
  return Eigen::VectorXd(p.qdot_A) + M.ldlt().solve(cs.W * P);
}

/// Frémond's k_N for the bar (docs/laws.md): with the normal law alone at the first impact, D_NE =
/// −e D_NA and P_N = (D_NE − D_NA)/G_NN = −k z|z|^(p−2) with z = (D_NA + D_NE)/2 = (1 − e) D_NA/2,
/// so k_N = (1 + e)/(G_NN ((1 − e)/2)^(p−1) |D_NA|^(p−2)); for p = 3 that is ≈ 85.36.
inline double bar_fremond_k_normal(double p, double e = kRestitution) {
  const ContactSpace cs = contact_space(bar_first_impact(false));
  const double dna = std::abs(cs.D_A(0)), gnn = cs.G(0, 0);
  return (1.0 + e) / (gnn * std::pow((1.0 - e) / 2.0, p - 1.0) * std::pow(dna, p - 2.0));
}

/// Frémond's laws for the bar as the tests use them: φ_N = k|z|³/3 with k from
/// bar_fremond_k_normal, alone, with the viscous dead zone (k_T = 1.5, q = 2, r = 0.2), or with
/// Coulomb (μ = 1).
struct BarFremondLaws {
  ImpactLaw p3, viscous, coulomb;
};
inline BarFremondLaws bar_fremond_laws() {
  const double k3 = bar_fremond_k_normal(3.0);
  return {ImpactLaw::fremond(PowerPotential(k3, 3.0)),
          ImpactLaw::fremond(PowerPotential(k3, 3.0), DeadZonePowerPotential(1.5, 2.0, 0.2)),
          ImpactLaw::fremond_coulomb(PowerPotential(k3, 3.0), 1.0)};
}

}  // namespace fremond::fixtures
