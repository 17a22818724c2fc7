#!/usr/bin/python3
"""The performance report from the files scripts/perf-report.sh leaves in its output directory.

    /usr/bin/python3 bench/plot_report.py out/perf [--docs docs/performance.md]

Reads the Google Benchmark JSON files (*_bench.json), the work-precision CSVs (work_precision.csv,
simulation_work_precision.csv) and machine.txt, and writes into the same directory:

  - benchmarks.csv: every benchmark run, flattened (name, label words, CPU and real ns, counters);
  - siconos_ratios.csv: Siconos's CPU time over ours for every pair of benchmarks with the same
    "problem=... law=..." label (bench/compare.py's pairing), with both answers' errors;
  - work_precision.png: time per solve against the actual error, one panel per case of the suite,
    one line per method (filled markers: converged; open: not);
  - work_precision_summary.png: the same for four representative cases, larger;
  - sparse_scaling.png: time per sparse solve against contacts, ours and Siconos's, log-log;
  - scaling.png: time per solve against the number of contacts (plate) and of degrees of freedom
    (random bodies), ours and Siconos's;
  - simulation_work_precision.png: Moreau-Jean's errors against the step, and its cost per
    simulated second against its error, beside Siconos's Moreau-Jean;
  - report.md: the machine, the tables (targets, per-solve times by method, the Siconos ratios,
    the work-precision summary with the reason wherever a method stops short of 1e-14, scaling,
    throughput, simulation).

With --docs, the performance page (docs/performance.md) is rewritten from the report's summary, with
the plots copied to docs/perf/, and the README's speed table (between its speed markers) from the
report's first table. Uses the standard library and matplotlib.
"""
import argparse
import csv
import json
import math
import os
import re
import shutil
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import compare  # noqa: E402  (the pairing of Siconos and fremond benchmarks)

UNIT_NS = compare.UNIT_NS
METHOD_ORDER = ["closed_form", "scalar_newton", "mode_enumeration", "automatic",
                "semismooth_newton", "proximal", "nlopt"]
METHOD_STYLE = {
    "closed_form": ("tab:olive", "D"),
    "scalar_newton": ("tab:cyan", "P"),
    "mode_enumeration": ("tab:pink", "X"),
    "automatic": ("black", "o"),
    "semismooth_newton": ("tab:blue", "s"),
    "proximal": ("tab:orange", "^"),
    "nlopt": ("tab:red", "v"),
}


# ---------------------------------------------------------------------------------------------
# Reading

def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path, encoding="utf-8", newline="") as f:
        return list(csv.DictReader(f))


