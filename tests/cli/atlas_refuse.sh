# `fremond atlas` refuses bad values: exit status 1, nothing on stdout, no file written, and a
# message naming the flag and the reason.
source "$(dirname "$0")/check_common.bash" "$1"

run_atlas() {
  "$FREMOND" atlas "$@" >"$TMP/out" 2>"$TMP/err"
  RC=$?
}

# refused NAME FLAG REASON ARGS...: refused naming FLAG and saying REASON; neither file written
# (both asked for, and a 4x4 grid, unless ARGS say otherwise).
refused() {
  local name=$1 flag=$2 reason=$3
  shift 3
  rm -f "$TMP/a.csv" "$TMP/a.npz"
  local extra=(--csv "$TMP/a.csv")
  [[ " $* " == *" --npz "* ]] || extra+=(--npz "$TMP/a.npz")
  [[ " $* " == *" --grid "* ]] || extra+=(--grid 4)
  run_atlas "${extra[@]}" "$@"
  local ok=1
  [ "$RC" -eq 1 ] || { fail "$name: exit status $RC, expected 1; stderr: $(cat "$TMP/err")"; ok=0; }
  [ -s "$TMP/out" ] && { fail "$name: printed on stdout: $(head -c 200 "$TMP/out")"; ok=0; }
  grep -qF -- ": $flag: " "$TMP/err" || { fail "$name: does not name '$flag': $(cat "$TMP/err")"; ok=0; }
  grep -qF -- "$reason" "$TMP/err" || { fail "$name: does not say '$reason': $(cat "$TMP/err")"; ok=0; }
  if [ -e "$TMP/a.csv" ] || [ -e "$TMP/a.npz" ] || ls -A "$TMP" | grep -q '^\.a\.'; then
    fail "$name: a file was written"
    ok=0
  fi
  [ "$ok" -eq 1 ] && pass
}

refused "unknown law" "--laws" "unknown law 'lagrange' (one of: newton," --laws newton,lagrange
refused "law twice" "--laws" "'newton' is listed twice" --laws newton,newton
refused "reference not mapped" "--reference" "'poisson' is not one of the laws" \
  --laws newton --reference poisson
refused "negative mu" "--mu" "must be >= 0, got -0.5" --mu 1,-0.5
refused "e above 1" "--e" "must lie in [0, 1], got 1.5" --e 0.5,1.5
refused "e = 1 with Frémond calibrated" "--e" "must lie in (0, 1) to calibrate" --e 0.5,1
refused "both swept" "--e" "sweep μ or e, not both" --e 0.5,0.9 --mu 0.2,1
refused "p = 1" "--p" "must be > 1, got 1" --p 1
refused "negative k_N" "--k-n" "must be >= 0, got -3" --k-n -3
refused "bad grid" "--grid" "needs N or NxM" --grid 20xq
refused "zero grid" "--grid" "needs N or NxM" --grid 0
refused "psi above 0" "--psi" "must be <= 0" --psi -1,0.5
refused "psi below -pi" "--psi" "must be >= -pi" --psi -4,0
refused "theta empty range" "--theta" "must be > theta_min" --theta 1,1
refused "one theta" "--theta" "needs MIN,MAX" --theta 1
refused "NaN spin" "--spin" "must be a finite number" --spin 0,nan
refused "negative speed" "--speed" "must be >= 0" --speed -1
refused "no such contact" "--contact" "must lie in [0, 2), got 5" --contact 5
refused "negative threads" "--threads" "must be 0 (one per core)" --threads -2
refused "unknown preset" "--preset" "unknown preset 'cube'" --preset cube
refused "missing scene file" "$TMP/none.json" "" --scene "$TMP/none.json"
refused "no such folder" "--npz" "no such folder" --npz "$TMP/no/such/a.npz"

rm -f "$TMP/a.csv"
run_atlas --grid 4
if [ "$RC" -eq 1 ] && grep -qF -- ": --csv: give --csv FILE and/or --npz FILE" "$TMP/err"; then
  pass
else
  fail "no output file: exit status $RC, stderr: $(cat "$TMP/err")"
fi

# Errors of the command line itself (CLI11): a usage error, no file.
for args in "--grid" "--frobnicate" "--mu abc" "--preset ball --scene $SCENES/ball_newton.json"; do
  # shellcheck disable=SC2086
  run_atlas --csv "$TMP/u.csv" $args
  if [ "$RC" -eq 0 ] || [ "$RC" -ge 128 ] || [ -e "$TMP/u.csv" ]; then
    fail "'atlas $args': exit status $RC, expected a usage error and no file"
  else
    pass
  fi
done

finish
