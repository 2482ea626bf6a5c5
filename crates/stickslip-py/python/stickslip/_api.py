"""The package's functions and result types (see ``stickslip/__init__.py``)."""

from __future__ import annotations

import copy
import json
from typing import (TYPE_CHECKING, Any, Dict, Generic, List, Literal, Mapping,
                    Optional, Sequence, Tuple, TypeVar, overload)

import numpy as np

from . import _checks, _core, _progress
from ._core import Experiment
from ._names import Renamed, renamed_key, warn_renamed
from ._progress import Progress

if TYPE_CHECKING:
    import pandas
    import xarray

#: The classes of steady motion (``motion_class``, the reports' ``class``), in the order of
#: their codes in ``class_code`` arrays: 'sliding', 'periodic-stick', 'undecided', 'static'
#: and 'chaotic' (a motion that does not repeat, with a largest Lyapunov exponent positive
#: beyond its error). 'undecided' is no kind of motion: no period was found within the budget
#: and λ1 is not positive beyond its error (the paper's "non-periodic motion with sticking"
#: lands there; its label was 'nonperiodic-stick'). 'static' is the paper's rule: a motion
#: whose amplitude (y_max − y_min)/2 is below β/100, whether or not it stops; it can hold a
#: motion that stops twice a drive period (at (w, β) = (2.0, 1.1) of the paper's circuit), so
#: ``stops_per_period`` is returned beside every class.
MOTION_CLASSES: Tuple[str, ...] = tuple(_core.MOTION_CLASSES)
#: The parameters that sweeps and maps vary, with their long names (units: dimensionless).
PARAMETERS: Dict[str, str] = dict(_core.PARAMETER_LONG_NAMES)
#: ``phase`` codes of a trajectory: +1 sliding with y' > 0, -1 sliding with y' < 0, 0 stuck.
PHASE_LABELS: Dict[int, str] = dict(_core.PHASE_LABELS)
#: ``kind`` of an event, by code, as in the command-line tool's event CSV.
EVENT_KINDS: Tuple[str, ...] = tuple(_core.EVENT_KINDS)
#: The structured dtype of event arrays.
EVENT_DTYPE = np.dtype([("tau", np.float64), ("y", np.float64), ("kind", "U5")])

_values = _checks.values

#: The documented ``static`` rule, repeated in the docstrings that return a class.
STATIC_RULE = ("'static' is the paper's rule, an amplitude (y_max − y_min)/2 below β/100, "
               "whether or not the motion stops")


def _with_model(experiment: Experiment, model: Optional[str]) -> Experiment:
    if not isinstance(experiment, Experiment):
        raise TypeError(
            f"expected a stickslip.Experiment, got {type(experiment).__name__}: "
            "build one with stickslip.Experiment(...) or Experiment.paper(...)"
        )
    if model is None:
        return experiment
    return _core.with_diode(experiment, model)


#: The fields of a sweep's report, by their names (``SweepResult[name]``): the library's
#: (``SweepRow::FIELDS``), a CSV column's name where the CSV has it.
SWEEP_COLUMNS: Tuple[str, ...] = tuple(_core.SWEEP_FIELDS)


def _plain(values: Any) -> List[Any]:
    """A numpy array as a list of plain values, as the library's JSON writes them: NaN and
    infinities as None (JSON has no such numbers)."""
    out = np.asarray(values).tolist()
    return [None if isinstance(x, float) and not np.isfinite(x) else x for x in out]


def _optional_period(period: np.ndarray) -> List[Optional[int]]:
    """Periods as the reports write them: None where the array holds -1 (none found)."""
    return [None if p < 0 else int(p) for p in np.asarray(period).tolist()]


def _events(tau: np.ndarray, y: np.ndarray, kind: np.ndarray) -> np.ndarray:
    events = np.empty(len(tau), dtype=EVENT_DTYPE)
    events["tau"] = tau
    events["y"] = y
    events["kind"] = np.asarray(EVENT_KINDS)[kind]
    return events


def _fixed_attributes(experiment: Experiment, varied: Sequence[str]) -> Dict[str, Any]:
    """The experiment's inputs that a sweep or map does not vary, as netCDF-safe attributes."""
    attrs: Dict[str, Any] = {
        "title": "stickslip: steady motions of the forced oscillator with dry friction",
        "Conventions": "CF-1.10",
        "experiment": str(experiment),
        "experiment_json": experiment.to_json(),
        "model": experiment.model,
        "system": experiment.system,
        "stickslip_version": _core.__version__,
    }
    for name in ("zeta", "w", "beta", "phi", "mu_s", "y0", "v0"):
        value = getattr(experiment, name)
        if name not in varied and value is not None:
            attrs[name] = value
    scales = experiment.scales()
    if scales is not None:
        attrs["f0_Hz"] = scales["f0"]
        for name in ("w", "beta"):
            value = getattr(experiment, name)
            if name not in varied and value is not None:
                physical, factor, _ = _physical_parameter(name, scales)
                attrs[physical] = value * factor
    return attrs


def _physical_parameter(name: str, scales: Mapping[str, Any]) -> Tuple[str, float, Dict[str, str]]:
    """The physical value beside a dimensionless parameter of a physical experiment: its name,
    the factor from the parameter to it, and its attributes (w → f_Hz; β → U_V or F_N)."""
    if name == "w":
        return "f_Hz", float(scales["f0"]), {"units": "Hz", "long_name": "drive frequency f = w f0"}
    unit = scales["force_unit"]
    if unit == "V":
        return "U_V", float(scales["force"]), {"units": "V",
                                               "long_name": "drive amplitude U = beta U_t"}
    return "F_N", float(scales["force"]), {"units": "N",
                                           "long_name": "drive amplitude F = beta F0"}


