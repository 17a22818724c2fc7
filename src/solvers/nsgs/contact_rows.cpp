// The contact rows of a sparse solve (contact_rows.hpp).
#include "solvers/nsgs/contact_rows.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace fremond::detail {

namespace {
constexpr double kEps = std::numeric_limits<double>::epsilon();
}  // namespace

Layout layout(RowMajorMatrix&& G, const Eigen::VectorXd& D_A, bool tangential, bool coulomb,
              const std::vector<double>& e, const std::vector<double>& mu) {
  Layout L;
  L.G.swap(G);
  L.G.makeCompressed();
  lay_out(L, D_A, tangential, coulomb, e, mu);
  return L;
}

void lay_out(Layout& L, const Eigen::VectorXd& D_A, bool tangential, bool coulomb,
             const std::vector<double>& e, const std::vector<double>& mu) {
  L.step = tangential ? 2 : 1;
  L.contacts = static_cast<int>(D_A.size()) / L.step;
  L.friction = tangential && coulomb;
  L.v_scale = std::numeric_limits<double>::min();
  const auto n = static_cast<std::size_t>(L.contacts);
  L.block.resize(n);
  L.e = e;
  L.mu.resize(n);
  L.shift.resize(n);
  for (int i = 0; i < L.contacts; ++i) {
    const int r = L.step * i;
    const auto k = static_cast<std::size_t>(i);
    auto& B = L.block[k];
    B.a = L.G.coeff(r, r);
    if (tangential) {
      B.b = L.G.coeff(r, r + 1);
      B.c = L.G.coeff(r + 1, r);
      B.d = L.G.coeff(r + 1, r + 1);
    }
    L.mu[k] = L.friction ? mu[k] : 0.0;
    const double DNA = D_A(r);
    L.shift[k] = e[k] * std::min(DNA, 0.0);
    if (DNA <= 0.0)
      L.v_scale = std::max({L.v_scale, std::fabs(DNA), tangential ? std::fabs(D_A(r + 1)) : 0.0});
  }
}

Measure measure(const Layout& L, const Eigen::VectorXd& D_A, const Eigen::VectorXd& P) {
  Measure m;
  measure(L, D_A, P, m);
  return m;
}

void measure(const Layout& L, const Eigen::VectorXd& D_A, const Eigen::VectorXd& P, Measure& m) {
  m.residual = m.excess = m.data_excess = m.squares = 0.0;
  const int rows = static_cast<int>(D_A.size());
  const bool data = L.has_data_rounding();
  m.D_E.resize(rows);
  m.rounding.resize(rows);
  m.data.resize(data ? rows : 0);
  for (int j = 0; j < rows; ++j) {
    double size = 0.0;
    m.D_E(j) = D_A(j) + row_times(L.G, j, P, &size);
    m.rounding(j) = 16 * kEps * (std::fabs(D_A(j)) + size);
    if (data) m.data(j) = L.G_rounding * size + L.D_A_rounding * std::fabs(D_A(j));
  }
  for (int i = 0; i < L.contacts; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const auto& A = L.block[k];
    const int r = L.step * i;
    const double wN = m.D_E(r) + L.shift[k];
    const double PN = P(r);
    const double RN = std::min(wN, PN == 0.0 ? 0.0 : A.a * PN);
    double R = std::fabs(RN);
    double floor = m.rounding(r);
    double data_floor = data ? m.data(r) : 0.0;
    m.squares += 0.5 * RN * RN;
    if (L.step == 2) {
      const double PT = P(r + 1), vT = m.D_E(r + 1);
      const double g = A.d > 0.0 ? A.d : A.a;
      const double bound = L.mu[k] * std::max(PN, 0.0);
      const double diff = PT - std::clamp(PT - vT / g, -bound, bound);
      const double RT = diff == 0.0 ? 0.0 : g * diff;
      R = std::max(R, std::fabs(RT));
      m.squares += 0.5 * RT * RT;
      floor = std::max(floor, m.rounding(r + 1));
      if (data) data_floor = std::max(data_floor, m.data(r + 1));
    }
    m.residual = std::max(m.residual, R);
    m.excess = std::max(m.excess, R - floor);
    m.data_excess = std::max(m.data_excess, R - floor - data_floor);
  }
}

