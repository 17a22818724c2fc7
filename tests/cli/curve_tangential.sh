# `fremond curve tangential` (Fig. 9): inside the dead zone D_TE = D_TA exactly, outside the q = 2
# closed form; the defaults are the paper's Fig. 9 in either scaling.
source "$(dirname "$0")/curve_common.bash" "$1"

run_curve tangential
expect_status "default run" 0
check_csv "defaults: the paper's figure, dead zone |D_TA| <= 0.2" '
assert all((r["scaling"], r["k_T"], r["q"], r["r"], r["k"], r["p"]) == ("library", 1.5, 2, 0.2, 4, 2) for r in rows)
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
cut -d, -f7- "$TMP/out" >"$TMP/spec.csv"

# The same law in the paper's scaling gives the same numbers (columns 7 on), and says so.
run_curve tangential --scaling paper
expect_status "paper scaling" 0
check_csv "paper scaling named" '
assert all((r["scaling"], r["k_T"], r["r"], r["k"]) == ("paper", 0.75, 0.4, 2) for r in rows)'
if diff -q <(cut -d, -f7- "$TMP/out") "$TMP/spec.csv" >/dev/null; then
  pass
else
  fail "paper scaling: the rows differ from the library's scaling for the same law"
fi

# Given explicitly in the paper's scaling: r_paper = 0.8 is our dead zone |D_TA| <= 0.4.
run_curve tangential --scaling paper --r 0.8 --kt 2 --q 3 --mass 2 --dna -3 --points 41 --max-speed 2
expect_status "explicit paper values" 0
check_csv "explicit paper values" '
assert all((r["k_T"], r["q"], r["r"]) == (2, 3, 0.8) for r in rows)
for r in rows:
    assert (r["in_dead_zone"] == 1) == (abs(r["D_TA"]) <= 0.4), r
    assert r["D_NA"] == -3
    if abs(r["D_TA"]) <= 0.4:
        assert r["D_TE"] == r["D_TA"]
    else:  # m(D_TE − D_TA) = −k_T (|z| − r)² sign z, z = (D_TA + D_TE)/2
        z = (r["D_TA"] + r["D_TE"]) / 2
        near(2 * (r["D_TE"] - r["D_TA"]), -8 * (abs(z) - 0.4) ** 2 * math.copysign(1, z), 1e-10)'

# --out: the file, and one line naming the constants in both scalings.
run_curve tangential --scaling paper --r 0.8 --kt 2 --q 3 --points 5 --out "$TMP/fig9.csv"
expect_status "--out" 0
if grep -qF "k_T = 8, q = 3, r = 0.4, k = 4 (library) = k_T 2, r 0.8, k 2 (paper)" "$TMP/out"; then
  pass
else
  fail "--out: the line does not give the constants in both scalings: $(cat "$TMP/out")"
fi

finish
