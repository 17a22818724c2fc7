"""The bindings: NumPy in and out, the laws against closed forms of the paper, the admissibility
report (Newton + Coulomb creates energy on the bar, §4.1), potentials written in Python (with the
GIL and their lifetime), the registry and the problem file, enums and option structs."""
import gc
import json
import math
import os
import subprocess
import sys
import threading

import numpy as np

from support import near, run_tests
import fremond as f

L = 0.5  # the bar's half-length (docs/laws.md)
G = 9.81
THETA = math.pi / 4


def bar_first_impact():
    """The bar's first impact built by hand (the paper's Fig. 1): the lower end at θ = π/4 reaches the
    ground after falling 1 − l sin θ, with ẋ = 2, θ̇ = 0."""
    v = math.sqrt(2 * G * (1 - L * math.sin(THETA)))
    M = np.diag([1.0, 1.0, L * L / 3])
    W_N = np.array([[0.0], [1.0], [-L * math.cos(THETA)]])
    W_T = np.array([[1.0], [0.0], [L * math.sin(THETA)]])
    return f.ImpactProblem(M=M, W_N=W_N, W_T=W_T, qdot_A=np.array([2.0, -v, 0.0])), v


def test_enums_use_the_library_names():
    assert str(f.Inequality.total_15) == "total_15"
    assert "poisson_coulomb" in f.law_names() and "fremond" in f.law_names()
    assert f.PaperLaw("fremond_viscous") == f.PaperLaw.fremond_viscous
    try:
        f.SolverMethod.from_string("fastest")
    except ValueError as e:
        assert "fastest" in str(e) and "semismooth_newton" in str(e)
    else:
        raise AssertionError("an unknown name was accepted")
    # A string is accepted wherever the enum is.
    opts = f.SolverOptions(method="nlopt")
    assert opts.method == f.SolverMethod.nlopt


def test_options_from_keywords():
    o = f.SolverOptions(tolerance=1e-12, check_uniqueness=False)
    assert o.tolerance == 1e-12 and not o.check_uniqueness
    try:
        f.SolverOptions(tolerence=1e-12)
    except AttributeError:
        pass
    else:
        raise AssertionError("a misspelt option was accepted")
    assert not f.SolverOptions(tolerance=1.0).is_valid()
    s = f.SimulationOptions(t_end=0.5, integrator="moreau_jean")
    assert s.integrator == f.Integrator.moreau_jean and s.t_end == 0.5


def test_problem_is_checked_and_numpy_in_and_out():
    pb, v = bar_first_impact()
    assert pb.dofs == 3 and pb.contacts == 1 and pb.has_tangential()
    assert isinstance(pb.M, np.ndarray) and pb.M.shape == (3, 3)
    for kwargs, key in [
        (dict(M=-np.eye(1), W_N=np.ones((1, 1)), qdot_A=[-1.0]), "M"),
        (dict(M=np.eye(2), W_N=np.ones((3, 1)), qdot_A=[-1.0, 0.0]), "W_N"),
        (dict(M=np.eye(1), W_N=np.ones((1, 1)), qdot_A=[math.inf]), "qdot_A"),
    ]:
        try:
            f.ImpactProblem(**kwargs)
        except ValueError as e:
            assert str(e).startswith(key), f"{e} does not name {key}"
        else:
            raise AssertionError(f"not refused: {key}")


def test_newton_frictionless_eq_6():
    # Eq. (6): q̇_E = q̇_A − M⁻¹W_N G_N⁻¹(1 + e) D_NA.
    pb, v = bar_first_impact()
    e = 0.9
    r = f.solve_impact(pb, f.ImpactLaw.newton(e))
    Minv = np.linalg.inv(pb.M)
    G_N = (pb.W_N.T @ Minv @ pb.W_N)[0, 0]
    ref = pb.qdot_A - (Minv @ pb.W_N)[:, 0] * (1 + e) * (-v) / G_N
    near(r.qdot_E, ref)
    near(r.D_NE, [e * v])
    assert r.ok() and r.admissibility.admissible
    # G_NN of eqs. (7)-(8): (1 + 3cos²θ)/m.
    near([G_N], [1 + 3 * math.cos(THETA) ** 2])


