#pragma once
/// @file Computes the admissibility certificate (docs/concepts.md) of any law's answer.
#include "fremond/admissibility/admissibility_report.hpp"
#include "fremond/core/impact_problem.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond {

/// Checks (15) in sum and per contact, (16)-(17) for Frémond's reaction, (19) for its dissipative
/// part, the Fenchel–Young gap of every potential with a known conjugate, and non-penetration, on
/// the velocities and percussions in `result`. Only reads `result`.
template <int MaxDofs, int MaxContacts>
AdmissibilityReportT<MaxContacts> check_admissibility(
    const ImpactProblemT<MaxDofs, MaxContacts>& problem, const ImpactLaw& law,
    const ImpactResultT<MaxDofs, MaxContacts>& result, const SolverOptions& options = {});

}  // namespace fremond
