#!/usr/bin/python3
"""Checks that the performance report's data files are well-formed (scripts/perf-report.sh runs it
before plotting): every *_bench.json is Google Benchmark JSON with at least one run; each CSV has
its header and, on every row, the right number of cells, numbers where numbers belong and known
statuses. Exits non-zero naming the file, the line and the cell.

    /usr/bin/python3 tests/perf/check_report.py out/perf
"""
import csv
import json
import math
import os
import sys

WORK_PRECISION = ["method", "problem", "law", "hard", "tolerance", "budget", "ns_per_solve",
                  "rel_error", "residual", "status", "answered_by", "iterations", "budget_hit",
                  "problems", "cond_G"]
SIMULATION = ["code", "law", "step", "steps", "impacts", "cpu_seconds", "ns_per_step",
              "ns_per_simulated_second", "energy_error", "energy_final_error", "trajectory_error",
              "early_trajectory_error", "final_state_error", "status"]
METHODS = {"automatic", "closed_form", "scalar_newton", "mode_enumeration", "semismooth_newton",
           "proximal", "nlopt"}
STATUSES = {"converged", "max_iterations", "stalled", "no_solution", "failed"}
SIM_STATUSES = {"completed", "max_impacts", "impact_failed", "contact_failed",
                "event_search_failed"}


def fail(msg):
    print(f"check_report: {msg}", file=sys.stderr)
    sys.exit(1)


def number(path, line, name, text, positive=False, nan_ok=False, inf_ok=False):
    try:
        v = float(text)
    except ValueError:
        fail(f"{path}:{line}: {name} = {text!r} is not a number")
    if math.isnan(v) and not nan_ok:
        fail(f"{path}:{line}: {name} is NaN")
    if math.isinf(v) and not inf_ok:
        fail(f"{path}:{line}: {name} is infinite")
    if positive and not (v > 0):
        fail(f"{path}:{line}: {name} = {v} is not positive")
    if not math.isnan(v) and v < 0:
        fail(f"{path}:{line}: {name} = {v} is negative")
    return v


def rows(path, header):
    with open(path, encoding="utf-8", newline="") as f:
        r = csv.reader(f)
        got = next(r, None)
        if got != header:
            fail(f"{path}: header {got} is not {header}")
        out = []
        for i, row in enumerate(r, start=2):
            if len(row) != len(header):
                fail(f"{path}:{i}: {len(row)} cells, expected {len(header)}")
            out.append((i, dict(zip(header, row))))
    if not out:
        fail(f"{path}: no rows")
    return out


def main(outdir):
    jsons = [n for n in os.listdir(outdir) if n.endswith("_bench.json")]
    if not jsons:
        fail(f"{outdir}: no *_bench.json")
    for n in jsons:
        with open(os.path.join(outdir, n), encoding="utf-8") as f:
            data = json.load(f)
        if not data.get("benchmarks"):
            fail(f"{n}: no benchmark runs")
    p = os.path.join(outdir, "work_precision.csv")
    for i, r in rows(p, WORK_PRECISION):
        if r["method"] not in METHODS:
            fail(f"{p}:{i}: unknown method {r['method']!r}")
        if r["status"] not in STATUSES:
            fail(f"{p}:{i}: unknown status {r['status']!r}")
        if r["hard"] not in ("0", "1") or r["budget_hit"] not in ("0", "1"):
            fail(f"{p}:{i}: hard/budget_hit not 0 or 1")
        number(p, i, "tolerance", r["tolerance"], positive=True)
        number(p, i, "budget", r["budget"])
        number(p, i, "ns_per_solve", r["ns_per_solve"], positive=True)
        number(p, i, "rel_error", r["rel_error"], nan_ok=True)
        number(p, i, "residual", r["residual"], inf_ok=True)
        number(p, i, "iterations", r["iterations"])
        number(p, i, "problems", r["problems"], positive=True)
        number(p, i, "cond_G", r["cond_G"], positive=True)
    p = os.path.join(outdir, "simulation_work_precision.csv")
    for i, r in rows(p, SIMULATION):
        if r["status"] not in SIM_STATUSES:
            fail(f"{p}:{i}: unknown status {r['status']!r}")
        number(p, i, "step", r["step"])
        number(p, i, "ns_per_simulated_second", r["ns_per_simulated_second"], positive=True)
        for k in ("ns_per_step", "energy_error", "energy_final_error", "trajectory_error",
                  "early_trajectory_error", "final_state_error"):
            number(p, i, k, r[k], nan_ok=True)
    print(f"check_report: {outdir} is well-formed ({len(jsons)} benchmark files, 2 CSVs)")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/perf")
