"""`fremond impact` on hard one-contact problems, against references computed with mpmath at 40
digits from the laws themselves (docs/laws.md), independently of the library and of its __float128
reference in tests/reference.

The problems are the paper's bar (the paper's Fig. 1) at random angles, with the issue's hard parameters:
mass ratios up to 1e6 (a light rotor: J = m l²/3 / 1e6), velocities from 1e-10 to 1e6, p from
1.01 to 50, q from 1.01, dead zones from 0 to far above every velocity, k from 1e-6 to 1e6. Each
answer must be `converged` and its velocity after impact within 1e-9 of the reference in the
kinetic-energy norm, relative to the velocity before. (The worst seen: 2e-10, on the light rotor
with k = 1e6, where the percussion P = -k z of a mean velocity z ~ 1e-6 is resolved only to k ε|D|.)

The references:
- Frémond with the viscous dead zone: both rows are monotone, so P_T is found by bisection on the
  tangential row with P_N(P_T) found by bisection on the normal row (reaction included).
- Frémond + Coulomb: stick (z_T = 0) and slide in either direction with either sign of P_N, each
  an affine P_T(P_N) and one monotone normal row; a mode counts when its inequalities hold.
- Newton + Coulomb: stick and slide, each a linear system (D_NE = -e D_NA).
- Poisson + Coulomb: the compression's modes (D_NC = 0), then the expansion's (open: P_NE = e P_NC;
  or closed: D_NE = 0 with P_NE >= e P_NC), each stick or slide.
"""
import json
import math
import random
import subprocess

import mpmath as mp

from support import cli, run_tests

mp.mp.dps = 40
L = 0.5  # the bar's half-length (the paper's Fig. 1)


def bar_problem(rng, law):
    """The bar at a random angle with the hard parameters of the docstring."""
    th = rng.uniform(0.05, 1.5)
    ratio = 10 ** rng.choice([0, 0, 3, 6])
    vs = 10 ** rng.choice([-10, -5, 0, 0, 3, 6])
    c, s = math.cos(th), math.sin(th)
    return {"M": [[1, 0, 0], [0, 1, 0], [0, 0, L * L / 3 / ratio]],
            "W_N": [[0], [1], [-L * c]], "W_T": [[1], [0], [L * s]],
            "qdot_A": [vs * rng.uniform(-2, 2), -vs * rng.uniform(0.1, 4), vs * rng.uniform(-3, 3)],
            "law": law(rng, vs)}


def contact_space(pb):
    """G = Wᵀ M⁻¹ W and D_A of the one contact (rows N, T), exactly from the doubles given."""
    Minv = mp.matrix(pb["M"]) ** -1
    wn = mp.matrix([row[0] for row in pb["W_N"]])
    wt = mp.matrix([row[0] for row in pb["W_T"]])
    qa = mp.matrix(pb["qdot_A"])
    G = [[(a.T * Minv * b)[0] for b in (wn, wt)] for a in (wn, wt)]
    return G, [(wn.T * qa)[0], (wt.T * qa)[0]], Minv, wn, wt, qa


def velocity_after(pb, PN, PT):
    _, _, Minv, wn, wt, qa = contact_space(pb)
    return qa + Minv * (wn * PN + wt * PT)


def error(pb, answer, qE):
    """‖q̇_E − q̇_E,ref‖_M / ‖q̇_A‖_M."""
    M = mp.matrix(pb["M"])
    qa = mp.matrix(pb["qdot_A"])
    d = mp.matrix([mp.mpf(answer[i]) - qE[i] for i in range(3)])
    return float(mp.sqrt((d.T * M * d)[0] / (qa.T * M * qa)[0]))


def bisect(f, lo, hi, iterations=160):
    flo = f(lo)
    for _ in range(iterations):
        mid = (lo + hi) / 2
        fm = f(mid)
        if fm == 0:
            return mid
        if (fm < 0) == (flo < 0):
            lo, flo = mid, fm
        else:
            hi = mid
    return (lo + hi) / 2


def root_of_increasing(f):
    a = mp.mpf(1)
    while f(-a) > 0:
        a *= 4
    b = mp.mpf(1)
    while f(b) < 0:
        b *= 4
    return bisect(f, -a, b)


