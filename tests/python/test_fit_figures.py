"""scripts/fit_figures.py on drops of a ball from several heights, made by Frémond's law with p = 3
(restitution rising with speed): the figures are written, and the ranking puts Frémond's law, which
made the data, above Newton's constant e, whose fitted e lies between the slowest and the fastest
drop's restitution."""
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

from support import run_tests
import fremond as f

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "fit_figures.py")
MASS, G = 0.2, 9.81


def drops():
    law = f.make_law("fremond", {"k": 0.8, "p": 3.0})
    rng = np.random.default_rng(5)
    rows, restitution = [], []
    for h in (0.02, 0.05, 0.1, 0.2, 0.4, 0.7, 1.0, 1.5, 2.0, 3.0):
        v = -math.sqrt(2 * G * h)
        pb = f.ImpactProblem(M=np.array([[MASS]]), W_N=np.array([[1.0]]), qdot_A=np.array([v]))
        after = f.solve_impact(pb, law).qdot_E[0]
        restitution.append(-after / v)
        sigma = 0.005 * abs(v)
        for _ in range(3):
            rows.append({"M": [[MASS]], "W_N": [[1.0]], "qdot_A": [v],
                         "qdot_E": [after + sigma * rng.standard_normal()], "sigma": [sigma]})
    return rows, restitution


def test_figures_and_ranking_of_drops():
    rows, restitution = drops()
    with tempfile.TemporaryDirectory() as tmp:
        data = os.path.join(tmp, "drops.json")
        with open(data, "w", encoding="utf-8") as fh:
            json.dump(rows, fh)
        out = os.path.join(tmp, "figures")
        run = subprocess.run([sys.executable, SCRIPT, data, "--law", "newton,fremond", "--out", out],
                             capture_output=True, text=True, check=False)
        assert run.returncode == 0, run.stderr
        for name in ("predicted_vs_measured.png", "residuals.png", "restitution.png"):
            assert os.path.getsize(os.path.join(out, name)) > 10000, name
        with open(os.path.join(out, "ranking.csv"), encoding="utf-8") as fh:
            lines = fh.read().splitlines()
    assert lines[0] == "family,parameters,training_rms,heldout_rms"
    first, second = (line.split(",") for line in lines[1:3])
    assert first[0] == "fremond" and second[0] == "newton", lines
    assert float(first[3]) < 2.0 < 5.0 < float(second[3]), lines
    e = float(second[1].split("=")[1])
    assert min(restitution) < e < max(restitution), (e, restitution)


if __name__ == "__main__":
    run_tests(globals())
