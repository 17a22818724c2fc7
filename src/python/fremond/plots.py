"""Plots and animations of the paper's figures, drawn from the library's results.

Nothing here computes physics: every number comes from a ``Simulation`` (``fremond.simulate``) or
a ``Curve`` (``fremond.normal_restitution_curve`` / ``fremond.tangential_curve``); this module only
picks what to draw and labels it.

- ``energy_plot``       energy against time, every impact marked, inadmissible ones flagged
                        (paper Figs. 3, 5, 7, 11, 13);
- ``poses_plot``        the body's motion as a strip of overlaid poses (Figs. 2, 4, 6, 10, 12);
- ``animate``           the same motion as an animated GIF;
- ``restitution_plot``  D_NE against |D_NA| for several p (Fig. 8);
- ``tangential_plot``   D_TE against D_TA for the viscous dead zone (Fig. 9);
- ``describe_law``      a title naming a law and its parameters.

matplotlib (and Pillow for GIFs) is imported only when a function needs it.
"""
from __future__ import annotations

import math

import numpy as np

from . import _fremond as _f

__all__ = [
    "describe_law",
    "energy_curve",
    "energy_jumps",
    "body_outline",
    "energy_plot",
    "poses_plot",
    "animate",
    "restitution_plot",
    "tangential_plot",
]

# Colours used throughout: admissible impacts, inadmissible ones, Moreau-Jean phases.
ADMISSIBLE = "#1b7837"
INADMISSIBLE = "#d7191c"
ACCUMULATION = "#777777"
MOREAU_JEAN = "#fdb863"


def _g(x: float) -> str:
    """A number for a label: four significant digits, no trailing zeros."""
    return f"{x:.4g}"


def _one(values) -> str:
    """A per-contact coefficient as text: one value, or the list."""
    values = list(values)
    if all(v == values[0] for v in values):
        return _g(values[0])
    return "[" + ", ".join(_g(v) for v in values) + "]"


def _potential_text(p, scaling_note: bool) -> str:
    if isinstance(p, _f.PowerPotential):
        text = f"p = {_g(p.p)}, k_N = {_g(p.k)}"
        if scaling_note:
            text += f" (paper's k_N = {_g(p.k * 2.0 ** (1.0 - p.p))})"
        return text
    if isinstance(p, _f.DeadZonePowerPotential):
        text = f"q = {_g(p.q)}, k_T = {_g(p.k)}, r = {_g(p.r)}"
        if scaling_note:
            text += f" (paper's k_T = {_g(p.k * 2.0 ** (1.0 - p.q))}, r = {_g(2.0 * p.r)})"
        return text
    return p.describe()


def describe_law(law, scaling_note: bool = True) -> str:
    """A human title for an ImpactLaw with its parameters, e.g. 'Newton + Coulomb (e = 0.9, μ = 1)'.

    Frémond's constants are the library's (potentials of the mean velocity); with ``scaling_note`` the
    paper's values (docs/laws.md) follow in parentheses.
    """
    t = law.type
    if t == "newton":
        return f"Newton, frictionless (e = {_one(law.e)})"
    if t == "poisson":
        return f"Poisson, frictionless (e = {_one(law.e)})"
    if t == "newton_coulomb":
        return f"Newton + Coulomb (e = {_one(law.e)}, μ = {_one(law.mu)})"
    if t == "poisson_coulomb":
        return f"Poisson + Coulomb (e = {_one(law.e)}, μ = {_one(law.mu)})"
    if t == "stronge":
        return f"Stronge, frictionless (e* = {_one(law.e)})"
    if t == "stronge_coulomb":
        return f"Stronge + Coulomb (e* = {_one(law.e)}, μ = {_one(law.mu)})"
    normal = law.normal[0] if law.normal else None
    parts = [_potential_text(normal, scaling_note)] if normal is not None else []
    if law.tangential == _f.TangentialLaw.coulomb:
        parts.append(f"μ = {_one(law.mu)}")
        return "Frémond + Coulomb (" + "; ".join(parts) + ")"
    if law.tangential == _f.TangentialLaw.potential:
        parts.append(_potential_text(law.tangential_potential[0], scaling_note))
        return "Frémond, viscous dead zone (" + "; ".join(parts) + ")"
    return "Frémond, normal law only (" + "; ".join(parts) + ")"


