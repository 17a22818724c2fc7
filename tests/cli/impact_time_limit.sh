# `fremond impact --time-limit`: a solve that runs long says so on stderr (after 1 s, then 2, 4, ...)
# and, past its limit, stops with exit status 6 and nothing on stdout. A bad limit is refused.
source "$(dirname "$0")/check_common.bash" "$1"

# 600 contacts on 1,200 dofs, dense random directions, Newton + Coulomb: Lemke (forced: automatic
# would take the sparse path from 64 contacts on) runs about 5 s on this machine (and fails,
# which does not matter here).
"$PY" - "$TMP/big.json" <<'PYEOF'
import json, random, sys
random.seed(1)
c, n = 600, 1200
# Four decimals: a file of 16 MB rather than 37, to write and to read.
W_N = [[round(random.gauss(0, 1), 4) for _ in range(c)] for _ in range(n)]
W_T = [[round(random.gauss(0, 1), 4) for _ in range(c)] for _ in range(n)]
M = [[1 if i == j else 0 for j in range(n)] for i in range(n)]
q = [round(random.gauss(0, 1), 4) for _ in range(n)]
json.dump({"M": M, "W_N": W_N, "W_T": W_T, "qdot_A": q,
           "law": {"type": "newton_coulomb", "e": 0.5, "mu": 0.5}}, open(sys.argv[1], "w"))
PYEOF

"$FREMOND" impact "$TMP/big.json" --method lemke --time-limit 1.5 >"$TMP/out" 2>"$TMP/err"
rc=$?
[ "$rc" -eq 6 ] && pass || fail "exit status $rc, expected 6: $(cat "$TMP/err")"
[ ! -s "$TMP/out" ] && pass || fail "printed on stdout: $(head -c 200 "$TMP/out")"
grep -qF "still solving after 1 s (600 contacts, 1200 dofs, newton_coulomb" "$TMP/err" && pass ||
  fail "no note after 1 s: $(cat "$TMP/err")"
grep -qF "error: no answer within --time-limit 1.5 s" "$TMP/err" && pass ||
  fail "no message at the limit: $(cat "$TMP/err")"

for bad in -1 nan inf; do
  "$FREMOND" impact "$TMP/big.json" --time-limit "$bad" >"$TMP/out" 2>"$TMP/err"
  rc=$?
  if [ "$rc" -eq 1 ] && grep -qF -- "--time-limit: " "$TMP/err" && [ ! -s "$TMP/out" ]; then
    pass
  else
    fail "--time-limit $bad: exit status $rc, stderr: $(cat "$TMP/err")"
  fi
done

# A quick solve with a limit is untouched: exit 0, no note.
echo '{"M": [[1]], "W_N": [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5}}' >"$TMP/small.json"
"$FREMOND" impact "$TMP/small.json" --time-limit 60 >"$TMP/out" 2>"$TMP/err"
rc=$?
if [ "$rc" -eq 0 ] && [ ! -s "$TMP/err" ] && grep -qF '"qdot_E":[0.5]' "$TMP/out"; then
  pass
else
  fail "small problem: exit status $rc, stderr: $(cat "$TMP/err"), stdout: $(head -c 200 "$TMP/out")"
fi

finish
