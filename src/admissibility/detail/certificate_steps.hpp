#pragma once
/// @file The admissibility certificate in three steps (docs/concepts.md): the impact's scales, one
/// contact's terms, and the verdict. check_admissibility runs them over a whole result; a solver
/// that has one contact's numbers as scalars runs the same steps on them, to the same bits.
#include <algorithm>
#include <cmath>
#include <limits>

#include "admissibility/detail/admissibility.hpp"
#include "fremond/admissibility/admissibility_report.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/solver_options.hpp"
#include "laws/detail/plugins.hpp"

namespace fremond::detail {

/// The scales an impact's certificate is judged by: the first pass over its contacts.
struct CertificateFrame {
  double kinetic_energy_A = 0.0;  ///< T_A
  /// The largest |D_NA|, |D_TA| over the contacts that take part (at least the smallest normal).
  double v_scale = std::numeric_limits<double>::min();
  double p_scale = 0.0;                  ///< the largest |P_N|, |P_T|
  double solved_to = 0.0;                ///< the stopping tolerance of the method that answered
  double admissibility_tolerance = 0.0;  ///< SolverOptions::admissibility_tolerance
  bool own_terms = false;    ///< the law adds terms of its own (Frémond's: (16), (17), (19))
  bool each_contact = true;  ///< (15) holds contact by contact, not only in sum
  double energy() const { return p_scale * v_scale; }  ///< the impact's energy scale

  CertificateFrame(const ImpactLaw& law, const SolverOptions& options, SolverMethod method,
                   double T_A)
      : kinetic_energy_A(T_A),
        solved_to(method == SolverMethod::nlopt ? options.nlopt_accepts() : options.tolerance),
        admissibility_tolerance(options.admissibility_tolerance),
        own_terms(law.visit([](const auto& l) { return has_certificate_terms(l); })),
        // A law whose contacts pass energy to one another (Stronge's on coupled contacts: a blow
        // runs along a chain) is held to (15) in total, not contact by contact.
        each_contact(law.visit([](const auto& l) {
          if constexpr (requires { l.shares_energy_between_contacts; })
            return !l.shares_energy_between_contacts;
          else
            return true;
        })) {}

