// Frémond + Coulomb on several contacts, solved in contact modes with the exact conditions along
// the null space of the columns a mode fixes (docs/laws.md). Why: see solve_in_coulomb_mode in
// detail/fremond.hpp.
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

#include "fremond/potentials/power.hpp"
#include "laws/detail/as_power.hpp"
#include "solvers/detail/fremond.hpp"

namespace fremond::detail {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

enum Kind : signed char { kFree, kReaction, kStick, kSlide };

/// The contact modes of one problem: per active contact, the normal row free (its power law) or
/// held by its reaction (D_NE = 0), the tangential row sticking (z_T = 0) or sliding with
/// P_T = σμ|P_N|; and Newton on a mode's equations.
template <int N, int C>
class CoulombModes {
 public:
  using CS = ContactSpaceT<N, C>;
  using Rows = typename CS::Rows;
  using RowMat = typename CS::RowMat;
  static constexpr int R = CS::kMaxRows;
  using Index = Eigen::Matrix<int, Eigen::Dynamic, 1, 0, R, 1>;
  using Kinds = Eigen::Matrix<signed char, Eigen::Dynamic, 1, 0, C, 1>;

  struct Mode {
    Kinds normal, tangent, sign;
  };
  enum class Outcome { feasible, switched, no_root };

  CoulombModes(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows)
      : pb_(pb), rows_(rows), cs_(*rows.cs), a_(cs_.active), n_(cs_.dofs) {
    k_.resize(a_);
    e_.resize(a_);
    mu_.resize(a_);
    applicable_ = rows.coulomb && a_ >= 1 && cs_.rows() == 2 * a_ && !rows.fixed_modes &&
                  !rows.fixed_normal && !rows.fixed_signs;
    for (int j = 0; j < a_ && applicable_; ++j) {
      const int i = rows.contact(j);
      const auto* power = as_power(rows.law->normal[i]);
      applicable_ = power && power->p() > 1.0 && power->k() > 0.0 && std::isfinite(power->k());
      if (!applicable_) break;
      k_(j) = power->k();
      e_(j) = 1.0 / (power->p() - 1.0);
      mu_(j) = rows.law->mu[i];
    }
  }

  /// Only power normal laws k|z|^p/p, p > 1: a free row's mean velocity is then an exact function
  /// of its percussion, z = −sign(P)(|P|/k)^e with e = 1/(p − 1) (P = −φ'(z)).
  bool applicable() const { return applicable_; }
  int contacts() const { return a_; }

  /// The mode of an answer: reactions where they act, sliding where |P_T| is at μ|P_N|.
  Mode mode_of(const Rows& P, const typename ImpactResultT<N, C>::CVec& P_N_reaction) const {
    Mode m{Kinds(a_), Kinds(a_), Kinds(a_)};
    for (int j = 0; j < a_; ++j) {
      m.normal(j) = P_N_reaction(rows_.contact(j)) > 0.0 ? kReaction : kFree;
      const double b = mu_(j) * std::fabs(P(j));
      m.tangent(j) = b > 0.0 && std::fabs(P(a_ + j)) >= b * (1.0 - 1e-9) ? kSlide : kStick;
      m.sign(j) = P(a_ + j) >= 0.0 ? 1 : -1;
    }
    return m;
  }

  /// Mode number `code` of the 6^a (per contact: free or reaction, times stick, slide +, slide −).
  Mode mode_number(int code) const {
    Mode m{Kinds(a_), Kinds(a_), Kinds(a_)};
    for (int j = 0; j < a_; ++j, code /= 6) {
      const int c = code % 6;
      m.normal(j) = c < 3 ? kFree : kReaction;
      m.tangent(j) = c % 3 == 0 ? kStick : kSlide;
      m.sign(j) = c % 3 == 2 ? -1 : 1;
    }
    return m;
  }