def num(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return math.nan


def load_benchmarks(outdir):
    """Every run of every *_bench.json, with its file's context."""
    runs, contexts = [], {}
    for name in sorted(os.listdir(outdir)):
        if not name.endswith("_bench.json"):
            continue
        path = os.path.join(outdir, name)
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
        contexts[name] = data.get("context", {})
        # Each benchmark's coefficient of variation over its repetitions, kept on its median.
        cvs = {b["run_name"]: float(b["cpu_time"]) for b in data.get("benchmarks", [])
               if b.get("aggregate_name") == "cv" and "run_name" in b}
        for b in data.get("benchmarks", []):
            if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
                continue
            b = dict(b)
            b["file"] = name
            if b.get("run_type") == "aggregate" and b.get("run_name") in cvs:
                b["cv"] = cvs[b["run_name"]]
            b["name"] = display(b["name"])  # the median of repetitions stands for the benchmark
            runs.append(b)
    return runs, contexts


def median_rel_error(b):
    """The relative standard error of a median of repetitions: √(π/2) cv / √n for times spread
    about normally; None for a single run or without the spread."""
    n = int(b.get("repetitions", 0) or 0)
    if "cv" not in b or n < 2:
        return None
    return math.sqrt(math.pi / 2) * b["cv"] / math.sqrt(n)


def ratio_error(ratio, a, b):
    """The standard error of ratio = time(a) / time(b), from each median's own."""
    ea, eb = median_rel_error(a), median_rel_error(b)
    if ratio is None or ea is None or eb is None:
        return None
    return ratio * math.hypot(ea, eb)


def fmt_ratio(ratio, err):
    """A ratio in bold, with its standard error where known."""
    if not ratio:
        return "–"
    return f"**{ratio:.2g}**" + (f" ± {fmt_spread(err)}" if err else "")


def fmt_spread(err):
    """A standard error to two decimals (a ratio's own precision), or one digit beyond 1."""
    return f"{err:.2f}" if err < 1 else f"{err:.1g}"


def display(name):
    """A benchmark's name without the aggregate's suffix."""
    return re.sub(r"_(median|mean)$", "", name)


def words(label):
    return dict(w.split("=", 1) for w in label.split() if "=" in w)


def cpu_ns(b):
    return float(b["cpu_time"]) * UNIT_NS[b.get("time_unit", "ns")]


def real_ns(b):
    return float(b["real_time"]) * UNIT_NS[b.get("time_unit", "ns")]


def fmt_ns(ns):
    if ns is None or not math.isfinite(ns):
        return "–"
    if ns < 1e3:
        return f"{ns:.3g} ns"
    if ns < 1e6:
        return f"{ns / 1e3:.3g} µs"
    if ns < 1e9:
        return f"{ns / 1e6:.3g} ms"
    return f"{ns / 1e9:.3g} s"


def fmt_err(e):
    if e is None or not math.isfinite(e):
        return "–"
    if e == 0:
        return "0"
    return f"{e:.1e}"


# ---------------------------------------------------------------------------------------------
# Tables

def md_table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    for r in rows:
        out.append("| " + " | ".join(str(c) for c in r) + " |")
    return "\n".join(out)


def write_benchmarks_csv(outdir, runs):
    keys = sorted({k for b in runs for k in b if k not in (
        "name", "label", "cpu_time", "real_time", "time_unit", "iterations", "file", "run_name",
        "run_type", "repetitions", "repetition_index", "threads", "family_index",
        "per_family_instance_index", "aggregate_name", "aggregate_unit", "error_occurred",
        "error_message")})
    with open(os.path.join(outdir, "benchmarks.csv"), "w", encoding="utf-8", newline="") as f:
        w = csv.writer(f)
        w.writerow(["file", "name", "label", "cpu_ns", "real_ns", "iterations", "threads", "error"] + keys)
        for b in runs:
            w.writerow([b["file"], b["name"], b.get("label", ""), f"{cpu_ns(b):.6g}",
                        f"{real_ns(b):.6g}", b.get("iterations", ""), b.get("threads", 1),
                        b.get("error_message", "")] + [b.get(k, "") for k in keys])


def siconos_pairs(runs):
    """(key, siconos run, our run, ratio) for every pair compare.py would print."""
    by_key = defaultdict(lambda: ([], []))
    for b in runs:
        if b.get("error_occurred"):
            continue
        k = compare.key(b.get("label", ""))
        if not k:
            continue
        by_key[k][0 if b["name"].startswith("BM_Siconos_") else 1].append(b)
    pairs = []
    for k in sorted(by_key):
        theirs, ours = by_key[k]
        for s in theirs:
            for o in ours:
                (sv, su), (ov, ou) = compare.cost(s), compare.cost(o)
                if su != ou or ov <= 0 or compare.depth(s) != compare.depth(o):
                    continue
                pairs.append((k, s, o, sv / ov, su))
    return pairs


def write_ratios_csv(outdir, pairs):
    with open(os.path.join(outdir, "siconos_ratios.csv"), "w", encoding="utf-8", newline="") as f:
        w = csv.writer(f)
        w.writerow(["key", "siconos", "siconos_cost", "fremond", "fremond_cost", "unit", "ratio",
                    "siconos_err", "fremond_err"])
        for k, s, o, ratio, unit in pairs:
            w.writerow([k, compare.name_of(s), f"{compare.cost(s)[0]:.6g}", compare.name_of(o),
                        f"{compare.cost(o)[0]:.6g}", unit, f"{ratio:.4g}", s.get("err", ""),
                        o.get("err", "")])


# ---------------------------------------------------------------------------------------------
# Plots

def wp_series(points):
    """method → list of (error, ns, converged) sorted by decreasing tolerance / increasing budget."""
    series = defaultdict(list)
    no_reference = all(not math.isfinite(num(p["rel_error"])) for p in points)
    for p in points:
        # Without a reference (Coulomb on several general contacts) the law's residual stands in.
        e = num(p["residual"]) if no_reference else num(p["rel_error"])
        if not math.isfinite(e):
            continue
        m = p["method"]
        if m == "nlopt" and p["budget"] == "0":
            m = "nlopt"  # the default budget: one more point on NLopt's line
        series[m].append((max(e, 1e-18), num(p["ns_per_solve"]), p["status"] == "converged",
                          num(p["tolerance"]), int(p["budget"]) or 10**9))
    for m in series:
        if m == "nlopt":
            series[m].sort(key=lambda t: (t[4], -t[3]))
        else:
            series[m].sort(key=lambda t: -t[3])
    return series


def plot_wp_panel(ax, points, title):
    series = wp_series(points)
    for m in METHOD_ORDER:
        if m not in series:
            continue
        color, marker = METHOD_STYLE[m]
        pts = series[m]
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", color=color, lw=1, alpha=0.7,
                label=m)
        for e, t, ok, _, _ in pts:
            ax.plot([e], [t], marker, color=color, ms=4, mfc=color if ok else "none")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.axvline(1e-14, color="grey", lw=0.6, ls=":")
    ax.set_title(title, fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(True, which="major", lw=0.3)


def plot_work_precision(outdir, wp):
    cases = []
    for p in wp:
        c = (p["problem"], p["law"])
        if c not in cases:
            cases.append(c)
    if not cases:
        return []
    n = len(cases)
    cols = 5
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(3.2 * cols, 2.7 * rows), squeeze=False)
    for i, c in enumerate(cases):
        ax = axes[i // cols][i % cols]
        pts = [p for p in wp if (p["problem"], p["law"]) == c]
        no_ref = all(not math.isfinite(num(p["rel_error"])) for p in pts)
        plot_wp_panel(ax, pts, f"{c[0]}\n{c[1]}" + (" (x: law residual, no reference)" if no_ref else ""))
        if i % cols == 0:
            ax.set_ylabel("ns per solve", fontsize=8)
        if i // cols == rows - 1:
            ax.set_xlabel("error vs quad reference", fontsize=8)
    for j in range(n, rows * cols):
        axes[j // cols][j % cols].axis("off")
    handles, labels = axes[0][0].get_legend_handles_labels()
    seen = dict(zip(labels, handles))
    for i in range(n):
        h, l = axes[i // cols][i % cols].get_legend_handles_labels()
        seen.update(zip(l, h))
    fig.legend([seen[k] for k in METHOD_ORDER if k in seen], [k for k in METHOD_ORDER if k in seen],
               loc="lower right", fontsize=9, ncol=2)
    fig.suptitle("Work-precision of Frémond's solvers: time per solve_impact against the error of "
                 "q̇_E (energy norm, relative) vs the __float128 reference\n(filled: converged; "
                 "open: not converged; dotted: 1e-14)", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    fig.savefig(os.path.join(outdir, "work_precision.png"), dpi=110)
    plt.close(fig)

    pick = [("bar_first_impact", "fremond_p3_viscous"), ("flat_bar", "fremond_p3_viscous"),
            ("random_n6_c3", "fremond_p3_viscous"), ("hard_p1.01_q1.01", "fremond_viscous")]
    pick = [c for c in pick if c in cases]
    if pick:
        fig, axes = plt.subplots(1, len(pick), figsize=(4.2 * len(pick), 3.8), squeeze=False)
        for ax, c in zip(axes[0], pick):
            plot_wp_panel(ax, [p for p in wp if (p["problem"], p["law"]) == c], f"{c[0]} / {c[1]}")
            ax.set_xlabel("relative error of q̇_E", fontsize=8)
        axes[0][0].set_ylabel("ns per solve", fontsize=8)
        axes[0][-1].legend(fontsize=7, loc="upper right")
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, "work_precision_summary.png"), dpi=110)
        plt.close(fig)
    return cases


def plot_scaling(outdir, runs):
    ours = defaultdict(list)  # (kind, law, storage) → [(x, ns)]
    theirs = defaultdict(list)
    for b in runs:
        if b["file"] != "scaling_bench.json" or b.get("error_occurred"):
            continue
        w = words(b.get("label", ""))
        prob = w.get("problem", "")
        m = re.match(r"plate_c(\d+)$", prob)
        r = re.match(r"random_n(\d+)_c\d+$", prob)
        if not (m or r):
            continue
        kind, x = ("plate", int(m.group(1))) if m else ("random", int(r.group(1)))
        target = theirs if b["name"].startswith("BM_Siconos_") else ours
        target[(kind, w.get("law", ""), w.get("storage", "heap"))].append((x, cpu_ns(b)))
    if not ours:
        return
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    colors = {"fremond_p3": "tab:blue", "fremond_p3_viscous": "tab:green",
              "fremond_p3_coulomb": "tab:purple", "newton": "tab:orange", "newton_coulomb": "tab:red"}
    for ax, kind, xlabel in ((axes[0], "plate", "contacts (plate, 3 dofs)"),
                             (axes[1], "random", "degrees of freedom n (n/2 contacts)")):
        for (k, law, storage), pts in sorted(ours.items()):
            if k != kind:
                continue
            pts.sort()
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "-o" if storage == "heap" else ":s",
                    color=colors.get(law, "k"), ms=4,
                    label=f"fremond {law}" + (" (small)" if storage == "small" else ""))
        for (k, law, _), pts in sorted(theirs.items()):
            if k != kind:
                continue
            pts.sort()
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "--x", color=colors.get(law, "k"),
                    ms=5, label=f"Siconos {law}")
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("CPU ns per solve")
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Cost of one impact solve as the problem grows")
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "scaling.png"), dpi=110)
    plt.close(fig)