def energy_curve(run):
    """(t, E): the energy curve exactly as energy_plot draws it, one point per trajectory sample.

    An impact contributes two samples at the same instant, just before and just after it, so the
    curve jumps there by the impact's energy change.
    """
    return np.asarray(run.t, dtype=float), np.asarray(run.energy, dtype=float)


def energy_jumps(t, energy):
    """The jumps of an energy curve: (t_i, E_before, E_after) wherever two samples share a time."""
    t = np.asarray(t)
    energy = np.asarray(energy)
    at = np.nonzero(t[1:] == t[:-1])[0]
    return [(float(t[i]), float(energy[i]), float(energy[i + 1])) for i in at]


def body_outline(scene, q):
    """World coordinates (k x 2) of the body's contact points at configuration q = (x, y, θ).

    For the bar these are its two ends; a polygonal body gives its corners in order.
    """
    x, y, th = (float(v) for v in q)
    c, s = math.cos(th), math.sin(th)
    pts = [np.asarray(p.r, dtype=float) for p in scene.body.points]
    return np.array([[x + c * r[0] - s * r[1], y + s * r[0] + c * r[1]] for r in pts])


def _frame(scene, q, margin: float = 0.3):
    """The axes' limits (x_lo, x_hi, y_lo, y_hi) that hold every pose of the run, disks whole, and
    the obstacles under them, whatever the direction of gravity's ground (slopes, walls)."""
    if not len(q):
        return -1.0, 1.0, -0.5, 1.5
    step = max(1, len(q) // 2000)
    pts = np.vstack([body_outline(scene, qi) for qi in q[::step]] + [body_outline(scene, q[-1])])
    reach = max([float(p.radius) for p in scene.body.points] + [0.0])
    x_lo, x_hi = pts[:, 0].min() - reach, pts[:, 0].max() + reach
    y_lo, y_hi = pts[:, 1].min() - reach, pts[:, 1].max() + reach
    for plane in scene.obstacles:  # the obstacle's edge across the body's span, if it is near
        n = np.asarray(plane.normal, dtype=float)
        if abs(n[1]) > 1e-12:
            ys = (plane.offset - n[0] * np.array([x_lo, x_hi])) / n[1]
            y_lo = min(y_lo, max(ys.min(), y_lo - 1.0))
            y_hi = max(y_hi, min(ys.max(), y_hi + 1.0))
    pad = max(margin, 0.1 * max(x_hi - x_lo, y_hi - y_lo))
    return x_lo - pad, x_hi + pad, y_lo - pad, y_hi + pad


def _draw_obstacles(ax, scene, frame):
    """Each half-plane n·x ≥ offset: its edge, and its forbidden side shaded, within the frame."""
    x_lo, x_hi, y_lo, y_hi = frame
    corners = np.array([[x_lo, y_lo], [x_hi, y_lo], [x_hi, y_hi], [x_lo, y_hi]])
    for plane in scene.obstacles:
        n = np.asarray(plane.normal, dtype=float)
        n = n / np.linalg.norm(n)
        offset = float(plane.offset) / float(np.linalg.norm(plane.normal))
        # The frame's rectangle clipped to n·x ≤ offset (Sutherland-Hodgman, one edge).
        inside = corners @ n <= offset
        poly = []
        for i in range(4):
            a, b = corners[i], corners[(i + 1) % 4]
            if inside[i]:
                poly.append(a)
            if inside[i] != inside[(i + 1) % 4]:
                da, db = a @ n - offset, b @ n - offset
                poly.append(a + (b - a) * da / (da - db))
        if len(poly) >= 3:
            poly = np.array(poly)
            ax.fill(poly[:, 0], poly[:, 1], color="#d9d9d9", lw=0, zorder=0)
        t = np.array([-n[1], n[0]])
        span = 2.0 * (x_hi - x_lo + y_hi - y_lo)
        edge = np.array([offset * n - span * t, offset * n + span * t])
        ax.plot(edge[:, 0], edge[:, 1], color="k", lw=1.0, zorder=1)


def _draw_pose(ax, scene, q, **style):
    """The body at configuration q: its outline through the contact points, and its disks."""
    pts = body_outline(scene, q)
    closed = np.vstack([pts, pts[:1]]) if len(pts) > 2 else pts
    if len(pts) > 1:
        ax.plot(closed[:, 0], closed[:, 1], solid_capstyle="round", **style)
    for k, p in enumerate(scene.body.points):
        if p.radius > 0:
            ax.add_patch(_pyplot().Circle(pts[k], float(p.radius), fill=False,
                                          color=style.get("color"), lw=style.get("lw", 1.0),
                                          alpha=style.get("alpha", 1.0)))


def _figure_size(frame, height: float, max_width: float):
    """A width that keeps equal axes readable: the frame's aspect ratio at the given height."""
    x_lo, x_hi, y_lo, y_hi = frame
    ratio = (x_hi - x_lo) / max(y_hi - y_lo, 1e-9)
    return min(max_width, max(4.0, 1.2 + (height - 0.8) * ratio)), height


def _pyplot():
    import matplotlib.pyplot as plt

    return plt


def _new_axes(ax, figsize):
    if ax is not None:
        return ax.figure, ax
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    return fig, ax


def _moreau_jean_spans(run):
    """Time intervals spent in the Moreau-Jean phase, from the run's phase changes."""
    spans, start = [], None
    for t, _from, to, _why in run.phase_changes:
        if to == _f.Phase.moreau_jean and start is None:
            start = t
        elif to == _f.Phase.event_driven and start is not None:
            spans.append((start, t))
            start = None
    if start is not None:
        spans.append((start, float(run.t[-1]) if len(run.t) else start))
    return spans


def energy_plot(run, ax=None, title=None, label_inadmissible: int = 3, show_initial: bool = True):
    """Energy ½q̇ᵀMq̇ + mgy against time (paper Figs. 3, 5, 7, 11, 13).

    Every impact of the log is marked at its energy after the impact: a green dot when its docs/concepts.md
    certificate holds, a red cross when it fails, labelled with the inequality that failed and the
    energy it created (the first ``label_inadmissible`` of them). Grey triangles mark closed
    accumulations of impacts; shaded spans are the Moreau-Jean (persistent contact) phase.
    Returns the figure.
    """
    fig, ax = _new_axes(ax, (9, 4.5))
    t, energy = energy_curve(run)
    ax.plot(t, energy, color="#2c7bb6", lw=1.4, label="energy ½q̇ᵀMq̇ + mgy")
    if show_initial and len(energy):
        ax.axhline(energy[0], color="#999999", lw=0.8, ls="--", label="initial energy")
    for i, (a, b) in enumerate(_moreau_jean_spans(run)):
        ax.axvspan(a, b, color=MOREAU_JEAN, alpha=0.25, lw=0,
                   label="Moreau–Jean (persistent contact)" if i == 0 else None)

    low, high = (float(energy.min()), float(energy.max())) if len(energy) else (0.0, 1.0)
    span = high - low + 1e-9
    ax.set_ylim(low - 0.05 * span, high + 0.25 * span)

    impacts = [im for im in run.impacts if im.kind != _f.ImpactKind.accumulation]
    good = [im for im in impacts if im.admissible]
    bad = [im for im in impacts if not im.admissible]
    acc = [im for im in run.impacts if im.kind == _f.ImpactKind.accumulation]
    if good:
        ax.plot([im.t for im in good], [im.energy_E for im in good], "o", ms=4, color=ADMISSIBLE,
                label=f"impact, admissible ({len(good)})")
    if bad:
        ax.plot([im.t for im in bad], [im.energy_E for im in bad], "X", ms=9, color=INADMISSIBLE,
                label=f"impact, INADMISSIBLE ({len(bad)})")
        t_mid = 0.5 * (t[0] + t[-1])
        for im in bad[:label_inadmissible]:
            gain = im.energy_E - im.energy_A
            # Keep the label inside the axes: left of late impacts, above low ones.
            left = im.t > t_mid
            above = im.energy_E < low + 0.5 * span
            ax.annotate(f"impact at t = {im.t:.3f} s creates {gain:+.3g} J:\n"
                        f"({str(im.failed).split('_')[-1]}) fails ({im.failed})",
                        xy=(im.t, im.energy_E), xytext=(-14 if left else 14, 24 if above else -34),
                        textcoords="offset points", ha="right" if left else "left",
                        color=INADMISSIBLE, fontsize=8,
                        bbox=dict(boxstyle="round,pad=0.25", fc="white", ec=INADMISSIBLE, lw=0.5),
                        arrowprops=dict(arrowstyle="-", color=INADMISSIBLE, lw=0.6))
    if acc:
        ax.plot([im.t for im in acc], [im.energy_E for im in acc], "v", ms=6, color=ACCUMULATION,
                label=f"accumulation of impacts closed ({len(acc)})")
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("energy (J)")
    ax.set_xlim(t[0] if len(t) else 0, t[-1] if len(t) else 1)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    if title:
        ax.set_title(title, fontsize=10)
    return fig


def poses_plot(run, scene, ax=None, title=None, interval: float = 0.075,
               show_impacts: bool = True):
    """The body's motion as a strip of overlaid poses (paper Figs. 2, 4, 6, 10, 12).

    One pose every ``interval`` seconds, coloured by time; the path of the centre of mass; the
    contact points of every impact (red crosses for inadmissible impacts). Returns the figure.
    """
    plt = _pyplot()
    t = np.asarray(run.t)
    q = np.asarray(run.q)
    frame = _frame(scene, q)
    fig, ax = _new_axes(ax, _figure_size(frame, 3.8, 16.0))
    cmap = plt.get_cmap("viridis")
    times = np.arange(t[0], t[-1] + 1e-12, interval) if len(t) else []
    t_end = max(float(t[-1]), 1e-12) if len(t) else 1.0
    for tk in times:
        i = min(np.searchsorted(t, tk), len(t) - 1)
        _draw_pose(ax, scene, q[i], color=cmap(tk / t_end), lw=1.4, alpha=0.85)
    ax.plot(q[:, 0], q[:, 1], color="#444444", lw=0.7, ls=":", label="centre of mass")
    if show_impacts:
        for label, wanted, color, marker in (("contact point at an impact", True, ADMISSIBLE, "o"),
                                             ("inadmissible impact", False, INADMISSIBLE, "X")):
            xs, ys = [], []
            for im in run.impacts:
                if im.kind == _f.ImpactKind.accumulation or im.admissible != wanted:
                    continue
                pts = body_outline(scene, im.q)
                for k in im.contacts:
                    xs.append(pts[scene.point_of(k)][0])
                    ys.append(pts[scene.point_of(k)][1])
            if xs:
                ax.plot(xs, ys, marker, color=color, ms=5 if wanted else 9, ls="none", label=label)
    _draw_obstacles(ax, scene, frame)
    ax.set_aspect("equal")
    ax.set_xlim(frame[0], frame[1])
    ax.set_ylim(frame[2], frame[3])
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(0, t_end))
    fig.colorbar(sm, ax=ax, label="time (s)", fraction=0.03, pad=0.01)
    ax.legend(loc="upper right", fontsize=7)
    if title:
        ax.set_title(title, fontsize=10)
    return fig


