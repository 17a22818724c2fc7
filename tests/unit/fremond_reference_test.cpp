// The library's Frémond solvers against the independent quad-precision reference
// (tests/reference/fremond_reference.hpp) on the hard cases of the core issue: p ∈ {1.01, 1.1, 1.5,
// 2, 3, 10, 50}; q down to 1.01; r = 0 and r above every velocity; velocities from 1e-10 to 1e6;
// k from 1e-6 to 1e6; mass ratios up to 1e6; the flat bar touching with both ends (singular G).
//
// For every case, solve_impact with `automatic` and with each method forced:
//  - a result marked converged has q̇_E within kTolerance of the reference,
//      ‖q̇_E − q̇_E,ref‖_M / ‖q̇_A‖_M ≤ max(1e-12, 16 ε κ(G))
//    (the kinetic-energy norm relative to the velocity before; to the nearest reference solution
//    where there are several). The looser 16 ε κ(G) applies only to ill-conditioned Delassus
//    matrices (the mass ratio 1e6 gives κ(G) ≈ 1e7): the contact-space methods form
//    z = D_A + G P/2, whose rounding is ε‖G‖‖P‖, so an answer is only determined to ε κ(G) there;
//    NLopt's answers are accepted at its own nlopt_tolerance (1e-9 by default): its bound is
//    4 × nlopt_tolerance; the proximal splitting (linear convergence, stopped on the residual) is
//    held to 100 × tolerance;
//  - a result marked converged is admissible (docs/concepts.md);
//  - a result that is not converged says so: a status other than converged and other than
//    not_run (a wrong answer is never marked converged: that is the first check);
//  - where the reference finds no solution (Coulomb, Painlevé-type data), the library says
//    no_solution;
//  - Frémond + Coulomb: the solutions of solve_impact_all are the reference's, in number and value.
// Each method's count of non-converged results is printed, so a loss of robustness shows.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "../bench/fremond_suite.hpp"