  /// Takes contact velocities before and percussions into the scales.
  void add_scales(bool takes_part, double D_NA, double D_TA, double P_N, double P_T) {
    if (takes_part) v_scale = std::max({v_scale, std::fabs(D_NA), std::fabs(D_TA)});
    p_scale = std::max({p_scale, std::fabs(P_N), std::fabs(P_T)});
  }
  /// An energy X is "negative" when X < −tol with tol relative to T_A (never below the rounding of
  /// T_A itself, so that a velocity-level answer exact to rounding always passes).
  double relative_tolerance() const {
    return std::max(admissibility_tolerance, 64 * std::numeric_limits<double>::epsilon()) *
           std::max(kinetic_energy_A, std::numeric_limits<double>::min());
  }
};

/// One contact of an answer, with how well its velocities after are known.
struct CertificateInput {
  bool takes_part = true;
  double P_N = 0.0, P_T = 0.0, D_NA = 0.0, D_TA = 0.0, D_NE = 0.0, D_TE = 0.0;
  double P_N_reaction = 0.0;      ///< the reaction part of P_N the result reports (0 if none)
  double rounding = 0.0;          ///< velocity_rounding's entry (0 if unknown)
  double percussion_floor = 0.0;  ///< velocity_rounding's percussion entry (0 if unknown)
  double w_N = 0.0, w_T = 0.0;    ///< the obstacle's velocity terms
};

/// The sums of the second pass, contact by contact in order.
struct CertificateTally {
  double energy_rounding = 0.0, reaction = 0.0, dissipation = 0.0;
  double complementarity = 0.0, penetration = 0.0, fenchel_young = 0.0;
  int worst_contact = -1;
  double worst_value = 0.0;
  /// Eq. (9) needs fixed obstacles only where a percussion acts: a contact without one adds
  /// nothing to T_E − T_A, however its obstacle moves.
  bool fixed_obstacles = true;
};

/// Contact i's terms into `t`; returns its (15) work −P·z.
[[gnu::always_inline]] inline double add_contact(const CertificateFrame& f, const ImpactLaw& law,
                                                 int i, const CertificateInput& a, double g_max,
                                                 CertificateTally& t) {
  const double eps = std::numeric_limits<double>::epsilon();
  // How well the energies P·z themselves are known: z carries the rounding of forming it
  // (`rounding`, 16ε Σ|G_jk P_k| when G is ill-conditioned), which at velocities near 1e-10 is
  // above the relative tolerance times T_A, and the solver's stopping tolerance (NLopt's 1e-9 of
  // the velocities moves P·z by 1e-9 of itself, above 1e-9·T_A when P·z is about T_A).
  const double dz = std::max(a.rounding, std::max(8 * eps, 2 * f.solved_to) * f.v_scale);
  t.energy_rounding += (std::fabs(a.P_N) + std::fabs(a.P_T)) * dz;
  const bool loaded = a.P_N != 0.0 || a.P_T != 0.0;
  t.fixed_obstacles = t.fixed_obstacles && ((a.w_N == 0.0 && a.w_T == 0.0) || !loaded);
  // Halved before the sum: velocities near the largest double (an obstacle's 1e308) have a
  // finite mean whose sum overflows, and 0·∞ would make a separating contact's energy NaN.
  const double zN = 0.5 * a.D_NA + 0.5 * a.D_NE;
  const double zT = 0.5 * a.D_TA + 0.5 * a.D_TE;
  // A work beyond the largest double is ±∞; where its two terms are infinite with opposite signs
  // it is unknown, and counts as −∞: energy created, the answer not certified.
  double pc = -(a.P_N * zN + a.P_T * zT);
  if (std::isnan(pc)) pc = -std::numeric_limits<double>::infinity();
  // A separating contact's reaction does positive work on its own true mean velocity by the
  // convention that holds it (docs/concepts.md): reported, and left to the total's check.
  if (pc < t.worst_value && a.takes_part) {
    t.worst_value = pc;
    t.worst_contact = i;
  }
  // Every contact takes part (docs/concepts.md): D_NE ≥ 0 for each, to how well D_NE is known
  // (rounding, velocity_rounding, or the solver's tolerance).
  const double dv = std::max(a.rounding, std::max(8 * eps, f.solved_to) * f.v_scale);
  t.penetration = std::max(t.penetration, std::max(0.0, -a.D_NE - 2 * dv) / f.v_scale);
  // A separating contact (D_NA > 0) carries the reaction alone, its law read with the velocity
  // before the impact at min(D_NA, 0) = 0: the reaction's (17) is then −P_N D_NE/2, and no
  // potential applies to it. Its (15) above keeps the true mean velocity (eq. 9).
  const bool separating = !a.takes_part;
  if (separating && !loaded) return pc;  // undriven: nothing to add
  // The law's own terms (its certificate_terms): Frémond's reaction, (16) and Fenchel-Young.
  CertificateTerms own;
  if (f.own_terms) {
    const CertificateContact contact{.separating = separating,
                                     .zN = zN,
                                     .zT = zT,
                                     .P_N = a.P_N,
                                     .P_T = a.P_T,
                                     .D_NE = a.D_NE,
                                     .D_TE = a.D_TE,
                                     .P_N_reaction = a.P_N_reaction,
                                     .rounding = a.rounding,
                                     .percussion_floor = a.percussion_floor,
                                     .solved_to = f.solved_to,
                                     .v_scale = f.v_scale,
                                     .p_scale = f.p_scale,
                                     .g_max = g_max,
                                     .energy = f.energy()};
    law.visit([&](const auto& l) { certificate_terms(l, i, contact, own); });
  }
  t.reaction += -own.reaction * (separating ? 0.5 * a.D_NE : zN);
  t.dissipation += -(a.P_N - own.reaction) * zN - a.P_T * zT;
  t.complementarity = std::max(t.complementarity, own.complementarity);
  t.fenchel_young = std::max(t.fenchel_young, own.fenchel_young);
  return pc;
}

/// The verdict into `rep`, whose per_contact works and their `total` are set: the tolerance, the
/// sums, and the first inequality that fails. `energy_allowance(base)`, asked only where the
/// energy change passes `base` but not the tolerance, returns how far T_E − T_A is known from the
/// velocities (or a negative number where that cannot be said).
template <class Report, class Allowance>
[[gnu::always_inline]] inline void finish_certificate(const CertificateFrame& f,
                                                      const CertificateTally& t,
                                                      double energy_change,
                                                      Allowance&& energy_allowance, Report& rep) {
  const double eps = std::numeric_limits<double>::epsilon();
  rep.kinetic_energy_A = f.kinetic_energy_A;
  rep.energy_change = energy_change;
  rep.tolerance = std::max(f.relative_tolerance(), t.energy_rounding);
  rep.reaction = t.reaction;
  rep.dissipation = f.own_terms ? t.dissipation : rep.total;
  rep.complementarity = t.complementarity;
  rep.penetration = t.penetration;
  rep.fenchel_young_gap = t.fenchel_young;

  const double tol = rep.tolerance;
  const double rel = std::max(f.admissibility_tolerance, 1e-12);
  // (15) in sum once more, from the velocities: for fixed obstacles T_E − T_A = P·z (eq. 9), but
  // P·z is known only to the percussions times the rounding of z, which can dwarf the energies
  // (a stick held by percussions 1e19 times the velocities on cond(M) = 1e10: an allowance of
  // 3e26 beside T_A = 1.5e6), while T_E − T_A = ½(q̇_E − q̇_A)ᵀM(q̇_E + q̇_A) is known to ε cond(M)
  // times its terms (velocities made through M⁻¹ carry that). Where that is the sharper test, an
  // energy gain beyond it fails (15) whatever P·z reads. Only on that path is cond(M) estimated,
  // so a certificate pays nothing for it otherwise. The allowance also holds the relative
  // tolerance on T_A and the solver's tolerance on the impact's energy scale.
  bool gains_energy = false;
  const double base_allowed =
      std::max(std::max(f.admissibility_tolerance, 64 * eps) *
                   std::max(f.kinetic_energy_A, std::numeric_limits<double>::min()),
               2 * f.solved_to * f.energy());
  if (t.fixed_obstacles && base_allowed < tol && energy_change > base_allowed &&
      std::isfinite(energy_change)) {
    const double allowed = energy_allowance(base_allowed);
    if (allowed >= 0.0) gains_energy = allowed < tol && energy_change > allowed;
  }
  auto fail = [&](Inequality what, double by, int contact = -1) {
    rep.failed = what;
    rep.violation = by;
    rep.failed_contact = contact;
  };
  if (!std::isfinite(rep.total) || rep.total < -tol)
    fail(Inequality::total_15, rep.total);
  else if (gains_energy)
    fail(Inequality::total_15, -energy_change);
  else if (f.each_contact && t.worst_contact >= 0 && t.worst_value < -tol)
    fail(Inequality::per_contact_15, t.worst_value, t.worst_contact);
  else if (f.own_terms && rep.reaction < -tol)
    fail(Inequality::reaction_17, rep.reaction);
  else if (f.own_terms && rep.dissipation < -tol)
    fail(Inequality::dissipation_19, rep.dissipation);
  else if (f.own_terms && t.complementarity > rel)
    fail(Inequality::complementarity_16, t.complementarity);
  else if (t.penetration > rel)
    fail(Inequality::non_penetration, t.penetration);
  else if (f.own_terms && t.fenchel_young > rel)
    fail(Inequality::fenchel_young, t.fenchel_young);
  rep.admissible = rep.failed == Inequality::none;
}

}  // namespace fremond::detail