def _physical_coordinates(experiment: Experiment, dims: Sequence[str],
                          values: Mapping[str, np.ndarray]) -> Dict[str, Any]:
    """Coordinates in physical units beside the dimensionless ones of a physical experiment:
    the drive frequency in Hz beside w, the drive amplitude in V (or N) beside β."""
    scales = experiment.scales()
    coords: Dict[str, Any] = {}
    if scales is None:
        return coords
    for d in dims:
        if d in ("w", "beta"):
            name, factor, attrs = _physical_parameter(d, scales)
            coords[name] = (d, values[d] * factor, attrs)
    return coords


def _coordinate(name: str, values: np.ndarray) -> Tuple[str, np.ndarray, Dict[str, str]]:
    return (name, values, {"units": "1", "long_name": PARAMETERS[name]})


def _motion_attributes() -> Dict[str, Any]:
    return {
        "long_name": "motion class of the steady state",
        "flag_values": np.arange(len(MOTION_CLASSES), dtype=np.int8),
        "flag_meanings": " ".join(MOTION_CLASSES),
    }


_PERIOD_ATTRIBUTES = {
    "long_name": "period of the steady motion in drive periods (-1: none found)",
    "units": "1",
}


#: Units and long names of the physical columns of a trajectory.
_COLUMN_ATTRIBUTES: Dict[str, Dict[str, str]] = {
    "tau": {"units": "1", "long_name": "dimensionless time tau = omega0 t"},
    "y": {"units": "1", "long_name": "position y (u_C/U_t for a circuit)"},
    "v": {"units": "1", "long_name": "velocity y' (dy/dtau)"},
    "drive": {"units": "1", "long_name": "drive beta cos(w tau + phi)"},
    "phase": {"long_name": "phase of the motion", "flag_meanings": "slip- stick slip+"},
    "t_s": {"units": "s", "long_name": "time t"},
    "uc_V": {"units": "V", "long_name": "capacitor voltage u_C"},
    "i_A": {"units": "A", "long_name": "current i"},
    "u_V": {"units": "V", "long_name": "drive voltage u"},
    "r_m": {"units": "m", "long_name": "displacement r"},
    "rdot_m_s": {"units": "m/s", "long_name": "velocity dr/dt"},
    "F_N": {"units": "N", "long_name": "drive force F"},
}


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
    motion that does not repeat (measured with the exact PWL model) lambda1, lambda1_error,
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


