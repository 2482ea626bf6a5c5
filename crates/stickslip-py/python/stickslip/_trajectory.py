"""A run's samples and a steady state: :class:`Trajectory` and :class:`SteadyState`."""

from __future__ import annotations

import copy
from typing import TYPE_CHECKING, Any, Dict, Optional, Tuple

import numpy as np

from . import _checks
from ._core import Experiment
from ._names import Renamed
from ._common import PHASE_LABELS, _COLUMN_ATTRIBUTES, _events, _fixed_attributes, _plain

if TYPE_CHECKING:
    import pandas
    import xarray

class Trajectory:
    """One run from the initial state, sampled evenly (``stickslip.simulate``).

    Attributes:
        tau, y, v, drive: numpy float64 arrays, one value per sample: dimensionless time
            τ = ω0·t, position, velocity, and the drive β cos(wτ + φ) (units of y).
        phase: int8 array: +1 sliding with y' > 0, -1 sliding with y' < 0, 0 stuck
            (``PHASE_LABELS``; ``phase_labels()`` gives the CSV's slip+/slip-/stick).
        events: structured array with fields ``tau``, ``y``, ``kind`` ('turn', 'stick' or
            'slip'), every event from τ = 0 to the last sample.
        columns: the names of every sample column, in the order of the command-line tool's
            CSV: tau, y, v, drive, phase, then for a circuit t_s, uc_V, i_A, u_V (seconds,
            volts, amperes, volts) or for a mechanical oscillator t_s, r_m, rdot_m_s, F_N,
            each also an attribute.
        periods, samples_per_period: the run's length in drive periods and its samples per
            drive period.
        experiment: the experiment that ran.

    ``to_dict()`` is the library's trajectory report, the shape every front end gives (the
    lab's ``/api/simulate`` answers it): ``periods``, ``samples_per_period``, ``columns``,
    one list per column (``phase`` as the labels slip+/slip-/stick) and ``events`` as rows
    ``{"tau", "y", "kind"}``. ``to_xarray()`` and ``to_pandas()`` give the samples as a
    dataset or a data frame.
    """

    #: Time t in seconds (circuits and mechanical oscillators only; AttributeError otherwise).
    t_s: np.ndarray
    #: Capacitor voltage u_C in volts (circuits only).
    uc_V: np.ndarray
    #: Current i in amperes (circuits only).
    i_A: np.ndarray
    #: Drive voltage u in volts (circuits only).
    u_V: np.ndarray
    #: Displacement r in metres (mechanical oscillators only).
    r_m: np.ndarray
    #: Velocity dr/dt in m/s (mechanical oscillators only).
    rdot_m_s: np.ndarray
    #: Drive force F in newtons (mechanical oscillators only).
    F_N: np.ndarray

    def __init__(self, experiment: Experiment, data: Dict[str, Any]) -> None:
        self.experiment = experiment
        self.tau: np.ndarray = data["tau"]
        self.y: np.ndarray = data["y"]
        self.v: np.ndarray = data["v"]
        self.drive: np.ndarray = data["drive"]
        self.phase: np.ndarray = data["phase"]
        self.events: np.ndarray = _events(data["event_tau"], data["event_y"], data["event_kind"])
        self.physical: Tuple[str, ...] = tuple(data["physical"])
        for name in self.physical:
            setattr(self, name, data[name])
        self.columns: Tuple[str, ...] = ("tau", "y", "v", "drive", "phase") + self.physical
        self.periods: Optional[float] = data.get("periods")
        self.samples_per_period: Optional[int] = data.get("samples_per_period")

    def __len__(self) -> int:
        return len(self.tau)

    def to_dict(self) -> Dict[str, Any]:
        """The library's trajectory report (a new dict of plain values): ``periods``,
        ``samples_per_period``, ``columns`` (every column's name, the header of
        ``stickslip simulate``'s CSV), one list per column under its name (``phase`` as
        'slip+', 'slip-' or 'stick') and ``events``, one dict ``{"tau", "y", "kind"}`` per
        event."""
        out: Dict[str, Any] = {
            "periods": self.periods,
            "samples_per_period": self.samples_per_period,
            "columns": list(self.columns),
        }
        for name in self.columns:
            out[name] = (self.phase_labels().tolist() if name == "phase"
                         else _plain(self[name]))
        out["events"] = [{"tau": float(e["tau"]), "y": float(e["y"]), "kind": str(e["kind"])}
                         for e in self.events]
        return out

    def __getitem__(self, column: str) -> np.ndarray:
        if column not in self.columns:
            raise KeyError(f"no column {column!r}: the columns are {', '.join(self.columns)}")
        return getattr(self, column)

    def phase_labels(self) -> np.ndarray:
        """The phase of every sample as 'slip+', 'slip-' or 'stick'."""
        labels = np.empty(3, dtype=object)
        for code, label in PHASE_LABELS.items():
            labels[code] = label
        return labels[self.phase].astype(str)

    def to_xarray(self) -> "xarray.Dataset":
        """An ``xarray.Dataset`` of the samples along the dimension ``tau`` (dimensionless
        time, the coordinate; ``t_s`` in seconds beside it for a physical experiment): ``y``,
        ``v``, ``drive``, ``phase`` (CF flags: -1 slip-, 0 stick, +1 slip+) and the physical
        columns (``uc_V``, ``i_A``, ``u_V`` or ``r_m``, ``rdot_m_s``, ``F_N``), each with
        ``units`` and ``long_name``; the events along the dimension ``event``
        (``event_tau``, ``event_y``, ``event_kind``); the experiment as attributes.

        Raises:
            ModuleNotFoundError: without xarray (``pip install 'stickslip[xarray]'``).
        """
        xr = _checks.optional_module("xarray", "xarray", "Trajectory.to_xarray()")
        coords: Dict[str, Any] = {"tau": ("tau", self.tau, dict(_COLUMN_ATTRIBUTES["tau"]))}
        data: Dict[str, Any] = {}
        for name in self.columns[1:]:
            attrs: Dict[str, Any] = dict(_COLUMN_ATTRIBUTES[name])
            if name == "phase":
                attrs["flag_values"] = np.array([-1, 0, 1], dtype=np.int8)
            target = coords if name == "t_s" else data
            target[name] = ("tau", self[name], attrs)
        data["event_tau"] = ("event", self.events["tau"], {"units": "1",
                                                            "long_name": "time tau of the event"})
        data["event_y"] = ("event", self.events["y"], {"units": "1",
                                                        "long_name": "position y at the event"})
        data["event_kind"] = ("event", self.events["kind"].astype(str),
                              {"long_name": "kind of the event: turn, stick or slip"})
        attrs = _fixed_attributes(self.experiment, [])
        attrs["title"] = "stickslip: a run of the forced oscillator with dry friction"
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def to_pandas(self) -> "pandas.DataFrame":
        """A ``pandas.DataFrame`` of the samples, one row each, with the columns of the
        command-line tool's CSV in its order (``columns``: tau, y, v, drive, phase, then the
        physical ones); the events stay in ``events``.

        Raises:
            ModuleNotFoundError: without pandas (``pip install 'stickslip[pandas]'``).
        """
        pd = _checks.optional_module("pandas", "pandas", "Trajectory.to_pandas()")
        return pd.DataFrame({name: self[name] for name in self.columns})

    def __repr__(self) -> str:
        return (
            f"<stickslip.Trajectory: {len(self)} samples, τ from {self.tau[0]:g} to "
            f"{self.tau[-1]:g}, {len(self.events)} events; columns {', '.join(self.columns)}>"
        )


