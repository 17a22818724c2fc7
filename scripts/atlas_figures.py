#!/usr/bin/python3
"""The law atlas of the paper's bar: where each law creates energy, as heat maps and a table.

Sweeps the bar's lower end over its angle theta and the direction psi of its velocity before the
impact (docs/atlas.md) under each law, through the Python bindings, and writes into the output
folder:

  atlas_energy.png     (T_E - T_A)/T_A per law at mu = 1, e = 0.9: the line of no energy change
                       (solid) and the stick/slide boundary (dashed); the paper's first impact
                       marked with a star
  atlas_modes.png      stick, slide or reversal after the impact, per law
  atlas_distance.png   each law's distance from the reference law's answer
  atlas_summary.txt    the fraction of the map where each law creates energy, as mu varies (e =
  atlas_summary.json   0.9) and as e varies (mu = 1); the same as data

Usage: atlas_figures.py [--out DIR] [--grid N] [--laws LIST] [--mu LIST] [--e LIST]
Needs the module built (PYTHONPATH=build/python, or --build DIR).
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
LAWS = ["newton_coulomb", "poisson_coulomb", "fremond", "stronge_coulomb"]
TITLES = {
    "newton": "Newton", "poisson": "Poisson", "newton_coulomb": "Newton + Coulomb",
    "poisson_coulomb": "Poisson + Coulomb", "fremond": "Frémond p = 3 + Coulomb",
    "stronge": "Stronge", "stronge_coulomb": "Stronge + Coulomb",
}
# A gain of kinetic energy beyond the certificate's default tolerance (1e-9 of T_A) is a creation.
CREATES = 1e-9


def import_fremond(build: Path | None):
    try:
        import fremond  # noqa: F401
    except ImportError:
        sys.path.insert(0, str((build or ROOT / "build") / "python"))
    import fremond

    return fremond


def number_list(text):
    return [float(v) for v in text.split(",") if v.strip()]


def created_fraction(a, law, value):
    """Fraction of the converged points of (law, value) where the law creates energy, and the
    fraction of the map that did not converge (no solution, or a stalled solve)."""
    import numpy as np

    ratio = a["energy_ratio"][law, value]
    solved = a["status"][law, value] == list(a["status_names"]).index("converged")
    n = max(int(solved.sum()), 1)
    return float(np.sum(ratio[solved] > CREATES)) / n, 1.0 - solved.mean()


def first_impact_point(f):
    """(theta, psi) of the paper's bar at its first impact."""
    scene = f.paper_bar_scene(f.PaperLaw.newton_coulomb)
    first = f.first_impact(scene, 10.0)
    theta = first.state.q[2]
    l = 0.5
    qd = first.state.qdot
    D_NA = qd[1] - l * math.cos(theta) * qd[2]
    D_TA = qd[0] + l * math.sin(theta) * qd[2]
    return theta, math.atan2(D_NA, D_TA)


def heat_maps(plt, a, star, what, title):
    """One panel per law: `what` ('energy', 'mode' or 'distance') over (psi, theta)."""
    import numpy as np
    from matplotlib.colors import BoundaryNorm, ListedColormap, TwoSlopeNorm

    laws = list(a["laws"])
    cols = min(len(laws), 2)
    rows = math.ceil(len(laws) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(6.2 * cols, 4.6 * rows), squeeze=False,
                             constrained_layout=True)
    psi, theta = np.degrees(a["psi"]), np.degrees(a["theta"])
    extent = (psi[0], psi[-1], theta[0], theta[-1])
    stick = list(a["mode_names"]).index("stick")
    for k, ax in enumerate(axes.flat):
        if k >= len(laws):
            ax.axis("off")
            continue
        ratio = a["energy_ratio"][k, 0, 0]
        mode = a["mode"][k, 0, 0]
        if what == "energy":
            # Losses and gains each on their own scale: a gain is small beside the losses.
            low = min(float(np.nanmin(ratio)), -1e-12)
            high = max(float(np.nanmax(ratio)), 1e-3 * -low)
            im = ax.imshow(ratio, origin="lower", extent=extent, aspect="auto", cmap="RdBu_r",
                           norm=TwoSlopeNorm(0.0, low, high))
            fig.colorbar(im, ax=ax, label="(T_E − T_A) / T_A")
        elif what == "mode":
            cmap = ListedColormap(["#4c72b0", "#dd8452", "#55a868", "#bbbbbb"])
            im = ax.imshow(mode, origin="lower", extent=extent, aspect="auto", cmap=cmap,
                           norm=BoundaryNorm([-0.5, 0.5, 1.5, 2.5, 3.5], 4))
            cb = fig.colorbar(im, ax=ax, ticks=[0, 1, 2, 3])
            cb.ax.set_yticklabels(list(a["mode_names"]))
        else:
            im = ax.imshow(a["distance"][k, 0, 0], origin="lower", extent=extent, aspect="auto",
                           cmap="viridis")
            fig.colorbar(im, ax=ax, label=f"‖q̇_E − q̇_E,{a['reference']}‖_M / ‖q̇_A‖_M")
        # The region boundaries: no energy change, and sticking against not sticking.
        if np.nanmax(ratio) > 0 > np.nanmin(ratio):
            ax.contour(psi, theta, ratio, levels=[0.0], colors="k", linewidths=1.2)
        is_stick = (mode == stick).astype(float)
        if 0 < is_stick.mean() < 1:
            ax.contour(psi, theta, is_stick, levels=[0.5], colors="w" if what != "mode" else "k",
                       linewidths=1.0, linestyles="--")
        ax.plot(np.degrees(star[1]), np.degrees(star[0]), marker="*", color="gold",
                markeredgecolor="k", markersize=13)
        ax.set_title(TITLES.get(laws[k], laws[k]))
        ax.set_xlabel("ψ: direction of (D_TA, D_NA) before the impact (°)")
        ax.set_ylabel("θ: the bar's angle (°)")
    fig.suptitle(title)
    return fig