  /// Newton on the mode's equations from X. `feasible`: X is the mode's root and keeps its
  /// inequalities. `switched`: X is its root, and `mode` now has the rows that break them in the
  /// other mode. `no_root`: Newton did not converge, or the mode leaves a percussion undetermined
  /// (X then undefined).
  Outcome solve(Mode& mode, Rows& X) {
    if (!set_up(mode)) return Outcome::no_root;
    sliding_percussions(mode, X);
    if (!data_conditions_hold(mode, X)) return Outcome::no_root;
    bool solved = false;
    for (int it = 0; it < 60 && !solved; ++it) {
      equations(mode, X, true);
      if (!h_.allFinite() || !J_.allFinite()) return Outcome::no_root;
      const double m0 = merit();
      if (m0 <= 64 * kEps) {
        solved = true;
        break;
      }
      // Each equation in its own scale: the null-space ones are of the size of the free rows'
      // z_N (1e-22 at p = 1.5, k = 1e6, speeds 5e-6), and the rank test must not read them as 0.
      Rows rhs(u_);
      for (int c = 0; c < u_; ++c) {
        J_.row(c) /= scale_(c);
        rhs(c) = -h_(c) / scale_(c);
      }
      Eigen::ColPivHouseholderQR<RowMat> qr(J_);
      qr.setThreshold(1e-13);
      if (qr.rank() < u_) return Outcome::no_root;  // the mode does not determine its percussions
      const Rows step = qr.solve(rhs);
      if (!step.allFinite()) return Outcome::no_root;
      bool moved = false;
      for (double lambda = 1.0; lambda > 1e-9 && !moved; lambda *= 0.5) {
        Rows trial = X;
        for (int t = 0; t < u_; ++t) trial(E_(t)) += lambda * step(t);
        sliding_percussions(mode, trial);
        equations(mode, trial, false);
        if (h_.allFinite() && merit() < m0) {
          X = trial;
          moved = true;
        }
      }
      if (!moved) {
        solved = m0 <= 1e3 * kEps;  // stagnation at rounding
        break;
      }
    }
    if (!solved) return Outcome::no_root;
    return keeps_inequalities(mode, X) ? Outcome::feasible : Outcome::switched;
  }

 private:
  static double sign_of(double x) { return x >= 0.0 ? 1.0 : -1.0; }

  double free_velocity(int j, double x, double& slope) const {
    const double s = std::pow(std::fabs(x) / k_(j), e_(j));
    slope = x != 0.0 ? -e_(j) * s / std::fabs(x)
                     : (e_(j) > 1.0 ? 0.0 : -std::numeric_limits<double>::infinity());
    return -std::copysign(s, x);
  }

  /// q̄ = q̇_A + M⁻¹W Q/2, the mean velocity of the percussions Q.
  VecT<N> mean_qdot(const Rows& Q) const {
    VecT<N> qbar = pb_.qdot_A;
    for (int j = 0; j < 2 * a_; ++j)
      if (Q(j) != 0.0) qbar += (0.5 * Q(j)) * cs_.MinvW.col(j);
    return qbar;
  }

  double offset(int row) const {  // w of a row (zero where the problem leaves w empty)
    if (row < a_) return pb_.w_N.size() ? pb_.w_N(cs_.index(row)) : 0.0;
    return pb_.w_T.size() ? pb_.w_T(cs_.index(row - a_)) : 0.0;
  }

  void sliding_percussions(const Mode& mode, Rows& Q) const {
    for (int j = 0; j < a_; ++j)
      if (mode.tangent(j) == kSlide) Q(a_ + j) = mode.sign(j) * mu_(j) * std::fabs(Q(j));
  }

