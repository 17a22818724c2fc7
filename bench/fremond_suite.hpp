#pragma once
/// @file The fixed suite of Frémond problems (issue 6, item 1) shared by bench/fremond_bench.cpp,
/// bench/work_precision.cpp and the tests of the performance report: the paper's bar at its first
/// impact with each of Frémond's laws, a point mass for p ∈ {1.1, 2, 3, 10}, the flat bar touching
/// with both ends (G singular with the friction rows), random problems with n = 6 and 3 contacts,
/// and the hard parameters of the core issue (p and q near 1, p = 50, r = 0 and r above every
/// velocity, velocities of 1e-10 and 1e6, k from 1e-6 to 1e6, a mass ratio of 1e6).
///
/// Every case carries its answer from the independent `__float128` reference
/// (tests/reference/fremond_reference.hpp; link with -lquadmath), so a benchmark can check what it
/// timed and the work-precision sweep can measure the actual error of each method:
///
///     error = ‖q̇_E − q̇_E,ref‖_M / ‖q̇_A‖_M,   ‖v‖_M = √(vᵀ M v),
///
/// the error of the velocity after the impact in the kinetic-energy norm, relative to the velocity
/// before (an admissible impact has ‖q̇_E‖_M ≤ ‖q̇_A‖_M, so this is also relative to the larger of
/// the two). Where the law has several solutions the distance to the nearest one is taken. Flat bar
/// with Coulomb: the reference has no Coulomb on several contacts, but at θ = 0 the normal and
/// tangential rows decouple (G_NT = 0) and both ends share one tangent, so the normal percussions
/// come from the reference's several-contact solver and the tangential total in closed form.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "../tests/reference/fremond_reference.hpp"
#include "problems.hpp"

namespace fremond::bench {

namespace ref = fremond_reference;

/// A Frémond law by its parameters, so that the library's law and the reference's are built from
/// the same numbers. The normal law is always the power law k_N|z|^p/p.
struct FremondLawSpec {
  enum class Tangential { none, dead_zone, coulomb };
  double k_N = 1.0, p = 2.0;
  Tangential tangential = Tangential::none;
  double k_T = 0.0, q = 2.0, r = 0.0;  ///< dead zone
  double mu = 0.0;                     ///< Coulomb

