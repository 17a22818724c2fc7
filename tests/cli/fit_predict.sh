# `fremond predict` and `fremond fit` on a point mass sliding onto the ground, its measurements made
# by hand from Newton + Coulomb's closed form (v_N' = −e v_N; v_T' = v_T − μ(1+e)|v_N| while it
# slides, 0 once it sticks): predict reproduces them, fit finds e and μ again and ranks
# newton_coulomb above newton; bad files and options are refused, naming the row and key.
source "$(dirname "$0")/check_common.bash" "$1"

"$PY" - "$TMP/data.json" <<'PY'
import json, sys
rows = []
e, mu = 0.7, 0.2
for vn in (-1.0, -2.0, -3.0):
    for vt in (0.0, 0.2, 0.5, 1.0, 2.0, 3.0):
        vt_e = max(vt - mu * (1 + e) * abs(vn), 0.0)
        rows.append({"M": [[1, 0], [0, 1]], "W_N": [[0], [1]], "W_T": [[1], [0]],
                     "qdot_A": [vt, vn], "qdot_E": [vt_e, -e * vn], "sigma": 0.01})
json.dump(rows, open(sys.argv[1], "w"))
PY

# predict: the exact law gives residuals 0.
"$FREMOND" predict "$TMP/data.json" --law newton_coulomb --params e=0.7,mu=0.2 \
  >"$TMP/pred.csv" 2>"$TMP/err"
RC=$?
if [ "$RC" -ne 0 ]; then
  fail "predict: exit status $RC: $(cat "$TMP/err")"
elif ! "$PY" - "$TMP/pred.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 36, len(rows)
assert list(rows[0]) == ["impact", "component", "measured", "predicted", "sigma", "residual",
                         "impact_rms", "status"], list(rows[0])
assert all(abs(float(r["residual"])) < 1e-9 for r in rows), rows
assert all(r["status"] == "converged" for r in rows)
PY
then
  fail "predict: wrong CSV"
elif ! grep -q "RMS 0 sigma\|RMS [0-9.e-]*e-[0-9]* sigma" "$TMP/err"; then
  fail "predict: no RMS on stderr: $(cat "$TMP/err")"
else
  pass
fi

# predict with a JSON law, a tenth off in e: the normal residuals are 0.1 |v_N| / 0.01.
"$FREMOND" predict "$TMP/data.json" --law '{"type": "newton_coulomb", "e": 0.8, "mu": 0.2}' \
  --out "$TMP/p2.csv" >/dev/null 2>&1 || fail "predict --law JSON: exit status $?"
"$PY" - "$TMP/p2.csv" <<'PY' || fail "predict --law JSON: wrong residuals"
import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["component"] == "1"]
for r in rows:
    assert abs(float(r["residual"]) - 0.1 * float(r["measured"]) / 0.7 / 0.01) < 1e-6, r
PY
pass

# fit: e and μ again, newton_coulomb first.
"$FREMOND" fit "$TMP/data.json" --law newton,newton_coulomb --folds 3 --json \
  --out "$TMP/fit.json" >/dev/null 2>"$TMP/err"
RC=$?
if [ "$RC" -ne 0 ]; then
  fail "fit: exit status $RC: $(cat "$TMP/err")"
elif ! "$PY" - "$TMP/fit.json" <<'PY'
import json, sys
fits = json.load(open(sys.argv[1]))
best = fits[0]
assert best["law"] == "newton_coulomb", fits
assert abs(best["parameters"]["e"] - 0.7) < 1e-6, best
assert abs(best["parameters"]["mu"] - 0.2) < 1e-6, best
assert best["rank"] == 1 and fits[1]["law"] == "newton"
assert best["heldout_rms"] < 1e-3 < fits[1]["heldout_rms"], fits
for key in ("uncertainties", "training_rms", "status", "evaluations", "global_status", "seconds"):
    assert key in best, key
PY
then
  fail "fit: wrong JSON: $(cat "$TMP/fit.json")"
else
  pass
fi

# The table, by default.
"$FREMOND" fit "$TMP/data.json" --law newton_coulomb --folds 0 --global-evaluations 50 \
  >"$TMP/table" 2>&1 || fail "fit table: exit status $?"
grep -q "^1 *newton_coulomb" "$TMP/table" || fail "fit table: $(cat "$TMP/table")"
pass

# Refusals: exit status 1, the row and key or the option named.
refused() {  # refused WHAT EXPECTED COMMAND...
  local what=$1 expected=$2
  shift 2
  "$FREMOND" "$@" >"$TMP/out" 2>"$TMP/err"
  local rc=$?
  if [ "$rc" -ne 1 ]; then
    fail "$what: exit status $rc, expected 1"
  elif ! grep -qF -- "$expected" "$TMP/err"; then
    fail "$what: expected '$expected' in: $(cat "$TMP/err")"
  elif [ -s "$TMP/out" ]; then
    fail "$what: wrote to stdout"
  else
    pass
  fi
}
"$PY" - "$TMP/data.json" "$TMP/bad.json" <<'PY'
import json, sys
rows = json.load(open(sys.argv[1]))
rows[3]["qdot_E"] = [1.0, "fast"]
json.dump(rows, open(sys.argv[2], "w"))
PY
refused "bad row" "impacts[3].qdot_E[1]: must be a number" predict "$TMP/bad.json" \
  --law newton --params e=0.5
refused "bad row (fit)" "impacts[3].qdot_E[1]" fit "$TMP/bad.json" --law newton
refused "unknown family" "--law: unknown law family 'hooke'" fit "$TMP/data.json" --law hooke
refused "missing parameter" "--params: mu: missing" predict "$TMP/data.json" \
  --law newton_coulomb --params e=0.5
refused "e out of range" "law.e" predict "$TMP/data.json" --law newton --params e=1.5
refused "one fold" "--folds: must be 0" fit "$TMP/data.json" --law newton --folds 1
refused "fix unknown" "--fix: fixed.k" fit "$TMP/data.json" --law newton --fix k=1
refused "bad loss" "--loss: unknown value 'cauchy'" fit "$TMP/data.json" --law newton \
  --loss cauchy
refused "missing file" "cannot open" fit "$TMP/none.json" --law newton

finish
