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
void modes_at(const Layout& L, const Eigen::VectorXd& P, const Eigen::VectorXd& D_E,
              std::vector<ContactMode>& modes) {
  modes.assign(static_cast<std::size_t>(L.contacts), ContactMode{});
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
}

// The mode's equations A x = b on the unknowns x (a contact's P_N, and its P_T where it sticks),
// one equation a row held at zero velocity; the percussions are then P = E x. With the layout's
// velocity factors A = Uᵀ V (U: W's columns of the equations' rows, V = X E), n × unknowns each,
// and A itself is not formed. Its vectors and factors are sized for every row at once and used
// on their first `unknowns()` entries, so that a run's steps allocate nothing on a rigid body.
struct ModeSystem {
  Eigen::SparseMatrix<double> A;
  Eigen::MatrixXd dense;  // A on few unknowns (kDenseUnknowns): room for that many, at most rows
  Eigen::MatrixXd U, V;
  Eigen::VectorXd b, scale;  // scale: each equation's own G diagonal
  std::vector<int> unknown;  // contact → its first unknown, −1 apart
  std::vector<int> row_of;   // unknown → its row of G
  std::vector<Eigen::Triplet<double>> entries;

  Eigen::Index unknowns() const { return static_cast<Eigen::Index>(row_of.size()); }
  bool factored() const { return U.rows() != 0; }
  bool is_dense() const { return !factored() && unknowns() <= kDenseUnknowns; }
  auto dense_A() const { return dense.topLeftCorner(unknowns(), unknowns()); }
  auto dense_A() { return dense.topLeftCorner(unknowns(), unknowns()); }
  auto U_cols() const { return U.leftCols(unknowns()); }
  auto V_cols() const { return V.leftCols(unknowns()); }

  // Coefficient-wise products (lazyProduct): n is a rigid body's few degrees of freedom, where a
  // general matrix-vector kernel's set-up costs more than the products. `v`: n entries of room.
  template <class X, class Out>
  void times(const X& x, Eigen::VectorXd& v, Out&& out) const {
    if (is_dense()) {
      out.noalias() = dense_A().lazyProduct(x);
      return;
    }
    if (!factored()) {
      out.noalias() = A * x;
      return;
    }
    v.noalias() = V_cols().lazyProduct(x);
    out.noalias() = U_cols().transpose().lazyProduct(v);
  }
};

// The velocity factors of the mode: U's column `eq` is W's column of the equation's row; V's
// column of a contact's normal unknown is X's normal column, plus s μ its tangential one where it
// slides (P_T = s μ P_N), and of a sticking contact's tangential unknown X's tangential column.
void velocity_factors_of(const Layout& L, const std::vector<ContactMode>& modes, ModeSystem& S) {
  S.U.resize(L.X.rows(), L.X.cols());
  S.V.resize(L.X.rows(), L.X.cols());
  for (Eigen::Index eq = 0; eq < S.unknowns(); ++eq)
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

void system_of(const Layout& L, const Eigen::VectorXd& D_A, const std::vector<ContactMode>& modes,
               ModeSystem& S) {
  S.unknown.assign(modes.size(), -1);
  S.row_of.clear();
  for (int i = 0; i < L.contacts; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (modes[k].mode == Mode::apart) continue;
    S.unknown[k] = static_cast<int>(S.row_of.size());
    S.row_of.push_back(L.step * i);
    if (L.step == 2 && modes[k].mode == Mode::stick) S.row_of.push_back(L.step * i + 1);
  }
  const int n = static_cast<int>(S.row_of.size());
  S.b.resize(D_A.size());
  S.scale.resize(D_A.size());
  for (int eq = 0; eq < n; ++eq) {
    const int R = S.row_of[static_cast<std::size_t>(eq)];
    const auto& B = L.block[static_cast<std::size_t>(R / L.step)];
    const bool normal = R % L.step == 0;
    S.b(eq) = -(D_A(R) + (normal ? L.shift[static_cast<std::size_t>(R / L.step)] : 0.0));
    S.scale(eq) = normal ? B.a : (B.d > 0.0 ? B.d : B.a);
  }
  if (L.has_velocity_factors()) {
    velocity_factors_of(L, modes, S);
    return;
  }
  // A's entries, each added where it goes (a sliding contact's two columns onto one unknown):
  // into the dense A on few unknowns, else into the triplets of the sparse one.
  const bool dense = S.is_dense();
  if (dense) {
    const auto room = std::min<Eigen::Index>(D_A.size(), kDenseUnknowns);
    S.dense.resize(room, room);
    S.dense_A().setZero();
  } else {
    S.entries.clear();
    S.entries.reserve(static_cast<std::size_t>(n) * 12);
  }
  auto add = [&](int eq, int u, double v) {
    if (dense)
      S.dense(eq, u) += v;
    else
      S.entries.emplace_back(eq, u, v);
  };
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
        add(eq, u + (tangent_column ? 1 : 0), v);
      else if (!tangent_column)
        add(eq, u, v);
      else if (modes[k].s != 0.0)
        add(eq, u, v * modes[k].s * L.mu[k]);
    }
  }
  if (dense) return;
  S.A.resize(n, n);
  S.A.setFromTriplets(S.entries.begin(), S.entries.end());
}

