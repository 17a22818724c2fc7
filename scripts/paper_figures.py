#!/usr/bin/python3
"""The paper's comparison on the bar, reproduced: every figure, and the table of the five laws.

Runs the paper's scene (the paper's Fig. 1) under each of its five laws, and under Stronge's
energetic restitution with Coulomb friction (not in the paper), through the Python bindings, prints
a table (per law: impacts, energy before and after each of the first impacts, whether every impact
was admissible, which inequality failed), and writes into the output folder:

  fig02_newton_animation.gif, fig02_newton_poses.png, fig03_newton_energy.png
  fig04_newton_coulomb_animation.gif, ..._poses.png, fig05_newton_coulomb_energy.png
  fig06_poisson_coulomb_animation.gif, ..._poses.png, fig07_poisson_coulomb_energy.png
  fig08_normal_restitution.png                  D_NE against |D_NA| for several p
  fig09_tangential_dead_zone.png                D_TE against D_TA, viscous dead zone
  fig10_fremond_coulomb_animation.gif, ..._poses.png, fig11_fremond_coulomb_energy.png
  fig12_fremond_viscous_animation.gif, ..._poses.png, fig13_fremond_viscous_energy.png
  stronge_coulomb_animation.gif, ..._poses.png, stronge_coulomb_energy.png  (not in the paper)
  <law>_impacts.csv                             the impact log of each run
  comparison.txt, comparison.json               the table, as printed and as data

Usage: paper_figures.py [--out DIR] [--t-end SECONDS] [--first N] [--no-animations]
Needs the module built (PYTHONPATH=build/python, or --build DIR).
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import os
import sys
import textwrap
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# The paper's figures of each law: (animation and poses, energy); None for a law the paper does not
# have, whose files are named by the law alone.
LAWS = [
    ("newton", 2, 3),
    ("newton_coulomb", 4, 5),
    ("poisson_coulomb", 6, 7),
    ("fremond_coulomb", 10, 11),
    ("fremond_viscous", 12, 13),
    ("stronge_coulomb", None, None),
]


def figure_name(n, law, kind):
    """fig04_newton_coulomb_poses.png for the paper's figure 4; stronge_coulomb_poses.png without."""
    return f"fig{n:02d}_{law}_{kind}" if n is not None else f"{law}_{kind}"


def figure_title(n, what):
    return f"Fig. {n}: {what}" if n is not None else f"Not in the paper: {what}"
FIG8_P = [1.5, 2.0, 2.5, 3.0, 4.0]


def import_fremond(build: Path | None):
    try:
        import fremond  # noqa: F401
    except ImportError:
        sys.path.insert(0, str((build or ROOT / "build") / "python"))
    import fremond

    return fremond


def wrap(title, width=80):
    """A long title over several lines."""
    return "\n".join(textwrap.wrap(title, width))


def law_row(f, name, scene, run, n_first):
    impacts = [im for im in run.impacts if im.kind != f.ImpactKind.accumulation]
    bad = [im for im in impacts if not im.admissible]
    failed = []
    for im in bad:
        failed.append({
            "impact": impacts.index(im) + 1,
            "t": im.t,
            "inequality": str(im.failed),
            "energy_A": im.energy_A,
            "energy_E": im.energy_E,
        })
    return {
        "law": name,
        "description": f.plots.describe_law(scene.law),
        "status": str(run.result.status),
        "impacts": int(run.result.impacts),
        "accumulations": int(run.result.accumulations),
        "first_impacts": [{"t": im.t, "energy_A": im.energy_A, "energy_E": im.energy_E,
                           "admissible": bool(im.admissible), "failed": str(im.failed)}
                          for im in impacts[:n_first]],
        "all_admissible": not bad,
        "inadmissible": failed,
        "energy_initial": run.result.energy_initial,
        "energy_final": run.result.energy_final,
    }


def table_text(rows, n_first, t_end):
    head = (f"The paper's bar (the paper's Fig. 1) under its five laws and Stronge's, "
            f"t = 0 to {t_end:g} s; "
            f"energy ½q̇ᵀMq̇ + mgy in J\n")
    cols = ["law", "impacts", f"energy before→after, impacts 1..{n_first}", "admissible",
            "failed"]
    lines = []
    for r in rows:
        energies = " | ".join(f"{i['energy_A']:.3f}→{i['energy_E']:.3f}"
                              + ("!" if not i["admissible"] else "") for i in r["first_impacts"])
        if r["all_admissible"]:
            adm, failed = "all", "-"
        else:
            adm = f"no ({len(r['inadmissible'])})"
            first = r["inadmissible"][0]
            gain = first["energy_E"] - first["energy_A"]
            failed = (f"{first['inequality']} at impact {first['impact']} "
                      f"(t = {first['t']:.3f} s, {gain:+.3f} J)")
        lines.append([r["law"], str(r["impacts"]), energies, adm, failed])
    widths = [max(len(c), *(len(l[i]) for l in lines)) for i, c in enumerate(cols)]
    fmt = lambda cells: "  ".join(c.ljust(w) for c, w in zip(cells, widths)).rstrip()  # noqa: E731
    out = [head, fmt(cols), fmt(["-" * w for w in widths])]
    out += [fmt(l) for l in lines]
    out.append("")
    out.append("! marks an impact that creates energy or otherwise fails the docs/concepts.md certificate; "
               "total_15 is (15), -P·z ≥ 0, i.e. T_E ≤ T_A (eq. 9).")
    for r in rows:
        out.append(f"{r['law']}: {r['description']}")
    return "\n".join(out) + "\n"


