// The admissibility certificate (SPEC §4): (15) in sum and per contact, (16)-(17) for the reaction,
// (19) for the dissipative part, Fenchel–Young gaps and non-penetration.
#include "fremond/admissibility/admissibility.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fremond {

namespace {

// Fenchel–Young gap of φ at (z, s), scaled by the size of its terms and by `energy`, the impact's
// energy scale (|P|·|D_A|), so that terms that are rounding noise near z = 0 or s = 0 do not
// count as a gap; 0 when the conjugate is unknown.
double scaled_gap(const Potential& phi, double z, double s, double energy) {
  if (!phi.capabilities().conjugate) return 0.0;
  const double fz = phi.value(z), fs = phi.conjugate(s);
  if (!std::isfinite(fz) || !std::isfinite(fs)) return std::numeric_limits<double>::infinity();
  const double scale = std::fabs(fz) + std::fabs(fs) + std::fabs(s * z) + energy + 1e-300;
  return std::max(0.0, fz + fs - s * z) / scale;
}

}  // namespace

template <int N, int C>
AdmissibilityReportT<C> check_admissibility(const ImpactProblemT<N, C>& pb, const ImpactLaw& law,
                                            const ImpactResultT<N, C>& r,
                                            const SolverOptions& options) {
  AdmissibilityReportT<C> rep;
  const int c = pb.contacts();
  // A result the solver did not fill (e.g. an unsupported method) certifies nothing.
  if (r.qdot_E.size() != pb.dofs() || r.P_N.size() != c || r.P_T.size() != c ||
      r.D_NA.size() != c || r.D_NE.size() != c || r.D_TA.size() != c || r.D_TE.size() != c ||
      r.takes_part.size() != c) {
    rep.per_contact.setZero(c);
    return rep;
  }
  rep.kinetic_energy_A = 0.5 * pb.qdot_A.dot(pb.M * pb.qdot_A);
  rep.energy_change = r.energy_change;
  // An energy X is "negative" when X < −tol with tol relative to T_A (never below the rounding of
  // T_A itself, so that a velocity-level answer exact to rounding always passes).
  const double eps = std::numeric_limits<double>::epsilon();
  rep.tolerance = std::max(options.admissibility_tolerance, 64 * eps) *
                  std::max(rep.kinetic_energy_A, std::numeric_limits<double>::min());
  double v_scale = std::numeric_limits<double>::min();
  for (int i = 0; i < c; ++i)
    if (r.takes_part(i)) v_scale = std::max({v_scale, std::fabs(r.D_NA(i)), std::fabs(r.D_TA(i))});

  rep.per_contact.setZero(c);
  double p_scale = 0.0;
  for (int i = 0; i < c; ++i) p_scale = std::max({p_scale, std::fabs(r.P_N(i)), std::fabs(r.P_T(i))});
  const double energy = p_scale * v_scale;  // the impact's energy scale
  const bool fremond = law.type == LawType::fremond;
  double reaction = 0.0, dissipation = 0.0, compl_viol = 0.0, pen = 0.0, fy = 0.0;
  int worst_contact = -1;
  double worst_contact_value = 0.0;
  for (int i = 0; i < c; ++i) {
    const double zN = 0.5 * (r.D_NA(i) + r.D_NE(i));
    const double zT = 0.5 * (r.D_TA(i) + r.D_TE(i));
    const double pc = -(r.P_N(i) * zN + r.P_T(i) * zT);
    rep.per_contact(i) = pc;
    if (pc < worst_contact_value) {
      worst_contact_value = pc;
      worst_contact = i;
    }
    if (!r.takes_part(i)) continue;
    pen = std::max(pen, std::max(0.0, -r.D_NE(i)) / v_scale);
    const double Pr = (fremond && r.P_N_reaction.size() == c) ? r.P_N_reaction(i) : 0.0;
    reaction += -Pr * zN;
    dissipation += -(r.P_N(i) - Pr) * zN - r.P_T(i) * zT;
    if (fremond) {
      // (16): I_reac = −P_reac ≤ 0, D_NE ≥ 0, I_reac·D_NE = 0 (scaled by P and v scales).
      const double pscale = std::fabs(r.P_N(i)) + std::fabs(r.P_T(i)) + 1e-300;
      compl_viol = std::max({compl_viol, std::max(0.0, -Pr) / pscale,
                             std::fabs(Pr * r.D_NE(i)) / (pscale * v_scale)});
      fy = std::max(fy, scaled_gap(law.normal[i], zN, -(r.P_N(i) - Pr), energy));
      if (law.tangential == TangentialLaw::potential)
        fy = std::max(fy, scaled_gap(law.tangential_potential[i], zT, -r.P_T(i), energy));
      if (law.tangential == TangentialLaw::coulomb) {
        // Coulomb's support function b|z_T| with b = μ|P_N|; its conjugate is the indicator of
        // [−b, b], so the gap is b|z_T| + P_T z_T when |P_T| ≤ b.
        const double b = law.mu[i] * std::fabs(r.P_N(i));
        const double s = -r.P_T(i);
        const double scale = b * std::fabs(zT) + std::fabs(s * zT) + energy + 1e-300;
        const double over = std::fabs(s) - b;
        // Outside the cone the conjugate is +∞; an excess that is rounding of the largest
        // percussion of the impact is not counted as one.
        if (over > 1e-12 * (b + std::fabs(s)))
          fy = std::max(fy, over / (b + std::fabs(s) + p_scale));
        else
          fy = std::max(fy, std::max(0.0, b * std::fabs(zT) - s * zT) / scale);
      }
    }
  }
  rep.total = rep.per_contact.sum();
  rep.reaction = reaction;
  rep.dissipation = fremond ? dissipation : rep.total;
  rep.complementarity = compl_viol;
  rep.penetration = pen;
  rep.fenchel_young_gap = fy;

  const double tol = rep.tolerance;
  const double rel = std::max(options.admissibility_tolerance, 1e-12);
  auto fail = [&](Inequality what, double by, int contact = -1) {
    rep.failed = what;
    rep.violation = by;
    rep.failed_contact = contact;
  };
  if (!std::isfinite(rep.total) || rep.total < -tol) fail(Inequality::total_15, rep.total);
  else if (worst_contact >= 0 && worst_contact_value < -tol)
    fail(Inequality::per_contact_15, worst_contact_value, worst_contact);
  else if (fremond && rep.reaction < -tol) fail(Inequality::reaction_17, rep.reaction);
  else if (fremond && rep.dissipation < -tol) fail(Inequality::dissipation_19, rep.dissipation);
  else if (fremond && compl_viol > rel) fail(Inequality::complementarity_16, compl_viol);
  else if (pen > rel) fail(Inequality::non_penetration, pen);
  else if (fremond && fy > rel) fail(Inequality::fenchel_young, fy);
  rep.admissible = rep.failed == Inequality::none;
  return rep;
}

template AdmissibilityReportT<Dynamic> check_admissibility(const ImpactProblemT<Dynamic, Dynamic>&,
                                                           const ImpactLaw&,
                                                           const ImpactResultT<Dynamic, Dynamic>&,
                                                           const SolverOptions&);
template AdmissibilityReportT<kSmallContacts> check_admissibility(
    const ImpactProblemT<kSmallDofs, kSmallContacts>&, const ImpactLaw&,
    const ImpactResultT<kSmallDofs, kSmallContacts>&, const SolverOptions&);

}  // namespace fremond
