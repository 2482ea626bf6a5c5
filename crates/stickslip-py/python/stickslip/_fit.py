"""Measurements and fits: ``read_scope``, ``read_amplitudes``, ``fit`` (see
``stickslip/__init__.py``)."""

from __future__ import annotations

import copy
import os
from typing import (TYPE_CHECKING, Any, Dict, List, Literal, Optional, Sequence, Tuple, Union,
                    overload)

import numpy as np
import numpy.typing as npt

from . import _checks, _core, _progress
from ._common import _with_model
from ._progress import Progress
from ._core import Experiment
from ._names import Renamed

if TYPE_CHECKING:
    import xarray

PathLike = Union[str, "os.PathLike[str]"]
_FloatArray = npt.NDArray[np.float64]


class ScopeRecord:
    """A scope record (``stickslip.read_scope``): the samples of every channel, the drive and
    response channels picked for fitting, and the drive's sine fit.

    Attributes:
        file: the file name ('a.csv+b.csv' for files merged on their common times).
        paths: the files read, in order.
        format: 'rigol', 'tektronix', 'keysight', 'siglent', 'merged' or 'plain'.
        sample_interval_s: the sample interval (s).
        t_s: float64 array of the sample times (s).
        channels: channel name → float64 array of its values (V).
        units: channel name → its unit ('V').
        resolution_V: channel name → the scope's vertical resolution (V, the smallest step
            between values; None when it cannot be told).
        clipped: channel name → the number of clipped samples (a flat run at the channel's
            extreme values; excluded from fits).
        metadata: the file's header entries (key → text).
        drive_channel, response_channel: the names of the drive and u_C channels.
        drive, response: their float64 arrays (V).
        freq_Hz, amplitude_V (peak), phase (rad), drive_offset_V: the drive's sine fit over
            its whole periods; periods: the number of whole drive periods captured.
        noise_V: the noise of u_C estimated from the data (V).
    """

    def __init__(self, paths: Tuple[str, ...], drive: Optional[str], response: Optional[str],
                 data: Dict[str, Any]) -> None:
        self.paths = paths
        self._drive_arg = drive
        self._response_arg = response
        self.file: str = data["file"]
        self.format: str = data["format"]
        self.sample_interval_s: float = data["sample_interval_s"]
        self.t_s: _FloatArray = data["t_s"]
        self.channels: Dict[str, _FloatArray] = dict(data["channels"])
        self.units: Dict[str, str] = dict(data["units"])
        self.resolution_V: Dict[str, Optional[float]] = dict(data["resolution_V"])
        self.clipped: Dict[str, int] = dict(data["clipped"])
        self.metadata: Dict[str, str] = dict(data["metadata"])
        self.drive_channel: str = data["drive_channel"]
        self.response_channel: str = data["response_channel"]
        self.drive: _FloatArray = self.channels[self.drive_channel]
        self.response: _FloatArray = self.channels[self.response_channel]
        self.freq_Hz: float = data["freq_Hz"]
        self.amplitude_V: float = data["amplitude_V"]
        self.phase: float = data["phase"]
        self.drive_offset_V: float = data["drive_offset_V"]
        self.periods: int = data["periods"]
        self.noise_V: float = data["noise_V"]

    def __len__(self) -> int:
        return len(self.t_s)

    def __repr__(self) -> str:
        return (f"<stickslip.ScopeRecord {self.file} ({self.format}): {len(self)} samples, "
                f"drive {self.drive_channel} {self.freq_Hz:.6g} Hz {self.amplitude_V:.6g} V, "
                f"u_C {self.response_channel}, {self.periods} periods>")


class AmplitudeTable:
    """A table of measured amplitudes (``stickslip.read_amplitudes``), one entry per row.

    Attributes:
        file: the file name.
        line: int64 array of each row's line in the file (1-based).
        freq_Hz: drive frequency (Hz); U_V: drive amplitude (V, peak); response_V: the
            response amplitude (V, half the peak-to-peak of u_C); A1_V, A3_V: the first and
            third harmonic of u_C from the scope's FFT (V; NaN where not given): float64 arrays.
        direction: the leg of the sweep of each row, 'up', 'down' or None.
    """

    def __init__(self, path: str, data: Dict[str, Any]) -> None:
        self.path = path
        self.file: str = data["file"]
        self.line: npt.NDArray[np.int64] = data["line"]
        self.freq_Hz: _FloatArray = data["freq_Hz"]
        self.U_V: _FloatArray = data["U_V"]
        self.response_V: _FloatArray = data["response_V"]
        self.A1_V: _FloatArray = data["A1_V"]
        self.A3_V: _FloatArray = data["A3_V"]
        self.direction: List[Optional[str]] = list(data["direction"])

    def __len__(self) -> int:
        return len(self.line)

    def __repr__(self) -> str:
        return f"<stickslip.AmplitudeTable {self.file}: {len(self)} rows>"


