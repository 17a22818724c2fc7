// Semismooth Newton on the contacts' modes (mode_newton.hpp, docs/sparse.md#mode-newton).
#include "solvers/nsgs/mode_newton.hpp"

#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <vector>

namespace fremond::detail {

namespace {

enum class Mode : signed char { apart, stick, slide };

// Mode equations of at most this many unknowns are factored dense.
constexpr int kDenseUnknowns = 96;

// A contact's mode and, sliding, the sign s of P_T = s μ P_N.
struct ContactMode {
  Mode mode = Mode::apart;
  double s = 0.0;
  bool operator==(const ContactMode&) const = default;
};

// The modes the natural map reads at P: apart where P_N − w_N/G_NN ≤ 0; else stuck where the
// tangential point P_T − D_TE/G_TT lies inside μ times the normal one, sliding its way otherwise.
std::vector<ContactMode> modes_at(const Layout& L, const Eigen::VectorXd& P,
                                  const Eigen::VectorXd& D_E) {
  std::vector<ContactMode> modes(static_cast<std::size_t>(L.contacts));
  for (int i = 0; i < L.contacts; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const auto& A = L.block[k];
    const int r = L.step * i;
    const double sigma_N = P(r) - (D_E(r) + L.shift[k]) / A.a;
    if (!(sigma_N > 0.0)) continue;
    if (L.step == 1) {
      modes[k] = {Mode::stick, 0.0};
      continue;
    }
    if (L.mu[k] == 0.0) {
      modes[k] = {Mode::slide, 0.0};
      continue;
    }
    const double g = A.d > 0.0 ? A.d : A.a;
    const double sigma_T = P(r + 1) - D_E(r + 1) / g;
    if (std::fabs(sigma_T) <= L.mu[k] * sigma_N)
      modes[k] = {Mode::stick, 0.0};
    else
      modes[k] = {Mode::slide, sigma_T > 0.0 ? 1.0 : -1.0};
  }
  return modes;
}

// The mode's equations A x = b on the unknowns x (a contact's P_N, and its P_T where it sticks),
// one equation a row held at zero velocity; the percussions are then P = E x. With the layout's
// velocity factors A = Uᵀ V (U: W's columns of the equations' rows, V = X E), n × unknowns each,
// and A itself is not formed.
struct ModeSystem {
  Eigen::SparseMatrix<double> A;
  Eigen::MatrixXd U, V;
  Eigen::VectorXd b, scale;  // scale: each equation's own G diagonal
  std::vector<int> unknown;  // contact → its first unknown, −1 apart
  std::vector<int> row_of;   // unknown → its row of G

