// The last fallback for Frémond's law: NLopt's SLSQP on the velocity-space problem of docs/laws.md,
// which needs only each potential's value and one subgradient.
//
//   minimise  uᵀ M u + Σ φ_N(z_N) + Σ φ_T(z_T)     z = D_A + Wᵀu,  u = v − q̇_A
//   subject to D_NE = D_NA + 2 W_Nᵀ u ≥ 0,          then q̇_E = q̇_A + 2u.
// Coulomb's b|z_T| is non-smooth: it enters through epigraph variables t ≥ |z_T| with b = μ|P_N|
// updated in an outer fixed point (the law is quasi-variational). The percussion follows from the
// velocities: P_j = −φ'(z_j) on rows where φ is single-valued, and the remaining rows (active
// reactions, Coulomb) by least squares on W P = 2 M u (without Coulomb, where that family has
// several members, the one whose reactions are ≥ 0, by an LCP).
//
// A library call must return, and return nothing that is not finite:
//  - SLSQP only, also with Coulomb. MMA (and CCSAQ, which shares its inner loop) solve a dual
//    subproblem per iteration whose inner loop has no bound of its own; on the Coulomb epigraph
//    (objective linear in t, constraints ±z_T − t ≤ 0) it may never return
//    (tests/unit/regression_fremond_test.cpp). Every SLSQP iteration
//    evaluates the objective, and its LSQ subproblem stops after 3n iterations, so the evaluation
//    budget bounds it.
//  - The objective and the constraints stop NLopt (nlopt_force_stop) as soon as a value or a
//    gradient is not finite (a potential k|z|^p overflowing far from the answer), rather than let
//    NLopt go on from NaN; a wall-clock limit is the last backstop.
//  - The answer is the best finite iterate (least law residual) over the outer iterations, or no
//    percussion at all (q̇_E = q̇_A) if none is finite; its status says whether it converged.
#include <nlopt.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "fremond/solvers/lemke.hpp"
#include "solvers/detail/fremond.hpp"