// The storage of mode_newton's runs: every vector is sized for all the rows (or the body's
// velocities), and a step uses its first `unknowns` entries.
struct ModeWork {
  std::vector<ContactMode> modes;
  ModeSystem S;
  Eigen::VectorXd x, r, step, inv, y, t;  // the unknowns' (inv, y, t: Woodbury's)
  Eigen::VectorXd next, d, trial, at;     // percussions
  Eigen::VectorXd v, z, w;                // the body's n velocities (z, w: Woodbury's)
  Eigen::MatrixXd H;                      // n × n
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  Measure tried, here;  // at `trial` and at `at`

  // Sized for L's rows and body; kept where they already are.
  void size_for(const Layout& L, Eigen::Index rows) {
    const Eigen::Index n = L.X.rows();
    for (Eigen::VectorXd* u : {&x, &r, &step, &inv, &y, &t, &next, &d, &trial, &at})
      u->resize(rows);
    for (Eigen::VectorXd* u : {&v, &z, &w}) u->resize(n);
    if (H.rows() != n) {
      H.resize(n, n);
      lu = Eigen::PartialPivLU<Eigen::MatrixXd>(n);
    }
  }
};

// The proximal steps x += K⁻¹(b − A x) with K = A + δ D applied by `solve` (into W.step), until
// the equations' residual is below 1e-3 of the target or stops halving (four at most).
template <class Solve>
bool refine(ModeWork& W, double target, const Solve& solve) {
  const ModeSystem& S = W.S;
  const Eigen::Index u = S.unknowns();
  auto x = W.x.head(u);
  auto r = W.r.head(u);
  double last = std::numeric_limits<double>::infinity();
  for (int step = 0; step < 4 && x.allFinite(); ++step) {
    S.times(x, W.v, r);
    r = S.b.head(u) - r;
    const double size = r.lpNorm<Eigen::Infinity>();
    if (size <= 1e-3 * target || !(size < 0.5 * last)) break;
    last = size;
    solve(r, W.step.head(u));
    x += W.step.head(u);
  }
  return x.allFinite();
}

// x with A x = b from x (the current point's unknowns): A is singular where G is, and its
// solutions then differ by percussions that move no velocity, of which the one nearest the
// current point keeps its signs and cone. (A + δ D) Δ = b − A x, D each equation's G diagonal,
// repeated: the proximal-point iteration, whose limit is that nearest solution. False when the
// factorisation fails.
bool solve_mode(ModeWork& W, double target, double delta) {
  const ModeSystem& S = W.S;
  const Eigen::Index u = S.unknowns();
  if (S.factored()) {
    // Woodbury: with B = δ D, (B + Uᵀ V)⁻¹ r = B⁻¹ r − B⁻¹ Uᵀ H⁻¹ V B⁻¹ r, H = I + V B⁻¹ Uᵀ of
    // size n. Its cancellation where δ is small is the refinement's to correct.
    auto inv = W.inv.head(u);
    inv = (delta * S.scale.head(u)).cwiseInverse();
    W.H.noalias() = S.V_cols() * inv.asDiagonal() * S.U_cols().transpose();
    W.H.diagonal().array() += 1.0;
    W.lu.compute(W.H);
    return refine(W, target, [&](const auto& r, auto out) {
      auto y = W.y.head(u);
      y = inv.cwiseProduct(r);
      W.w.noalias() = S.V_cols().lazyProduct(y);
      W.z = W.lu.solve(W.w);
      auto t = W.t.head(u);
      t.noalias() = S.U_cols().transpose().lazyProduct(W.z);
      out = y - inv.cwiseProduct(t);
    });
  }
  // A few dozen unknowns (a plate on many contacts: G dense) factor faster dense.
  if (S.is_dense()) {
    Eigen::MatrixXd K = S.dense_A();
    K.diagonal() += delta * S.scale.head(u);
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(K);
    return refine(W, target, [&](const auto& r, auto out) { out = lu.solve(r); });
  }
  Eigen::SparseMatrix<double> K = S.A;
  for (int j = 0; j < K.rows(); ++j) K.coeffRef(j, j) += delta * S.scale(j);
  K.makeCompressed();
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(K);
  if (lu.info() != Eigen::Success) return false;
  return refine(W, target, [&](const auto& r, auto out) { out = lu.solve(r); });
}

}  // namespace