def test_newton_coulomb_creates_energy_on_the_bar():
    # Paper §4.1 and Fig. 5: with D_NE = −e D_NA and Coulomb on D_TE the bar sticks (D_TE = 0),
    # and the impact creates kinetic energy: (15) fails. The stick percussion, by hand:
    # P = G⁻¹(D_E − D_A) with G of eqs. (7)-(8), |P_T| ≤ μP_N.
    pb, v = bar_first_impact()
    e, mu = 0.9, 1.0
    c, s = math.cos(THETA), math.sin(THETA)
    Gm = np.array([[1 + 3 * c * c, -3 * s * c], [-3 * s * c, 1 + 3 * s * s]])
    D_A = np.array([-v, 2.0])
    D_E = np.array([e * v, 0.0])
    P = np.linalg.solve(Gm, D_E - D_A)
    assert abs(P[1]) <= mu * P[0]
    gain = P @ (D_A + D_E) / 2  # eq. (9): T_E − T_A = P·z
    assert gain > 0.6

    r = f.solve_impact(pb, f.ImpactLaw.newton_coulomb(e, mu))
    near(r.P_N, [P[0]], rel=1e-12)
    near(r.P_T, [P[1]], rel=1e-12)
    near([r.energy_change], [gain], rel=1e-10)
    rep = r.admissibility
    assert not rep.admissible and rep.failed == f.Inequality.total_15
    assert str(rep.failed) == "total_15"
    near([rep.total], [-gain], rel=1e-10)

    # Poisson + Coulomb on the same impact does not create energy (Pfeiffer & Glocker).
    rp = f.solve_impact(pb, f.ImpactLaw.poisson_coulomb(e, mu))
    assert rp.admissibility.admissible and rp.energy_change <= 0 and rp.has_phases


def test_fremond_calibrated_restitution_on_the_bar():
    # docs/laws.md: k_N such that the normal law alone gives −D_NE/D_NA = 0.9 at the first impact.
    pb, v = bar_first_impact()
    k = f.paper_bar_normal_stiffness()
    near([k], [85.36], rel=1e-3)
    frictionless = f.ImpactProblem(M=pb.M, W_N=pb.W_N, qdot_A=pb.qdot_A)
    r = f.solve_impact(frictionless, f.ImpactLaw.fremond(f.PowerPotential(k, 3.0)))
    near(r.D_NE, [0.9 * v], rel=1e-10)
    cal = f.calibrate_normal_stiffness(pb, 3.0, 0.9)
    assert cal.converged
    near([cal.k_N], [k], rel=1e-9)


class PyPower(f.Potential):
    """k|z|^p/p written in Python with value and subgradient only (the NLopt route)."""

    def __init__(self, k, p):
        f.Potential.__init__(self)
        self.k, self.p = k, p

    def do_value(self, z):
        return self.k * abs(z) ** self.p / self.p

    def do_subgradient(self, z):
        return 0.0 if z == 0 else self.k * z * abs(z) ** (self.p - 2)


class PyPowerExact(PyPower):
    """The same with its subdifferential (so the prox by bisection, hence Newton) and conjugate."""

    def do_name(self):
        return "py_power"

    def do_subdifferential(self, z):
        g = self.do_subgradient(z)
        return (g, g)

    def do_conjugate(self, s):
        q = self.p / (self.p - 1)  # the conjugate exponent
        return abs(s) ** q / (q * self.k ** (q - 1))

    def do_describe(self):
        return f"py_power(k={self.k}, p={self.p})"


class PyQuadratic(f.Potential):
    """k z²/2 with its prox in closed form: prox_{τφ}(x) = x/(1 + τk), derivative 1/(1 + τk)."""

    def __init__(self, k):
        f.Potential.__init__(self)
        self.k = k

    def do_value(self, z):
        return 0.5 * self.k * z * z

    def do_subgradient(self, z):
        return self.k * z

    def do_prox(self, x, tau):
        return x / (1 + tau * self.k), 1 / (1 + tau * self.k)

    def do_conjugate(self, s):
        return 0.5 * s * s / self.k


def test_python_potentials_inside_solve_impact():
    pb, v = bar_first_impact()
    k = f.paper_bar_normal_stiffness()
    ref = f.solve_impact(pb, f.ImpactLaw.fremond(f.PowerPotential(k, 3.0),
                                                 f.DeadZonePowerPotential(1.5, 2.0, 0.2)))
    exact = f.solve_impact(pb, f.ImpactLaw.fremond(PyPowerExact(k, 3.0),
                                                   f.DeadZonePowerPotential(1.5, 2.0, 0.2)))
    near(exact.qdot_E, ref.qdot_E, rel=1e-11, tiny=1e-12)
    assert exact.ok() and exact.admissibility.admissible
    slow = f.solve_impact(pb, f.ImpactLaw.fremond(PyPower(k, 3.0),
                                                  f.DeadZonePowerPotential(1.5, 2.0, 0.2)))
    assert slow.ok(), slow.solver
    near(slow.qdot_E, ref.qdot_E, rel=1e-6, tiny=1e-8)
    # p = 2 with a closed-form prox, on a point mass: eq. (24).
    r = f.solve_impact(f.point_mass_problem(1.0, -2.0), f.ImpactLaw.fremond(PyQuadratic(38.0)))
    near(r.D_NE, [2.0 * 36 / 40])