def power_slope(k, p):
    return lambda z: k * mp.sign(z) * abs(z) ** (p - 1)


def dead_zone_slope(k, q, r):
    return lambda y: k * mp.sign(y) * max(mp.mpf(0), abs(y) - r) ** (q - 1)


def normal_row(G, D, dphi, a0, a1):
    """P_N of Frémond's normal row (power law and reaction, docs/laws.md) with P_T = a0 + a1 P_N; None
    where the row is not monotone (a Painlevé-type slide, μ|G_NT| > G_NN)."""
    c = G[0][0] + G[0][1] * a1
    if c <= 0:
        return None
    lb = D[0] / 2  # z_N >= D_NA/2, i.e. D_NE >= 0
    at_bound = (lb - D[0] - G[0][1] * a0 / 2) * 2 / c
    if at_bound + dphi(lb) >= 0:
        return at_bound
    z = lambda PN: D[0] + (G[0][0] * PN + G[0][1] * (a0 + a1 * PN)) / 2  # noqa: E731
    return root_of_increasing(lambda PN: PN + dphi(z(PN)))


def fremond_viscous(pb):
    G, D, *_ = contact_space(pb)
    if D[0] > 0:
        return [(0, 0)]
    n, t = pb["law"]["normal"], pb["law"]["tangential"]
    dN = power_slope(mp.mpf(n["k"]), mp.mpf(n["p"]))
    dT = dead_zone_slope(mp.mpf(t["k"]), mp.mpf(t["q"]), mp.mpf(t["r"]))

    def tangential(PT):
        PN = normal_row(G, D, dN, PT, 0)
        return PT + dT(D[1] + (G[1][0] * PN + G[1][1] * PT) / 2)

    PT = root_of_increasing(tangential)
    return [(normal_row(G, D, dN, PT, 0), PT)]


def fremond_coulomb(pb):
    G, D, *_ = contact_space(pb)
    if D[0] > 0:
        return [(0, 0)]
    n, mu = pb["law"]["normal"], mp.mpf(pb["law"]["tangential"]["mu"])
    dN = power_slope(mp.mpf(n["k"]), mp.mpf(n["p"]))
    out = []
    a0, a1 = -2 * D[1] / G[1][1], -G[1][0] / G[1][1]  # stick: z_T = 0
    PN = normal_row(G, D, dN, a0, a1)
    if PN is None:
        return None
    if abs(a0 + a1 * PN) <= mu * abs(PN) * (1 + mp.mpf(10) ** -30):
        out.append((PN, a0 + a1 * PN))
    for slide in (1, -1):
        for sign in (1, -1):  # of P_N: Frémond's normal law may pull
            PN = normal_row(G, D, dN, 0, -slide * mu * sign)
            if PN is None:
                return None
            if PN * sign < 0:
                continue
            PT = -slide * mu * abs(PN)
            if (D[1] + (G[1][0] * PN + G[1][1] * PT) / 2) * slide > 0:
                out.append((PN, PT))
    return out


def stick_or_slide(G, D, target_N, mu, PN_min=0):
    """The phase's answers with D_N after = target_N: stick (D_T after = 0) or slide."""
    out = []
    det = G[0][0] * G[1][1] - G[0][1] * G[1][0]
    if det != 0:
        b0, b1 = target_N - D[0], -D[1]
        PN = (b0 * G[1][1] - G[0][1] * b1) / det
        PT = (G[0][0] * b1 - G[1][0] * b0) / det
        if PN >= PN_min and abs(PT) <= mu * PN * (1 + mp.mpf(10) ** -30):
            out.append((PN, PT))
    for slide in (1, -1):
        c = G[0][0] - slide * mu * G[0][1]
        if c == 0:
            continue
        PN = (target_N - D[0]) / c
        PT = -slide * mu * PN
        if PN >= PN_min and (D[1] + G[1][0] * PN + G[1][1] * PT) * slide > 0:
            out.append((PN, PT))
    return out


def newton_coulomb(pb):
    G, D, *_ = contact_space(pb)
    if D[0] > 0:
        return [(0, 0)]
    e, mu = mp.mpf(pb["law"]["e"]), mp.mpf(pb["law"]["mu"])
    return stick_or_slide(G, D, -e * D[0], mu)


