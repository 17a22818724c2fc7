# `fremond impact` when its output cannot be written: a full disk (/dev/full), a file-size limit
# reached half-way through the result (ulimit -f, the shape of a disk filling up), a closed
# standard output. Each must exit non-zero with a message on stderr: a caller that only looks at
# the exit status must never take a cut-off result for an answer.
source "$(dirname "$0")/impact_common.bash" "$1"
PROBLEM="$DATA/fremond_coulomb_point.json"

# expect_write_failure NAME RC: the command exited RC, which must be non-zero and not a crash,
# with a message on stderr ($TMP/err).
expect_write_failure() {
  local name=$1 rc=$2
  if [ "$rc" -eq 0 ]; then
    fail "$name: exit status 0 although the result could not be written"
  elif [ "$rc" -ge 128 ]; then
    fail "$name: killed by signal $((rc - 128))"
  elif ! grep -qi "fremond" "$TMP/err"; then
    fail "$name: exit status $rc but no message on stderr"
  else
    pass
  fi
}

# The result is written normally first (the baseline: it is longer than 1 KiB with --pretty, so
# the size limit below cuts it).
"$FREMOND" impact --pretty "$PROBLEM" >"$TMP/full.json" 2>"$TMP/err"
rc=$?
if [ "$rc" -ne 0 ]; then
  fail "baseline: exit status $rc: $(cat "$TMP/err")"
elif [ "$(wc -c <"$TMP/full.json")" -le 1024 ]; then
  fail "baseline: the pretty result is only $(wc -c <"$TMP/full.json") bytes; the size-limit check needs more than 1 KiB"
else
  pass
fi

# 1. A full disk.
if [ -w /dev/full ]; then
  "$FREMOND" impact "$PROBLEM" >/dev/full 2>"$TMP/err"
  expect_write_failure "stdout on /dev/full" $?
  "$FREMOND" impact --pretty --all-solutions "$PROBLEM" >/dev/full 2>"$TMP/err"
  expect_write_failure "stdout on /dev/full, --all-solutions" $?
fi

# 2. The file-size limit reached in the middle of the result: the write fails with EFBIG (the
# signal SIGXFSZ is ignored, as a caller's shell may do).
(
  trap '' XFSZ
  ulimit -f 1
  exec "$FREMOND" impact --pretty "$PROBLEM" >"$TMP/cut.json" 2>"$TMP/err"
)
expect_write_failure "file-size limit half-way through the result" $?

# 3. Standard output closed.
"$FREMOND" impact "$PROBLEM" >&- 2>"$TMP/err"
expect_write_failure "stdout closed" $?

# 4. A refusal still writes nothing on stdout and says why, even when stdout is unusable.
echo '{"M": [[1]]}' | "$FREMOND" impact - >/dev/full 2>"$TMP/err"
rc=$?
if [ "$rc" -eq 1 ] && grep -q "W_N" "$TMP/err"; then pass; else fail "refusal with stdout on /dev/full: status $rc, $(cat "$TMP/err")"; fi

finish
