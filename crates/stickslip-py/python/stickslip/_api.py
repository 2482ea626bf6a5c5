"""The package's functions that run and settle an experiment: :func:`simulate`, :func:`steady`,
:func:`theory`, :func:`boundary`, :func:`sweep` and :func:`phase_diagram` (see
``stickslip/__init__.py``)."""

from __future__ import annotations

from typing import Any, Dict, Literal, Mapping, Optional, Sequence, Tuple, overload

import numpy as np

from . import _checks, _core, _progress
from ._core import Experiment
from ._progress import Progress
from ._common import PARAMETERS, _values, _with_model
from ._trajectory import SteadyState, Trajectory
from ._tables import PhaseDiagram, SweepResult

def simulate(experiment: Experiment, periods: float, samples_per_period: int = 200, *,
             model: Optional[str] = None, progress: Progress = None) -> Trajectory:
    """Run the experiment from its initial state and sample the motion.

    The exact event-driven solver (or the stiff solver with Shockley diodes) runs for
    ``periods`` drive periods; the motion is sampled at τ_k = k·(periods·T)/n, k = 0 … n,
    with T = 2π/w and n = ⌈periods × samples_per_period⌉ (n + 1 samples), exactly as
    ``stickslip simulate`` writes its CSV.

    Args:
        experiment: a ``stickslip.Experiment`` with its drive (w and β) given.
        periods: drive periods to run (> 0; a number, whole or not). The run must end
            within the time range the solvers resolve: τ ≤ 2³² and w·τ ≤ 2³², i.e. at most
            6.8·10⁸·min(1, w) periods (``docs/limits.md``), checked before any work.
        samples_per_period: samples per drive period (an integer from 1; default 200); at
            most 5·10⁷ samples in all.
        model: 'pwl' or 'shockley' to use that diode law instead of the experiment's own
            (Shockley diodes need a circuit).
        progress: True for a progress bar (tqdm), or a callable ``progress(done, total)``
            (drive periods), or one of one argument given the periods done since its last
            call (a tqdm bar's ``update``); called from the calling thread about every 50 ms.

    Returns:
        A ``Trajectory`` with numpy arrays tau, y, v, drive, phase (and t_s, uc_V, i_A, u_V for
        a circuit) and the structured array ``events`` (tau, y, kind).

    Raises:
        ValueError: bad input, a missing drive or a run too long, with the library's message.
        TypeError: an argument of the wrong type (samples_per_period=2.5).
        KeyboardInterrupt: Ctrl-C stops a long run.

    Example:
        >>> import stickslip
        >>> run = stickslip.simulate(stickslip.Experiment.paper(w=0.7, beta=1.2), periods=30)
        >>> len(run), run.columns[-1]
        (6001, 'u_V')
    """
    experiment = _with_model(experiment, model)
    periods = _checks.number("periods", periods)
    samples = _checks.integer("samples_per_period", samples_per_period, "simulate")
    with _progress.reporter(progress, "simulate", "periods") as callback:
        data = _core.simulate(experiment, periods, samples, callback)
    data["periods"] = periods
    data["samples_per_period"] = samples
    return Trajectory(experiment, data)