namespace {
// One sweep, with `rows` giving a row of G times the current percussions (times(row)) and told of
// each percussion's change (moved(row, by)).
template <class Rows>
double sweep_with(const Layout& L, const Eigen::VectorXd& D_A, Eigen::VectorXd& P, bool backward,
                  Rows& rows) {
  double change = 0.0;
  for (int step = 0; step < L.contacts; ++step) {
    const int i = backward ? L.contacts - 1 - step : step;
    const auto k = static_cast<std::size_t>(i);
    const auto& A = L.block[k];
    const int r = L.step * i;
    if (L.step == 1) {
      const double old_N = P(r);
      const double fN = D_A(r) + L.shift[k] + rows.times(r) - A.a * old_N;
      const double PN = fN < 0.0 ? -fN / A.a : 0.0;
      change = std::max(change, A.a * std::fabs(PN - old_N));
      rows.moved(r, PN - old_N);
      P(r) = PN;
      if (!std::isfinite(PN)) return std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const ContactPercussion old{P(r), P(r + 1)};
    const double fN = D_A(r) + L.shift[k] + rows.times(r) - A.a * old.N - A.b * old.T;
    const double fT = D_A(r + 1) + rows.times(r + 1) - A.c * old.N - A.d * old.T;
    const auto now = coulomb_contact(A, fN, fT, L.mu[k], old);
    change = std::max(change,
                      std::max(A.a * std::fabs(now.N - old.N) + std::fabs(A.b * (now.T - old.T)),
                               std::fabs(A.c * (now.N - old.N)) + A.d * std::fabs(now.T - old.T)));
    rows.moved(r, now.N - old.N);
    rows.moved(r + 1, now.T - old.T);
    P(r) = now.N;
    P(r + 1) = now.T;
    // A non-finite percussion ends the sweep as NaN, which std::max above would drop.
    if (!std::isfinite(now.N) || !std::isfinite(now.T))
      return std::numeric_limits<double>::quiet_NaN();
  }
  return change;
}

// G's rows read against P itself.
struct RowsOfG {
  const Layout& L;
  const Eigen::VectorXd& P;
  double times(int row) const { return row_times(L.G, row, P, nullptr); }
  void moved(int, double) const {}
};

// The rows through the velocities v = X P (Layout::W, X): W_rᵀ v, v moved by X's columns. v is
// formed anew each sweep, so its rounding does not build up. Plain loops: n is a rigid body's few
// degrees of freedom.
struct RowsThroughVelocities {
  const Layout& L;
  Eigen::VectorXd& v;
  RowsThroughVelocities(const Layout& layout, const Eigen::VectorXd& P, Eigen::VectorXd& room)
      : L(layout), v(room) {
    v.noalias() = L.X.lazyProduct(P);
  }
  double times(int row) const {
    const auto n = v.size();
    const double* w = L.W.data() + n * row;
    double sum = 0.0;
    for (Eigen::Index d = 0; d < n; ++d) sum += w[d] * v[d];
    return sum;
  }
  void moved(int row, double by) {
    if (by == 0.0) return;
    const auto n = v.size();
    const double* x = L.X.data() + n * row;
    for (Eigen::Index d = 0; d < n; ++d) v[d] += by * x[d];
  }
};
}  // namespace

// One Gauss–Seidel sweep, over the contacts in order or `backward`; returns the largest change of
// a contact's velocity it made.
double sweep(const Layout& L, const Eigen::VectorXd& D_A, Eigen::VectorXd& P, bool backward,
             Eigen::VectorXd& velocities) {
  if (L.has_velocity_factors()) {
    RowsThroughVelocities rows(L, P, velocities);
    return sweep_with(L, D_A, P, backward, rows);
  }
  RowsOfG rows{L, P};
  return sweep_with(L, D_A, P, backward, rows);
}

}  // namespace fremond::detail