  /// The rows whose velocity the mode fixes (E) are also its unknowns: every normal row, and the
  /// tangential rows that stick; a sliding row's percussion is σμ|P_N|. [B N] is an orthonormal
  /// basis of R^u from the SVD of W_E: z_E − t_E(P) = 0 is written as Bᵀ(…) = 0, which double
  /// precision resolves, and Nᵀ(…) = 0, where Nᵀz_E = (W_E N)ᵀq̄ + Nᵀw_E is exact: for the
  /// columns' exact dependences W_E N is rounding and is dropped, leaving Nᵀt_E(P) = Nᵀw_E with
  /// t_E exact functions of the percussions (the free rows' power laws), far below the rounding
  /// of D_A + G P/2 where those laws are steep at z_N = 0. False where a null direction holds a
  /// free row and a reaction with entries above 1e-8: the free row's z_N against the reaction's
  /// rounded D_NA/2.
  bool set_up(const Mode& mode) {
    E_.resize(2 * a_);
    u_ = 0;
    for (int j = 0; j < a_; ++j) E_(u_++) = j;
    for (int j = 0; j < a_; ++j)
      if (mode.tangent(j) == kStick) E_(u_++) = a_ + j;
    E_.conservativeResize(u_);
    WE_.resize(n_, u_);
    for (int t = 0; t < u_; ++t) WE_.col(t) = cs_.W.col(E_(t));
    svd_.compute(WE_, Eigen::ComputeFullV | Eigen::ComputeThinU);
    const auto& sv = svd_.singularValues();
    rank_ = 0;
    for (int t = 0; t < sv.size(); ++t)
      if (sv(t) > 1e-10 * sv(0)) ++rank_;
    V_ = svd_.matrixV();
    d_ = u_ - rank_;
    v_.resize(n_, d_);
    Nw_.resize(d_);
    null_free_.resize(d_);
    null_reaction_.resize(d_);
    homogeneous_.resize(d_);
    null_log_.setConstant(d_, -kInfinity);
    const double size = u_ ? WE_.cwiseAbs().maxCoeff() : 0.0;
    for (int c = 0; c < d_; ++c) {
      const auto nc = V_.col(rank_ + c);
      double on_free = 0.0, on_reaction = 0.0;
      for (int t = 0; t < u_; ++t) {
        if (E_(t) >= a_) continue;
        (mode.normal(E_(t)) == kFree ? on_free : on_reaction) += std::fabs(nc(t));
      }
      if (on_free > 1e-8 && on_reaction > 1e-8) return false;
      // A null vector's entries are known to ε·u of its unit norm; anything above is a real
      // dependence, however small: tangents 1.4e-12 apart tie two sticking rows to the normals
      // through entries of 2δ = 2.7e-12 (the bar nearly flat on both ends), and read as zero
      // they let a mode that breaks Σ n_t t_t = 0 pass as the law's own continuum. A direction
      // tied to both a free row and a reaction only through such entries (below 1e-8) keeps the
      // reaction's t = D_NA/2 in its condition.
      const double known = 64 * kEps * u_;
      null_free_(c) = on_free > known;
      null_reaction_(c) = on_reaction > known;
      for (int i = 0; i < n_; ++i) {
        v_(i, c) = 0.0;
        for (int t = 0; t < u_; ++t) v_(i, c) += WE_(i, t) * nc(t);
      }
      if (v_.col(c).cwiseAbs().maxCoeff() <= 64 * kEps * size * u_) v_.col(c).setZero();
      Nw_(c) = 0.0;
      for (int t = 0; t < u_; ++t) Nw_(c) += nc(t) * offset(E_(t));
      homogeneous_(c) =
          null_free_(c) && !null_reaction_(c) && v_.col(c).isZero(0.0) && Nw_(c) == 0.0;
    }
    return true;
  }

