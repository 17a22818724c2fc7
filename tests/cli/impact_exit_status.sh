# The exit status of `fremond impact` (see `fremond impact --help`): 0 solved; 1 input refused
# (impact_refuse_*.sh); 2 the solver did not converge, with the result printed so that its status
# can be read; 3 the law has no solution for these data (docs/laws.md), result printed, message on
# stderr.
source "$(dirname "$0")/impact_common.bash" "$1"

run_impact "$DATA/fremond_point.json"
expect_status "converged: 0" 0
[ -s "$TMP/err" ] && fail "converged: wrote on stderr: $(cat "$TMP/err")" || pass

# A separating contact (D_NA > 0) that nothing drives: no percussion, exit 0 (docs/concepts.md).
run_impact - <<'JSON'
{"M": [[1]], "W_N": [[1]], "qdot_A": [2], "law": {"type": "newton", "e": 0.5}}
JSON
expect_status "separating contact: 0" 0
check_json "separating contact: no percussion" '
near(d["P_N"], [0.0])
near(d["qdot_E"], [2.0])
assert d["takes_part"] == [False]
assert d["solver"]["status"] == "converged"
'

# No solution: a contact approached by a moving obstacle (w_N = −1) in a direction the body cannot
# move (W_N column zero): no percussion can separate them, under any law.
run_impact "$DATA/fremond_no_solution.json"
expect_status "no solution: 3" 3
check_json "no solution: the result is printed" 'assert d["solver"]["status"] == "no_solution"'
grep -qF "has no solution for these data" "$TMP/err" && pass || fail "no solution: no message on stderr"
run_impact --all-solutions "$DATA/fremond_no_solution.json"
expect_status "no solution, --all-solutions: 3" 3
check_json "no solution, --all-solutions: an empty list" '
assert d == {"count": 0, "solutions": []}, d
'

# Not converged: a method that does not apply to the law (Lemke is for the classical laws' LCP)
# reports `unsupported`; the result is printed anyway, with exit status 2.
run_impact --method lemke "$DATA/fremond_point.json"
expect_status "unsupported method: 2" 2
check_json "unsupported method: the result is printed" '
assert d["solver"]["status"] == "unsupported", d["solver"]
assert d["solver"]["residual"] is None or isinstance(d["solver"]["residual"], float)
'
grep -qF "did not converge (status unsupported" "$TMP/err" && pass ||
  fail "unsupported method: no message on stderr: $(cat "$TMP/err")"

# Inadmissible: Newton + Coulomb creates energy on the paper's bar (Fig. 5). The answer is the
# law's: exit 0 with a note on stderr, or 5 with --require-admissible.
bar='{"M": [[1, 0, 0], [0, 1, 0], [0, 0, 0.0833333333333]],
 "W_N": [[0], [1], [-0.353553390593]], "W_T": [[1], [0], [0.353553390593]],
 "qdot_A": [2, -3.5613, 0], "law": {"type": "newton_coulomb", "e": 0.9, "mu": 1.0}}'
run_impact - <<<"$bar"
expect_status "inadmissible: 0" 0
grep -qF "note: the answer is not admissible: total_15 fails" "$TMP/err" && pass ||
  fail "inadmissible: no note on stderr: $(cat "$TMP/err")"
run_impact --require-admissible - <<<"$bar"
expect_status "inadmissible, --require-admissible: 5" 5
check_json "inadmissible, --require-admissible: the result is printed" '
assert d["admissibility"]["admissible"] is False and d["admissibility"]["failed"] == "total_15"
'

# Usage errors exit 1, as the help says, whatever the parser's own code.
run_impact --no-such-option "$DATA/fremond_point.json"
expect_status "unknown option: 1" 1
run_impact --tolerance "$DATA/fremond_point.json"
expect_status "option without its value: 1" 1
run_impact
expect_status "no file: 1" 1

finish
