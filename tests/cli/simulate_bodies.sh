# `fremond simulate` on scenes of several bodies: the presets cradle3 and ball-on-ball and two scene
# files with "bodies", against their flights and impacts worked out by hand; bad bodies refused
# naming the key, with nothing written.
source "$(dirname "$0")/check_common.bash" "$1"
# check NAME 'python on s (summary), imp (impacts), rows (trajectory floats), head' DIR
check() {
  if "$PY" - "$3" "$2" 2>"$TMP/pyerr" <<'PYEOF'; then pass; else fail "$1: $(tail -n 3 "$TMP/pyerr")"; fi
import csv, json, math, sys
d = sys.argv[1]
def reject(c): raise ValueError("not JSON: " + c)
s = json.loads(open(d + "/summary.json").read(), parse_constant=reject)
imp = json.loads(open(d + "/impacts.json").read(), parse_constant=reject)
table = list(csv.reader(open(d + "/trajectory.csv")))
head, rows = table[0], [[float(x) for x in r] for r in table[1:]]
exec(sys.argv[2])
PYEOF
}

# Three balls, Newton e = 0.9, ball 0 at 1 m/s: G = [[2, -1], [-1, 2]], D_A = (-1, 0); both contacts
# active, D_E = (0.9, 0): P = (3.8, 1.9)/3, v = (1 - 3.8/3, 1.9/3, 1.9/3). One impact, at t = 0.
"$FREMOND" simulate --preset cradle3 --law newton --t-end 1 --out "$TMP/cradle" --no-progress \
  >"$TMP/stdout" 2>&1 && pass || fail "cradle3: $(cat "$TMP/stdout")"
check "cradle3" '
assert s["status"] == "completed" and s["bodies"] == 3 and s["impacts"] == 1, s
i = imp[0]
assert i["t"] == 0 and i["contacts"] == [0, 2], i
want = [1 - 3.8 / 3, 1.9 / 3, 1.9 / 3]
for b in range(3):
    assert abs(i["qdot_E"][3 * b] - want[b]) < 1e-14, (b, i["qdot_E"])
    assert abs(s["q"][3 * b] - (0.2 * b + want[b])) < 1e-14, s["q"]
assert head[:7] == ["t", "x0", "y0", "theta0", "xdot0", "ydot0", "thetadot0"] and head[-1] == "energy", head
assert len(head) == 2 + 18 and rows[-1][0] == 1.0
' "$TMP/cradle"

# A ball dropped from 0.5 m above an equal ball resting on the ground, Newton e = 1: contact at
# t1 = sqrt(2h/g) at v = sqrt(2gh), the upper ball sent back at v, the lower one left at rest;
# again at 3 t1.
"$FREMOND" simulate "$SCENES/ball_on_ball_newton.json" --out "$TMP/drop" --no-progress \
  >"$TMP/stdout" 2>&1 && pass || fail "ball_on_ball: $(cat "$TMP/stdout")"
check "ball_on_ball" '
g, h = 9.81, 0.5
t1, v = math.sqrt(2 * h / g), math.sqrt(2 * g * h)
assert s["status"] == "completed" and s["impacts"] == 2, s
assert abs(imp[0]["t"] - t1) < 1e-12 and abs(imp[1]["t"] - 3 * t1) < 1e-12, imp
assert abs(imp[0]["qdot_A"][4] + v) < 1e-12 and abs(imp[0]["qdot_E"][4] - v) < 1e-12, imp[0]
assert all(r[2] == 0.1 for r in rows), "the lower ball moved"
assert abs(s["energy_final"] - s["energy_initial"]) < 1e-12, s
' "$TMP/drop"

# Five balls under Stronge'"'"'s distributing law (e* = 1): momentum 1 and energy 1/2 kept, the last
# ball leaving with nearly all the speed.
"$FREMOND" simulate "$SCENES/cradle_five_stronge.json" --out "$TMP/five" --no-progress \
  >"$TMP/stdout" 2>&1 && pass || fail "cradle_five: $(cat "$TMP/stdout")"
check "cradle_five" '
v = [s["qdot"][3 * b] for b in range(5)]
assert abs(sum(v) - 1) < 1e-12 and abs(0.5 * sum(x * x for x in v) - 0.5) < 1e-9, v
assert v[4] > 0.9 and s["impacts"] == 1, v
' "$TMP/five"