def _path(path: Any) -> str:
    if isinstance(path, (str, os.PathLike)):
        return os.fspath(path)
    raise TypeError(f"expected a file path (str or os.PathLike), got {type(path).__name__}")


def read_scope(path: Union[PathLike, Sequence[PathLike]], drive: Optional[str] = None,
               response: Optional[str] = None) -> ScopeRecord:
    """Read a scope record (CSV): Rigol, Tektronix, Keysight InfiniiVision and Siglent exports
    are told from their header; a plain CSV needs a header row with a time column (t, time,
    time_s, second). A list of paths merges single-channel files (a Tektronix export writes
    one per channel) on their common times.

    Args:
        path: the file, or a list of files to merge.
        drive: the drive channel (its name, 'CHn' or position) [default: the first].
        response: the u_C channel [default: the second].

    Returns:
        A ``ScopeRecord``: numpy arrays of the times (s) and channels (V), units, metadata,
        and the drive's frequency (Hz), amplitude (V) and phase from a sine fit over its whole
        periods.

    Raises:
        ValueError: a file that cannot be read or used (a garbage row, a non-monotonic time
            column, a record shorter than one drive period, a missing or fully clipped
            channel), naming the file and the line where there is one.

    Example:
        >>> r = stickslip.read_scope("run1.csv")          # doctest: +SKIP
        >>> r.freq_Hz, r.amplitude_V                      # doctest: +SKIP
    """
    paths = (_path(path),) if isinstance(path, (str, os.PathLike)) else tuple(
        _path(p) for p in path)
    if not paths:
        raise ValueError("read_scope: no file given")
    return ScopeRecord(paths, drive, response, _core.read_scope(list(paths), drive, response))


def read_amplitudes(path: PathLike) -> AmplitudeTable:
    """Read a table of measured amplitudes (CSV), the way the paper's Fig. 4 was taken:
    columns freq_Hz (Hz), U_V (V, peak) and response_V (V, half the peak-to-peak of u_C),
    optionally direction (up/down), A1_V and A3_V. Unknown columns are refused.

    Raises:
        ValueError: a file that cannot be read or used, naming the file and the line.
    """
    p = _path(path)
    return AmplitudeTable(p, _core.read_amplitudes(p))


class FitRecord:
    """One record of a fit: the measured u_C and the fitted model at the used samples, and
    the record's summary.

    Attributes:
        file: the record's file name.
        t_s: float64 array of the fitted samples' times (s; clipped samples left out).
        measured_V, model_V, residual_V: float64 arrays of u_C measured, modelled, and
            model − measured (V).
        freq_Hz, amplitude_V: the drive (Hz, V peak); w, beta: dimensionless drive;
        motion_class: the motion class of the fitted steady state (``motion``, its name
            before, still works with a ``DeprecationWarning``); periods: whole drive periods;
        clipped: clipped samples; rms_residual_V: RMS of the residuals (V); offset_V: the
        fitted DC offset of u_C (V); time_shift_s: the fitted time shift (s). Of an
        undriven belt's record: freq_Hz, w and periods are its self-excited cycle's
        (frequency, angular frequency over ω0, whole cycles), amplitude_V and beta are 0,
        and time_shift_s is the time of the cycle's section (s since the first sample).
    """

    motion = Renamed("motion_class")

    def __init__(self, arrays: Dict[str, Any], summary: Dict[str, Any]) -> None:
        self.file: str = arrays["file"]
        self.t_s: _FloatArray = arrays["t_s"]
        self.measured_V: _FloatArray = arrays["measured_V"]
        self.model_V: _FloatArray = arrays["model_V"]
        self.residual_V: _FloatArray = arrays["residual_V"]
        self.freq_Hz: float = summary["freq_Hz"]
        self.amplitude_V: float = summary["amplitude_V"]
        self.w: float = summary["w"]
        self.beta: float = summary["beta"]
        self.motion_class: str = summary["class"]
        self.periods: int = summary["periods"]
        self.clipped: int = summary["clipped"]
        self.rms_residual_V: float = summary["rms_residual_V"]
        self.offset_V: float = summary["offset_V"]
        self.time_shift_s: float = summary["time_shift_s"]

    def __repr__(self) -> str:
        return (f"<stickslip.FitRecord {self.file}: {len(self.t_s)} samples, RMS residual "
                f"{self.rms_residual_V:.3g} V>")


