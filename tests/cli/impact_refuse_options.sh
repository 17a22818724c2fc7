# `fremond impact` refuses bad options before reading anything: non-zero exit, nothing on stdout,
# a message naming the option.
source "$(dirname "$0")/impact_common.bash" "$1"

expect_refusal "unknown --method" "--method" "unknown value 'fastest'" \
  --method fastest "$DATA/fremond_point.json"
expect_refusal "--tolerance too large" "--tolerance" "must lie in [1e-16, 1e-2], got 1" \
  --tolerance 1 "$DATA/fremond_point.json"
expect_refusal "--tolerance zero" "--tolerance" "must lie in [1e-16, 1e-2], got 0" \
  --tolerance 0 "$DATA/fremond_point.json"
# Every tolerance of the range is taken, the loose ones too (NLopt's own threshold follows it).
for tol in 1e-2 1e-8; do
  run_impact --tolerance "$tol" --method nlopt "$DATA/fremond_point.json"
  expect_status "--tolerance $tol accepted" 0
  check_json "--tolerance $tol: NLopt's answer within it" "
assert d['solver']['status'] == 'converged', d['solver']
assert d['solver']['residual'] <= $tol, d['solver']
"
done
# A bad option is refused even when the input would be refused too: the options come first.
expect_refusal "--method before bad input" "--method" "unknown value" --method x - <<<'[1]'

# Errors of the command line itself (CLI11's messages and exit codes): never a result on stdout.
cli_error() {
  local name=$1 mention=$2
  shift 2
  run_impact "$@"
  if [ "$RC" -eq 0 ] || [ "$RC" -ge 128 ]; then
    fail "$name: exit status $RC, expected a usage error"
  elif [ -s "$TMP/out" ]; then
    fail "$name: printed on stdout: $(head -c 200 "$TMP/out")"
  elif ! grep -qF -- "$mention" "$TMP/err"; then
    fail "$name: the message does not mention '$mention': $(cat "$TMP/err")"
  else
    pass
  fi
}
cli_error "--tolerance not a number" "--tolerance" --tolerance abc "$DATA/fremond_point.json"
cli_error "no FILE" "FILE" </dev/null
cli_error "two files" "not expected" "$DATA/fremond_point.json" "$DATA/fremond_point.json"
cli_error "unknown option" "--frobnicate" --frobnicate "$DATA/fremond_point.json"

finish
