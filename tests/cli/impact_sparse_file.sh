# `fremond impact` on problem files whose matrices are written sparse (docs/problem-file.md,
# docs/sparse.md): solved by the sparse path under Newton's law, by the dense solvers under the
# others, each with the answer of the same file written dense.
source "$(dirname "$0")/impact_common.bash" "$1"

# to_triplets SRC DST: the problem file SRC with M, W_N and W_T written as triplets.
to_triplets() {
  "$PY" - "$DATA/$1" >"$TMP/$2" <<'PYEOF'
import json, sys
d = json.load(open(sys.argv[1]))
for key in ['M', 'W_N', 'W_T']:
    if key in d:
        rows = d[key]
        d[key] = {'rows': len(rows), 'cols': len(rows[0]) if rows else 0,
                  'triplets': [[i, j, v] for i, r in enumerate(rows) for j, v in enumerate(r) if v != 0]}
print(json.dumps(d))
PYEOF
}

for problem in newton_bar.json newton_coulomb_point.json spec_example.json fremond_point.json \
  poisson_coulomb_point.json; do
  run_impact "$DATA/$problem"
  cp "$TMP/out" "$TMP/dense"
  to_triplets "$problem" sparse.json
  run_impact "$TMP/sparse.json" --tolerance 1e-14
  expect_status "$problem as triplets" 0
  check_json "$problem as triplets: the dense file's answer" "
dense = __import__('json').load(open('$TMP/dense'))
for key in ['qdot_E', 'P_N', 'P_T', 'D_NE', 'D_TE']:
    near(d[key], dense[key], 1e-10, 1e-12)
assert d['admissibility']['admissible'] == dense['admissibility']['admissible']
law = p['law']['type']
sparse_law = law in ('newton', 'newton_coulomb')
# The sparse path answers in contact coordinates: its attempts start with the sweeps.
assert (d['solver']['attempts'][0]['method'] == 'nsgs') == sparse_law, (law, d['solver'])
" "$problem"
done

# A small file written dense with --method nsgs: the dense solvers run the sweeps, to the answer of
# the method automatic; one answer is looked for, so uniqueness is not claimed.
for problem in newton_bar.json newton_coulomb_point.json spec_example.json; do
  run_impact "$DATA/$problem"
  cp "$TMP/out" "$TMP/automatic"
  run_impact "$DATA/$problem" --method nsgs
  expect_status "$problem with nsgs" 0
  check_json "$problem with nsgs: the automatic answer" "
automatic = __import__('json').load(open('$TMP/automatic'))
for key in ['qdot_E', 'P_N', 'P_T', 'D_NE', 'D_TE']:
    near(d[key], automatic[key], 1e-10, 1e-12)
assert d['solver']['status'] == 'converged'
assert d['admissibility']['admissible'] == automatic['admissibility']['admissible']
assert d['unique'] is False and d['solutions_found'] is None
" "$problem"
done

refuse "a row index out of range" "M.triplets[1][0]" "a row index must be a whole number in [0, 2)" \
  '{"M": {"rows": 2, "cols": 2, "triplets": [[0, 0, 1], [2, 1, 1]]}, "W_N": [[1], [0]],
    "qdot_A": [-1, 0], "law": {"type": "newton", "e": 0.5}}'
refuse "an entry given twice" "M.triplets[1]" "the entry (0, 0) is also triplets[0]" \
  '{"M": {"rows": 2, "cols": 2, "triplets": [[0, 0, 1], [0, 0, 1], [1, 1, 1]]}, "W_N": [[1], [0]],
    "qdot_A": [-1, 0], "law": {"type": "newton", "e": 0.5}}'
refuse "an unknown key of a sparse matrix" "W_N.values" "unknown key" \
  '{"M": [[1, 0], [0, 1]], "W_N": {"rows": 2, "cols": 1, "values": []},
    "qdot_A": [-1, 0], "law": {"type": "newton", "e": 0.5}}'
refuse "a sparse M that is not positive definite" "M" "positive definite" \
  '{"M": {"rows": 2, "cols": 2, "triplets": [[0, 0, 1], [1, 1, -1]]}, "W_N": [[1], [0]],
    "qdot_A": [-1, 0], "law": {"type": "newton", "e": 0.5}}'

finish
