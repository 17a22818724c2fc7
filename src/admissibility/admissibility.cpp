// The admissibility certificate (docs/concepts.md): (15) in sum and per contact, (16)-(17) for the
// reaction, (19) for the dissipative part, Fenchel–Young gaps and non-penetration.
#include "fremond/admissibility/admissibility.hpp"

#include "admissibility/detail/admissibility.hpp"
#include "admissibility/detail/certificate_steps.hpp"
#include "core/detail/cholesky.hpp"
#include "core/detail/sized_vector.hpp"
#include "fremond/core/error.hpp"
#include "laws/detail/plugins.hpp"
#include "laws/detail/separating_contacts.hpp"
#include "laws/fremond/rows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include "core/detail/impact_problem.hpp"

namespace fremond {

namespace {

// f at x and at x ∓ d: each value is computed once and shared by the noise estimate and the
// resolvability test below (a potential's value may cost a pow).
struct Around {
  double at, below, above;
};
Around around(const auto& f, double x, double fx, double d) {
  return {fx, f(x - d), f(x + d)};
}

// How much f can change when its argument moves by up to d (the larger one-sided change; an
// infinite side, e.g. across an indicator's boundary, does not count).
double change_within(const Around& f) {
  double worst = 0.0;
  for (double fy : {f.below, f.above})
    if (std::isfinite(fy)) worst = std::max(worst, std::fabs(fy - f.at));
  return worst;
}

// Fenchel–Young gap of φ at (z, s) beyond what the rounding of z and s explains, scaled by the size
// of its terms and by `energy`, the impact's energy scale (|P|·|D_A|); 0 when the conjugate is
// unknown. z = (D_A + D_E)/2 is known to δz ≈ ε·|D| and s to δs ≈ ε·|P|: near z = 0 a potential
// with p close to 1 (φ ≈ k|z|) turns rounding noise δz into a gap φ(δz) ≈ k·δz comparable to
// |P|·|D_A| itself (the exact z underflows), which is not a violation of the law.
// Out of line and cold: only a user's potential without a conjugate takes it.
[[gnu::cold, gnu::noinline]] double sampled_gap(const Potential& phi, double z, double s,
                                                double energy, double dz, double ds);

}  // namespace

double detail::scaled_gap(const Potential& phi, double z, double s, double energy, double dz,
                          double ds) {
  if (!phi.capabilities().conjugate) return sampled_gap(phi, z, s, energy, dz, ds);
  // A point outside the domain of φ or φ* (an indicator's boundary, |s| ≤ b for b|z|, s = 0 when
  // k = 0) by less than its rounding is taken on the boundary: moved toward 0 by that rounding.
  auto on_domain = [](const auto& f, double& x, double d) {
    double fx = f(x);
    if (!std::isfinite(fx)) {
      const double y = x - std::copysign(std::min(d, std::fabs(x)), x);
      const double fy = f(y);
      if (std::isfinite(fy)) {
        x = y;
        fx = fy;
      }
    }
    return fx;
  };
  // s ∈ ∂φ(z), tested on the subdifferential, which is monotone: s within ds of ∂φ over
  // [z − dz, z + dz]. The same statement as a zero gap (docs/laws.md), used where the values cannot
  // tell: φ* too steep for double precision (p = 1.0001: conjugate exponent 10⁴, so its value
  // within ds of s spans hundreds of orders of magnitude), or overflowing (|s|^p' > 1e308).
  auto subdifferential_miss = [&] {
    const Interval lo = phi.subdifferential(z - dz), hi = phi.subdifferential(z + dz);
    if (lo.is_empty() || hi.is_empty()) return std::numeric_limits<double>::infinity();
    const Interval hull{lo.lo, hi.hi};
    return std::max(0.0, hull.distance(s) - ds) /
           (std::fabs(s) + std::fabs(hull.lo) + std::fabs(hull.hi) + ds + 1e-300);
  };
  const double fz = on_domain([&](double x) { return phi.value(x); }, z, dz);
  const double fs = on_domain([&](double x) { return phi.conjugate(x); }, s, ds);
  if (!std::isfinite(fz) || !std::isfinite(fs) || !std::isfinite(s * z))
    return subdifferential_miss();
  // The gap is what is left after the noise, and the noise is at least the rounding of z and s
  // acting on the product s·z: where that alone covers φ(z) + φ*(s) − s·z (every solved problem,
  // up to rounding), the gap is zero and the four evaluations around (z, s) are not needed.
  const double excess = fz + fs - s * z;
  const double product_noise = dz * std::fabs(s) + ds * std::fabs(z);
  if (excess - product_noise <= 0.0) return 0.0;
  const Around conj = around([&](double x) { return phi.conjugate(x); }, s, fs, ds);
  const double conj_noise = change_within(conj);
  const Around val = around([&](double x) { return phi.value(x); }, z, fz, dz);
  const double noise = product_noise + change_within(val) + conj_noise;
  const double scale = std::fabs(fz) + std::fabs(fs) + std::fabs(s * z) + energy + 1e-300;
  const double gap = std::max(0.0, excess - noise) / scale;
  if (gap == 0.0) return 0.0;
  // The values decide wherever φ and φ* are resolvable near (z, s), so that a wrong conjugate (a
  // user's potential that lies about itself) is caught; only where φ within dz of z or φ* within
  // ds of s leaves double precision (an indicator's boundary, or p = 33 on a z known to ±1e12 when
  // cond(M) = 1e9 and the percussions are 1e18), or φ* swings by the gap's own size, does the
  // subdifferential test decide.
  const bool resolvable = std::isfinite(val.below) && std::isfinite(val.above) &&
                          std::isfinite(conj.below) && std::isfinite(conj.above) &&
                          conj_noise < 0.5 * scale;
  return resolvable ? gap : std::min(gap, subdifferential_miss());
}

namespace {

// Without a conjugate, φ*(s) ≥ s y − φ(y) for every y bounds the gap from below by
// φ(z) − φ(y) − s (z − y): sampled at a few points, a potential that is not convex (its slope at
// z is then no subgradient) or not zero at 0 is caught at the answer. Scaled as scaled_gap; what
// the rounding of z (dz) and s (ds) can make of each sample is not counted.
[[gnu::cold, gnu::noinline]] double sampled_gap(const Potential& phi, double z, double s,
                                                double energy, double dz, double ds) {
  const double fz = phi.value(z);
  if (!std::isfinite(fz) || !std::isfinite(s)) return 0.0;  // the other checks speak for those
  const double moved = change_within(around([&](double x) { return phi.value(x); }, z, fz, dz));
  double worst = 0.0;
  const double h = std::max(std::fabs(z), 1e3 * dz);  // a step at the scale of z, never 0
  for (double y : {0.0, -z, 0.5 * z, 1.5 * z, 2.0 * z, z - h, z + h}) {
    const double fy = phi.value(y);
    if (!std::isfinite(fy)) continue;
    const double excess = fz + s * (y - z) - fy;
    const double terms = std::fabs(fz) + std::fabs(fy) + std::fabs(s * (y - z));
    const double noise = moved + dz * std::fabs(s) + ds * std::fabs(y - z) + 1e-12 * terms;
    worst = std::max(worst, std::max(0.0, excess - noise) / (terms + energy + 1e-300));
  }
  return worst;
}

}  // namespace

namespace detail {

bool not_a_pseudo_potential(const Potential& phi, double z) {
  const double f0 = phi.value(0.0), fz = phi.value(z);
  if (!std::isfinite(fz)) return false;  // outside the domain: the certificate's finding
  if (!(std::fabs(f0) <= 1e-12 * std::fabs(fz)) || fz < 0.0) return true;
  // Midpoint convexity on five chords among −z, 0, z/2, z, 3z/2, 2z, each to its rounding.
  auto above_chord = [&](double a, double b) {
    const double fa = phi.value(a), fb = phi.value(b), fm = phi.value(0.5 * (a + b));
    return std::isfinite(fa) && std::isfinite(fb) &&
           fm - 0.5 * (fa + fb) > 1e-9 * (std::fabs(fa) + std::fabs(fb)) + 1e-300;
  };
  return above_chord(0.0, z) || above_chord(0.0, 2.0 * z) || above_chord(0.5 * z, 1.5 * z) ||
         above_chord(-z, z) || above_chord(z, 2.0 * z);
}

namespace {
/// One row's share of velocity_rounding: Σ_k |G_jk||P_k| (GP) and the row's rounding
/// 16ε (|D_A,j| + κ GP + |W_j|ᵀ|q̇_E|) (d, without the last term where q̇_E is null),
/// summed in row order over loops of K = the dofs where fixed. P: the rows' percussions by index.
struct RowRounding {
  double GP, d;
};

/// Whether the solver filled the result (an unsupported method leaves it empty): an empty one
/// certifies nothing.
template <int N, int C>
bool filled(const ImpactProblemT<N, C>& pb, const ImpactResultT<N, C>& r) {
  const int c = pb.contacts();
  return r.qdot_E.size() == pb.dofs() && r.P_N.size() == c && r.P_T.size() == c &&
         r.D_NA.size() == c && r.D_NE.size() == c && r.D_TA.size() == c && r.D_TE.size() == c &&
         r.takes_part.size() == c;
}
template <int K, int N, int C, class Percussion>
RowRounding row_rounding(const ContactSpaceT<N, C>& cs, int j, const Percussion& P,
                         const double* qdot_E) {
  double GP = 0.0, WqE = 0.0;
  for (int k = 0; k < cs.rows(); ++k) GP += std::fabs(cs.G(j, k)) * std::fabs(P(k));
  if (qdot_E) {
    const int n = sized<K>(cs.dofs);
    const double* w = cs.W.data() + static_cast<std::ptrdiff_t>(cs.W.rows()) * j;
    for (int k = 0; k < n; ++k) WqE += std::fabs(w[k]) * std::fabs(qdot_E[k]);
  }
  return {GP, 16 * std::numeric_limits<double>::epsilon() *
                  (std::fabs(cs.D_A(j)) + cs.condition() * GP + WqE)};
}
}  // namespace

template <int N, int C>
VecT<C> velocity_rounding(const ContactSpaceT<N, C>& cs, const ImpactResultT<N, C>& r,
                          VecT<C>* percussion) {
  VecT<C> out = VecT<C>::Zero(cs.contacts);
  if (percussion) percussion->setZero(cs.contacts);
  const int rows = cs.rows();
  if (r.P_N.size() != cs.contacts || r.P_T.size() != cs.contacts) return out;
  typename ContactSpaceT<N, C>::Rows P = ContactSpaceT<N, C>::Rows::Zero(rows);
  for (int k = 0; k < cs.active; ++k) {
    P(cs.normal_row(k)) = r.P_N(cs.index(k));
    if (cs.tangential) P(cs.tangential_row(k)) = r.P_T(cs.index(k));
  }
  // G = Wᵀ M⁻¹ W comes from a Cholesky solve, accurate to ε κ(M) relative (row_rounding).
  // And q̇_E = q̇_A + M⁻¹WP is itself stored in doubles, each component to ε|q̇_E|: the contact
  // velocity of the answer returned is known to no better than ε |W_j|ᵀ|q̇_E|, which for a touching
  // contact (D_A exact and far below |W||q̇|, accurate_dot.hpp) is the whole of what is known.
  const double* stored = r.qdot_E.size() == cs.dofs ? r.qdot_E.data() : nullptr;
  const double g_max = percussion ? delassus_max(cs) : 0.0;
  with_size<N>(cs.dofs, [&](auto size) {
    for (int j = 0; j < rows; ++j) {
      const RowRounding row = row_rounding<decltype(size)::value>(cs, j, P, stored);
      const int i = cs.index(j < cs.active ? j : j - cs.active);
      out(i) = std::max(out(i), row.d);
      if (percussion) {
        // The stopping test's own τ_j and floor (fremond_rows.hpp).
        const double tau = row_tau(cs.G(j, j), g_max);
        const double floor = row_rounding_floor(cs.D_A(j), row.GP, tau, P(j), cs.v_scale);
        (*percussion)(i) = std::max((*percussion)(i), floor / tau);
      }
    }
  });
  return out;
}

/// How far T_E − T_A is known from the velocities (finish_certificate's energy_allowance):
/// ε cond(M) times its terms, cond(M) estimated from M's Cholesky factor, as velocity_rounding
/// does; −1 where M cannot say.
template <int N, int C>
double velocity_energy_allowance(const ImpactProblemT<N, C>& pb, const double* qdot_E,
                                 double base_allowed) {
  if (pb.M.rows() != pb.dofs() || pb.qdot_A.size() != pb.dofs()) return -1.0;
  double terms = 0.0;
  for (int i = 0; i < pb.dofs(); ++i) {
    double row = 0.0;
    for (int j = 0; j < pb.dofs(); ++j)
      row += std::fabs(pb.M(i, j)) * (std::fabs(qdot_E[j]) + std::fabs(pb.qdot_A(j)));
    terms += std::fabs(qdot_E[i] - pb.qdot_A(i)) * row;
  }
  const detail::CholeskyT<N> llt(pb.M);  // stack storage for the small sizes
  const double kappa = llt.info() == Eigen::Success ? condition_estimate(llt) : 0.0;
  if (!(kappa > 0.0)) return -1.0;
  return std::max(base_allowed, 16 * std::numeric_limits<double>::epsilon() * kappa * terms);
}

template <int N, int C>
AdmissibilityReportT<C> certify_one_contact(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                                            const OneContactFacts& r, const SolverOptions& options,
                                            const ContactSpaceT<N, C>& cs) {
  AdmissibilityReportT<C> rep;
  // velocity_rounding's sums for the contact's rows, in its order, with the percussion's floor
  // where the law has terms of its own.
  const int rows = cs.rows();
  const bool own = law.visit([](const auto& l) { return has_certificate_terms(l); });
  const double g_max = own ? delassus_max(cs) : 0.0;
  const double P[2] = {r.P_N, cs.tangential ? r.P_T : 0.0};
  const auto p = [&](int k) { return P[k]; };
  struct Sums {
    double rounding = 0.0, percussion_floor = 0.0;
  };
  const auto sums = [&](auto own_terms) {
    return with_size<N>(cs.dofs, [&](auto size) {
      Sums s;
      for (int j = 0; j < rows; ++j) {
        const RowRounding row = row_rounding<decltype(size)::value>(cs, j, p, r.qdot_E);
        s.rounding = std::max(s.rounding, row.d);
        if constexpr (decltype(own_terms)::value) {
          const double tau = row_tau(cs.G(j, j), g_max);
          const double floor = row_rounding_floor(cs.D_A(j), row.GP, tau, P[j], cs.v_scale);
          s.percussion_floor = std::max(s.percussion_floor, floor / tau);
        }
      }
      return s;
    });
  };
  const Sums rows_sums = own ? sums(std::true_type{}) : sums(std::false_type{});
  const double rounding = rows_sums.rounding, percussion_floor = rows_sums.percussion_floor;
  // check_admissibility's steps on the one contact.
  CertificateFrame f(law, options, r.method, kinetic_energy(pb.M, pb.qdot_A));
  f.add_scales(r.takes_part, r.D_NA, r.D_TA, r.P_N, r.P_T);
  CertificateTally t;
  const CertificateInput a{.takes_part = r.takes_part,
                           .P_N = r.P_N,
                           .P_T = r.P_T,
                           .D_NA = r.D_NA,
                           .D_TA = r.D_TA,
                           .D_NE = r.D_NE,
                           .D_TE = r.D_TE,
                           .P_N_reaction = r.P_N_reaction,
                           .rounding = rounding,
                           .percussion_floor = percussion_floor,
                           .w_N = pb.w_N.size() ? pb.w_N(0) : 0.0,
                           .w_T = pb.w_T.size() ? pb.w_T(0) : 0.0};
  rep.per_contact.resize(1);
  rep.per_contact(0) = add_contact(f, law, 0, a, g_max, t);
  // A work that is not a number leaves the total unknown (check_admissibility's sum).
  rep.total = std::isnan(rep.per_contact(0)) ? -std::numeric_limits<double>::infinity()
                                             : rep.per_contact(0);
  finish_certificate(
      f, t, r.energy_change,
      [&](double base) { return velocity_energy_allowance(pb, r.qdot_E, base); }, rep);
  return rep;
}

template <int N, int C>
AdmissibilityReportT<C> check_one_contact(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                                          const ImpactResultT<N, C>& r,
                                          const SolverOptions& options,
                                          const ContactSpaceT<N, C>& cs) {
  if (!filled(pb, r)) {
    AdmissibilityReportT<C> rep;
    rep.per_contact.setZero(1);
    return rep;
  }
  return certify_one_contact(pb, law, one_contact_facts(r), options, cs);
}

template <int N, int C>
AdmissibilityReportT<C> check_admissibility(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                                            const ImpactResultT<N, C>& r,
                                            const SolverOptions& options, const VecT<C>& rounding,
                                            double g_max, const VecT<C>* percussion) {
  AdmissibilityReportT<C> rep;
  const int c = pb.contacts();
  // A result the solver did not fill (e.g. an unsupported method) certifies nothing.
  if (!filled(pb, r)) {
    rep.per_contact.setZero(c);
    return rep;
  }
  CertificateFrame f(law, options, r.solver.method, kinetic_energy(pb.M, pb.qdot_A));
  for (int i = 0; i < c; ++i)
    f.add_scales(r.takes_part(i), r.D_NA(i), r.D_TA(i), r.P_N(i), r.P_T(i));
  rep.per_contact.setZero(c);
  CertificateTally t;
  for (int i = 0; i < c; ++i) {
    const CertificateInput a{
        .takes_part = r.takes_part(i) != 0,
        .P_N = r.P_N(i),
        .P_T = r.P_T(i),
        .D_NA = r.D_NA(i),
        .D_TA = r.D_TA(i),
        .D_NE = r.D_NE(i),
        .D_TE = r.D_TE(i),
        .P_N_reaction = r.P_N_reaction.size() == c ? r.P_N_reaction(i) : 0.0,
        .rounding = rounding.size() == c ? rounding(i) : 0.0,
        .percussion_floor = percussion && percussion->size() == c ? (*percussion)(i) : 0.0,
        .w_N = pb.w_N.size() ? pb.w_N(i) : 0.0,
        .w_T = pb.w_T.size() ? pb.w_T(i) : 0.0};
    rep.per_contact(i) = add_contact(f, law, i, a, g_max, t);
  }
  rep.total = rep.per_contact.sum();
  // Partial sums that overflow both ways (∞ − ∞): finite works are summed again scaled by 2⁻⁶⁰,
  // exact for works that large, to their sum or, beyond the largest double, ±∞; infinite works of
  // both signs leave the total unknown, −∞ as above.
  if (std::isnan(rep.total))
    rep.total = rep.per_contact.allFinite()
                    ? std::ldexp((std::ldexp(1.0, -60) * rep.per_contact).sum(), 60)
                    : -std::numeric_limits<double>::infinity();
  auto energy_allowance = [&](double base) {
    return velocity_energy_allowance(pb, r.qdot_E.data(), base);
  };
  finish_certificate(f, t, r.energy_change, energy_allowance, rep);
  return rep;
}

}  // namespace detail

template <int N, int C>
AdmissibilityReportT<C> check_admissibility(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                                            const ImpactResultT<N, C>& r,
                                            const SolverOptions& options) {
  if constexpr (N == Dynamic && C == Dynamic) {
    // In the storage solve_impact uses for this problem, so that the result's own certificate
    // reads the same to the last bit (solve_impact.cpp).
    if (fits_small(pb) && fits_small(r))
      return to_dynamic(check_admissibility(to_small(pb), law, to_small(r), options));
  }
  // The user's own result: form G as solve_impact does, for the velocities' rounding; data that
  // cannot be factorised (M not positive definite), or whose Delassus entries overflow (a
  // separating contact given a percussion), gets no rounding allowance.
  VecT<C> rounding = VecT<C>::Zero(pb.contacts()), percussion = VecT<C>::Zero(pb.contacts());
  double g_max = 0.0;
  const bool shapes =
      pb.M.rows() == pb.dofs() && pb.M.cols() == pb.dofs() && pb.W_N.rows() == pb.dofs() &&
      pb.W_N.cols() == pb.contacts() &&
      (pb.W_T.cols() == 0 || (pb.W_T.rows() == pb.dofs() && pb.W_T.cols() == pb.contacts()));
  if (shapes && pb.qdot_A.size() == pb.dofs()) {
    // The contacts solve_impact held: every one where a separating contact carries a percussion.
    const bool every = detail::stops_a_separating_contact(r);
    detail::ContactSpaceT<N, C> cs;
    bool formed = true;
    try {
      detail::build_contact_space(
          pb, law.has_friction(), cs,
          every ? detail::HeldContacts::every : detail::HeldContacts::approaching);
    } catch (const InvalidArgument&) {
      formed = false;
    }
    if (formed && cs.llt.info() == Eigen::Success) {
      rounding = detail::velocity_rounding(cs, r, &percussion);
      g_max = detail::delassus_max(cs);
    }
  }
  return detail::check_admissibility(pb, law, r, options, rounding, g_max, &percussion);
}

#define FREMOND_INSTANTIATE(N, C)                                                    \
  template VecT<C> detail::velocity_rounding(const detail::ContactSpaceT<N, C>&,     \
                                             const ImpactResultT<N, C>&, VecT<C>*);  \
  template AdmissibilityReportT<C> detail::check_admissibility(                      \
      const ImpactProblemT<N, C>&, const ImpactLaw&, const ImpactResultT<N, C>&,     \
      const SolverOptions&, const VecT<C>&, double, const VecT<C>*);                 \
  template AdmissibilityReportT<C> detail::check_one_contact(                        \
      const ImpactProblemT<N, C>&, const ImpactLaw&, const ImpactResultT<N, C>&,     \
      const SolverOptions&, const detail::ContactSpaceT<N, C>&);                     \
  template AdmissibilityReportT<C> detail::certify_one_contact(                      \
      const ImpactProblemT<N, C>&, const ImpactLaw&, const detail::OneContactFacts&, \
      const SolverOptions&, const detail::ContactSpaceT<N, C>&);                     \
  template AdmissibilityReportT<C> check_admissibility(                              \
      const ImpactProblemT<N, C>&, const ImpactLaw&, const ImpactResultT<N, C>&,     \
      const SolverOptions&);
FREMOND_INSTANTIATE(kSmallDofs, kSmallContacts)
FREMOND_INSTANTIATE(Dynamic, Dynamic)
#undef FREMOND_INSTANTIATE

}  // namespace fremond