def plot_simulation(outdir, sim):
    if not sim:
        return
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    groups = defaultdict(list)
    for r in sim:
        if r["code"] == "fremond_event_driven":
            continue
        groups[(r["code"], r["law"])].append(r)
    palette = ["tab:blue", "tab:green", "tab:purple", "tab:orange", "tab:brown"]
    for i, ((code, law), rows) in enumerate(sorted(groups.items())):
        rows.sort(key=lambda r: num(r["step"]))
        h = [num(r["step"]) for r in rows]
        siconos = code.startswith("siconos")
        color = "tab:red" if siconos else palette[i % len(palette)]
        who = "Siconos" if siconos else "fremond"
        ef = [num(r["energy_final_error"]) for r in rows]
        axes[0].plot(h, ef, "--x" if siconos else "-o", color=color, ms=4,
                     label=f"{who} {law}: |ΔE(3 s)|/E0")
        if not siconos:
            te = [num(r["early_trajectory_error"]) for r in rows]
            axes[0].plot(h, te, ":s", color=color, ms=3, label=f"{who} {law}: max |Δq| (t ≤ 0.5 s), m")
        cost = [num(r["ns_per_simulated_second"]) for r in rows]
        axes[1].plot([max(e, 1e-17) for e in ef], cost, "--x" if siconos else "-o", color=color,
                     ms=4, label=f"{who} {law}")
    axes[0].set_xscale("log")
    axes[0].set_yscale("log")
    axes[0].set_xlabel("step h (s)")
    axes[0].set_ylabel("error against the event-driven run")
    axes[0].grid(True, lw=0.3)
    axes[0].legend(fontsize=6)
    axes[1].set_xscale("log")
    axes[1].set_yscale("log")
    axes[1].set_xlabel("|E(3 s) − E_event-driven(3 s)| / E0")
    axes[1].set_ylabel("CPU ns per simulated second")
    axes[1].grid(True, lw=0.3)
    axes[1].legend(fontsize=7)
    fig.suptitle("Moreau-Jean on the paper's bar, 3 s: work-precision against the event-driven run")
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "simulation_work_precision.png"), dpi=110)
    plt.close(fig)


# ---------------------------------------------------------------------------------------------
# The report

def find(runs, name_prefix=None, **want):
    """Runs whose label has every word in `want` (and whose name starts with name_prefix)."""
    out = []
    for b in runs:
        if b.get("error_occurred"):
            continue
        if name_prefix and not b["name"].startswith(name_prefix):
            continue
        w = words(b.get("label", ""))
        if all(w.get(k) == v for k, v in want.items()):
            out.append(b)
    return out


def best(runs):
    return min(runs, key=cpu_ns) if runs else None


def target_rows(runs):
    """The speed targets of the issues and what was measured (CPU time)."""
    rows = []

    def add(what, target_ns, measured, note=""):
        ns = cpu_ns(measured) if measured else None
        verdict = "–" if ns is None else ("met" if ns < target_ns else "missed")
        rows.append((what, fmt_ns(target_ns), fmt_ns(ns), verdict,
                     (display(measured["name"]) if measured else "not measured") + (f"; {note}" if note else "")))

    add("bar p=3 + viscous dead zone, one contact, solve_impact", 200,
        best(find(runs, "BM_Fremond/", problem="bar_first_impact", law="fremond_p3_viscous",
                  method="automatic", stage="solve_impact")))
    add("  the same, law stage (no validation, no certificate)", 200,
        best(find(runs, "BM_FremondLaw/", problem="bar_first_impact", law="fremond_p3_viscous")))
    add("point mass p=2, solve_impact", 10,
        best(find(runs, "BM_Fremond/", problem="point_mass", law="fremond_p2", method="automatic")))
    add("  the same, kernel (one prox, the clamp, P)", 10,
        best(find(runs, "BM_FremondKernel/", problem="point_mass", law="fremond_p2")))
    add("flat bar, two contacts (Frémond p=3), solve_impact", 1000,
        best(find(runs, "BM_Fremond/", problem="flat_bar", law="fremond_p3", method="automatic")))
    add("flat bar, two contacts (Frémond p=3 viscous), solve_impact", 1000,
        best(find(runs, "BM_Fremond/", problem="flat_bar", law="fremond_p3_viscous", method="automatic")))
    add("classical: one contact with friction (Newton+Coulomb), kernel", 12,
        best(find(runs, "BM_Classical_Kernel/", problem="bar_first_impact", law="newton_coulomb")))
    add("classical: one contact with friction, solve_impact", 12,
        best(find(runs, "BM_Classical_SolveImpact/", problem="bar_first_impact", law="newton_coulomb")))
    add("classical: two contacts (flat bar, Newton+Coulomb), kernel", 100,
        best(find(runs, "BM_Classical_Kernel/", problem="flat_bar", law="newton_coulomb")))
    add("classical: two contacts, solve_impact", 100,
        best(find(runs, "BM_Classical_SolveImpact/", problem="flat_bar", law="newton_coulomb")))
    ed = [b for b in runs if b["name"].startswith("BM_EventDriven/3") and not b.get("error_occurred")]
    add("simulation: bar 3 s event-driven, Frémond + Coulomb", 1e5, best(ed))
    mj = [b for b in runs if b["name"].startswith("BM_MoreauJean/") and not b.get("error_occurred")]
    if mj:
        b = best([m for m in mj if m["name"].startswith("BM_MoreauJean/3")] or mj)
        per = b.get("per_step")
        steps = b.get("mj_steps")
        ns = per * 1e9 if per else (cpu_ns(b) / steps if steps else None)
        rows.append(("simulation: Moreau-Jean, per step", fmt_ns(100), fmt_ns(ns),
                     "–" if ns is None else ("met" if ns < 100 else "missed"), display(b["name"])))
    return rows


def nlopt_beside(runs):
    rows = []
    for b in runs:
        if not b["name"].startswith("BM_Fremond/") or not b["name"].endswith("/automatic"):
            continue
        w = words(b.get("label", ""))
        nl = find(runs, "BM_Fremond/", problem=w["problem"], law=w["law"], method="nlopt",
                  stage="solve_impact")
        nl_err = [x for x in runs if x["name"] == b["name"][:-len("automatic")] + "nlopt"]
        note = nl_err[0].get("error_message", "") if nl_err and nl_err[0].get("error_occurred") else ""
        rows.append((w["problem"], w["law"], fmt_ns(cpu_ns(b)), fmt_err(b.get("err")),
                     fmt_ns(cpu_ns(nl[0])) if nl else ("not timed" if note else "–"),
                     fmt_err(nl[0].get("err")) if nl else "–",
                     f"{cpu_ns(nl[0]) / cpu_ns(b):.0f}×" if nl else ""))
    return rows


def method_table(runs):
    """Per case, CPU ns of solve_impact by method."""
    table = defaultdict(dict)
    order = []
    for b in runs:
        if not b["name"].startswith("BM_Fremond/") or b.get("error_occurred"):
            continue
        w = words(b.get("label", ""))
        c = (w["problem"], w["law"])
        if c not in order:
            order.append(c)
        table[c][w["method"]] = b
    methods = [m for m in METHOD_ORDER if any(m in table[c] for c in order)]
    rows = []
    for c in order:
        cells = []
        for m in methods:
            b = table[c].get(m)
            if not b:
                cells.append("")
                continue
            conv = b.get("converged", 1)
            cells.append(fmt_ns(cpu_ns(b)) + ("" if conv >= 1 else f" ({conv:.0%} conv.)"))
        rows.append([c[0], c[1]] + cells)
    return ["problem", "law"] + methods, rows


def why_short(p, cases_info):
    """Why a method's best error on a case stays above 1e-14."""
    prob = p["problem"]
    if p["method"] == "nlopt":
        if p["budget_hit"] == "1":
            return "NLopt stops on its evaluation budget (its own criterion never fires here)"
        return "NLopt (SLSQP/MMA) accepts its answer at nlopt_tolerance"
    cond = num(p.get("cond_G"))
    err = num(p["rel_error"])
    if p["status"] != "converged":
        why = f"does not converge ({p['status']}) at any tolerance tried"
        if math.isfinite(cond) and cond > 1e5:
            why += f"; κ(G) = {cond:.1g} slows the Gauss-Seidel sweeps to a crawl"
        return why
    if math.isfinite(cond) and err <= 64 * 2.2e-16 * cond:
        return (f"within 64 ε κ(G) = {64 * 2.2e-16 * cond:.1g} (κ(G) = {cond:.2g}): the rounding "
                "level of contact space, where z = D_A + G P/2 is rounded to ε‖G‖‖P‖")
    if p["method"] == "proximal":
        return ("linear convergence: stops on the residual at its rounding floor, and the error "
                "is the residual times up to 1/(1 − ρ)")
    return "stops at its rounding floor (16 ε × the terms of the residual)"


