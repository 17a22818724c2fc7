#include "laws/stronge/darboux_keller.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/detail/validate.hpp"
#include "fremond/core/enum_names.hpp"
#include "fremond/core/error.hpp"

namespace fremond::detail {

namespace {

constexpr EnumNames<StrongeRegime, 5> kRegimeNames{{
    {StrongeRegime::no_impact, "no_impact"},
    {StrongeRegime::slide, "slide"},
    {StrongeRegime::slip_stick, "slip_stick"},
    {StrongeRegime::slip_reversal, "slip_reversal"},
    {StrongeRegime::stick, "stick"},
}};

constexpr double kInf = std::numeric_limits<double>::infinity();

// Below this sin² of the angle between w_N and w_T in the metric M⁻¹ (det G / (G_NN G_TT)), G is
// taken as singular: the stick slope det G / G_TT would drown in the rounding of G
// (docs/stronge.md).
constexpr double kSingularDelassus = 1e-12;

struct Delassus {
  double NN, NT, TT;
  double sin2;  // det G / (G_NN G_TT), formed without overflow
};

// One phase of the integration in p_N on [p0, p1): every contact quantity is affine in p_N.
struct Phase {
  double p0 = 0.0, p1 = kInf;
  double D_N0 = 0.0, D_T0 = 0.0, P_T0 = 0.0;  // values at p0
  double dD_N = 0.0, dD_T = 0.0, dP_T = 0.0;  // slopes d/dp_N
  double s = 0.0;                             // slip direction ±1; 0 while stuck
};

// Slip in direction s: dp_T = −μ s dp_N, so dD_N = (G_NN − μ s G_NT) dp_N and
// dD_T = (G_NT − μ s G_TT) dp_N (docs/stronge.md, eq. (4)).
Phase slipping(const Delassus& G, double mu, double s) {
  Phase ph;
  ph.s = s;
  ph.dP_T = -mu * s;
  ph.dD_N = G.NN - mu * s * G.NT;
  ph.dD_T = G.NT - mu * s * G.TT;
  return ph;
}

// Stick keeps dD_T = 0: dp_T/dp_N = −G_NT/G_TT, and then dD_N/dp_N = det G / G_TT > 0 (eq. (5)).
Phase sticking(const Delassus& G) {
  Phase ph;
  ph.dP_T = -G.NT / G.TT;
  ph.dD_N = G.NN * G.sin2;
  return ph;
}

// x ≥ 0 with D0 x + a x²/2 = R (D0 ≥ 0, a > 0, R ≥ 0): the work of one restitution phase
// (eq. (7)). Written 2R/(D0 + √(D0² + 2aR)) so that nothing cancels when D0² ≫ aR.
double restitution_length(double D0, double a, double R) {
  const double den = D0 + std::sqrt(D0 * D0 + 2.0 * a * R);
  return den > 0.0 ? 2.0 * R / den : 0.0;
}

template <class Vec>
void require_all_finite(const char* name, const Vec& v) {
  if (!v.allFinite()) throw InvalidArgument(name, "must hold finite numbers only");
}

void require_size(const char* name, Eigen::Index size, Eigen::Index n) {
  if (size != n)
    throw InvalidArgument(name, "must have " + std::to_string(n) +
                                    " entries (one per degree of freedom), got " +
                                    std::to_string(size));
}

void validate(const Eigen::MatrixXd& M, const Eigen::VectorXd& w_N, const Eigen::VectorXd& w_T,
              const Eigen::VectorXd& qdot_A, double e, double mu) {
  const Eigen::Index n = M.rows();
  if (n == 0) throw InvalidArgument("M", "the mass matrix is empty");
  if (M.cols() != n)
    throw InvalidArgument(
        "M", "must be square, got " + std::to_string(n) + "x" + std::to_string(M.cols()));
  require_all_finite("M", M);
  const double scale = M.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i + 1; j < n; ++j)
      if (std::fabs(M(i, j) - M(j, i)) > 1e-12 * scale)
        throw InvalidArgument("M", "must be symmetric; M[" + std::to_string(i) + "][" +
                                       std::to_string(j) + "] = " + format_number(M(i, j)) +
                                       " but M[" + std::to_string(j) + "][" + std::to_string(i) +
                                       "] = " + format_number(M(j, i)));
  require_size("w_N", w_N.size(), n);
  require_all_finite("w_N", w_N);
  require_size("w_T", w_T.size(), n);
  require_all_finite("w_T", w_T);
  require_size("qdot_A", qdot_A.size(), n);
  require_all_finite("qdot_A", qdot_A);
  require_in_unit_interval("e", e);
  require_finite_at_least("mu", mu, 0.0);
}

}  // namespace

