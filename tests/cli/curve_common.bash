# Shared by the tests/cli/curve_*.sh scripts; not a test itself (ctest runs *.sh only).
#
#   source "$(dirname "$0")/curve_common.bash" "$1"   # $1: the fremond binary
#   ...checks...
#   finish
#
# Every check counts; `finish` exits non-zero when one failed, after all have run.
source "$(dirname "${BASH_SOURCE[0]}")/check_common.bash" "$1"

# run_curve ARGS...: runs `fremond curve ARGS`; sets RC, leaves the output in $TMP/out, $TMP/err.
run_curve() {
  "$FREMOND" curve "$@" >"$TMP/out" 2>"$TMP/err"
  RC=$?
}

# check_csv NAME CODE [FILE]: runs the Python statements CODE with `rows` the CSV rows (dicts of
# floats where a value is a number) of FILE (default: the last output) and near(a, b, rel=1e-12,
# tiny=1e-13). The file must be plain CSV: a header row, then rows, no comment lines.
check_csv() {
  local name=$1 code=$2 file=${3:-$TMP/out}
  if "$PY" - "$file" "$code" 2>"$TMP/pyerr" <<'PYEOF'; then
import csv, io, math, sys
text = open(sys.argv[1]).read()
assert not any(l.startswith("#") for l in text.splitlines()), "a comment line in the CSV"
def number(v):
    try:
        return float(v)
    except ValueError:
        return v
rows = [{k: number(v) for k, v in r.items()} for r in csv.DictReader(io.StringIO(text))]
def near(a, b, rel=1e-12, tiny=1e-13):
    assert abs(a - b) <= rel * max(abs(a), abs(b)) + tiny, f"{a!r} != {b!r}"
exec(sys.argv[2], {"rows": rows, "near": near, "math": math})
PYEOF
    pass
  else
    fail "$name: $(tail -n 3 "$TMP/pyerr") -- output: $(head -c 300 "$file")"
  fi
}

# expect_status NAME STATUS: the last run exited with STATUS.
expect_status() {
  if [ "$RC" -eq "$2" ]; then
    pass
  else
    fail "$1: exit status $RC, expected $2; stderr: $(cat "$TMP/err")"
  fi
}

# expect_refusal NAME OPTION REASON ARGS...: `fremond curve ARGS` must refuse: exit status 1 (not
# a crash), nothing on stdout, and a message naming OPTION (as ": OPTION: ") and saying REASON.
expect_refusal() {
  local name=$1 option=$2 reason=$3
  shift 3
  run_curve "$@"
  local ok=1
  if [ "$RC" -ne 1 ]; then
    fail "$name: exit status $RC, expected 1; stderr: $(cat "$TMP/err")"
    ok=0
  fi
  if [ -s "$TMP/out" ]; then
    fail "$name: printed on stdout: $(head -c 200 "$TMP/out")"
    ok=0
  fi
  if ! grep -qF -- ": $option: " "$TMP/err"; then
    fail "$name: the message does not name '$option': $(cat "$TMP/err")"
    ok=0
  fi
  if ! grep -qF -- "$reason" "$TMP/err"; then
    fail "$name: the message does not say '$reason': $(cat "$TMP/err")"
    ok=0
  fi
  [ "$ok" -eq 1 ] && pass
}