def natural(k):
    """Sort key with numbers compared as numbers: plate_c2 before plate_c16."""
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", k)]


def pair_picks(pairs):
    """Per pair key (problem and law), the runs the tables set side by side: Siconos's fastest
    from the data (`siconos`) and from G (`driver`), and ours: the prepared solver, the public
    solve_impact (`api`), the same work as Siconos's (`same`) and the kernel; None where absent."""
    by = defaultdict(lambda: ({}, {}))
    for k, sr, o, _, unit in pairs:
        by[k][0][sr["name"]] = sr
        by[k][1][o["name"]] = o
    picks = {}
    for k in sorted(by, key=natural):
        theirs, ours = by[k]

        def fastest(runs, pred):
            c = [b for b in runs if pred(b)]
            return min(c, key=lambda b: compare.cost(b)[0]) if c else None

        def pick(pred):
            return fastest(ours.values(), pred)

        picks[k] = {
            "siconos": fastest(theirs.values(), lambda b: compare.depth(b) == "data"),
            "driver": fastest(theirs.values(), lambda b: compare.depth(b) == "G"),
            "api": pick(lambda b: "SolveImpact" in b["name"] and "unchecked" in b["name"]) or pick(
                lambda b: b["name"].startswith("BM_Fremond/") and b["name"].endswith("/automatic"))
            or pick(lambda b: "stage=solve_impact" in b.get("label", "")),
            "prepared": pick(lambda b: ("Prepared" in b["name"] and "unchecked" in b["name"])
                             or b["name"].startswith("BM_FremondPrepared/")),
            "same": pick(lambda b: "FromData" in b["name"] or b["name"].startswith("BM_FremondLaw/")),
            "kernel": pick(lambda b: "Kernel" in b["name"]),
        }
    return picks


def siconos_summary(pairs):
    """One row per pair key: the fastest Siconos run against ours at three depths."""
    rows = []
    for k, p in pair_picks(pairs).items():
        sbest, sdrv = p["siconos"], p["driver"]
        if sbest is None:
            continue
        sv, unit = compare.cost(sbest)
        api, prepared, same, kern = p["api"], p["prepared"], p["same"], p["kernel"]
        def cell(v):
            return fmt_ns(v) if unit == "ns" else f"{v:.3g} {unit}"

        cells = []
        for b in (prepared, api, same):
            if b is None:
                cells += ["–", ""]
            else:
                v = compare.cost(b)[0]
                cells += [cell(v), f"**{sv / v:.2g}**"]
        # The kernel against Siconos's driver alone: both start from G and D_A.
        if sdrv is None:
            cells += ["–", "", "–", ""]
        else:
            dv = compare.cost(sdrv)[0]
            cells += [display(sdrv["name"]), cell(dv)]
            if kern is None:
                cells += ["–", ""]
            else:
                v = compare.cost(kern)[0]
                cells += [cell(v), f"**{dv / v:.2g}**"]
        errs = [num(b.get("err")) for b in (prepared, api, same, kern) if b is not None]
        rows.append([k.replace("problem=", "").replace(" law=", " / "), display(sbest["name"]),
                     cell(sv), fmt_err(num(sbest.get("err")))]
                    + cells + [fmt_err(max(errs) if errs else math.nan)])
    return rows


# What a user gets (the prepared solver, the one-shot solve_impact, the batch), beside Siconos,
# for the problems of the public-path targets; the targets' verdicts follow.
USER_KEYS = [("bar_first_impact", "newton_coulomb"), ("point_mass", "newton_coulomb"),
             ("flat_bar", "newton_coulomb"), ("bar_first_impact", "fremond_p3_coulomb"),
             ("plate_c8", "newton_coulomb"), ("plate_c16", "newton_coulomb"),
             ("plate_c32", "newton_coulomb"), ("random_n12_c6", "newton_coulomb"),
             ("random_n18_c9", "newton_coulomb"), ("random_n24_c12", "newton_coulomb"),
             ("random_n30_c15", "newton_coulomb"), ("plate_c8", "newton"), ("plate_c16", "newton"),
             ("plate_c32", "newton"), ("random_n12_c6", "newton"), ("random_n18_c9", "newton"),
             ("random_n24_c12", "newton"), ("random_n30_c15", "newton")]


def user_rows(runs, pairs):
    """Rows of (problem / law, prepared, ratio, solve_impact, ratio, Siconos's fastest, its time,
    errors), and the ratios by problem for the targets."""
    picks = pair_picks(pairs)
    rows, ratios = [], {}
    for problem, law in USER_KEYS:
        p = picks.get(f"problem={problem} law={law}")
        if p is None:  # no Siconos peer (Frémond + Coulomb): ours alone
            ours = {"prepared": find(runs, "BM_FremondPrepared/", problem=problem, law=law),
                    "api": find(runs, "BM_Fremond/", problem=problem, law=law, method="automatic")}
            p = {k: best(v) for k, v in ours.items()}
            p["siconos"] = None
        s = p["siconos"]
        sv = compare.cost(s)[0] if s else None
        cells = [f"{problem} / {law}"]
        for which in ("prepared", "api"):
            b = p.get(which)
            v = compare.cost(b)[0] if b else None
            ratio = sv / v if (sv and v) else None
            err = ratio_error(ratio, s, b) if (s and b) else None
            ratios[(problem, law, which)] = (v, ratio, err)
            cells += [fmt_ns(v), fmt_ratio(ratio, err)]
        ours = [b for b in (p.get("prepared"), p.get("api")) if b is not None]
        errs = [num(b.get("err")) for b in ours if "err" in b]
        # Without a reference (plates, random bodies) ours is judged by the law's own residual.
        residuals = [num(b.get("residual")) for b in ours if "residual" in b]
        our_err = (fmt_err(max(errs)) if errs else
                   f"residual {fmt_err(max(residuals))}" if residuals else "–")
        cells += [display(s["name"]) if s else "– (no Siconos solver for this law)", fmt_ns(sv),
                  fmt_err(num(s.get("err"))) if s else "–", our_err]
        rows.append(cells)
    return rows, ratios


def noise_control(runs):
    """Pairs of benchmarks that time the same work: solve_impact on one contact with and without
    check_uniqueness (one contact's modes are settled in closed form either way), as
    (problem / law, faster ns, slower ns); what this run's timing alone makes of identical work."""
    medians = {b["name"]: cpu_ns(b) for b in runs
               if b["name"].startswith("BM_Classical_SolveImpact/") and not b.get("error_occurred")}
    out = []
    for name, t in sorted(medians.items()):
        if not name.endswith("/checked"):
            continue
        other = medians.get(name[:-len("checked")] + "unchecked")
        problem, law = name.split("/")[1:3]
        if other and problem in ("bar_first_impact", "point_mass"):
            out.append((f"{problem} / {law}", min(t, other), max(t, other)))
    return out