  /// h(Q) (u equations), their scales where `jacobian` (else the last ones: a trial point is
  /// measured in its base point's scales, since the null-space equations' own, Σ|n_t t_t|, keep
  /// |h|/scale at 1 wherever their terms have one sign), and then their Jacobian in the unknowns.
  void equations(const Mode& mode, const Rows& Q, bool jacobian) {
    const Rows base_scale = scale_;
    h_.resize(u_);
    scale_.resize(u_);
    tE_.resize(u_);
    dtE_.resize(u_);
    log_t_.resize(u_);
    sign_t_.resize(u_);
    rows_.mean_velocity(Q, z_);
    for (int t = 0; t < u_; ++t) {
      const int row = E_(t);
      dtE_(t) = 0.0;
      if (row >= a_)
        tE_(t) = 0.0;  // sticking: z_T = 0
      else if (mode.normal(row) == kReaction)
        tE_(t) = 0.5 * cs_.D_A(row);  // D_NE = 0
      else
        tE_(t) = free_velocity(row, Q(row), dtE_(t));
      // log|t| and the sign of t for a free row: t itself underflows where e is large (p = 1.01:
      // e = 100 puts z_N near 1e-1000), its ratios to the other rows' do not.
      log_t_(t) = row < a_ && mode.normal(row) == kFree && Q(row) != 0.0
                      ? e_(row) * std::log(std::fabs(Q(row)) / k_(row))
                      : -std::numeric_limits<double>::infinity();
      sign_t_(t) = -sign_of(Q(row));
    }
    const VecT<N> qbar = mean_qdot(Q);
    const double q_size = qbar.cwiseAbs().maxCoeff();
    Rows size(u_);  // each row's terms: |D_A| + ½Σ|G P| + |t_E|
    for (int t = 0; t < u_; ++t)
      size(t) = std::fabs(cs_.D_A(E_(t))) + 0.5 * rows_.abs_GP(E_(t), Q) + std::fabs(tE_(t));
    for (int c = 0; c < rank_; ++c) {
      h_(c) = scale_(c) = 0.0;
      for (int t = 0; t < u_; ++t) {
        h_(c) += V_(t, c) * (z_(E_(t)) - tE_(t));
        scale_(c) += std::fabs(V_(t, c)) * size(t);
      }
    }
    for (int c = 0; c < d_; ++c) {
      const int eq = rank_ + c;
      if (!null_free_(c)) {  // no free row on it: the law leaves it free; stay put
        h_(eq) = 0.0;
        scale_(eq) = 1.0;
        continue;
      }
      if (homogeneous_(c)) {  // Σ n_t t_t = 0, every term scaled by the largest
        if (jacobian) {
          null_log_(c) = -std::numeric_limits<double>::infinity();
          for (int t = 0; t < u_; ++t)
            if (V_(t, eq) != 0.0) null_log_(c) = std::max(null_log_(c), log_t_(t));
        }
        h_(eq) = 0.0;
        scale_(eq) = 1.0;
        if (negligible_null(c)) continue;
        double size = 0.0;
        for (int t = 0; t < u_; ++t) {
          const double x = std::exp(log_t_(t) - null_log_(c));
          h_(eq) -= V_(t, eq) * sign_t_(t) * x;
          size += std::fabs(V_(t, eq)) * x;
        }
        scale_(eq) = std::max(size, std::numeric_limits<double>::min());
        continue;
      }
      h_(eq) = v_.col(c).dot(qbar) + Nw_(c);
      scale_(eq) = v_.col(c).cwiseAbs().sum() * q_size + std::fabs(Nw_(c));
      for (int t = 0; t < u_; ++t) {
        if (E_(t) >= a_ || (mode.normal(E_(t)) != kFree && !null_reaction_(c))) continue;
        h_(eq) -= V_(t, eq) * tE_(t);
        scale_(eq) += std::fabs(V_(t, eq) * tE_(t));
      }
      if (!(scale_(eq) > 0.0)) scale_(eq) = std::numeric_limits<double>::min();
    }
    if (!jacobian) {
      scale_ = base_scale;
      return;
    }
    // ∂P/∂(unknowns): a sliding row follows its P_N.
    RowMat dP = RowMat::Zero(2 * a_, u_);
    for (int t = 0; t < u_; ++t) {
      const int row = E_(t);
      dP(row, t) = 1.0;
      if (row < a_ && mode.tangent(row) == kSlide)
        dP(a_ + row, t) = mode.sign(row) * mu_(row) * sign_of(Q(row));
    }
    J_.resize(u_, u_);
    for (int c = 0; c < rank_; ++c)
      for (int s = 0; s < u_; ++s) {
        double g = 0.0;
        for (int t = 0; t < u_; ++t) {
          double Gd = 0.0;
          for (int l = 0; l < 2 * a_; ++l) Gd += cs_.G(E_(t), l) * dP(l, s);
          g += V_(t, c) * (0.5 * Gd - (t == s ? dtE_(t) : 0.0));
        }
        J_(c, s) = g;
      }
    for (int c = 0; c < d_; ++c) {
      const int eq = rank_ + c;
      for (int s = 0; s < u_; ++s) {
        if (!null_free_(c)) {
          J_(eq, s) = V_(s, eq);
          continue;
        }
        const bool free_row = E_(s) < a_ && mode.normal(E_(s)) == kFree;
        if (homogeneous_(c) && negligible_null(c)) {
          J_(eq, s) = V_(s, eq);
          continue;
        }
        if (homogeneous_(c)) {  // ∂(−n_s t_s e^(−L))/∂P_s = n_s e_s e^(log|t_s| − L)/|P_s|
          const double x = Q(E_(s));
          J_(eq, s) = 0.0;
          if (free_row)
            J_(eq, s) =
                x != 0.0 ? V_(s, eq) * e_(E_(s)) * std::exp(log_t_(s) - null_log_(c)) / std::fabs(x)
                         : (e_(E_(s)) > 1.0 ? 0.0 : V_(s, eq) * kInfinity);
          continue;
        }
        double g = 0.0;
        for (int l = 0; l < 2 * a_; ++l)
          if (dP(l, s) != 0.0) g += 0.5 * v_.col(c).dot(cs_.MinvW.col(l)) * dP(l, s);
        if (free_row) g -= V_(s, eq) * dtE_(s);
        J_(eq, s) = g;
      }
    }
  }

