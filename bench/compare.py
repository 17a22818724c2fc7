#!/usr/bin/python3
"""Siconos / fremond time ratios from Google Benchmark's JSON output.

Run the benchmarks with JSON output, then this script on every file, e.g. the small problems'
program, which holds ours and Siconos's peers (timed interleaved, as scripts/perf-report.sh runs it):

    build/bench/small_problems_bench --benchmark_enable_random_interleaving=true \
        --benchmark_repetitions=9 --benchmark_out=small.json --benchmark_out_format=json
    /usr/bin/python3 bench/compare.py small.json

or any programs run apart (siconos_numerics_bench, classical_bench: their ratios then also hold
the machine's change of pace between the two runs).

Benchmarks are paired by the "problem=... law=..." words of their label (bench_label() in
bench/problems.hpp; further words, e.g. "stage=solve_impact", only describe the benchmark): every
benchmark whose name starts with BM_Siconos_ is compared with every other benchmark of the same
problem and law at the same depth (depth()): Siconos's driver alone on its assembled problem
("stage=driver") with our kernel, which also starts from G, and every other Siconos run, timed from
the data, with every other run of ours. The ratio is Siconos's CPU time over ours (> 1: we are
faster). Where both report a
`us_per_step` counter (time stepping), that is compared instead of the time of a whole run. Uses the
standard library only.
"""
import argparse
import json
import sys
from collections import defaultdict

UNIT_NS = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}


def load(paths):
    """Every benchmark run (not aggregates other than the mean) from the given JSON files."""
    runs = []
    for path in paths:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
        for b in data.get("benchmarks", []):
            if b.get("error_occurred"):
                continue
            if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "mean":
                continue
            runs.append(b)
    return runs


def key(label):
    """The pairing key: the label's "problem=..." and "law=..." words (others, e.g. "stage=...",
    only describe the benchmark)."""
    words = [w for w in label.split() if w.startswith(("problem=", "law="))]
    return " ".join(words) if words and words[0].startswith("problem=") else ""


def depth(b):
    """Where the timed work starts: "G" (Siconos's driver on its own assembled problem, our law's
    kernel on the contact-space data) or "data" (from M, W and q̇_A). Only runs of one depth are
    compared: a kernel against Siconos from the data would credit us with its assembly."""
    if b["name"].startswith("BM_Siconos_"):
        return "G" if "stage=driver" in b.get("label", "").split() else "data"
    return "G" if "Kernel" in b["name"] else "data"


def name_of(b):
    """The benchmark's name, with the words of its label that are not part of the key."""
    extra = [w for w in b.get("label", "").split() if not w.startswith(("problem=", "law="))]
    return " ".join([b["name"]] + extra)


def cost(b):
    """(value, unit) used for the comparison: µs per step if given, else CPU ns per iteration."""
    if "us_per_step" in b:
        return float(b["us_per_step"]), "us/step"
    return float(b["cpu_time"]) * UNIT_NS[b.get("time_unit", "ns")], "ns"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("json", nargs="+", help="Google Benchmark JSON output files")
    args = parser.parse_args(argv)

    by_label = defaultdict(lambda: ([], []))
    for b in load(args.json):
        label = key(b.get("label", ""))
        if not label:
            continue
        siconos = b["name"].startswith("BM_Siconos_")
        by_label[label][0 if siconos else 1].append(b)

    rows = []
    for label in sorted(by_label):
        theirs, ours = by_label[label]
        for s in theirs:
            for o in ours:
                (sv, su), (ov, ou) = cost(s), cost(o)
                if su != ou or ov <= 0 or depth(s) != depth(o):
                    continue
                rows.append((label, name_of(s), sv, name_of(o), ov, su, sv / ov))
    if not rows:
        print("no pairs: no Siconos benchmark shares a label with one of ours "
              "(was the benchmark built with Siconos? see the CMake message)")
        return 1
    w1 = max(len(r[1]) for r in rows)
    w3 = max(len(r[3]) for r in rows)
    print(f"{'Siconos':<{w1}}  {'time':>12}  {'fremond':<{w3}}  {'time':>12}  ratio")
    current = None
    for label, sn, sv, on, ov, unit, ratio in rows:
        if label != current:
            print(f"# {label}")
            current = label
        print(f"{sn:<{w1}}  {sv:>9.4g} {unit:<3}  {on:<{w3}}  {ov:>9.4g} {unit:<3}  {ratio:6.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
