#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ in the sanitized tree of scripts/sanitize.sh (clang++,
# ASan + UBSan, build-sanitize/), replays every saved regression input, then fuzzes each target.
#
#   bash scripts/fuzz.sh                          # every target, seeded (what CI runs, 10-90 s each)
#   bash scripts/fuzz.sh solver_fuzz              # one target
#   FREMOND_FUZZ_SEED=0 FREMOND_FUZZ_SECONDS=600 bash scripts/fuzz.sh   # exploration (check-long)
#
# Two modes. Seeded (the default, FREMOND_FUZZ_SEED=1 or any other fixed seed): one process per
# target, a fixed seed, a fixed number of inputs (FREMOND_FUZZ_RUNS, else 10-90 s' worth per
# target on a 2-core machine) from a fresh copy of the seed corpus, stopped after
# 1.5 x FREMOND_FUZZ_SECONDS (90 s) where inputs come slower (an input under way still finishes).
# libFuzzer's comparison feedback also records heap addresses, which differ between runs, so two
# runs drift apart after a few thousand inputs: a run can draw the slow inputs below (solver_fuzz
# drew a 38 s and a 43 s one in 1,481, 248 s in all), which the time limit keeps CI's share within
# its minutes.
# Exploration (FREMOND_FUZZ_SEED=0): a random seed, fork mode, for FREMOND_FUZZ_SECONDS (60) each,
# from the corpus grown in the build tree by earlier runs: this is how new bugs are found; each one
# becomes a regression input (below) and a unit test, replayed first on every run.
#
# A crash, a sanitizer report, a broken invariant (fuzz/*.cpp say which) or an input slower than
# FREMOND_FUZZ_TIMEOUT seconds (120) fails the run, unless it is a known library issue
# (tests/stress/known_issues.txt: broken invariants by their sentence, timeouts by the input's law
# family). libFuzzer writes the input to <tree>/artifacts/<target>/; run the target on it with
# FREMOND_FUZZ_VERBOSE=1 (solver_fuzz) to see it as a problem file. Copy it into
# fuzz/regressions/<target>/ (and turn it into a unit test) once the bug is fixed: every file there
# is replayed first on every run. The seed corpus in fuzz/corpus/ is copied to <tree>/corpus/
# and grows there, not in the tree.
set -uo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
build=${FREMOND_SANITIZE_BUILD_DIR:-build-sanitize}
seconds=${FREMOND_FUZZ_SECONDS:-60}
seed=${FREMOND_FUZZ_SEED:-1}
# An input's time limit under ASan + UBSan (5-10x slower than Release): a hang detector, not a
# speed test. Every solver is bounded by its iteration budgets; the slowest inputs seen take 30-50 s
# here (three repeated touching contacts with a sum of powers, where the proximal splitting needs
# 117,000 sweeps; Frémond + Coulomb on four contacts of one dof, which seed 1 draws, by every
# method), 0.2-3 s in Release.
timeout=${FREMOND_FUZZ_TIMEOUT:-120}
jobs=$(nproc)
[ "$jobs" -gt 2 ] && jobs=2

summary() {
  echo "fuzz: $1 ($(($(date +%s) - start)) s)"
}

targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(problem_file_fuzz solver_fuzz scene_file_fuzz siconos_file_fuzz)
if ! bash scripts/sanitize.sh --build-only; then
  summary "FAILED (the sanitized tree did not build)"
  exit 1
fi

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:allocator_may_return_null=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Known library issues (reported, with disabled regression tests) do not stop the fuzzing.
export FREMOND_KNOWN_ISSUES="$PWD/tests/stress/known_issues.txt"

# known_hang LAW: true when the known issues list a hang of that law family.
known_hang() {
  grep -Eq "^[[:space:]]*(\*|$1)[[:space:]]*\|[[:space:]]*\^?HANG" "$FREMOND_KNOWN_ISSUES"
}

