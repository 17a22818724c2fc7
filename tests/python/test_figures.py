"""The figures' data, not their pixels: the energy curves jump exactly by the impact log's energy
changes; Newton + Coulomb's first impact creates energy and is flagged (Fig. 5); the plotted Fig. 8
line for p = 2 is eq. (24); the plotted Fig. 9 points in the dead zone keep D_TE = D_TA; and after
the main job every figure file exists and is a valid image."""
import json
import math
import sys
import tempfile
from pathlib import Path

import matplotlib
import matplotlib.patches

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402

from support import ROOT, near, run_tests  # noqa: E402
import fremond as f  # noqa: E402

LAWS = ["newton", "newton_coulomb", "poisson_coulomb", "fremond_coulomb", "fremond_viscous",
        "stronge_coulomb"]
_runs = {}


def paper_run(name, t_end=3.0):
    if name not in _runs:
        scene = f.paper_bar_scene(name)
        _runs[name] = (scene, f.simulate(scene, f.SimulationOptions(t_end=t_end)))
    return _runs[name]


def test_energy_curve_jumps_are_the_impact_log():
    for name in LAWS:
        scene, run = paper_run(name)
        assert run.result.ok(), (name, run.result.message)
        t, energy = f.plots.energy_curve(run)
        jumps = f.plots.energy_jumps(t, energy)
        events = [im for im in run.impacts if im.kind == f.ImpactKind.event]
        assert len(events) >= 5, name
        # Every event impact is one jump of the curve, by exactly its logged energy change.
        by_time = {}
        for tj, before, after in jumps:
            by_time.setdefault(tj, []).append((before, after))
        for im in events:
            assert im.t in by_time, f"{name}: no jump at the impact t = {im.t}"
            before, after = by_time[im.t][0]
            near([before, after], [im.energy_A, im.energy_E], rel=1e-12, tiny=1e-12)
            near([after - before], [im.energy_E - im.energy_A], rel=1e-9, tiny=1e-12)
        # And the curve has no other jump than the log's entries.
        logged = {im.t for im in run.impacts}
        assert all(tj in logged for tj, _, _ in jumps), name
        # Between impacts of the event-driven phase the energy is constant (exact flights).
        phases = np.asarray([p == f.Phase.event_driven for p in run.phase])
        flight = (t[1:] > t[:-1]) & phases[1:] & phases[:-1]
        assert np.max(np.abs(np.diff(energy)[flight])) < 1e-9 * energy[0], name


def test_newton_coulomb_first_impact_creates_energy_and_is_flagged():
    scene, run = paper_run("newton_coulomb")
    first = run.impacts[0]
    assert not first.admissible and first.failed == f.Inequality.total_15
    assert first.energy_E - first.energy_A > 0.6  # ≈ +0.668 J (paper Fig. 5)
    fig = f.plots.energy_plot(run, title="Newton + Coulomb")
    ax = fig.axes[0]
    flagged = [l for l in ax.get_lines() if (l.get_label() or "").startswith("impact, INADMISSIBLE")]
    assert len(flagged) == 1
    near([flagged[0].get_xdata()[0], flagged[0].get_ydata()[0]], [first.t, first.energy_E])
    texts = " ".join(t.get_text() for t in ax.texts)
    assert "(15) fails" in texts and "total_15" in texts
    plt.close(fig)
    for name in LAWS:
        if name != "newton_coulomb":
            _, other = paper_run(name)
            assert other.impacts[0].admissible, name


def test_stronge_first_impact_loses_what_the_hand_derivation_says():
    # The bar at its first impact (θ = π/4, l = 0.5, m = 1, J = 1/12): G_NN = G_TT = 2.5,
    # G_NT = -1.5, D_TA = 2, D_NA = -v. It slips (dD_T/dp = -4) until D_T = 0 at p = 1/2, then
    # sticks (|G_NT| <= μ G_TT) with dD_N/dp = det G / G_TT = 1.6. The energy lost is the normal
    # work (1 - e²)|W_c| plus the friction work μ ∫|D_T| dp = 1/2.
    _, run = paper_run("stronge_coulomb")
    first = run.impacts[0]
    v = math.sqrt(2 * 9.81 * (1 - 0.5 * math.sin(math.pi / 4)))
    w_c = 0.5 * (v + (v - 2)) * 0.5 + (v - 2) ** 2 / 3.2
    near([first.energy_E - first.energy_A], [-(1 - 0.81) * w_c - 0.5], rel=1e-12)
    assert first.admissible


