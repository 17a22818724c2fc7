#!/usr/bin/env bash
# The whole test suite again, built with AddressSanitizer and UndefinedBehaviorSanitizer
# (FREMOND_SANITIZE), in its own build tree `build-sanitize`. Any report of either sanitizer fails
# the test that triggered it (halt_on_error, -fno-sanitize-recover), so ctest's summary is the verdict.
#
#   bash scripts/sanitize.sh            # after scripts/test.sh (or alone: it installs nothing)
#
# Lean on purpose: -O1 (fast enough to run, slow enough to keep frames), no benchmarks, no Python
# module. The packaging test is left out: it installs and builds its own plain copy of the library
# (outside this tree's flags), so it checks nothing the normal stage does not. The stress tests run
# a tenth of their count here (FREMOND_STRESS_SCALE); the normal stage runs the full CI count.
set -uo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
build=${FREMOND_SANITIZE_BUILD_DIR:-build-sanitize}
jobs=$(nproc)
[ "$jobs" -gt 2 ] && jobs=2

summary() {
  echo "sanitize: $1 ($(($(date +%s) - start)) s)"
}

if ! cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
    -DFREMOND_SANITIZE=ON -DFREMOND_BUILD_BENCHMARKS=OFF -DFREMOND_BUILD_PYTHON=OFF >/dev/null; then
  summary "FAILED (configure)"
  exit 1
fi
if ! cmake --build "$build" -j"$jobs"; then
  summary "FAILED (build)"
  exit 1
fi

# detect_leaks: LeakSanitizer too. abort_on_error gives a non-zero status ctest sees as a failure.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:check_initialization_order=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# The stress tests: a tenth of their count, with a deadline per case that allows for the slowdown.
export FREMOND_STRESS_SCALE=${FREMOND_STRESS_SCALE:-0.1}
export FREMOND_STRESS_HANG=${FREMOND_STRESS_HANG:-30}
if ctest --test-dir "$build" --output-on-failure -j"$jobs" -E '^packaging\.'; then
  summary "PASSED: every test clean under ASan+UBSan"
  exit 0
fi
summary "FAILED: see the tests above"
exit 1
