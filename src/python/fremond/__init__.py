"""fremond: impact laws of rigid bodies (Newton, Poisson, Coulomb, Frémond).

The compiled module (``fremond._fremond``, a thin pybind11 layer over the C++ library) is
re-exported here; ``fremond.plots`` holds the plotting helpers that draw the paper's figures from
its results (matplotlib and Pillow).

    import fremond
    run = fremond.simulate(fremond.paper_bar_scene("newton_coulomb"),
                           fremond.SimulationOptions(t_end=3.0))
    fremond.plots.energy_plot(run, title="Newton + Coulomb")
"""
from ._fremond import *  # noqa: F401,F403

__version__ = "0.1.0"

# The plotting helpers import matplotlib only when used, so the module itself needs only NumPy.
from . import plots  # noqa: E402,F401