namespace fremond::detail {

namespace {

struct NloptData {
  const MatrixX* M;
  const MatrixX* W;  // n × rows
  const VectorX* DA;
  const FremondLaw* law;
  int n, a, rows;
  bool coulomb, tangential;
  VectorX b;  // Coulomb bounds
  const std::vector<int>* contact;
  nlopt_opt opt = nullptr;  // the running optimiser, to stop it on a non-finite value
  bool breakdown = false;   // a value or gradient was not finite: NLopt was stopped
};

// Stops NLopt for good: SLSQP given NaN has no way back (its line search compares with NaN).
double stop_non_finite(NloptData& d) {
  d.breakdown = true;
  if (d.opt) nlopt_force_stop(d.opt);
  return std::numeric_limits<double>::max();
}

double objective(unsigned nx, const double* x, double* grad, void* data) {
  auto& d = *static_cast<NloptData*>(data);
  if (!Eigen::Map<const VectorX>(x, nx).allFinite()) return stop_non_finite(d);
  Eigen::Map<const VectorX> u(x, d.n);
  const VectorX Mu = (*d.M) * u;
  const VectorX z = *d.DA + d.W->transpose() * u;
  double f = u.dot(Mu);
  VectorX gz = VectorX::Zero(d.rows);
  for (int k = 0; k < d.a; ++k) {
    const Potential& pn = d.law->normal[(*d.contact)[k]];
    f += pn.value(z(k));
    gz(k) = pn.subgradient(z(k));
    if (d.tangential && !d.coulomb) {
      const Potential& pt = d.law->tangential_potential[(*d.contact)[k]];
      f += pt.value(z(d.a + k));
      gz(d.a + k) = pt.subgradient(z(d.a + k));
    }
  }
  if (d.coulomb)
    for (int k = 0; k < d.a; ++k) f += d.b(k) * x[d.n + k];
  if (grad) {
    Eigen::Map<VectorX> g(grad, nx);
    g.head(d.n) = 2.0 * Mu + (*d.W) * gz;
    if (d.coulomb) g.tail(d.a) = d.b;
    if (!g.allFinite()) return stop_non_finite(d);
  }
  if (!std::isfinite(f)) return stop_non_finite(d);
  return f;
}

// m constraints c(x) ≤ 0: −D_NE,k ≤ 0; with Coulomb also ±z_T,k − t_k ≤ 0.
void constraints(unsigned m, double* result, unsigned nx, const double* x, double* grad,
                 void* data) {
  auto& d = *static_cast<NloptData*>(data);
  Eigen::Map<const VectorX> u(x, d.n);
  if (!Eigen::Map<const VectorX>(x, nx).allFinite()) {
    std::fill(result, result + m, 0.0);
    if (grad) std::fill(grad, grad + m * nx, 0.0);
    stop_non_finite(d);
    return;
  }
  if (grad) std::fill(grad, grad + m * nx, 0.0);
  for (int k = 0; k < d.a; ++k) {
    result[k] = -((*d.DA)(k) + 2.0 * d.W->col(k).dot(u));
    if (grad)
      for (int i = 0; i < d.n; ++i) grad[k * nx + i] = -2.0 * (*d.W)(i, k);
  }
  if (!d.coulomb) return;
  for (int k = 0; k < d.a; ++k) {
    const int j = d.a + k;
    const double zt = (*d.DA)(j) + d.W->col(j).dot(u);
    for (int s = 0; s < 2; ++s) {
      const double sg = s == 0 ? 1.0 : -1.0;
      const int row = d.a + 2 * k + s;
      result[row] = sg * zt - x[d.n + k];
      if (grad) {
        for (int i = 0; i < d.n; ++i) grad[row * nx + i] = sg * (*d.W)(i, j);
        grad[row * nx + d.n + k] = -1.0;
      }
    }
  }
}

// SLSQP stops where the objective no longer resolves the step, about √ε relative in u. A Newton
// polish of the KKT system, with the active set SLSQP found and the Hessian from differences of the
// subgradients, takes u to the last digits:
//   F(u, λ) = [2Mu + W s(z) − Σ λ_i ∇c_i ; c_A(u)] = 0,   s_j = φ_j'(z_j) (b sign z_T when
//   sliding),
// with c_i = D_NE,i = D_NA,i + 2 W_N,iᵀu for the contacts whose reaction acts (λ_i ≥ 0) and
// c_i = z_T,i for the contacts that stick under Coulomb (λ_i free). Kept only if its multipliers
// have the right sign and it keeps every other contact open; the caller keeps it only if the law's
// residual improves.
bool polish(NloptData& d, VectorX& u, double v_scale) {
  const int n = d.n, a = d.a, r = d.rows;
  struct Constraint {
    int row;        // column of W
    double factor;  // ∇c = factor · W_row
    bool signed_multiplier;
  };
  std::vector<Constraint> act;
  const VectorX z0 = *d.DA + d.W->transpose() * u;
  for (int k = 0; k < a; ++k)
    if ((*d.DA)(k) + 2.0 * d.W->col(k).dot(u) <= 1e-6 * v_scale) act.push_back({k, 2.0, true});
  std::vector<double> slide_sign(r, 0.0);
  if (d.coulomb)
    for (int k = 0; k < a; ++k) {
      const int j = a + k;
      if (std::fabs(z0(j)) <= 1e-6 * v_scale && d.b(k) > 0.0)
        act.push_back({j, 1.0, false});
      else
        slide_sign[j] = z0(j) > 0.0 ? 1.0 : -1.0;
    }
  const int m = static_cast<int>(act.size());
  auto smooth = [&](int j) -> const Potential* {
    if (j < a) return &d.law->normal[(*d.contact)[j]];
    if (d.coulomb) return nullptr;
    return &d.law->tangential_potential[(*d.contact)[j - a]];
  };
  auto constraint_value = [&](const VectorX& x, const Constraint& c) {
    return c.row < a ? (*d.DA)(c.row) + 2.0 * d.W->col(c.row).dot(x)
                     : (*d.DA)(c.row) + d.W->col(c.row).dot(x);
  };
  VectorX lambda = VectorX::Zero(m), x = u;
  for (int it = 0; it < 40; ++it) {
    const VectorX z = *d.DA + d.W->transpose() * x;
    VectorX s = VectorX::Zero(r), h = VectorX::Zero(r);
    for (int j = 0; j < r; ++j) {
      const Potential* pot = smooth(j);
      if (!pot) {  // Coulomb row: b sign(z_T) when sliding, a constraint when sticking
        s(j) = d.b(j - a) * slide_sign[j];
        continue;
      }
      s(j) = pot->subgradient(z(j));
      const double dz = 1e-8 * (std::fabs(z(j)) + v_scale);  // small: kinks of φ'' nearby
      h(j) = (pot->subgradient(z(j) + dz) - pot->subgradient(z(j) - dz)) / (2.0 * dz);
      if (!std::isfinite(h(j)) || h(j) < 0.0) h(j) = 0.0;
    }
    MatrixX K = MatrixX::Zero(n + m, n + m);
    VectorX F(n + m);
    K.topLeftCorner(n, n) = 2.0 * (*d.M) + (*d.W) * h.asDiagonal() * d.W->transpose();
    F.head(n) = 2.0 * ((*d.M) * x) + (*d.W) * s;
    for (int i = 0; i < m; ++i) {
      const VectorX g = act[i].factor * d.W->col(act[i].row);
      K.block(0, n + i, n, 1) = -g;
      K.block(n + i, 0, 1, n) = g.transpose();
      F.head(n) -= lambda(i) * g;
      F(n + i) = constraint_value(x, act[i]);
    }
    const VectorX step = K.fullPivLu().solve(-F);
    if (!step.allFinite()) return false;
    x += step.head(n);
    lambda += step.tail(m);
    if (step.head(n).norm() <= 4 * std::numeric_limits<double>::epsilon() * (x.norm() + 1e-300))
      break;
  }
  const double lscale = lambda.size() ? lambda.cwiseAbs().maxCoeff() : 0.0;
  for (int i = 0; i < m; ++i)
    if (act[i].signed_multiplier && lambda(i) < -1e-12 * (lscale + 1e-300)) return false;
  for (int k = 0; k < a; ++k)
    if ((*d.DA)(k) + 2.0 * d.W->col(k).dot(x) < -1e-12 * v_scale) return false;
  u = x;
  return true;
}

}  // namespace

// The wall-clock backstop of one NLopt solve. Never the intended stop: the evaluation budget
// bounds SLSQP (about 1e5 evaluations per second on the small problems of an impact); it only keeps
// a library call from running for ever should an NLopt algorithm loop without evaluating.
constexpr double kNloptSeconds = 10.0;

template <int N, int C>
MethodOutcome nlopt_velocity_space(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows,
                                   typename FremondRowsT<N, C>::Rows& P, const SolverOptions& opt) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(kNloptSeconds);
  const auto& cs = *rows.cs;
  MethodOutcome o;
  const int n = cs.dofs, a = cs.active, r = cs.rows();
  const MatrixX M = pb.M;
  const MatrixX W = cs.W;
  // NLopt works in y = Lᵀu (M = LLᵀ), where the kinetic term is |y|²: SLSQP's quasi-Newton model
  // then starts well conditioned whatever the mass ratios.
  const Eigen::LLT<MatrixX> llt(M);
  const MatrixX L = llt.matrixL();
  const MatrixX Iy = MatrixX::Identity(n, n);
  const MatrixX Wy = L.triangularView<Eigen::Lower>().solve(W);
  auto to_u = [&](const VectorX& y) -> VectorX {
    return L.transpose().triangularView<Eigen::Upper>().solve(y);
  };
  const VectorX DA = cs.D_A;
  std::vector<int> contact(a);
  for (int k = 0; k < a; ++k) contact[k] = cs.index(k);
  NloptData d{&Iy, &Wy,          &DA,           rows.law,         n,       a,
              r,   rows.coulomb, cs.tangential, VectorX::Zero(a), &contact};
  const int nx = n + (rows.coulomb ? a : 0);
  const int m = a + (rows.coulomb ? 2 * a : 0);
  // Whether q̇_E = q̇_A + M⁻¹WP is determined by P in double precision. Far from the answer
  // (a potential k|z|^p with p ~ 30 at large z) the least-squares recovery below can give
  // percussions of 1e22 whose velocity change cancels to 1e7: finite, but q̇_E then no longer
  // follows from P beyond its rounding ε Σ|M⁻¹W||P| (0.2 of it there). Such an iterate is not
  // an answer. The bound is 1e-8 of the velocities, not tighter: a body with cond(M) = 3e5 stopped
  // by three contacts has percussions whose terms cancel by 1e5 (a rounding of 3e-11), and with
  // 1e-11 no iterate of such a problem is usable; the law's residual decides the rest.
  auto resolved = [&](const VectorX& Pc) {
    if (Pc.size() != r || !Pc.allFinite()) return false;
    const VectorX dq = cs.MinvW * Pc;
    const double rounding =
        std::numeric_limits<double>::epsilon() * (cs.MinvW.cwiseAbs() * Pc.cwiseAbs()).maxCoeff();
    const double size = pb.qdot_A.cwiseAbs().maxCoeff() + dq.cwiseAbs().maxCoeff();
    return dq.allFinite() && rounding <= 1e-8 * size;
  };
  // The percussion given (an earlier method's last iterate), kept as the answer of last resort.
  const VectorX P_given = P;
  const bool given_usable = resolved(P_given);
  // Start from the given percussion's velocities (u = M⁻¹WP/2); without one, from the plastic
  // impact (every contact that takes part stopped, D_NE = 0: λ solves G_NN λ = −D_NA), which is
  // feasible: SLSQP started at an infeasible point can stop there on its step tolerance.
  std::vector<double> x(nx, 0.0);
  {
    VectorX u0;
    if (given_usable && P_given.cwiseAbs().maxCoeff() > 0.0) {
      u0 = 0.5 * (cs.MinvW * P_given);
    } else {
      const MatrixX GNN = cs.G.topLeftCorner(a, a);
      const VectorX lambda = GNN.completeOrthogonalDecomposition().solve(-DA.head(a));
      u0 = 0.5 * (cs.MinvW.leftCols(a) * lambda);
    }
    VectorX y0 = L.transpose() * u0;
    if (!y0.allFinite()) y0.setZero();  // u = 0 (no percussion) is finite, if not feasible
    for (int i = 0; i < n; ++i) x[i] = y0(i);
  }
  const double target = opt.nlopt_accepts() * cs.v_scale;
  // The percussion from the velocities, and the law's residual there.
  auto recover = [&](const VectorX& u, VectorX& Pout) {
    const VectorX z = DA + W.transpose() * u;
    const VectorX rhs = 2.0 * (M * u);
    std::vector<int> free_rows;
    VectorX known = VectorX::Zero(r);
    for (int j = 0; j < r; ++j) {
      const bool normal = j < a;
      const double lb = normal ? 0.5 * DA(j) : 0.0;
      const bool at_bound = normal && z(j) <= lb + 1e-9 * cs.v_scale;
      if (at_bound || (!normal && rows.coulomb)) {
        free_rows.push_back(j);
      } else {
        const Potential& pot =
            normal ? rows.law->normal[contact[j]] : rows.law->tangential_potential[contact[j - a]];
        known(j) = -pot.subgradient(z(j));
      }
    }
    Pout = known;
    if (!free_rows.empty()) {
      MatrixX Wf(n, free_rows.size());
      for (std::size_t i = 0; i < free_rows.size(); ++i) Wf.col(i) = W.col(free_rows[i]);
      const VectorX sol = Wf.completeOrthogonalDecomposition().solve(rhs - W * known);
      for (std::size_t i = 0; i < free_rows.size(); ++i) Pout(free_rows[i]) = sol(i);
    }
    auto law_residual = [&](const VectorX& Pc) {
      if (!resolved(Pc)) return std::numeric_limits<double>::infinity();
      typename FremondRowsT<N, C>::Rows Pr = Pc, zr, R;
      return rows.residual(Pr, zr, R);
    };
    const double plain = law_residual(Pout);
    // More contacts at rest (D_NE = 0) than W's rank: the percussions that make 2Mu are a family,
    // and the law takes the one whose reactions are ≥ 0 (P_j ≥ −φ'(z_j)), which the minimum-norm
    // one above need not be (three contacts on a body of 2 dofs with p = 1.0001: no iterate is
    // usable otherwise). Without Coulomb those rows are the only free ones, and that choice is a
    // nonnegative least-squares problem in the metric of M⁻¹: with P_f = b_f + s, s ≥ 0 ⊥ G_ff s −
    // W_fᵀM⁻¹(rhs − W·known − W_f b_f) ≥ 0, a symmetric positive semidefinite LCP, which Lemke
    // solves (a ray: 2Mu is not reached with reactions ≥ 0). Kept where its residual is the lower.
    if (rows.coulomb || free_rows.size() < 2 || plain == 0.0) return plain;
    const int f = static_cast<int>(free_rows.size());
    MatrixX Wf(n, f);
    VectorX base(f);
    for (int i = 0; i < f; ++i) {
      const int j = free_rows[i];
      Wf.col(i) = W.col(j);
      base(i) = -rows.law->normal[contact[j]].subgradient(z(j));
    }
    const VectorX b = rhs - W * known - Wf * base;
    const MatrixX MinvWf = llt.solve(Wf);
    const MatrixX Gff = Wf.transpose() * MinvWf;
    const VectorX q = -(MinvWf.transpose() * b);
    if (!Gff.allFinite() || !q.allFinite()) return plain;
    const LcpResult lcp = solve_lcp<Dynamic>(0.5 * (Gff + Gff.transpose()), q);
    if (!lcp.ok()) return plain;
    VectorX Pn = Pout;
    for (int i = 0; i < f; ++i) Pn(free_rows[i]) = base(i) + std::max(0.0, lcp.z(i));
    const double bounded = law_residual(Pn);
    if (!(bounded < plain)) return plain;
    Pout = Pn;
    return bounded;
  };
  int evaluations = 0;
  bool breakdown = false, out_of_time = false, out_of_budget = false, settled = !rows.coulomb;
  // The best finite iterate over the outer iterations (least residual of the law).
  VectorX P_best;
  double best = std::numeric_limits<double>::infinity();
  nlopt_result code = NLOPT_FAILURE;
  for (int outer = 0; outer < (rows.coulomb ? 100 : 1); ++outer) {
    const double seconds_left = std::chrono::duration<double>(deadline - Clock::now()).count();
    if (seconds_left <= 0.0) {
      out_of_time = true;
      break;
    }
    // SLSQP in every case (see the file comment for why not MMA): with Coulomb, its
    // constraints ±z_T − t ≤ 0 are linear, which its LSQ subproblem takes exactly.
    nlopt_opt solver = nlopt_create(NLOPT_LD_SLSQP, nx);
    d.opt = solver;
    d.breakdown = false;
    nlopt_set_min_objective(solver, objective, &d);
    // SLSQP returns its best *feasible* point. On an active constraint its iterates are off by
    // the rounding of z = D_A + Wᵀu (a few ε of the velocities): with a tolerance of 0 every one
    // of them counts as infeasible and SLSQP hands back its start (with Coulomb: the previous
    // fixed point's answer, whatever b now is). The polish below and the law's residual, not this
    // tolerance, decide the answer's accuracy.
    std::vector<double> ctol(m, 1e-12 * cs.v_scale);
    nlopt_add_inequality_mconstraint(solver, m, constraints, &d, ctol.data());
    nlopt_set_xtol_rel(solver, 1e-15);
    nlopt_set_maxeval(solver, std::max(1, opt.max_nlopt_evaluations - evaluations));
    nlopt_set_maxtime(solver, seconds_left);
    if (rows.coulomb) {
      const VectorX zt =
          DA.tail(a) + Wy.rightCols(a).transpose() * Eigen::Map<const VectorX>(x.data(), n);
      for (int k = 0; k < a; ++k) x[n + k] = std::fabs(zt(k));
    }
    const std::vector<double> x_start = x;
    double f = 0.0;
    code = nlopt_optimize(solver, x.data(), &f);
    evaluations += nlopt_get_numevals(solver);
    nlopt_destroy(solver);
    d.opt = nullptr;
    breakdown = breakdown || d.breakdown;
    // SLSQP hands back its best feasible point; should that not be finite, its start.
    if (!Eigen::Map<const VectorX>(x.data(), nx).allFinite()) x = x_start;
    VectorX u = Eigen::Map<const VectorX>(x.data(), n);  // y
    VectorX Pv;
    double res = recover(to_u(u), Pv);
    if (u.allFinite()) {
      VectorX up = u, Pp;
      if (polish(d, up, cs.v_scale)) {
        const double resp = recover(to_u(up), Pp);
        if (resp < res) {
          res = resp;
          Pv = Pp;
          for (int i = 0; i < n; ++i) x[i] = up(i);
        }
      }
    }
    if (std::isfinite(res) && res < best) {
      best = res;
      P_best = Pv;
    }
    if (code == NLOPT_MAXTIME_REACHED) out_of_time = true;
    if (code == NLOPT_MAXEVAL_REACHED || evaluations >= opt.max_nlopt_evaluations)
      out_of_budget = true;
    if (!rows.coulomb || out_of_time || out_of_budget || !std::isfinite(res)) break;
    VectorX bnew(a);
    for (int k = 0; k < a; ++k) bnew(k) = rows.law->mu[contact[k]] * std::fabs(Pv(k));
    const double change = (bnew - d.b).cwiseAbs().maxCoeff();
    d.b = bnew;
    if (change <= 1e-14 * (bnew.cwiseAbs().maxCoeff() + 1e-300)) {
      settled = true;
      break;
    }
  }
  o.native_code = static_cast<int>(code);
  o.iterations = evaluations;
  o.criterion = StopCriterion::nlopt;
  typename FremondRowsT<N, C>::Rows zr, R;
  if (P_best.size() != r) {
    // No finite (and resolved) iterate at all: the given percussion if it is one, else none (q̇_E =
    // q̇_A). Either way q̇_E follows from P (q̇_E = q̇_A + M⁻¹WP) and nothing non-finite leaves the
    // library.
    if (given_usable)
      P = P_given;
    else
      P.setZero(r);
    o.residual = rows.residual(P, zr, R);
    if (!std::isfinite(o.residual)) o.residual = std::numeric_limits<double>::max();
    o.status = SolverStatus::failed;
    o.message = given_usable
                    ? "NLopt: no usable iterate; the percussion given to it is returned"
                    : "NLopt: no usable iterate; no percussion is returned (qdot_E = qdot_A)";
    return o;
  }
  P = P_best;
  o.residual = rows.residual(P, zr, R);
  if (rows.converged(P, R, target)) {
    o.status = SolverStatus::converged;
    o.message = "NLopt (SLSQP) converged to the NLopt tolerance";
  } else if (breakdown) {
    o.status = SolverStatus::failed;
    o.message =
        "NLopt: a value or gradient of the objective was not finite (overflow far from the "
        "answer); stopped, the best finite iterate is returned";
  } else if (out_of_time) {
    o.status = SolverStatus::max_iterations;
    o.message = "NLopt: time limit reached above tolerance; the best finite iterate is returned";
  } else if (out_of_budget) {
    o.status = SolverStatus::max_iterations;
    o.message =
        "NLopt: evaluation budget exhausted above tolerance; the best finite iterate is "
        "returned";
  } else if (!settled) {
    // Coulomb's bound b = μ|P_N| cycles (e.g. between stick with P_N = 0 and slip with P_N > 0
    // where the law may have no solution): the rounds are bounded, the answer says so.
    o.status = SolverStatus::stalled;
    o.message =
        "NLopt: the fixed point on Coulomb's bound b = mu|P_N| did not settle; the best "
        "finite iterate is returned";
  } else {
    o.status = SolverStatus::stalled;
    o.message =
        "NLopt stopped with the residual above tolerance; the best finite iterate is "
        "returned";
  }
  return o;
}

#define FREMOND_INSTANTIATE(N, C)                                          \
  template MethodOutcome nlopt_velocity_space(const ImpactProblemT<N, C>&, \
                                              const FremondRowsT<N, C>&,   \
                                              FremondRowsT<N, C>::Rows&, const SolverOptions&);
FREMOND_INSTANTIATE(Dynamic, Dynamic)
FREMOND_INSTANTIATE(kSmallDofs, kSmallContacts)
#undef FREMOND_INSTANTIATE

}  // namespace fremond::detail
