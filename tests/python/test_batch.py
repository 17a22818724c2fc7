"""Batches from Python: a list of problems, or NumPy arrays of shape (N, ...), each answer equal to
solve_impact's and balancing momentum."""
import math

import numpy as np

from support import run_tests
import fremond as f

L = 0.5


def bar_arrays(n, seed=3):
    """n bars at random angles, lower end approaching: M shared, W_N, W_T and qdot_A per bar."""
    rng = np.random.default_rng(seed)
    theta = rng.uniform(0.05, 1.5, n)
    W_N = np.zeros((n, 3, 1))
    W_T = np.zeros((n, 3, 1))
    W_N[:, 1, 0] = 1.0
    W_N[:, 2, 0] = -L * np.cos(theta)
    W_T[:, 0, 0] = 1.0
    W_T[:, 2, 0] = L * np.sin(theta)
    qdot_A = np.column_stack([rng.uniform(-3, 3, n), -1 - rng.uniform(0, 3, n), rng.uniform(-3, 3, n)])
    M = np.diag([1.0, 1.0, L * L / 3])
    return M, W_N, W_T, qdot_A


def test_arrays_give_solve_impacts_answers():
    M, W_N, W_T, qdot_A = bar_arrays(200)
    law = f.ImpactLaw.newton_coulomb(e=0.9, mu=1.0)
    out = f.solve_batch_arrays(M, W_N, qdot_A, law, W_T=W_T, threads=2)
    assert out["qdot_E"].shape == (200, 3) and out["P_N"].shape == (200, 1)
    for i in range(200):
        p = f.ImpactProblem(M=M, W_N=W_N[i], W_T=W_T[i], qdot_A=qdot_A[i])
        r = f.solve_impact(p, law)
        assert np.array_equal(out["qdot_E"][i], r.qdot_E), i
        assert np.array_equal(out["P_N"][i], r.P_N) and np.array_equal(out["P_T"][i], r.P_T), i
        assert f.SolverStatus(int(out["status"][i])) == r.solver.status, i
        assert out["admissible"][i] == r.admissibility.admissible, i
    # Momentum balance, an identity the answers must keep: M (qdot_E - qdot_A) = W_N P_N + W_T P_T.
    lhs = (out["qdot_E"] - qdot_A) @ M.T
    rhs = np.einsum("ijk,ik->ij", W_N, out["P_N"]) + np.einsum("ijk,ik->ij", W_T, out["P_T"])
    assert np.max(np.abs(lhs - rhs)) <= 1e-13 * (1 + np.max(np.abs(rhs)))


def test_one_configuration_many_velocities():
    # Only qdot_A per problem: the configuration is prepared once; the answers are still
    # solve_impact's, bit for bit, and a bad velocity is named by its index in qdot_A.
    M, W_N, W_T, qdot_A = bar_arrays(300, seed=7)
    law = f.ImpactLaw.poisson_coulomb(e=0.6, mu=0.4)
    out = f.solve_batch_arrays(M, W_N[0], qdot_A, law, W_T=W_T[0], threads=2)
    for i in range(300):
        r = f.solve_impact(f.ImpactProblem(M=M, W_N=W_N[0], W_T=W_T[0], qdot_A=qdot_A[i]), law)
        assert np.array_equal(out["qdot_E"][i], r.qdot_E), i
        assert np.array_equal(out["P_N"][i], r.P_N) and np.array_equal(out["P_T"][i], r.P_T), i
        assert out["residual"][i] == r.solver.residual and out["energy_change"][i] == r.energy_change
    bad = qdot_A.copy()
    bad[5, 2] = np.nan
    try:
        f.solve_batch_arrays(M, W_N[0], bad, law, W_T=W_T[0])
        raise AssertionError("a velocity that is not a number was solved")
    except ValueError as e:
        assert str(e).startswith("qdot_A[5][2]"), e


def test_an_unsupported_method_gives_nan_rows():
    # Stronge's law has no Lemke: each answer is `unsupported`, with no velocities or percussions,
    # and their rows read NaN on both paths (one configuration, and a problem per row).
    M, W_N, W_T, qdot_A = bar_arrays(20)
    law = f.ImpactLaw.from_json('{"type": "stronge_coulomb", "e": 0.8, "mu": 0.5}')
    options = f.SolverOptions(method="lemke")
    for W_N_given, W_T_given in ((W_N[0], W_T[0]), (W_N, W_T)):
        out = f.solve_batch_arrays(M, W_N_given, qdot_A, law, W_T=W_T_given, options=options)
        assert all(f.SolverStatus(int(s)) == f.SolverStatus.unsupported for s in out["status"])
        assert np.isnan(out["qdot_E"]).all() and np.isnan(out["P_N"]).all()


def test_list_of_problems_and_frictionless_closed_form():
    # Newton frictionless on one contact (eq. 5): D_NE = -e D_NA where the contact approaches,
    # D_NE = D_NA (no percussion) where it separates.
    M, W_N, _, qdot_A = bar_arrays(50, seed=5)
    problems = [f.ImpactProblem(M=M, W_N=W_N[i], qdot_A=qdot_A[i]) for i in range(50)]
    results = f.solve_batch(problems, f.ImpactLaw.newton(e=0.7))
    approaching = 0
    for i, r in enumerate(results):
        D_NA = float(W_N[i][:, 0] @ qdot_A[i])
        expected = -0.7 * D_NA if D_NA < 0 else D_NA
        approaching += D_NA < 0
        assert math.isclose(r.D_NE[0], expected, rel_tol=1e-13, abs_tol=1e-14), (i, r.D_NE, expected)
    assert approaching > 25


def test_bad_shapes_and_problems_are_named():
    M, W_N, W_T, qdot_A = bar_arrays(4)
    law = f.ImpactLaw.newton(e=0.5)
    try:
        f.solve_batch_arrays(M, W_N[:3], qdot_A, law)
        raise AssertionError("a W_N of 3 problems was paired with 4 velocities")
    except ValueError as e:
        assert "W_N" in str(e), e
    bad = np.array([M, M, M, M])
    bad[2, 2, 2] = -1.0
    try:
        f.solve_batch_arrays(bad, W_N, qdot_A, law)
        raise AssertionError("a mass matrix that is not positive definite was accepted")
    except ValueError as e:
        assert "problems[2].M" in str(e), e


def test_what_a_law_answers():
    phi = f.PowerPotential(k=4.0, p=3.0)
    cases = [
        (f.ImpactLaw.newton(e=0.5), (False, False, False, False, False)),
        (f.ImpactLaw.poisson_coulomb(e=0.5, mu=0.3), (False, True, True, True, False)),
        (f.ImpactLaw.fremond(normal=phi), (True, False, False, False, False)),
        (f.ImpactLaw.fremond(normal=phi, tangential=phi), (True, False, True, False, True)),
        (f.ImpactLaw.fremond_coulomb(normal=phi, mu=0.3), (True, False, True, True, False)),
    ]
    for law, want in cases:
        got = (law.is_fremond(), law.has_phases(), law.has_friction(), law.uses_coulomb(),
               law.has_tangential_potential())
        assert got == want, (law.describe(), got, want)


if __name__ == "__main__":
    run_tests(globals())