std::string_view to_string(StrongeRegime r) {
  return enum_to_string(kRegimeNames, r);
}

StrongeAnswer stronge_contact(double G_NN, double G_NT, double G_TT, double D_NA_in, double D_TA_in,
                              double e, double mu) {
  Delassus G{G_NN, G_NT, G_TT, 1.0 - (G_NT / G_NN) * (G_NT / G_TT)};
  StrongeAnswer out;
  out.D_NA = D_NA_in;
  out.D_TA = D_TA_in;
  out.D_NE = out.D_NA;
  out.D_TE = out.D_TA;
  if (!(out.D_NA < 0.0)) return out;  // not approaching: no impact

  // The phases in p_N (docs/stronge.md, "Regimes"): one, or slip then stick / reversed slip.
  const double D_NA = out.D_NA, D_TA = out.D_TA;
  const bool stick_admissible = std::fabs(G.NT) <= mu * G.TT;
  std::array<Phase, 2> ph;
  int count = 1;
  if (D_TA == 0.0) {
    // From rest tangentially: stick if the cone holds it, else slide the way G_NT drives D_T.
    ph[0] = stick_admissible ? sticking(G) : slipping(G, mu, G.NT > 0.0 ? 1.0 : -1.0);
    out.regime = stick_admissible ? StrongeRegime::stick : StrongeRegime::slide;
  } else {
    const double s = D_TA > 0.0 ? 1.0 : -1.0;
    ph[0] = slipping(G, mu, s);
    if (s * ph[0].dD_T >= 0.0) {
      out.regime = StrongeRegime::slide;  // D_T never returns to 0
    } else {
      // D_T reaches 0 at p1 (eq. (6)). Reversal happens only when s G_NT < 0, so it slides as −s.
      const double p1 = -D_TA / ph[0].dD_T;
      ph[0].p1 = p1;
      ph[1] = stick_admissible ? sticking(G) : slipping(G, mu, -s);
      ph[1].p0 = p1;
      ph[1].D_N0 = D_NA + ph[0].dD_N * p1;
      ph[1].P_T0 = ph[0].dP_T * p1;
      count = 2;
      out.regime = stick_admissible ? StrongeRegime::slip_stick : StrongeRegime::slip_reversal;
      out.p_N_transition = p1;
    }
  }
  ph[0].D_N0 = D_NA;
  ph[0].D_T0 = D_TA;

  // Compression: the first zero of the piecewise affine D_N. The last phase has dD_N > 0 (stick:
  // det G / G_TT; a never-ending slip or a reversal: ≥ det G / G_TT too), so it exists. The work
  // is summed by trapezoids of negative values: nothing cancels.
  int k = 0;
  double W_c = 0.0;
  for (;; ++k) {
    const Phase& f = ph[k];
    const double D_end = k + 1 < count ? ph[k + 1].D_N0 : kInf;
    if (D_end >= 0.0) {
      const double p_c = std::min(f.p1, f.p0 - f.D_N0 / f.dD_N);
      W_c += 0.5 * f.D_N0 * (p_c - f.p0);
      out.p_N_compression = p_c;
      break;
    }
    W_c += 0.5 * (f.D_N0 + D_end) * (f.p1 - f.p0);
  }
  out.work_compression = W_c;

  // Restitution: from p_Nc until its work reaches −e² W_N(p_Nc) (eq. (7)), across the phase
  // boundary where the stick or reversal comes during restitution.
  double R = -e * e * W_c;
  double p_start = out.p_N_compression, D_start = 0.0;
  for (;; ++k) {
    const Phase& f = ph[k];
    if (k + 1 < count) {
      const double D_end = ph[k + 1].D_N0;
      const double available = 0.5 * (D_start + D_end) * (f.p1 - p_start);
      if (R > available) {
        R -= available;
        p_start = f.p1;
        D_start = D_end;
        continue;
      }
    }
    const double x = std::min(restitution_length(D_start, f.dD_N, R), f.p1 - p_start);
    out.P_N = p_start + x;
    out.D_NE = D_start + f.dD_N * x;
    break;
  }

  // A stick or reversal due after P_N does not happen: the contact slid throughout.
  if (k == 0 && count == 2) {
    out.regime = StrongeRegime::slide;
    out.p_N_transition = std::numeric_limits<double>::quiet_NaN();
  }
  // The tangential state at P_N, in the phase k that holds it.
  const Phase& last = ph[k];
  const double dp = out.P_N - last.p0;
  out.P_T = last.P_T0 + last.dP_T * dp;
  out.D_TE = last.D_T0 + last.dD_T * dp;
  // A slip phase keeps its sign up to its end, where D_T = 0: rounding must not flip it.
  if (last.s != 0.0) out.D_TE = last.s * std::max(0.0, last.s * out.D_TE);
  // Tangential work −μ ∫|D_T| dp_N over the slip phases (|D_T| affine on each: trapezoids).
  for (int j = 0; j <= k; ++j) {
    if (ph[j].s == 0.0) continue;
    const double p_end = j < k ? ph[j].p1 : out.P_N;
    const double D_T_end = j < k ? 0.0 : out.D_TE;
    out.dissipated_tangential +=
        mu * 0.5 * (std::fabs(ph[j].D_T0) + std::fabs(D_T_end)) * (p_end - ph[j].p0);
  }
  out.dissipated_normal = -(1.0 - e * e) * W_c;
  out.energy_change = -(out.dissipated_normal + out.dissipated_tangential);

  return out;
}