def steady(experiment: Experiment, model: Optional[str] = None, **options: Any) -> SteadyState:
    """The steady motion reached from the initial state.

    The state once per drive period is followed until it repeats with a period p ≤ 16 drive
    periods, then p whole periods are recorded, classified from the exact event log and
    analysed by a real FFT (exactly as ``stickslip steady``).

    Args:
        experiment: a ``stickslip.Experiment`` with its drive given.
        model: 'pwl' or 'shockley' to use that diode law instead of the experiment's own.
        **options: tolerance (relative, of the once-per-period repetition; default 1e-10, or
            the stiff solver's 1e-6 with Shockley diodes), max_periods (5000; 1 to 1e8),
            max_period (16; 1 to 64), min_stop_fraction (1e-8 of a period), accelerate (True:
            extrapolate the stroboscopic map to its fixed point), harmonics (16; 1 to 256),
            samples_per_period (None: chosen from the event log; else a power of two from 16
            to 2²⁰), lyapunov_periods (5000: drive periods over which a motion that does not
            repeat is measured by its largest Lyapunov exponent (either law); 0:
            not measured; else 20 to 1e8). Counts are integers (``int`` or numpy integers;
            a float such as 100.0 is refused).

    Returns:
        A ``SteadyState``; ``to_dict()`` equals ``stickslip steady --json``. Its class
        (``motion_class``) is one of ``MOTION_CLASSES``: 'static' is the paper's rule, an
        amplitude (y_max − y_min)/2 below β/100, whether or not the motion stops (at (w, β) =
        (2.0, 1.1) of the paper's circuit it holds a motion that stops twice a period), so
        read ``stops_per_period`` beside it.

    Raises:
        ValueError: bad input, with the library's message. TypeError: an unknown option or
        one of the wrong type.

    Example:
        >>> s = stickslip.steady(stickslip.Experiment.paper(w=0.7, beta=1.2))
        >>> s.motion_class, s.period, s.stops_per_period
        ('periodic-stick', 1, 2.0)
    """
    experiment = _with_model(experiment, model)
    options = _checks.steady_options(options, True, "steady")
    return SteadyState(experiment, _core.steady(experiment, options))


def theory(experiment: Experiment) -> Dict[str, Any]:
    """The paper's series solution (its eqs. 11 and 13) and the exact periodic solution at the
    experiment's (ζ, w, β, μs): the dict that ``stickslip theory --json`` prints, with
    ``params``, ``paper`` (A1, A3, A5, phi0, gain, beta_c) and ``exact`` (exists, peak, A1,
    A3, A5, phase, gain, beta_c, spectral_radius); a value that does not exist is None and
    ``note`` says why. Phases in radians. The initial state is not used. The theory is that of
    the piecewise-linear model (no Shockley diodes).

    Example:
        >>> t = stickslip.theory(stickslip.Experiment(zeta=0.0468, w=0.9, beta=2.0))
        >>> t["exact"]["exists"]
        True
    """
    _with_model(experiment, None)
    return _core.theory(experiment)


def boundary(zeta: Any, w: Any, mu_s: Any = 1.0) -> Tuple[np.ndarray, np.ndarray]:
    """The stick-slip boundary β_c: the paper's (eq. 13, which takes μs = 1) and the exact one
    (the smallest β at which the symmetric sliding orbit exists without sticking), vectorised.

    Args:
        zeta: damping ratio(s) ζ ≥ 0.
        w: drive frequency(ies) w = Ω/ω0 > 0, any shape.
        mu_s: static-to-kinetic friction ratio(s) μs ≥ 1 (default 1).
        The three broadcast against each other.

    Returns:
        ``(beta_c_paper, beta_c_exact)``: float64 arrays of the broadcast shape, NaN where no
        boundary exists (as the empty cells of ``stickslip theory --curve boundary``).

    Example:
        >>> paper, exact = stickslip.boundary(0.0468, [0.7, 1.5])
        >>> round(float(paper[0]), 2), round(float(exact[0]), 3)
        (1.75, 1.556)
    """
    z, ww, m = np.broadcast_arrays(*(_checks.array(name, value) for name, value in
                                     (("zeta", zeta), ("w", w), ("mu_s", mu_s))))
    shape = ww.shape
    flat = [np.require(a.ravel(), np.float64, ["C", "A"]) for a in (z, ww, m)]
    if ww.size == 0:
        return np.empty(shape), np.empty(shape)
    paper, exact = _core.boundary(*flat)
    return paper.reshape(shape), exact.reshape(shape)


#: The keys of a physical drive a sweep can go over, and the parameter each sets.
_PHYSICAL_SWEEPS = {"f": "w", "omega": "w", "U": "beta", "F": "beta"}


def _physical_sweep(experiment: Experiment, key: str, values: Any) -> Tuple[str, np.ndarray]:
    """A sweep over a physical drive key (f in Hz, omega, U, F) as one over w or β: each value
    turned by the experiment, as ``replace`` turns it."""
    if experiment.scales() is None:
        raise ValueError(f"a sweep over {key!r} needs a physical experiment (a circuit or a "
                         "mechanical oscillator): this one is dimensionless; sweep over 'w' "
                         "or 'beta'")
    parameter = _PHYSICAL_SWEEPS[key]
    physical = _values("values", values)
    turned = [getattr(experiment.replace(**{key: float(v)}), parameter)  # type: ignore[arg-type]
              for v in physical]
    return parameter, np.asarray(turned, dtype=np.float64)


