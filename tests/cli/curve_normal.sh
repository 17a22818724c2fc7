# `fremond curve normal` (Fig. 8): the p = 2 curve is eq. (24)'s straight line in either scaling,
# p = 3 follows its closed form, and the output says which scaling its constants are in.
source "$(dirname "$0")/curve_common.bash" "$1"

run_curve normal
expect_status "default run" 0
check_csv "default: scaling named, four p, 101 speeds each" '
assert all(r["scaling"] == "library" for r in rows)
assert sorted({r["p"] for r in rows}) == [1.5, 2.0, 3.0, 4.0]
assert len(rows) == 4 * 101
assert all(r["status"] == "converged" and r["admissible"] == 1 for r in rows)
assert rows[0]["abs_D_NA"] == 0 and max(r["abs_D_NA"] for r in rows) == 5'
# Eq. (24) in the library's scaling: ε = (k − 2m)/(k + 2m), here k = 4, m = 1: ε = 1/3.
check_csv "p = 2 is eq. (24)" '
for r in rows:
    if r["p"] == 2:
        near(r["D_NE"], r["abs_D_NA"] / 3)
        near(r["D_NA"], -r["abs_D_NA"], 0, 0)'

# The paper's scaling: ε = (k_paper − m)/(k_paper + m); k_paper = 19, m = 2 → 17/21.
run_curve normal --scaling paper --k 19 --p 2 --mass 2 --max-speed 3 --points 7
expect_status "paper scaling" 0
check_csv "paper scaling: eq. (24) as the paper writes it" '
assert all(r["scaling"] == "paper" for r in rows)
assert len(rows) == 7 and all(r["k"] == 19 for r in rows)
for r in rows:
    near(r["D_NE"], 17 / 21 * r["abs_D_NA"])
    near(r["P_N"], 2 * (1 + 17 / 21) * r["abs_D_NA"])'

# p = 3, k = 4, m = 1: the mass stops while |D_NA| ≤ 4m/k = 1 (the reaction takes m|D_NA|);
# above, D_NE = a − u with (k/4)u² + m u − 2ma = 0.
run_curve normal --p 3 --points 21
expect_status "p = 3" 0
check_csv "p = 3 closed form" '
for r in rows:
    a = r["abs_D_NA"]
    if a <= 1:
        near(r["D_NE"], 0.0)
        near(r["P_N"], a)
    else:
        u = (-1 + math.sqrt(1 + 8 * a)) / 2
        near(r["D_NE"], a - u, 1e-11)
        near(r["P_N_reaction"], 0.0)'

# --out writes the file and says so on stdout, with the scaling.
run_curve normal --p 2 --points 3 --out "$TMP/fig8.csv"
expect_status "--out" 0
if grep -qF "wrote $TMP/fig8.csv: Fig. 8 data" "$TMP/out" && grep -qF "library scaling; p = 2: k = 4 (library) = 2 (paper)" "$TMP/out"; then
  pass
else
  fail "--out: no message naming the file and scaling: $(cat "$TMP/out")"
fi
check_csv "--out file" '
assert len(rows) == 3
near(rows[2]["D_NE"], 5 / 3)' "$TMP/fig8.csv"

# The file is plain CSV: numpy's genfromtxt(names=True) and the csv module read the same columns
# and the same numbers (a '#' line before the header used to become numpy's field names).
if "$PY" - "$TMP/fig8.csv" <<'PYEOF' 2>"$TMP/pyerr"; then
import csv, sys
import numpy as np
data = np.genfromtxt(sys.argv[1], delimiter=",", names=True, dtype=None, encoding="utf-8")
rows = list(csv.DictReader(open(sys.argv[1])))
assert data.dtype.names[:4] == ("scaling", "p", "k", "abs_D_NA"), data.dtype.names
assert len(data) == len(rows) == 3
assert [float(r["D_NE"]) for r in rows] == list(data["D_NE"])
assert abs(data["D_NE"][2] - 5 / 3) < 1e-15
PYEOF
  pass
else
  fail "numpy.genfromtxt(names=True) does not read the CSV: $(cat "$TMP/pyerr")"
fi

finish
