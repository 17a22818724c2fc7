"""Scenes of several bodies from Python: Newton's cradle against the answers derived by hand in
tests/unit/ball_chain_test.cpp, and the dropped ball's run against its flight in closed form."""
import math

import numpy as np

from support import near, run_tests
import fremond as f


def test_cradle_of_three_under_newton():
    # G = [[2, -1], [-1, 2]], D_A = (-1, 0); e = 1: P = (4/3, 2/3), v = (-1/3, 2/3, 2/3).
    s = f.cradle_scene(f.CradleParameters(balls=3), f.ImpactLaw.newton(1.0))
    idx = f.touching_contacts(s, s.initial.q)
    assert list(idx) == [0, 2]
    pb = f.impact_problem(s, s.initial, idx)
    r = f.solve_impact(pb, f.law_of(s, idx))
    near(r.qdot_E[0::3], [-1 / 3, 2 / 3, 2 / 3], rel=0, tiny=1e-15)
    near(f.momentum(s, r.qdot_E), [1.0, 0.0], rel=0, tiny=1e-15)


def test_dropped_ball_run():
    # Contact at t1 = sqrt(2h/g) at v = sqrt(2gh); Newton e = 1 sends the upper ball back at v.
    g, h = 9.81, 0.5
    s = f.ball_on_ball_scene(f.BallOnBallParameters(drop_height=h), f.ImpactLaw.newton(1.0))
    run = f.simulate(s, f.SimulationOptions(t_end=0.5, sample_interval=0.01))
    assert run.result.ok() and run.result.impacts == 1
    near([run.impacts[0].t], [math.sqrt(2 * h / g)], rel=1e-12)
    near([run.impacts[0].qdot_E[4]], [math.sqrt(2 * g * h)], rel=1e-12)
    assert run.q.shape[1] == 6 and np.all(run.q[:, 1] == 0.1)
    near(run.energy, np.full(len(run.energy), run.energy[0]), rel=1e-13)


if __name__ == "__main__":
    run_tests(globals())
