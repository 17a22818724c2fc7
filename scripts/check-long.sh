#!/usr/bin/env bash
# The long checks, run by hand after any change to a solver or a reader (about 1.5 hours on 2
# cores); CI runs a share of each (scripts/test.sh, scripts/sanitize.sh, scripts/fuzz.sh).
#
#   bash scripts/check-long.sh                  # everything below
#   FREMOND_LONG_STRESS_COUNT=20000 FREMOND_FUZZ_SECONDS=120 bash scripts/check-long.sh   # shorter
#
# 1. Every test of the suite under ASan + UBSan (scripts/sanitize.sh --full), the stress smoke at
#    its full count.
# 2. Stress: FREMOND_LONG_STRESS_COUNT (100,000) random problems per law from a random seed
#    (FREMOND_LONG_STRESS_SEED to repeat one), in the Release tree, two laws at a time.
# 3. Each fuzz target for FREMOND_FUZZ_SECONDS (600) from a random seed, its corpus growing in
#    build-sanitize/corpus/ from one run to the next.
# Prints each stage's time and verdict, and exits non-zero if any failed.
set -uo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/build-env.sh
count=${FREMOND_LONG_STRESS_COUNT:-100000}
seed=${FREMOND_LONG_STRESS_SEED:-$((RANDOM * 32768 + RANDOM + 1))}
failed=()

stage release-build bash -c 'bash scripts/install-deps.sh &&
  source scripts/lib/build-env.sh &&
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${FREMOND_CMAKE_LAUNCHER[@]}" >/dev/null &&
  cmake --build build -j"$(nproc)" >/dev/null' || { echo "the Release tree did not build"; exit 1; }

FREMOND_STRESS_SCALE=1 stage sanitize-full bash scripts/sanitize.sh --full || failed+=(sanitize)

mkdir -p build/long-stress
stress_law() {
  build/tests/stress/fremond_stress --law "$1" --count "$count" --seed "$seed" --hang 60 --show 3 \
    --known tests/stress/known_issues.txt >"build/long-stress/$1.log" 2>&1
  local rc=$?
  echo "  stress $1 (seed $seed, $count problems): $([ $rc -eq 0 ] && echo ok || echo FAILED) -" \
    "build/long-stress/$1.log"
  return $rc
}
export -f stress_law
export count seed
stage stress bash -c 'printf "%s\n" newton poisson newton_coulomb poisson_coulomb fremond \
  fremond_viscous fremond_coulomb | xargs -P 2 -I{} bash -c "stress_law {}"' || failed+=(stress)

FREMOND_FUZZ_SEED=0 FREMOND_FUZZ_SECONDS=${FREMOND_FUZZ_SECONDS:-600} stage fuzz \
  bash scripts/fuzz.sh || failed+=(fuzz)

if [ ${#failed[@]} -ne 0 ]; then
  echo "check-long: FAILED: ${failed[*]}"
  exit 1
fi
echo "check-long: PASSED (stress seed $seed)"