def write_impacts_csv(path, run):
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["index", "t", "kind", "contacts", "energy_A", "energy_E", "admissible",
                    "failed", "P_N", "P_T", "D_NA", "D_NE", "D_TA", "D_TE", "solver_status"])
        for im in run.impacts:
            join = lambda v: " ".join(repr(float(x)) for x in v)  # noqa: E731
            w.writerow([im.index, repr(im.t), str(im.kind), " ".join(map(str, im.contacts)),
                        repr(im.energy_A), repr(im.energy_E), int(im.admissible), str(im.failed),
                        join(im.P_N), join(im.P_T), join(im.D_NA), join(im.D_NE), join(im.D_TA),
                        join(im.D_TE), str(im.solver.status)])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path, default=Path(os.environ.get("FREMOND_OUT", "out/paper")),
                    help="output folder (default out/paper, or $FREMOND_OUT)")
    ap.add_argument("--t-end", type=float, default=3.0, help="simulated time (s), default 3")
    ap.add_argument("--first", type=int, default=3,
                    help="how many first impacts the table shows, default 3")
    ap.add_argument("--no-animations", action="store_true", help="skip the GIFs (faster)")
    ap.add_argument("--build", type=Path, help="build folder holding python/fremond")
    args = ap.parse_args(argv)
    if not (args.t_end > 0 and math.isfinite(args.t_end)):
        ap.error(f"--t-end must be a finite number > 0, got {args.t_end}")
    if args.first < 1:
        ap.error(f"--first must be >= 1, got {args.first}")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    f = import_fremond(args.build)
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    written = []

    def save(fig, name):
        fig.savefig(out / name, dpi=110)
        plt.close(fig)
        written.append(name)

    rows = []
    started = time.time()
    for name, fig_motion, fig_energy in LAWS:
        scene = f.paper_bar_scene(f.PaperLaw(name))
        run = f.simulate(scene, f.SimulationOptions(t_end=args.t_end))
        if not run.result.ok():
            print(f"paper_figures: {name}: the run stopped early: {run.result.message}",
                  file=sys.stderr)
        law_text = f.plots.describe_law(scene.law)
        save(f.plots.energy_plot(
            run, title=wrap(figure_title(fig_energy, f"energy, {law_text}"), 110)),
            figure_name(fig_energy, name, "energy.png"))
        save(f.plots.poses_plot(
            run, scene, title=wrap(figure_title(fig_motion, f"motion, {law_text}"), 65)),
            figure_name(fig_motion, name, "poses.png"))
        if not args.no_animations:
            gif = figure_name(fig_motion, name, "animation.gif")
            f.plots.animate(run, scene, out / gif,
                            title=wrap(figure_title(fig_motion, law_text), 75))
            written.append(gif)
        write_impacts_csv(out / f"{name}_impacts.csv", run)
        written.append(f"{name}_impacts.csv")
        rows.append(law_row(f, name, scene, run, args.first))

    # Fig. 8: a point mass, normal law alone, the same k for every p (the library's default, 4 in
    # the library's scaling: the paper does not give its own).
    speeds = [5.0 * i / 200 for i in range(201)]
    curves = [f.normal_restitution_curve(f.NormalCurveParameters(p=p), speeds)
              for p in FIG8_P]
    save(f.plots.restitution_plot(
        curves, title="Fig. 8: Frémond's normal law on a point mass (m = 1 kg), "
                      "D_NE against |D_NA| for several p\n"
                      "φ_N = k|z|^p/p, k = 4 in the library's scaling (paper's k = 4·2^(1−p))"),
        "fig08_normal_restitution.png")

    # Fig. 9: the viscous dead zone with the paper's r = 0.4, k_T = 0.75, q = 2 (paper's scaling).
    fig9 = f.TangentialCurveParameters.paper_figure(f.Scaling.paper)
    d_ta = [-1.5 + 3.0 * i / 300 for i in range(301)]
    tcurve = f.tangential_curve(fig9, d_ta)
    save(f.plots.tangential_plot(
        tcurve, title="Fig. 9: viscous dead zone on a point mass (m = 1 kg), D_TE against D_TA\n"
                      "paper's r = 0.4, k_T = 0.75, q = 2 (the library's r = 0.2, k_T = 1.5)\n"
                      f"normal law fixed: k = {fig9.in_library_scaling().k_N:g}, p = {fig9.p:g}, "
                      f"D_NA = {fig9.D_NA:g} m/s"),
        "fig09_tangential_dead_zone.png")

    table = table_text(rows, args.first, args.t_end)
    print(table, end="")
    (out / "comparison.txt").write_text(table)
    (out / "comparison.json").write_text(json.dumps(
        {"t_end": args.t_end, "laws": rows, "files": sorted(written)}, indent=1))
    files = sorted(p.name for p in out.iterdir() if p.is_file())
    print(f"\n{out} holds {len(files)} files ({time.time() - started:.1f} s):")
    for name in files:
        print(f"  {name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