class SweepResult:
    """A sweep with continuation (``stickslip.sweep``): one entry per step, in the order run.

    Attributes:
        over: the swept parameter ('w', 'beta', 'zeta' or 'mu_s').
        value: float64 array, the swept parameter's value at each step.
        direction: array of 'up' or 'down' (the direction of the leg each step belongs to).
        w, beta, zeta, mu_s: float64 arrays, the parameters of each step.
        motion_class: array of the class labels (``MOTION_CLASSES``); class_code: their int8
            codes into ``labels``. 'static' is the paper's rule, an amplitude below β/100
            whether or not the motion stops: read ``stops_per_period`` beside it.
        period: int16, period in drive periods, -1 where none was found.
        stops_per_period: float64, stops of non-zero duration per drive period.
        gain, gain1, peak: float64 arrays: G = (y_max − y_min)/(2β), G1 = A1/β (the gain of
            the fundamental, NaN where not measured) and the largest |y|.
        phase_lag: float64, lag of the fundamental behind the drive (radians; NaN without one).
        harmonics: float64 array (steps × harmonics): A_1, A_2, ... of y (NaN where absent).
        A1, A3, f_Hz: float64 arrays, the report's names: the first and third harmonics (NaN
            where not measured) and the drive frequency in Hz (NaN for a dimensionless
            experiment).
        symmetric: bool array; periods_to_settle: int64 array.
        experiment, options: what was run.

    ``result[name]`` gives a column by the report's name (the CSV's and the JSON's):
    ``result["class"]`` the labels. The names before (``leg``, ``motion`` for the codes,
    ``stops_per_cycle``, ``motion_labels()``) still work, with a ``DeprecationWarning``.

    ``to_dict()`` is the library's sweep report, the JSON shape every front end gives: the
    swept parameter ``over``, the ``direction`` asked for and one dict per step in ``points``
    (``SWEEP_COLUMNS``: value, w, beta, zeta, mu_s, direction, gain, gain1, peak, A1, A3,
    class, stops_per_period, period, phase_lag, f_Hz), as ``stickslip sweep`` writes its CSV
    columns.
    """

    leg = Renamed("direction")
    motion = Renamed("class_code")
    stops_per_cycle = Renamed("stops_per_period")

    def __init__(self, experiment: Experiment, over: str, options: Dict[str, Any],
                 data: Dict[str, Any]) -> None:
        self.experiment = experiment
        self.over = over
        self.options = options
        self.labels: Tuple[str, ...] = MOTION_CLASSES
        self.value: np.ndarray = data["value"]
        self.w: np.ndarray = data["w"]
        self.beta: np.ndarray = data["beta"]
        self.zeta: np.ndarray = data["zeta"]
        self.mu_s: np.ndarray = data["mu_s"]
        self.gain: np.ndarray = data["gain"]
        self.peak: np.ndarray = data["peak"]
        self.stops_per_period: np.ndarray = data["stops_per_cycle"]
        self.phase_lag: np.ndarray = data["phase_lag"]
        self.class_code: np.ndarray = data["motion"]
        self.motion_class: np.ndarray = np.asarray(self.labels)[self.class_code]
        self.period: np.ndarray = data["period"]
        self.symmetric: np.ndarray = data["symmetric"]
        self.periods_to_settle: np.ndarray = data["periods_to_settle"]
        self.direction = np.asarray([p["direction"] for p in data["report"]["points"]],
                                    dtype=str)
        self.harmonics = data["harmonics"].reshape(len(self.value), data["harmonic_count"])
        self._report: Dict[str, Any] = data["report"]
        points = self._report["points"]

        def column(name: str) -> np.ndarray:
            return np.asarray([np.nan if p[name] is None else p[name] for p in points],
                              dtype=np.float64)

        self.gain1: np.ndarray = column("gain1")
        self.A1: np.ndarray = column("A1")
        self.A3: np.ndarray = column("A3")
        self.f_Hz: np.ndarray = column("f_Hz")

    def __getitem__(self, name: str) -> np.ndarray:
        """A column by the report's name (``class`` gives the labels), or by an attribute's."""
        name = renamed_key("SweepResult", name, {"leg": "direction", "motion": "class_code",
                                                 "stops_per_cycle": "stops_per_period"})
        if name == "class":
            return self.motion_class
        if name in SWEEP_COLUMNS or name in ("class_code", "harmonics", "symmetric",
                                             "periods_to_settle"):
            return np.asarray(getattr(self, name))
        raise KeyError(f"no column {name!r}: the columns are {', '.join(SWEEP_COLUMNS)}")

    def to_dict(self) -> Dict[str, Any]:
        """The library's sweep report (a new dict of plain values): ``over``, ``direction``
        and ``points``, one dict per step."""
        return copy.deepcopy(self._report)

    def __len__(self) -> int:
        return len(self.value)

    def motion_labels(self) -> np.ndarray:
        """The class of every step as a label (deprecated: ``motion_class``)."""
        warn_renamed("SweepResult", "motion_labels()", "motion_class")
        return self.motion_class

    def to_xarray(self) -> "xarray.Dataset":
        """An ``xarray.Dataset`` with dimensions ``direction`` ('up', 'down': those run) and the
        swept parameter (its values in the given order; the down leg is reordered to match),
        and a ``harmonic`` dimension for the harmonics. Coordinates carry ``units`` and
        ``long_name``, ``motion_class`` (codes) the CF ``flag_values``/``flag_meanings`` (with
        ``stops_per_period`` beside it: 'static' is the paper's rule, an amplitude below
        β/100), the dataset the fixed inputs and the package version. ``gain`` is G =
        (y_max − y_min)/(2β), ``gain1`` G1 = A1/β.

        For a physical experiment (a circuit or a mechanical oscillator) the physical values
        stand beside the dimensionless ones: ``f_Hz`` (drive frequency in Hz) beside ``w``,
        ``U_V`` (drive amplitude in V; ``F_N`` in N for a mechanical oscillator) beside
        ``beta``, as coordinates of the swept parameter or variables of the others, and
        ``peak_V`` (``peak_m``) beside ``peak``.

        Raises:
            ModuleNotFoundError: without xarray (``pip install 'stickslip[xarray]'``).
        """
        xr = _checks.optional_module("xarray", "xarray", "SweepResult.to_xarray()")

        legs = [leg for leg in ("up", "down") if np.any(self.direction == leg)]

        def table(column: np.ndarray) -> np.ndarray:
            rows = []
            for leg in legs:
                part = column[self.direction == leg]
                rows.append(part[::-1] if leg == "down" else part)
            return np.stack(rows)

        values = table(self.value)[0]
        dims = ("direction", self.over)
        coords: Dict[str, Any] = {
            "direction": ("direction", np.asarray(legs),
                          {"long_name": "direction of the sweep leg"}),
            self.over: _coordinate(self.over, values),
            "harmonic": ("harmonic", np.arange(1, self.harmonics.shape[1] + 1),
                         {"long_name": "order k of the drive harmonic", "units": "1"}),
        }
        data: Dict[str, Any] = {
            "motion_class": (dims, table(self.class_code), _motion_attributes()),
            "period": (dims, table(self.period), dict(_PERIOD_ATTRIBUTES)),
            "stops_per_period": (dims, table(self.stops_per_period),
                                 {"long_name": "stops of non-zero duration per drive period",
                                  "units": "1"}),
            "gain": (dims, table(self.gain),
                     {"long_name": "gain G = (y_max - y_min)/(2 beta)", "units": "1"}),
            "gain1": (dims, table(self.gain1),
                      {"long_name": "gain of the fundamental G1 = A1/beta", "units": "1"}),
            "peak": (dims, table(self.peak), {"long_name": "largest |y|", "units": "1"}),
            "phase_lag": (dims, table(self.phase_lag),
                          {"long_name": "lag of the fundamental behind the drive",
                           "units": "rad"}),
            "harmonics": (dims + ("harmonic",),
                          np.stack([table(self.harmonics[:, k])
                                    for k in range(self.harmonics.shape[1])], axis=-1),
                          {"long_name": "amplitude A_k of the drive harmonic k of y",
                           "units": "1"}),
        }
        for name in ("w", "beta", "zeta", "mu_s"):
            if name != self.over:
                data.setdefault(name, (dims, table(getattr(self, name)), _coordinate(name, values)[2]))
        scales = self.experiment.scales()
        if scales is not None:
            coords.update(_physical_coordinates(self.experiment, [self.over], {self.over: values}))
            for name in ("w", "beta"):
                if name != self.over:
                    physical, factor, attrs = _physical_parameter(name, scales)
                    data[physical] = (dims, table(getattr(self, name)) * factor, attrs)
            unit = scales["position_unit"]
            data[f"peak_{unit}"] = (dims, table(self.peak) * float(scales["position"]),
                                    {"long_name": "largest |u_C|" if unit == "V"
                                     else "largest |r|", "units": unit})
        attrs = _fixed_attributes(self.experiment, [self.over])
        attrs["steady_options"] = json.dumps(self.options)
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def __repr__(self) -> str:
        return f"<stickslip.SweepResult over {self.over}: {len(self)} steps>"


#: The type of a map's exponent arrays: an array with ``lyapunov=True``, else None (a plain
#: ``PhaseDiagram`` annotation means either).
if TYPE_CHECKING:
    from typing_extensions import TypeVar as _TypeVar

    _Exponents = _TypeVar("_Exponents", bound=Optional[np.ndarray], covariant=True,
                          default=Optional[np.ndarray])
else:
    _Exponents = TypeVar("_Exponents", bound=Optional[np.ndarray], covariant=True)


