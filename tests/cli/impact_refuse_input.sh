# `fremond impact` refuses input that is not a JSON object, and files it cannot read (docs/problem-file.md):
# exit status 1, nothing on stdout, a message naming the key (or the file) and the reason.
source "$(dirname "$0")/impact_common.bash" "$1"

refuse "bad JSON: trailing comma in a list" "W_N[0][1]" "not valid JSON" \
  '{"M": [[1]], "W_N": [[1, ]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5}}'
refuse "bad JSON: two commas between keys" "problem" "not valid JSON" \
  '{"M": [[1]],, "W_N": [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5}}'
refuse "bad JSON: missing colon" "W_N" "not valid JSON" \
  '{"M": [[1]], "W_N" [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5}}'
refuse "bad JSON: unterminated object" "problem" 'unexpected end of input; expected '"'}'"' (after the value of "law")' \
  '{"M": [[1]], "W_N": [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5}'
refuse "bad JSON: text after the object" "problem" "not valid JSON" \
  '{"M": [[1]], "W_N": [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5}} {}'
refuse "bad JSON: NaN is not JSON" "M[0][0]" "not valid JSON" \
  '{"M": [[NaN]], "W_N": [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5}}'
refuse "bad JSON: Infinity is not JSON" "law.e" "not valid JSON" \
  '{"M": [[1]], "W_N": [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": Infinity}}'
refuse "bad JSON: comments are not JSON" "problem" "not valid JSON" \
  '// a comment
  {"M": [[1]], "W_N": [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5}}'
refuse "duplicate key at the top level" "M" "duplicate key" \
  '{"M": [[1]], "M": [[2]], "W_N": [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5}}'
refuse "duplicate key in the law" "law.e" "duplicate key" \
  '{"M": [[1]], "W_N": [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5, "e": 0.9}}'

refuse "not an object: a list" "problem" "must be a JSON object, got a list" '[1, 2]'
refuse "not an object: a number" "problem" "must be a JSON object, got the number 3" '3'
refuse "not an object: a string" "problem" "must be a JSON object, got a string" '"M"'
refuse "not an object: null" "problem" "must be a JSON object, got null" 'null'

expect_refusal "empty input (no bytes)" "problem" "empty input" - </dev/null
refuse "empty input (blank lines)" "problem" "empty input" '

'
expect_refusal "missing file" "$TMP/no-such-problem.json" "cannot open" "$TMP/no-such-problem.json"
expect_refusal "a directory" "$TMP" "is a directory" "$TMP"
: >"$TMP/empty.json"
expect_refusal "empty file" "problem" "empty input" "$TMP/empty.json"

finish