  // Coefficient-wise products (lazyProduct): n is a rigid body's few degrees of freedom, where a
  // general matrix-vector kernel's set-up costs more than the products.
  Eigen::VectorXd times(const Eigen::VectorXd& x) const {
    if (U.size() == 0) return A * x;
    const Eigen::VectorXd v = V.lazyProduct(x);
    return U.transpose().lazyProduct(v);
  }
};

// The velocity factors of the mode: U's column `eq` is W's column of the equation's row; V's
// column of a contact's normal unknown is X's normal column, plus s μ its tangential one where it
// slides (P_T = s μ P_N), and of a sticking contact's tangential unknown X's tangential column.
void velocity_factors_of(const Layout& L, const std::vector<ContactMode>& modes, ModeSystem& S) {
  const auto n = L.X.rows(), u = static_cast<Eigen::Index>(S.row_of.size());
  S.U.resize(n, u);
  S.V.resize(n, u);
  for (Eigen::Index eq = 0; eq < u; ++eq)
    S.U.col(eq) = L.W.col(S.row_of[static_cast<std::size_t>(eq)]);
  for (int i = 0; i < L.contacts; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const int x = S.unknown[k];
    if (x < 0) continue;
    const int r = L.step * i;
    S.V.col(x) = L.X.col(r);
    if (L.step == 1) continue;
    if (modes[k].mode == Mode::stick)
      S.V.col(x + 1) = L.X.col(r + 1);
    else if (modes[k].s != 0.0)
      S.V.col(x) += (modes[k].s * L.mu[k]) * L.X.col(r + 1);
  }
}

ModeSystem system_of(const Layout& L, const Eigen::VectorXd& D_A,
                     const std::vector<ContactMode>& modes) {
  ModeSystem S;
  S.unknown.assign(modes.size(), -1);
  for (int i = 0; i < L.contacts; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (modes[k].mode == Mode::apart) continue;
    S.unknown[k] = static_cast<int>(S.row_of.size());
    S.row_of.push_back(L.step * i);
    if (L.step == 2 && modes[k].mode == Mode::stick) S.row_of.push_back(L.step * i + 1);
  }
  const int n = static_cast<int>(S.row_of.size());
  S.b.resize(n);
  S.scale.resize(n);
  for (int eq = 0; eq < n; ++eq) {
    const int R = S.row_of[static_cast<std::size_t>(eq)];
    const auto& B = L.block[static_cast<std::size_t>(R / L.step)];
    const bool normal = R % L.step == 0;
    S.b(eq) = -(D_A(R) + (normal ? L.shift[static_cast<std::size_t>(R / L.step)] : 0.0));
    S.scale(eq) = normal ? B.a : (B.d > 0.0 ? B.d : B.a);
  }
  if (L.has_velocity_factors()) {
    velocity_factors_of(L, modes, S);
    return S;
  }
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(n) * 12);
  for (int eq = 0; eq < n; ++eq) {
    const int R = S.row_of[static_cast<std::size_t>(eq)];
    for (int p = L.G.outerIndexPtr()[R]; p < L.G.outerIndexPtr()[R + 1]; ++p) {
      const int j = L.G.innerIndexPtr()[p];
      const double v = L.G.valuePtr()[p];
      const auto k = static_cast<std::size_t>(j / L.step);
      const int u = S.unknown[k];
      if (u < 0) continue;
      const bool tangent_column = j % L.step == 1;
      if (modes[k].mode == Mode::stick)
        entries.emplace_back(eq, u + (tangent_column ? 1 : 0), v);
      else if (!tangent_column)
        entries.emplace_back(eq, u, v);
      else if (modes[k].s != 0.0)
        entries.emplace_back(eq, u, v * modes[k].s * L.mu[k]);
    }
  }
  S.A.resize(n, n);
  S.A.setFromTriplets(entries.begin(), entries.end());
  return S;
}

// The proximal steps x += K⁻¹(b − A x) with K = A + δ D applied by `solve`, until the equations'
// residual is below 1e-3 of the target or stops halving (four at most).
template <class Solve>
bool refine(const ModeSystem& S, double target, const Solve& solve, Eigen::VectorXd& x) {
  double last = std::numeric_limits<double>::infinity();
  for (int step = 0; step < 4 && x.allFinite(); ++step) {
    const Eigen::VectorXd r = S.b - S.times(x);
    const double size = r.lpNorm<Eigen::Infinity>();
    if (size <= 1e-3 * target || !(size < 0.5 * last)) break;
    last = size;
    x += solve(r);
  }
  return x.allFinite();
}

// x with A x = b from x (the current point's unknowns): A is singular where G is, and its
// solutions then differ by percussions that move no velocity, of which the one nearest the
// current point keeps its signs and cone. (A + δ D) Δ = b − A x, D each equation's G diagonal,
// repeated: the proximal-point iteration, whose limit is that nearest solution. False when the
// factorisation fails.
bool solve_mode(const ModeSystem& S, double target, double delta, Eigen::VectorXd& x) {
  if (S.U.size() != 0) {
    // Woodbury: with B = δ D, (B + Uᵀ V)⁻¹ r = B⁻¹ r − B⁻¹ Uᵀ H⁻¹ V B⁻¹ r, H = I + V B⁻¹ Uᵀ of
    // size n. Its cancellation where δ is small is the refinement's to correct.
    const Eigen::VectorXd inv = (delta * S.scale).cwiseInverse();
    Eigen::MatrixXd H = S.V * inv.asDiagonal() * S.U.transpose();
    H.diagonal().array() += 1.0;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(H);
    return refine(
        S, target,
        [&](const Eigen::VectorXd& r) {
          const Eigen::VectorXd y = inv.cwiseProduct(r);
          const Eigen::VectorXd z = lu.solve(S.V.lazyProduct(y));
          return (y - inv.cwiseProduct(S.U.transpose().lazyProduct(z))).eval();
        },
        x);
  }
  Eigen::SparseMatrix<double> K = S.A;
  for (int j = 0; j < K.rows(); ++j) K.coeffRef(j, j) += delta * S.scale(j);
  // A few dozen unknowns (a plate on many contacts: G dense) factor faster dense.
  if (K.rows() <= kDenseUnknowns) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu{Eigen::MatrixXd(K)};
    return refine(
        S, target, [&](const Eigen::VectorXd& r) { return lu.solve(r).eval(); }, x);
  }
  K.makeCompressed();
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(K);
  if (lu.info() != Eigen::Success) return false;
  return refine(
      S, target, [&](const Eigen::VectorXd& r) { return lu.solve(r).eval(); }, x);
}

}  // namespace

