# `fremond impact` on Siconos's 2-D friction-contact files (docs/sparse.md): a one-contact file with
# its answer derived by hand, one of Siconos's own granular problems, and the refusals.
source "$(dirname "$0")/impact_common.bash" "$1"
SICONOS="$HERE/../data/siconos-fc2d"

# One contact: G = [[2, 0.5], [0.5, 1]], D_A = (-1, 0.25), mu = 0.3. Sticking would need
# |P_T| = 0.571 > 0.3 P_N = 0.193, so it slides with P_T = -0.3 P_N and D_NE = 0:
# P_N = 1 / (2 - 0.3 * 0.5) = 20/37, P_T = -6/37, D_TE = 0.25 + 0.5 P_N + P_T = 0.25 + 4/37 > 0.
printf '2\n1\n0\n2\n2\n2.0 0.5 0.5 1.0\n-1 0.25\n0.3\n' >"$TMP/one.dat"
run_impact "$TMP/one.dat"
expect_status "one contact" 0
check_json "one contact: the hand-derived slide" "
near(d['P_N'], [20/37], 1e-10)
near(d['P_T'], [-6/37], 1e-10)
near(d['D_NE'], [0.0], 0, 1e-10)
near(d['D_TE'], [0.25 + 4/37], 1e-10)
assert d['qdot_E'] == [], d['qdot_E']
assert d['solver']['status'] == 'converged'
assert d['admissibility']['admissible']
"

# Siconos's granular flow of 667 contacts, from its own test data.
run_impact "$SICONOS/fc2d_granularflowonwall_00667_00000.dat" --tolerance 1e-10
expect_status "667 contacts" 0
check_json "667 contacts: every contact closed or apart, no penetration" "
assert len(d['P_N']) == 667
assert d['solver']['residual'] <= 1e-10
assert min(d['P_N']) >= 0
assert d['admissibility']['penetration'] == 0
"

# The global form: M, H, q, b.
run_impact "$SICONOS/gfc2d_granularflowonwall_00069_00350.dat"
expect_status "69 contacts, global form" 0
check_json "69 contacts: the velocities after" "
assert len(d['qdot_E']) == 900 and len(d['P_N']) == 69
assert d['solver']['status'] == 'converged'
"

expect_refusal "a method the sparse path does not have" "--method" "nsgs" --method lemke "$TMP/one.dat"
expect_refusal "every solution" "--all-solutions" "a Siconos file" --all-solutions "$TMP/one.dat"
printf '2\n1\n0\n2\n2\n2.0 0.5 x 1.0\n-1 0.25\n0.3\n' >"$TMP/bad.dat"
expect_refusal "a word among the numbers" "line 6" "'x' is not a number" "$TMP/bad.dat"
printf '2\n1\n0\n2\n2\n2.0 0.5 0.5 1.0\n-1 0.25\n' >"$TMP/short.dat"
expect_refusal "a file cut short" "line 7" "the file ends where mu was expected" "$TMP/short.dat"

finish
