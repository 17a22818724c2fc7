# `fremond curve` refuses bad values: exit status 1, nothing on stdout, a message naming the option.
source "$(dirname "$0")/curve_common.bash" "$1"

expect_refusal "p = 1" "--p" "must be > 1, got 1" normal --p 2,1
expect_refusal "negative k" "--k" "must be >= 0, got -1" normal --k -1
expect_refusal "zero mass" "--mass" "must be > 0, got 0" normal --mass 0
expect_refusal "NaN mass" "--mass" "must be a finite number" tangential --mass nan
expect_refusal "unknown scaling" "--scaling" "unknown value 'metric' (one of: library, paper)" \
  normal --scaling metric
expect_refusal "one point" "--points" "must lie in [2, 1000000], got 1" normal --points 1
expect_refusal "zero max speed" "--max-speed" "must be a finite number > 0, got 0" \
  tangential --max-speed 0
expect_refusal "infinite max speed" "--max-speed" "must be a finite number > 0, got inf" \
  normal --max-speed inf
expect_refusal "separating D_NA" "--dna" "must be <= 0" tangential --dna 0.5
expect_refusal "negative r" "--r" "must be >= 0, got -0.1" tangential --r -0.1
expect_refusal "q = 0.5" "--q" "must be > 1, got 0.5" tangential --q 0.5
expect_refusal "negative k_T" "--kt" "must be >= 0, got -2" tangential --kt -2
expect_refusal "normal p of Fig. 9" "--p" "must be > 1, got 1" tangential --p 1
expect_refusal "unwritable --out" "--out" "cannot write '$TMP/no/such/dir/x.csv'" \
  normal --out "$TMP/no/such/dir/x.csv"

# Errors of the command line itself (CLI11): a usage error, never a curve on stdout.
for args in "normal --k abc" "normal --frobnicate" "" "sideways"; do
  # shellcheck disable=SC2086
  run_curve $args
  if [ "$RC" -eq 0 ] || [ "$RC" -ge 128 ]; then
    fail "'curve $args': exit status $RC, expected a usage error"
  elif grep -q '^D_\|^p,' "$TMP/out"; then
    fail "'curve $args': printed a curve"
  else
    pass
  fi
done

finish
