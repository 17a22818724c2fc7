# `fremond simulate` refuses what it cannot run: exit status 1, a message naming the key or the
# option, and nothing written.
source "$(dirname "$0")/check_common.bash" "$1"

# refused NAME KEY REASON ARGS...: exit status 1, KEY and REASON in the message, no output file.
refused() {
  local name=$1 key=$2 reason=$3
  shift 3
  rm -rf "$TMP/out"
  "$FREMOND" simulate "$@" >"$TMP/stdout" 2>"$TMP/stderr"
  local rc=$? ok=1
  [ "$rc" -eq 1 ] || { fail "$name: exit status $rc, expected 1 ($(cat "$TMP/stderr"))"; ok=0; }
  grep -qF -- "$key: " "$TMP/stderr" || { fail "$name: does not name '$key': $(cat "$TMP/stderr")"; ok=0; }
  grep -qF -- "$reason" "$TMP/stderr" || { fail "$name: does not say '$reason': $(cat "$TMP/stderr")"; ok=0; }
  [ ! -s "$TMP/stdout" ] || { fail "$name: printed on stdout"; ok=0; }
  for f in trajectory.csv impacts.json summary.json; do
    [ ! -e "$TMP/out/$f" ] || { fail "$name: wrote $f"; ok=0; }
  done
  [ "$ok" -eq 1 ] && pass
}

# edited NAME KEY REASON 'python statement on d': the bar's scene file, changed, must be refused.
edited() {
  local name=$1 key=$2 reason=$3 edit=$4
  "$PY" - "$SCENES/paper_bar_newton_coulomb.json" "$edit" >"$TMP/scene.json" <<'PYEOF'
import json, sys
d = json.load(open(sys.argv[1]))
exec(sys.argv[2], {"d": d})
print(json.dumps(d))
PYEOF
  refused "$name" "$key" "$reason" "$TMP/scene.json" --out "$TMP/out" --no-progress
}

refused "no scene" "SCENE" "give a scene file" --out "$TMP/out"
refused "no --out" "--out" "required" --preset paper-bar --law newton
refused "both" "--preset" "not both" "$SCENES/ball_newton.json" --preset paper-bar --law newton --out "$TMP/out"
refused "unknown preset" "--preset" "unknown preset 'rod'" --preset rod --law newton --out "$TMP/out"
refused "no law" "--law" "required with --preset" --preset paper-bar --out "$TMP/out"
refused "unknown law" "--law" "unknown value 'hertz'" --preset paper-bar --law hertz --out "$TMP/out"
refused "a bad law before a missing --out" "--law" "unknown value 'hertz'" --preset paper-bar --law hertz
refused "negative --max-rows" "--max-rows" ">= 0" --preset paper-bar --law newton --max-rows -1 --out "$TMP/out"
refused "law with a file" "--law" "only with --preset" "$SCENES/ball_newton.json" --law newton --out "$TMP/out"
refused "negative t_end" "--t-end" "> 0" --preset paper-bar --law newton --t-end -1 --out "$TMP/out"
refused "zero step" "--step" "(0, t_end]" --preset paper-bar --law newton --step 0 --out "$TMP/out"
refused "zero max impacts" "--max-impacts" ">= 1" --preset paper-bar --law newton --max-impacts 0 --out "$TMP/out"
refused "small gap budget" "--max-gap-evaluations" ">= 100" --preset paper-bar --law newton --max-gap-evaluations 10 --out "$TMP/out"
refused "bad integrator" "--integrator" "unknown value 'rk4'" --preset paper-bar --law newton --integrator rk4 --out "$TMP/out"
refused "missing file" "/nonexistent/scene.json" "cannot open" /nonexistent/scene.json --out "$TMP/out"
refused "a directory" "$SCENES" "is a directory" "$SCENES" --out "$TMP/out"
echo '{"body": ' >"$TMP/broken.json"
refused "not JSON" "broken.json" "" "$TMP/broken.json" --out "$TMP/out"

edited "unknown key" "tend" "unknown key" 'd["tend"] = 3'
edited "unknown body key" "body.length" "unknown key" 'd["body"]["length"] = 1'
edited "negative mass" "body.mass" "must be > 0" 'd["body"]["mass"] = -1'
edited "bad normal" "obstacles[0].normal" "must not be zero" 'd["obstacles"][0]["normal"] = [0, 0]'
edited "short q" "initial.q" "3 entries" 'd["initial"]["q"] = [0, 1]'
edited "missing law" "law" "missing" 'del d["law"]'
edited "bad e" "law.e" "[0, 1]" 'd["law"]["e"] = 2'
edited "too many mu" "law.mu" "one per contact" 'd["law"]["mu"] = [1, 1, 1]'
edited "bad method" "integrator.method" "unknown value" 'd["integrator"]["method"] = "euler"'
edited "small gap budget" "integrator.max_gap_evaluations" ">= 100" 'd["integrator"]["max_gap_evaluations"] = 5'
edited "fractional gap budget" "integrator.max_gap_evaluations" "whole number" 'd["integrator"]["max_gap_evaluations"] = 1000.5'
edited "bad sample interval" "output.sample_interval" "> 0" 'd["output"]["sample_interval"] = -1'

finish
