#!/usr/bin/env bash
# The performance report (issue 6) in one command: builds the benchmarks (Release, in their own
# build directory), runs every benchmark and the work-precision sweeps, and writes into out/perf/:
#   *_bench.json                 Google Benchmark's output of each benchmark program
#   benchmarks.csv               every benchmark run, flattened
#   siconos_compare.txt          bench/compare.py: Siconos's time over ours, pair by pair
#   siconos_ratios.csv           the same pairs with each answer's error
#   work_precision.csv           per method, case and tolerance: ns per solve, error vs the quad reference
#   simulation_work_precision.csv  Moreau-Jean against the step, vs the event-driven run (and Siconos)
#   *.png, report.md             the plots and the Markdown report, with the machine (machine.txt)
#
# Usage: bash scripts/perf-report.sh [--quick] [--docs] [--out DIR] [--build DIR] [--jobs N]
#   --quick   short timings and a reduced sweep (minutes less; figures not for publication)
#   --docs    also rewrite docs/performance.md from the report (plots copied to docs/perf/)
# Run it on a quiet machine: every figure is a time, and the report records the load average
# before and after.
set -euo pipefail
cd "$(dirname "$0")/.."

out=out/perf
build=build-perf
jobs=2
quick=0
docs=0
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --docs) docs=1 ;;
    --out) out="$2"; shift ;;
    --build) build="$2"; shift ;;
    --jobs) jobs="$2"; shift ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    *) echo "perf-report.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done

mkdir -p "$out"
rm -f "$out"/*_bench.json

echo "== build ($build, Release)"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DFREMOND_BUILD_BENCHMARKS=ON >/dev/null
# small_problems_bench: fremond_bench, classical_bench and siconos_numerics_bench in one program,
# so that ours and Siconos's small problems are timed interleaved, in the same process.
benches=(small_problems_bench batch_bench simulation_bench siconos_moreau_jean_bench scaling_bench
         sparse_bench scene_bench)
cmake --build "$build" -j"$jobs" --target "${benches[@]}" work_precision

load() { cut -d' ' -f1-3 /proc/loadavg; }
{
  echo "date:      $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "cpu:       $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
  echo "cores:     $(nproc) (nproc)"
  echo "kernel:    $(uname -srm)"
  echo "compiler:  $(${CXX:-c++} --version | head -n1)"
  echo "commit:    $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet 2>/dev/null || echo ' (with local changes)')"
  echo "mode:      $([ $quick = 1 ] && echo 'quick (short timings: not for publication)' || echo 'full')"
  echo "timing:    $([ $quick = 1 ] && echo 'one run of each benchmark, at least 0.01 s' || echo 'the median of 9 repetitions of at least 0.1 s, in random order within each program')"
  echo "load avg:  $(load) before the runs"
} > "$out/machine.txt"

if [ $quick = 1 ]; then
  gb=(--benchmark_min_time=0.01)
  wp=(--quick)
else
  # The median of 9 repetitions of at least 0.1 s each, run in random order among the program's
  # other benchmarks: a slow stretch of the machine then falls on ours and on the Siconos peers
  # of the same program alike, instead of on whichever ran during it.
  gb=(--benchmark_min_time=0.1 --benchmark_repetitions=9 --benchmark_enable_random_interleaving=true
      --benchmark_report_aggregates_only=true)
  wp=()
fi

for b in "${benches[@]}"; do
  echo "== $b"
  "$build/bench/$b" "${gb[@]}" --benchmark_out="$out/$b.json" --benchmark_out_format=json \
    > "$out/$b.txt"
done
echo "== work_precision"
"$build/bench/work_precision" --out "$out" "${wp[@]}" 2> "$out/work_precision.log"
echo "load avg:  $(load) after the runs" >> "$out/machine.txt"

echo "== report"
/usr/bin/python3 bench/compare.py "$out"/*_bench.json > "$out/siconos_compare.txt" || true
/usr/bin/python3 tests/perf/check_report.py "$out"
if [ $docs = 1 ]; then
  /usr/bin/python3 bench/plot_report.py "$out" --docs docs/performance.md
else
  /usr/bin/python3 bench/plot_report.py "$out"
fi
echo "done: $out/report.md"