class PyBump(f.Potential):
    """k z²/(1 + z²): zero at 0 and non-negative, but concave for |z| > 1/√3."""

    def __init__(self, k):
        f.Potential.__init__(self)
        self.k = k

    def do_value(self, z):
        return self.k * z * z / (1 + z * z)

    def do_subgradient(self, z):
        return 2 * self.k * z / (1 + z * z) ** 2


class PyNegative(f.Potential):
    """−k z²/2: concave and negative."""

    def __init__(self, k):
        f.Potential.__init__(self)
        self.k = k

    def do_value(self, z):
        return -0.5 * self.k * z * z

    def do_subgradient(self, z):
        return -self.k * z


def test_a_potential_that_is_no_pseudo_potential_is_not_an_answer():
    # Both used to come back converged and admissible (the bump, a stationary point of a non-convex
    # function) or stalled with a message about double precision (the negative one).
    for phi in (PyBump(4.0), PyNegative(1.0)):
        assert not f.check_potential(phi).ok
        r = f.solve_impact(f.point_mass_problem(1.0, -3.0), f.ImpactLaw.fremond(phi))
        assert r.solver.status == f.SolverStatus.unsupported, (r.solver.status, r.solver.message)
        assert "not a pseudo-potential" in r.solver.message
        assert not r.ok() and not r.admissibility.admissible
        assert r.admissibility.failed_contact == 0
    # The bump's answer: D_NE = 0 with P = 3, of which the slope φ'(−3/2) = −48/42.25 is the
    # potential's part: a stationary point, with φ(0) = 0 below its tangent there.
    r = f.solve_impact(f.point_mass_problem(1.0, -3.0), f.ImpactLaw.fremond(PyBump(4.0)))
    assert r.admissibility.failed == f.Inequality.fenchel_young
    # A convex potential written the same way (value and subgradient only) is still an answer.
    r = f.solve_impact(f.point_mass_problem(1.0, -2.0), f.ImpactLaw.fremond(PyPower(38.0, 2.0)))
    assert r.ok() and r.admissibility.admissible, r.solver.message
    near(r.D_NE, [2.0 * 36 / 40], rel=1e-6)


def test_laws_and_point_masses_refuse_bad_values_where_they_are_made():
    for make, name in ((lambda: f.ImpactLaw.newton_coulomb(0.5, -1.0), "law.mu"),
                       (lambda: f.ImpactLaw.fremond_coulomb(f.PowerPotential(4, 2), -0.1),
                        "law.mu"),
                       (lambda: f.ImpactLaw.newton(1.5), "law.e"),
                       (lambda: f.ImpactLaw.poisson([0.5, -0.5]), "law.e[1]"),
                       (lambda: f.point_mass_problem(-1.0, -3.0), "mass"),
                       (lambda: f.point_mass_problem(1.0, float("nan")), "D_NA")):
        try:
            make()
        except ValueError as e:
            assert str(e).startswith(name + ":"), str(e)
        else:
            raise AssertionError(f"accepted: {name}")


def test_python_potential_interface_and_conformance():
    p = PyPowerExact(2.0, 3.0)
    assert p.name == "py_power" and p.describe() == "py_power(k=2.0, p=3.0)"
    caps = p.capabilities()
    assert caps.subdifferential and caps.prox and caps.conjugate
    assert not PyPower(2.0, 3.0).capabilities().prox
    near([p.value(-1.5)], [2.0 * 1.5**3 / 3])
    # The prox by the library's bisection on the Python subdifferential: y + τk y|y| = x.
    y = p.prox(1.0, 0.5)
    near([y + 0.5 * 2.0 * y * abs(y)], [1.0])
    near([p.fenchel_young_gap(0.7, p.subgradient(0.7))], [0.0], tiny=1e-14)
    report = f.check_potential(p, f.ConformanceOptions(samples=60))
    assert report.ok, report.summary()
    report = f.check_potential(PyQuadratic(3.0), f.ConformanceOptions(samples=60))
    assert report.ok, report.summary()

    class NotConvex(PyPowerExact):
        def do_value(self, z):
            return -abs(z)

    assert not f.check_potential(NotConvex(1.0, 2.0), f.ConformanceOptions(samples=30)).ok


