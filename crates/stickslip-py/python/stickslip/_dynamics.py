"""Bifurcation diagrams, basins of attraction and branches of periodic orbits (see
``stickslip/__init__.py``): the package's side of ``stickslip bifurcation``, ``stickslip
basins`` and ``stickslip continue``."""

from __future__ import annotations

import copy
import json
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _checks, _core, _progress
from ._common import (_coordinate, _fixed_attributes, _optional_period,
                      _physical_coordinates, _plain, _values, _with_model)
from ._core import Experiment
from ._names import Renamed, renamed_key, warn_renamed
from ._progress import Progress

if TYPE_CHECKING:
    import xarray

#: What a motion settles on (``motion_class`` of a bifurcation diagram or a basin map, the
#: reports' ``class``), in the order of the codes in ``class_code`` arrays: 'periodic',
#: 'static' (rest: the motion stops for good; not the steady-state class 'static' of
#: ``MOTION_CLASSES``, which is the paper's amplitude rule), 'chaotic', 'quasiperiodic',
#: 'undecided' (no verdict within the budget; its label was 'unsettled').
ATTRACTOR_KINDS: Tuple[str, ...] = tuple(_core.ATTRACTOR_KINDS)


def _kind_attributes() -> Dict[str, Any]:
    return {
        "long_name": "what the motion settled on",
        "flag_values": np.arange(len(ATTRACTOR_KINDS), dtype=np.int8),
        "flag_meanings": " ".join(ATTRACTOR_KINDS),
    }


