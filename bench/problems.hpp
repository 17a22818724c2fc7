#pragma once
/// @file The benchmark problems, built once here and used by every benchmark (ours and the Siconos
/// peers), so that every time printed is for the same data; and their answers in closed form, so
/// that every benchmark can check that it solved the problem it timed.
///
/// Conventions are docs/concepts.md: `D = Wᵀ q̇ + w`, `G = Wᵀ M⁻¹ W`, P_N ≥ 0 pushes the bodies
/// apart.
///
/// Labels: every benchmark that solves one of these problems sets its label with `bench_label()`,
/// e.g. "problem=bar_first_impact law=newton_coulomb". `bench/compare.py` groups Google Benchmark's
/// JSON output by label and prints each Siconos time (names starting with `BM_Siconos_`) over each
/// of ours, so a new benchmark only has to use the same label to be compared.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Dense>
#include <fremond/fremond.hpp>

namespace fremond::bench {

// ---------------------------------------------------------------------------------------------
// The scene of the paper's Fig. 1 (paper Fig. 1).

inline constexpr double kMass = 1.0;                                       ///< m, kg.
inline constexpr double kHalfLength = 0.5;                                 ///< l, m.
inline constexpr double kInertia = kMass * kHalfLength * kHalfLength / 3;  ///< J = m l²/3.
inline constexpr double kGravity = 9.81;                                   ///< g, m/s².
inline constexpr double kRestitution = 0.9;                                ///< Newton's e (§3).
inline constexpr double kFriction = 1.0;                                   ///< μ (§4).
inline constexpr double kTheta0 = std::numbers::pi / 4;                    ///< θ at t = 0.
inline constexpr double kY0 = 1.0;                                         ///< y at t = 0.
inline constexpr double kXdot0 = 2.0;                                      ///< ẋ at t = 0.

/// The label of a benchmark that solves `problem` under `law` (see the file comment).
inline std::string bench_label(std::string_view problem, std::string_view law) {
  return "problem=" + std::string(problem) + " law=" + std::string(law);
}

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
inline SmallImpactProblem point_mass(double m = 1.0, bool with_friction = true) {
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

/// Random problem number `index` (0 ≤ index): n = 6 degrees of freedom, 3 contacts with friction
/// rows, M = A Aᵀ/6 + I/2 (eigenvalues in [0.5, ~7]), W_N, W_T, q̇_A with entries uniform in
/// [−1, 1); each W_N column is flipped if needed so that every contact takes part (D_NA < 0).
inline SmallImpactProblem random_spd_problem(int index, bool with_friction = true) {
  constexpr int n = 6, c = 3;
  SplitMix64 rng(kRandomSeed + 0x1000ULL * static_cast<std::uint64_t>(index));
  Eigen::Matrix<double, n, n> A;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = rng.uniform(-1.0, 1.0);
  SmallImpactProblem p;
  p.M = A * A.transpose() / n + 0.5 * Eigen::Matrix<double, n, n>::Identity();
  p.W_N.resize(n, c);
  SmallImpactProblem::Jac WT(n, c);
  for (int j = 0; j < c; ++j)
    for (int i = 0; i < n; ++i) {
      p.W_N(i, j) = rng.uniform(-1.0, 1.0);
      WT(i, j) = rng.uniform(-1.0, 1.0);
    }
  p.qdot_A.resize(n);
  for (int i = 0; i < n; ++i) p.qdot_A(i) = rng.uniform(-1.0, 1.0);
  for (int j = 0; j < c; ++j)
    if (p.W_N.col(j).dot(p.qdot_A) > 0) p.W_N.col(j) *= -1.0;
  p.W_T = with_friction ? WT : SmallImpactProblem::Jac(n, 0);
  p.w_N = SmallImpactProblem::CVec::Zero(c);
  p.w_T = SmallImpactProblem::CVec::Zero(with_friction ? c : 0);
  return p;
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

/// Newton + Coulomb on ONE contact in closed form (docs/laws.md, paper §4): with b = (−(1+e) D_NA,
/// −D_TA) either the contact sticks, P = G⁻¹ b with |P_T| ≤ μ P_N, or it slides with P_T = −σ μ
/// P_N, P_N = −(1+e) D_NA/(G_NN − σ μ G_NT), σ = sign(D_TE) ≠ 0. Returns (P_N, P_T); throws when no
/// mode fits (μ|G_NT| > G_NN can make that happen) or when D_NA > 0 (no impact).
inline Eigen::Vector2d newton_coulomb_one_contact(const Eigen::Matrix2d& G, double D_NA,
                                                  double D_TA, double e, double mu) {
  if (D_NA > 0) return Eigen::Vector2d::Zero();
  const Eigen::Vector2d b(-(1.0 + e) * D_NA, -D_TA);
  const Eigen::Vector2d stick = G.inverse() * b;
  if (stick(0) >= 0 && std::abs(stick(1)) <= mu * stick(0) * (1 + 1e-14)) return stick;
  for (double sigma : {1.0, -1.0}) {
    const double denom = G(0, 0) - sigma * mu * G(0, 1);
    if (denom <= 0) continue;
    const double pn = -(1.0 + e) * D_NA / denom;
    const double pt = -sigma * mu * pn;
    const double dte = D_TA + G(1, 0) * pn + G(1, 1) * pt;
    if (sigma * dte > 0) return {pn, pt};
  }
  throw std::runtime_error("newton_coulomb_one_contact: no contact mode fits");
}

/// Newton frictionless on c ≤ 4 contacts in closed form per active set (paper eq. 6 for one): the
/// LCP 0 ≤ P_N ⊥ G_NN P_N + (1 + e) D_NA ≥ 0 has, for a P-matrix G_NN, one solution; each of the
/// 2^c active sets S gives P_S = −G_SS⁻¹ (1 + e) D_NA,S and the one that is feasible is it.
inline Eigen::VectorXd newton_frictionless(const Eigen::MatrixXd& G_NN, const Eigen::VectorXd& D_NA,
                                           double e) {
  const int c = static_cast<int>(D_NA.size());
  const Eigen::VectorXd q = (1.0 + e) * D_NA;
  for (int set = 0; set < (1 << c); ++set) {
    Eigen::VectorXd P = Eigen::VectorXd::Zero(c);
    std::vector<int> idx;
    for (int i = 0; i < c; ++i)
      if (set & (1 << i)) idx.push_back(i);
    const int k = static_cast<int>(idx.size());
    Eigen::MatrixXd Gs(k, k);
    Eigen::VectorXd qs(k);
    for (int a = 0; a < k; ++a) {
      qs(a) = q(idx[a]);
      for (int b = 0; b < k; ++b) Gs(a, b) = G_NN(idx[a], idx[b]);
    }
    if (k > 0) {
      const Eigen::VectorXd Ps = Gs.lu().solve(-qs);
      for (int a = 0; a < k; ++a) P(idx[a]) = Ps(a);
    }
    const Eigen::VectorXd w = G_NN * P + q;
    const double scale = q.cwiseAbs().maxCoeff() + 1e-300;
    if (P.minCoeff() >= -1e-13 * scale && w.minCoeff() >= -1e-12 * scale) return P;
  }
  throw std::runtime_error("newton_frictionless: no active set fits");
}

/// Newton + Coulomb (e, μ) on the flat bar in closed form. Both ends take part; with θ = 0,
/// G_NT = 0, so the normal part is newton_frictionless on G_NN and the tangential part sees the
/// total ΣP_T only: D_TE = D_TA + ΣP_T/m. It sticks (ẋ_E = 0) when m|ẋ_A| ≤ μ ΣP_N, else slides.
/// Returns q̇_E (unique although the split of P_T is not).
inline Eigen::Vector3d flat_bar_newton_coulomb_velocity(double e = kRestitution,
                                                        double mu = kFriction) {
  const SmallImpactProblem p = flat_bar_two_contacts(false);
  const ContactSpace cs = contact_space(p);
  const Eigen::VectorXd PN = newton_frictionless(cs.G, cs.D_A, e);
  const double xdot = p.qdot_A(0), total_n = PN.sum();
  const double pt_sum =
      (kMass * std::abs(xdot) <= mu * total_n) ? -kMass * xdot : -std::copysign(mu * total_n, xdot);
  Eigen::VectorXd qE = velocity_after(p, cs, PN);
  qE(0) += pt_sum / kMass;
  return qE;
}

/// Every solution of Newton + Coulomb (docs/laws.md; e, μ the same for every contact) by
/// enumeration of the 4^c contact modes (separate, stick, slide with D_TE > 0, slide with D_TE <
/// 0), each a linear system in the percussions of the contacts that touch; for c ≤ 4 contacts that
/// all take part and problems whose mode systems are regular (G singular, as on the flat bar, can
/// hide a continuum of solutions: use the closed form there). Returns q̇_E of each distinct
/// solution.
inline std::vector<Eigen::VectorXd> newton_coulomb_enumerate(const SmallImpactProblem& p, double e,
                                                             double mu) {
  const ContactSpace cs = contact_space(p);
  const int c = cs.contacts;
  if (cs.rows_per_contact != 2) throw std::invalid_argument("newton_coulomb_enumerate: no W_T");
  const double scale = cs.D_A.cwiseAbs().maxCoeff() + 1e-300, tol = 1e-10 * scale;
  std::vector<Eigen::VectorXd> found;
  int modes = 1;
  for (int i = 0; i < c; ++i) modes *= 4;
  for (int code = 0; code < modes; ++code) {
    std::vector<int> mode(c);
    for (int i = 0, k = code; i < c; ++i, k /= 4) mode[i] = k % 4;
    // Unknowns P (2c); one equation per row: separate: P_N = P_T = 0; stick: D_NE + e D_NA = 0,
    // D_TE = 0; slide σ: D_NE + e D_NA = 0, P_T + σ μ P_N = 0.
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * c, 2 * c);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(2 * c);
    for (int i = 0; i < c; ++i) {
      const int n = 2 * i, t = n + 1;
      if (mode[i] == 0) {
        A(n, n) = 1;
        A(t, t) = 1;
        continue;
      }
      A.row(n) = cs.G.row(n);
      b(n) = -(1 + e) * cs.D_A(n);
      if (mode[i] == 1) {
        A.row(t) = cs.G.row(t);
        b(t) = -cs.D_A(t);
      } else {
        const double sigma = mode[i] == 2 ? 1.0 : -1.0;
        A(t, t) = 1;
        A(t, n) = sigma * mu;
      }
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
    if (!lu.isInvertible()) continue;
    const Eigen::VectorXd P = lu.solve(b);
    const Eigen::VectorXd D_E = cs.D_A + cs.G * P;
    bool ok = true;
    for (int i = 0; i < c && ok; ++i) {
      const int n = 2 * i, t = n + 1;
      const double wn = D_E(n) + e * cs.D_A(n);
      const double pscale = tol / std::max(cs.G(n, n), 1e-300);
      switch (mode[i]) {
        case 0:
          ok = wn >= -tol;
          break;
        case 1:
          ok = P(n) >= -pscale && std::abs(P(t)) <= mu * P(n) + pscale;
          break;
        case 2:
          ok = P(n) >= -pscale && D_E(t) >= -tol;
          break;
        default:
          ok = P(n) >= -pscale && D_E(t) <= tol;
          break;
      }
    }
    if (!ok) continue;
    const Eigen::VectorXd qE = velocity_after(p, cs, P);
    bool known = false;
    for (const auto& f : found) known = known || (f - qE).norm() <= 1e-9 * (1 + qE.norm());
    if (!known) found.push_back(qE);
  }
  return found;
}

}  // namespace fremond::bench