  /// The null directions that hold no free row but a reaction (entries above their rounding) ask
  /// nothing of the unknowns, and equations() leaves them free; they ask something of the data.
  /// Along such a direction n, every row's velocity is fixed (D_NA/2 for a reaction, 0 for a
  /// sticking tangent), and z_E = W_Eᵀq̄ + w_E gives, exactly for any vector n and the mode's exact
  /// q̄*, Σ n_t (t_t − w_t) = (W_E n)ᵀ q̄*. With W_E n at rounding (its columns' dependence), the
  /// left side must be that small too, or the mode has no root. The bar tilted by 3.6e-12 rad on
  /// both ends (tangents' lever arms ±δ): both reactions and both tangents sticking ask 2δ(D_NA,1 −
  /// D_NA,2)/2 = 0, which the data break by 1e-26 against |W_E n|·|q̄| = 3e-28: that mode's answer
  /// is off every exact solution. q̄* is not known before the mode is solved: |q̄*|₁ is taken as at
  /// most four times the larger of |q̇_A|₁ and the start's |q̄|₁ (a dissipative impact does not speed
  /// the body up, in M's norm); a mode refused here is left to the enumeration's other modes.
  bool data_conditions_hold(const Mode& mode, const Rows& X) const {
    double q_size = -1.0;  // |q̄|₁ bound, computed for the first direction that needs it
    for (int c = 0; c < d_; ++c) {
      if (null_free_(c) || !null_reaction_(c)) continue;
      if (q_size < 0.0) {
        const VecT<N> qbar = mean_qdot(X);
        q_size = pb_.qdot_A.cwiseAbs().sum();
        if (qbar.allFinite()) q_size = std::max(q_size, qbar.cwiseAbs().sum());
      }
      const auto nc = V_.col(rank_ + c);
      // |W_E n| to its last bits (Dot2): the plain sum's rounding, ε·u of the terms, is of the
      // size of the exact value of a computed null vector's W_E n.
      double v_exact = 0.0;
      for (int i = 0; i < n_; ++i)
        v_exact = std::max(v_exact, std::fabs(accurate_dot(WE_.row(i).transpose(), nc)));
      double r = 0.0, terms = 0.0, free = 0.0;
      for (int t = 0; t < u_; ++t) {
        const int row = E_(t);
        if (row < a_ && mode.normal(row) == kFree) {  // an entry at rounding (not null_free_)
          free += std::fabs(nc(t)) * 2.0 * cs_.v_scale;
          continue;
        }
        const double fixed = row < a_ ? 0.5 * cs_.D_A(row) : 0.0;  // reaction, or sticking
        const double term = nc(t) * (fixed - offset(row));
        r += term;
        terms += std::fabs(term);
      }
      const double floor = 4.0 * v_exact * q_size + 16 * kEps * u_ * terms + free;
      if (std::fabs(r) > floor) return false;
    }
    return true;
  }