def _number(value: Optional[float]) -> float:
    return float("nan") if value is None else float(value)


class FitNotConverged(RuntimeError):
    """A fit that did not converge, raised by ``stickslip.fit(..., strict=True)`` (the
    meaning of ``stickslip fit``'s exit status 3): its steps or its gradient had not settled,
    or a restart from elsewhere ended lower in χ². The message is the fit's ``not-converged``
    warning; ``result`` is the ``FitResult`` (or the list of them, ``per_record=True``)
    with its values, error bars and warnings, which are not those of a minimum."""

    def __init__(self, message: str, result: Any) -> None:
        super().__init__(message)
        self.result = result


class FitResult:
    """A fit of an experiment to measurements (``stickslip.fit``).

    ``to_dict()`` is exactly the JSON of ``stickslip fit --json`` for the same files.

    Attributes:
        names: the free parameters, in the order given ('resistance', 'ut', 'rd', 'diode-is',
            'diode-n', 'diode-rs', 'inductance', 'capacitance', 'mu-s'; mechanics: 'damping',
            'friction', 'mass', 'stiffness', 'mu-s').
        parameters: name → fitted value, in SI units (Ω, V, A, H, F; N·s/m, N, kg, N/m; n
            and μs are pure numbers; a held parameter's starting value); stderr: name → its
            standard error (NaN where there is none: a parameter held or unseen, a singular
            fit; a warning says why); ci95: name → the 95 % confidence interval (lo, hi).
        intervals: name → how its interval was found: 'linear' (value ± t·stderr, in ln I_s
            for I_s, checked at both ends), 'profile' (the profile likelihood, where the
            linear approximation fails), 'held' (not identified: held at its start) or
            'none'.
        warnings: what the fit warns of, as ``stickslip fit`` prints on standard error: a
            list of dicts ``{'kind', 'parameters', 'message'}``, kind one of
            'not-converged', 'not-identified' (parameters the records see only as a
            combination, such as R + R_s), 'unseen', 'correlated' (|r| > 0.99),
            'at-bound' and 'clipped'.
        covariance: float64 array (len(names) × len(names)) of the parameters' covariance
            (SI units squared); correlation: float64 array of their correlation.
        records: a ``FitRecord`` per record (empty for a table), with residual arrays.
        rows: a table's rows as dicts (line, freq_Hz, U_V, direction, measured_V, model_V,
            class); empty for records.
        rms_residual_V: RMS of all residuals (V); chi2_dof: χ²/dof with the noise estimated
            from the data (None when unknown); converged: the step and gradient criteria hold
            and no restart from elsewhere found a lower χ² (else a 'not-converged' warning
            says why; ``fit(..., strict=True)`` raises ``FitNotConverged``); iterations: of
            Levenberg–Marquardt; jacobian: how its Jacobian at the solution was computed,
            'exact' (from the tangent dynamics of the PWL model's periodic orbits),
            'sensitivities' (the stiff solver's forward sensitivities along the Shockley
            model's periodic orbits), 'central-differences' (a mechanical oscillator on a
            belt or with the Stribeck law) or 'finite-differences';
            aic, bic: information criteria; model: the diode law, 'pwl' or 'shockley' (a
            mechanical oscillator's Coulomb law is 'pwl').
        units: the units of the drive and of the response, ``{'drive': 'V', 'response':
            'V'}`` for a circuit, ``{'drive': 'N', 'response': 'm'}`` for a mechanical
            oscillator: the values named in V are in these units (``to_dict()`` has the key
            ``units`` for a mechanical oscillator only, as the command line's JSON).
        exp: the fitted experiment (the experiment with the fitted values).
        experiment: the experiment fitted from (the starting values).
    """

    def __init__(self, experiment: Experiment, data: Dict[str, Any]) -> None:
        r: Dict[str, Any] = data["report"]
        self.experiment = experiment
        self._report = r
        self.names: Tuple[str, ...] = tuple(data["names"])
        self.parameters: Dict[str, float] = {k: v["value"] for k, v in r["parameters"].items()}
        self.stderr: Dict[str, float] = {k: _number(v["stderr"])
                                         for k, v in r["parameters"].items()}
        self.ci95: Dict[str, Tuple[float, float]] = {
            k: (_number(v["ci95"][0]), _number(v["ci95"][1]))
            for k, v in r["parameters"].items()}
        self.intervals: Dict[str, str] = {k: v["interval"] for k, v in r["parameters"].items()}
        self.warnings: List[Dict[str, Any]] = copy.deepcopy(r["warnings"])
        self.covariance: _FloatArray = np.asarray(data["covariance"], dtype=np.float64).reshape(
            len(self.names), len(self.names))
        self.correlation: _FloatArray = np.array(
            [[_number(c) for c in row] for row in r["correlation"]],
            dtype=np.float64).reshape(len(self.names), len(self.names))
        self.records: List[FitRecord] = [FitRecord(a, s) for a, s in
                                         zip(data["records"], r.get("records", []))]
        self.rows: List[Dict[str, Any]] = list(r.get("rows", []))
        self.rms_residual_V: float = r["rms_residual_V"]
        self.chi2_dof: Optional[float] = r["chi2_dof"]
        self.converged: bool = r["converged"]
        self.iterations: int = r["iterations"]
        self.jacobian: str = r["jacobian"]
        self.aic: float = r["aic"]
        self.bic: float = r["bic"]
        self.model: str = r["model"]
        self.units: Dict[str, str] = dict(r.get("units", {"drive": "V", "response": "V"}))
        self.exp: Experiment = experiment.replace(**data["keys"])

    def to_dict(self) -> Dict[str, Any]:
        """The report as ``stickslip fit --json`` prints it (a new dict of plain values)."""
        return copy.deepcopy(self._report)

    def to_xarray(self) -> "xarray.Dataset":
        """The residuals as an ``xarray.Dataset``. Records: along the dimension ``sample``
        (every record's fitted samples, one after the other), ``measured_V``, ``model_V`` and
        ``residual_V`` with the coordinates ``t_s`` and ``file``. A table: along ``row``, with
        the coordinates ``line``, ``freq_Hz`` and ``U_V``. The fitted values are attributes.

        Raises:
            ModuleNotFoundError: without xarray (``pip install 'stickslip[xarray]'``).
        """
        xr = _checks.optional_module("xarray", "xarray", "FitResult.to_xarray()")
        attrs: Dict[str, Any] = {"model": self.model, "converged": int(self.converged),
                                 "rms_residual_V": self.rms_residual_V}
        for name in self.names:
            attrs[name] = self.parameters[name]
            attrs[f"{name}_stderr"] = self.stderr[name]
        volts = {"units": self.units["response"]}
        if self.records:
            def joined(name: str) -> _FloatArray:
                return np.concatenate([getattr(r, name) for r in self.records])
            coords: Dict[str, Any] = {
                "t_s": ("sample", joined("t_s"), {"units": "s", "long_name": "time"}),
                "file": ("sample", np.concatenate(
                    [np.full(len(r.t_s), r.file, dtype=object) for r in self.records]
                ).astype(str), {"long_name": "record"}),
            }
            data = {
                "measured_V": ("sample", joined("measured_V"),
                               dict(volts, long_name="measured u_C")),
                "model_V": ("sample", joined("model_V"), dict(volts, long_name="fitted u_C")),
                "residual_V": ("sample", joined("residual_V"),
                               dict(volts, long_name="model − measured u_C")),
            }
            return xr.Dataset(data, coords=coords, attrs=attrs)
        rows = self.rows
        measured = np.array([r["measured_V"] for r in rows], dtype=np.float64)
        model = np.array([r["model_V"] for r in rows], dtype=np.float64)
        coords = {
            "line": ("row", np.array([r["line"] for r in rows], dtype=np.int64)),
            "freq_Hz": ("row", np.array([r["freq_Hz"] for r in rows], dtype=np.float64),
                        {"units": "Hz", "long_name": "drive frequency"}),
            "U_V": ("row", np.array([r["U_V"] for r in rows], dtype=np.float64),
                    dict(volts, long_name="drive amplitude")),
        }
        data = {
            "measured_V": ("row", measured, dict(volts, long_name="measured amplitude")),
            "model_V": ("row", model, dict(volts, long_name="fitted amplitude")),
            "residual_V": ("row", model - measured,
                           dict(volts, long_name="model − measured amplitude")),
        }
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def __repr__(self) -> str:
        values = ", ".join(f"{n} = {self.parameters[n]:.6g} ± {self.stderr[n]:.2g}"
                           for n in self.names)
        return (f"<stickslip.FitResult {self.model}: {values}; RMS residual "
                f"{self.rms_residual_V:.3g} {self.units['response']}, {'converged' if self.converged else 'NOT converged'}>")


