# `fremond simulate` on long runs: a grid the user did not choose is made coarser rather than
# writing millions of rows; an interrupted run writes what it computed; a slide the law does not
# resist is named.
source "$(dirname "$0")/check_common.bash" "$1"

# check NAME DIR 'python statements on s (summary.json) and rows (trajectory.csv, floats)'
check() {
  if "$PY" - "$2" "$3" 2>"$TMP/pyerr" <<'PYEOF'; then
import csv, json, sys
d = sys.argv[1]
s = json.load(open(d + "/summary.json"))
rows = [[float(v) for v in r] for r in list(csv.reader(open(d + "/trajectory.csv")))[1:]]
exec(sys.argv[2], {"s": s, "rows": rows})
PYEOF
    pass
  else
    fail "$1: $(tail -n 3 "$TMP/pyerr")"
  fi
}

# 3,000 s of the paper's bar under the viscous dead zone: at the default 1 ms, 3 million rows;
# without --sample-interval the grid becomes t_end / 1,000,000 = 3 ms, and stderr says so.
"$FREMOND" simulate --preset paper-bar --law fremond_viscous --t-end 3000 --out "$TMP/long" \
  --no-progress >"$TMP/stdout" 2>"$TMP/stderr"
rc=$?
[ "$rc" -eq 0 ] && pass || fail "long run: exit status $rc: $(cat "$TMP/stderr")"
grep -qF "rows every 0.003 s, not 0.001 s" "$TMP/stderr" && pass ||
  fail "long run: no note on the coarser grid: $(cat "$TMP/stderr")"
# The bar ends lying on the ground, sliding at 0.03 m/s, inside the dead zone |D_T| <= r = 0.2:
# no tangential percussion, so nothing stops it; D_T of a flat bar is its x velocity.
check "long run: grid and slide" "$TMP/long" '
assert s["status"] == "completed", s["status"]
assert 1000000 <= len(rows) <= 1000000 + 2 * s["impacts"] + 2, len(rows)
steps = [b[0] - a[0] for a, b in zip(rows[-100:], rows[-99:])]
assert all(abs(h - 0.003) < 1e-9 for h in steps), steps[:3]
slide = s["unresisted_slide"]
assert slide is not None and slide["contact"] in (0, 1), slide
assert abs(slide["D_T"] - s["qdot"][0]) <= 1e-12 and 0.01 < slide["D_T"] < 0.2, slide
assert abs(s["q"][1]) < 1e-5 and abs(abs(s["q"][2]) - 3.141592653589793) < 1e-5, s["q"]'
grep -qF "nothing in the model stops it" "$TMP/stdout" && pass ||
  fail "long run: the summary does not explain the slide: $(cat "$TMP/stdout")"

# --sample-interval chosen by the user is kept; --max-rows 0 keeps the scene's grid.
"$FREMOND" simulate --preset paper-bar --law fremond_viscous --t-end 30 --max-rows 1000 \
  --sample-interval 0.001 --out "$TMP/chosen" --no-progress >/dev/null 2>"$TMP/stderr"
check "chosen interval kept" "$TMP/chosen" 'assert len(rows) >= 30000, len(rows)'
"$FREMOND" simulate --preset paper-bar --law fremond_viscous --t-end 30 --max-rows 0 \
  --out "$TMP/nolimit" --no-progress >/dev/null 2>"$TMP/stderr"
check "no limit" "$TMP/nolimit" 'assert len(rows) >= 30000, len(rows)'

# Newton + Coulomb stops the bar: no unresisted slide.
"$FREMOND" simulate --preset paper-bar --law newton_coulomb --out "$TMP/nc" --no-progress \
  >/dev/null 2>&1
check "Coulomb stops the slide" "$TMP/nc" 'assert s["unresisted_slide"] is None, s["unresisted_slide"]'

# Interrupted (SIGINT, as Ctrl-C sends; SIGTERM as timeout(1) does): exit status 128 + the signal,
# and complete files up to where the run stopped. --foreground: one signal, to the command alone
# (timeout otherwise signals its process group too, and a second signal ends the run at once).
for sig in INT TERM; do
  rm -rf "$TMP/cut"
  timeout --foreground --preserve-status -s "$sig" 1 "$FREMOND" simulate --preset paper-bar \
    --law fremond_viscous --t-end 1e7 --out "$TMP/cut" --no-progress >"$TMP/stdout" 2>"$TMP/stderr"
  rc=$?
  want=$([ "$sig" = INT ] && echo 130 || echo 143)
  [ "$rc" -eq "$want" ] && pass || fail "SIG$sig: exit status $rc, expected $want: $(cat "$TMP/stderr")"
  grep -qF "interrupted at t =" "$TMP/stderr" && pass || fail "SIG$sig: no message: $(cat "$TMP/stderr")"
  check "SIG$sig: files up to the stop" "$TMP/cut" '
assert s["status"] == "interrupted", s["status"]
assert 0 < s["t"] < 1e7 and rows[-1][0] == s["t"], (s["t"], rows[-1][0])
assert rows[0][0] == 0 and len(rows) > 10'
done

finish