  /// A null-space condition Σ n_t t_t = 0 on mean velocities all below ε² of the velocity scale
  /// (2^-104: p = 1.0017 puts them near 1e-1000) is taken as met, whatever the percussions: the
  /// direction is then left free, as the law's own set-valued rows leave theirs, where exact
  /// arithmetic would ask those velocities, and so the percussions, to vanish.
  bool negligible_null(int c) const {
    return !(null_log_(c) > std::log(kEps * kEps * cs_.v_scale));
  }

  double merit() const {
    double m = 0.0;
    for (int c = 0; c < u_; ++c) m = std::max(m, std::fabs(h_(c)) / scale_(c));
    return m;
  }

  /// z of a row outside E from the mode's exact conditions, where its column is W_E c (to
  /// rounding): z = cᵀ(t_E − w_E) + w; false where it is not in their span. For fixed obstacles z
  /// and its floor come scaled by e^(−log_scale).
  bool exact_velocity(const Mode& mode, int row, const Rows& Q, double& z, double& floor,
                      double& log_scale) {
    log_scale = 0.0;
    if (rank_ == 0) return false;
    const auto Wr = cs_.W.col(row);
    VecT<R> c = VecT<R>::Zero(u_);
    const auto& U = svd_.matrixU();
    const auto& sv = svd_.singularValues();
    for (int l = 0; l < rank_; ++l) {
      const double coef = U.col(l).dot(Wr) / sv(l);
      for (int t = 0; t < u_; ++t) c(t) += V_(t, l) * coef;
    }
    double off = 0.0, size = 0.0;
    for (int i = 0; i < n_; ++i) {
      double x = -Wr(i), xs = std::fabs(Wr(i));
      for (int t = 0; t < u_; ++t) x += WE_(i, t) * c(t), xs += std::fabs(WE_(i, t) * c(t));
      off = std::max(off, std::fabs(x));
      size = std::max(size, xs);
    }
    if (!(off <= 64 * kEps * u_ * size)) return false;
    equations(mode, Q, false);  // t_E at Q
    bool fixed_obstacles = offset(row) == 0.0;
    for (int t = 0; t < u_; ++t) fixed_obstacles = fixed_obstacles && offset(E_(t)) == 0.0;
    if (fixed_obstacles) {
      // z = Σ c_t t_t, scaled by its largest term (only its sign and its floor are read): the
      // free rows' t underflow where their e is large.
      auto log_of = [&](int t) {
        return log_t_(t) > -kInfinity || tE_(t) == 0.0 ? log_t_(t) : std::log(std::fabs(tE_(t)));
      };
      double L = -kInfinity;
      for (int t = 0; t < u_; ++t)
        if (c(t) != 0.0) L = std::max(L, log_of(t));
      z = floor = 0.0;
      if (!std::isfinite(L)) return true;  // every t is zero: so is z
      log_scale = L;
      for (int t = 0; t < u_; ++t) {
        if (c(t) == 0.0 || !(log_of(t) > -kInfinity)) continue;
        const double term = c(t) * std::exp(log_of(t) - L);
        // term carries c_t's sign; t_t's multiplies it (a copysign would drop c_t's).
        z += (log_t_(t) > -kInfinity ? sign_t_(t) : sign_of(tE_(t))) * term;
        floor += 64 * kEps * u_ * std::fabs(term);
      }
      return true;
    }
    z = offset(row);
    floor = 64 * kEps * std::fabs(z);
    for (int t = 0; t < u_; ++t) {
      const double term = c(t) * (tE_(t) - offset(E_(t)));
      z += term;
      floor += 64 * kEps * u_ * std::fabs(term);
    }
    return true;
  }