Measurements = Union[ScopeRecord, AmplitudeTable, PathLike]


@overload
def fit(exp: Experiment, data: Union[Measurements, Sequence[Measurements]] = ...,
        free: Union[str, Sequence[str], None] = ..., model: Optional[str] = ...,
        per_record: Literal[False] = ..., *, progress: Progress = ...,
        strict: bool = ..., from_rest: Optional[float] = ...,
        belt_speeds: Optional[Sequence[Optional[float]]] = ...) -> FitResult: ...


@overload
def fit(exp: Experiment, data: Union[Measurements, Sequence[Measurements]] = ...,
        free: Union[str, Sequence[str], None] = ..., model: Optional[str] = ...,
        *, per_record: Literal[True], progress: Progress = ...,
        strict: bool = ..., from_rest: Optional[float] = ...,
        belt_speeds: Optional[Sequence[Optional[float]]] = ...) -> List[FitResult]: ...


@overload
def fit(exp: Experiment, data: Union[Measurements, Sequence[Measurements]] = ...,
        free: Union[str, Sequence[str], None] = ..., model: Optional[str] = ...,
        per_record: bool = ..., *, progress: Progress = ..., strict: bool = ...,
        from_rest: Optional[float] = ...,
        belt_speeds: Optional[Sequence[Optional[float]]] = ...
        ) -> Union[FitResult, List[FitResult]]: ...


