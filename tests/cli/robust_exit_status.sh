# Every failure of the `fremond` command exits non-zero with a message, and no input makes it
# crash: bad command lines (no command, unknown command or option, a missing or malformed value),
# options out of range (NaN, infinities, text), and hostile input (random bytes, NUL bytes, deep
# nesting, a very long number, a large file). Exit statuses of `fremond impact`: 1 refused, 2 not
# converged, 3 no solution (impact_exit_status.sh); a crash is a status ≥ 128.
source "$(dirname "$0")/impact_common.bash" "$1"
PROBLEM="$DATA/newton_bar.json"

# expect_failure NAME ARGS...: `fremond ARGS` (stdin from $TMP/in when it exists) must exit with
# a status in 1..127 and print a message on stderr (CLI11 prints usage errors there too). Leaves
# the status in $rc.
expect_failure() {
  local name=$1
  shift
  if [ -f "$TMP/in" ]; then
    timeout 120 "$FREMOND" "$@" <"$TMP/in" >"$TMP/out" 2>"$TMP/err"
  else
    timeout 120 "$FREMOND" "$@" </dev/null >"$TMP/out" 2>"$TMP/err"
  fi
  rc=$?
  if [ "$rc" -eq 124 ]; then
    fail "$name: did not finish within 120 s"
  elif [ "$rc" -eq 0 ]; then
    fail "$name: exit status 0"
  elif [ "$rc" -ge 128 ]; then
    fail "$name: crashed (signal $((rc - 128)))"
  elif [ ! -s "$TMP/err" ]; then
    fail "$name: exit status $rc without a message on stderr"
  else
    pass
  fi
}

# --- The command line
rm -f "$TMP/in"
expect_failure "no command"
expect_failure "unknown command" frobnicate
expect_failure "unknown option" impact --no-such-option "$PROBLEM"
expect_failure "impact without a file" impact
expect_failure "two files" impact "$PROBLEM" "$PROBLEM"
expect_failure "--method without a value" impact "$PROBLEM" --method
expect_failure "--method unknown" impact --method fastest "$PROBLEM"
for t in nan NaN inf -inf 1e999 0 -1e-13 0.5 abc '' 1e-13x; do
  expect_failure "--tolerance '$t'" impact --tolerance "$t" "$PROBLEM"
done

# --- Hostile input on stdin: refused (status 1), never a crash.
# refuse_stdin NAME: `fremond impact -` on $TMP/in must refuse it: status 1, a message, nothing
# on stdout.
refuse_stdin() {
  local name=$1
  expect_failure "$name" impact -
  if [ "$rc" -ne 1 ]; then
    fail "$name: exit status $rc, expected 1 (refused)"
  elif [ -s "$TMP/out" ]; then
    fail "$name: printed on stdout although refused"
  else
    pass
  fi
}
head -c 4096 /dev/urandom >"$TMP/in"
refuse_stdin "random bytes"
printf '{"M": [[1]], "W_N": [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5}}\0' >"$TMP/in"
refuse_stdin "a NUL byte after the object"
printf '{"M": [[1\0]], "W_N": [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5}}' >"$TMP/in"
refuse_stdin "a NUL byte inside"
printf '\xef\xbb\xbf{"M": [[1]], "W_N": [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5}, "\xff": 1}' >"$TMP/in"
refuse_stdin "invalid UTF-8 in a key"
python3 -c 'print("[" * 200000 + "]" * 200000)' >"$TMP/in"
refuse_stdin "200,000 nested lists"
python3 -c 'print("{\"M\": " + "{\"a\": " * 100000 + "1" + "}" * 100000 + "}")' >"$TMP/in"
refuse_stdin "100,000 nested objects"
python3 -c 'print("{\"M\": [[1" + "0" * 100000 + "]], \"W_N\": [[1]], \"qdot_A\": [-1], \"law\": {\"type\": \"newton\", \"e\": 0.5}}")' >"$TMP/in"
refuse_stdin "a number of 100,000 digits"
python3 -c '
import json
n = 400
print(json.dumps({"M": [[1.0 if i == j else 0.0 for j in range(n)] for i in range(n)],
                  "W_N": [[1.0] for _ in range(n)], "qdot_A": [-1.0] * n,
                  "law": {"type": "newton", "e": 1.5}}))' >"$TMP/in"
refuse_stdin "a 400x400 problem with e out of range"
rm -f "$TMP/in"

# --- Commands that are not there yet say so.
for cmd in simulate curve; do
  if "$FREMOND" "$cmd" --help >/dev/null 2>&1; then
    expect_failure "$cmd without arguments" "$cmd"
  fi
done

finish