struct ModeNewtonWorkspace::Work : ModeWork {};

ModeNewtonWorkspace::ModeNewtonWorkspace() = default;
ModeNewtonWorkspace::~ModeNewtonWorkspace() = default;
ModeNewtonWorkspace::ModeNewtonWorkspace(const ModeNewtonWorkspace&) {}
ModeNewtonWorkspace& ModeNewtonWorkspace::operator=(const ModeNewtonWorkspace&) {
  return *this;
}
ModeNewtonWorkspace::ModeNewtonWorkspace(ModeNewtonWorkspace&&) noexcept = default;
ModeNewtonWorkspace& ModeNewtonWorkspace::operator=(ModeNewtonWorkspace&&) noexcept = default;

ModeNewtonOutcome mode_newton(const Layout& L, const Eigen::VectorXd& D_A, Eigen::VectorXd& P,
                              Measure& m, double target, int max_steps, ModeNewtonWorkspace& ws) {
  ModeNewtonOutcome out;
  auto met = [target](const Measure& x) { return x.residual <= target || x.excess <= target; };
  out.converged = met(m);
  if (out.converged || max_steps <= 0) return out;
  if (!ws.work) ws.work = std::make_unique<ModeNewtonWorkspace::Work>();
  ModeWork& W = *ws.work;
  W.size_for(L, D_A.size());
  Eigen::VectorXd& at = W.at;
  at = P;
  Measure& here = W.here;
  here = m;
  // The proximal weight δ adapts as Levenberg–Marquardt's does: far from the answer the modes
  // read are wrong, their equations inconsistent, and a large δ keeps the step short; a full
  // step accepted shrinks it toward Newton's.
  double delta = 1e-4;
  int failures = 0, slow = 0;
  while (!out.converged && out.steps < max_steps && failures < 4 && slow < 2) {
    modes_at(L, at, here.D_E, W.modes);
    system_of(L, D_A, W.modes, W.S);
    const ModeSystem& S = W.S;
    for (std::size_t u = 0; u < S.row_of.size(); ++u)
      W.x(static_cast<Eigen::Index>(u)) = at(S.row_of[u]);
    if (!S.row_of.empty() && !solve_mode(W, target, delta)) break;
    ++out.steps;
    W.next.setZero();
    for (int i = 0; i < L.contacts; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const int u = S.unknown[k];
      if (u < 0) continue;
      const int r = L.step * i;
      W.next(r) = W.x(u);
      if (L.step == 2)
        W.next(r + 1) =
            W.modes[k].mode == Mode::stick ? W.x(u + 1) : W.modes[k].s * L.mu[k] * W.x(u);
    }
    // Backtracking on ½ Σ R² (Armijo): the mode's equations are its Jacobian on the branch read
    // at the current point, so the step descends it.
    W.d = W.next - at;
    const double f0 = here.squares;
    double t = 1.0;
    for (; t > 0.01; t *= 0.5) {
      W.trial = at + t * W.d;
      measure(L, D_A, W.trial, W.tried);
      if (W.tried.squares <= (1.0 - 1e-4 * t) * f0) break;
    }
    if (!(t > 0.01)) {
      delta *= 10.0;
      ++failures;
      continue;
    }
    failures = 0;
    delta = t == 1.0 ? std::max(0.1 * delta, 1e-12) : std::min(4.0 * delta, 1.0);
    // The accepted point and its measure are the last trial's.
    std::swap(at, W.trial);
    const double before = here.residual;
    std::swap(here, W.tried);
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
