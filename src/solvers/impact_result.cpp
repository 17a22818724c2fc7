// Moving a result between storages (impact_result.hpp).
#include "fremond/solvers/impact_result.hpp"

namespace fremond {

namespace {
AdmissibilityReportT<Dynamic> to_dynamic(const AdmissibilityReportT<kSmallContacts>& a) {
  AdmissibilityReportT<Dynamic> d;
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
  return d;
}
}  // namespace

ImpactResult to_dynamic(const SmallImpactResult& s) {
  ImpactResult d;
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
  d.takes_part = s.takes_part;
  d.energy_change = s.energy_change;
  d.unique = s.unique;
  d.solutions_found = s.solutions_found;
  d.admissibility = to_dynamic(s.admissibility);
  d.solver = s.solver;
  return d;
}

}  // namespace fremond