def animate(run, scene, path, title=None, fps: int = 25, speed: float = 1.0, dpi: int = 100):
    """Writes the body's motion as an animated GIF (paper Figs. 2, 4, 6, 10, 12) and returns the
    number of frames. One frame every speed/fps seconds of simulated time; the frames just after
    an impact circle its contact points (red when the impact is inadmissible).

    The axes, ground and labels are drawn once by matplotlib; each frame only draws the body, the
    path of its centre and the clock onto a copy of that picture (Pillow), which keeps a few
    seconds of motion to about a second of work.
    """
    from matplotlib import font_manager
    from PIL import Image, ImageDraw, ImageFont

    plt = _pyplot()
    t = np.asarray(run.t)
    q = np.asarray(run.q)
    energy = np.asarray(run.energy)
    frame_t = np.arange(t[0], t[-1] + 1e-12, speed / fps)
    frame = _frame(scene, q)
    fig, ax = plt.subplots(figsize=_figure_size(frame, 3.2, 12.0), dpi=dpi, layout="constrained")
    _draw_obstacles(ax, scene, frame)
    ax.set_aspect("equal")
    ax.set_xlim(frame[0], frame[1])
    ax.set_ylim(frame[2], frame[3])
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.grid(alpha=0.2)
    if title:
        ax.set_title(title, fontsize=9)
    fig.canvas.draw()
    background = Image.fromarray(np.asarray(fig.canvas.buffer_rgba())).convert("RGB")
    height = background.height
    to_pixels = ax.transData.transform
    corner_u, corner_v = ax.transAxes.transform((0.015, 0.97))
    corner = (float(corner_u), float(height - corner_v))
    plt.close(fig)

    def pixels(xy):
        p = to_pixels(np.atleast_2d(xy))
        return [(float(u), float(height - v)) for u, v in p]

    font = ImageFont.truetype(font_manager.findfont("DejaVu Sans"), max(10, dpi // 7))
    impacts = [im for im in run.impacts if im.kind != _f.ImpactKind.accumulation]
    impact_t = np.array([im.t for im in impacts])
    centre_px = pixels(q[:, :2])
    metre_px = float(to_pixels([[1.0, 0.0]])[0][0] - to_pixels([[0.0, 0.0]])[0][0])
    disk_px = [float(p.radius) * metre_px for p in scene.body.points]
    width_px = max(2, dpi // 33)
    frames = []
    for tk in frame_t:
        i = max(min(np.searchsorted(t, tk, side="right") - 1, len(t) - 1), 0)
        img = background.copy()
        draw = ImageDraw.Draw(img)
        if i > 0:
            draw.line(centre_px[: i + 1], fill="#999999", width=1)
        pts = body_outline(scene, q[i])
        closed = np.vstack([pts, pts[:1]]) if len(pts) > 2 else pts
        if len(pts) > 1:
            draw.line(pixels(closed), fill="#2c7bb6", width=2 * width_px, joint="curve")
        for (u, v), r in zip(pixels(pts), disk_px):
            if r > 0:
                draw.ellipse([u - r, v - r, u + r, v + r], outline="#2c7bb6", width=2 * width_px)
        recent = np.nonzero((impact_t <= tk) & (impact_t > tk - 3.0 * speed / fps))[0]
        if len(recent):
            im = impacts[recent[-1]]
            colour = ADMISSIBLE if im.admissible else INADMISSIBLE
            for u, v in pixels(body_outline(scene, im.q)[[scene.point_of(c) for c in im.contacts]]):
                r = 3 * width_px
                draw.ellipse([u - r, v - r, u + r, v + r], outline=colour, width=width_px)
            if not im.admissible:
                draw.text((corner[0], corner[1] + 1.6 * font.size),
                          f"impact at t = {im.t:.3f} s creates {im.energy_E - im.energy_A:+.3f} J"
                          f" ({im.failed} fails)", fill=INADMISSIBLE, font=font)
        draw.text(corner,
                  f"t = {tk:5.2f} s   E = {energy[i]:6.3f} J", fill="black", font=font)
        frames.append(img.quantize(colors=64, method=Image.Quantize.MEDIANCUT))
    frames[0].save(str(path), save_all=True, append_images=frames[1:],
                   duration=int(round(1000 / fps)), loop=0)
    return len(frames)


def restitution_plot(curves, ax=None, title=None):
    """D_NE against |D_NA| for several p (paper Fig. 8), one line a Curve from
    normal_restitution_curve. For p = 2 eq. (24)'s straight line is drawn under the curve; the
    dotted diagonal is the elastic impact D_NE = |D_NA|."""
    fig, ax = _new_axes(ax, (7, 5))
    vmax = 0.0
    for c in curves:
        par = c.parameters
        speed = -np.asarray(c.D_NA)
        vmax = max(vmax, float(speed.max()))
        spec = par.in_library_scaling()
        ax.plot(speed, c.D_NE, lw=1.8,
                label=f"p = {_g(par.p)} (k = {_g(spec.k)}; paper's {_g(par.in_paper_scaling().k)})")
        if par.p == 2.0:
            eps = max(_f.equivalent_restitution(par), 0.0)
            ax.plot(speed, eps * speed, color="k", lw=4, alpha=0.18,
                    label=f"eq. (24): D_NE = {_g(eps)} |D_NA|")
        if not all(c.admissible):
            ax.plot(speed[~np.asarray(c.admissible)], np.asarray(c.D_NE)[~np.asarray(c.admissible)],
                    "X", color=INADMISSIBLE, label="inadmissible")
    ax.plot([0, vmax], [0, vmax], ":", color="#999999", lw=1, label="elastic, D_NE = |D_NA|")
    ax.set_xlim(0, vmax)
    ax.set_ylim(0, vmax)
    ax.set_xlabel("|D_NA|, normal velocity before the impact (m/s)")
    ax.set_ylabel("D_NE, normal velocity after the impact (m/s)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    if title:
        ax.set_title(title, fontsize=10)
    return fig


def tangential_plot(curve, ax=None, title=None):
    """D_TE against D_TA for the viscous dead zone (paper Fig. 9), from tangential_curve. The
    shaded band is the dead zone |D_TA| ≤ r (the library's scaling), where D_TE = D_TA; the dotted line is
    D_TE = D_TA."""
    fig, ax = _new_axes(ax, (7, 5))
    par = curve.parameters
    spec, paper = par.in_library_scaling(), par.in_paper_scaling()
    d_ta = np.asarray(curve.D_TA)
    d_te = np.asarray(curve.D_TE)
    ax.axvspan(-spec.r, spec.r, color="#abd9e9", alpha=0.5, lw=0,
               label=f"dead zone |D_TA| ≤ r = {_g(spec.r)} m/s (paper's r = {_g(paper.r)})")
    ax.plot(d_ta, d_ta, ":", color="#999999", lw=1, label="D_TE = D_TA (no tangential percussion)")
    ax.plot(d_ta, d_te, lw=1.8, color="#d95f02",
            label=f"Frémond viscous: q = {_g(spec.q)}, k_T = {_g(spec.k_T)} "
                  f"(paper's {_g(paper.k_T)})")
    inside = np.asarray(curve.in_dead_zone)
    ax.plot(d_ta[inside], d_te[inside], ".", color="#2c7bb6", ms=4, label="points in the dead zone")
    ax.set_xlabel("D_TA, tangential velocity before the impact (m/s)")
    ax.set_ylabel("D_TE, tangential velocity after the impact (m/s)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    if title:
        ax.set_title(title, fontsize=10)
    return fig