def sweep(experiment: Experiment, over: str, values: Any, direction: str = "both", *,
          model: Optional[str] = None, progress: Progress = None,
          **options: Any) -> SweepResult:
    """Sweep one parameter with the others fixed, each step starting from the state where the
    step before ended (as when turning a knob), so hysteresis and coexisting motions show.

    Args:
        experiment: a ``stickslip.Experiment``; it needs no value of the swept parameter.
        over: 'w', 'beta', 'zeta' or 'mu_s'; for a circuit or a mechanical oscillator also
            'f' (drive frequency in Hz), 'omega' (rad/s), 'U' (drive amplitude in V) or 'F'
            (N): each value is turned into w or β as the experiment turns that key
            (``experiment.replace(f=value).w``), and the result is a sweep over w or β (with
            ``f_Hz`` beside w).
        values: the swept values, in order (any array-like of floats).
        direction: 'up' (values in order), 'down' (reversed) or 'both' (up, then down from
            where the up leg ended; the default).
        model: 'pwl' or 'shockley' to use that diode law instead of the experiment's own.
        progress: True for a progress bar (tqdm), a callable ``progress(done, total)``
            (steps) or a tqdm bar's ``update`` (given the steps done since its last call).
        **options: as for ``steady``.

    Returns:
        A ``SweepResult`` (numpy arrays per step; ``to_xarray()``): ``motion_class`` (labels
        of ``MOTION_CLASSES``; 'static' is the paper's rule, an amplitude below β/100 whether
        or not the motion stops) with ``stops_per_period`` beside it.

    Raises:
        ValueError: bad input, with the library's message. KeyboardInterrupt: Ctrl-C.

    Example:
        >>> import numpy as np
        >>> exp = stickslip.Experiment.paper(beta=3.61)
        >>> s = stickslip.sweep(exp, over="w", values=np.linspace(0.5, 1.5, 11))
        >>> print(len(s), s.direction[0], s.direction[-1])
        22 up down
    """
    experiment = _with_model(experiment, model)
    options = _checks.steady_options(options, True, "sweep")
    if over in _PHYSICAL_SWEEPS:
        over, values = _physical_sweep(experiment, over, values)
    with _progress.reporter(progress, "sweep", "steps") as callback:
        data = _core.sweep(experiment, over, _values("values", values), direction, options,
                           callback)
    return SweepResult(experiment, over, dict(options), data)


def _axes(kwargs: Dict[str, Any], count: Sequence[int], caller: str
          ) -> Tuple[Dict[str, np.ndarray], Dict[str, Any]]:
    """Split keyword arguments into parameter arrays (in the order given) and options, each
    checked; an unknown keyword is named first (``gamma=`` is not an option misread)."""
    options_known = _checks.option_names(spectrum=False)
    for k in kwargs:
        if k not in PARAMETERS and k not in options_known:
            _checks.unknown_keyword(caller, k, [("the parameters", PARAMETERS),
                                                ("the options", options_known)])
    axes = {k: _values(k, v) for k, v in kwargs.items() if k in PARAMETERS}
    options = _checks.steady_options({k: v for k, v in kwargs.items() if k not in PARAMETERS},
                                     False, caller)
    if len(axes) not in count:
        wanted = " or ".join(str(c) for c in count)
        got = ", ".join(axes) or "none"
        raise TypeError(
            f"{caller} takes {wanted} parameter arrays as keywords (of {', '.join(PARAMETERS)}), "
            f"e.g. w=np.linspace(0.1, 2.5, 400), beta=np.linspace(0.5, 4, 400); got {got}"
        )
    return axes, options


@overload
def phase_diagram(experiment: Experiment, *, model: Optional[str] = ...,
                  threads: Optional[int] = ..., progress: Progress = ...,
                  lyapunov: Literal[False] = ..., **axes_and_options: Any) -> PhaseDiagram[None]:
    ...