ModeNewtonOutcome mode_newton(const Layout& L, const Eigen::VectorXd& D_A, Eigen::VectorXd& P,
                              Measure& m, double target, int max_steps) {
  ModeNewtonOutcome out;
  auto met = [target](const Measure& x) { return x.residual <= target || x.excess <= target; };
  out.converged = met(m);
  Eigen::VectorXd at = P;
  Measure here = m;
  // The proximal weight δ adapts as Levenberg–Marquardt's does: far from the answer the modes
  // read are wrong, their equations inconsistent, and a large δ keeps the step short; a full
  // step accepted shrinks it toward Newton's.
  double delta = 1e-4;
  int failures = 0, slow = 0;
  while (!out.converged && out.steps < max_steps && failures < 4 && slow < 2) {
    const std::vector<ContactMode> modes = modes_at(L, at, here.D_E);
    const ModeSystem S = system_of(L, D_A, modes);
    Eigen::VectorXd x(static_cast<Eigen::Index>(S.row_of.size()));
    for (std::size_t u = 0; u < S.row_of.size(); ++u)
      x(static_cast<Eigen::Index>(u)) = at(S.row_of[u]);
    if (!S.row_of.empty() && !solve_mode(S, target, delta, x)) break;
    ++out.steps;
    Eigen::VectorXd next = Eigen::VectorXd::Zero(at.size());
    for (int i = 0; i < L.contacts; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const int u = S.unknown[k];
      if (u < 0) continue;
      const int r = L.step * i;
      next(r) = x(u);
      if (L.step == 2)
        next(r + 1) = modes[k].mode == Mode::stick ? x(u + 1) : modes[k].s * L.mu[k] * x(u);
    }
    // Backtracking on ½ Σ R² (Armijo): the mode's equations are its Jacobian on the branch read
    // at the current point, so the step descends it.
    const Eigen::VectorXd d = next - at;
    const double f0 = here.squares;
    double t = 1.0;
    for (; t > 0.01; t *= 0.5)
      if (measure(L, D_A, at + t * d).squares <= (1.0 - 1e-4 * t) * f0) break;
    if (!(t > 0.01)) {
      delta *= 10.0;
      ++failures;
      continue;
    }
    failures = 0;
    delta = t == 1.0 ? std::max(0.1 * delta, 1e-12) : std::min(4.0 * delta, 1.0);
    at += t * d;
    const double before = here.residual;
    here = measure(L, D_A, at);
    // Newton, once its modes are right, ends in a step or two; steps that do not halve the
    // residual are the sweeps' work, done cheaper by the sweeps.
    slow = here.residual > 0.5 * before ? slow + 1 : 0;
    if (here.residual < m.residual) {
      P = at;
      m = here;
      out.converged = met(m);
    }
  }
  return out;
}

}  // namespace fremond::detail
