// The last fallback for Frémond's law: NLopt's SLSQP on the velocity-space problem of SPEC §2,
// which needs only each potential's value and one subgradient.
//
//   minimise  uᵀ M u + Σ φ_N(z_N) + Σ φ_T(z_T)     z = D_A + Wᵀu,  u = v − q̇_A
//   subject to D_NE = D_NA + 2 W_Nᵀ u ≥ 0,          then q̇_E = q̇_A + 2u.
// Coulomb's b|z_T| is non-smooth: it enters through epigraph variables t ≥ |z_T| with b = μ|P_N|
// updated in an outer fixed point (the law is quasi-variational). The percussion follows from the
// velocities: P_j = −φ'(z_j) on rows where φ is single-valued, and the remaining rows (active
// reactions, Coulomb) by least squares on W P = 2 M u.
#include <nlopt.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "detail/fremond.hpp"

namespace fremond::detail {

namespace {

struct NloptData {
  const MatrixX* M;
  const MatrixX* W;  // n × rows
  const VectorX* DA;
  const ImpactLaw* law;
  int n, a, rows;
  bool coulomb, tangential;
  VectorX b;  // Coulomb bounds
  const std::vector<int>* contact;
};

double objective(unsigned nx, const double* x, double* grad, void* data) {
  auto& d = *static_cast<NloptData*>(data);
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
  }
  return f;
}

// m constraints c(x) ≤ 0: −D_NE,k ≤ 0; with Coulomb also ±z_T,k − t_k ≤ 0.
void constraints(unsigned m, double* result, unsigned nx, const double* x, double* grad,
                 void* data) {
  auto& d = *static_cast<NloptData*>(data);
  Eigen::Map<const VectorX> u(x, d.n);
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
//   F(u, λ) = [2Mu + W s(z) − Σ λ_i ∇c_i ; c_A(u)] = 0,   s_j = φ_j'(z_j) (b sign z_T when sliding),
// with c_i = D_NE,i = D_NA,i + 2 W_N,iᵀu for the contacts whose reaction acts (λ_i ≥ 0) and
// c_i = z_T,i for the contacts that stick under Coulomb (λ_i free). Kept only if its multipliers have
// the right sign and it keeps every other contact open; the caller keeps it only if the law's
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
      if (std::fabs(z0(j)) <= 1e-6 * v_scale && d.b(k) > 0.0) act.push_back({j, 1.0, false});
      else slide_sign[j] = z0(j) > 0.0 ? 1.0 : -1.0;
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

template <int N, int C>
MethodOutcome nlopt_velocity_space(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows,
                                   typename FremondRowsT<N, C>::Rows& P, const SolverOptions& opt) {
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
  NloptData d{&Iy, &Wy, &DA, rows.law, n, a, r, rows.coulomb, cs.tangential, VectorX::Zero(a),
              &contact};
  const int nx = n + (rows.coulomb ? a : 0);
  const int m = a + (rows.coulomb ? 2 * a : 0);
  // Start from the given percussion's velocities (u = M⁻¹WP/2); without one, from the plastic
  // impact (every contact that takes part stopped, D_NE = 0: λ solves G_NN λ = −D_NA), which is
  // feasible: SLSQP started at an infeasible point can stop there on its step tolerance.
  std::vector<double> x(nx, 0.0);
  {
    VectorX u0;
    if (P.size() == r && P.allFinite() && P.cwiseAbs().maxCoeff() > 0.0) {
      u0 = 0.5 * (cs.MinvW * P);
    } else {
      const MatrixX GNN = cs.G.topLeftCorner(a, a);
      const VectorX lambda = GNN.completeOrthogonalDecomposition().solve(-DA.head(a));
      u0 = 0.5 * (cs.MinvW.leftCols(a) * lambda);
    }
    const VectorX y0 = L.transpose() * u0;
    for (int i = 0; i < n; ++i) x[i] = y0(i);
  }
  const double target = opt.nlopt_tolerance * cs.v_scale;
  int evaluations = 0;
  VectorX Pv = VectorX::Zero(r);
  for (int outer = 0; outer < (rows.coulomb ? 100 : 1); ++outer) {
    // SLSQP for smooth potentials; with Coulomb's epigraph variables (linear in t, no curvature)
    // SLSQP's quasi-Newton model stalls at the previous fixed point's answer, MMA does not.
    nlopt_opt solver = nlopt_create(rows.coulomb ? NLOPT_LD_MMA : NLOPT_LD_SLSQP, nx);
    nlopt_set_min_objective(solver, objective, &d);
    std::vector<double> ctol(m, 0.0);
    nlopt_add_inequality_mconstraint(solver, m, constraints, &d, ctol.data());
    nlopt_set_xtol_rel(solver, 1e-15);
    nlopt_set_maxeval(solver, std::max(1, opt.max_nlopt_evaluations - evaluations));
    if (rows.coulomb) {
      const VectorX zt = DA.tail(a) + Wy.rightCols(a).transpose() *
                                           Eigen::Map<const VectorX>(x.data(), n);
      for (int k = 0; k < a; ++k) x[n + k] = std::fabs(zt(k));
    }
    double f = 0.0;
    const nlopt_result code = nlopt_optimize(solver, x.data(), &f);
    evaluations += nlopt_get_numevals(solver);
    nlopt_destroy(solver);
    o.native_code = static_cast<int>(code);
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
          const Potential& pot = normal ? rows.law->normal[contact[j]]
                                        : rows.law->tangential_potential[contact[j - a]];
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
      typename FremondRowsT<N, C>::Rows Pr = Pout, zr, R;
      return rows.residual(Pr, zr, R);
    };
    VectorX u = Eigen::Map<const VectorX>(x.data(), n);  // y
    double res = recover(to_u(u), Pv);
    if (std::isfinite(res) || u.allFinite()) {
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
    if (!rows.coulomb) break;
    VectorX bnew(a);
    for (int k = 0; k < a; ++k) bnew(k) = rows.law->mu[contact[k]] * std::fabs(Pv(k));
    const double change = (bnew - d.b).cwiseAbs().maxCoeff();
    d.b = bnew;
    if (change <= 1e-14 * (bnew.cwiseAbs().maxCoeff() + 1e-300)) break;
    if (evaluations >= opt.max_nlopt_evaluations) break;
  }
  P = Pv;
  typename FremondRowsT<N, C>::Rows zr, R;
  o.residual = rows.residual(P, zr, R);
  o.iterations = evaluations;
  o.criterion = StopCriterion::nlopt;
  if (!std::isfinite(o.residual)) {
    o.status = SolverStatus::failed;
    o.message = "NLopt: the answer is not finite";
  } else if (rows.converged(P, R, target)) {
    o.status = SolverStatus::converged;
    o.message = "NLopt (SLSQP) converged to the NLopt tolerance";
  } else if (o.native_code == NLOPT_MAXEVAL_REACHED) {
    o.status = SolverStatus::max_iterations;
    o.message = "NLopt: evaluation budget exhausted above tolerance";
  } else {
    o.status = SolverStatus::stalled;
    o.message = "NLopt stopped with the residual above tolerance";
  }
  return o;
}

#define FREMOND_INSTANTIATE(N, C)                                                                  \
  template MethodOutcome nlopt_velocity_space(const ImpactProblemT<N, C>&,                        \
                                              const FremondRowsT<N, C>&,                          \
                                              FremondRowsT<N, C>::Rows&, const SolverOptions&);
FREMOND_INSTANTIATE(Dynamic, Dynamic)
FREMOND_INSTANTIATE(kSmallDofs, kSmallContacts)
#undef FREMOND_INSTANTIATE

}  // namespace fremond::detail