def test_fig8_plotted_p2_line_is_eq_24():
    speeds = np.linspace(0, 5, 51)
    curves = [f.normal_restitution_curve(f.NormalCurveParameters(p=p), speeds) for p in (2.0, 3.0)]
    fig = f.plots.restitution_plot(curves)
    lines = {l.get_label(): l for l in fig.axes[0].get_lines()}
    p2 = next(l for k, l in lines.items() if k.startswith("p = 2 "))
    k, m = 4.0, 1.0
    near(p2.get_xdata(), speeds)
    near(p2.get_ydata(), (k - 2 * m) / (k + 2 * m) * speeds, tiny=1e-13)
    assert any(k.startswith("eq. (24)") for k in lines)
    plt.close(fig)


def test_fig9_plotted_dead_zone_points_keep_D_TE():
    par = f.TangentialCurveParameters.paper_figure(f.Scaling.paper)
    curve = f.tangential_curve(par, np.linspace(-1.5, 1.5, 151))
    fig = f.plots.tangential_plot(curve)
    dots = next(l for l in fig.axes[0].get_lines() if l.get_label() == "points in the dead zone")
    x, y = dots.get_xdata(), dots.get_ydata()
    assert len(x) > 10 and np.all(np.abs(x) <= 0.2)
    assert np.array_equal(x, y)
    plt.close(fig)


def _inside(ax, xy):
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    xy = np.atleast_2d(xy)
    return np.all((xy[:, 0] >= x0) & (xy[:, 0] <= x1) & (xy[:, 1] >= y0) & (xy[:, 1] <= y1))


def test_poses_plot_frames_a_ball_on_a_slope():
    # A ball rolling down a 20° slope through the origin ends over a metre lower than it starts: every
    # pose, disk included, and the slope under it must lie inside the axes (they used to be fixed
    # to y >= -0.15 and drew a ball as nothing).
    a = math.radians(20.0)
    ball = f.BallParameters()
    ball.initial = f.PlanarState()
    ball.initial.q = [0.0, 0.2, 0.0]
    ball.initial.qdot = [2.0, 0.0, 0.0]
    scene = f.ball_scene(ball, f.paper_law(f.PaperLaw.fremond_coulomb, 1e4))
    plane = f.HalfPlane()
    plane.normal, plane.offset = [math.sin(a), math.cos(a)], 0.0
    scene.obstacles = [plane]
    run = f.simulate(scene, f.SimulationOptions(t_end=1.5))
    q = np.asarray(run.q)
    assert q[-1, 1] < -1.0, q[-1]  # it went down the slope
    fig = f.plots.poses_plot(run, scene)
    ax = fig.axes[0]
    rho = ball.radius
    for qi in q[::25]:
        ring = qi[:2] + rho * np.array([[1, 0], [-1, 0], [0, 1], [0, -1]])
        assert _inside(ax, ring), (qi, ax.get_xlim(), ax.get_ylim())
    circles = [p for p in ax.patches if isinstance(p, matplotlib.patches.Circle)]
    assert len(circles) >= 5 and all(abs(c.get_radius() - rho) < 1e-15 for c in circles)
    # The slope's edge under the first and the last pose is in view.
    for x in (q[0, 0], q[-1, 0]):
        assert _inside(ax, [x, -math.tan(a) * x])
    plt.close(fig)


def test_main_job_writes_every_figure():
    sys.path.insert(0, str(ROOT / "scripts"))
    import paper_figures

    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "paper"
        assert paper_figures.main(["--out", str(out)]) == 0
        expected = [paper_figures.figure_name(n, law, kind) for law, a, e in paper_figures.LAWS
                    for n, kind in ((a, "animation.gif"), (a, "poses.png"), (e, "energy.png"))]
        assert "stronge_coulomb_energy.png" in expected
        expected += ["fig08_normal_restitution.png", "fig09_tangential_dead_zone.png"]
        for name in expected:
            path = out / name
            assert path.exists(), f"missing {name}"
            with Image.open(path) as im:
                im.verify()  # a valid image file, not only a name
            with Image.open(path) as im:
                assert im.width >= 300 and im.height >= 200, (name, im.size)
                assert im.format == ("GIF" if name.endswith(".gif") else "PNG")
                if name.endswith(".gif"):
                    assert im.n_frames > 25, (name, im.n_frames)
        summary = json.loads((out / "comparison.json").read_text())
        rows = {r["law"]: r for r in summary["laws"]}
        assert set(rows) == set(LAWS)
        nc = rows["newton_coulomb"]
        assert not nc["all_admissible"]
        assert nc["inadmissible"][0]["impact"] == 1
        assert nc["inadmissible"][0]["inequality"] == "total_15"
        assert nc["first_impacts"][0]["energy_E"] > nc["first_impacts"][0]["energy_A"]
        for name in LAWS:
            if name != "newton_coulomb":
                assert rows[name]["all_admissible"], name
        table = (out / "comparison.txt").read_text()
        assert "total_15 at impact 1" in table


if __name__ == "__main__":
    run_tests(globals())