  /// The rounding floor of the stopping test (row_rounding_floor) of a row, as a percussion:
  /// what a row's percussion may be off by and still pass it.
  double percussion_floor(int row, const Rows& X) const {
    return rows_.rounding_floor(row, X) / rows_.tau(row);
  }

  /// The mode's inequalities (docs/laws.md) at its root X; the rows that break them are switched.
  bool keeps_inequalities(Mode& mode, const Rows& X) {
    rows_.mean_velocity(X, z_);
    const Rows z = z_;
    bool kept = true;
    for (int j = 0; j < a_; ++j) {
      if (mode.normal(j) == kFree) {  // D_NE ≥ 0, with z_N exact from the power law
        double slope = 0.0;
        const double D_NE = 2.0 * free_velocity(j, X(j), slope) - cs_.D_A(j);
        if (D_NE < -2.0 * rows_.rounding_floor(j, X)) mode.normal(j) = kReaction, kept = false;
      } else {  // the reaction pushes: P_N + φ'(D_NA/2) ≥ 0
        const double reaction =
            X(j) + rows_.law->normal[rows_.contact(j)].subgradient(0.5 * cs_.D_A(j));
        if (reaction < -percussion_floor(j, X)) mode.normal(j) = kFree, kept = false;
      }
      const double b = mu_(j) * std::fabs(X(j));
      if (mode.tangent(j) == kStick) {
        // Within the cone to the stopping test's own rounding: the root of a sticking mode at
        // its bound is as far off as the mode's condition makes it (3e-13 relative at a pivot of
        // 4e-4: two contacts on two dofs, both at their bounds).
        if (std::fabs(X(a_ + j)) >
            b + mu_(j) * percussion_floor(j, X) + percussion_floor(a_ + j, X)) {
          mode.tangent(j) = kSlide;
          mode.sign(j) = X(a_ + j) >= 0.0 ? 1 : -1;
          kept = false;
        }
        continue;
      }
      // Sliding against its velocity: σ z_T ≤ 0, read from the mode's exact conditions where
      // its W_T lies in the span of W_E (the velocities the mode fixes may all be far below the
      // rounding of D_A + G P/2).
      // A z_T below ε² of the row's velocities (2^-104, 5e-32 relative) is taken as zero, where
      // sliding either way holds: beyond what a quad-precision reference resolves, and what the
      // law can mean (p = 1.01 puts these velocities near 1e-1000, where each direction of
      // sliding is the exact answer of no contact mode).
      const int row = a_ + j;
      double zt = z(row), floor = 0.0, log_scale = 0.0;
      const double row_scale = std::fabs(cs_.D_A(row)) + 0.5 * rows_.abs_GP(row, X);
      if (!exact_velocity(mode, row, X, zt, floor, log_scale)) floor = rows_.rounding_floor(row, X);
      const bool negligible =
          std::log(std::fabs(zt)) + log_scale <= std::log(kEps * kEps * row_scale);
      if (zt * mode.sign(j) > floor && !negligible) mode.tangent(j) = kStick, kept = false;
    }
    return kept;
  }