failed=()
report=()
for t in "${targets[@]}"; do
  bin="$build/fuzz/$t"
  dict=""
  case "$t" in
    problem_file_fuzz) dict="-dict=fuzz/problem_file.dict" ;;
    scene_file_fuzz) dict="-dict=fuzz/scene_file.dict" ;;
  esac
  artifacts="$build/artifacts/$t"
  rm -rf "$artifacts"
  mkdir -p "$artifacts"
  # 1. Every saved regression input must pass (a fixed bug stays fixed).
  if [ -d "fuzz/regressions/$t" ] && [ -n "$(ls -A "fuzz/regressions/$t")" ]; then
    echo "== $t: replaying fuzz/regressions/$t"
    if ! "$bin" -timeout="$timeout" -rss_limit_mb=2048 fuzz/regressions/"$t"/* \
        >"$artifacts/regressions.log" 2>&1; then
      tail -n 60 "$artifacts/regressions.log"
      failed+=("$t (regression input)")
      report+=("$t: a saved regression input fails again")
      continue
    fi
  fi
  log="$artifacts/fuzz.log"
  if [ "$seed" != 0 ]; then
    # 2a. Seeded: fixed seed and input count, fresh seed corpus, one process (fork mode bounds its
    # jobs by time, which makes the runs differ far more). The time limit bounds a run that drew
    # slow inputs.
    runs=${FREMOND_FUZZ_RUNS:-}
    if [ -z "$runs" ]; then
      case "$t" in
        solver_fuzz) runs=1500 ;;        # the solvers with every method and solve_impact_all: ~30 inputs/s
        scene_file_fuzz) runs=500000 ;;  # ~15,000 inputs/s
        siconos_file_fuzz) runs=100000 ;;  # the Siconos reader and the sparse solve
        *) runs=200000 ;;                # the problem-file reader: ~6,000 inputs/s
      esac
    fi
    corpus="$build/corpus-seed$seed/$t"
    rm -rf "$corpus"
    mkdir -p "$corpus"
    cp fuzz/corpus/"$t"/* "$corpus"/ 2>/dev/null
    echo "== $t: $runs inputs from seed $seed"
    # shellcheck disable=SC2086
    "$bin" "$corpus" $dict -seed="$seed" -runs="$runs" -max_total_time=$((3 * seconds / 2)) \
      -timeout="$timeout" -rss_limit_mb=2048 -max_len=4096 -print_final_stats=1 \
      -artifact_prefix="$artifacts/" >"$log" 2>&1
    rc=$?
  else
    # 2b. Exploration from the seeds and whatever earlier runs in this tree added, in fork mode: an
    # input slower than the timeout is kept and the fuzzing goes on; a crash or a broken invariant
    # stops it.
    corpus="$build/corpus/$t"
    mkdir -p "$corpus"
    cp -n fuzz/corpus/"$t"/* "$corpus"/ 2>/dev/null
    echo "== $t: fuzzing for $seconds s from a random seed"
    # shellcheck disable=SC2086
    "$bin" "$corpus" $dict -fork=1 -ignore_timeouts=1 -ignore_crashes=0 -ignore_ooms=0 \
      -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=2048 -max_len=4096 \
      -print_final_stats=1 -artifact_prefix="$artifacts/" >"$log" 2>&1
    rc=$?
  fi
  cov=$(grep -Eo 'cov: [0-9]+' "$log" | tail -n 1 | grep -Eo '[0-9]+')
  runs=$(grep -Eo '^#[0-9]+' "$log" | tail -n 1 | tr -d '#')
  # Inputs that timed out: a known hang of their law family, or a failure.
  timeouts=0
  unknown_timeouts=()
  for f in "$artifacts"/timeout-*; do
    [ -e "$f" ] || continue
    timeouts=$((timeouts + 1))
    family=$(FREMOND_FUZZ_CLASSIFY=1 "$bin" "$f" 2>/dev/null | grep -Eo 'law_family: [a-z_]+' | cut -d' ' -f2)
    if [ -z "$family" ] || ! known_hang "$family"; then unknown_timeouts+=("$f (${family:-no law})"); fi
  done
  crashes=$(find "$artifacts" -name 'crash-*' -o -name 'oom-*' -o -name 'leak-*' | wc -l)
  if [ "$rc" -ne 0 ] || [ "$crashes" -ne 0 ] || [ ${#unknown_timeouts[@]} -ne 0 ]; then
    grep -E 'INVARIANT BROKEN|ERROR: |runtime error|SUMMARY' "$log" | head -n 20
    tail -n 40 "$log"
    for f in "${unknown_timeouts[@]}"; do echo "timeout, not a known hang: $f"; done
    failed+=("$t")
    report+=("$t: FAILED after ${runs:-?} runs (exit $rc, $crashes crash input(s), ${#unknown_timeouts[@]} unknown timeout(s)); inputs in $artifacts/")
  else
    note=""
    [ "$timeouts" -ne 0 ] && note=", $timeouts input(s) hit the known hang (tests/stress/known_issues.txt)"
    report+=("$t: ${runs:-?} runs, coverage ${cov:-?}, corpus $(ls "$corpus" | wc -l) inputs, no failure$note")
  fi
done

for line in "${report[@]}"; do echo "  $line"; done
if [ ${#failed[@]} -ne 0 ]; then
  summary "FAILED: ${failed[*]}"
  exit 1
fi
if [ "$seed" != 0 ]; then
  summary "PASSED: ${#targets[@]} target(s) from seed $seed, no crash, no broken invariant"
else
  summary "PASSED: ${#targets[@]} target(s), ${seconds} s each, no crash, no broken invariant"
fi