# Every preset under every law of --law: the run ends at t_end, energy is never created (the
# impacts are head-on: friction has no slip to act on), and no ball goes into another or the ground.
for preset in cradle3 cradle5 ball-on-ball; do
  for law in newton newton_coulomb poisson_coulomb fremond_coulomb fremond_viscous stronge_coulomb; do
    "$FREMOND" simulate --preset "$preset" --law "$law" --t-end 2 --out "$TMP/$preset-$law" \
      --no-progress >"$TMP/stdout" 2>&1 && pass || fail "$preset $law: $(cat "$TMP/stdout")"
    check "$preset $law" '
assert s["status"] == "completed" and s["t"] == 2 and s["impacts"] >= 1, s
assert s["max_energy_rise"] <= 1e-12 and s["energy_final"] <= s["energy_initial"] + 1e-12, s
for i in imp:
    assert i["energy_E"] <= i["energy_A"] * (1 + 1e-9) + 1e-12, i
n = s["bodies"]
for r in rows:
    for a in range(n):
        if n == 2:
            assert r[1 + 6 * a + 1] >= 0.1 - 1e-9, r
        for b in range(a + 1, n):
            dx = r[1 + 6 * b] - r[1 + 6 * a]
            dy = r[1 + 6 * b + 1] - r[1 + 6 * a + 1]
            assert math.hypot(dx, dy) >= 0.2 - 1e-9, (a, b, r)
' "$TMP/$preset-$law"
  done
done

# Refused naming the key, nothing written.
refused() {
  local name=$1 key=$2 reason=$3
  shift 3
  rm -rf "$TMP/out"
  "$FREMOND" simulate "$@" >"$TMP/stdout" 2>"$TMP/stderr"
  local rc=$? ok=1
  [ "$rc" -eq 1 ] || { fail "$name: exit status $rc, expected 1 ($(cat "$TMP/stderr"))"; ok=0; }
  grep -qF -- "$key: " "$TMP/stderr" || { fail "$name: does not name '$key': $(cat "$TMP/stderr")"; ok=0; }
  grep -qF -- "$reason" "$TMP/stderr" || { fail "$name: does not say '$reason': $(cat "$TMP/stderr")"; ok=0; }
  for f in trajectory.csv impacts.json summary.json; do
    [ ! -e "$TMP/out/$f" ] || { fail "$name: wrote $f"; ok=0; }
  done
  [ "$ok" -eq 1 ] && pass
}
edited() {
  local name=$1 key=$2 reason=$3 edit=$4
  "$PY" - "$SCENES/ball_on_ball_newton.json" "$edit" >"$TMP/scene.json" <<'PYEOF'
import json, sys
d = json.load(open(sys.argv[1]))
exec(sys.argv[2], {"d": d})
print(json.dumps(d))
PYEOF
  refused "$name" "$key" "$reason" "$TMP/scene.json" --out "$TMP/out" --no-progress
}
edited "negative mass" "bodies[1].mass" "> 0" 'd["bodies"][1]["mass"] = -1'
edited "no q" "bodies[0].q" "missing" 'del d["bodies"][0]["q"]'
edited "short qdot" "bodies[1].qdot" "3 entries" 'd["bodies"][1]["qdot"] = [0, 1]'
edited "unknown key" "bodies[0].colour" "unknown key of a ball" 'd["bodies"][0]["colour"] = "red"'
edited "bad radius" "bodies[0].points[0].radius" ">= 0" 'd["bodies"][0] = {"mass": 1, "inertia": 1, "points": [{"r": [0, 0], "radius": -1}], "q": [0, 0.1, 0]}'
edited "law per contact" "law.e" "" 'd["law"]["e"] = [1, 1]'
edited "empty bodies" "bodies" "non-empty list" 'd["bodies"] = []'
edited "inside each other" "initial" "in penetration" 'd["bodies"][1]["q"] = [0, 0.2, 0]'
edited "off-centre disk" "bodies[1].points[0].r" "centre" 'd["bodies"][1] = {"mass": 1, "inertia": 1, "points": [{"r": [0.01, 0], "radius": 0.1}], "q": [0, 0.8, 0]}'
edited "body and bodies" "body" "unknown key" 'd["body"] = {"shape": "ball", "mass": 1, "radius": 0.1}'
refused "moreau_jean" "integrator.method" "event-driven only" "$SCENES/ball_on_ball_newton.json" \
  --integrator moreau_jean --out "$TMP/out" --no-progress
finish
