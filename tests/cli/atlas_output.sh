# `fremond atlas` writes what it says: the summary on stdout, progress on stderr for long sweeps
# (a line every tenth when stderr is no terminal) and none with --no-progress, files complete.
source "$(dirname "$0")/check_common.bash" "$1"

# exit_status NAME: the last run exited with 0.
exit_status() { [ "$RC" -eq 0 ] && pass || fail "$1: exit status $RC; stderr: $(cat "$TMP/err")"; }

"$FREMOND" atlas --laws newton_coulomb,fremond --grid 320x160 --npz "$TMP/a.npz" \
  >"$TMP/out" 2>"$TMP/err"
RC=$?
exit_status "long sweep"
if grep -qF "fremond atlas: 102400 / 102400 points (100%)" "$TMP/err" &&
  [ "$(grep -c '^fremond atlas: .* points' "$TMP/err")" -eq 10 ]; then
  pass
else
  fail "progress: expected ten lines, got: $(cat "$TMP/err")"
fi
if grep -qF "wrote $TMP/a.npz: 2 laws x 1 mu x 1 spins x 320x160 configurations (102400 points)" \
  "$TMP/out" && grep -qF "newton_coulomb creates energy on 8." "$TMP/out" &&
  grep -qF "fremond creates energy on 0.00%" "$TMP/out"; then
  pass
else
  fail "summary: $(cat "$TMP/out")"
fi
[ -s "$TMP/a.npz" ] && ! ls -A "$TMP" | grep -q '^\.' && pass || fail "the NPZ is missing, or a temporary file is left"

"$FREMOND" atlas --laws newton_coulomb,fremond --grid 320x160 --csv "$TMP/b.csv" --no-progress \
  >"$TMP/out" 2>"$TMP/err"
RC=$?
exit_status "no progress"
[ -s "$TMP/err" ] && fail "--no-progress printed: $(cat "$TMP/err")" || pass
# One header row and one row per point.
[ "$(wc -l <"$TMP/b.csv")" -eq 102401 ] && pass || fail "CSV rows: $(wc -l <"$TMP/b.csv")"
head -1 "$TMP/b.csv" | grep -qx "law,mu,e,k_N,spin,theta,psi,D_NA,D_TA,T_A,energy_ratio,admissible,failed,solutions,mode,status,distance,P_N,P_T,D_NE,D_TE,xdot_E,ydot_E,thetadot_E" &&
  pass || fail "CSV header: $(head -1 "$TMP/b.csv")"

finish
