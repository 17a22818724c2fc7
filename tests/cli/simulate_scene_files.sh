# `fremond simulate SCENE.json --out DIR` on the scene files of tests/data/scenes: a ball against
# its closed form, a block between a floor and a wall, the integrator and options from the command
# line, and outputs that are complete or absent.
source "$(dirname "$0")/check_common.bash" "$1"
# check NAME 'python on s (summary), imp (impacts), rows (trajectory floats)' DIR
check() {
  if "$PY" - "$3" "$2" 2>"$TMP/pyerr" <<'PYEOF'; then pass; else fail "$1: $(tail -n 3 "$TMP/pyerr")"; fi
import csv, json, math, sys
d = sys.argv[1]
def reject(c): raise ValueError("not JSON: " + c)
s = json.loads(open(d + "/summary.json").read(), parse_constant=reject)
imp = json.loads(open(d + "/impacts.json").read(), parse_constant=reject)
rows = [[float(x) for x in r] for r in list(csv.reader(open(d + "/trajectory.csv")))[1:]]
exec(sys.argv[2])
PYEOF
}

# A ball dropped from 1 m, e = 0.5: bounces e^(2n) h0, accumulation at t1 + 2 v1 e/(g(1 - e)),
# then at rest at y = radius.
"$FREMOND" simulate "$SCENES/ball_newton.json" --out "$TMP/ball" --no-progress >"$TMP/stdout" 2>&1 &&
  pass || fail "ball: $(cat "$TMP/stdout")"
check "ball" '
g, h0, e = 9.81, 1.0, 0.5
v1, t1 = math.sqrt(2 * g * h0), math.sqrt(2 * h0 / g)
assert abs(s["first_accumulation_time"] - (t1 + 2 * v1 * e / (g * (1 - e)))) < 1e-9, s
events = [i for i in imp if i["kind"] == "event"]
for n, i in enumerate(events, 1):
    up = i["qdot_E"][1]
    assert abs(up * up / (2 * g) - e ** (2 * n) * h0) < 1e-9, (n, up)
acc = [i for i in imp if i["kind"] == "accumulation"]
assert len(acc) == 1 and abs(acc[0]["accumulation_limit"] - s["first_accumulation_time"]) < 1e-15
assert abs(s["q"][1] - 0.1) < 1e-12 and max(abs(v) for v in s["qdot"]) < 1e-12, s
assert abs(rows[-1][1 + 1] - 0.1) < 1e-12
' "$TMP/ball"

# A block with four corners against a floor and a wall (8 contacts), Frémond + Coulomb.
"$FREMOND" simulate "$SCENES/block_walls_fremond.json" --out "$TMP/block" --no-progress \
  >"$TMP/stdout" 2>&1 && pass || fail "block: $(cat "$TMP/stdout")"
check "block" '
assert s["status"] == "completed" and s["impacts"] > 5, s
assert s["inadmissible_impacts"] == 0 and s["max_energy_rise"] <= 1e-12, s
walls = [i for i in imp if any(c % 2 == 1 for c in i["contacts"])]
assert walls, "the block never reaches the wall"
# No corner goes through the wall x <= 1 or the floor y >= 0 (beyond the step-sized slack of Moreau-Jean).
for r in rows:
    for cx, cy in [(-0.2, -0.1), (0.2, -0.1), (0.2, 0.1), (-0.2, 0.1)]:
        x = r[1] + math.cos(r[3]) * cx - math.sin(r[3]) * cy
        y = r[2] + math.sin(r[3]) * cx + math.cos(r[3]) * cy
        assert x <= 1.0 + 1e-4 and y >= -1e-4, (r, cx, cy, x, y)
for i in imp:
    assert i["energy_E"] <= i["energy_A"] + 1e-12, i
' "$TMP/block"

# The command line overrides the file: Moreau-Jean, its step, the end time, the sample interval.
"$FREMOND" simulate "$SCENES/paper_bar_newton_coulomb.json" --integrator moreau_jean --step 0.0005 \
  --t-end 1.5 --sample-interval 0.01 --out "$TMP/mj" --no-progress >"$TMP/stdout" 2>&1 &&
  pass || fail "moreau_jean: $(cat "$TMP/stdout")"
check "moreau_jean" '
assert s["integrator"] == "moreau_jean" and s["step"] == 0.0005 and s["t"] == 1.5, s
assert s["moreau_jean_steps"] == 3000, s["moreau_jean_steps"]
assert all(i["kind"] == "time_step" for i in imp), [i["kind"] for i in imp]
assert 150 <= len(rows) <= 200, len(rows)
' "$TMP/mj"

# --out must be a directory; an existing file is refused and left alone.
echo keep >"$TMP/afile"
"$FREMOND" simulate --preset paper-bar --law newton --out "$TMP/afile" --no-progress >/dev/null 2>"$TMP/err"
[ $? -eq 1 ] && grep -q "cannot create the directory" "$TMP/err" && [ "$(cat "$TMP/afile")" = keep ] &&
  pass || fail "--out a file: $(cat "$TMP/err")"
# Outputs are replaced whole: a previous run's files are overwritten, not appended to.
"$FREMOND" simulate --preset paper-bar --law newton --t-end 0.5 --out "$TMP/mj" --no-progress >/dev/null 2>&1
check "overwrite" '
assert s["t"] == 0.5 and s["integrator"] == "event_driven", s
assert rows[-1][0] == 0.5 and all(r[0] <= 0.5 for r in rows), rows[-1]
assert len(rows) == 501 + 2 * len(imp), (len(rows), len(imp))
' "$TMP/mj"

# A body spinning at 1e9 rad/s, 1 m above the ground without gravity: its events cannot be
# resolved within the event search's budget. The run stops at t = 0 with exit status 2, says why,
# and writes its files up to there (one trajectory row, no impact).
cat >"$TMP/spin.json" <<'EOF'
{"body": {"shape": "bar", "mass": 1, "half_length": 0.5}, "gravity": 0,
 "initial": {"q": [0, 1, 0.3], "qdot": [0, 0, 1e9]}, "law": {"type": "newton", "e": 0.9},
 "t_end": 1, "integrator": {"max_gap_evaluations": 20000}}
EOF
"$FREMOND" simulate "$TMP/spin.json" --out "$TMP/spin" --no-progress >"$TMP/stdout" 2>"$TMP/err"
rc=$?
[ $rc -eq 2 ] && grep -q "event_search_failed" "$TMP/err" && grep -q "max_gap_evaluations" "$TMP/err" &&
  pass || fail "spin: exit $rc: $(cat "$TMP/err")"
check "spin" '
assert s["status"] == "event_search_failed" and s["t"] == 0, s
assert imp == [] and len(rows) == 1 and rows[0][0] == 0, (imp, rows)
' "$TMP/spin"
# The same flight at 1e3 rad/s is resolved: no impact, the run completes.
sed 's/1e9/1e3/' "$TMP/spin.json" >"$TMP/spin3.json"
"$FREMOND" simulate "$TMP/spin3.json" --out "$TMP/spin3" --no-progress >/dev/null 2>"$TMP/err" &&
  pass || fail "spin at 1e3 rad/s: $(cat "$TMP/err")"
check "spin3" '
assert s["status"] == "completed" and s["t"] == 1 and imp == [], s
' "$TMP/spin3"

finish