namespace fremond {
namespace {

using namespace fremond::bench;
constexpr double kEps = std::numeric_limits<double>::epsilon();

/// The error allowed for a converged answer of problem p (see the file comment).
double allowed_error(const SmallImpactProblem& p, bool tangential) {
  const Eigen::MatrixXd M = p.M;
  Eigen::MatrixXd W(p.dofs(), 0);
  std::vector<Eigen::VectorXd> cols;
  for (int i = 0; i < p.contacts(); ++i) {
    cols.push_back(p.W_N.col(i));
    if (tangential && p.has_tangential()) cols.push_back(p.W_T.col(i));
  }
  W.resize(p.dofs(), static_cast<int>(cols.size()));
  for (std::size_t j = 0; j < cols.size(); ++j) W.col(static_cast<int>(j)) = cols[j];
  const Eigen::MatrixXd G = W.transpose() * M.ldlt().solve(W);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(G);
  const double lmax = es.eigenvalues().maxCoeff();
  const double lmin = es.eigenvalues().minCoeff();
  // A singular G (the flat bar with friction rows) is not ill-conditioned for the answer, which is
  // in the range of G: its conditioning is that of the non-zero eigenvalues.
  double lpos = lmax;
  for (int i = 0; i < es.eigenvalues().size(); ++i)
    if (es.eigenvalues()(i) > 1e-12 * lmax) lpos = std::min(lpos, es.eigenvalues()(i));
  (void)lmin;
  return std::max(1e-12, 16 * kEps * lmax / lpos);
}

struct Tally {
  int solved = 0, not_converged = 0, unsupported = 0;
  double seconds = 0.0;
};

/// Checks one library result against the reference; returns a description of a failure or "".
std::string check_result(const SmallImpactProblem& p, const ReferenceAnswer& ref,
                         const SmallImpactResult& r, double allowed) {
  if (r.solver.status == SolverStatus::not_run) return "status not_run";
  if (ref.ok && ref.qdot_E.empty()) {
    if (r.ok()) return "marked converged, but the reference finds no solution";
    return "";
  }
  if (!r.ok()) return "";
  const double e = relative_error(p, ref, r.qdot_E);
  char buf[256];
  if (!(e <= allowed)) {
    std::snprintf(buf, sizeof buf,
                  "converged (%s, residual %.3g) but off the reference by %.3g > %.3g",
                  std::string(to_string(r.solver.method)).c_str(), r.solver.residual, e, allowed);
    return buf;
  }
  if (!r.admissibility.admissible) {
    std::snprintf(buf, sizeof buf, "converged but not admissible (%s, violation %.3g)",
                  std::string(to_string(r.admissibility.failed)).c_str(),
                  r.admissibility.violation);
    return buf;
  }
  return "";
}

std::string describe(const SmallImpactProblem& p, const FremondLawSpec& s) {
  std::ostringstream os;
  os.precision(17);
  os << "law " << s.law().describe() << "\n  M = ["
     << Eigen::MatrixXd(p.M).format(Eigen::IOFormat(17, 0, ", ", "; ")) << "]\n  W_N = ["
     << Eigen::MatrixXd(p.W_N).format(Eigen::IOFormat(17, 0, ", ", "; ")) << "]\n  W_T = ["
     << Eigen::MatrixXd(p.W_T).format(Eigen::IOFormat(17, 0, ", ", "; ")) << "]\n  qdot_A = ["
     << Eigen::VectorXd(p.qdot_A).transpose().format(Eigen::IOFormat(17, 0, ", ", ", ")) << "]";
  return os.str();
}

const std::vector<SolverMethod>& all_methods() {
  static const std::vector<SolverMethod> m{SolverMethod::automatic,
                                           SolverMethod::closed_form,
                                           SolverMethod::scalar_newton,
                                           SolverMethod::mode_enumeration,
                                           SolverMethod::semismooth_newton,
                                           SolverMethod::proximal,
                                           SolverMethod::nlopt};
  return m;
}

/// Runs every method on one problem and law; `nlopt` off skips the (slow) NLopt fallback.
void run_case(const SmallImpactProblem& p, const FremondLawSpec& spec, bool nlopt,
              std::map<std::string, Tally>& tally, int& failures) {
  const ReferenceAnswer ref = reference_answer(p, spec);
  ASSERT_TRUE(ref.ok) << describe(p, spec);
  const ImpactLaw law = spec.law();
  const double allowed = allowed_error(p, spec.tangential != FremondLawSpec::Tangential::none);
  for (SolverMethod m : all_methods()) {
    if (m == SolverMethod::nlopt && !nlopt) continue;
    SolverOptions opt;
    opt.method = m;
    // Budgets that bound the test's time (NLopt says so when it runs out): its MMA path for Coulomb
    // spends milliseconds per evaluation in MMA's inner loop on stiff data.
    opt.max_nlopt_evaluations =
        spec.tangential == FremondLawSpec::Tangential::coulomb ? 300 : 20000;
    const auto t0 = std::chrono::steady_clock::now();
    const SmallImpactResult r = solve_impact(p, law, opt);
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    Tally& t = tally[std::string(to_string(m))];
    t.seconds += secs;
    if (secs > 0.2)
      std::printf("  slow: %s took %.2f s (%s), %s\n", std::string(to_string(m)).c_str(), secs,
                  std::string(to_string(r.solver.status)).c_str(), law.describe().c_str());
    if (r.solver.status == SolverStatus::unsupported) {
      ++t.unsupported;
      continue;
    }
    ++t.solved;
    if (!r.ok()) ++t.not_converged;
    // NLopt's answers are accepted at its own, looser tolerance by design (nlopt_tolerance, 1e-9 by
    // default: SLSQP on a non-smooth problem), so its bound is that tolerance, not 1e-12.
    // The proximal splitting converges linearly and stops as soon as the residual is below
    // `tolerance`: where the law is flat near the answer (p = 10 and a small z_N) the distance to
    // the answer is up to ~1/(1 − rate) times that residual, so its bound is 100 × tolerance.
    double bound = allowed;
    if (r.solver.method == SolverMethod::nlopt) bound = std::max(allowed, 4 * opt.nlopt_accepts());
    if (r.solver.method == SolverMethod::proximal) bound = std::max(allowed, 100 * opt.tolerance);
    const std::string why = check_result(p, ref, r, bound);
    if (!why.empty()) {
      ++failures;
      ADD_FAILURE() << "method " << to_string(m) << ": " << why << "\n  " << describe(p, spec)
                    << "\n  status " << to_string(r.solver.status) << ", " << r.solver.message;
    }
    if (ref.qdot_E.empty() && m == SolverMethod::automatic) {
      EXPECT_EQ(r.solver.status, SolverStatus::no_solution) << describe(p, spec);
    }
  }
}

void print_tally(const char* what, const std::map<std::string, Tally>& tally) {
  std::printf("%s:\n", what);
  for (const auto& [m, t] : tally)
    std::printf("  %-18s solved %4d, not converged %4d, unsupported %4d, %.3f s\n", m.c_str(),
                t.solved, t.not_converged, t.unsupported, t.seconds);
}

/// SplitMix64, as the benchmarks' problems.
struct Rng {
  SplitMix64 g{0};
  explicit Rng(std::uint64_t s) : g(s) {}
  double uniform(double lo, double hi) { return g.uniform(lo, hi); }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
};

/// One contact: the bar at angle θ (mass ratio by its inertia), a point mass, or a random body.
SmallImpactProblem one_contact_problem(int kind, double speed, double mass_ratio, Rng& rng) {
  SmallImpactProblem p;
  if (kind == 0 || kind == 1) {  // the bar, at θ = π/4 or at a random angle
    const double th = kind == 0 ? kTheta0 : rng.uniform(0.1, 1.4);
    p = bar_first_impact(true);
    p.W_N = bar_end_normal(-1.0, th);
    p.W_T = bar_end_tangent(-1.0, th);
    p.M(2, 2) /= mass_ratio;
    p.qdot_A =
        Eigen::Vector3d(rng.uniform(-1, 1), -1.0, rng.uniform(-1, 1) * std::sqrt(mass_ratio));
  } else if (kind == 2) {  // a point mass of mass 1/mass_ratio
    p = planar_point_mass(1.0 / mass_ratio, true);
    p.qdot_A = Eigen::Vector2d(rng.uniform(-2, 2), -1.0);
  } else {  // a random body with n = 4 dofs, masses spread by mass_ratio
    const int n = 4;
    Eigen::Matrix4d B;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) B(i, j) = rng.uniform(-1, 1);
    Eigen::Vector4d s;
    for (int i = 0; i < n; ++i) s(i) = std::sqrt(rng.log_uniform(1.0, mass_ratio));
    const Eigen::Matrix4d M0 = B * B.transpose() / n + 0.5 * Eigen::Matrix4d::Identity();
    p.M = s.asDiagonal() * M0 * s.asDiagonal();
    Eigen::Vector4d wn, wt, qa;
    for (int i = 0; i < n; ++i) {
      wn(i) = rng.uniform(-1, 1);
      wt(i) = rng.uniform(-1, 1);
      qa(i) = rng.uniform(-1, 1);
    }
    if (wn.dot(qa) > 0) wn = -wn;
    p.W_N = wn;
    p.W_T = wt;
    p.w_N = SmallImpactProblem::CVec::Zero(1);
    p.w_T = SmallImpactProblem::CVec::Zero(1);
    p.qdot_A = qa;
  }
  // Scale the velocities so that the largest contact velocity is `speed`.
  const double dn = std::fabs(p.W_N.col(0).dot(p.qdot_A));
  const double dt = std::fabs(p.W_T.col(0).dot(p.qdot_A));
  p.qdot_A *= speed / std::max(dn, dt);
  return p;
}

// ---------------------------------------------------------------------------------------------

TEST(FremondAgainstReference, OneContactHardGrid) {
  const auto t0 = std::chrono::steady_clock::now();
  const double ps[] = {1.01, 1.1, 1.5, 2.0, 3.0, 10.0, 50.0};
  const double qs[] = {1.01, 1.5, 2.0, 3.0};
  const double speeds[] = {1e-10, 1e-3, 1.0, 1e6};
  const double ks[] = {1e-6, 1.0, 1e6};
  const double ratios[] = {1.0, 1e6};
  Rng rng(11);
  std::map<std::string, Tally> tally;
  int failures = 0, index = 0;
  for (double p : ps)
    for (double speed : speeds)
      for (double k : ks) {
        const int i = index++;
        const double ratio = ratios[i % 2];
        SmallImpactProblem pb = one_contact_problem(i % 4, speed, ratio, rng);
        const double vmax = speed;
        // r: 0, inside the velocities' range, or above every velocity.
        const double r = i % 3 == 0 ? 0.0 : (i % 3 == 1 ? 0.3 * vmax : 10.0 * vmax);
        const double q = qs[i % 4];
        const double kT = ks[(i / 3) % 3];
        const double mu = (i % 5 == 4) ? 3.0 : 0.1 + 0.3 * (i % 4);  // μ = 3: Painlevé on the bar
        const std::vector<FremondLawSpec> laws{normal_only(k, p), with_dead_zone(k, p, kT, q, r),
                                               with_coulomb(k, p, mu)};
        for (const FremondLawSpec& s : laws) {
          run_case(pb, s, i % 7 == 0, tally, failures);
        }
      }
  print_tally("one contact", tally);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("  %d cases in %.2f s\n", index * 3, secs);
}

// Frémond + Coulomb on one contact: every solution of solve_impact_all is a reference solution and
// every reference solution is found, including the Painlevé-type cases (μ|G_NT| > G_NN) with
// three solutions or none.
TEST(FremondAgainstReference, CoulombSolutionSetsEqualTheReference) {
  Rng rng(5);
  int multiple = 0, none = 0;
  for (int i = 0; i < 240; ++i) {
    const double p = std::vector<double>{1.01, 1.1, 1.5, 2.0, 3.0, 10.0, 50.0}[i % 7];
    const double speed = std::vector<double>{1e-10, 1e-3, 1.0, 1e6}[(i / 7) % 4];
    const double k = rng.log_uniform(1e-6, 1e6);
    const double mu = i % 3 == 0 ? rng.uniform(1.7, 6.0) : rng.uniform(0.0, 2.0);
    const SmallImpactProblem pb = one_contact_problem(i % 4, speed, i % 5 == 0 ? 1e6 : 1.0, rng);
    const FremondLawSpec spec = with_coulomb(k, p, mu);
    const ReferenceAnswer ref = reference_answer(pb, spec);
    ASSERT_TRUE(ref.ok);
    const auto all = solve_impact_all(to_dynamic(pb), spec.law());
    const double allowed = allowed_error(pb, true);
    if (ref.qdot_E.size() > 1) ++multiple;
    if (ref.qdot_E.empty()) ++none;
    ASSERT_EQ(all.size(), ref.qdot_E.size()) << "case " << i << ": " << describe(pb, spec);
    // Each library solution is near a distinct reference solution.
    std::vector<bool> used(ref.qdot_E.size(), false);
    for (const ImpactResult& r : all) {
      EXPECT_TRUE(r.ok()) << "case " << i;
      EXPECT_TRUE(r.admissibility.admissible) << "case " << i << ": " << describe(pb, spec);
      double best = std::numeric_limits<double>::infinity();
      int which = -1;
      for (std::size_t j = 0; j < ref.qdot_E.size(); ++j) {
        if (used[j]) continue;
        ReferenceAnswer one;
        one.ok = true;
        one.qdot_E = {ref.qdot_E[j]};
        const double e = relative_error(pb, one, r.qdot_E);
        if (e < best) {
          best = e;
          which = static_cast<int>(j);
        }
      }
      ASSERT_GE(which, 0);
      used[which] = true;
      EXPECT_LE(best, allowed) << "case " << i << ": " << describe(pb, spec);
      EXPECT_EQ(r.unique, ref.qdot_E.size() == 1) << "case " << i;
    }
  }
  std::printf("  Coulomb: %d cases with several solutions, %d with none\n", multiple, none);
  EXPECT_GT(multiple, 0);  // the grid does reach the Painlevé-type cases
}

// Several contacts, tangential law none or dead zone: the flat bar (two contacts, G singular with
// the tangential rows) and random bodies with 2 to 4 contacts, over the same ranges.
TEST(FremondAgainstReference, SeveralContacts) {
  const auto t0 = std::chrono::steady_clock::now();
  Rng rng(17);
  std::map<std::string, Tally> tally;
  int failures = 0;
  const double ps[] = {1.01, 1.1, 1.5, 2.0, 3.0, 10.0, 50.0};
  const double qs[] = {1.01, 1.5, 2.0, 3.0};
  int cases = 0;
  for (int i = 0; i < 42; ++i) {
    const double p = ps[i % 7];
    const double speed = std::vector<double>{1e-10, 1.0, 1e6}[i % 3];
    const double k = std::vector<double>{1e-6, 1.0, 1e6}[(i / 3) % 3];
    SmallImpactProblem pb;
    if (i % 3 == 0) {
      pb = flat_bar_two_contacts(true);
    } else {
      const int c = 2 + i % 3;
      const ImpactProblem d = random_problem_any(6, c, 100 + i, true);
      pb = to_small(d);
      if (i % 6 == 4) {  // a mass ratio of 1e6
        Eigen::Matrix<double, 6, 1> s;
        for (int j = 0; j < 6; ++j) s(j) = std::sqrt(rng.log_uniform(1.0, 1e6));
        pb.M = (s.asDiagonal() * Eigen::Matrix<double, 6, 6>(pb.M) * s.asDiagonal()).eval();
      }
    }
    double vmax = 0.0;
    for (int j = 0; j < pb.contacts(); ++j)
      vmax = std::max(
          {vmax, std::fabs(pb.W_N.col(j).dot(pb.qdot_A)), std::fabs(pb.W_T.col(j).dot(pb.qdot_A))});
    pb.qdot_A *= speed / vmax;
    const double r = i % 4 == 0 ? 0.0 : (i % 4 == 1 ? 10.0 * speed : 0.3 * speed);
    const std::vector<FremondLawSpec> laws{
        normal_only(k, p),
        with_dead_zone(k, p, std::vector<double>{1e-6, 1.0, 1e6}[i % 3], qs[i % 4], r)};
    for (const FremondLawSpec& s : laws) {
      SmallImpactProblem q = pb;
      if (s.tangential == FremondLawSpec::Tangential::none) {
        q.W_T.resize(q.dofs(), 0);
        q.w_T.resize(0);
      }
      run_case(q, s, i % 5 == 0, tally, failures);
      ++cases;
    }
  }
  print_tally("several contacts", tally);
  std::printf("  %d cases in %.2f s\n", cases,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

}  // namespace
}  // namespace fremond