def batch_rows(runs, ratios):
    """Impacts per second of solve_batch on 1 and 2 threads, and the gain of the second core;
    Siconos's one-core rate from its fastest bar solve beside the Newton + Coulomb rows."""
    rows, rates = [], {}
    sic = ratios.get(("bar_first_impact", "newton_coulomb", "api"))
    for name, law, form in (("BM_Batch_SmallBar_NewtonCoulomb", "Newton + Coulomb", "small"),
                            ("BM_Batch_Bar_NewtonCoulomb", "Newton + Coulomb", "heap"),
                            ("BM_Batch_SmallBar_FremondCoulomb_p3", "Frémond + Coulomb p = 3", "small"),
                            ("BM_Batch_Bar_FremondCoulomb_p3", "Frémond + Coulomb p = 3", "heap"),
                            ("BM_Batch_PreparedSmallBar_NewtonCoulomb", "Newton + Coulomb",
                             "prepared, small"),
                            ("BM_Batch_PreparedBar_NewtonCoulomb", "Newton + Coulomb", "prepared, heap"),
                            ("BM_Batch_PreparedSmallBar_FremondCoulomb_p3", "Frémond + Coulomb p = 3",
                             "prepared, small"),
                            ("BM_Batch_PreparedSmallBarColumns_NewtonCoulomb", "Newton + Coulomb",
                             "prepared, columns"),
                            ("BM_Batch_PreparedSmallBarColumns_FremondCoulomb_p3",
                             "Frémond + Coulomb p = 3", "prepared, columns")):
        got = {}
        for t in (1, 2):
            r = [b for b in runs if b["name"].startswith(f"{name}/{t}/") and not b.get("error_occurred")]
            got[t] = r[0].get("items_per_second") if r else None
        if got[1] is None and got[2] is None:
            continue
        rates[(law, form)] = got
        gain = f"{got[2] / got[1]:.2f}×" if got[1] and got[2] else "–"
        rows.append([law, form, f"{got[1] / 1e6:.2f} M/s" if got[1] else "–",
                     f"{got[2] / 1e6:.2f} M/s" if got[2] else "–", gain])
    siconos_rate = None
    if sic and sic[0] and sic[1]:
        siconos_rate = 1e9 / (sic[0] * sic[1])  # Siconos's time = ours × ratio
    return rows, rates, siconos_rate


def public_path_targets(ratios, rates):
    """The public path's targets (prepared ≥ 5× Siconos, one-shot ≥ 2×, many contacts ≥ 1×,
    the batch's rate and gain, Frémond + Coulomb prepared under 150 ns) and what was measured;
    a ratio whose target lies within two standard errors of it says so."""
    rows = []

    def verdict(ok):
        return "–" if ok is None else ("met" if ok else "missed")

    def ratio_row(what, key, want):
        _, r, err = ratios.get(key, (None, None, None))
        if not r:
            rows.append([what, f"≥ {want:g}× Siconos", "–", "–"])
            return
        v = verdict(r >= want)
        if err and abs(r - want) < 2 * err:
            v += " (within two standard errors)"
        rows.append([what, f"≥ {want:g}× Siconos",
                     f"{r:.2g}×" + (f" ± {fmt_spread(err)}" if err else ""), v])

    for problem in ("bar_first_impact", "point_mass", "flat_bar"):
        ratio_row(f"{problem}, Newton + Coulomb, prepared", (problem, "newton_coulomb", "prepared"), 5)
        ratio_row(f"{problem}, Newton + Coulomb, solve_impact", (problem, "newton_coulomb", "api"), 2)
    many = ("plate_c8", "plate_c16", "plate_c32", "random_n12_c6", "random_n18_c9",
            "random_n24_c12", "random_n30_c15")
    # The many-contact target holds for every law Siconos solves, Newton's without friction too.
    for law, name in (("newton_coulomb", "Newton + Coulomb"), ("newton", "Newton")):
        for problem in many:
            ratio_row(f"{problem}, {name}, solve_impact", (problem, law, "api"), 1)
    v, _, _ = ratios.get(("bar_first_impact", "fremond_p3_coulomb", "prepared"), (None, None, None))
    rows.append(["bar, Frémond + Coulomb p = 3, prepared", "< 150 ns", fmt_ns(v),
                 verdict(v < 150 if v else None)])
    for law, want in (("Newton + Coulomb", 10e6), ("Frémond + Coulomb p = 3", 2e6)):
        for forms, what in ((("small", "heap"), "independent bars"),
                            (("prepared, small", "prepared, heap", "prepared, columns"),
                             "one bar, many velocities")):
            two = max((rates.get((law, f), {}).get(2) or 0) for f in forms)
            if two:
                rows.append([f"batch, {what}, {law}, 2 threads", f"≥ {want / 1e6:.0f} M/s",
                             f"{two / 1e6:.2f} M/s", verdict(two >= want)])
    for form in ("small", "prepared, small", "prepared, columns"):
        g = rates.get(("Newton + Coulomb", form), {})
        gain = g[2] / g[1] if g.get(1) and g.get(2) else None
        if gain:
            rows.append([f"batch ({form}), second core's gain", "≥ 1.8×", f"{gain:.2f}×",
                         verdict(gain >= 1.8)])
    return rows


def sim_siconos_rows(sim):
    """Moreau-Jean per step, ours against Siconos's at the same step (Newton + Coulomb)."""
    ours = {r["step"]: r for r in sim if r["code"] == "fremond_moreau_jean" and r["law"] == "newton_coulomb"}
    theirs = {r["step"]: r for r in sim if r["code"] == "siconos_moreau_jean"}
    rows = []
    for h in sorted(set(ours) & set(theirs), key=float):
        o, t = ours[h], theirs[h]
        rows.append((h, fmt_ns(num(t["ns_per_step"])), fmt_ns(num(o["ns_per_step"])),
                     f"**{num(t['ns_per_step']) / num(o['ns_per_step']):.3g}**",
                     fmt_err(num(t["energy_final_error"])), fmt_err(num(o["energy_final_error"])),
                     t["impacts"], o["impacts"]))
    if not rows:
        return []
    return ["Moreau-Jean on the paper's bar over 3 s with Newton + Coulomb, per step (CPU), and each "
            "run's final energy against the event-driven run of the same law:", "",
            md_table(["h (s)", "Siconos per step", "ours per step", "ratio", "Siconos |ΔE(3 s)|/E0",
                      "ours |ΔE(3 s)|/E0", "Siconos impacts", "our impacts"], rows), ""]