class PhaseDiagram(Generic[_Exponents]):
    """Steady motions on a grid of parameters, each point from the initial state
    (``stickslip.phase_diagram``, ``stickslip.dask.phase_diagram``, ``stickslip.dask.sweep_grid``).

    Attributes:
        dims: the parameters along the axes, in the order given (a map has two; a stack of
            maps from ``sweep_grid`` has the outer ones first).
        coords: dict from each parameter to its float64 values.
        motion_class: array of shape ``tuple(len(coords[d]) for d in dims)`` of the class
            labels, ``MOTION_CLASSES`` = ('sliding', 'periodic-stick', 'undecided', 'static',
            'chaotic'); class_code: their int8 codes into ``labels``. 'undecided': no period
            within the budget and not chaotic. 'static' is the paper's rule, an amplitude
            (y_max − y_min)/2 below β/100, whether or not the motion stops (at (w, β) =
            (2.0, 1.1) of the paper's circuit it holds a motion that stops twice a period):
            read ``stops_per_period`` beside it.
        period: int16 array, the period in drive periods, **-1 where none was found** (up to
            the ``max_period`` option, 16 by default).
        stops_per_period: float64 array, stops of non-zero duration per drive period.
        gain: float64 array, G = (y_max − y_min)/(2β) (inf at β = 0 with motion).
        symmetric: bool array; periods_to_settle: int64 array.
        lambda1, lambda1_error: float64 arrays of the largest Lyapunov exponent λ1 per unit τ
            and its standard error, with ``phase_diagram(..., lyapunov=True)`` (None
            otherwise): exactly ln|μ1|/(pT) from the Floquet multiplier of the orbit where the
            motion repeats (error 0), measured where it does not; -inf where both multipliers
            vanish, NaN where the flow has no derivative.
        experiment, options: what was run.

    ``to_dict()`` is the library's map report, the shape of ``stickslip phase-diagram``'s
    CSV and of the lab's ``/api/map``: ``lyapunov`` (whether the exponents were measured) and
    ``points``, one dict per point in the order of the grid's rows, keyed by the library's
    columns (``_core.MAP_COLUMNS``: w, beta, class, period, stops_per_period, gain; with
    exponents ``_core.MAP_EXPONENT_COLUMNS``: lambda1, lambda1_error). ``diagram[name]``
    gives a field by the report's name (``diagram["class"]``: the labels). The names before
    (``motion`` for the codes, ``stops_per_cycle``, ``lyapunov``, ``lyapunov_error``,
    ``lambda_error``, ``diagram["lambda"]``, ``motion_labels()``) still work, with a
    ``DeprecationWarning``.
    """

    motion = Renamed("class_code")
    stops_per_cycle = Renamed("stops_per_period")
    lyapunov = Renamed("lambda1")
    lyapunov_error = Renamed("lambda1_error")
    lambda_error = Renamed("lambda1_error")

    def __init__(self, experiment: Experiment, dims: Sequence[str],
                 coords: Mapping[str, np.ndarray], options: Dict[str, Any],
                 arrays: Mapping[str, np.ndarray]) -> None:
        self.experiment = experiment
        self.dims: Tuple[str, ...] = tuple(dims)
        self.coords: Dict[str, np.ndarray] = {d: coords[d] for d in self.dims}
        self.options = options
        self.labels: Tuple[str, ...] = MOTION_CLASSES
        # `arrays` holds the arrays by their names (FIELDS, EXPONENT_FIELDS) or by the
        # compiled core's keys (_CORE_KEYS, _CORE_EXPONENT_KEYS).
        def array(name: str, core: str) -> Optional[np.ndarray]:
            return arrays[name] if name in arrays else arrays.get(core)

        found = {name: array(name, core) for name, core in
                 zip(self.FIELDS + self.EXPONENT_FIELDS,
                     self._CORE_KEYS + self._CORE_EXPONENT_KEYS)}
        missing = [name for name in self.FIELDS if found[name] is None]
        if missing:
            raise KeyError(f"PhaseDiagram needs the arrays {', '.join(self.FIELDS)}: "
                           f"{', '.join(missing)} missing")
        self.class_code: np.ndarray = found["class_code"]  # type: ignore[assignment]
        self.period: np.ndarray = found["period"]  # type: ignore[assignment]
        self.stops_per_period: np.ndarray = found["stops_per_period"]  # type: ignore[assignment]
        self.gain: np.ndarray = found["gain"]  # type: ignore[assignment]
        self.symmetric: np.ndarray = found["symmetric"]  # type: ignore[assignment]
        self.periods_to_settle: np.ndarray = found["periods_to_settle"]  # type: ignore[assignment]
        # An array with lyapunov=True, None otherwise: the type says which
        # (``PhaseDiagram[np.ndarray]`` from ``phase_diagram(..., lyapunov=True)``).
        self.lambda1: _Exponents = found["lambda1"]  # type: ignore[assignment]
        self.lambda1_error: _Exponents = found["lambda1_error"]  # type: ignore[assignment]

    #: The arrays of every map, by their attributes' names.
    FIELDS = ("class_code", "period", "stops_per_period", "gain", "symmetric",
              "periods_to_settle")
    #: The arrays of a map asked for its exponents.
    EXPONENT_FIELDS = ("lambda1", "lambda1_error")
    #: The compiled core's keys of the same arrays (``_core.grid``), as ``arrays`` holds them.
    _CORE_KEYS = ("motion", "period", "stops_per_cycle", "gain", "symmetric",
                  "periods_to_settle")
    _CORE_EXPONENT_KEYS = ("lyapunov", "lyapunov_error")
    #: Fields by name (``diagram[name]``): the library's columns and the other attributes.
    _NAMES = FIELDS + EXPONENT_FIELDS
    #: Names retired, by the name now.
    _RETIRED = {"lambda": "lambda1", "lambda_error": "lambda1_error", "lyapunov": "lambda1",
                "lyapunov_error": "lambda1_error", "motion": "class_code",
                "stops_per_cycle": "stops_per_period"}

    @property
    def motion_class(self) -> np.ndarray:
        """The class of every point as a label (the reports' ``class``)."""
        return np.asarray(self.labels)[self.class_code]

    def __getitem__(self, name: str) -> np.ndarray:
        """A field by the report's name (``class``: the labels; ``lambda1``,
        ``lambda1_error``: the exponents), or by an attribute's."""
        name = renamed_key("PhaseDiagram", name, self._RETIRED)
        if name == "class":
            return self.motion_class
        value = getattr(self, name, None) if name in self._NAMES else None
        if value is None:
            raise KeyError(f"no field {name!r}: the fields are class, period, "
                           "stops_per_period, gain, symmetric, periods_to_settle (lambda1, "
                           "lambda1_error with lyapunov=True)")
        return value

    def _parameter(self, name: str) -> np.ndarray:
        """The value of ``name`` at every point: its axis broadcast, or the experiment's."""
        if name in self.dims:
            axis = self.dims.index(name)
            shape = [1] * len(self.dims)
            shape[axis] = -1
            return np.broadcast_to(np.reshape(self.coords[name], shape), self.shape)
        value = getattr(self.experiment, name)
        return np.full(self.shape, np.nan if value is None else value)

    def _column(self, name: str) -> List[Any]:
        """The library's column ``name`` as plain values, the grid's rows one after the other."""
        if name in ("w", "beta"):
            return _plain(self._parameter(name).ravel())
        if name == "class":
            return self.motion_class.ravel().tolist()
        if name == "period":
            return _optional_period(self.period.ravel())
        return _plain(self[name].ravel())

    def to_dict(self) -> Dict[str, Any]:
        """The library's map report (a new dict of plain values): ``lyapunov`` and ``points``,
        one dict per point keyed by the library's columns, the grid's rows one after the
        other (as ``stickslip phase-diagram`` writes its CSV)."""
        lyapunov = self.lambda1 is not None and self.lambda1_error is not None
        names = list(_core.MAP_COLUMNS)
        if lyapunov:
            names += list(_core.MAP_EXPONENT_COLUMNS)
        columns = [self._column(name) for name in names]
        points = [dict(zip(names, row)) for row in zip(*columns)]
        return {"lyapunov": lyapunov, "points": points}

    @property
    def shape(self) -> Tuple[int, ...]:
        return self.class_code.shape

    def motion_labels(self) -> np.ndarray:
        """The class of every point as a label (deprecated: ``motion_class``)."""
        warn_renamed("PhaseDiagram", "motion_labels()", "motion_class")
        return self.motion_class

    def counts(self) -> Dict[str, int]:
        """How many points of each class."""
        return {label: int(np.sum(self.class_code == k)) for k, label in enumerate(self.labels)}

    def to_xarray(self) -> "xarray.Dataset":
        """An ``xarray.Dataset`` with one dimension per parameter (named after it; coordinates
        with ``units`` and ``long_name``), ``motion_class`` (codes) with the CF
        ``flag_values`` and ``flag_meanings`` ('static' is the paper's rule, an amplitude
        below β/100: ``stops_per_period`` says whether such a motion stops), ``period`` (-1:
        none found; written to netCDF with -1 as its ``_FillValue``), ``stops_per_period``,
        ``gain``, ``symmetric``, ``periods_to_settle``, with ``lyapunov=True`` also
        ``lambda1`` and ``lambda1_error`` (per unit τ), and the fixed inputs, the options and
        the package version as attributes. The variables carry the attributes' names
        (``motion_class``: ``class`` is a Python keyword, which ``ds.<name>`` cannot reach).

        For a physical experiment (a circuit or a mechanical oscillator) the physical values
        stand beside the dimensionless axes as coordinates: ``f_Hz`` (drive frequency in Hz)
        beside ``w``, ``U_V`` (drive amplitude in V; ``F_N`` in N for a mechanical
        oscillator) beside ``beta``; ``f0_Hz`` and the fixed drive in physical units are
        attributes.

        Raises:
            ModuleNotFoundError: without xarray (``pip install 'stickslip[xarray]'``).
        """
        xr = _checks.optional_module("xarray", "xarray", "PhaseDiagram.to_xarray()")

        coords: Dict[str, Any] = {d: _coordinate(d, self.coords[d]) for d in self.dims}
        coords.update(_physical_coordinates(self.experiment, self.dims, self.coords))
        data: Dict[str, Any] = {
            "motion_class": (self.dims, self.class_code, _motion_attributes()),
            "period": (self.dims, self.period, dict(_PERIOD_ATTRIBUTES)),
            "stops_per_period": (self.dims, self.stops_per_period,
                                 {"long_name": "stops of non-zero duration per drive period",
                                  "units": "1"}),
            "gain": (self.dims, self.gain,
                     {"long_name": "gain G = (y_max - y_min)/(2 beta)", "units": "1"}),
            "symmetric": (self.dims, self.symmetric.astype(np.int8),
                          {"long_name": "whether the cycle is symmetric",
                           "flag_values": np.array([0, 1], dtype=np.int8),
                           "flag_meanings": "asymmetric symmetric"}),
            "periods_to_settle": (self.dims, self.periods_to_settle,
                                  {"long_name": "drive periods run before the cycle was found",
                                   "units": "1"}),
        }
        if self.lambda1 is not None and self.lambda1_error is not None:
            data["lambda1"] = (self.dims, self.lambda1,
                               {"long_name": "largest Lyapunov exponent lambda1 per unit tau",
                                "units": "1"})
            data["lambda1_error"] = (self.dims, self.lambda1_error,
                                     {"long_name": "standard error of the largest Lyapunov "
                                                   "exponent per unit tau", "units": "1"})
        attrs = _fixed_attributes(self.experiment, self.dims)
        attrs["steady_options"] = json.dumps(self.options)
        # `period` keeps -1 for "none found" as a value, not a _FillValue: a fill value would
        # make xarray read it back as float32 with NaN.
        return xr.Dataset(data, coords=coords, attrs=attrs)

    @classmethod
    def from_xarray(cls, dataset: "xarray.Dataset") -> "PhaseDiagram[Any]":
        """The map back from its ``to_xarray()`` dataset, or from a netCDF file that dataset
        was saved to (``PhaseDiagram.from_xarray(xarray.open_dataset("map.nc"))``): the same
        experiment, options, coordinates and arrays, with their dtypes (``period`` int16 with
        -1 where none was found, also from files that stored -1 as a fill value).

        Raises:
            ValueError: a dataset that is not a map of this package (no ``motion_class``,
                ``motion`` in files written before, with its flag meanings, no
                ``experiment_json``), or a class this version does not know.
        """
        def first(*names: str) -> Optional[str]:
            return next((n for n in names if n in dataset), None)

        classes = first("motion_class", "motion")
        if classes is None or "experiment_json" not in dataset.attrs:
            raise ValueError("not a map of stickslip: PhaseDiagram.from_xarray reads what "
                             "PhaseDiagram.to_xarray() writes (a 'motion_class' variable and "
                             "the attribute 'experiment_json')")
        motion = dataset[classes]
        dims = tuple(str(d) for d in motion.dims)
        coords = {d: np.require(dataset[d].values, np.float64, ["C", "A"]) for d in dims}
        # Labels retired read as the labels now ('nonperiodic-stick' is 'undecided').
        retired = {"nonperiodic-stick": "undecided"}
        labels = [retired.get(label, label)
                  for label in str(motion.attrs.get("flag_meanings", "")).split()]
        unknown = [label for label in labels if label not in MOTION_CLASSES]
        if not labels or unknown:
            raise ValueError(f"the map's motion classes {labels} are not this version's "
                             f"{list(MOTION_CLASSES)}")
        lookup = np.array([MOTION_CLASSES.index(label) for label in labels], dtype=np.int8)
        period = np.asarray(dataset["period"].values)
        if period.dtype.kind == "f":
            period = np.where(np.isnan(period), -1, period)
        stops = first("stops_per_period", "stops_per_cycle") or "stops_per_period"
        arrays: Dict[str, np.ndarray] = {
            "class_code": lookup[np.asarray(motion.values, dtype=np.int64)],
            "period": period.astype(np.int16),
            "stops_per_period": np.asarray(dataset[stops].values, dtype=np.float64),
            "gain": np.asarray(dataset["gain"].values, dtype=np.float64),
            "symmetric": np.asarray(dataset["symmetric"].values).astype(bool),
            "periods_to_settle": np.asarray(dataset["periods_to_settle"].values,
                                            dtype=np.int64),
        }
        for name, older in (("lambda1", ("lyapunov", "lambda")),
                            ("lambda1_error", ("lyapunov_error", "lambda_error"))):
            stored = first(name, *older)
            if stored is not None:
                arrays[name] = np.asarray(dataset[stored].values, dtype=np.float64)
        experiment = Experiment.from_json(str(dataset.attrs["experiment_json"]))
        options = json.loads(str(dataset.attrs.get("steady_options", "{}")))
        return cls(experiment, dims, coords, options, arrays)

    def __repr__(self) -> str:
        axes = " × ".join(f"{d} ({len(self.coords[d])})" for d in self.dims)
        counts = ", ".join(f"{k} {v}" for k, v in self.counts().items() if v)
        return f"<stickslip.PhaseDiagram {axes}: {counts}>"


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
            repeat is measured by its largest Lyapunov exponent, with the exact PWL model; 0:
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
            f"{caller} takes {wanted} parameter arrays as keywords (of zeta, w, beta, mu_s), "
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

    Give the two parameters as keyword arrays, any two of ``zeta``, ``w``, ``beta``,
    ``mu_s``; the first keyword is the first axis (rows), the second the second (columns).

    Args:
        experiment: a ``stickslip.Experiment``; it needs no value of either parameter.
        model: 'pwl' or 'shockley' to use that diode law instead of the experiment's own.
        threads: compute on a pool of this many threads (an integer from 1 to 1024;
            default: one per core). Results are the same for any number.
        progress: True for a progress bar (tqdm), or a callable ``progress(done, total)``
            (points), or one of one argument given the points done since its last call (a
            tqdm bar's ``update``); called from the calling thread about every 50 ms.
        lyapunov: also the largest Lyapunov exponent of every point (exact PWL model; as
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


def _exponent(value: Any) -> float:
    """An exponent of a report: a number, or the text "-inf" for −∞."""
    return float("-inf") if value == "-inf" else float(value)


#: The structured dtype of an orbit's stops.
STOP_DTYPE = np.dtype([("start", np.float64), ("duration", np.float64)])


class PeriodicOrbit:
    """A periodic orbit found by Newton's method, with its Floquet multipliers
    (``stickslip.orbit``).

    ``to_dict()`` is exactly the JSON of ``stickslip orbit --json`` for the same input.
    Everything is dimensionless (times in τ = ω0·t).

    Attributes:
        period: p in drive periods, as asked for (or found); least_period: the divisor of p
            after which the orbit repeats (Newton's method asked for p = 2 may land on an
            orbit of period 1).
        drive_period: T = 2π/w.
        state: (y, y') at the orbit's strobe (τ = 0 mod pT); stuck_at_strobe: bool.
        multipliers: complex128 array of the two Floquet multipliers, the larger modulus
            first (one is 0 when the orbit stops: a stop erases the velocity perturbation);
            moduli: their |μ|.
        stable: whether every perturbation decays (|μ1| < 1); stability: 'stable',
            'unstable' or 'neutral'.
        lambda1, lambda1_per_period: the largest Lyapunov exponent of the orbit, λ1 =
            ln|μ1|/(pT) per unit τ and ln|μ1|/p per drive period (-inf when both multipliers
            vanish; the names before, ``exponent_per_tau`` and ``exponent_per_period``, still
            work with a ``DeprecationWarning``).
        monodromy: 2×2 float64 array M = ∂P^p/∂(y, y').
        iterations: Newton steps; residuals: float64 array, max(|Δy|, |Δy'|) of P^p(x) − x
            at the guess and after every step.
        events: structured array (tau, y, kind) over one orbit period, times from the strobe;
            stops: structured array (start, duration); stops_per_period: stops longer than
            1e-8 drive periods per drive period.
        experiment: the experiment.
    """

    exponent_per_tau = Renamed("lambda1")
    exponent_per_period = Renamed("lambda1_per_period")

    def __init__(self, experiment: Experiment, report: Dict[str, Any]) -> None:
        self.experiment = experiment
        self._report = report
        r = report
        self.period: int = r["period"]
        self.least_period: int = r["least_period"]
        self.drive_period: float = r["drive_period"]
        self.state: Tuple[float, float] = (r["y"], r["v"])
        self.stuck_at_strobe: bool = r["stuck_at_strobe"]
        self.multipliers = np.array([complex(m["re"], m["im"]) for m in r["multipliers"]])
        self.moduli = np.asarray(r["moduli"], dtype=np.float64)
        self.stable: bool = r["stable"]
        self.stability: str = r["stability"]
        self.lambda1: float = _exponent(r["lambda1"])
        self.lambda1_per_period: float = _exponent(r["lambda1_per_period"])
        self.monodromy = np.asarray(r["monodromy"], dtype=np.float64)
        self.iterations: int = r["iterations"]
        self.residuals = np.asarray(r["residuals"], dtype=np.float64)
        self.stops_per_period: float = r["stops_per_period"]
        events = r["events"]
        self.events = np.empty(len(events), dtype=EVENT_DTYPE)
        self.events["tau"] = [e["tau"] for e in events]
        self.events["y"] = [e["y"] for e in events]
        self.events["kind"] = [e["kind"] for e in events]
        self.stops = np.array([(s["start"], s["duration"]) for s in r["stops"]],
                              dtype=STOP_DTYPE)

    def to_dict(self) -> Dict[str, Any]:
        """The report as ``stickslip orbit --json`` prints it (a new dict of plain values)."""
        return copy.deepcopy(self._report)

    def __repr__(self) -> str:
        mu = ", ".join(f"{m:.6g}" for m in self.multipliers)
        return (f"<stickslip.PeriodicOrbit period {self.period}: {self.stability}, "
                f"multipliers {mu}, {self.iterations} Newton steps>")


class LyapunovResult:
    """The Lyapunov exponents of a motion and what they say (``stickslip.lyapunov``).

    ``to_dict()`` is exactly the JSON of ``stickslip lyapunov --json`` for the same input.
    Rates are per unit τ = ω0·t (``*_per_period``: per drive period).

    Attributes:
        lambda1, lambda1_error: the largest exponent λ1 and its standard error (from the block
            means); lambda1_per_period, lambda1_error_per_period: the same per drive period.
        motion_class: 'periodic' when the motion has reached a periodic orbit or rest (its
            strobe repeats within 16 periods; ``period`` gives the period), else
            'chaotic' (λ1 > kσ), 'quasi-periodic' (|λ1| ≤ kσ), 'contracting'
            (λ1 < −kσ: settling onto a periodic attractor) or 'undecided' (the two halves of
            the measurement disagree), with k = ``significance`` (the JSON's ``class``).
        verdict: what λ1 alone says ('chaotic', 'quasi-periodic', 'contracting',
            'undecided'); period: the period reached, or None.
        converged: whether the two halves agree.
        lambda2, lambda2_per_period: the second exponent (-inf once the motion stops: a stop
            erases the velocity perturbation; ``lambda2_reason`` says so; the JSON of
            ``to_dict()`` has null there); lambda2_error: its standard error.
        stops_per_period: stops longer than 1e-8 drive periods per drive period.
        block_means: float64 array of λ1 per block, in time order.
        transient_periods, periods, blocks, significance: how it was measured (``periods``:
            the drive periods measured, fewer than ``cap_periods`` when the verdict was
            decided early; ``sequential``: whether it could stop early).
        final_state: (y, y') at the end of the measurement (a strobe).
        experiment: the experiment.

    The names before (``lambda_per_tau``, ``error_per_tau``, ``lambda_per_period``,
    ``error_per_period``, ``lambda2_per_tau``, ``lambda2_error_per_tau``) still work, with a
    ``DeprecationWarning``.
    """

    lambda_per_tau = Renamed("lambda1")
    error_per_tau = Renamed("lambda1_error")
    lambda_per_period = Renamed("lambda1_per_period")
    error_per_period = Renamed("lambda1_error_per_period")
    lambda2_per_tau = Renamed("lambda2")
    lambda2_error_per_tau = Renamed("lambda2_error")

    def __init__(self, experiment: Experiment, report: Dict[str, Any]) -> None:
        self.experiment = experiment
        self._report = report
        r = report
        self.lambda1: float = r["lambda1"]
        self.lambda1_error: float = r["lambda1_error"]
        self.lambda1_per_period: float = r["lambda1_per_period"]
        self.lambda1_error_per_period: float = r["lambda1_error_per_period"]
        self.motion_class: str = r["class"]
        self.verdict: str = r["verdict"]
        self.period: Optional[int] = r["period"]
        self.converged: bool = r["converged"]
        minus_infinity = r["lambda2"] is None
        self.lambda2: float = float("-inf") if minus_infinity else float(r["lambda2"])
        self.lambda2_error: Optional[float] = r["lambda2_error"]
        self.lambda2_per_period: float = (float("-inf") if minus_infinity
                                          else float(r["lambda2_per_period"]))
        self.lambda2_reason: Optional[str] = r["lambda2_reason"]
        self.stops_per_period: float = r["stops_per_period"]
        self.block_means = np.asarray(r["block_means"], dtype=np.float64)
        self.transient_periods: int = r["transient_periods"]
        self.periods: int = r["periods"]
        self.cap_periods: int = r["cap_periods"]
        self.sequential: bool = r["sequential"]
        self.blocks: int = r["blocks"]
        self.significance: float = r["significance"]
        self.drive_period: float = r["drive_period"]
        self.final_state: Tuple[float, float] = (r["final_y"], r["final_v"])

    def to_dict(self) -> Dict[str, Any]:
        """The report as ``stickslip lyapunov --json`` prints it (a new dict of plain values)."""
        return copy.deepcopy(self._report)

    def __repr__(self) -> str:
        return (f"<stickslip.LyapunovResult {self.motion_class}: λ1 = {self.lambda1:+.4e} "
                f"± {self.lambda1_error:.1e} per unit τ over {self.periods} periods>")


def orbit(experiment: Experiment, period: Optional[int] = None, *, transient: int = 0,
          tolerance: float = 1e-12, max_iterations: int = 30, progress: Progress = None,
          **options: Any) -> PeriodicOrbit:
    """A periodic orbit by Newton's method on the p-fold strobe map (the state once every p
    drive periods), with its Jacobian: its Floquet multipliers say whether it is stable and
    how fast perturbations grow or decay (as ``stickslip orbit``). With the PWL law the
    Jacobian is exact; with Shockley diodes it is the derivative of the stiff solver's
    computed map (the variational equations on the solver's own steps).

    Args:
        experiment: a ``stickslip.Experiment`` with its drive given (PWL or Shockley diodes,
            or Coulomb friction).
        period: p in drive periods (1 to 1000). None (the default): the motion from the
            initial state is run to its steady state, which gives p and the guess.
        transient: with a period, drive periods run from the initial state before Newton's
            method starts (0 to 1e8; 0: from the initial state y0, v0 itself, which can aim
            at an unstable orbit).
        tolerance: relative tolerance of Newton's method (default 1e-12).
        max_iterations: most Newton steps (1 to 1000; default 30).
        progress: True for a progress bar (tqdm), a callable ``progress(done, total)``
            (drive periods of the transient) or a tqdm bar's ``update``.
        **options: of the steady-state search without a period: max_periods (5000),
            max_period (16), tolerance is Newton's (above).

    Returns:
        A ``PeriodicOrbit``; ``to_dict()`` equals ``stickslip orbit --json``.

    Raises:
        ValueError: bad input, no period found, Newton's method failing,
            with the library's message. KeyboardInterrupt: Ctrl-C stops a long transient.

    Example:
        >>> o = stickslip.orbit(stickslip.Experiment.paper(w=0.7, beta=1.2))
        >>> o.period, o.stable, round(float(o.moduli[0]), 6), o.stops_per_period
        (1, True, 0.626452, 2.0)
        >>> u = stickslip.orbit(stickslip.Experiment(zeta=0, mu_s=3, w=0.33, beta=9),
        ...                     period=1, transient=2000)
        >>> u.stability, round(u.lambda1, 5)
        ('unstable', 0.01747)
    """
    experiment = _with_model(experiment, None)
    unknown = set(options) - {"max_periods", "max_period"}
    if unknown:
        raise TypeError(f"orbit() got an unknown option {sorted(unknown)[0]!r}: the options are "
                        "max_periods, max_period")
    options = _checks.steady_options(options, False, "orbit")
    if period is not None:
        period = _checks.integer("period", period, "orbit")
    transient = _checks.integer("transient", transient, "orbit")
    tolerance = _checks.number("tolerance", tolerance)
    max_iterations = _checks.integer("max_iterations", max_iterations, "orbit")
    with _progress.reporter(progress, "orbit", "periods") as callback:
        report = _core.orbit(experiment, period, transient, options, tolerance, max_iterations,
                             callback)
    return PeriodicOrbit(experiment, report)


def lyapunov(experiment: Experiment, *, transient: int = 1000, periods: int = 20000,
             blocks: int = 20, significance: float = 4.0,
             progress: Progress = None, fixed: bool = False) -> LyapunovResult:
    """The Lyapunov exponents of the motion from the initial state, by the tangent dynamics
    (as ``stickslip lyapunov``): the PWL law's exact ones, or with Shockley diodes those of
    the stiff solver's computed solution.

    The 2×2 Jacobian of the exact flow is carried along the trajectory; after ``transient``
    drive periods the largest exponent λ1 is averaged over at most ``periods`` more, cut into
    ``blocks`` blocks whose spread gives its standard error σ. Two motions that start δ
    apart are about e^(λ1 τ)·δ apart later (τ = ω0·t). The measurement stops at the first of
    its looks (after about periods/32, /16, …, /2 and all of them) where the halves agree and
    |λ1| > kσ (docs/stability.md gives the rule and its significance).

    Args:
        experiment: a ``stickslip.Experiment`` with its drive given (either diode law).
        transient: drive periods run before measuring (0 to 1e9; default 1000).
        periods: drive periods measured (``blocks`` to 1e9; default 20000; rounded down to a
            multiple of ``blocks``).
        blocks: even, from 4 to 10000 (default 20).
        significance: k, the standard errors that make λ1 significant (default 4).
        progress: True for a progress bar (tqdm), a callable ``progress(done, total)``
            (drive periods) or a tqdm bar's ``update``.
        fixed: measure all ``periods`` even when the verdict is decided sooner (default
            False; as ``--fixed``).

    Returns:
        A ``LyapunovResult``; ``to_dict()`` equals ``stickslip lyapunov --json``.

    Raises:
        ValueError: bad input, with the library's message.
        KeyboardInterrupt: Ctrl-C stops a long measurement.

    Example:
        >>> c = stickslip.lyapunov(stickslip.Experiment(zeta=0, mu_s=3, w=0.33, beta=9),
        ...                        transient=500, periods=2000)
        >>> c.motion_class, c.lambda1 > 4 * c.lambda1_error, c.lambda2
        ('chaotic', True, -inf)
    """
    experiment = _with_model(experiment, None)
    blocks = _checks.integer("blocks", blocks, "lyapunov")
    transient = _checks.integer("transient", transient, "lyapunov")
    periods = _checks.integer("periods", periods)
    significance = _checks.number("significance", significance)
    with _progress.reporter(progress, "lyapunov", "periods") as callback:
        report = _core.lyapunov(experiment, transient, periods, blocks, significance, callback,
                                bool(fixed))
    return LyapunovResult(experiment, report)
