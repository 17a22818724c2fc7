"""The data of Figs. 8 and 9 against closed forms (eq. 24, the q = 2 viscous law) and independent
bisections of eqs. (23) and (25); the two scalings; the command line's CSV against the bindings."""
import csv
import io
import math
import subprocess

import numpy as np

from support import (cli, deadzone_point_mass_D_TE, fremond_point_mass_D_NE, near, run_tests)
import fremond as f

SPEEDS = np.linspace(0.0, 5.0, 41)


def test_fig8_p2_is_the_straight_line_of_eq_24():
    # ε = (k − 2m)/(k + 2m) in the library's scaling (docs/laws.md), written here from eq. (24) directly.
    for m, k in [(1.0, 4.0), (1.0, 38.0), (2.5, 7.0), (0.3, 100.0)]:
        c = f.normal_restitution_curve(f.NormalCurveParameters(mass=m, k=k, p=2.0), SPEEDS)
        eps = (k - 2 * m) / (k + 2 * m)
        near(c.D_NE, eps * SPEEDS, rel=1e-12, tiny=1e-13)
        near(c.P_N, m * (1 + eps) * SPEEDS, rel=1e-12, tiny=1e-13)
        assert all(c.admissible)
        near([f.equivalent_restitution(c.parameters)], [eps])
        # Eq. (9): T_E − T_A = ½m(D_NE² − D_NA²) for a point mass.
        near(c.energy_change, 0.5 * m * (eps**2 - 1) * SPEEDS**2, rel=1e-11, tiny=1e-13)


def test_fig8_p2_in_the_papers_scaling():
    # The paper's eq. (24): ε = (k_paper − m)/(k_paper + m).
    m, k_paper = 1.0, 19.0
    par = f.NormalCurveParameters(mass=m, k=k_paper, p=2.0, scaling=f.Scaling.paper)
    c = f.normal_restitution_curve(par, SPEEDS)
    near(c.D_NE, (k_paper - m) / (k_paper + m) * SPEEDS, tiny=1e-13)
    near([par.in_library_scaling().k], [2 * k_paper])


def test_fig8_p2_soft_law_stops_the_mass():
    # k < 2m: eq. (24) gives ε < 0, so the reaction stops the mass: D_NE = 0 and the reaction
    # takes the whole percussion m|D_NA| (eq. 16).
    m, k = 1.0, 1.0
    par = f.NormalCurveParameters(mass=m, k=k, p=2.0)
    assert f.equivalent_restitution(par) < 0
    c = f.normal_restitution_curve(par, SPEEDS)
    near(c.D_NE, np.zeros_like(SPEEDS), tiny=1e-14)
    near(c.P_N, m * SPEEDS, tiny=1e-13)
    # z = −a/2, φ'(z) = k z: the dissipative part is −k z = k a/2, the reaction the rest.
    near(c.P_N_reaction, (m - k / 2) * SPEEDS, tiny=1e-13)


def test_fig8_other_exponents_against_bisection_of_eq_23():
    for m, k, p in [(1.0, 4.0, 1.5), (1.0, 4.0, 3.0), (1.0, 4.0, 4.0), (2.0, 85.36, 3.0),
                    (1.0, 4.0, 2.5)]:
        c = f.normal_restitution_curve(f.NormalCurveParameters(mass=m, k=k, p=p), SPEEDS)
        ref = [fremond_point_mass_D_NE(m, k, p, a) for a in SPEEDS]
        near(c.D_NE, ref, rel=1e-10, tiny=1e-12)
        assert all(c.admissible), f"p = {p}: {c.failed}"
        assert all(s == f.SolverStatus.converged for s in c.status)


def test_fig8_p3_threshold_closed_form():
    # p = 3: the mass stops while a ≤ 4m/k; above, (k/4)u² + m u − 2ma = 0 with u = a − D_NE.
    m, k = 1.0, 4.0
    c = f.normal_restitution_curve(f.NormalCurveParameters(mass=m, k=k, p=3.0), SPEEDS)
    for a, d in zip(SPEEDS, c.D_NE):
        if a <= 4 * m / k:
            near([d], [0.0], tiny=1e-13)
        else:
            u = (-m + math.sqrt(m * m + 2 * k * m * a)) / (k / 2)
            near([d], [a - u], rel=1e-11, tiny=1e-13)


def test_fig9_dead_zone_keeps_D_TE_equal_to_D_TA():
    par = f.TangentialCurveParameters.paper_figure(f.Scaling.paper)
    assert par.scaling == f.Scaling.paper
    near([par.r, par.k_T, par.q], [0.4, 0.75, 2.0])
    d_ta = np.linspace(-1.5, 1.5, 301)
    c = f.tangential_curve(par, d_ta)
    inside = np.asarray(c.in_dead_zone)
    near([inside.sum()], [np.sum(np.abs(d_ta) <= 0.2)])  # our r = r_paper/2 = 0.2
    assert inside.sum() > 10
    assert np.array_equal(np.asarray(c.D_TE)[inside], d_ta[inside]), "D_TE != D_TA in the dead zone"
    assert np.all(np.asarray(c.P_T)[inside] == 0.0)
    assert np.all(np.asarray(c.P_T)[~inside] != 0.0)
    assert all(c.admissible)


