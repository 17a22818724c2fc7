// Moving a result between storages (impact_result.hpp).
#include "fremond/solvers/impact_result.hpp"

#include <string>

#include "fremond/core/error.hpp"
#include "solvers/detail/result_copy.hpp"

namespace fremond {

namespace {
/// Every member of the certificate a into d.
template <int To, int From>
void assign_report(const AdmissibilityReportT<From>& a, AdmissibilityReportT<To>& d) {
  d.kinetic_energy_A = a.kinetic_energy_A;
  d.energy_change = a.energy_change;
  d.total = a.total;
  d.per_contact = a.per_contact;
  d.reaction = a.reaction;
  d.dissipation = a.dissipation;
  d.complementarity = a.complementarity;
  d.penetration = a.penetration;
  d.fenchel_young_gap = a.fenchel_young_gap;
  d.tolerance = a.tolerance;
  d.admissible = a.admissible;
  d.failed = a.failed;
  d.failed_contact = a.failed_contact;
  d.violation = a.violation;
}

/// The certificate in the other storage: every member.
template <int To, int From>
AdmissibilityReportT<To> convert(const AdmissibilityReportT<From>& a) {
  AdmissibilityReportT<To> d;
  assign_report(a, d);
  return d;
}

/// Every member of s into d, d's heap vectors reused where their sizes already match.
template <int N, int C, int N0, int C0>
void assign(const ImpactResultT<N0, C0>& s, ImpactResultT<N, C>& d) {
  d.qdot_E = s.qdot_E;
  d.P_N = s.P_N;
  d.P_T = s.P_T;
  d.D_NA = s.D_NA;
  d.D_TA = s.D_TA;
  d.D_NE = s.D_NE;
  d.D_TE = s.D_TE;
  d.P_N_reaction = s.P_N_reaction;
  d.has_phases = s.has_phases;
  d.P_NC = s.P_NC;
  d.P_TC = s.P_TC;
  d.D_NC = s.D_NC;
  d.D_TC = s.D_TC;
  d.qdot_C = s.qdot_C;
  d.takes_part = s.takes_part;
  d.energy_change = s.energy_change;
  d.unique = s.unique;
  d.solutions_found = s.solutions_found;
  assign_report(s.admissibility, d.admissibility);
  d.solver = s.solver;
}

/// The result in the other storage: every member.
template <int N, int C, int N0, int C0>
ImpactResultT<N, C> convert(const ImpactResultT<N0, C0>& s) {
  ImpactResultT<N, C> d;
  assign(s, d);
  return d;
}
}  // namespace

AdmissibilityReportT<Dynamic> to_dynamic(const AdmissibilityReportT<kSmallContacts>& report) {
  return convert<Dynamic>(report);
}

ImpactResult to_dynamic(const SmallImpactResult& result) {
  return convert<Dynamic, Dynamic>(result);
}

void detail::copy_into(const SmallImpactResult& from, ImpactResult& to) {
  assign(from, to);
}

bool fits_small(const ImpactResult& r) {
  if (r.qdot_E.size() > kSmallDofs || r.qdot_C.size() > kSmallDofs) return false;
  for (const Eigen::VectorXd* v :
       {&r.P_N, &r.P_T, &r.D_NA, &r.D_TA, &r.D_NE, &r.D_TE, &r.P_N_reaction, &r.P_NC, &r.P_TC,
        &r.D_NC, &r.D_TC, &r.admissibility.per_contact})
    if (v->size() > kSmallContacts) return false;
  return r.takes_part.size() <= kSmallContacts;
}

SmallImpactResult to_small(const ImpactResult& result) {
  if (!fits_small(result))
    throw InvalidArgument("result", "does not fit the small form (at most " +
                                        std::to_string(kSmallDofs) + " velocities and " +
                                        std::to_string(kSmallContacts) + " contacts)");
  return convert<kSmallDofs, kSmallContacts>(result);
}

}  // namespace fremond