class BifurcationDiagram:
    """Strobe points and the largest Lyapunov exponent against a parameter
    (``stickslip.bifurcation``): one entry per value, in the order run.

    Attributes:
        over: the stepped parameter ('w', 'beta', 'zeta' or 'mu_s').
        value: float64 array (values,): the parameter at each value run.
        direction: array of 'up' or 'down', the leg of each value.
        y, v: float64 arrays (values, points): the strobe points (y, y') once per drive period
            at drive phase φ, after the transient.
        lambda1: float64 array: the largest Lyapunov exponent λ1 per unit τ: over the recorded
            periods where the points repeat, else measured sequentially from the last point
            as ``steady`` does; lambda1_error: its standard error (NaN with fewer than 8
            points).
        motion_class: what each value settled on, labels of ``labels`` = ``ATTRACTOR_KINDS``
            ('static' is rest: the motion stopped for good; 'undecided': no verdict within
            the record); class_code: their int8 codes.
        period: int16, the period in drive periods, -1 without one.
        events, stops: int64, events and stops while recording.
        experiment, options: what was run.

    ``to_dict()`` is the library's bifurcation report, the rows of ``stickslip
    bifurcation``'s CSV: ``parameter`` and ``points``, one dict per strobe point keyed by the
    library's fields (``_core.BIFURCATION_FIELDS``: value, y, v, direction, lambda1, class,
    period). ``diagram[name]`` gives a per-value column by the report's name (``class``: the
    labels). The names before (``leg``, ``exponent``, ``exponent_error``, ``kind`` for the
    codes, ``kind_labels()``, ``diagram["lambda"]``) still work, with a
    ``DeprecationWarning``.
    """

    leg = Renamed("direction")
    exponent = Renamed("lambda1")
    exponent_error = Renamed("lambda1_error")
    kind = Renamed("class_code")

    #: Names retired, by the name now.
    _RETIRED = {"lambda": "lambda1", "leg": "direction", "exponent": "lambda1",
                "exponent_error": "lambda1_error", "kind": "class_code"}

    def __init__(self, experiment: Experiment, over: str, options: Dict[str, Any],
                 data: Dict[str, Any]) -> None:
        self.experiment = experiment
        self.over = over
        self.options = options
        self.labels: Tuple[str, ...] = ATTRACTOR_KINDS
        self.value: np.ndarray = data["value"]
        self.direction: np.ndarray = np.asarray(_core.SWEEP_LEGS)[data["leg"]]
        points = int(data["points"])
        self.y: np.ndarray = data["y"].reshape(len(self.value), points)
        self.v: np.ndarray = data["v"].reshape(len(self.value), points)
        self.lambda1: np.ndarray = data["exponent"]
        self.lambda1_error: np.ndarray = data["exponent_error"]
        self.class_code: np.ndarray = data["kind"]
        self.motion_class: np.ndarray = np.asarray(self.labels)[self.class_code]
        self.period: np.ndarray = data["period"]
        self.events: np.ndarray = data["events"]
        self.stops: np.ndarray = data["stops"]

    def __len__(self) -> int:
        return len(self.value)

    def __getitem__(self, name: str) -> np.ndarray:
        """A per-value column by the report's name (``direction``, ``lambda1``, ``class`` as
        labels, ``period``, ``value``), or by an attribute's."""
        name = renamed_key("BifurcationDiagram", name, self._RETIRED)
        if name == "class":
            return self.motion_class
        if name in ("value", "direction", "lambda1", "lambda1_error", "class_code",
                    "motion_class", "period", "events", "stops", "y", "v"):
            return np.asarray(getattr(self, name))
        raise KeyError(f"no column {name!r}: the columns are "
                       f"{', '.join(_core.BIFURCATION_FIELDS)}")

    def to_dict(self) -> Dict[str, Any]:
        """The library's bifurcation report (a new dict of plain values): ``parameter`` (the
        stepped one) and ``points``, one dict per strobe point in the order run, keyed by the
        library's fields (value, y, v, direction, lambda1, class, period; None where the CSV's
        cell is empty)."""
        rows = self.rows()
        names = list(_core.BIFURCATION_FIELDS)

        def column(name: str) -> List[Any]:
            values = rows[self.over if name == "value" else name]
            if name == "period":
                return _optional_period(values)
            if name in ("direction", "class"):
                return values.tolist()
            return _plain(values)

        columns = [column(name) for name in names]
        return {"parameter": self.over,
                "points": [dict(zip(names, row)) for row in zip(*columns)]}

    @property
    def points(self) -> int:
        """Strobe points per value."""
        return self.y.shape[1]

    def kind_labels(self) -> np.ndarray:
        """What each value settled on, as a label (deprecated: ``motion_class``)."""
        warn_renamed("BifurcationDiagram", "kind_labels()", "motion_class")
        return self.motion_class

    def rows(self) -> Dict[str, np.ndarray]:
        """The rows of ``stickslip bifurcation``'s CSV as columns, one per strobe point, keyed
        by the CSV's columns (``<over>`` and ``_core.BIFURCATION_COLUMNS``: y, v, direction,
        lambda1, class, period; the period -1 where the CSV's cell is empty)."""
        n = self.points
        per_point = {"y": self.y.ravel(), "v": self.v.ravel()}
        out = {self.over: np.repeat(self.value, n)}
        for name in _core.BIFURCATION_COLUMNS:
            out[name] = per_point[name] if name in per_point else np.repeat(self[name], n)
        return out

    def to_xarray(self) -> "xarray.Dataset":
        """An ``xarray.Dataset`` with dimensions ``direction`` ('up', 'down': those run), the
        stepped parameter (the down leg reordered to match the up leg) and ``point`` (the
        strobe points): ``y``, ``v`` (direction, parameter, point), ``lambda1``,
        ``lambda1_error``, ``motion_class`` (codes, CF flags), ``period`` (-1: none),
        ``events``, ``stops``. For a physical experiment, ``f_Hz`` (Hz) or ``U_V`` (V; ``F_N``
        in N) stands beside a stepped ``w`` or ``beta`` as a coordinate.

        Raises:
            ModuleNotFoundError: without xarray (``pip install 'stickslip[xarray]'``).
        """
        xr = _checks.optional_module("xarray", "xarray", "BifurcationDiagram.to_xarray()")

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
            "direction": ("direction", np.asarray(legs), {"long_name": "direction of the leg"}),
            self.over: _coordinate(self.over, values),
            "point": ("point", np.arange(self.points),
                      {"long_name": "index of the strobe point after the transient"}),
        }
        coords.update(_physical_coordinates(self.experiment, [self.over], {self.over: values}))
        data = {
            "y": (dims + ("point",), table(self.y),
                  {"long_name": "position y at the strobe (drive phase phi)", "units": "1"}),
            "v": (dims + ("point",), table(self.v),
                  {"long_name": "velocity y' at the strobe (drive phase phi)", "units": "1"}),
            "lambda1": (dims, table(self.lambda1),
                        {"long_name": "largest Lyapunov exponent lambda1 per unit tau",
                         "units": "1"}),
            "lambda1_error": (dims, table(self.lambda1_error),
                              {"long_name": "standard error of lambda1", "units": "1"}),
            "motion_class": (dims, table(self.class_code), _kind_attributes()),
            "period": (dims, table(self.period),
                       {"long_name": "period in drive periods (-1: none found)", "units": "1"}),
            "events": (dims, table(self.events),
                       {"long_name": "events while recording", "units": "1"}),
            "stops": (dims, table(self.stops),
                      {"long_name": "stops while recording", "units": "1"}),
        }
        attrs = _fixed_attributes(self.experiment, [self.over])
        attrs["title"] = "stickslip: bifurcation diagram of the forced oscillator with dry friction"
        for name, value in self.options.items():
            attrs[name] = value
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def __repr__(self) -> str:
        counts = ", ".join(f"{label} {int(np.sum(self.class_code == k))}"
                           for k, label in enumerate(self.labels)
                           if np.any(self.class_code == k))
        return (f"<stickslip.BifurcationDiagram over {self.over}: {len(self)} values × "
                f"{self.points} strobe points; {counts}>")