def test_python_potential_outlives_its_python_name():
    # The law keeps the Python object alive (clone() holds a reference), across threads too.
    law = f.ImpactLaw.fremond(PyQuadratic(38.0))
    gc.collect()
    normal = law.normal[0]
    assert normal.value(2.0) == 0.5 * 38.0 * 4.0
    results = []

    def worker():
        results.append(f.solve_impact(f.point_mass_problem(1.0, -1.0), law).D_NE[0])

    threads = [threading.Thread(target=worker) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    near(results, [0.9] * 4)


def test_python_potential_errors_reach_python():
    class Broken(PyPower):
        def do_subgradient(self, z):
            raise RuntimeError("broken potential")

    try:
        f.solve_impact(f.point_mass_problem(1.0, -1.0), f.ImpactLaw.fremond(Broken(1.0, 2.0)))
    except RuntimeError as e:
        assert "broken potential" in str(e)
    else:
        raise AssertionError("the exception was lost")


def test_registry_and_problem_file_with_a_python_kind():
    reg = f.PotentialRegistry.with_builtins()
    reg.add("py_power", lambda params: PyPowerExact(params["k"], params["p"]),
            required=["k", "p"], description="k|z|^p/p, in Python")
    assert "py_power" in reg.names() and "power" in reg.names()
    text = json.dumps({"M": [[1.0]], "W_N": [[1.0]], "qdot_A": [-1.0],
                       "law": {"type": "fremond",
                               "normal": {"potential": "py_power", "k": 38.0, "p": 2}}})
    problem, law = f.parse_problem_file(text, reg)
    r = f.solve_impact(problem, law)
    near(r.D_NE, [0.9])
    out = json.loads(f.result_to_json(r))
    near(out["D_NE"], [0.9])
    assert out["admissibility"]["admissible"] is True
    try:
        f.parse_problem_file(text)  # the built-in registry does not know it
    except ValueError as e:
        assert "py_power" in str(e)
    else:
        raise AssertionError("an unknown potential was accepted")


def test_all_solutions_and_residual():
    pb, _ = bar_first_impact()
    law = f.ImpactLaw.newton_coulomb(0.9, 1.0)
    sols = f.solve_impact_all(pb, law)
    assert len(sols) >= 1 and all(s.ok() for s in sols)
    for s in sols:
        assert f.law_residual(pb, law, s) < 1e-12
        rep = f.check_admissibility(pb, law, s)
        assert rep.failed == f.Inequality.total_15


def test_ctrl_c_stops_a_long_run():
    # simulate() releases the GIL; Ctrl-C (SIGINT) must still stop it with KeyboardInterrupt. In a
    # child process: 1e5 s of the viscous bar take about 15 s, the signal comes after 0.3 s.
    code = """
import os, signal, threading, time
import fremond as f
scene = f.paper_bar_scene(f.PaperLaw.fremond_viscous)
threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
t0 = time.time()
try:
    f.simulate(scene, f.SimulationOptions(t_end=1e5, sample_interval=10.0))
    print("finished", time.time() - t0)
except KeyboardInterrupt:
    print("interrupted", time.time() - t0)
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120, env=dict(os.environ)).stdout.split()
    assert out and out[0] == "interrupted", out
    assert float(out[1]) < 5.0, out


def test_a_flight_too_fast_to_resolve_stops_the_run():
    """A bar 1 m up, no gravity, spinning at 1e9 rad/s: its lowest point stays 0.5 m above the
    ground, but the event search cannot prove it within its budget; the run says so at t = 0."""
    scene = f.bar_scene(f.BarParameters(), f.ImpactLaw.newton(0.9))
    scene.gravity = 0.0
    scene.initial = f.PlanarState(q=np.array([0.0, 1.0, 0.3]), qdot=np.array([0.0, 0.0, 1e9]))
    opts = f.SimulationOptions(t_end=1.0, max_gap_evaluations=1000)
    r = f.simulate(scene, opts).result
    assert r.status == f.SimulationStatus.event_search_failed and not r.ok(), r.status
    assert str(r.status) == "event_search_failed" and r.t == 0.0 and r.impacts == 0
    assert r.gap_evaluations == 1000
    opts.max_gap_evaluations = 10
    assert not opts.is_valid()

def test_prepared_solver_answers_as_solve_impact_and_keeps_its_state_on_bad_input():
    # A point mass m falling at v under Newton's law: qdot_E = -e v, P_N = m (1 + e)|v|, at every
    # velocity the prepared solver is given; and each answer equal to solve_impact's.
    m, e = 2.0, 0.5
    pb = f.ImpactProblem(M=np.array([[m]]), W_N=np.array([[1.0]]), qdot_A=np.array([-1.0]))
    law = f.ImpactLaw.newton(e)
    solver = f.ImpactSolver(pb, law)
    for v in (-0.25, -1.0, -40.0):
        r = solver.solve(np.array([v]))
        near(r.qdot_E, [-e * v], rel=1e-15)
        near(r.P_N, [m * (1 + e) * -v], rel=1e-15)
        one_shot = f.solve_impact(
            f.ImpactProblem(M=np.array([[m]]), W_N=np.array([[1.0]]), qdot_A=np.array([v])), law)
        assert r.qdot_E[0] == one_shot.qdot_E[0] and r.P_N[0] == one_shot.P_N[0]
    try:
        solver.solve(np.array([1.0, 2.0]))
        raise AssertionError("a velocity of the wrong size was accepted")
    except ValueError as err:
        assert "qdot_A" in str(err)
    near(solver.solve().qdot_E, [20.0], rel=1e-15)  # the last valid velocity, -40, kept
    # The bar turned: update() takes the next configuration; the answer is solve_impact's on it.
    bar, _ = bar_first_impact()
    nc = f.ImpactLaw.newton_coulomb(0.9, 1.0)
    solver = f.ImpactSolver(bar, nc)
    theta = math.pi / 3
    W_N = np.array([[0.0], [1.0], [-L * math.cos(theta)]])
    W_T = np.array([[1.0], [0.0], [L * math.sin(theta)]])
    solver.update(bar.M, W_N, W_T)
    turned = f.ImpactProblem(M=bar.M, W_N=W_N, W_T=W_T, qdot_A=bar.qdot_A)
    assert list(solver.solve().qdot_E) == list(f.solve_impact(turned, nc).qdot_E)
    try:
        solver.update(np.eye(4), W_N, W_T)
        raise AssertionError("a mass matrix of the wrong size was accepted")
    except ValueError as err:
        assert str(err).startswith("M")
    assert list(solver.result.qdot_E) == list(f.solve_impact(turned, nc).qdot_E)


if __name__ == "__main__":
    run_tests(globals())


def test_any_law_from_its_file_schema():
    # Stronge + Coulomb on a point mass sliding throughout: P_N = (1 + e)|D_NA|, P_T = -mu P_N.
    law = f.ImpactLaw.from_json('{"type": "stronge_coulomb", "e": 0.5, "mu": 0.25}')
    assert law.type == "stronge_coulomb" and law.e == [0.5] and law.mu == [0.25]
    assert law.normal is None
    assert law.eta == [1.0] and law.stiffness == [1.0]
    assert f.ImpactLaw.newton(0.5).eta is None
    pb = f.ImpactProblem(M=np.eye(2), W_N=np.array([[0.0], [1.0]]), W_T=np.array([[1.0], [0.0]]),
                         qdot_A=np.array([1.0, -2.0]))
    r = f.solve_impact(pb, law)
    assert abs(r.P_N[0] - 3.0) < 1e-15 and abs(r.P_T[0] + 0.75) < 1e-15
    assert r.energy_change < 0
    try:
        f.ImpactLaw.from_json('{"type": "stronge", "e": 2}')
    except ValueError as e:
        assert "law.e" in str(e)
    else:
        raise AssertionError("e = 2 accepted")


def test_stronge_on_coupled_contacts():
    # A ball in the middle struck from both sides at speed 1 (masses 1): by symmetry it stays at
    # rest and each outer ball meets a wall, P = 1 + e, whatever eta and the equal stiffnesses.
    law = f.ImpactLaw.from_json('{"type": "stronge", "e": 0.6, "eta": 1.5, "stiffness": [2, 2]}',
                                contacts=2)
    assert law.eta == [1.5] and law.stiffness == [2.0, 2.0]
    pb = f.ImpactProblem(M=np.eye(3), W_N=np.array([[-1.0, 0.0], [1.0, -1.0], [0.0, 1.0]]),
                         qdot_A=np.array([1.0, 0.0, -1.0]))
    r = f.solve_impact(pb, law)
    assert r.solver.method == f.SolverMethod.impulse_integration
    assert abs(r.P_N[0] - 1.6) < 1e-9 and abs(r.P_N[1] - 1.6) < 1e-9
    try:
        f.ImpactLaw.from_json('{"type": "stronge", "e": 0.5, "eta": 0}')
    except ValueError as e:
        assert "law.eta" in str(e)
    else:
        raise AssertionError("eta = 0 accepted")