  ImpactLaw law() const {
    switch (tangential) {
      case Tangential::dead_zone:
        return ImpactLaw::fremond(PowerPotential(k_N, p), DeadZonePowerPotential(k_T, q, r));
      case Tangential::coulomb:
        return ImpactLaw::fremond_coulomb(PowerPotential(k_N, p), mu);
      case Tangential::none:
        break;
    }
    return ImpactLaw::fremond(PowerPotential(k_N, p));
  }
  ref::PowerLaw ref_normal() const {
    return {static_cast<ref::quad>(k_N), static_cast<ref::quad>(p)};
  }
  ref::TangentialLaw ref_tangential() const {
    switch (tangential) {
      case Tangential::dead_zone:
        return ref::TangentialLaw::dead_zone(k_T, q, r);
      case Tangential::coulomb:
        return ref::TangentialLaw::coulomb(mu);
      case Tangential::none:
        break;
    }
    return ref::TangentialLaw::none();
  }
};

inline FremondLawSpec normal_only(double k, double p) {
  FremondLawSpec s;
  s.k_N = k;
  s.p = p;
  return s;
}
inline FremondLawSpec with_dead_zone(double k, double p, double k_T, double q, double r) {
  FremondLawSpec s = normal_only(k, p);
  s.tangential = FremondLawSpec::Tangential::dead_zone;
  s.k_T = k_T;
  s.q = q;
  s.r = r;
  return s;
}
inline FremondLawSpec with_coulomb(double k, double p, double mu) {
  FremondLawSpec s = normal_only(k, p);
  s.tangential = FremondLawSpec::Tangential::coulomb;
  s.mu = mu;
  return s;
}

/// The reference answers of one problem: q̇_E of every solution, in quad precision.
struct ReferenceAnswer {
  std::vector<ref::QVec> qdot_E;
  bool ok = false;  ///< false: no reference for this problem (the error is then NaN)
};

/// One case of the suite: a problem (or several, cycled through by the benchmarks), one law.
struct FremondCase {
  std::string problem;   ///< the `problem=` word of the label
  std::string law_name;  ///< the `law=` word of the label
  bool hard = false;     ///< one of the core issue's hard parameters
  std::vector<SmallImpactProblem> problems;
  FremondLawSpec spec;
  ImpactLaw law;
  std::vector<ReferenceAnswer> reference;  ///< one per problem
};

// ---------------------------------------------------------------------------------------------
// The reference answers.

inline ref::Problem to_reference(const SmallImpactProblem& p) {
  const Eigen::MatrixXd M = p.M, WN = p.W_N, WT = p.W_T;
  const Eigen::VectorXd qA = p.qdot_A;
  return ref::problem_from(M, WN, WT, qA);
}

/// True when every tangent is the same column and the normal and tangential rows decouple
/// (W_Nᵀ M⁻¹ W_T = 0): the flat bar, where Coulomb on several contacts has a closed form.
inline bool shared_decoupled_tangent(const SmallImpactProblem& p) {
  if (p.contacts() < 2 || !p.has_tangential()) return false;
  const Eigen::MatrixXd M = p.M;
  const Eigen::MatrixXd WT = p.W_T, WN = p.W_N;
  for (int i = 1; i < p.contacts(); ++i)
    if ((WT.col(i) - WT.col(0)).lpNorm<Eigen::Infinity>() != 0.0) return false;
  const Eigen::MatrixXd GNT = WN.transpose() * M.ldlt().solve(WT);
  return GNT.lpNorm<Eigen::Infinity>() <= 1e-15;
}

/// Frémond + Coulomb on contacts sharing one tangent t decoupled from the normal rows: P_N from the
/// normal law alone, then the total tangential percussion S acting along t: z_T = D_TA + g S/2,
/// g = tᵀM⁻¹t; stick (z_T = 0) when |2 D_TA/g| ≤ μ Σ|P_N,i|, else S = −μ Σ|P_N,i| sign(D_TA).
inline ReferenceAnswer shared_tangent_coulomb(const SmallImpactProblem& p,
                                              const FremondLawSpec& s) {
  using ref::quad;
  ReferenceAnswer out;
  const ref::Problem rp = to_reference(p);
  ref::Problem normal_part = rp;
  normal_part.W_T.clear();
  const ref::Solution sn =
      ref::fremond_several(normal_part, {s.ref_normal()}, {ref::TangentialLaw::none()});
  if (!sn.ok) return out;
  const int n = rp.dofs();
  const ref::QVec& t = rp.W_T[0];
  ref::detail::Cholesky chol(rp.M);
  const ref::QVec Minv_t = chol.solve(t);
  const quad g = ref::detail::dot(t, Minv_t);
  quad bound = 0, DTA = ref::detail::dot(t, rp.qdot_A);
  for (int i = 0; i < rp.contacts(); ++i)
    if (sn.takes_part[i]) bound += static_cast<quad>(s.mu) * fabsq(sn.P_N[i]);
  const quad stick = -2 * DTA / g;
  const quad S = fabsq(stick) <= bound ? stick : (DTA > 0 ? -bound : bound);
  ref::QVec qE = sn.qdot_E;
  for (int k = 0; k < n; ++k) qE[k] += S * Minv_t[k];
  out.qdot_E.push_back(qE);
  out.ok = true;
  return out;
}

inline ReferenceAnswer reference_answer(const SmallImpactProblem& p, const FremondLawSpec& s) {
  ReferenceAnswer out;
  const ref::Problem rp = to_reference(p);
  if (p.contacts() == 1) {
    for (const ref::Solution& sol :
         ref::fremond_one_contact(rp, s.ref_normal(), s.ref_tangential()))
      out.qdot_E.push_back(sol.qdot_E);
    out.ok = true;  // an empty list: no solution
    return out;
  }
  if (s.tangential == FremondLawSpec::Tangential::coulomb) {
    if (shared_decoupled_tangent(p)) return shared_tangent_coulomb(p, s);
    return out;  // no reference for Coulomb on several general contacts
  }
  ref::Problem rq = rp;
  if (s.tangential == FremondLawSpec::Tangential::none) rq.W_T.clear();
  const ref::Solution sol = ref::fremond_several(rq, {s.ref_normal()}, {s.ref_tangential()});
  if (!sol.ok) return out;
  out.qdot_E.push_back(sol.qdot_E);
  out.ok = true;
  return out;
}

/// ‖q̇_E − q̇_E,ref‖_M / ‖q̇_A‖_M to the nearest reference solution (see the file comment), computed
/// in quad precision; NaN without a reference, +∞ when the reference has no solution.
template <class Vec>
double relative_error(const SmallImpactProblem& p, const ReferenceAnswer& r, const Vec& qdot_E) {
  using ref::quad;
  if (!r.ok) return std::nan("");
  const int n = p.dofs();
  auto m_norm = [&](const ref::QVec& v) {
    quad s = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) s += v[i] * static_cast<quad>(p.M(i, j)) * v[j];
    return sqrtq(fmaxq(s, 0));
  };
  ref::QVec qA(n);
  for (int i = 0; i < n; ++i) qA[i] = p.qdot_A(i);
  const quad scale = m_norm(qA);
  double best = std::numeric_limits<double>::infinity();
  for (const ref::QVec& qE : r.qdot_E) {
    ref::QVec d(n);
    for (int i = 0; i < n; ++i) d[i] = static_cast<quad>(qdot_E(i)) - qE[i];
    const double e = static_cast<double>(m_norm(d) / scale);
    if (!(e >= best)) best = e;  // NaN never wins over a number, but is kept if alone
  }
  return best;
}

