#!/usr/bin/python3
"""The performance report's arithmetic and labels (bench/plot_report.py), on hand-made benchmark
runs: each median keeps its repetitions' spread, a ratio's standard error is √(π/2) cv/√n of each
median combined, a target within two of them says so, the control pairs identical work, and the
sparse table names whose solver each row is.

    /usr/bin/python3 tests/perf/test_plot_report.py
"""
import json
import math
import os
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
os.environ.setdefault("MPLBACKEND", "Agg")
import plot_report as pr  # noqa: E402


def near(a, b, rel=1e-12):
    assert abs(a - b) <= rel * max(abs(a), abs(b)), f"{a!r} != {b!r}"


def aggregates(name, median_ns, cv, reps=9, **extra):
    """Google Benchmark's aggregate rows of one benchmark (report_aggregates_only)."""
    rows = []
    for agg, value in (("mean", median_ns), ("median", median_ns), ("stddev", cv * median_ns),
                       ("cv", cv)):
        rows.append(dict(name=f"{name}_{agg}", run_name=name, run_type="aggregate",
                         aggregate_name=agg, repetitions=reps, cpu_time=value, real_time=value,
                         time_unit="ns", **extra))
    return rows


def test_median_keeps_its_coefficient_of_variation():
    with tempfile.TemporaryDirectory() as d:
        with open(os.path.join(d, "x_bench.json"), "w", encoding="utf-8") as f:
            json.dump({"context": {}, "benchmarks": aggregates("BM_A/1", 500.0, 0.3) +
                       [dict(name="BM_B/iterations:1/repeats:1", run_name="BM_B/iterations:1",
                             run_type="iteration", repetitions=1, cpu_time=7.0, real_time=7.0,
                             time_unit="ms")]}, f)
        runs, _ = pr.load_benchmarks(d)
    by = {b["name"]: b for b in runs}
    assert set(by) == {"BM_A/1", "BM_B/iterations:1/repeats:1"}, sorted(by)
    near(by["BM_A/1"]["cpu_time"], 500.0)  # the median stands for the benchmark
    near(by["BM_A/1"]["cv"], 0.3)
    assert "cv" not in by["BM_B/iterations:1/repeats:1"]
    assert pr.median_rel_error(by["BM_B/iterations:1/repeats:1"]) is None  # one run: no spread


def test_ratio_error_combines_both_medians():
    a = dict(cv=0.3, repetitions=9)
    b = dict(cv=0.4, repetitions=4)
    # √(π/2)·0.3/3 and √(π/2)·0.4/2, combined in quadrature, times the ratio 2.
    ea, eb = math.sqrt(math.pi / 2) * 0.1, math.sqrt(math.pi / 2) * 0.2
    near(pr.median_rel_error(a), ea)
    near(pr.ratio_error(2.0, a, b), 2.0 * math.sqrt(ea * ea + eb * eb))
    assert pr.fmt_ratio(0.74, 0.1253) == "**0.74** ± 0.13"
    assert pr.fmt_ratio(None, 0.1) == "–"


def test_targets_say_when_within_two_standard_errors():
    ratios = {("plate_c8", "newton_coulomb", "api"): (1.0, 0.74, 0.07),   # 3.7 σ short: missed
              ("plate_c16", "newton_coulomb", "api"): (1.0, 0.84, 0.09),  # 1.8 σ short
              ("plate_c32", "newton_coulomb", "api"): (1.0, 1.1, 0.06)}   # 1.7 σ over
    rows = {r[0]: r for r in pr.public_path_targets(ratios, {})}
    assert rows["plate_c8, Newton + Coulomb, solve_impact"][2:] == ["0.74× ± 0.07", "missed"]
    assert rows["plate_c16, Newton + Coulomb, solve_impact"][3] == \
        "missed (within two standard errors)"
    assert rows["plate_c32, Newton + Coulomb, solve_impact"][3] == \
        "met (within two standard errors)"
    assert rows["random_n12_c6, Newton + Coulomb, solve_impact"][2:] == ["–", "–"]
    # The frictionless law has the same many-contact target.
    assert rows["plate_c8, Newton, solve_impact"][1:] == ["≥ 1× Siconos", "–", "–"]


def test_control_pairs_identical_work_on_one_contact():
    def run(name, ns):
        return dict(name=name, cpu_time=ns, time_unit="ns")
    runs = [run("BM_Classical_SolveImpact/point_mass/newton_coulomb/checked", 446.0),
            run("BM_Classical_SolveImpact/point_mass/newton_coulomb/unchecked", 606.0),
            run("BM_Classical_SolveImpact/bar_first_impact/newton/checked", 562.0),
            run("BM_Classical_SolveImpact/bar_first_impact/newton/unchecked", 517.0),
            # Two contacts: checking uniqueness enumerates the modes, other work.
            run("BM_Classical_SolveImpact/flat_bar/newton_coulomb/checked", 11061.0),
            run("BM_Classical_SolveImpact/flat_bar/newton_coulomb/unchecked", 1784.0),
            run("BM_Classical_SolveImpact/bar_first_impact/poisson/checked", 600.0)]  # no twin
    assert pr.noise_control(runs) == [("bar_first_impact / newton", 517.0, 562.0),
                                      ("point_mass / newton_coulomb", 446.0, 606.0)]


def test_sparse_rows_name_their_solver():
    def run(name, label, **counters):
        return dict(name=name, label=label, file="sparse_bench.json", cpu_time=2.0,
                    time_unit="ms", **counters)
    runs = [run("BM_Sparse_Pile/3/3", "converged", contacts=15, sweeps=17, residual=1e-13),
            run("BM_Dense_Pile/fremond_coulomb/3/3", "converged", contacts=15, iterations=14,
                residual=2e-16),
            run("BM_Siconos_Pile/19/19/iterations:1/repeats:1", "solver=fc2d_nsgs info=0",
                contacts=703, iterations=48796, our_residual=1.7e-8)]
    rows = pr.sparse_runs(runs)
    assert [(r["what"], r["solver"], r["contacts"], r["sweeps"]) for r in rows] == [
        ("pile", "ours: nsgs", 15, 17),
        ("pile", "ours: dense solve_impact, fremond_coulomb", 15, 14),
        ("pile", "Siconos: nsgs", 703, 48796)]


def main():
    names = sorted(n for n, f in globals().items() if n.startswith("test_") and callable(f))
    failed = 0
    for n in names:
        try:
            globals()[n]()
            print(f"ok   {n}")
        except Exception as e:  # noqa: BLE001  report every failure, then exit non-zero
            failed += 1
            print(f"FAIL {n}: {type(e).__name__}: {e}")
    print(f"{len(names) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
