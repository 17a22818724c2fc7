#!/usr/bin/python3
"""Laws fitted to measured impacts, drawn (docs/measurements.md#figures).

    /usr/bin/python3 scripts/fit_figures.py DATA.json --law newton_coulomb,fremond_coulomb --out DIR

Fits each law family on the measured-impact file (fremond.fit_laws, cross-validated), prints the
ranking, and writes into DIR:

- predicted_vs_measured.png: each measured component against each fitted law's prediction, one
  panel per component, the diagonal for a perfect law;
- residuals.png: the weighted residuals (in sigmas) of each law against the first contact's angle
  of incidence (from the normal) and its speed before the impact;
- restitution.png: the normal restitution -D_NE/D_NA of the first contact against its impact
  speed |D_NA|, measured (where every component of qdot_E was measured) and as each fitted law
  predicts it: Newton's constant e beside the curves of laws whose restitution varies with speed;
- ranking.csv: family, parameters, training and held-out RMS.

Runs with the bindings of the build tree (PYTHONPATH=build/python) and Debian's matplotlib.
"""
import argparse
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import fremond as f  # noqa: E402


def first_contact(mi):
    """(D_NA, D_TA) of the impact's first contact, from its data."""
    pb = mi.problem
    d_n = float(pb.W_N[:, 0] @ pb.qdot_A + (pb.w_N[0] if len(pb.w_N) else 0.0))
    d_t = 0.0
    if pb.W_T.shape[1]:
        d_t = float(pb.W_T[:, 0] @ pb.qdot_A + (pb.w_T[0] if len(pb.w_T) else 0.0))
    return d_n, d_t


def normal_after(mi, qdot_E):
    pb = mi.problem
    return float(pb.W_N[:, 0] @ qdot_E + (pb.w_N[0] if len(pb.w_N) else 0.0))


def label(r):
    values = ", ".join(f"{n}={v:.4g}" for n, v in zip(r.names, r.values))
    return f"{r.family} ({values})"


def draw(data, fits, out):
    predictions = [f.predict(data, r.law) for r in fits]
    n = max(len(mi.qdot_E) for mi in data)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]

    fig, axes = plt.subplots(1, n, figsize=(4.2 * n, 4), squeeze=False)
    for j in range(n):
        ax = axes[0][j]
        measured = [mi.qdot_E[j] for mi in data if j < len(mi.qdot_E) and mi.mask[j]]
        for k, (r, p) in enumerate(zip(fits, predictions)):
            pts = [(mi.qdot_E[j], q[j]) for mi, q in zip(data, p.qdot_E)
                   if j < len(mi.qdot_E) and mi.mask[j]]
            if pts:
                x, y = zip(*pts)
                ax.plot(x, y, ".", color=colours[k % len(colours)], label=label(r))
        if measured:
            lo, hi = min(measured), max(measured)
            ax.plot([lo, hi], [lo, hi], "k-", lw=0.8)
        ax.set_xlabel(f"measured qdot_E[{j}]")
        ax.set_ylabel("predicted")
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "predicted_vs_measured.png"), dpi=120)
    plt.close(fig)

    incidence, speed = [], []
    for mi in data:
        d_n, d_t = first_contact(mi)
        incidence.append(math.degrees(math.atan2(abs(d_t), -d_n)))
        speed.append(math.hypot(d_n, d_t))
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for k, (r, p) in enumerate(zip(fits, predictions)):
        for ax, x in zip(axes, (incidence, speed)):
            xs, ys = [], []
            for xi, res in zip(x, p.residuals):
                for v in res:
                    if math.isfinite(v):
                        xs.append(xi)
                        ys.append(v)
            ax.plot(xs, ys, ".", color=colours[k % len(colours)], label=r.family)
    axes[0].set_xlabel("angle of incidence from the normal (deg)")
    axes[1].set_xlabel("contact speed before the impact")
    for ax in axes:
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_ylabel("residual (sigmas)")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "residuals.png"), dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 4))
    approaching = [(i, first_contact(mi)[0]) for i, mi in enumerate(data)]
    approaching = [(i, d) for i, d in approaching if d < 0]
    order = sorted(approaching, key=lambda t: -t[1])
    full = [(-d, -normal_after(data[i], data[i].qdot_E) / d) for i, d in order if all(data[i].mask)]
    if full:
        x, y = zip(*full)
        ax.plot(x, y, "k.", label="measured")
    for k, (r, p) in enumerate(zip(fits, predictions)):
        pts = [(-d, -normal_after(data[i], p.qdot_E[i]) / d) for i, d in order]
        x, y = zip(*pts)
        ax.plot(x, y, "-", color=colours[k % len(colours)], label=label(r))
    ax.set_xlabel("impact speed |D_NA|")
    ax.set_ylabel("normal restitution -D_NE/D_NA")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "restitution.png"), dpi=120)
    plt.close(fig)

    with open(os.path.join(out, "ranking.csv"), "w", encoding="utf-8") as csv:
        csv.write("family,parameters,training_rms,heldout_rms\n")
        for r in fits:
            params = " ".join(f"{n}={v:.17g}" for n, v in zip(r.names, r.values))
            csv.write(f"{r.family},{params},{r.training_rms:.6g},{r.heldout_rms:.6g}\n")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("data", help="the measured-impact file (JSON)")
    parser.add_argument("--law", required=True, help="law families, comma-separated")
    parser.add_argument("--out", required=True, help="directory for the figures")
    parser.add_argument("--folds", type=int, default=5)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(argv)
    with open(args.data, encoding="utf-8") as fh:
        data = f.parse_measurements(fh.read())
    families = [s for s in args.law.split(",") if s]
    os.makedirs(args.out, exist_ok=True)
    fits = f.fit_laws(data, families, folds=args.folds, seed=args.seed)
    for r in fits:
        print(f"{label(r)}: training {r.training_rms:.3g}, held out {r.heldout_rms:.3g} sigmas")
    draw(data, fits, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
