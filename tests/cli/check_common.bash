# Shared by every script of tests/cli (directly, or through curve_common.bash and
# impact_common.bash); not a test itself (ctest runs *.sh only).
#
#   source "$(dirname "$0")/check_common.bash" "$1"   # $1: the fremond binary
#   ...checks, each calling pass or fail...
#   finish
#
# Sets FREMOND, PY (Debian's Python), HERE (this folder), SCENES (the scene files) and TMP (removed
# on exit). Every check counts; `finish` exits non-zero when one failed, after all have run.
set -u
FREMOND=${1:?usage: bash script.sh path/to/fremond}
PY=/usr/bin/python3
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
SCENES="$HERE/../data/scenes"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
failures=0
checks=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
pass() { checks=$((checks + 1)); }

finish() {
  if [ "$failures" -ne 0 ]; then
    echo "$failures check(s) failed, $checks passed" >&2
    exit 1
  fi
  echo "all $checks checks passed"
  exit 0
}
