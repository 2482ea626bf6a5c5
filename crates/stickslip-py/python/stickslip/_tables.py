"""Tables of steady states: a sweep (:class:`SweepResult`) and a map (:class:`PhaseDiagram`)."""

from __future__ import annotations

import copy
import json
from typing import (TYPE_CHECKING, Any, Dict, Generic, List, Mapping, Optional, Sequence, Tuple,
                    TypeVar)

import numpy as np

from . import _checks, _core
from ._core import Experiment
from ._names import Renamed, renamed_key, warn_renamed
from ._common import (MOTION_CLASSES, SWEEP_COLUMNS, _PERIOD_ATTRIBUTES, _coordinate,
                      _fixed_attributes, _motion_attributes, _optional_period,
                      _physical_coordinates, _physical_parameter, _plain)

if TYPE_CHECKING:
    import xarray
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
        amplitude, y_max, y_min: float64 arrays: (y_max − y_min)/2 and the extremes of y.
        cycle_period_tau, cycle_period_s, stick_fraction: float64 arrays, a self-excited
            belt's (no drive): the cycle's own period in τ = ω0·t and in seconds (NaN for
            steady sliding, a forced step, or seconds of a dimensionless experiment) and the
            fraction of it stuck to the belt (NaN for a forced step). Sweep ``vb`` up and
            down for the classic amplitude against belt speed, with its hysteresis.
        experiment, options: what was run.

    ``result[name]`` gives a column by the report's name (the CSV's and the JSON's):
    ``result["class"]`` the labels. The names before (``leg``, ``motion`` for the codes,
    ``stops_per_cycle``, ``motion_labels()``) still work, with a ``DeprecationWarning``.

    ``to_dict()`` is the library's sweep report, the JSON shape every front end gives: the
    swept parameter ``over``, the ``direction`` asked for and one dict per step in ``points``
    (``SWEEP_COLUMNS``: value, w, beta, zeta, mu_s, direction, gain, gain1, peak, A1, A3,
    class, stops_per_period, period, phase_lag, f_Hz, amplitude, y_max, y_min,
    cycle_period_tau, cycle_period_s, stick_fraction), as ``stickslip sweep`` writes its CSV
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
        self.amplitude: np.ndarray = column("amplitude")
        self.y_max: np.ndarray = column("y_max")
        self.y_min: np.ndarray = column("y_min")
        self.cycle_period_tau: np.ndarray = column("cycle_period_tau")
        self.cycle_period_s: np.ndarray = column("cycle_period_s")
        self.stick_fraction: np.ndarray = column("stick_fraction")

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
            "amplitude": (dims, table(self.amplitude),
                          {"long_name": "amplitude (y_max - y_min)/2", "units": "1"}),
            "y_max": (dims, table(self.y_max), {"long_name": "largest y", "units": "1"}),
            "y_min": (dims, table(self.y_min), {"long_name": "smallest y", "units": "1"}),
            "cycle_period_tau": (dims, table(self.cycle_period_tau),
                                 {"long_name": "period of the self-excited cycle in "
                                               "tau = omega0 t", "units": "1"}),
            "cycle_period_s": (dims, table(self.cycle_period_s),
                               {"long_name": "period of the self-excited cycle", "units": "s"}),
            "stick_fraction": (dims, table(self.stick_fraction),
                               {"long_name": "fraction of the self-excited cycle stuck to "
                                             "the belt", "units": "1"}),
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
            'chaotic', then the belt's self-excited 'stick-slip-cycle', 'pure-slip-cycle',
            'steady-sliding'); class_code: their int8 codes into ``labels`` (fixed: a new
            class is added last). 'undecided': no period
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
    columns (``_core.MAP_COLUMNS``: w, beta (a map over two other keys: their names),
    class, period, stops_per_period, gain; with
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
        if name in ("w", "beta") or name in self.dims:
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
        if len(self.dims) == 2 and set(self.dims) != {"w", "beta"}:
            # A map over two other keys names them first, as the CSV does
            # (``MapRow::columns_over``): vb, mu_s, class, ...
            names = list(self.dims) + names[2:]
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