def fit(exp: Experiment, data: Union[Measurements, Sequence[Measurements]] = (),
        free: Union[str, Sequence[str], None] = None, model: Optional[str] = None,
        per_record: bool = False, *, progress: Progress = None, strict: bool = False,
        from_rest: Optional[float] = None,
        belt_speeds: Optional[Sequence[Optional[float]]] = None
        ) -> Union[FitResult, List[FitResult]]:
    """Fit the circuit's (or the mechanical oscillator's) parameters to measurements: least
    squares of the model's steady u_C (or displacement) against every scope record at once
    (with the drive of each record as measured, a DC offset of the response and a time shift
    per record), or of the steady amplitudes against a table. The same fit as
    ``stickslip fit``.

    A mechanical oscillator (``Experiment(mass=..., stiffness=..., damping=...,
    friction=...)``) is fitted to records of the drive force and the displacement whose
    header gives their units, N and m (a plain CSV ``time_s,F (N),r (m)``); its free
    parameters are 'damping' (γ), 'friction' (F0), 'mass', 'stiffness' and 'mu-s', and on
    a belt with the Stribeck law (``belt_speed=``, ``friction_law='stribeck'``) also
    'stribeck-speed' and 'viscous-friction' (docs/fit.md, "A belt's friction law"). The
    values named in V (``rms_residual_V``, a record's ``amplitude_V``, ``measured_V`` …) then
    hold newtons (the drive) and metres (the response), as ``units`` says. Tables are for
    circuits.

    An undriven belt (no drive force: the block's self-excited cycle on a belt moving at
    ``belt_speed``) is fitted to records of the displacement alone (a plain CSV
    ``time_s,r (m)``, or beside a constant force channel): the model is the settled
    self-excited cycle at the parameters' values, aligned to each record by the time of a
    section (a record's ``time_shift_s``) fitted with the rest; a record's ``freq_Hz`` is
    then the cycle's frequency, ``w`` its angular frequency over ω0, ``periods`` its whole
    cycles, and its ``amplitude_V`` and ``beta`` are 0. Each record must hold
    a whole cycle; with the offset of r free, F0 only shifts r (give it, and fit 'mu-s',
    'stribeck-speed', 'viscous-friction', 'damping'). A record that starts as the belt starts
    under the block at rest is fitted with ``from_rest`` (the model is then the motion from
    rest, and F0 is seen apart from 'mu-s'); records at several belt speeds with
    ``belt_speeds``. See docs/fit.md, "An undriven belt".

    Args:
        exp: the circuit or the mechanical oscillator, with the starting values.
        data: ``ScopeRecord``\\ s (``read_scope``) or file paths of scope records (read with
            the default channels), or one ``AmplitudeTable`` (``read_amplitudes``).
        free: the free parameters: 'resistance', 'ut', 'rd' (PWL), 'diode-is', 'diode-n',
            'diode-rs' (Shockley), 'inductance', 'capacitance', 'mu-s' (underscores are
            accepted); for mechanics 'damping', 'friction', 'mass', 'stiffness', 'mu-s', and
            with the Stribeck friction law 'stribeck-speed' (m/s) and 'viscous-friction'
            (N·s/m), the belt speed given; a comma-separated string or a sequence [default: the library's free set of the system
            and diode law: ('resistance', 'ut') with PWL diodes, ('resistance', 'diode-is',
            'diode-n') with Shockley diodes; mechanics: ('damping', 'friction')].
        model: the diode law, 'pwl' or 'shockley' [default: the experiment's].
        per_record: fit each record alone (how a parameter drifts with the drive): returns a
            list of results, one per record, as ``stickslip fit --per-record --json``.
        progress: True for a progress bar (tqdm), a tqdm bar's ``update`` (given the
            iterations done since its last call), or a callable: ``progress(done, total)``
            is called from the calling thread as the fit
            goes on (at most every 50 ms, and once at the end): Levenberg–Marquardt
            iterations done, of the most it may take (4·50 per fit of records: two passes,
            a restart and the intervals' profiles, usually far fewer; 50 for a table; summed
            over the records with ``per_record``). An exception it raises stops the fit and
            propagates.
        from_rest: undriven records from rest: the block at rest on the ground this far (m)
            from the spring's rest length when the belt starts, at each record's first sample
            (``stickslip fit --from-rest``).
        belt_speeds: one per record of ``data``: the belt speed (m/s) of an undriven record
            taken at a speed of its own, None for the experiment's (``--data FILE@SPEED``).
        strict: raise ``FitNotConverged`` when a fit did not converge (what ``stickslip
            fit``'s exit status 3 says) instead of returning it with ``converged`` False.

    Returns:
        A ``FitResult`` (values in SI units, standard errors, covariance, residuals, the
        fitted experiment ``exp``), or a list of them with ``per_record=True``.

    Raises:
        ValueError: bad measurements (naming the file and line), an unknown or repeated free
            parameter, a parameter of the other diode law or of the other twin (a circuit's
            on a mechanical oscillator or the other way round), a record whose units do not
            fit the twin, no data, or a model that cannot be computed at the starting values.
        FitNotConverged: with ``strict=True``, a fit that did not converge (its result is
            the exception's ``result``).
        KeyboardInterrupt: Ctrl-C stops a long fit.

    Example:
        >>> r = stickslip.fit(stickslip.Experiment.paper(), data=["run1.csv"])  # doctest: +SKIP
        >>> r.parameters["resistance"], r.stderr["resistance"]                # doctest: +SKIP
    """
    experiment = _with_model(exp, model)
    names: Optional[List[str]] = (
        None if free is None
        else [n.strip() for n in free.split(",")] if isinstance(free, str) else list(free))
    items: List[Measurements] = (
        [data] if isinstance(data, (str, os.PathLike, ScopeRecord, AmplitudeTable))
        else list(data))
    records: List[Tuple[List[str], Optional[str], Optional[str]]] = []
    table: Optional[str] = None
    for item in items:
        if isinstance(item, AmplitudeTable):
            if table is not None or len(items) > 1:
                raise ValueError("fit: an amplitude table is fitted alone (give one table, "
                                 "or scope records)")
            table = item.path
        elif isinstance(item, ScopeRecord):
            records.append((list(item.paths), item._drive_arg, item._response_arg))
        else:
            records.append(([_path(item)], None, None))
    if table is not None and per_record:
        raise ValueError("fit: per_record takes scope records, not a table")
    if table is None and not records:
        raise ValueError("fit: no data: give scope records or an amplitude table (data=[...])")
    with _progress.reporter(progress, "fit", "iterations") as callback:
        results = [FitResult(experiment, d) for d in
                   _core.fit(experiment, records, table, names, per_record, callback,
                             from_rest, None if belt_speeds is None else list(belt_speeds))]
    result = results if per_record else results[0]
    if strict:
        for r in results:
            if not r.converged:
                why = next((w["message"] for w in r.warnings if w["kind"] == "not-converged"),
                           "the fit did not converge")
                raise FitNotConverged(why, result)
    return result
