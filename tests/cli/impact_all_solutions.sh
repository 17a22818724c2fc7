# `fremond impact --all-solutions` prints every solution found (docs/laws.md):
# {"count": N, "solutions": [result, ...]}, each result in the format of a single solve.
source "$(dirname "$0")/impact_common.bash" "$1"

for problem in fremond_point.json fremond_coulomb_point.json fremond_viscous_point.json \
  newton_bar.json poisson_bar.json newton_coulomb_point.json poisson_coulomb_point.json \
  poisson_coulomb_two_contacts.json spec_example.json; do
  run_impact "$DATA/$problem"
  cp "$TMP/out" "$TMP/single"
  run_impact --all-solutions "$DATA/$problem"
  expect_status "$problem --all-solutions" 0
  # These problems have one solution: the list holds it, and it is the answer of a single solve.
  check_json "$problem --all-solutions: one solution, the single solve's" "
import json
single = json.load(open('$TMP/single'))
assert sorted(d) == ['count', 'solutions'], sorted(d)
assert d['count'] == len(d['solutions']) == 1, d['count']
s = d['solutions'][0]
assert s['solver']['status'] == 'converged' and s['unique']
for key in ['qdot_E', 'P_N', 'P_T', 'D_NE', 'D_TE']:
    near(s[key], single[key], 1e-12, 1e-12)
for key in ['admissibility', 'solver', 'takes_part', 'energy_change', 'solutions_found']:
    assert key in s, key
"
done

run_impact --all-solutions --pretty "$DATA/spec_example.json"
expect_status "--all-solutions --pretty" 0
[ "$(wc -l <"$TMP/out")" -gt 10 ] && pass || fail "--all-solutions --pretty is not indented"

finish
