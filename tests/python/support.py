"""Shared by the Python tests: imports fremond from the build tree, and independent references.

The references here are closed forms and plain bisections written from the paper's equations, so
the tests compare the library against something that does not use it.
"""
import math
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

try:
    import fremond  # noqa: F401  (PYTHONPATH=<build>/python, as ctest sets it)
except ImportError:
    sys.path.insert(0, str(ROOT / "build" / "python"))
    import fremond  # noqa: F401


def near(a, b, rel=1e-12, tiny=1e-12):
    """|a - b| <= rel * max(|a|, |b|) + tiny, elementwise, with a message naming both."""
    try:
        pairs = list(zip(a, b))
        assert len(list(a)) == len(list(b)), f"lengths differ: {len(list(a))} != {len(list(b))}"
    except TypeError:
        pairs = [(a, b)]
    for x, y in pairs:
        x, y = float(x), float(y)
        assert abs(x - y) <= rel * max(abs(x), abs(y)) + tiny, f"{x!r} != {y!r} (rel {rel})"


def bisect(f, lo, hi, iterations=200):
    """A root of a continuous f with f(lo) and f(hi) of opposite signs."""
    flo = f(lo)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        fm = f(mid)
        if (fm > 0) == (flo > 0):
            lo, flo = mid, fm
        else:
            hi = mid
    return 0.5 * (lo + hi)


def fremond_point_mass_D_NE(m, k, p, speed):
    """D_NE of a point mass hitting the ground at |D_NA| = speed under φ_N = k|z|^p/p (the library's
    scaling): m(D_NE + a) = k((a - D_NE)/2)^(p-1) when that has a root D_NE in [0, a], otherwise
    the reaction stops the mass (D_NE = 0). Eq. (23) with the mean z = (D_NA + D_NE)/2."""
    a = speed
    if a == 0:
        return 0.0
    g = lambda d: k * ((a - d) / 2.0) ** (p - 1.0) - m * (d + a)  # noqa: E731  decreasing in d
    if g(0.0) <= 0.0:
        return 0.0
    return bisect(g, 0.0, a)


def deadzone_point_mass_D_TE(m, k, q, r, d_ta):
    """D_TE of a point mass under φ_T = (k/q) max(0, |z| - r)^q alone (the normal law does not
    couple for a point mass): m(D_TE - D_TA) = -φ_T'((D_TA + D_TE)/2), by bisection on D_TE."""
    def dphi(z):
        return math.copysign(k * max(0.0, abs(z) - r) ** (q - 1.0), z)

    h = lambda d: m * (d - d_ta) + dphi(0.5 * (d_ta + d))  # noqa: E731  increasing in d
    span = abs(d_ta) + 1.0
    return bisect(h, -span, span)


def cli():
    """The fremond command, or None when the tests run without it."""
    path = os.environ.get("FREMOND_CLI")
    if path and Path(path).exists():
        return path
    candidate = ROOT / "build" / "fremond"
    return str(candidate) if candidate.exists() else None


def run_tests(namespace):
    """Runs every test_* function of a module (when pytest is not installed)."""
    names = sorted(n for n in namespace if n.startswith("test_") and callable(namespace[n]))
    failed = 0
    for n in names:
        try:
            namespace[n]()
            print(f"ok   {n}")
        except Exception as e:  # noqa: BLE001  report every failure, then exit non-zero
            failed += 1
            print(f"FAIL {n}: {type(e).__name__}: {e}")
    print(f"{len(names) - failed} passed, {failed} failed")
    sys.exit(1 if failed else 0)
