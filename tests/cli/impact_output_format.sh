# The result of `fremond impact` (docs/problem-file.md): valid JSON (never NaN), every key of docs/problem-file.md plus the
# full admissibility and solver reports, enum values by their names, and the same answer whether
# the problem comes from a file or standard input, compact or --pretty.
source "$(dirname "$0")/impact_common.bash" "$1"

CONTACT_LISTS='["P_N", "P_T", "D_NA", "D_TA", "D_NE", "D_TE", "P_N_reaction", "takes_part"]'
FORMAT='
for key in ["qdot_E", "P_N", "P_T", "D_NA", "D_TA", "D_NE", "D_TE", "P_N_reaction",
            "takes_part", "energy_change", "unique", "solutions_found", "admissibility",
            "solver"]:
    assert key in d, "missing " + key
n, c = len(p["M"]), len(p["W_N"][0])
assert len(d["qdot_E"]) == n
for key in '"$CONTACT_LISTS"':
    assert len(d[key]) == c, key
assert all(isinstance(x, bool) for x in d["takes_part"])
assert isinstance(d["unique"], bool)
# null when the solutions were not counted, else how many were found (at least one)
assert d["solutions_found"] is None or (isinstance(d["solutions_found"], int) and d["solutions_found"] >= 1)
a = d["admissibility"]
assert sorted(a) == sorted(["total", "per_contact", "reaction", "dissipation", "complementarity",
    "penetration", "fenchel_young_gap", "tolerance", "admissible", "failed", "failed_contact",
    "violation", "energy_change", "kinetic_energy_A"]), sorted(a)
assert len(a["per_contact"]) == c and isinstance(a["admissible"], bool)
assert a["failed"] in ["none", "total_15", "per_contact_15", "reaction_17", "dissipation_19",
    "complementarity_16", "fenchel_young", "non_penetration"], a["failed"]
assert isinstance(a["failed_contact"], int)
s = d["solver"]
assert sorted(s) == sorted(["method", "status", "criterion", "iterations", "residual", "message",
    "native_code", "fallbacks", "attempts", "attempt_count"]), sorted(s)
assert s["method"] in ["automatic", "trivial", "closed_form", "scalar_newton", "mode_enumeration",
    "lemke", "semismooth_newton", "proximal", "nlopt"], s["method"]
assert s["status"] in ["not_run", "converged", "max_iterations", "stalled", "no_solution",
    "failed", "unsupported"], s["status"]
assert s["criterion"] in ["none", "exact", "residual", "step", "iterations", "nlopt"]
assert isinstance(s["iterations"], int) and isinstance(s["native_code"], int)
assert isinstance(s["message"], str)
assert s["residual"] is None or isinstance(s["residual"], float)
# The attempt log: every method the chain ran, in order; the answer method is among them.
assert s["attempt_count"] == len(s["attempts"]) >= 1
assert all(sorted(t) == ["method", "residual", "start", "status"] for t in s["attempts"])
assert all(t["start"] in ["none", "decoupled_guess", "zero", "newton_end", "splitting_end",
    "nlopt_end", "velocity_newton_end", "normal_rows"] for t in s["attempts"])
assert s["method"] in [t["method"] for t in s["attempts"]]
'

for problem in newton_bar.json poisson_bar.json spec_example.json newton_coulomb_point.json \
  poisson_coulomb_point.json poisson_coulomb_two_contacts.json \
  fremond_point.json fremond_reaction.json fremond_coulomb_point.json \
  fremond_viscous_point.json fremond_per_contact.json; do
  run_impact "$DATA/$problem"
  expect_status "$problem: solved" 0
  check_json "$problem: format" "$FORMAT" "$problem"
  [ "$(wc -l <"$TMP/out")" -eq 1 ] && pass || fail "$problem: compact output is not one line"
  cp "$TMP/out" "$TMP/from_file"

  run_impact - <"$DATA/$problem"
  expect_status "$problem: from stdin" 0
  if cmp -s "$TMP/out" "$TMP/from_file"; then pass; else fail "$problem: stdin and file differ"; fi

  run_impact --pretty "$DATA/$problem"
  expect_status "$problem: --pretty" 0
  [ "$(wc -l <"$TMP/out")" -gt 10 ] && pass || fail "$problem: --pretty output is not indented"
  check_json "$problem: --pretty gives the same values" \
    "import json; assert d == json.load(open('$TMP/from_file')), 'values differ'"
done

# Poisson's phases appear when the solver reports them (docs/laws.md), with one entry per contact.
run_impact "$DATA/poisson_coulomb_two_contacts.json"
check_json "poisson: phases" '
for key in ["P_NC", "P_TC", "D_NC", "D_TC"]:
    assert len(d[key]) == 2, key
'

# A result that is not usable still prints valid JSON: a residual that was not computed is null,
# never NaN (the exit status says the solve failed, see impact_exit_status.sh).
run_impact --method lemke "$DATA/fremond_point.json"
check_json "not converged: still valid JSON" "$FORMAT
assert d['solver']['status'] != 'converged'" fremond_point.json

finish