class BasinMap:
    """Which attractor the motion settles on from each initial state of a grid
    (``stickslip.basins``).

    Attributes:
        y0, v0: float64 arrays, the initial positions (rows) and velocities (columns).
        attractor: int32 array (len(y0), len(v0)): the number of the attractor reached, -1
            where the motion settled on nothing within the caps (undecided).
        motion_class: labels of ``labels`` = ``ATTRACTOR_KINDS`` per cell ('static' is rest:
            the motion stopped for good; 'undecided': no attractor within the caps), the CSV's
            ``class``; class_code: their int8 codes.
        period: int16, period of the cell's attractor in drive periods, -1 without one.
        attractors: list of dicts, one per attractor as ``stickslip basins --json`` lists
            them: id, class, period, fraction, cells, state {y, v}, strobes (at most 64),
            lambda1 (per unit τ; None where not finite), multipliers ([re, im] pairs,
            periodic only), rest_range (static only), first_cell.
        undecided: cells without an attractor.
        experiment: what was run (φ = the drive phase of the initial states).

    The names before (``kind`` for the codes, ``kind_labels()``, ``unsettled``) still work,
    with a ``DeprecationWarning``.
    """

    kind = Renamed("class_code")
    unsettled = Renamed("undecided")

    def __init__(self, experiment: Experiment, data: Dict[str, Any]) -> None:
        self.experiment = experiment
        self._report: Dict[str, Any] = data["report"]
        shape = tuple(data["shape"])
        self.labels: Tuple[str, ...] = ATTRACTOR_KINDS
        self.y0: np.ndarray = data["y0"]
        self.v0: np.ndarray = data["v0"]
        self.attractor: np.ndarray = data["attractor"].reshape(shape)
        self.class_code: np.ndarray = data["kind"].reshape(shape)
        self.motion_class: np.ndarray = np.asarray(self.labels)[self.class_code]
        self.period: np.ndarray = data["period"].reshape(shape)
        self.attractors: List[Dict[str, Any]] = copy.deepcopy(self._report["attractors"])
        self.undecided: int = self._report["undecided"]

    @property
    def shape(self) -> Tuple[int, int]:
        return self.attractor.shape  # type: ignore[return-value]

    def to_dict(self) -> Dict[str, Any]:
        """The summary as ``stickslip basins --json`` prints it (model, grid, attractors,
        undecided, undecided_fraction; a new dict of plain values)."""
        return copy.deepcopy(self._report)

    def kind_labels(self) -> np.ndarray:
        """What each cell settled on, as a label (deprecated: ``motion_class``)."""
        warn_renamed("BasinMap", "kind_labels()", "motion_class")
        return self.motion_class

    def to_xarray(self) -> "xarray.Dataset":
        """An ``xarray.Dataset`` with dimensions ``y0`` and ``v0``: ``attractor`` (-1:
        undecided), ``motion_class`` (codes, CF flags), ``period`` (-1: none), the model's
        parameters and the summary (JSON) as attributes.

        Raises:
            ModuleNotFoundError: without xarray (``pip install 'stickslip[xarray]'``).
        """
        import json

        xr = _checks.optional_module("xarray", "xarray", "BasinMap.to_xarray()")

        dims = ("y0", "v0")
        coords = {
            "y0": ("y0", self.y0, {"long_name": "initial position y0", "units": "1"}),
            "v0": ("v0", self.v0, {"long_name": "initial velocity y0'", "units": "1"}),
        }
        data = {
            "attractor": (dims, self.attractor,
                          {"long_name": "number of the attractor reached (-1: undecided)"}),
            "motion_class": (dims, self.class_code, _kind_attributes()),
            "period": (dims, self.period,
                       {"long_name": "period in drive periods (-1: none)", "units": "1"}),
        }
        attrs = _fixed_attributes(self.experiment, ["y0", "v0"])
        attrs["title"] = "stickslip: basins of attraction of the forced oscillator with dry friction"
        attrs["summary_json"] = json.dumps(self._report)
        ds = xr.Dataset(data, coords=coords, attrs=attrs)
        ds["attractor"].encoding["_FillValue"] = np.int32(-1)
        return ds

    def __repr__(self) -> str:
        parts = []
        for a in self.attractors:
            period = f" period {a['period']}" if a["period"] is not None else ""
            parts.append(f"#{a['id']} {a['class']}{period} ({100 * a['fraction']:.1f} %)")
        return (f"<stickslip.BasinMap {self.shape[0]} × {self.shape[1]}: "
                f"{len(self.attractors)} attractors: {', '.join(parts)}; "
                f"{self.undecided} undecided>")


