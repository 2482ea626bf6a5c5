"""Constants and helpers shared by the package's result types and functions."""

from __future__ import annotations

from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from . import _checks, _core
from ._core import Experiment


#: The classes of steady motion (``motion_class``, the reports' ``class``), in the order of
#: their codes in ``class_code`` arrays: 'sliding', 'periodic-stick', 'undecided', 'static'
#: and 'chaotic' (a motion that does not repeat, with a largest Lyapunov exponent positive
#: beyond its error), then the self-excited motions of a block on a moving belt without a
#: drive: 'stick-slip-cycle', 'pure-slip-cycle' and 'steady-sliding' (a new class is always
#: added last: a code never changes). 'undecided' is no kind of motion: no period was found within the budget
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


def _exponent(value: Any) -> float:
    """An exponent of a report: a number, or the text "-inf" for −∞."""
    return float("-inf") if value == "-inf" else float(value)