class SteadyState:
    """The steady motion reached from the initial state (``stickslip.steady``).

    ``to_dict()`` is exactly the JSON of ``stickslip steady --json`` for the same input (same
    keys, same numbers): class, period (None: none found), stops_per_period, symmetric,
    peak, gain, gain1, phase_lag (radians), harmonics, harmonic_phases, current_harmonics,
    subharmonic, mean, periods_to_settle, samples_per_period, w, beta, zeta, mu_s; and for a
    motion that does not repeat (measured by its law's tangent dynamics) lambda1, lambda1_error,
    lambda1_per_period, lambda1_error_per_period, lambda1_periods, lambda1_converged and
    verdict. Each is also an attribute (``motion_class`` for the class: ``class`` is a Python
    keyword), the lists as numpy arrays; the exponent's attributes are None for a motion that
    repeats. The names before (``motion``, ``stops_per_cycle``, ``lambda_per_tau``,
    ``error_per_tau``, ``lambda_per_period``, ``error_per_period``) still work, with a
    ``DeprecationWarning``.

    Attributes:
        motion_class: 'sliding', 'periodic-stick', 'undecided' (no period within the budget,
            not chaotic), 'static' or 'chaotic' (no period, and the largest Lyapunov exponent
            positive beyond 4 standard errors). 'static' is the paper's rule, an amplitude
            (y_max − y_min)/2 below β/100, whether or not the motion stops (at (w, β) =
            (2.0, 1.1) of the paper's circuit it holds a motion that stops twice a period):
            read ``stops_per_period`` beside it.
        stops_per_period: stops of non-zero duration per drive period.
        gain: G = (y_max − y_min)/(2β); gain1: G1 = A1/β, the gain of the fundamental (the
            paper's formula, its eq. 11, gives G1; None without a spectrum).
        lambda1, lambda1_error: the largest Lyapunov exponent λ1 of a motion that does not
            repeat and its standard error, per unit τ = ω0·t (None otherwise);
            lambda1_per_period, lambda1_error_per_period: the same per drive period; verdict:
            'chaotic', 'quasi-periodic', 'contracting' or 'undecided'.
        harmonics, harmonic_phases, current_harmonics: float64 arrays: A_k of y, their phases
            θ_k (radians), and k·w·A_k (the harmonics of y'), for k = 1, 2, ...
        trace: the recorded cycle sampled for the spectrum, an object with float64 arrays
            ``tau, y, v, drive`` and int8 ``phase`` (empty when the spectrum is off).
        xy: (drive, y) at every sample of the trace: the oscilloscope's X-Y picture.
        events: structured array (tau, y, kind) of the events of the recorded cycle.
        start: τ at which the record starts (a whole number of drive periods).
        recorded_periods, stops, y_min, y_max, longest_stop: as the library's SteadyState.
    """

    motion = Renamed("motion_class")
    stops_per_cycle = Renamed("stops_per_period")
    lambda_per_tau = Renamed("lambda1")
    error_per_tau = Renamed("lambda1_error")
    lambda_per_period = Renamed("lambda1_per_period")
    error_per_period = Renamed("lambda1_error_per_period")

    def __init__(self, experiment: Experiment, data: Dict[str, Any]) -> None:
        self.experiment = experiment
        self._report: Dict[str, Any] = data["report"]
        r = self._report
        self.motion_class: str = r["class"]
        self.period: Optional[int] = r["period"]
        self.stops_per_period: float = r["stops_per_period"]
        self.symmetric: bool = r["symmetric"]
        self.peak: float = r["peak"]
        self.gain: Optional[float] = r["gain"]
        self.gain1: Optional[float] = r["gain1"]
        self.phase_lag: Optional[float] = r["phase_lag"]
        self.harmonics = np.asarray(r["harmonics"], dtype=np.float64)
        self.harmonic_phases = np.asarray(r["harmonic_phases"], dtype=np.float64)
        self.current_harmonics = np.asarray(r["current_harmonics"], dtype=np.float64)
        self.subharmonic: Optional[float] = r["subharmonic"]
        self.mean: Optional[float] = r["mean"]
        self.periods_to_settle: int = r["periods_to_settle"]
        self.samples_per_period: Optional[int] = r["samples_per_period"]
        self.w: float = r["w"]
        self.beta: float = r["beta"]
        self.zeta: float = r["zeta"]
        self.mu_s: float = r["mu_s"]
        self.lambda1: Optional[float] = r.get("lambda1")
        self.lambda1_error: Optional[float] = r.get("lambda1_error")
        self.lambda1_per_period: Optional[float] = r.get("lambda1_per_period")
        self.lambda1_error_per_period: Optional[float] = r.get("lambda1_error_per_period")
        self.verdict: Optional[str] = r.get("verdict")
        tau = data["trace_tau"]
        drive = data["xy_drive"]
        self.trace = _Trace(tau, data["trace_y"], data["trace_v"], drive, data["trace_phase"])
        self.xy: Tuple[np.ndarray, np.ndarray] = (drive, data["xy_y"])
        self.events = _events(data["event_tau"], data["event_y"], data["event_kind"])
        self.start: float = data["start"]
        self.recorded_periods: int = data["recorded_periods"]
        self.stops: int = data["stops"]
        self.y_min: float = data["y_min"]
        self.y_max: float = data["y_max"]
        self.longest_stop: float = data["longest_stop"]

    def to_dict(self) -> Dict[str, Any]:
        """The report as ``stickslip steady --json`` prints it (a new dict of plain values)."""
        return copy.deepcopy(self._report)

    def __repr__(self) -> str:
        period = "none found" if self.period is None else self.period
        return (
            f"<stickslip.SteadyState {self.motion_class}: period {period}, "
            f"{self.stops_per_period:g} stops per period, gain {self.gain}, at w = {self.w:g}, "
            f"β = {self.beta:g}>"
        )


class _Trace:
    """Samples of a recorded cycle."""

    def __init__(self, tau: np.ndarray, y: np.ndarray, v: np.ndarray, drive: np.ndarray,
                 phase: np.ndarray) -> None:
        self.tau, self.y, self.v, self.drive, self.phase = tau, y, v, drive, phase

    def __len__(self) -> int:
        return len(self.tau)

    def __repr__(self) -> str:
        return f"<trace: {len(self)} samples>"