class Branch:
    """A branch of periodic orbits (``stickslip.continuation``), one entry per point in order
    along the branch: the columns of ``stickslip continue``'s CSV.

    Attributes:
        over: the continued parameter.
        value: float64, the parameter at each point.
        y, v: float64, the strobe point (fixed point of the p-fold strobe map).
        amplitude: float64, (max y − min y)/2 of the orbit.
        period: int64, period p in drive periods; stops_per_period: float64; turns: int64,
            turning points per orbit period.
        mu1_re, mu1_im, mu2_re, mu2_im: float64, the Floquet multipliers, the larger first;
            ``multipliers``: the same as a complex (points, 2) array.
        stable: bool, the larger multiplier has modulus below 1.
        arclength: float64, arclength in (y, y', parameter) from the first point.
        special: list of dicts (kind 'fold', 'branch-point', 'period-doubling',
            'neimark-sacker' or 'grazing'; value, y, v, width, located, before, after).
        begin, end: dicts saying why the branch ends there (``reason`` and details);
            end_text: the end in words.
        start: (y, v, period, stops) of the orbit settled on at the start value.
        experiment: what was run.
    """

    COLUMNS = ("value", "y", "v", "amplitude", "period", "stops_per_period", "turns",
               "mu1_re", "mu1_im", "mu2_re", "mu2_im", "stable", "arclength")

    value: np.ndarray
    y: np.ndarray
    v: np.ndarray
    amplitude: np.ndarray
    period: np.ndarray
    stops_per_period: np.ndarray
    turns: np.ndarray
    mu1_re: np.ndarray
    mu1_im: np.ndarray
    mu2_re: np.ndarray
    mu2_im: np.ndarray
    stable: np.ndarray
    arclength: np.ndarray

    def __init__(self, experiment: Experiment, over: str, data: Dict[str, Any]) -> None:
        self.experiment = experiment
        self.over = over
        self._report: Dict[str, Any] = data["report"]
        for name in self.COLUMNS:
            setattr(self, name, data[name])
        self.multipliers = np.stack([data["mu1_re"] + 1j * data["mu1_im"],
                                     data["mu2_re"] + 1j * data["mu2_im"]], axis=-1)
        self.special: List[Dict[str, Any]] = copy.deepcopy(self._report["special"])
        self.begin: Dict[str, Any] = dict(self._report["begin"])
        self.end: Dict[str, Any] = dict(self._report["end"])
        self.end_text: str = self._report["end_text"]
        self.start: Tuple[float, float, int, int] = tuple(data["start"])  # type: ignore[assignment]

    def __len__(self) -> int:
        return len(self.value)

    def to_dict(self) -> Dict[str, Any]:
        """The summary as ``stickslip continue --json`` prints it (parameter, period, points,
        begin, end, end_text, special; a new dict of plain values)."""
        return copy.deepcopy(self._report)

    def to_xarray(self) -> "xarray.Dataset":
        """An ``xarray.Dataset`` of the branch along the dimension ``point`` (in order along
        the branch): the continued parameter (named after it) and ``arclength`` as
        coordinates (for a physical experiment ``f_Hz`` beside ``w``, ``U_V`` or ``F_N``
        beside ``beta``), the CSV's columns as variables (``stable`` with CF flags), the
        special points along the dimension ``special`` (``special_kind``,
        ``special_value``, ``special_y``, ``special_v``), and as attributes the fixed
        inputs, the orbit's period, why the branch begins and ends (``begin``, ``end`` as
        JSON, ``end_text``) and the package version.

        Raises:
            ModuleNotFoundError: without xarray (``pip install 'stickslip[xarray]'``).
        """
        xr = _checks.optional_module("xarray", "xarray", "Branch.to_xarray()")
        one = {"units": "1"}
        coords: Dict[str, Any] = {
            self.over: ("point", self.value, _coordinate(self.over, self.value)[2]),
            "arclength": ("point", self.arclength,
                          {"long_name": "arclength in (y, y', parameter) from the first point",
                           **one}),
        }
        for name, (_, values, attrs) in _physical_coordinates(
                self.experiment, [self.over], {self.over: self.value}).items():
            coords[name] = ("point", values, attrs)
        names = {
            "y": "strobe position y of the orbit", "v": "strobe velocity y' of the orbit",
            "amplitude": "(max y - min y)/2 of the orbit",
            "period": "period of the orbit in drive periods",
            "stops_per_period": "stops per drive period",
            "turns": "turning points per orbit period",
            "mu1_re": "real part of the larger Floquet multiplier",
            "mu1_im": "imaginary part of the larger Floquet multiplier",
            "mu2_re": "real part of the smaller Floquet multiplier",
            "mu2_im": "imaginary part of the smaller Floquet multiplier",
        }
        data: Dict[str, Any] = {name: ("point", getattr(self, name),
                                       {"long_name": text, **one})
                                for name, text in names.items()}
        data["stable"] = ("point", np.asarray(self.stable).astype(np.int8),
                          {"long_name": "whether the orbit is stable (|mu1| < 1)",
                           "flag_values": np.array([0, 1], dtype=np.int8),
                           "flag_meanings": "unstable stable"})
        data["special_kind"] = ("special", np.asarray([str(p["kind"]) for p in self.special],
                                                      dtype=str),
                                {"long_name": "kind of the special point"})
        for field, text in (("value", self.over), ("y", "y"), ("v", "y'")):
            data[f"special_{field}"] = ("special",
                                        np.asarray([p[field] for p in self.special],
                                                   dtype=np.float64),
                                        {"long_name": f"{text} at the special point", **one})
        attrs = _fixed_attributes(self.experiment, [self.over])
        attrs["title"] = "stickslip: a branch of periodic orbits"
        attrs["orbit_period"] = int(self._report["period"])
        attrs["begin"] = json.dumps(self.begin)
        attrs["end"] = json.dumps(self.end)
        attrs["end_text"] = self.end_text
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def __repr__(self) -> str:
        special = ", ".join(f"{s['kind']} at {s['value']:.6g}" for s in self.special) or "none"
        return (f"<stickslip.Branch of period-{self._report['period']} orbits over {self.over}: "
                f"{len(self)} points from {self.value[0]:.6g} to {self.value[-1]:.6g}; "
                f"special points: {special}; ends: {self.end_text}>")


