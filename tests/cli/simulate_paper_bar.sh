# `fremond simulate --preset paper-bar --law LAW --out DIR` for each law of the paper (the paper's Fig. 1):
# the files are complete and consistent, the energy never rises except at flagged impacts, and a
# rerun writes the same bytes.
source "$(dirname "$0")/check_common.bash" "$1"

for law in newton newton_coulomb poisson_coulomb fremond_coulomb fremond_viscous; do
  out="$TMP/$law"
  "$FREMOND" simulate --preset paper-bar --law "$law" --t-end 3 --out "$out" --no-progress \
    >"$TMP/stdout" 2>"$TMP/stderr"
  rc=$?
  if [ "$rc" -ne 0 ]; then fail "$law: exit status $rc: $(cat "$TMP/stderr")"; continue; fi
  pass
  grep -q "^status: *completed" "$TMP/stdout" && pass || fail "$law: no summary: $(cat "$TMP/stdout")"
  if "$PY" - "$out" "$law" 2>"$TMP/pyerr" <<'PYEOF'; then pass; else fail "$law: $(tail -n 3 "$TMP/pyerr")"; fi
import csv, json, math, sys
out, law = sys.argv[1], sys.argv[2]
def reject(c): raise ValueError("not JSON: " + c)
impacts = json.loads(open(out + "/impacts.json").read(), parse_constant=reject)
summary = json.loads(open(out + "/summary.json").read(), parse_constant=reject)
rows = list(csv.reader(open(out + "/trajectory.csv")))
assert rows[0] == ["t", "x", "y", "theta", "xdot", "ydot", "thetadot", "energy"], rows[0]
data = [[float(x) for x in r] for r in rows[1:]]
assert len(data) > 3000, len(data)
t = [r[0] for r in data]
assert t[0] == 0.0 and t[-1] == 3.0, (t[0], t[-1])
assert all(b >= a for a, b in zip(t, t[1:])), "time goes back"
# Energy column: 1/2 qdot'M qdot + m g y, M = diag(1, 1, 1/12) (the paper's Fig. 1).
for r in data:
    e = 0.5 * (r[4] ** 2 + r[5] ** 2 + r[6] ** 2 / 12) + 9.81 * r[2]
    assert abs(e - r[7]) <= 1e-9 * (1 + abs(e)), (r, e)
# The impact log: every key, one entry per impact.
keys = ["t", "contacts", "qdot_A", "qdot_E", "P_N", "P_T", "energy_A", "energy_E", "admissible",
        "failed"]
assert isinstance(impacts, list) and len(impacts) >= summary["impacts"] > 5
for imp in impacts:
    for k in keys:
        assert k in imp, k
    assert len(imp["P_N"]) == len(imp["contacts"])
    assert imp["admissible"] == (imp["failed"] == "none"), imp
first = impacts[0]
assert first["contacts"] == [0] and abs(first["t"] - math.sqrt(2 * (1 - 0.5 * math.sin(math.pi / 4)) / 9.81)) < 1e-12
# Energy between rows rises only across impacts flagged inadmissible.
flagged = [imp["t"] for imp in impacts if not imp["admissible"]]
for a, b in zip(data, data[1:]):
    if b[7] - a[7] > 1e-12 and not any(a[0] <= f <= b[0] for f in flagged):
        raise AssertionError(f"energy rises from {a[7]} to {b[7]} between t={a[0]} and {b[0]}")
assert summary["max_energy_rise"] <= 1e-12
assert summary["status"] == "completed" and summary["t"] == 3.0
# Newton + Coulomb creates energy at impacts (paper 4.1, Fig. 5), the others do not.
if law == "newton_coulomb":
    assert summary["inadmissible_impacts"] > 0 and any(i["energy_E"] > i["energy_A"] for i in impacts if not i["admissible"])
else:
    assert summary["inadmissible_impacts"] == 0, summary
PYEOF
  # Reproducible to the last bit.
  "$FREMOND" simulate --preset paper-bar --law "$law" --t-end 3 --out "$TMP/again" --no-progress \
    >/dev/null 2>&1
  for f in trajectory.csv impacts.json summary.json; do
    cmp -s "$out/$f" "$TMP/again/$f" && pass || fail "$law: $f differs on a rerun"
  done
  # No temporary file left behind.
  [ -z "$(ls -A "$out" | grep -v -x -e trajectory.csv -e impacts.json -e summary.json)" ] && pass ||
    fail "$law: stray files: $(ls -A "$out")"
done

# 30 s, and --max-impacts bounds the run.
"$FREMOND" simulate --preset paper-bar --law poisson_coulomb --t-end 30 --out "$TMP/long" \
  --no-progress >"$TMP/stdout" 2>&1 && pass || fail "30 s: $(cat "$TMP/stdout")"
grep -q "accumulation: 1" "$TMP/stdout" && pass || fail "30 s: no accumulation: $(cat "$TMP/stdout")"
"$FREMOND" simulate --preset paper-bar --law newton --max-impacts 3 --out "$TMP/three" \
  --no-progress >"$TMP/stdout" 2>&1
[ $? -eq 0 ] && grep -q "status: *max_impacts" "$TMP/stdout" && pass ||
  fail "--max-impacts: $(cat "$TMP/stdout")"
"$PY" -c "import json,sys; d=json.load(open('$TMP/three/impacts.json')); assert len(d)==3, len(d)" &&
  pass || fail "--max-impacts 3 did not log 3 impacts"

finish
