#!/usr/bin/env bash
# The tests again, built with clang++ under AddressSanitizer and UndefinedBehaviorSanitizer, in the
# tree build-sanitize/. The same tree holds the libFuzzer targets (scripts/fuzz.sh): one library
# build serves both. Any report of either sanitizer fails the test that triggered it
# (halt_on_error, -fno-sanitize-recover), so ctest's summary is the verdict.
#
#   bash scripts/sanitize.sh               # CI's share: the solvers' and readers' tests
#   bash scripts/sanitize.sh --full        # every test of the tree (scripts/check-long.sh)
#   bash scripts/sanitize.sh --build-only  # configure and build the tree, run nothing
#
# -O1 -g1: fast enough to run, slow enough to keep frames. No benchmarks, no Python module; the
# packaging tests install the tree and build a plain consumer, so they check nothing here.
set -uo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/build-env.sh
mode=${1:-ci}
build=${FREMOND_SANITIZE_BUILD_DIR:-build-sanitize}
jobs=$(nproc)
[ "$jobs" -gt 2 ] && jobs=2

if ! command -v clang++ >/dev/null; then
  echo "sanitize: clang++ not found (scripts/install-deps.sh installs clang)" >&2
  exit 1
fi
stage sanitize-configure cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  "${FREMOND_CMAKE_LAUNCHER[@]}" -DFREMOND_SANITIZE=ON -DFREMOND_BUILD_FUZZERS=ON \
  -DFREMOND_BUILD_BENCHMARKS=OFF -DFREMOND_BUILD_PYTHON=OFF >/dev/null || exit 1
stage sanitize-build cmake --build "$build" -j"$jobs" || exit 1
[ "$mode" = --build-only ] && exit 0

# detect_leaks: LeakSanitizer too. abort_on_error gives a non-zero status ctest sees as a failure.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:check_initialization_order=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# The stress smoke at a tenth of its count (Frémond + Coulomb: 100 problems, about 90 s here). The
# deadline per case is a hang detector: ASan -O1 runs the solvers 50x slower (a 4-contact Frémond +
# Coulomb enumeration: 0.2 s -> 11 s).
export FREMOND_STRESS_SCALE=${FREMOND_STRESS_SCALE:-0.1}
export FREMOND_STRESS_HANG=${FREMOND_STRESS_HANG:-120}
exclude='^(packaging\.|format$)'
if [ "$mode" != --full ]; then
  # CI's share leaves out the tests of the test suite's own reference (ReferenceSelfTest: no
  # library code), the simulation's long runs, Siconos's large problems and the many random
  # problems of Stronge's integrator (its paths are the one-contact tests'); each of those takes
  # one to two minutes here. check-long.sh runs them too.
  exclude='^(packaging\.|format$|ReferenceSelfTest\.|SimulationSweep\.|SiconosLarge\.|cli\.simulate_long_runs$|StrongeLzb\.RandomCoupledProblemsDissipate$)'
fi
stage sanitize-ctest ctest --test-dir "$build" --output-on-failure -j"$jobs" -E "$exclude"
