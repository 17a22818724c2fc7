#pragma once
/// @file The benchmark problems, used by every benchmark (ours and the Siconos peers), so that
/// every time printed is for the same data: the shared fixtures (tests/support/fixtures.hpp, the
/// same problems the tests solve, random ones included) and their answers in closed form, so that
/// every benchmark can check that it solved the problem it timed.
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

#include "support/fixtures.hpp"

namespace fremond::bench {

using namespace fremond::fixtures;  // the problems and the bar's laws

/// The label of a benchmark that solves `problem` under `law` (see the file comment).
inline std::string bench_label(std::string_view problem, std::string_view law) {
  return "problem=" + std::string(problem) + " law=" + std::string(law);
}

// ---------------------------------------------------------------------------------------------
// Answers in closed form.

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
