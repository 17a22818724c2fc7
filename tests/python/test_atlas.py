"""The law atlas from Python: `fremond atlas`'s CSV and NPZ load back with numpy to the same
numbers, which are fremond.atlas's arrays to the last bit; the NPZ is a plain stored zip; a bad
value raises ValueError naming it; and a closed form written here (a frictionless point under
Newton's law, which keeps its tangential velocity) holds on the map."""
import csv
import math
import subprocess
import tempfile
import zipfile
from pathlib import Path

import numpy as np

from support import cli, run_tests
import fremond as f

SWEEP = dict(laws=["newton_coulomb", "fremond"], values=[0.3, 1.0], theta_count=12,
             psi_count=15, spins=[0.0, 0.5])
CLI_ARGS = ["--laws", "newton_coulomb,fremond", "--mu", "0.3,1", "--grid", "12x15", "--spin",
            "0,0.5"]


def same(a, b):
    """Equal to the last bit, NaN where both are NaN."""
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype.kind == "f":
        return a.shape == b.shape and np.array_equal(a, b, equal_nan=True)
    return a.shape == b.shape and np.array_equal(a, b)


def test_cli_csv_and_npz_load_back_as_the_bindings_arrays():
    exe = cli()
    if exe is None:
        print("skipped: no fremond command (set FREMOND_CLI)")
        return
    with tempfile.TemporaryDirectory() as tmp:
        npz_path, csv_path = Path(tmp) / "a.npz", Path(tmp) / "a.csv"
        subprocess.run([exe, "atlas", *CLI_ARGS, "--npz", str(npz_path), "--csv", str(csv_path)],
                       capture_output=True, text=True, check=True)
        with zipfile.ZipFile(npz_path) as z:
            assert z.testzip() is None  # every CRC-32 right
            assert {i.compress_type for i in z.infolist()} == {zipfile.ZIP_STORED}
        with np.load(npz_path) as data:
            npz = {k: data[k] for k in data.files}
        with open(csv_path, newline="") as fh:
            rows = list(csv.DictReader(fh))
    mine = f.atlas(**SWEEP)
    assert set(npz) == set(mine)
    for k, v in mine.items():
        assert same(npz[k], v), k

    shape = npz["energy_ratio"].shape
    assert shape == (2, 2, 2, 12, 15)
    assert len(rows) == int(np.prod(shape))
    names = {k: list(npz[k + "_names"]) for k in ("failed", "status", "mode")}
    for k, row in enumerate(rows):
        l, v, s, i, j = np.unravel_index(k, shape)
        assert row["law"] == npz["laws"][l]
        assert float(row["mu"]) == npz["values"][v] and float(row["e"]) == npz["e"]
        assert float(row["spin"]) == npz["spins"][s]
        assert float(row["theta"]) == npz["theta"][i] and float(row["psi"]) == npz["psi"][j]
        for col in ("D_NA", "D_TA"):
            assert float(row[col]) == npz[col][s, i, j]
        assert float(row["T_A"]) == npz["kinetic_energy"][s, i, j]
        for col in ("energy_ratio", "distance", "P_N", "P_T", "D_NE", "D_TE"):
            assert same(float(row[col]), npz[col][l, v, s, i, j]), col
        for d, col in enumerate(("xdot_E", "ydot_E", "thetadot_E")):
            assert same(float(row[col]), npz["qdot_E"][l, v, s, i, j, d]), col
        assert int(row["admissible"]) == npz["admissible"][l, v, s, i, j]
        assert int(row["solutions"]) == npz["solutions"][l, v, s, i, j]
        for col in ("failed", "status", "mode"):
            assert row[col] == names[col][npz[col][l, v, s, i, j]], col
        k_N = float(row["k_N"])
        assert (math.isnan(k_N) if row["law"] != "fremond" else k_N == npz["fremond_k_N"][v])


def test_frictionless_newton_keeps_the_tangential_velocity():
    # Without friction P_T = 0, so D_NE = -e D_NA and D_TE = D_TA + G_TN P_N with
    # P_N = (1 + e)|D_NA| / G_NN; for the bar (m = 1, l = 0.5, J = 1/12) at angle theta,
    # G_NN = 1 + 3 cos^2, G_TN = -3 cos sin (the lower end a = (-l cos, -l sin)).
    e = 0.7
    d = f.atlas(laws=["newton"], parameter="e", values=[e], theta_count=9, psi_count=11,
                theta_max=3.0, speed=2.0)
    th = d["theta"][:, None]
    G_NN, G_TN = 1 + 3 * np.cos(th) ** 2, -3 * np.cos(th) * np.sin(th)
    P_N = (1 + e) * -d["D_NA"][0] / G_NN
    assert np.allclose(d["P_N"][0, 0, 0], P_N, rtol=1e-13, atol=1e-14)
    assert np.allclose(d["D_NE"][0, 0, 0], -e * d["D_NA"][0], rtol=1e-13, atol=1e-14)
    assert np.allclose(d["D_TE"][0, 0, 0], d["D_TA"][0] + G_TN * P_N, rtol=1e-13, atol=1e-14)
    assert np.all(d["energy_ratio"] <= 0) and np.all(d["admissible"] == 1)


def test_bad_values_raise_naming_them():
    for kwargs, name in [(dict(laws=["lagrange"]), "laws[0]"), (dict(values=[-1.0]), "values[0]"),
                         (dict(parameter="k"), "parameter"), (dict(psi_max=1.0), "psi_max"),
                         (dict(theta_count=0), "theta_count")]:
        try:
            f.atlas(**kwargs)
        except ValueError as e:
            assert str(e).startswith(name + ":"), (kwargs, str(e))
        else:
            raise AssertionError(f"{kwargs} accepted")


def test_progress_is_called_with_the_lock():
    calls = []
    f.atlas(laws=["newton_coulomb"], theta_count=70, psi_count=70,
            progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1] == (4900, 4900)
    assert [c[0] for c in calls] == sorted(c[0] for c in calls)


if __name__ == "__main__":
    run_tests(globals())