def wp_summary(wp):
    """Per method: cases, how many reach ≤ 1e-14, the error and cost at the default tolerance."""
    rows, short = [], []
    by = defaultdict(list)
    for p in wp:
        by[(p["method"], p["problem"], p["law"])].append(p)
    per_method = defaultdict(lambda: {"cases": 0, "reach": 0, "errs": [], "ns": [], "ns8": []})
    for (m, prob, law), pts in sorted(by.items()):
        ref = [p for p in pts if math.isfinite(num(p["rel_error"]))]
        if not ref:
            continue
        d = per_method[m]
        d["cases"] += 1
        conv = [p for p in ref if p["status"] == "converged"]
        best_p = min(ref, key=lambda p: num(p["rel_error"]))
        if num(best_p["rel_error"]) <= 1e-14:
            d["reach"] += 1
        else:
            short.append((m, prob, law, fmt_err(num(best_p["rel_error"])), best_p["status"],
                          why_short(best_p, None)))
        default = [p for p in pts if num(p["tolerance"]) == 1e-13 and p["budget"] == "0"]
        if m == "nlopt":
            default = [p for p in pts if num(p["tolerance"]) == 1e-9 and p["budget"] == "0"]
        if default:
            d["errs"].append(num(default[0]["rel_error"]))
            d["ns"].append(num(default[0]["ns_per_solve"]))
        cheap = [p for p in conv if num(p["rel_error"]) <= 1e-8]
        if cheap:
            d["ns8"].append(min(num(p["ns_per_solve"]) for p in cheap))
    for m in METHOD_ORDER:
        if m not in per_method:
            continue
        d = per_method[m]
        med = lambda v: sorted(v)[len(v) // 2] if v else math.nan  # noqa: E731
        rows.append((m, d["cases"], d["reach"], fmt_err(max(d["errs"]) if d["errs"] else math.nan),
                     fmt_err(med(d["errs"])), fmt_ns(med(d["ns"])), fmt_ns(med(d["ns8"]))))
    return rows, short


def scaling_tables(runs):
    plate, rnd, thr = defaultdict(dict), defaultdict(dict), defaultdict(dict)
    for b in runs:
        if b["file"] != "scaling_bench.json" or b.get("error_occurred"):
            continue
        w = words(b.get("label", ""))
        prob, law = w.get("problem", ""), w.get("law", "")
        who = "Siconos " + law if b["name"].startswith("BM_Siconos_") else law
        if w.get("storage") == "small":
            who += " (small)"
        m = re.match(r"plate_c(\d+)$", prob)
        r = re.match(r"random_n(\d+)_c\d+$", prob)
        conv = b.get("converged", 1)
        cell = fmt_ns(cpu_ns(b)) + ("" if conv >= 1 else f" ({conv:.0%} conv.)")
        if m:
            plate[who][int(m.group(1))] = cell
        elif r:
            rnd[who][int(r.group(1))] = cell
        elif prob.startswith("bar_batch"):
            thr[law][int(b.get("threads", 1))] = b.get("items_per_second")
    return plate, rnd, thr


def grid(table, xs, first):
    rows = [[who] + [table[who].get(x, "") for x in xs] for who in sorted(table)]
    return md_table([first] + [str(x) for x in xs], rows)


def sparse_runs(runs):
    """The sparse benchmarks (bench/sparse_bench.cpp): the disk piles (square), the beds (four
    layers, growing in width) and Siconos's files, ours and Siconos's, as rows of (kind, contacts,
    ms, sweeps or iterations, residual by our measure)."""
    out = []
    for b in runs:
        if b["file"] != "sparse_bench.json" or b.get("error_occurred"):
            continue
        name = b["name"]
        if name.startswith("BM_Sparse_ReadFile"):
            continue
        # BM_Dense_Pile/<law>/...: the same pile handed to the dense solve_impact, ours too.
        dense = name.startswith("BM_Dense_")
        ours = name.startswith("BM_Sparse_") or dense
        # The file's part of the name; Google Benchmark appends "/iterations:N" to a fixed count.
        parts = [w for w in name.split("/") if not re.match(r"^(iterations|repeats):\d+$", w)]
        what = ("pile" if "Pile" in name else "bed" if "Bed" in name
                else parts[-1].replace(".dat", ""))
        solver = (f"ours: dense solve_impact, {parts[1]}" if dense else "ours: nsgs" if ours
                  else "Siconos: " + words(b.get("label", "")).get("solver", "?").replace("fc2d_", ""))
        status = b.get("label", "").split(" ")[0] if ours else "converged"
        out.append(dict(what=what, solver=solver, status=status, contacts=int(b.get("contacts", 0)),
                        ms=cpu_ns(b) / 1e6,
                        sweeps=int(b.get("sweeps", b.get("iterations", 0)) or 0),
                        residual=b.get("residual", b.get("our_residual"))))
    return out


def log_slope(pts):
    """The least-squares slope of log y against log x, or None with fewer than two points."""
    if len(pts) < 2:
        return None
    xs = [math.log(p[0]) for p in pts]
    ys = [math.log(p[1]) for p in pts]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


FAMILIES = (("pile", "square disk piles"), ("bed", "disk beds, 4 layers"))


def sparse_slopes(rows):
    """Per family of generated problems and solver: the slope of the CPU time per solve against
    contacts, over the solves that reached the tolerance (a stalled one stopped early), and of the
    time per sweep or iteration (what one costs, whatever their number), from 100 contacts on."""
    out = {}
    for what, _ in FAMILIES:
        for solver in ("ours: nsgs", "Siconos: nsgs"):
            done = [r for r in rows if r["what"] == what and r["solver"] == solver and
                    r["status"] == "converged"]
            solve = log_slope(sorted((r["contacts"], r["ms"]) for r in done))
            sweep = log_slope(sorted((r["contacts"], r["ms"] / r["sweeps"]) for r in done
                                     if r["sweeps"] > 0 and r["contacts"] >= 100))
            if solve is not None:
                out[(what, solver)] = (solve, sweep)
    return out


def plot_sparse(outdir, rows):
    """sparse_scaling.png: time per solve against contacts, log-log, ours and Siconos's."""
    if not rows:
        return
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    slopes = sparse_slopes(rows)
    for (what, family), (solver, style) in [(f, s) for f in FAMILIES for s in
                                            (("ours: nsgs", "-o"), ("Siconos: nsgs", "--x"))]:
        pts = sorted((r["contacts"], r["ms"]) for r in rows if r["what"] == what and r["solver"] == solver)
        if not pts:
            continue
        slope = slopes.get((what, solver), (None, None))[0]
        fill = "none" if what == "bed" else None
        ax.plot([p[0] for p in pts], [p[1] for p in pts], style, mfc=fill,
                label=f"{solver}, {family}" + (f" (slope {slope:.2f})" if slope else ""))
    files = [r for r in rows if r["what"] not in dict(FAMILIES)]
    for solver, marker in (("ours: nsgs", "s"), ("Siconos: nsgs", "^"), ("Siconos: cpg", "v"),
                           ("Siconos: enumeration", "D")):
        pts = sorted((r["contacts"], r["ms"]) for r in files if r["solver"] == solver)
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], marker, ms=6,
                    label=f"{solver}, Siconos's granular files")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("contacts")
    ax.set_ylabel("CPU ms per solve (to 1e-8)")
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7)
    ax.set_title("Sparse problems: cost of a solve against contacts")
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "sparse_scaling.png"), dpi=110)
    plt.close(fig)