def summary_text(mu_rows, e_rows, laws, mus, es):
    def table(rows, name, values):
        head = f"{'law':<18}" + "".join(f"{name + ' = ' + format(v, 'g'):>12}" for v in values)
        lines = [head, "-" * len(head)]
        for law in laws:
            lines.append(f"{law:<18}" + "".join(f"{100 * r[0]:>11.2f}%" for r in rows[law]))
        return "\n".join(lines)

    return ("Fraction of the bar's impact configurations (θ × ψ, spin 0) where each law creates\n"
            "kinetic energy ((T_E − T_A)/T_A > 1e-9), among the points solved.\n\n"
            f"As μ varies (e = 0.9):\n{table(mu_rows, 'mu', mus)}\n\n"
            f"As e varies (μ = 1):\n{table(e_rows, 'e', es)}\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path, default=Path(os.environ.get("FREMOND_OUT", "out/atlas")),
                    help="output folder (default out/atlas, or $FREMOND_OUT)")
    ap.add_argument("--grid", type=int, default=200, help="cells along θ and ψ, default 200")
    ap.add_argument("--laws", default=",".join(LAWS), help="comma-separated law names")
    ap.add_argument("--mu", type=number_list, default=[0.1, 0.3, 0.5, 1.0, 2.0],
                    help="μ of the summary, comma-separated")
    ap.add_argument("--e", type=number_list, default=[0.3, 0.5, 0.7, 0.9],
                    help="e of the summary, comma-separated, in (0, 1)")
    ap.add_argument("--build", type=Path, help="build folder holding python/fremond")
    args = ap.parse_args(argv)
    if not 2 <= args.grid <= 2000:
        ap.error(f"--grid must lie in [2, 2000], got {args.grid}")
    laws = [name for name in args.laws.split(",") if name]

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    f = import_fremond(args.build)
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    started = time.time()
    common = dict(laws=laws, theta_count=args.grid, psi_count=args.grid, theta_max=math.pi / 2)
    try:
        maps = f.atlas(values=[1.0], e=0.9, **common)
        by_mu = f.atlas(values=args.mu, e=0.9, **common)
        by_e = f.atlas(parameter="e", values=args.e, mu=1.0, **common)
    except ValueError as err:
        ap.error(str(err))

    star = first_impact_point(f)
    for what, name, title in [
            ("energy", "atlas_energy.png", "Energy change of the paper's bar's impacts, μ = 1, "
                                            "e = 0.9 (black: no change; dashed: stick/slide)"),
            ("mode", "atlas_modes.png", "Contact mode after the impact, μ = 1, e = 0.9"),
            ("distance", "atlas_distance.png",
             f"Distance from {TITLES.get(str(maps['reference']), maps['reference'])}'s answer")]:
        fig = heat_maps(plt, maps, star, what, title + f"  (★: the paper's first impact, "
                                                       f"speed {maps['speed']:.3g} m/s)")
        fig.savefig(out / name, dpi=110)
        plt.close(fig)

    mu_rows = {law: [created_fraction(by_mu, k, v) for v in range(len(args.mu))]
               for k, law in enumerate(laws)}
    e_rows = {law: [created_fraction(by_e, k, v) for v in range(len(args.e))]
              for k, law in enumerate(laws)}
    text = summary_text(mu_rows, e_rows, laws, args.mu, args.e)
    print(text, end="")
    (out / "atlas_summary.txt").write_text(text)
    (out / "atlas_summary.json").write_text(json.dumps({
        "grid": args.grid, "speed": maps["speed"], "first_impact": {"theta": star[0], "psi": star[1]},
        "by_mu": {"e": 0.9, "mu": args.mu, "fremond_k_N": list(by_mu["fremond_k_N"]),
                  "created": {k: [r[0] for r in v] for k, v in mu_rows.items()},
                  "unsolved": {k: [r[1] for r in v] for k, v in mu_rows.items()}},
        "by_e": {"mu": 1.0, "e": args.e, "fremond_k_N": list(by_e["fremond_k_N"]),
                 "created": {k: [r[0] for r in v] for k, v in e_rows.items()},
                 "unsolved": {k: [r[1] for r in v] for k, v in e_rows.items()}},
    }, indent=1, default=float))
    print(f"\n{out}: atlas_energy.png, atlas_modes.png, atlas_distance.png, atlas_summary.txt, "
          f"atlas_summary.json ({time.time() - started:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
