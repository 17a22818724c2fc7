"""Sparse problems from Python (docs/sparse.md): scipy.sparse matrices in, the hand-derived answer
of a falling stack out, the dense solvers' answer on a random problem, and Siconos's own file."""
import numpy as np
import scipy.sparse as sp

from support import ROOT, near, run_tests
import fremond as f


def falling_stack(v):
    """Three disks (m = 1, J = 0.1, r = 0.5) stacked on the ground, all falling at v."""
    n = 9
    M = sp.diags([1, 1, 0.1] * 3).tocsc()
    W_N = np.zeros((n, 3))
    W_T = np.zeros((n, 3))
    W_N[1, 0], W_T[0, 0], W_T[2, 0] = 1, 1, -0.5
    for k in (1, 2):
        lo, hi = 3 * (k - 1), 3 * k
        W_N[hi + 1, k], W_N[lo + 1, k] = 1, -1
        W_T[hi, k], W_T[hi + 2, k], W_T[lo, k], W_T[lo + 2, k] = 1, -0.5, -1, -0.5
    qdot_A = np.zeros(n)
    qdot_A[1::3] = -v
    return f.SparseImpactProblem(M=M, W_N=sp.csc_matrix(W_N), W_T=sp.csc_matrix(W_T),
                                 qdot_A=qdot_A)


def test_falling_stack_stops_as_one_body():
    # e = 0: the ground takes 3 m v, the next contact 2 m v, the top one m v.
    r = f.solve_sparse(falling_stack(2.0), f.ImpactLaw.newton_coulomb(e=0.0, mu=0.5))
    assert r.ok()
    near(r.P_N, [6.0, 4.0, 2.0], 1e-9, 1e-9)
    near(r.qdot_E, np.zeros(9), 0, 1e-9)
    near([r.energy_change], [-6.0], 1e-9)


def test_agrees_with_the_dense_solver():
    rng = np.random.default_rng(5)
    n, c = 12, 4
    A = rng.uniform(-1, 1, (n, n))
    M = A @ A.T / n + 0.5 * np.eye(n)
    W_N = rng.uniform(-1, 1, (n, c))
    W_T = rng.uniform(-1, 1, (n, c))
    qdot_A = rng.uniform(-1, 1, n)
    W_N[:, W_N.T @ qdot_A > 0] *= -1
    law = f.ImpactLaw.newton_coulomb(e=0.5, mu=0.3)
    dense = f.solve_impact(f.ImpactProblem(M=M, W_N=W_N, W_T=W_T, qdot_A=qdot_A), law)
    sparse = f.solve_sparse(
        f.SparseImpactProblem(M=sp.csc_matrix(M), W_N=sp.csc_matrix(W_N), W_T=sp.csc_matrix(W_T),
                              qdot_A=qdot_A), law, f.SparseSolverOptions(tolerance=1e-15))
    assert dense.ok() and sparse.ok()
    near(sparse.P_N, dense.P_N, 1e-10, 1e-12)
    near(sparse.qdot_E, dense.qdot_E, 1e-10, 1e-12)


def test_siconos_file():
    p = f.read_siconos_file(str(ROOT / "tests/data/siconos-fc2d/fc2d_granularflowonwall_00667_00000.dat"))
    assert p.form == "local" and p.contacts() == 667
    r = f.solve_contact_problem(p.contact, p.law(), f.SparseSolverOptions(tolerance=1e-10))
    assert r.ok() and r.solver.residual <= 1e-10
    assert f.contact_residual(p.contact, p.law(), r) <= 1e-10
    assert min(r.P_N) >= 0
    # G printed with 6 significant digits, q with 25: each known to half a unit of its last digit.
    assert p.contact.G_rounding == 5e-6 and p.contact.D_A_rounding == 5e-25
    exact = f.ContactProblem(p.contact.G, p.contact.D_A)
    assert exact.G_rounding == 0.0 and exact.D_A_rounding == 0.0
    try:
        f.ContactProblem(p.contact.G, p.contact.D_A, G_rounding=0.5)
        raise AssertionError("accepted")
    except ValueError as e:
        assert "G_rounding" in str(e)


def test_refusals_name_the_value():
    try:
        f.SparseSolverOptions(tolerance=0.5).validate()
        raise AssertionError("accepted")
    except ValueError as e:
        assert "tolerance" in str(e)
    try:
        f.read_siconos_file("/nonexistent.dat")
        raise AssertionError("accepted")
    except ValueError as e:
        assert "cannot open" in str(e)


def test_newton_polish_is_an_option():
    o = f.SparseSolverOptions(tolerance=1e-12, newton_polish=False)
    assert o.newton_polish is False
    assert f.SparseSolverOptions().newton_polish is True
    assert f.AttemptStart.sweeps_end.name == "sweeps_end"


def test_acceleration_is_an_option_and_both_meet_the_law():
    assert f.SparseSolverOptions().acceleration is True
    p = f.read_siconos_file(str(ROOT / "tests/data/siconos-fc2d/fc2d_granularflowonwall_00667_00000.dat"))
    for on in (True, False):
        o = f.SparseSolverOptions(tolerance=1e-10, acceleration=on)
        assert o.acceleration is on
        r = f.solve_contact_problem(p.contact, p.law(), o)
        assert r.ok()
        assert f.contact_residual(p.contact, p.law(), r) <= 1e-10


if __name__ == "__main__":
    run_tests(globals())
