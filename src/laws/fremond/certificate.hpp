#pragma once
// Frémond's terms of the admissibility certificate (docs/concepts.md): the reaction apart from the
// potentials' part of P_N, complementarity (16), and the Fenchel–Young gaps of φ_N, φ_T and of
// Coulomb's support function.
#include <algorithm>
#include <cmath>
#include <limits>

#include "admissibility/detail/admissibility.hpp"
#include "fremond/laws/fremond/fremond_law.hpp"

namespace fremond::detail {

inline bool has_certificate_terms(const FremondLaw& /*law*/) {
  return true;
}

/// Contact i's terms (CertificateTerms) for the answer seen as `k`.
inline void certificate_terms(const FremondLaw& law, int i, const CertificateContact& k,
                              CertificateTerms& out) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const bool separating = k.separating;
  const double zN = k.zN, zT = k.zT, v_scale = k.v_scale, p_scale = k.p_scale;
  const double solved_to = k.solved_to, g_max = k.g_max, energy = k.energy;
  // A separating contact's reaction is all of P_N: it obeys its law with no potential.
  const double Pr = separating ? k.P_N : k.P_N_reaction;
  out.reaction = Pr;
  double compl_viol = 0.0, fy = 0.0;
  // How well z = (D_A + D_E)/2 and the percussions are known (see scaled_gap): to the
  // solver's stopping tolerance on the law's residual (relative to the velocities), and never
  // better than rounding.
  const double dz =
      std::max(k.rounding, std::max(8 * eps, 2 * solved_to) *
                               std::max({v_scale, std::fabs(k.D_NE), std::fabs(k.D_TE)}));
  // The stopping test (fremond_rows.hpp) weighs row j's residual by τ_max/τ_j, so it bounds
  // the percussion error of every row by tolerance · v_scale / τ_max with τ_max = G_max/2,
  // whatever the percussions' own size: a contact barely loaded (P ≪ v_scale/G_max, e.g.
  // D_NA ≪ D_TA) has its P known to that, not to the tolerance times max|P|. The same
  // percussion scale as the reference's, max(max|P|, v_scale/max G_jj).
  const double p_known = std::max(p_scale, g_max > 0.0 ? 2.0 * v_scale / g_max : 0.0);
  // And a row that stopped at its rounding floor knows its percussion only to floor/τ_j.
  const double ds = std::max({8 * eps * p_scale, 2 * solved_to * p_known, k.percussion_floor});
  // (16): I_reac = −P_reac ≤ 0, D_NE ≥ 0, I_reac·D_NE = 0 (scaled by P and v scales).
  // A separating contact's reaction is held to the impact's percussion scale: a solve on
  // every contact leaves the open ones rounding's percussions, not exact zeros.
  const double pscale = std::fabs(k.P_N) + std::fabs(k.P_T) + (separating ? p_scale : 0.0) + 1e-300;
  // D_NE = 0 holds only to how well D_NE is known (dz: rounding, or the solver's tolerance).
  compl_viol =
      std::max({compl_viol, std::max(0.0, -Pr) / pscale,
                std::fabs(Pr) * std::max(0.0, std::fabs(k.D_NE) - 2 * dz) / (pscale * v_scale)});
  if (!separating) fy = std::max(fy, scaled_gap(law.normal[i], zN, -(k.P_N - Pr), energy, dz, ds));
  if (law.has_tangential_potential()) {
    if (!separating)
      fy = std::max(fy, scaled_gap(law.tangential_potential[i], zT, -k.P_T, energy, dz, ds));
    else  // φ_T = 0: its conjugate allows P_T = 0 alone
      fy = std::max(fy, std::max(0.0, std::fabs(k.P_T) - ds) / (p_scale + 1e-300));
  }
  if (law.uses_coulomb()) {
    // Coulomb's support function b|z_T| with b = μ|P_N|; its conjugate is the indicator of
    // [−b, b], so the gap is b|z_T| + P_T z_T when |P_T| ≤ b.
    const double b = law.mu[i] * std::fabs(k.P_N);
    const double s = -k.P_T;
    const double scale = b * std::fabs(zT) + std::fabs(s * zT) + energy + 1e-300;
    const double over = std::fabs(s) - b;
    // Outside the cone the conjugate is +∞. But P_T is known only to ds, and b = μ|P_N| to
    // μ·ds: an excess within that, or within the rounding of the two, is not counted as one.
    // (A contact touching below rounding beside fast sliding with μ = 1e8 has P_N and P_T
    // of 1e-12 while ds is 2e-9: its percussions are noise the law cannot be held to.)
    const double known = (1.0 + law.mu[i]) * ds + 1e-12 * (b + std::fabs(s));
    if (over > known)
      fy = std::max(fy, (over - known) / (b + std::fabs(s) + p_scale));
    else
      // The gap b|z_T| + P_T z_T less what the errors of z_T (dz), of P_T (ds) and of b
      // (μ·ds) can make of it.
      fy = std::max(fy, std::max(0.0, b * std::fabs(zT) - s * zT - (b + std::fabs(s)) * dz -
                                          (1.0 + law.mu[i]) * ds * std::fabs(zT)) /
                            scale);
  }
  out.complementarity = compl_viol;
  out.fenchel_young = fy;
}

}  // namespace fremond::detail
