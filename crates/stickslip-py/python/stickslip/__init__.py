"""stickslip: the forced harmonic oscillator damped by dry (Coulomb) friction, and its
electrical twin, a series RLC circuit damped by two anti-parallel diodes.

In dimensionless time τ = ω0·t::

    y'' + 2ζ y' + y + sgn(y') = β cos(w τ + φ)        while sliding
    y' = 0 and |β cos(w τ + φ) − y| ≤ μs               while stuck

For the circuit y = u_C/U_t, 2ζ = (R + R_D)√(C/L), β = U/U_t, w = Ω/ω0.

- ``Experiment``: what to run (dimensionless, the paper's circuit, any circuit with PWL or
  Shockley diodes, a mechanical oscillator, or a TOML file).
- ``simulate``: an exact trajectory as numpy arrays, with its events.
- ``steady``: the steady state (class, period, stops, gain, harmonics, X-Y data).
- ``theory`` and ``boundary``: the paper's series solution and the exact one; the stick-slip
  boundary β_c.
- ``sweep``: one parameter up and down with continuation (hysteresis).
- ``phase_diagram``: motion classes on a grid of two parameters, in parallel; ``to_xarray()``;
  with ``lyapunov=True`` the largest Lyapunov exponent of every point.
- ``orbit``: a periodic orbit by Newton's method, with its Floquet multipliers (stable or not).
- ``lyapunov``: the Lyapunov exponents of a motion: chaotic or not.
- ``bifurcation``: strobe points and the largest Lyapunov exponent against a parameter.
- ``basins``: the attractor reached from each initial state of a grid, attractors numbered.
- ``continuation``: a branch of periodic orbits with its stability, folds, period doublings
  and grazings.
- ``curve``: a fold, period doubling, Neimark–Sacker point or grazing followed in two
  parameters, with its codimension-two points; ``to_xarray()``, ``to_pandas()``.
- ``read_scope``, ``read_amplitudes``: oscilloscope exports and tables of measured amplitudes.
- ``fit``: the circuit's parameters (R, U_t, diode laws, ...) fitted to measurements, with error
  bars and residuals; ``to_dict()`` is ``stickslip fit --json``.
- ``stickslip.dask``: the same maps as Dask tasks on any cluster.

Every computation releases the GIL; Ctrl-C stops a long sweep, map or run; bad input raises
``ValueError`` with the library's one-line message.

Example::

    import numpy as np
    import stickslip

    exp = stickslip.Experiment.paper(w=0.7, beta=1.2)      # the paper's circuit
    print(stickslip.steady(exp).to_dict()["class"])        # periodic-stick
    m = stickslip.phase_diagram(stickslip.Experiment.paper(),
                                w=np.linspace(0.1, 2.5, 200), beta=np.linspace(0.5, 4, 200))
    print(m.counts())
"""

from ._api import boundary, phase_diagram, simulate, steady, sweep, theory
from ._common import EVENT_DTYPE, EVENT_KINDS, MOTION_CLASSES, PARAMETERS, PHASE_LABELS
from ._stability import (
    STOP_DTYPE,
    LyapunovResult,
    PeriodicOrbit,
    SelfExcitedOrbit,
    lyapunov,
    orbit,
)
from ._tables import PhaseDiagram, SweepResult
from ._trajectory import SteadyState, Trajectory
from ._core import Experiment, __version__
from ._fit import (
    AmplitudeTable,
    FitNotConverged,
    FitRecord,
    FitResult,
    ScopeRecord,
    fit,
    read_amplitudes,
    read_scope,
)
from ._curve import Curve, curve
from ._dynamics import (
    ATTRACTOR_KINDS,
    BasinMap,
    BifurcationDiagram,
    Branch,
    basins,
    bifurcation,
    continuation,
)

__all__ = [
    "AmplitudeTable",
    "FitNotConverged",
    "FitRecord",
    "FitResult",
    "ScopeRecord",
    "fit",
    "read_amplitudes",
    "read_scope",
    "ATTRACTOR_KINDS",
    "BasinMap",
    "BifurcationDiagram",
    "Branch",
    "basins",
    "bifurcation",
    "continuation",
    "Curve",
    "curve",
    "EVENT_DTYPE",
    "EVENT_KINDS",
    "Experiment",
    "MOTION_CLASSES",
    "PARAMETERS",
    "PHASE_LABELS",
    "STOP_DTYPE",
    "LyapunovResult",
    "PeriodicOrbit",
    "PhaseDiagram",
    "SelfExcitedOrbit",
    "SteadyState",
    "SweepResult",
    "Trajectory",
    "__version__",
    "boundary",
    "lyapunov",
    "orbit",
    "phase_diagram",
    "simulate",
    "steady",
    "sweep",
    "theory",
]