def write_report(outdir, runs, contexts, wp, sim, pairs, cases):
    lines = []
    machine = ""
    mpath = os.path.join(outdir, "machine.txt")
    if os.path.exists(mpath):
        with open(mpath, encoding="utf-8") as f:
            machine = f.read().strip()
    lines += ["# Performance report", "",
              "Generated by `scripts/perf-report.sh` (do not edit by hand). Times are CPU time per "
              "call (Google Benchmark's `cpu_time`, or the sweep's fastest repetition), Release "
              "build.", "", "## Machine", "", "```", machine, "```", ""]
    sic = {c.get("siconos") for c in contexts.values() if c.get("siconos")}
    if sic:
        lines += [f"Siconos: {', '.join(sorted(sic))} (Debian packages).", ""]

    if pairs:
        urows, ratios = user_rows(runs, pairs)
        brows, rates, siconos_rate = batch_rows(runs, ratios)
        lines += ["## What a user gets", "",
                  "CPU time per impact on one core, from the data, with the admissibility "
                  "certificate: the prepared solver (`ImpactSolver`, set up once per "
                  "configuration, then `solve(q̇_A)`), the one-shot `solve_impact` (validation "
                  "included), and Siconos's fastest solver on the same problem, timed from "
                  "(M, W, q̇_A) in the same run. Ratio = Siconos's time over ours (> 1: we are "
                  "faster). `err`: distance of the answers' q̇_E to the closed form or the quad "
                  "reference, relative in the kinetic-energy norm; the plates and random bodies "
                  "have no reference, so there Siconos's `err` is its distance to our answer and "
                  "ours is the law's scaled residual (docs/solvers.md). Each time is the median "
                  "of the repetitions named under Machine; ± is the ratio's standard error from "
                  "the two times' spread over them (√(π/2) cv/√n each), so a ratio within two of "
                  "it of 1 is a tie on this machine. Each Siconos peer runs interleaved with ours "
                  "in one program (small_problems_bench for the small bodies, scaling_bench for "
                  "the plates and random bodies), so that a change of the machine's pace between "
                  "programs does not enter the ratios.", "",
                  md_table(["problem / law", "ours: prepared", "ratio", "ours: solve_impact",
                            "ratio", "Siconos, fastest from the data", "time", "its err",
                            "our err"], urows), ""]
        control = noise_control(runs)
        if control:
            worst = max(control, key=lambda c: c[2] / c[1])
            spread = [c[2] / c[1] - 1 for c in control]
            lines += [f"A control: {len(control)} pairs of benchmarks in this run time the same "
                      "work, solve_impact on one contact with and without check_uniqueness (one "
                      "contact's modes are settled in closed form either way). Their medians "
                      f"differed by {100 * min(spread):.0f} to {100 * max(spread):.0f} % "
                      f"({worst[0]}: {fmt_ns(worst[1])} and {fmt_ns(worst[2])}): a ratio "
                      "closer than that to its target is not settled by one run on this "
                      "machine.", ""]
        if brows:
            lines += ["Batches (`solve_batch`): 4,096 bar impacts at random angles and velocities, "
                      "each certified, on 1 and 2 threads; `small`: the stack-stored problems and "
                      "results, `heap`: the heap-stored ones; `prepared`: one bar at a fixed angle "
                      "and 4,096 velocities, solved on a prepared solver (`solve_batch(solver, "
                      "qdot_A)`), each answer kept as a whole result or (`columns`) as "
                      "`BatchAnswers`' columns." +
                      (f" Siconos solves the bar on one core at {siconos_rate / 1e6:.2f} M/s "
                       "(from its fastest time above)." if siconos_rate else ""), "",
                      md_table(["law", "storage", "1 thread", "2 threads", "second core"], brows),
                      ""]
        lines += ["### The public path's targets", "",
                  md_table(["what", "target", "measured", ""], public_path_targets(ratios, rates)),
                  ""]

    lines += ["## Targets", "", md_table(["what", "target", "measured", "", "benchmark"],
                                         target_rows(runs)), ""]

    hdr, rows = method_table(runs)
    if rows:
        lines += ["## Frémond: time per solve_impact by method", "",
                  "The suite of `bench/fremond_suite.hpp`; columns are the method requested "
                  "(`automatic`: the driver's own choice; a forced exact method answers with "
                  "whichever exact method applies, e.g. scalar Newton for `closed_form` on p ≠ 2). "
                  "Random cases cycle through 16 problems (the mean per solve). An empty cell: the "
                  "method does not apply (or, for NLopt, it does not stop on its own within 2000 "
                  "evaluations there).", "",
                  md_table(hdr, rows), ""]
        lines += ["### NLopt beside the default chain", "",
                  md_table(["problem", "law", "automatic", "its error", "NLopt", "its error",
                            "NLopt / automatic"], nlopt_beside(runs)), ""]

    if pairs:
        lines += ["## Against Siconos (same problems, same run)", "",
                  "Ratio = Siconos's CPU time over ours (> 1: we are faster; the issue asks for "
                  "≥ 10 at the same answer). Each ratio compares like with like. From the data: "
                  "Siconos's fastest solver on the pair, timed from (M, W, q̇_A) (G = WᵀM⁻¹W by "
                  "Eigen, then its driver), against our prepared solver (`ImpactSolver`: set up once "
                  "per configuration, then solved from q̇_A with its certificate), our public "
                  "`solve_impact` (which adds validation and the admissibility certificate) and "
                  "against the same work as "
                  "Siconos's (`FromData` / the law stage: the contact space, then the law). From "
                  "G: Siconos's fastest driver alone on its assembled problem (`_Driver`) against "
                  "our law's kernel, which also starts from G and D_A. `err`: each answer's "
                  "distance to the closed form or the quad reference (relative): the answers "
                  "agree to about −log10(max err) digits. Every pair: `siconos_ratios.csv`.", "",
                  md_table(["problem / law", "Siconos from the data (fastest)", "time", "err",
                            "ours: prepared", "ratio", "ours: solve_impact", "ratio",
                            "ours: same work", "ratio",
                            "Siconos from G (fastest driver)", "time", "ours: kernel", "ratio",
                            "our err"],
                           siconos_summary(pairs)), ""]
        if sim:
            lines += sim_siconos_rows(sim)

    if wp:
        srows, short = wp_summary(wp)
        lines += ["## Work-precision", "",
                  "Error: ‖q̇_E − q̇_E,ref‖_M / ‖q̇_A‖_M against the `__float128` reference; "
                  "tolerances 1e-2 … 1e-16 (NLopt: evaluation budgets, then its nlopt_tolerance). "
                  "Full data: `work_precision.csv`; plots: `work_precision.png`.", "",
                  md_table(["method", "cases", "reach ≤ 1e-14", "worst error at default tol.",
                            "median error at default tol.", "median time at default tol.",
                            "median time for ≤ 1e-8"], srows), ""]
        if short:
            lines += ["Where a method's best error stays above 1e-14:", "",
                      md_table(["method", "problem", "law", "best error", "status", "why"], short), ""]
        lines += ["![work-precision](work_precision_summary.png)", "",
                  "![work-precision, every case](work_precision.png)", ""]

    plate, rnd, thr = scaling_tables(runs)
    if plate:
        lines += ["## Scaling", "", "CPU time per solve on the plate touching at c points "
                  "(3 dofs; G singular from c = 4):", "", grid(plate, [1, 2, 4, 8, 16, 32], "law / contacts"),
                  "", "Random bodies, n dofs and n/2 contacts:", "",
                  grid(rnd, [6, 12, 18, 24, 30], "law / n"), ""]
        if thr:
            trows = []
            for law in sorted(thr):
                one, two = thr[law].get(1), thr[law].get(2)
                trows.append((law, f"{one:.3g}" if one else "–", f"{two:.3g}" if two else "–",
                              f"{two / one:.2f}" if one and two else "–"))
            lines += ["Throughput on a batch of 4096 independent bar impacts (impacts per second, "
                      "wall clock):", "", md_table(["law", "1 thread", "2 threads", "speed-up"], trows), ""]
        lines += ["![scaling](scaling.png)", ""]

    srows = sparse_runs(runs)
    if srows:
        plot_sparse(outdir, srows)
        slopes = sparse_slopes(srows)
        order = {"pile": 0, "bed": 1}
        suffix = {"converged": "", "converged(data)": " (converged to the file's digits)"}
        table = [(r["what"], r["contacts"], r["solver"] + suffix.get(r["status"], f" ({r['status']})"),
                  f"{r['ms']:.3g}", r["sweeps"],
                  fmt_err(num(str(r["residual"]))) if r["residual"] is not None else "–")
                 for r in sorted(srows, key=lambda r: (order.get(r["what"], 2), r["contacts"], r["solver"]))]
        slope_rows = [(family, solver, f"{solve:.2f}", f"{sweep:.2f}" if sweep is not None else "–")
                      for what, family in FAMILIES for solver in ("ours: nsgs", "Siconos: nsgs")
                      for solve, sweep in [slopes.get((what, solver), (None, None))] if solve is not None]
        lines += ["## Sparse problems", "",
                  "Newton + Coulomb (e = 0) on disk piles (square packings, G singular), on disk "
                  "beds (the same packing, four layers deep, growing in width) and on Siconos's own "
                  "granular-flow files (docs/sparse.md), to 1e-8 of the velocity scale (Siconos: "
                  "its own 1e-8, or 1e-6 on 2,020 contacts, where both solvers' sweeps stall near "
                  "1e-6; the two largest files keep 6 digits of G, which on the 2,020-contact one "
                  "determine the velocities to no better than 7e-6 of their scale: ours then ends "
                  "converged to the file's digits, docs/sparse.md#numbers-as-printed). `residual`: "
                  "every answer measured by our residual "
                  "(contact_residual). Siconos's 2-D driver takes G dense, so its sweep costs "
                  "contacts² where ours costs G's non-zeros. `dense solve_impact`: the small "
                  "piles handed to our dense solver as dense M and W (its default tolerance, "
                  "1e-9; Frémond + Coulomb with p = 2, k = 1), what a user of the dense form "
                  "pays beside the sparse one.", "",
                  md_table(["problem", "contacts", "solver", "CPU ms", "sweeps / iterations",
                            "residual"], table), ""]
        if slope_rows:
            lines += ["How the cost grows: the least-squares slope of log(time) against "
                      "log(contacts) over the solves that reached 1e-8, per solve and per sweep or "
                      "iteration (problems of 100 contacts and more). Our sweep costs what G's non-zeros "
                      "cost; the sweeps a solve needs grow with the height a blow crosses (the "
                      "piles), much less with the width (the beds).", "",
                      md_table(["problems", "solver", "slope per solve", "slope per sweep"],
                               slope_rows), ""]
        lines += ["![sparse scaling](sparse_scaling.png)", ""]

    if sim:
        srow = []
        for r in sim:
            srow.append((r["code"], r["law"], r["step"] if r["step"] != "0" else "–", r["steps"],
                         r["impacts"], fmt_ns(num(r["ns_per_step"])),
                         fmt_ns(num(r["ns_per_simulated_second"])),
                         fmt_err(num(r["energy_final_error"])), fmt_err(num(r["energy_error"])),
                         fmt_err(num(r["early_trajectory_error"])),
                         fmt_err(num(r["final_state_error"]))))
        lines += ["## Simulation work-precision", "",
                  "The paper's bar over 3 s; errors against the event-driven run of the same law "
                  "(energy relative to E(0); positions in m, θ times l). Siconos: its Moreau-Jean "
                  "with Newton + Coulomb (the law it implements).", "",
                  md_table(["code", "law", "h (s)", "steps", "impacts", "per step",
                            "per simulated s", "|ΔE(3 s)|", "max |ΔE(t)|", "max |Δq| t ≤ 0.5 s",
                            "|Δq(3 s)|"], srow), "",
                  "![simulation](simulation_work_precision.png)", ""]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(outdir, "report.md"), "w", encoding="utf-8") as f:
        f.write(text)
    return text