def bifurcation(experiment: Experiment, over: str, values: Any, direction: str = "both", *,
                points: int = 100, transient: int = 200, first_transient: int = 2000,
                max_period: int = 32, progress: Progress = None) -> BifurcationDiagram:
    """A bifurcation diagram: at each value of one parameter, after a transient, the strobe
    points (y, y') once per drive period at drive phase φ, the largest Lyapunov exponent over
    them and what the motion settled on (as ``stickslip bifurcation``). Each value starts from
    the state where the value before ended, as when turning a knob, so the two directions show
    coexisting branches. A period-p orbit gives p distinct points; chaos a cloud and λ > 0.

    Args:
        experiment: a ``stickslip.Experiment`` (the exact solver for the piecewise-linear
            law, the stiff solver and its tangent dynamics for Shockley diodes); it needs no
            value of the stepped parameter. The first value starts from its initial state.
        over: 'w', 'beta', 'zeta' or 'mu_s'.
        values: the parameter's values, in order (any array-like of floats; dimensionless).
        direction: 'up' (values in order), 'down' (reversed) or 'both' (up, then down from
            where the up leg ended; the default).
        points: strobe points recorded at each value (drive periods; 1 to 10⁶; default 100).
        transient: drive periods run at each value before recording (0 to 1e8; default 200).
        first_transient: drive periods of transient at the first value (0 to 1e8; default
            2000).
        max_period: longest period looked for in the recorded points (drive periods; 1 to
            1000; default 32).
        progress: True for a progress bar (tqdm), a callable ``progress(done, total)``
            (values) or a tqdm bar's ``update``.

    Returns:
        A ``BifurcationDiagram``: ``y``, ``v`` (values × points), ``lambda1``,
        ``motion_class``, ``period`` per value; ``rows()`` = the CSV of ``stickslip bifurcation``;
        ``to_xarray()``.

    Raises:
        ValueError: bad input, with the library's message. KeyboardInterrupt: Ctrl-C.

    Example:
        >>> import numpy as np
        >>> exp = stickslip.Experiment(zeta=0.0, beta=9.0, mu_s=3.0)
        >>> d = stickslip.bifurcation(exp, "w", [0.25, 0.33], direction="up", points=60)
        >>> d.motion_class.tolist(), int(d.period[0]), len(np.unique(d.y[0].round(6)))
        (['periodic', 'chaotic'], 1, 1)
        >>> bool(d.lambda1[1] > 0), len(np.unique(d.y[1].round(6))) > 30
        (True, True)
    """
    experiment = _with_model(experiment, None)
    options = {name: _checks.integer(name, value, "bifurcation")
               for name, value in (("points", points), ("transient", transient),
                                   ("first_transient", first_transient),
                                   ("max_period", max_period))}
    values = _values("values", values)
    with _progress.reporter(progress, "bifurcation", "values") as callback:
        data = _core.bifurcation(experiment, over, values, direction,
                                 options["points"], options["transient"],
                                 options["first_transient"], options["max_period"], callback)
    return BifurcationDiagram(experiment, over, options, data)


