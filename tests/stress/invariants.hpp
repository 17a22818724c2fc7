#pragma once
/// @file What every answer of solve_impact must satisfy, whatever the input: the contract the
/// stress runs (tests/stress) and the fuzz targets (fuzz/) check on every result.
///
///  1. the solver ran and says how it ended (status ≠ not_run, a method other than automatic);
///  2. every vector has its size (n or c), and no NaN or infinity leaves the library: velocities,
///     percussions, energy, the solver's residual (except for no_solution, where there is no answer
///     to measure) and the admissibility report are finite;
///  3. takes_part is D_NA ≤ 0; without tangential rows, P_T = 0;
///  4. q̇_E agrees with the percussions, M (q̇_E − q̇_A) = W_N P_N + W_T P_T, and D_NE, D_TE with q̇_E
///     (to rounding);
///  5. a converged result satisfies its own residual check: the residual it reports is within the
///     tolerance its method promises (tolerance, or nlopt_tolerance for NLopt), and law_residual,
///     recomputed from the answer, is too, up to the rounding of recomputing it;
///  6. a converged Frémond result is admissible (docs/concepts.md), except that a reaction stopping
///  a
///     separating contact may break (15), which is measured with its true mean velocity;
///  7. a converged frictionless Newton or Poisson result has P_N ≥ 0 (to rounding);
///  8. in a converged result of any law no contact ends with D_NE < 0 beyond rounding, and a
///     separating contact (D_NA > 0) carries at most a reaction, P_N ≥ 0 (every contact takes
///     part: docs/concepts.md).
///
/// check_result() returns the first broken invariant as a sentence, or "" when all hold.
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "fremond/fremond.hpp"