def readme_speed(urows, brows):
    """The README's speed table: a few rows of "What a user gets", the batch on two threads."""
    keep = {"bar_first_impact / newton_coulomb", "flat_bar / newton_coulomb",
            "bar_first_impact / fremond_p3_coulomb", "plate_c32 / newton_coulomb"}
    rows = [[r[0], r[1], r[3], r[6], r[4]] for r in urows if r[0] in keep]
    table = md_table(["problem / law", "prepared", "solve_impact", "Siconos (fastest)",
                      "Siconos / solve_impact"], rows)
    batch = [f"{r[0]} ({r[1]}): {r[3]} on two threads" for r in brows
             if r[1] in ("small", "prepared, small")]
    return table + ("\n\nBatches of 4,096 bar impacts: " + "; ".join(batch) + "." if batch else "")


def update_readme(readme, text):
    """Replaces what stands between the README's speed markers with `text`."""
    begin, end = "<!-- speed:begin -->", "<!-- speed:end -->"
    if not os.path.exists(readme):
        return
    with open(readme, encoding="utf-8") as f:
        page = f.read()
    if begin not in page or end not in page:
        return
    head, rest = page.split(begin, 1)
    _, tail = rest.split(end, 1)
    with open(readme, "w", encoding="utf-8") as f:
        f.write(head + begin + "\n" + text + "\n" + end + tail)


def update_docs(page, outdir, report):
    """Rewrites the performance page (docs/performance.md) from the report's machine, targets,
    Siconos and work-precision sections, with the plots copied to perf/ beside the page."""
    docs = os.path.join(os.path.dirname(os.path.abspath(page)), "perf")
    os.makedirs(docs, exist_ok=True)
    for png in ("work_precision_summary.png", "scaling.png", "simulation_work_precision.png",
                "sparse_scaling.png"):
        if os.path.exists(os.path.join(outdir, png)):
            shutil.copy(os.path.join(outdir, png), os.path.join(docs, png))
    keep = []
    for sec in re.split(r"(?=^## )", report, flags=re.M):
        if sec.startswith(("## Machine", "## What a user gets", "## Targets", "## Against Siconos",
                           "## Work-precision", "## Sparse problems")):
            keep.append(sec.replace("](work_precision_summary.png)", "](perf/work_precision_summary.png)")
                        .replace("](sparse_scaling.png)", "](perf/sparse_scaling.png)")
                        .replace("![work-precision, every case](work_precision.png)\n", ""))
    text = ("# Performance\n\nThe figures below were measured on the machine described under "
            "\"Machine\". `bash\nscripts/perf-report.sh` regenerates all of them (and more: "
            "scaling, throughput, the simulation's\nwork-precision, every CSV, the plots) into "
            "`out/perf/`; `--quick` runs a shorter version,\n`--docs` rewrites this page.\n\n" +
            "\n".join(keep) +
            "![scaling](perf/scaling.png)\n\n![simulation](perf/simulation_work_precision.png)\n")
    with open(page, "w", encoding="utf-8") as f:
        f.write(text)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("outdir")
    ap.add_argument("--docs", help="the performance page (docs/performance.md) to rewrite")
    args = ap.parse_args(argv)
    runs, contexts = load_benchmarks(args.outdir)
    wp = read_csv(os.path.join(args.outdir, "work_precision.csv"))
    sim = read_csv(os.path.join(args.outdir, "simulation_work_precision.csv"))
    write_benchmarks_csv(args.outdir, runs)
    pairs = siconos_pairs(runs)
    write_ratios_csv(args.outdir, pairs)
    cases = plot_work_precision(args.outdir, wp)
    plot_scaling(args.outdir, runs)
    plot_simulation(args.outdir, sim)
    report = write_report(args.outdir, runs, contexts, wp, sim, pairs, cases)
    if args.docs:
        update_docs(args.docs, args.outdir, report)
        if pairs:
            urows, ratios = user_rows(runs, pairs)
            brows, _, _ = batch_rows(runs, ratios)
            readme = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(args.docs))),
                                  "README.md")
            update_readme(readme, readme_speed(urows, brows))
    print(f"wrote {args.outdir}/report.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