def basins(experiment: Experiment, y0: Tuple[float, float], v0: Tuple[float, float],
           steps: Union[int, Tuple[int, int]] = 100, *, phase: Optional[float] = None,
           max_periods: int = 1000, max_period: int = 16, lyapunov_periods: int = 1000,
           threads: Optional[int] = None, progress: Progress = None,
           method: str = "recurrence") -> BasinMap:
    """Basins of attraction: which motion the oscillator settles on from each initial state
    (y0, y0') of a grid given at drive phase φ (as ``stickslip basins``). The
    attractors are numbered in the order of the cells (rows of y0, then y0'): a periodic orbit
    by its period and its fixed point (refined by Newton's method), rest, chaos by a positive
    largest Lyapunov exponent and its strobe set, quasi-periodic motion by an exponent within
    its error of zero. The result is the same for any number of threads.

    Args:
        experiment: a ``stickslip.Experiment`` with its drive (either diode law); its
            initial state is not used (the grid sets it).
        y0: (smallest, largest) initial position (dimensionless, units of y).
        v0: (smallest, largest) initial velocity y0'.
        steps: values along each axis, both ends included (an integer from 1 to 2000, or
            (rows, columns); default 100), checked before any work.
        phase: drive phase φ (radians) at which the initial states are given (default: the
            experiment's φ).
        max_periods: drive periods run at most per cell to find a period (1 to 1e8; default
            1000).
        max_period: longest period looked for, 1 to 64 drive periods (default 16).
        lyapunov_periods: drive periods over which the exponent of a motion without a period
            is measured (8 to 1e7; default 1000).
        threads: a pool of this many threads (1 to 1024; default: one per core; the exhaustive
            method's cells run in parallel, the recurrence method's one after the other).
        progress: True for a progress bar (tqdm), a callable ``progress(done, total)``
            (cells) or a tqdm bar's ``update``.
        method: ``'recurrence'`` (default: each initial state is followed on a grid of the
            state space 1024 cells across the map until it lands on cells labelled with an
            attractor or its basin, or declares a new attractor, classified once) or
            ``'exhaustive'`` (every cell run to its steady state and classified on its own,
            in parallel; the reference, costly where the motion is chaotic).

    Returns:
        A ``BasinMap``: ``attractor``, ``motion_class``, ``period`` per cell (the CSV of
        ``stickslip basins``), ``attractors`` and ``to_dict()`` (its ``--json``), ``to_xarray()``.

    Raises:
        ValueError: bad input, with the library's message. KeyboardInterrupt: Ctrl-C.

    Example:
        >>> exp = stickslip.Experiment(zeta=0.0, w=0.6, beta=3.269, mu_s=3.0)
        >>> m = stickslip.basins(exp, y0=(-8, 8), v0=(-8, 8), steps=12)
        >>> [(a["class"], a["period"]) for a in m.attractors]
        [('periodic', 1), ('periodic', 1)]
        >>> m.attractor.shape, int((m.attractor == -1).sum())
        ((12, 12), 0)
    """
    experiment = _with_model(experiment, None)
    if isinstance(steps, (tuple, list)):
        if len(steps) != 2:
            raise TypeError(f"steps must be an integer or a (rows, columns) pair, got {steps!r}")
        rows, cols = steps
    else:
        rows, cols = steps, steps
    with _progress.reporter(progress, "basins", "cells") as callback:
        data = _core.basins(experiment, _checks.pair("y0", y0), _checks.pair("v0", v0),
                            (_checks.integer("steps", rows, "basins"),
                             _checks.integer("steps", cols, "basins")),
                            None if phase is None else _checks.number("phase", phase),
                            _checks.integer("max_periods", max_periods, "basins"),
                            _checks.integer("max_period", max_period, "basins"),
                            _checks.integer("lyapunov_periods", lyapunov_periods, "basins"),
                            _checks.threads(threads), callback, method)
    if phase is not None:
        experiment = experiment.replace(phi=float(phase))
    return BasinMap(experiment, data)