namespace fremond::robust {

/// Numbers about one check, for the stress summary.
struct CheckStats {
  double residual = 0.0;        ///< law_residual of the result.
  double residual_bound = 0.0;  ///< what a converged result is held to.
};

namespace detail {

template <class Derived>
bool all_finite(const Eigen::MatrixBase<Derived>& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!std::isfinite(static_cast<double>(v(i)))) return false;
  return true;
}

inline std::string num(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

}  // namespace detail

/// ‖q̇ − q̇_ref‖_M / ‖q̇_A‖_M: a velocity's distance to a reference in the kinetic-energy norm,
/// relative to the velocity before the impact.
template <int N, int C, class Vec, class RefVec>
double kinetic_distance(const ImpactProblemT<N, C>& pb, const Vec& qdot, const RefVec& ref) {
  const Eigen::VectorXd d = Eigen::VectorXd(qdot) - Eigen::VectorXd(ref);
  const Eigen::MatrixXd M = pb.M;
  const Eigen::VectorXd qA = pb.qdot_A;
  return std::sqrt(d.dot(M * d) / qA.dot(M * qA));
}

/// The tolerance a converged result promises for its method.
inline double promised_tolerance(const SolverOptions& options, SolverMethod method) {
  return method == SolverMethod::nlopt ? options.nlopt_accepts() : options.tolerance;
}

template <int N, int C>
std::string check_result(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                         const SolverOptions& options, const ImpactResultT<N, C>& r,
                         CheckStats* stats = nullptr) {
  using detail::all_finite;
  using detail::num;
  const double eps = std::numeric_limits<double>::epsilon();
  const int n = pb.dofs(), c = pb.contacts();
  const SolverStatus status = r.solver.status;
  const std::string tag = " [status " + std::string(to_string(status)) + ", method " +
                          std::string(to_string(r.solver.method)) + ": " +
                          std::string(r.solver.message) + "]";

  // 1. The solver ran.
  if (status == SolverStatus::not_run) return "status not_run after solve_impact" + tag;
  if (r.solver.method == SolverMethod::automatic) return "method left as automatic" + tag;

  // 2. Sizes, then finiteness.
  if (r.qdot_E.size() != n)
    return "qdot_E has " + std::to_string(r.qdot_E.size()) + " entries" + tag;
  for (auto [name, size] : {std::pair{"P_N", r.P_N.size()},
                            {"P_T", r.P_T.size()},
                            {"D_NA", r.D_NA.size()},
                            {"D_NE", r.D_NE.size()},
                            {"D_TA", r.D_TA.size()},
                            {"D_TE", r.D_TE.size()},
                            {"takes_part", r.takes_part.size()},
                            {"admissibility.per_contact", r.admissibility.per_contact.size()}})
    if (size != c) return std::string(name) + " has " + std::to_string(size) + " entries" + tag;
  if (r.P_N_reaction.size() != 0 && r.P_N_reaction.size() != c)
    return "P_N_reaction has " + std::to_string(r.P_N_reaction.size()) + " entries" + tag;
  if (r.has_phases)
    for (auto [name, size] : {std::pair{"P_NC", r.P_NC.size()},
                              {"P_TC", r.P_TC.size()},
                              {"D_NC", r.D_NC.size()},
                              {"D_TC", r.D_TC.size()}})
      if (size != c) return std::string(name) + " has " + std::to_string(size) + " entries" + tag;
  if (r.has_phases && r.qdot_C.size() != n)
    return "qdot_C has " + std::to_string(r.qdot_C.size()) + " entries" + tag;

  for (auto [name, ok] : {std::pair{"qdot_E", all_finite(r.qdot_E)},
                          {"P_N", all_finite(r.P_N)},
                          {"P_T", all_finite(r.P_T)},
                          {"D_NA", all_finite(r.D_NA)},
                          {"D_NE", all_finite(r.D_NE)},
                          {"D_TA", all_finite(r.D_TA)},
                          {"D_TE", all_finite(r.D_TE)},
                          {"P_N_reaction", all_finite(r.P_N_reaction)},
                          {"energy_change", std::isfinite(r.energy_change)},
                          // no_solution: there is no answer whose residual could be measured
                          {"solver.residual", std::isfinite(r.solver.residual) ||
                                                  status == SolverStatus::no_solution}})
    if (!ok) return std::string("not finite: ") + name + tag;
  if (r.has_phases)
    for (auto [name, ok] : {std::pair{"P_NC", all_finite(r.P_NC)},
                            {"P_TC", all_finite(r.P_TC)},
                            {"D_NC", all_finite(r.D_NC)},
                            {"D_TC", all_finite(r.D_TC)},
                            {"qdot_C", all_finite(r.qdot_C)}})
      if (!ok) return std::string("not finite: ") + name + tag;
  const auto& a = r.admissibility;
  for (auto [name, v] : {std::pair{"total", a.total},
                         {"reaction", a.reaction},
                         {"dissipation", a.dissipation},
                         {"complementarity", a.complementarity},
                         {"penetration", a.penetration},
                         {"tolerance", a.tolerance},
                         {"violation", a.violation},
                         {"kinetic_energy_A", a.kinetic_energy_A},
                         {"fenchel_young_gap", a.fenchel_young_gap},
                         {"energy_change", a.energy_change}})
    if (std::isnan(v)) return std::string("NaN in admissibility.") + name + tag;
  // A contact's work −P·z is ±∞ only where one of its products overflows (docs/concepts.md).
  for (int i = 0; i < c; ++i) {
    const double pc = a.per_contact(i);
    const double zN = 0.5 * r.D_NA(i) + 0.5 * r.D_NE(i), zT = 0.5 * r.D_TA(i) + 0.5 * r.D_TE(i);
    const bool overflows = std::isinf(r.P_N(i) * zN) || std::isinf(r.P_T(i) * zT);
    if (std::isnan(pc) || (std::isinf(pc) && !overflows))
      return "not finite: admissibility.per_contact[" + std::to_string(i) + "] = " + num(pc) + tag;
  }

  // 3. Who takes part.
  const bool tangential = pb.has_tangential() && law.has_friction();
  for (int i = 0; i < c; ++i) {
    if ((r.takes_part(i) != 0) != (r.D_NA(i) <= 0.0))
      return "takes_part[" + std::to_string(i) + "] disagrees with D_NA = " + num(r.D_NA(i)) + tag;
    if (!tangential && r.P_T(i) != 0.0)
      return "P_T[" + std::to_string(i) + "] = " + num(r.P_T(i)) + " without friction" + tag;
  }

  // 4. Velocities agree with the percussions: q̇_E against q̇_A + M⁻¹(W_N P_N + W_T P_T), in the
  // energy norm, relative to the velocities' own size. Both sides carry the rounding of a solve
  // with M (about √cond(M)·eps in this norm, cond up to 1e12); a real disagreement is O(1).
  {
    const Eigen::MatrixXd M = pb.M;
    Eigen::VectorXd f = pb.W_N * Eigen::VectorXd(r.P_N);
    if (pb.has_tangential()) f += pb.W_T * Eigen::VectorXd(r.P_T);
    const Eigen::LLT<Eigen::MatrixXd> llt(M);
    const Eigen::VectorXd qA = pb.qdot_A, qE = r.qdot_E;
    const Eigen::VectorXd expected = qA + llt.solve(f);
    auto energy_norm = [&](const Eigen::VectorXd& v) {
      return std::sqrt(std::max(0.0, v.dot(M * v)));
    };
    // The percussions' own contributions, |W||P| term by term: where they cancel (repeated rows,
    // moving obstacles) q̇_E carries their rounding, not that of its (smaller) size.
    Eigen::VectorXd fabs_ = pb.W_N.cwiseAbs() * Eigen::VectorXd(r.P_N).cwiseAbs();
    if (pb.has_tangential()) fabs_ += pb.W_T.cwiseAbs() * Eigen::VectorXd(r.P_T).cwiseAbs();
    const double size =
        energy_norm(qA) + energy_norm(qE) + energy_norm(expected) + energy_norm(llt.solve(fabs_));
    const double gap = energy_norm(qE - expected);
    // A backward-stable solve errs by up to cond(M)·eps in this norm (relative).
    const Eigen::VectorXd ev =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M, Eigen::EigenvaluesOnly).eigenvalues();
    const double cond = ev(0) > 0 ? ev(n - 1) / ev(0) : 1e16;
    if (!(gap <= (1e-10 + 64 * (n + 1) * eps * cond) * size))
      return "qdot_E does not match the percussions: |q̇_E − (q̇_A + M⁻¹WP)|_M = " + num(gap) +
             " against velocities of size " + num(size) + tag;
    for (int i = 0; i < c; ++i) {
      const double wn = pb.w_N.size() ? pb.w_N(i) : 0.0;
      const double dne = pb.W_N.col(i).dot(Eigen::VectorXd(r.qdot_E)) + wn;
      const double s =
          pb.W_N.col(i).cwiseAbs().dot(Eigen::VectorXd(r.qdot_E).cwiseAbs()) + std::fabs(wn);
      if (std::fabs(dne - r.D_NE(i)) > 64 * eps * (n + 1) * s + 1e-300)
        return "D_NE[" + std::to_string(i) + "] = " + num(r.D_NE(i)) +
               " but W_Nᵀ q̇_E + w_N = " + num(dne) + tag;
    }
  }

