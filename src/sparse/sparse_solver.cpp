// Newton's law, with or without Coulomb friction, on sparse problems: nonsmooth Gauss–Seidel over
// the contacts (docs/sparse.md), the natural-map residual and the certificate in contact
// coordinates, each at a cost linear in the non-zeros of G.
#include "fremond/sparse/sparse_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"
#include "solvers/nsgs/contact_rows.hpp"
#include "solvers/nsgs/sweeps.hpp"
#include "sparse/detail/mass_inverse.hpp"

namespace fremond {

namespace {

using detail::Layout;
using detail::Measure;
using detail::measure;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// The sweeps' view of a problem in contact coordinates under Newton's law.
Layout layout_of(const ContactProblem& pb, const RestitutionLaw& law) {
  std::vector<double> e, mu;
  for (int i = 0; i < pb.contacts(); ++i) {
    e.push_back(law.e[i]);
    mu.push_back(law.coulomb ? law.mu[i] : 0.0);
  }
  Layout L = detail::layout(pb.G, pb.D_A, pb.tangential, law.coulomb, e, mu);
  L.G_rounding = pb.G_rounding;
  L.D_A_rounding = pb.D_A_rounding;
  return L;
}

// The certificate of a classical law in contact coordinates (docs/concepts.md): (15) in sum and
// per contact, and non-penetration, each to how well the energies and velocities are known (their
// rounding, and the data's where the problem's numbers were given with fewer digits).
void certify(const Layout& L, const Measure& m, ImpactResult& r, double kinetic_A,
             const SparseSolverOptions& options) {
  auto& rep = r.admissibility;
  const int c = L.contacts;
  rep.kinetic_energy_A = kinetic_A;
  rep.energy_change = r.energy_change;
  rep.per_contact.setZero(c);
  double p_scale = 0.0, energy_rounding = 0.0, pen = 0.0;
  int worst = -1;
  double worst_value = 0.0;
  for (int i = 0; i < c; ++i) {
    const int row = L.step * i;
    p_scale = std::max({p_scale, std::fabs(r.P_N(i)), std::fabs(r.P_T(i))});
    const double zN = 0.5 * r.D_NA(i) + 0.5 * r.D_NE(i), zT = 0.5 * r.D_TA(i) + 0.5 * r.D_TE(i);
    const double pc = -(r.P_N(i) * zN + r.P_T(i) * zT);
    rep.per_contact(i) = pc;
    if (pc < worst_value && r.takes_part(i)) {
      worst_value = pc;
      worst = i;
    }
    auto known = [&m](int j) { return m.rounding(j) + (m.data.size() ? m.data(j) : 0.0); };
    const double rounding = std::max(known(row), L.step == 2 ? known(row + 1) : 0.0);
    const double dz = std::max(rounding, std::max(8 * kEps, 2 * options.tolerance) * L.v_scale);
    energy_rounding += (std::fabs(r.P_N(i)) + std::fabs(r.P_T(i))) * dz;
    const double dv = std::max(rounding, std::max(8 * kEps, options.tolerance) * L.v_scale);
    pen = std::max(pen, std::max(0.0, -r.D_NE(i) - 2 * dv) / L.v_scale);
  }
  rep.total = rep.per_contact.sum();
  rep.dissipation = rep.total;
  rep.penetration = pen;
  const double reference = std::isfinite(kinetic_A) ? kinetic_A : p_scale * L.v_scale;
  rep.tolerance = std::max(std::max(options.admissibility_tolerance, 64 * kEps) *
                               std::max(reference, std::numeric_limits<double>::min()),
                           energy_rounding);
  const double tol = rep.tolerance;
  auto fail = [&rep](Inequality what, double by, int contact = -1) {
    rep.failed = what;
    rep.violation = by;
    rep.failed_contact = contact;
  };
  if (!std::isfinite(rep.total) || rep.total < -tol)
    fail(Inequality::total_15, rep.total);
  else if (worst >= 0 && worst_value < -tol)
    fail(Inequality::per_contact_15, worst_value, worst);
  else if (pen > std::max(options.admissibility_tolerance, 1e-12))
    fail(Inequality::non_penetration, pen);
  rep.admissible = rep.failed == Inequality::none;
}

// The rows of P and D into the result's per-contact vectors.
void scatter(const Layout& L, const ContactProblem& pb, const Eigen::VectorXd& P,
             const Eigen::VectorXd& D_E, ImpactResult& r) {
  const int c = L.contacts;
  for (auto* v : {&r.P_N, &r.P_T, &r.D_NA, &r.D_TA, &r.D_NE, &r.D_TE, &r.P_N_reaction})
    v->setZero(c);
  r.takes_part.resize(c);
  for (int i = 0; i < c; ++i) {
    const int row = L.step * i;
    r.P_N(i) = P(row);
    r.D_NA(i) = pb.D_A(row);
    r.D_NE(i) = D_E(row);
    r.takes_part(i) = pb.D_A(row) <= 0.0;
    if (L.step == 1) continue;
    r.P_T(i) = P(row + 1);
    r.D_TA(i) = pb.D_A(row + 1);
    r.D_TE(i) = D_E(row + 1);
  }
}

// The percussions of `start` as rows; `clip` keeps the normal ones ≥ 0 (a starting point).
Eigen::VectorXd rows_of(const ContactProblem& pb, const ImpactResult* start, bool clip) {
  Eigen::VectorXd P = Eigen::VectorXd::Zero(pb.rows());
  if (!start) return P;
  const int c = pb.contacts();
  if (start->P_N.size() != c || (pb.tangential && start->P_T.size() != c))
    throw InvalidArgument("start", "must hold the percussions of the problem's " +
                                       std::to_string(c) + " contacts, got " +
                                       std::to_string(start->P_N.size()));
  for (int i = 0; i < c; ++i) {
    const double PN = start->P_N(i), PT = pb.tangential ? start->P_T(i) : 0.0;
    if (!std::isfinite(PN) || !std::isfinite(PT))
      throw InvalidArgument("start",
                            "contact " + std::to_string(i) + ": the percussions must be finite");
    P(pb.tangential ? 2 * i : i) = clip ? std::max(PN, 0.0) : PN;
    if (pb.tangential) P(2 * i + 1) = PT;
  }
  return P;
}

ImpactResult solve(const ContactProblem& pb, const ImpactLaw& law,
                   const SparseSolverOptions& options, const ImpactResult* start,
                   double kinetic_A) {
  options.validate();
  const int c = pb.contacts();
  law.validate(c);
  ImpactResult r;
  r.solver.method = SolverMethod::nsgs;
  const RestitutionLaw* classical = law.get_if<RestitutionLaw>();
  if (!solved_sparse(law)) {
    r.solver.status = SolverStatus::unsupported;
    r.solver.criterion = StopCriterion::none;
    r.solver.message =
        "sparse problems are solved under Newton's law, with or without Coulomb friction (and "
        "Poisson's with e = 0, the same law); other laws need the dense solvers (solve_impact on "
        "an ImpactProblem)";
    r.solver.record(SolverMethod::nsgs, AttemptStart::none, SolverStatus::unsupported,
                    std::numeric_limits<double>::quiet_NaN());
    return r;
  }
  Eigen::VectorXd P = rows_of(pb, start, true);
  const Layout L = layout_of(pb, *classical);
  detail::SweepWorkspace ws;
  const detail::SweepOutcome o =
      detail::solve_by_sweeps(L, pb.D_A, P,
                              {.tolerance = options.tolerance,
                               .max_sweeps = options.max_sweeps,
                               .newton_polish = options.newton_polish,
                               .acceleration = options.acceleration},
                              start ? AttemptStart::none : AttemptStart::zero, r.solver, ws);
  const Measure& m = ws.measure;
  r.solver.status = o.status;
  r.solver.criterion = o.criterion;
  r.solver.message = o.message;
  r.solver.method = o.method;
  r.solver.iterations = o.iterations;
  r.solver.residual = m.residual / L.v_scale;
  // One answer is looked for: other solutions, or other percussions of the same velocities where
  // G is singular, are not ruled out (docs/concepts.md#existence-and-uniqueness).
  r.unique = false;
  scatter(L, pb, P, m.D_E, r);
  // T_E − T_A = P·z for fixed obstacles (eq. 9); solve_impact replaces it by the velocities'.
  r.energy_change = r.P_N.dot(0.5 * (r.D_NA + r.D_NE)) + r.P_T.dot(0.5 * (r.D_TA + r.D_TE));
  certify(L, m, r, kinetic_A, options);
  return r;
}

}  // namespace

bool solved_sparse(const ImpactLaw& law) {
  const RestitutionLaw* classical = law.get_if<RestitutionLaw>();
  return classical && (classical->kind == RestitutionLaw::Kind::newton ||
                       std::all_of(classical->e.values.begin(), classical->e.values.end(),
                                   [](double e) { return e == 0.0; }));
}

bool SparseSolverOptions::is_valid(std::string* why) const {
  auto no = [why](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (!(tolerance >= 1e-16 && tolerance <= 1e-2))
    return no("tolerance: must lie in [1e-16, 1e-2], got " + detail::format_number(tolerance));
  if (max_sweeps < 1) return no("max_sweeps: must be >= 1, got " + std::to_string(max_sweeps));
  if (!(admissibility_tolerance >= 0.0 && admissibility_tolerance < 1.0))
    return no("admissibility_tolerance: must lie in [0, 1), got " +
              detail::format_number(admissibility_tolerance));
  return true;
}

void SparseSolverOptions::validate() const {
  std::string why;
  if (is_valid(&why)) return;
  const auto colon = why.find(':');
  throw InvalidArgument(why.substr(0, colon), why.substr(colon + 2));
}

ImpactResult solve_contact_problem(const ContactProblem& problem, const ImpactLaw& law,
                                   const SparseSolverOptions& options, const ImpactResult* start) {
  validate(problem);
  return solve(problem, law, options, start, std::numeric_limits<double>::quiet_NaN());
}

ImpactResult solve_impact(const SparseImpactProblem& problem, const ImpactLaw& law,
                          const SparseSolverOptions& options, const ImpactResult* start) {
  const detail::ContactJacobians j = detail::contact_jacobians(problem);  // validates
  const SparseMatrix& X = j.X;
  const ContactProblem cp = detail::contact_form(problem, j.W, X);
  const int c = problem.contacts(), step = cp.tangential ? 2 : 1;
  const double T_A = 0.5 * problem.qdot_A.dot(problem.M * problem.qdot_A);
  ImpactResult r = solve(cp, law, options, start, T_A);
  if (r.solver.status == SolverStatus::unsupported) return r;
  Eigen::VectorXd P(cp.rows());
  for (int i = 0; i < c; ++i) {
    P(step * i) = r.P_N(i);
    if (cp.tangential) P(step * i + 1) = r.P_T(i);
  }
  const Eigen::VectorXd dq = X * P;
  r.qdot_E = problem.qdot_A + dq;
  r.energy_change = 0.5 * dq.dot(problem.M * (r.qdot_E + problem.qdot_A));
  r.admissibility.energy_change = r.energy_change;
  return r;
}

double contact_residual(const ContactProblem& problem, const ImpactLaw& law,
                        const ImpactResult& result) {
  validate(problem);
  const RestitutionLaw* classical = law.get_if<RestitutionLaw>();
  if (!classical) throw InvalidArgument("law", "contact_residual measures Newton's law only");
  const Eigen::VectorXd P = rows_of(problem, &result, false);
  const Layout L = layout_of(problem, *classical);
  return measure(L, problem.D_A, P).residual / L.v_scale;
}

}  // namespace fremond