// ---------------------------------------------------------------------------------------------
// The problems.

/// The bar's lower end at θ = π/4 (the paper's Fig. 1) with the given q̇_A and mass matrix scale of
/// θ.
inline SmallImpactProblem bar_one_contact(const Eigen::Vector3d& qdot_A,
                                          double inertia_scale = 1.0) {
  SmallImpactProblem p = bar_first_impact(true);
  p.qdot_A = qdot_A;
  p.M(2, 2) *= inertia_scale;
  return p;
}

/// A point mass m = 1 on the ground, frictionless rows only (q = (x, y), q̇_A = (2, −1)).
inline SmallImpactProblem point_mass_normal() {
  return planar_point_mass(1.0, false);
}

/// Frémond's k_N giving a point mass (G = 1/m) the normal restitution e at D_NA (normal law alone):
/// as bar_fremond_k_normal, k = (1 + e)/(G ((1 − e)/2)^(p−1) |D_NA|^(p−2)).
inline double point_mass_k_normal(double p, double e, double m = 1.0, double dna = 1.0) {
  return (1.0 + e) * m / (std::pow((1.0 - e) / 2.0, p - 1.0) * std::pow(dna, p - 2.0));
}

// ---------------------------------------------------------------------------------------------
// The suite.

inline FremondCase make_case(std::string problem, std::string law_name, FremondLawSpec spec,
                             std::vector<SmallImpactProblem> problems, bool hard = false,
                             bool with_reference = true) {
  FremondCase c;
  c.problem = std::move(problem);
  c.law_name = std::move(law_name);
  c.hard = hard;
  c.spec = spec;
  c.law = spec.law();
  c.problems = std::move(problems);
  for (const auto& p : c.problems)
    c.reference.push_back(with_reference ? reference_answer(p, spec) : ReferenceAnswer{});
  return c;
}

/// Which cases to build.
struct SuiteOptions {
  bool bar = true, point_mass = true, flat_bar = true, random = true, hard = true;
  int random_problems = kRandomProblems;  ///< random cases cycle through this many problems
};