  // 5. Converged: the law's own residual, recomputed.
  const double residual = law_residual(pb, law, r);
  const double promised = promised_tolerance(options, r.solver.method);
  // Recomputing velocities from the percussions rounds by about eps (|D_A| + |G||P|) per row,
  // relative to the velocity scale, and by eps times the terms the data's velocities are summed
  // from, |w_i| + |W_i|ᵀ|q̇_A| (a D_NA of 2e-17 from terms of 1e-12 is known to 1e-11 of itself;
  // the answer's q̇_E is not trusted for this); allow that on top of the promised tolerance.
  double v_scale = std::numeric_limits<double>::min(), p_scale = 0.0, w_scale = 0.0;
  double terms = 0.0;
  const Eigen::VectorXd q_abs = Eigen::VectorXd(pb.qdot_A).cwiseAbs();
  for (int i = 0; i < c; ++i) {
    p_scale = std::max({p_scale, std::fabs(r.P_N(i)), std::fabs(r.P_T(i))});
    if (!r.takes_part(i)) continue;
    v_scale = std::max({v_scale, std::fabs(r.D_NA(i)), std::fabs(r.D_TA(i))});
    double t = (pb.w_N.size() ? std::fabs(pb.w_N(i)) : 0.0) +
               Eigen::VectorXd(pb.W_N.col(i)).cwiseAbs().dot(q_abs);
    if (pb.has_tangential())
      t += (pb.w_T.size() ? std::fabs(pb.w_T(i)) : 0.0) +
           Eigen::VectorXd(pb.W_T.col(i)).cwiseAbs().dot(q_abs);
    if (std::isfinite(t)) terms = std::max(terms, t);
  }
  {
    Eigen::LLT<Eigen::MatrixXd> llt(Eigen::MatrixXd(pb.M));
    for (int i = 0; i < c; ++i) {
      w_scale = std::max(w_scale, pb.W_N.col(i).dot(llt.solve(Eigen::VectorXd(pb.W_N.col(i)))));
      if (pb.has_tangential())
        w_scale = std::max(w_scale, pb.W_T.col(i).dot(llt.solve(Eigen::VectorXd(pb.W_T.col(i)))));
    }
  }
  // (no percussion: no rounding from it, even where |W|² overflows and w_scale is infinite)
  const double rounding =
      1e3 * eps * (c + 1) *
      (1.0 + (p_scale == 0.0 ? 0.0 : w_scale * p_scale / v_scale) + terms / v_scale);
  const double bound = 10.0 * promised + rounding;
  if (stats) {
    stats->residual = residual;
    stats->residual_bound = bound;
  }
  if (status != SolverStatus::converged) return "";
  // The status's own definition (solver_status.hpp): converged means the residual it reports is
  // within the tolerance (no allowance: the solver's test on the solver's numbers), or, with the
  // criterion `rounding`, that the tolerance is below floating point's resolution for these data:
  // the residual must then be within this file's own, independent, estimate of that rounding.
  if (r.solver.criterion == StopCriterion::rounding) {
    if (!(r.solver.residual <= promised + rounding))
      return "converged at the rounding floor but the solver's own residual " +
             num(r.solver.residual) + " exceeds the rounding estimate " + num(rounding) + tag;
  } else if (!(r.solver.residual <= promised * (1.0 + 1e-9))) {
    return "converged but the solver's own residual " + num(r.solver.residual) +
           " exceeds the tolerance " + num(promised) + tag;
  }

