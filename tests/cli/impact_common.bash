# Shared by the tests/cli/impact_*.sh scripts; not a test itself (ctest runs *.sh only).
#
#   source "$(dirname "$0")/impact_common.bash" "$1"   # $1: the fremond binary
#   ...checks...
#   finish
#
# Every check counts; `finish` exits non-zero when one failed, after all have run, so one run
# lists every broken refusal at once.
source "$(dirname "${BASH_SOURCE[0]}")/check_common.bash" "$1"
DATA="$HERE/../data/problems"

# run_impact ARGS...: runs `fremond impact ARGS` with the caller's standard input; sets RC, leaves
# the output in $TMP/out and $TMP/err.
run_impact() {
  "$FREMOND" impact "$@" >"$TMP/out" 2>"$TMP/err"
  RC=$?
}

# expect_refusal NAME KEY REASON ARGS...: the command must refuse the input: exit status 1 (not a
# crash), nothing on stdout, and a message naming KEY (as "...: KEY: ...") and containing REASON.
expect_refusal() {
  local name=$1 key=$2 reason=$3
  shift 3
  run_impact "$@"
  local ok=1
  if [ "$RC" -ge 128 ]; then
    fail "$name: crashed (exit status $RC)"
    ok=0
  elif [ "$RC" -ne 1 ]; then
    fail "$name: exit status $RC, expected 1"
    ok=0
  fi
  if [ -s "$TMP/out" ]; then
    fail "$name: printed on stdout: $(head -c 200 "$TMP/out")"
    ok=0
  fi
  if ! grep -qF -- ": $key: " "$TMP/err"; then
    fail "$name: the message does not name '$key': $(cat "$TMP/err")"
    ok=0
  fi
  if ! grep -qF -- "$reason" "$TMP/err"; then
    fail "$name: the message does not say '$reason': $(cat "$TMP/err")"
    ok=0
  fi
  [ "$ok" -eq 1 ] && pass
}

# refuse NAME KEY REASON TEXT: TEXT on standard input (`fremond impact -`) must be refused.
refuse() {
  expect_refusal "$1" "$2" "$3" - <<<"$4"
}

# refuse_edit NAME KEY REASON BASE 'python statement on d': the problem file BASE (in $DATA),
# changed by the statement, written to a file and passed by name, must be refused. In the statement
# raw('1e999') puts text into the file as it is (JSON numbers that Python would not write).
refuse_edit() {
  local name=$1 key=$2 reason=$3 base=$4 edit=$5
  if ! "$PY" - "$DATA/$base" "$edit" >"$TMP/in.json" 2>"$TMP/pyerr" <<'EOF'; then
import json, re, sys
d = json.load(open(sys.argv[1]))
def raw(text):
    return "@@raw@@" + text + "@@"
exec(sys.argv[2], {"d": d, "raw": raw})
out = json.dumps(d, allow_nan=False)
print(re.sub(r'"@@raw@@(.*?)@@"', r"\1", out))
EOF
    fail "$name: could not write the input: $(cat "$TMP/pyerr")"
    return
  fi
  expect_refusal "$name" "$key" "$reason" "$TMP/in.json"
}

# check_json NAME CODE [PROBLEM]: runs the Python statements CODE with `d` the JSON that the last
# run printed (refusing NaN and Infinity, which are not JSON), `p` the problem file PROBLEM (in
# $DATA) if given, and near(a, b, rel=1e-12) for numbers and lists of numbers.
check_json() {
  local name=$1 code=$2 problem=${3:-}
  if "$PY" - "$TMP/out" "$code" "${problem:+$DATA/$problem}" 2>"$TMP/pyerr" <<'EOF'; then
import json, math, sys
def reject(constant):
    raise ValueError("not JSON: " + constant)
d = json.loads(open(sys.argv[1]).read(), parse_constant=reject)
p = json.load(open(sys.argv[3])) if sys.argv[3] else None
def near(a, b, rel=1e-12, tiny=1e-12):
    if isinstance(b, (list, tuple)):
        assert isinstance(a, list) and len(a) == len(b), f"{a} != {b}"
        for x, y in zip(a, b):
            near(x, y, rel, tiny)
        return
    assert isinstance(a, (int, float)) and not isinstance(a, bool), f"{a!r} is not a number"
    assert abs(a - b) <= rel * max(abs(a), abs(b)) + tiny, f"{a!r} != {b!r}"
exec(sys.argv[2], {"d": d, "p": p, "near": near, "math": math})
EOF
    pass
  else
    fail "$name: $(tail -n 3 "$TMP/pyerr") -- output: $(head -c 400 "$TMP/out")"
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
