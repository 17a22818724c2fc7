# `fremond impact` with Frémond's law (docs/laws.md), on problems whose answer is known by hand.
source "$(dirname "$0")/impact_common.bash" "$1"

# p = 2 on a point mass m: Newton's law with ε = (k − 2m)/(k + 2m) (eq. 24 in the library's scaling).
# m = 2, k = 12: ε = 1/2; D_NA = −3: D_NE = 1.5, P_N = m (D_NE − D_NA) = 9, no reaction.
run_impact "$DATA/fremond_point.json"
expect_status "fremond p = 2, point mass" 0
check_json "fremond p = 2, point mass: eq. (24)" '
m, k, DNA = p["M"][0][0], p["law"]["normal"]["k"], p["qdot_A"][0]
eps = (k - 2 * m) / (k + 2 * m)
near(d["D_NE"], [-eps * DNA])
near(d["qdot_E"], [-eps * DNA])
near(d["P_N"], [m * (-eps * DNA - DNA)])
near(d["P_N_reaction"], [0.0])
near(d["energy_change"], 0.5 * m * ((eps * DNA) ** 2 - DNA ** 2))
assert d["admissibility"]["admissible"] and d["unique"]
assert d["solver"]["status"] == "converged"
' fremond_point.json

# k < 2m: the power law alone would let the mass go on into the ground (ε < 0); the reaction
# stops it: D_NE = 0, P_N = m |D_NA| = 1, of which the power law gives −k z = 0.5 (z = −0.5)
# and the reaction the other 0.5 (eq. 16: −I_reac ≥ 0).
run_impact "$DATA/fremond_reaction.json"
expect_status "fremond reaction" 0
check_json "fremond reaction: stops at D_NE = 0" '
near(d["D_NE"], [0.0], 0, 1e-14)
near(d["P_N"], [1.0])
near(d["P_N_reaction"], [0.5])
near(d["admissibility"]["reaction"], 0.25)
assert d["admissibility"]["admissible"]
'

# Frémond + Coulomb on a point mass (G diagonal): P_N = 1.5 as above (m = 1, k = 6), and the mean
# tangential velocity z_T > 0 slides: P_T = −mu P_N = −0.15, D_TE = 2 − 0.15.
run_impact "$DATA/fremond_coulomb_point.json"
expect_status "fremond coulomb, point mass" 0
check_json "fremond coulomb, point mass: sliding" '
near(d["P_N"], [1.5])
near(d["P_T"], [-0.15])
near(d["D_NE"], [0.5])
near(d["D_TE"], [1.85])
assert d["admissibility"]["admissible"]
'

# The viscous dead zone (eq. 25), k = 2, q = 2, r = 0.2, D_TA = 2: P_T = −k (z_T − r) with
# z_T = (D_TA + D_TE)/2 and D_TE = D_TA + P_T: P_T = −1.8, D_TE = 0.2, z_T = 1.1.
run_impact "$DATA/fremond_viscous_point.json"
expect_status "fremond viscous, point mass" 0
check_json "fremond viscous, point mass: dead zone" '
near(d["P_N"], [1.5])
near(d["P_T"], [-1.8])
near(d["D_TE"], [0.2])
near(d["qdot_E"], [0.2, 0.5])
assert d["admissibility"]["admissible"]
'

# Per-contact parameters (lists in the file) on two independent contacts: contact 1 has k = 3,
# ε = 1/5, D_NA = −2: D_NE = 0.4, P_N = 2.4; r = 0.1, D_TA = 1: P_T = −0.9, D_TE = 0.1.
run_impact "$DATA/fremond_per_contact.json"
expect_status "fremond per contact" 0
check_json "fremond per contact: one potential per contact" '
near(d["P_N"], [1.5, 2.4])
near(d["D_NE"], [0.5, 0.4])
near(d["P_T"], [-1.8, -0.9])
near(d["D_TE"], [0.2, 0.1])
near(d["admissibility"]["per_contact"], [2.355, 2.415])
'

finish