  const ImpactProblemT<N, C>& pb_;
  const FremondRowsT<N, C>& rows_;
  const CS& cs_;
  const int a_, n_;
  bool applicable_ = false;
  VecT<C> k_, e_, mu_;
  // The current mode's system (set_up, equations).
  Index E_;
  int u_ = 0, rank_ = 0, d_ = 0;
  MatT<N, R> WE_, v_;
  Eigen::JacobiSVD<MatT<N, R>> svd_;
  RowMat V_, J_;
  Rows Nw_, h_, scale_, tE_, dtE_, z_;
  Rows log_t_, sign_t_;  ///< log|t_E| and sign t_E of the free rows (−∞ elsewhere)
  Rows null_log_;        ///< the largest log|t| of each homogeneous null-space equation
  Eigen::Matrix<bool, Eigen::Dynamic, 1, 0, R, 1> null_free_, null_reaction_, homogeneous_;
};

}  // namespace

template <int N, int C>
bool solve_in_coulomb_mode(const ImpactProblemT<N, C>& pb, const FremondRowsT<N, C>& rows,
                           typename FremondRowsT<N, C>::Rows& P,
                           const typename ImpactResultT<N, C>::CVec& P_N_reaction,
                           const SolverOptions& opt) {
  using Modes = CoulombModes<N, C>;
  using Rows = typename Modes::Rows;
  Modes modes(pb, rows);
  if (!modes.applicable()) return false;
  const int a = modes.contacts();
  const double target = opt.tolerance * rows.cs->v_scale;
  auto passes = [&](const Rows& X) {
    Rows z, R;
    return std::isfinite(rows.residual(X, z, R)) && rows.converged(X, R, target);
  };
  // From the answer's own mode, switching the rows that break their inequalities.
  auto mode = modes.mode_of(P, P_N_reaction);
  Rows X = P;
  for (int change = 0; change <= 2 * a + 2; ++change) {
    const auto outcome = modes.solve(mode, X);
    if (outcome == Modes::Outcome::no_root) break;
    if (outcome == Modes::Outcome::feasible) {
      if (!passes(X)) break;
      P = X;
      return true;
    }
  }
  // Else every mode from the answer (6^a of them, up to 4 contacts: a rare path), and the root
  // nearest to the answer among those that keep their inequalities and pass the law's test.
  if (a > 4) return false;
  int count = 1;
  for (int j = 0; j < a; ++j) count *= 6;
  Rows best;
  double best_distance = std::numeric_limits<double>::infinity();
  const double P_size = std::max(P.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  // Two starts: the answer, and the answer with its normal percussions made positive. A sliding
  // contact's bound μ|P_N| has a root of each sign of P_N, and Newton takes the one its start is
  // nearer: a start with P_N < 0 can end outside the friction cone where the answer has P_N > 0.
  Rows pushing = P;
  for (int j = 0; j < a; ++j) pushing(j) = std::fabs(P(j));
  const bool one_start = pushing == P;
  for (int code = 0; code < count; ++code)
    for (int start = 0; start < (one_start ? 1 : 2); ++start) {
      auto m = modes.mode_number(code);
      X = start == 0 ? P : pushing;
      if (modes.solve(m, X) != Modes::Outcome::feasible || !passes(X)) continue;
      const double distance = (X - P).cwiseAbs().maxCoeff() / P_size;
      if (distance < best_distance) {
        best_distance = distance;
        best = X;
      }
    }
  if (!std::isfinite(best_distance)) return false;
  P = best;
  return true;
}

#define FREMOND_INSTANTIATE(N, C)                                                                  \
  template bool solve_in_coulomb_mode(const ImpactProblemT<N, C>&, const FremondRowsT<N, C>&,      \
                                      FremondRowsT<N, C>::Rows&, const ImpactResultT<N, C>::CVec&, \
                                      const SolverOptions&);
FREMOND_INSTANTIATE(Dynamic, Dynamic)
FREMOND_INSTANTIATE(kSmallDofs, kSmallContacts)
#undef FREMOND_INSTANTIATE

}  // namespace fremond::detail
