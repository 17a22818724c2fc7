"""Laws against measurements from Python (docs/measurements.md): predict and fit_law on a point mass
sliding onto the ground, its measurements made from Newton + Coulomb's closed form here
(v_N' = -e v_N; v_T' = v_T - mu (1 + e)|v_N| while it slides, 0 once it sticks)."""
import json
import math

import numpy as np

from support import run_tests
import fremond as f

E, MU = 0.7, 0.2


def closed_form(vt, vn, e=E, mu=MU):
    return max(vt - mu * (1 + e) * abs(vn), 0.0), -e * vn


def impacts(noise=0.0, seed=2):
    rng = np.random.default_rng(seed)
    out = []
    for vn in (-1.0, -2.0, -3.0):
        for vt in (0.0, 0.2, 0.5, 1.0, 2.0, 3.0):
            pb = f.ImpactProblem(np.eye(2), np.array([[0.0], [1.0]]), np.array([vt, vn]),
                                 W_T=np.array([[1.0], [0.0]]))
            after = np.array(closed_form(vt, vn)) + noise * rng.standard_normal(2)
            out.append(f.MeasuredImpact(pb, after, sigma=np.full(2, noise or 0.01)))
    return out


def test_predict_matches_the_closed_form():
    data = impacts()
    p = f.predict(data, f.make_law("newton_coulomb", {"e": E, "mu": MU}))
    assert p.rms < 1e-9 and p.failed == 0 and p.measured == 36
    off = f.predict(data, f.ImpactLaw.newton_coulomb(e=0.8, mu=MU))
    for mi, r in zip(data, off.residuals):
        assert abs(r[1] - 0.1 * abs(mi.problem.qdot_A[1]) / 0.01) < 1e-6


def test_fit_recovers_e_and_mu_without_noise():
    r = f.fit_law(impacts(), "newton_coulomb", folds=3)
    assert r.family == "newton_coulomb" and r.names == ["e", "mu"]
    assert abs(r.parameters["e"] - E) < 1e-6 and abs(r.parameters["mu"] - MU) < 1e-6, r
    assert r.heldout_rms < 1e-3 and r.evaluations > 0


def test_fit_with_noise_within_its_uncertainty_and_ranked_first():
    data = impacts(noise=0.01)
    ranked = f.fit_laws(data, ["newton", "newton_coulomb", "fremond"], seed=4)
    best = ranked[0]
    assert best.family == "newton_coulomb", [(x.family, x.heldout_rms) for x in ranked]
    for name, true in (("e", E), ("mu", MU)):
        sd = best.parameter_uncertainties[name]
        assert 0 < sd < 0.05 and abs(best.parameters[name] - true) < 4 * sd, (name, best)


def test_measurement_file_and_refusals():
    rows = [{"M": [[1, 0], [0, 1]], "W_N": [[0], [1]], "W_T": [[1], [0]], "qdot_A": [1, -1],
             "qdot_E": [None, 0.7]}]
    data = f.parse_measurements(json.dumps(rows))
    assert list(data[0].mask) == [False, True] and data[0].measured() == 1
    rows.append(dict(rows[0], sigma=[1, -1]))
    try:
        f.parse_measurements(json.dumps(rows))
        raise AssertionError("accepted a negative sigma")
    except ValueError as e:
        assert "impacts[1].sigma[1]" in str(e), e
    try:
        f.fit_law(impacts(), "newton", folds=1)
        raise AssertionError("accepted one fold")
    except ValueError as e:
        assert "folds" in str(e), e
    assert "fremond_deadzone" in f.law_families()
    assert f.fitted_parameters("fremond_coulomb") == ["k", "p", "mu"]
    assert math.isfinite(f.fit_law(impacts(), "newton", folds=0, global_evaluations=0).values[0])


if __name__ == "__main__":
    run_tests(globals())