StrongeAnswer stronge_one_contact(const Eigen::MatrixXd& M, const Eigen::VectorXd& w_N,
                                  const Eigen::VectorXd& w_T, const Eigen::VectorXd& qdot_A,
                                  double e, double mu) {
  validate(M, w_N, w_T, qdot_A, e, mu);
  const Eigen::Index n = M.rows();
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  if (llt.info() != Eigen::Success) throw InvalidArgument("M", "must be positive definite");

  // With M = L Lᵀ and Y = L⁻¹[w_N w_T]: G = YᵀY (exactly symmetric) and M⁻¹w = L⁻ᵀ(L⁻¹w).
  Eigen::Matrix<double, Eigen::Dynamic, 2> Y(n, 2);
  Y.col(0) = w_N;
  Y.col(1) = w_T;
  llt.matrixL().solveInPlace(Y);
  Delassus G{Y.col(0).squaredNorm(), Y.col(0).dot(Y.col(1)), Y.col(1).squaredNorm(), 0.0};
  G.sin2 = 1.0 - (G.NT / G.NN) * (G.NT / G.TT);  // NaN for w_T = 0: refused below
  if (!(G.NN > 0.0) || !std::isfinite(G.NN))
    throw InvalidArgument("w_N",
                          "w_N^T M^-1 w_N must be positive and finite, got " + format_number(G.NN));
  if (!std::isfinite(G.TT) || !std::isfinite(G.NT))
    throw InvalidArgument("w_T", "w_T^T M^-1 w_T overflows");
  if (!(G.sin2 > kSingularDelassus))
    throw InvalidArgument("w_T",
                          "must be nonzero and not parallel to w_N in the metric M^-1 "
                          "(singular Delassus matrix)");

  const double D_NA = w_N.dot(qdot_A), D_TA = w_T.dot(qdot_A);
  if (!std::isfinite(D_NA) || !std::isfinite(D_TA))
    throw InvalidArgument("qdot_A", "the contact velocities overflow");
  StrongeAnswer out = stronge_contact(G.NN, G.NT, G.TT, D_NA, D_TA, e, mu);
  out.qdot_E = qdot_A;
  if (out.regime == StrongeRegime::no_impact) return out;
  // q̇_E = q̇_A + M⁻¹(w_N P_N + w_T P_T) = q̇_A + L⁻ᵀ Y (P_N, P_T).
  Eigen::VectorXd dq = Y * Eigen::Vector2d(out.P_N, out.P_T);
  llt.matrixU().solveInPlace(dq);
  out.qdot_E += dq;
  return out;
}

}  // namespace fremond::detail
