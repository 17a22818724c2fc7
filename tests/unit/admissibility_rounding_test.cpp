// The certificate (SPEC §4) on answers whose numbers sit at the edge of double precision: it
// accepts the solver's right answers and still refuses a wrong one on the same data (found by the
// stress runs, tests/stress).
#include <gtest/gtest.h>

#include "fremond/fremond.hpp"
#include "fremond/io/problem_file.hpp"

namespace fremond {
namespace {

// Three contacts, all plastic (the reaction takes everything), p = 1.0001 and velocities of 1e7:
// the dissipative percussion P_N − P_reac ≈ k_N|z|^(p−1) ≈ 1.4e-5 is at the rounding of P_N ≈ 1e11,
// and φ*'s exponent p' ≈ 10⁴ makes its values within that rounding span hundreds of orders of
// magnitude. The Fenchel–Young gap was reported as 1 on the right answer (all methods agreed).
constexpr const char* kPlasticNearLinear = R"json(
{"M": [[17262.179223924228, -65562.632828086716, -39235.919354009857, -51992.251568370193, -24024.549051655224], [-65562.632828086716, 250468.85141772701, 150128.86543422661, 198296.27192363818, 92438.905134551722], [-39235.919354009857, 150128.86543422661, 94847.673822422934, 121651.66743425795, 59845.678551165838], [-51992.251568370193, 198296.27192363818, 121651.66743425795, 158903.44127553355, 74992.082533714085], [-24024.549051655224, 92438.905134551722, 59845.678551165838, 74992.082533714085, 40648.84822300099]],
 "W_N": [[-0.50660523510341804, 0.44828346105950345, -0.54348851449173652], [0.76314311488740594, -0.84676492179247898, 0.5080959882741074], [0.92201950425940726, 0.46632609040114859, -0.31941241564210099], [0.62698844880524018, -0.013077506165014019, 0.53029233943018195], [0.39913060250631816, 0.65197690246446438, 0.66859123853130797]],
 "qdot_A": [-11516384.197718339, 6303393.6914986782, -7588359.3975508157, -32617870.044752739, -10253428.219684813],
 "law": {"type": "fremond", "normal": {"potential": "power", "k": 1.4459318133958133e-05, "p": 1.0001144805582629}}}
)json";

TEST(AdmissibilityAtRounding, PlasticImpactWithPNearOneIsAdmissible) {
  const io::ProblemFile f =
      io::parse_problem_file(kPlasticNearLinear, PotentialRegistry::with_builtins());
  for (SolverMethod m : {SolverMethod::automatic, SolverMethod::proximal}) {
    SolverOptions o;
    o.method = m;
    const ImpactResult r = solve_impact(f.problem, f.law, o);
    ASSERT_TRUE(r.ok()) << to_string(m) << ": " << r.solver.message;
    EXPECT_TRUE(r.admissibility.admissible)
        << to_string(m) << ": " << to_string(r.admissibility.failed) << " by "
        << r.admissibility.violation;
    // The same energies with a tenth of the percussion moved from the reaction to the
    // dissipative part: s = −P_d is then 1e10, far outside ∂φ_N(z) ≈ 1.4e-5, and the certificate
    // must say so (by Fenchel–Young or by the reaction's inequality (17)).
    ImpactResult wrong = r;
    wrong.P_N_reaction *= 0.9;
    const auto rep = check_admissibility(f.problem, f.law, wrong, o);
    EXPECT_FALSE(rep.admissible) << to_string(m);
  }
}

}  // namespace
}  // namespace fremond