def continuation(experiment: Experiment, over: str, start: float, to: float, *,
                 max_points: int = 5000, max_step: float = 0.1,
                 progress: Progress = None) -> Branch:
    """Follow a branch of periodic orbits as one parameter goes from ``start`` to ``to``,
    stable and unstable alike (as ``stickslip continue``). It starts from the periodic orbit
    the motion settles on at ``start`` (from the experiment's initial state), refined by
    Newton's method, and continues the fixed point of the p-fold strobe map in (y, y',
    parameter) by pseudo-arclength steps, so it goes round folds. The exact solver finds the
    events of every orbit afresh, so the branch goes on where a stop appears or disappears.
    Special points, each located to 1e-9 in arclength: fold (a multiplier through +1, the
    branch turns back), branch point, period doubling (through −1), grazing (the turning
    points or stops per period change), each with the orbit on either side.

    Args:
        experiment: a ``stickslip.Experiment`` (either diode law); the other parameters and
            the initial state come from it.
        over: the continued parameter: 'w', 'beta', 'zeta', 'mu_s', 'vb' or a friction
            law's own ('vs', 'delta', 'eta'; 'k1', 'k3') (not 'mu_s' with
            Shockley diodes, whose law has no static threshold).
        start: the start value (dimensionless).
        to: the value to continue towards; the branch stays between the two.
        max_points: most points of the branch (2 to 10⁷; default 5000).
        max_step: largest step of arclength in (y, y', parameter) (default 0.1).
        progress: True for a progress bar (tqdm), a callable ``progress(done, total)``
            (points, of max_points) or a tqdm bar's ``update``.

    Returns:
        A ``Branch``: the CSV's columns as numpy arrays, ``special``, ``end`` and
        ``to_dict()`` (= ``stickslip continue --json``).

    Raises:
        ValueError: bad input, a start at rest (start from a moving state: y0, v0), no orbit
            found; with the library's message. KeyboardInterrupt: Ctrl-C.

    Example:
        >>> exp = stickslip.Experiment.paper(mu_s=1.5, w=0.9, y0=0.25, v0=2.1)
        >>> b = stickslip.continuation(exp, "beta", start=1.45, to=1.25)
        >>> [s["kind"] for s in b.special]
        ['grazing', 'fold']
        >>> bool(b.stable[0]), bool(b.stable[-1])
        (True, False)
    """
    experiment = _with_model(experiment, None)
    start = _checks.number("start", start)
    to = _checks.number("to", to)
    max_points = _checks.integer("max_points", max_points, "continuation")
    max_step = _checks.number("max_step", max_step)
    with _progress.reporter(progress, "continuation", "points") as callback:
        data = _core.continuation(experiment, over, start, to, max_points, max_step, callback)
    return Branch(experiment, over, data)


__all__: Sequence[str] = (
    "ATTRACTOR_KINDS",
    "BasinMap",
    "BifurcationDiagram",
    "Branch",
    "basins",
    "bifurcation",
    "continuation",
)