def test_fig9_outside_the_dead_zone_q2_closed_form():
    # q = 2: m(D_TE − D_TA) = −k_T(z − r sign z), z = (D_TA + D_TE)/2, so
    # D_TE = ((m − k_T/2) D_TA + k_T r sign D_TA)/(m + k_T/2).
    par = f.TangentialCurveParameters()  # the paper's figure in the library's scaling
    m, k, r = par.mass, par.k_T, par.r
    near([k, r], [1.5, 0.2])
    d_ta = np.linspace(-2.0, 2.0, 81)
    c = f.tangential_curve(par, d_ta)
    for v, d in zip(d_ta, c.D_TE):
        ref = v if abs(v) <= r else ((m - k / 2) * v + k * r * math.copysign(1, v)) / (m + k / 2)
        near([d], [ref], rel=1e-12, tiny=1e-14)
    # The normal law is the fixed p = 2 law: D_NE = ε|D_NA| at every point.
    eps = (par.k_N - 2 * m) / (par.k_N + 2 * m)
    near(c.D_NE, np.full(len(d_ta), -eps * par.D_NA))


def test_fig9_other_exponents_against_bisection():
    par = f.TangentialCurveParameters(mass=2.0, k_T=3.0, q=3.0, r=0.3, k_N=50.0, p=3.0,
                                      D_NA=-2.0)
    d_ta = np.linspace(-3.0, 3.0, 61)
    c = f.tangential_curve(par, d_ta)
    ref = [deadzone_point_mass_D_TE(2.0, 3.0, 3.0, 0.3, v) for v in d_ta]
    near(c.D_TE, ref, rel=1e-10, tiny=1e-12)


def test_scalings_describe_the_same_law():
    spec = f.TangentialCurveParameters(k_T=1.5, q=2.0, r=0.2, k_N=4.0, p=3.0)
    paper = spec.in_paper_scaling()
    near([paper.k_T, paper.r, paper.k_N], [0.75, 0.4, 1.0])
    d_ta = np.linspace(-1, 1, 21)
    a, b = f.tangential_curve(spec, d_ta), f.tangential_curve(paper, d_ta)
    near(a.D_TE, b.D_TE)
    near(a.D_NE, b.D_NE)
    n = f.NormalCurveParameters(k=21.34, p=3.0, scaling=f.Scaling.paper)
    near([n.in_library_scaling().k], [85.36])


def test_bad_parameters_are_refused_by_name():
    cases = [
        (lambda: f.normal_restitution_curve(f.NormalCurveParameters(p=1.0), [1.0]), "p: must be > 1"),
        (lambda: f.normal_restitution_curve(f.NormalCurveParameters(k=-1.0), [1.0]), "k: must be >= 0"),
        (lambda: f.normal_restitution_curve(f.NormalCurveParameters(mass=0.0), [1.0]), "mass:"),
        (lambda: f.normal_restitution_curve(f.NormalCurveParameters(), [1.0, -2.0]), "speeds[1]"),
        (lambda: f.tangential_curve(f.TangentialCurveParameters(r=-0.1), [0.0]), "r: must be >= 0"),
        (lambda: f.tangential_curve(f.TangentialCurveParameters(D_NA=0.5), [0.0]), "D_NA: must be <= 0"),
        (lambda: f.tangential_curve(f.TangentialCurveParameters(), [0.0, math.nan]), "D_TA[1]"),
        (lambda: f.equivalent_restitution(f.NormalCurveParameters(p=3.0)), "p: eq. (24)"),
    ]
    for call, message in cases:
        try:
            call()
        except ValueError as e:
            assert message in str(e), f"{message!r} not in {str(e)!r}"
        else:
            raise AssertionError(f"not refused: {message}")


def read_cli_csv(text):
    return list(csv.DictReader(io.StringIO(text)))


def test_cli_curves_are_the_bindings_curves():
    exe = cli()
    if exe is None:
        print("skipped: no fremond command (set FREMOND_CLI)")
        return
    out = subprocess.run([exe, "curve", "normal", "--p", "2,3", "--points", "11"],
                         capture_output=True, text=True, check=True).stdout
    rows = read_cli_csv(out)
    assert {r["scaling"] for r in rows} == {"library"}
    assert len(rows) == 22
    for p in (2.0, 3.0):
        mine = [r for r in rows if float(r["p"]) == p]
        speeds = [float(r["abs_D_NA"]) for r in mine]
        near([speeds[0], speeds[-1]], [0.0, 5.0])
        c = f.normal_restitution_curve(f.NormalCurveParameters(p=p), speeds)
        near([float(r["D_NE"]) for r in mine], c.D_NE, rel=0, tiny=0)  # %.17g reads back exactly
        near([float(r["P_N_reaction"]) for r in mine], c.P_N_reaction, rel=0, tiny=0)

    out = subprocess.run([exe, "curve", "tangential", "--scaling", "paper", "--points", "21"],
                         capture_output=True, text=True, check=True).stdout
    rows = read_cli_csv(out)
    assert {r["scaling"] for r in rows} == {"paper"}
    d_ta = [float(r["D_TA"]) for r in rows]  # the command's own grid
    near([d_ta[0], d_ta[-1], len(d_ta)], [-1.0, 1.0, 21])
    c = f.tangential_curve(f.TangentialCurveParameters.paper_figure(f.Scaling.paper), d_ta)
    near([float(r["D_TE"]) for r in rows], c.D_TE, rel=0, tiny=0)
    assert [r["in_dead_zone"] == "1" for r in rows] == list(c.in_dead_zone)


if __name__ == "__main__":
    run_tests(globals())