@overload
def phase_diagram(experiment: Experiment, *, model: Optional[str] = ...,
                  threads: Optional[int] = ..., progress: Progress = ...,
                  lyapunov: Literal[True], **axes_and_options: Any
                  ) -> PhaseDiagram[np.ndarray]:
    ...


@overload
def phase_diagram(experiment: Experiment, *, model: Optional[str] = ...,
                  threads: Optional[int] = ..., progress: Progress = ...,
                  lyapunov: bool = ..., **axes_and_options: Any
                  ) -> PhaseDiagram[Optional[np.ndarray]]:
    ...


def phase_diagram(experiment: Experiment, *, model: Optional[str] = None,
                  threads: Optional[int] = None, progress: Progress = None,
                  lyapunov: bool = False, **axes_and_options: Any) -> PhaseDiagram[Any]:
    """Classify the steady motion on a grid of two parameters, every point started from the
    experiment's initial state (rest, as in the paper's Fig. 7), in parallel.

    Give the two parameters as keyword arrays, any two of ``PARAMETERS`` (``zeta``, ``w``,
    ``beta``, ``mu_s``, the belt speed ``vb``, the friction laws' ``vs``, ``delta``, ``eta``,
    ``k1``, ``k3``); the first keyword is the first axis (rows), the second the second
    (columns), and the xarray dimensions are named by them. Without a drive (``beta=0``) a
    belt's map, e.g. ``vb=..., mu_s=...``, has the self-excited classes 'stick-slip-cycle',
    'pure-slip-cycle' and 'steady-sliding'.

    Args:
        experiment: a ``stickslip.Experiment``; it needs no value of either parameter.
        model: 'pwl' or 'shockley' to use that diode law instead of the experiment's own.
        threads: compute on a pool of this many threads (an integer from 1 to 1024;
            default: one per core). Results are the same for any number.
        progress: True for a progress bar (tqdm), or a callable ``progress(done, total)``
            (points), or one of one argument given the points done since its last call (a
            tqdm bar's ``update``); called from the calling thread about every 50 ms.
        lyapunov: also the largest Lyapunov exponent of every point (either law; as
            ``stickslip phase-diagram --color lambda1``): arrays ``lambda1`` and
            ``lambda1_error`` per unit τ.
        **axes_and_options: the two parameter arrays, then options as for ``steady``
            (tolerance, max_periods, max_period, min_stop_fraction, accelerate,
            lyapunov_periods).

    Returns:
        A ``PhaseDiagram``: ``motion_class`` (the labels; ``class_code`` their int8 codes into
        ``labels``; 'static' is the paper's rule, an amplitude below β/100 whether or not the
        motion stops), ``stops_per_period`` beside it, ``period`` (-1: none found), ``gain``,
        ... each of shape (len(first), len(second)), and ``to_xarray()``.

    Raises:
        ValueError: bad input, with the library's message; a grid of more than 10⁸ points
        (``docs/limits.md``), before any work. TypeError: an unknown keyword (named), or an
        argument of the wrong type. KeyboardInterrupt: Ctrl-C.

    Example:
        >>> import numpy as np
        >>> m = stickslip.phase_diagram(stickslip.Experiment.paper(),
        ...                             w=np.linspace(0.1, 2.5, 60), beta=np.linspace(0.5, 4, 40))
        >>> m.motion_class.shape, str(m.motion_class[59, 39])
        ((60, 40), 'sliding')
    """
    experiment = _with_model(experiment, model)
    axes, options = _axes(axes_and_options, (2,), "phase_diagram")
    (first, v1), (second, v2) = axes.items()
    threads = _checks.threads(threads)
    lyapunov = _checks.flag("lyapunov", lyapunov)
    with _progress.reporter(progress, "phase_diagram", "points") as callback:
        data = _core.grid(experiment, first, v1, second, v2, options, threads, None, None,
                          callback, lyapunov)
    return PhaseDiagram(experiment, (first, second), axes, options, _reshape(data, (len(v1), len(v2))))


def _reshape(data: Mapping[str, np.ndarray], shape: Tuple[int, ...]) -> Dict[str, np.ndarray]:
    names = PhaseDiagram._CORE_KEYS + tuple(n for n in PhaseDiagram._CORE_EXPONENT_KEYS
                                            if n in data)
    return {name: data[name].reshape(shape) for name in names}