def poisson_coulomb(pb):
    G, D, *_ = contact_space(pb)
    if D[0] > 0:
        return [(0, 0)]
    e, mu = mp.mpf(pb["law"]["e"]), mp.mpf(pb["law"]["mu"])
    after = lambda D, PN, PT: [D[0] + G[0][0] * PN + G[0][1] * PT,  # noqa: E731
                               D[1] + G[1][0] * PN + G[1][1] * PT]
    out = []
    for PNC, PTC in stick_or_slide(G, D, 0, mu):
        DC = after(D, PNC, PTC)
        PNE = e * PNC  # open: ΔP = 0, D_NE >= 0
        expansion = []
        for PTE in [-(DC[1] + G[1][0] * PNE) / G[1][1], -mu * PNE, mu * PNE]:
            DE = after(DC, PNE, PTE)
            stick = abs(PTE) <= mu * PNE * (1 + mp.mpf(10) ** -30) and abs(DE[1]) < 1e-30
            slide = PTE == -mp.sign(DE[1]) * mu * PNE and DE[1] != 0
            if DE[0] >= 0 and (stick or slide):
                expansion.append((PNE, PTE))
        expansion += stick_or_slide(G, DC, 0, mu, PN_min=e * PNC)  # closed: D_NE = 0
        out += [(PNC + a, PTC + b) for a, b in expansion]
    return out


def check(law_of, reference, cases, seed):
    exe = cli()
    if exe is None:
        print("skipped: no fremond command (set FREMOND_CLI)")
        return
    rng = random.Random(seed)
    worst = 0.0
    for case in range(cases):
        pb = bar_problem(rng, law_of)
        out = subprocess.run([exe, "impact", "-"], input=json.dumps(pb), capture_output=True,
                             text=True)
        r = json.loads(out.stdout)
        where = f"case {case}: {json.dumps(pb)}"
        answers = reference(pb)
        if answers is None:  # a Painlevé-type mode: the reference does not enumerate its roots
            continue
        assert answers, f"the reference finds no answer: {where}"
        assert r["solver"]["status"] == "converged", f"{r['solver']}: {where}"
        err = min(error(pb, r["qdot_E"], velocity_after(pb, PN, PT)) for PN, PT in answers)
        assert err <= 1e-9, f"q̇_E {err:.2e} from the reference: {where}"
        worst = max(worst, err)
    print(f"worst {worst:.2e} over {cases} problems")


def viscous_law(rng, vs):
    return {"type": "fremond",
            "normal": {"potential": "power", "k": 10 ** rng.choice([-6, -2, 0, 2, 6]),
                       "p": rng.choice([1.01, 1.1, 1.5, 2, 3, 10, 50])},
            "tangential": {"potential": "deadzone_power", "k": 10 ** rng.choice([-6, 0, 2, 6]),
                           "q": rng.choice([1.01, 1.5, 2, 3]),
                           "r": rng.choice([0, 0.2 * vs, 1e3 * vs, 0.5 * vs])}}


def coulomb_law(rng, vs):
    return {"type": "fremond",
            "normal": {"potential": "power", "k": 10 ** rng.choice([-6, -2, 0, 2, 6]),
                       "p": rng.choice([1.01, 1.1, 1.5, 2, 3, 10, 50])},
            "tangential": {"potential": "coulomb", "mu": rng.choice([0, 0.1, 0.5, 1, 2])}}


def classical_law(kind):
    return lambda rng, vs: {"type": kind, "e": rng.choice([0, 0.5, 0.9, 1]),
                            "mu": rng.choice([0, 0.1, 0.5, 1, 2])}


def test_fremond_viscous_against_mpmath():
    check(viscous_law, fremond_viscous, 40, seed=4)


def test_fremond_coulomb_against_mpmath():
    check(coulomb_law, fremond_coulomb, 40, seed=2)


def test_newton_coulomb_against_mpmath():
    check(classical_law("newton_coulomb"), newton_coulomb, 60, seed=2)


def test_poisson_coulomb_against_mpmath():
    check(classical_law("poisson_coulomb"), poisson_coulomb, 60, seed=2)


if __name__ == "__main__":
    run_tests(globals())