  if (!(residual <= bound))
    return "converged but law_residual = " + num(residual) + " > " + num(bound) + " (promised " +
           num(promised) + ", solver reported " + num(r.solver.residual) + ")" + tag;
  // 6. Frémond: admissible; where a reaction stops a separating contact, (15) may fail.
  bool drives_separating = false;
  for (int i = 0; i < c; ++i)
    drives_separating |= !r.takes_part(i) && (r.P_N(i) != 0.0 || r.P_T(i) != 0.0);
  const bool energy_only =
      a.failed == Inequality::total_15 || a.failed == Inequality::per_contact_15;
  if (law.is<FremondLaw>() && !a.admissible && !(drives_separating && energy_only))
    return "converged Frémond result not admissible: " + std::string(to_string(a.failed)) +
           (a.failed_contact >= 0 ? " (contact " + std::to_string(a.failed_contact) + ")" : "") +
           " by " + num(a.violation) + tag;

  // 7. Frictionless classical laws: P_N ≥ 0 on every contact.
  const double p_floor = bound * v_scale / std::max(w_scale, 1e-300);
  if ((law.name() == "newton" || law.name() == "poisson")) {
    for (int i = 0; i < c; ++i)
      if (r.P_N(i) < -p_floor)
        return "P_N[" + std::to_string(i) + "] = " + num(r.P_N(i)) + " < 0" + tag;
  }
  // 8. Every law: no contact penetrates, and a separating one carries at most a reaction.
  for (int i = 0; i < c; ++i) {
    if (r.D_NE(i) < -bound * v_scale)
      return "contact " + std::to_string(i) + " penetrates: D_NE = " + num(r.D_NE(i)) +
             " (D_NA = " + num(r.D_NA(i)) + ")" + tag;
    if (!r.takes_part(i) && r.P_N(i) < -p_floor)
      return "separating contact " + std::to_string(i) + " pulled: P_N = " + num(r.P_N(i)) + tag;
  }
  return "";
}

}  // namespace fremond::robust
