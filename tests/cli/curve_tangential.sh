# `fremond curve tangential` (Fig. 9): inside the dead zone D_TE = D_TA exactly, outside the q = 2
# closed form; the defaults are the paper's Fig. 9 in either scaling.
source "$(dirname "$0")/curve_common.bash" "$1"

run_curve tangential
expect_status "default run" 0
check_csv "defaults: the paper's figure, dead zone |D_TA| <= 0.2" '
assert any(c.startswith("# scaling: spec") for c in comments), comments
assert any("k_T = 1.5, q = 2, r = 0.2 (spec) = k_T 0.75, r 0.4 (paper)" in c for c in comments), comments
assert len(rows) == 201
inside = [r for r in rows if r["in_dead_zone"] == 1]
assert len(inside) > 20
for r in rows:
    assert (r["in_dead_zone"] == 1) == (abs(r["D_TA"]) <= 0.2), r
    assert r["admissible"] == 1 and r["status"] == "converged"
for r in inside:
    assert r["D_TE"] == r["D_TA"] and r["P_T"] == 0, r'
# q = 2, k_T = 1.5, r = 0.2, m = 1: D_TE = ((m − k/2) D_TA + k r sign D_TA)/(m + k/2).
check_csv "outside the dead zone: closed form" '
for r in rows:
    v = r["D_TA"]
    if abs(v) > 0.2:
        near(r["D_TE"], (0.25 * v + 0.3 * math.copysign(1, v)) / 1.75)
        near(r["P_T"], r["D_TE"] - v)'
grep -v '^#' "$TMP/out" >"$TMP/spec.csv"

# The same law in the paper's scaling gives the same numbers, and says so.
run_curve tangential --scaling paper
expect_status "paper scaling" 0
check_csv "paper scaling named" '
assert any(c.startswith("# scaling: paper") for c in comments), comments'
if diff -q <(grep -v '^#' "$TMP/out") "$TMP/spec.csv" >/dev/null; then
  pass
else
  fail "paper scaling: the rows differ from the library's scaling for the same law"
fi

# Given explicitly in the paper's scaling: r_paper = 0.8 is our dead zone |D_TA| <= 0.4.
run_curve tangential --scaling paper --r 0.8 --kt 2 --q 3 --mass 2 --dna -3 --points 41 --max-speed 2
expect_status "explicit paper values" 0
check_csv "explicit paper values" '
assert any("k_T = 8, q = 3, r = 0.4 (spec) = k_T 2, r 0.8 (paper)" in c for c in comments), comments
for r in rows:
    assert (r["in_dead_zone"] == 1) == (abs(r["D_TA"]) <= 0.4), r
    assert r["D_NA"] == -3
    if abs(r["D_TA"]) <= 0.4:
        assert r["D_TE"] == r["D_TA"]
    else:  # m(D_TE − D_TA) = −k_T (|z| − r)² sign z, z = (D_TA + D_TE)/2
        z = (r["D_TA"] + r["D_TE"]) / 2
        near(2 * (r["D_TE"] - r["D_TA"]), -8 * (abs(z) - 0.4) ** 2 * math.copysign(1, z), 1e-10)'

finish