/// The suite (issue 6, item 1). Building it runs the quad reference on every problem: about a
/// second in all.
inline std::vector<FremondCase> fremond_suite(const SuiteOptions& o = {}) {
  std::vector<FremondCase> v;
  const double kN3 = bar_fremond_k_normal(3.0);
  const FremondLawSpec p3 = normal_only(kN3, 3.0);
  const FremondLawSpec viscous =
      with_dead_zone(kN3, 3.0, 1.5, 2.0, 0.2);  // the paper's Fig. 1 (our scaling)
  const FremondLawSpec coulomb = with_coulomb(kN3, 3.0, kFriction);
  if (o.bar) {
    v.push_back(make_case("bar_first_impact", "fremond_p3", p3, {bar_first_impact(false)}));
    v.push_back(
        make_case("bar_first_impact", "fremond_p3_viscous", viscous, {bar_first_impact(true)}));
    v.push_back(
        make_case("bar_first_impact", "fremond_p3_coulomb", coulomb, {bar_first_impact(true)}));
  }
  if (o.point_mass) {
    // k_N from a normal restitution of 0.5 at D_NA = −1.
    for (const double p : {1.1, 2.0, 3.0, 10.0}) {
      char name[32];
      std::snprintf(name, sizeof name, "fremond_p%g", p);
      v.push_back(make_case("point_mass", name, normal_only(point_mass_k_normal(p, 0.5), p),
                            {point_mass_normal()}));
    }
  }
  if (o.flat_bar) {
    v.push_back(
        make_case("flat_bar", "fremond_p2", normal_only(8.0, 2.0), {flat_bar_two_contacts(false)}));
    v.push_back(make_case("flat_bar", "fremond_p3", p3, {flat_bar_two_contacts(false)}));
    v.push_back(
        make_case("flat_bar", "fremond_p3_viscous", viscous, {flat_bar_two_contacts(true)}));
    v.push_back(
        make_case("flat_bar", "fremond_p3_coulomb", coulomb, {flat_bar_two_contacts(true)}));
  }
  if (o.random) {
    std::vector<SmallImpactProblem> frictionless, friction;
    for (int i = 0; i < o.random_problems; ++i) {
      frictionless.push_back(random_spd_problem(i, false));
      friction.push_back(random_spd_problem(i, true));
    }
    v.push_back(make_case("random_n6_c3", "fremond_p2", normal_only(8.0, 2.0), frictionless));
    v.push_back(make_case("random_n6_c3", "fremond_p3", p3, frictionless));
    v.push_back(make_case("random_n6_c3", "fremond_p3_viscous", viscous, friction));
    v.push_back(make_case("random_n6_c3", "fremond_p3_coulomb", coulomb, friction, false, false));
  }
  if (o.hard) {
    const Eigen::Vector3d qA = bar_first_impact(true).qdot_A;  // (2, −3.56, 0)
    // p and q near 1, r = 0 (the dead zone is a kink at 0).
    v.push_back(make_case("hard_p1.01_q1.01", "fremond_viscous",
                          with_dead_zone(1.0, 1.01, 1.0, 1.01, 0.0), {bar_one_contact(qA)}, true));
    // A steep normal law: p = 50.
    v.push_back(make_case("hard_p50", "fremond_viscous", with_dead_zone(1e6, 50.0, 1.5, 3.0, 0.2),
                          {bar_one_contact(qA)}, true));
    // Slow: velocities of 1e-10, r above every velocity (the contact sticks in the dead zone).
    v.push_back(make_case("hard_v1e-10_r_above", "fremond_viscous",
                          with_dead_zone(kN3, 3.0, 1.5, 2.0, 1.0),
                          {bar_one_contact(qA * (1e-10 / 3.5613))}, true));
    // Fast: velocities of 1e6 with soft laws (k = 1e-6) and q = 1.5.
    v.push_back(make_case("hard_v1e6_k1e-6", "fremond_viscous",
                          with_dead_zone(1e-6, 3.0, 1e-6, 1.5, 0.0),
                          {bar_one_contact(qA * (1e6 / 3.5613))}, true));
    // Stiff: k = 1e6, p = 1.5, Coulomb.
    v.push_back(make_case("hard_k1e6", "fremond_coulomb", with_coulomb(1e6, 1.5, 0.3),
                          {bar_one_contact(qA)}, true));
    // A mass ratio of 1e6 (the bar's rotational inertia divided by 1e6), spinning.
    v.push_back(make_case("hard_mass_ratio_1e6", "fremond_viscous",
                          with_dead_zone(kN3, 3.0, 1.5, 2.0, 0.2),
                          {bar_one_contact(Eigen::Vector3d(2.0, -3.5613, 5.0), 1e-6)}, true));
  }
  return v;
}

}  // namespace fremond::bench
