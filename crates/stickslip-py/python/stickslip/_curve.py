"""Curves of special points in two parameters (:func:`curve`): folds, period doublings,
Neimark–Sacker points and grazings of a periodic orbit followed in two parameters."""

from __future__ import annotations

import copy
import json
from typing import TYPE_CHECKING, Any, Dict, Iterator, List, Sequence

import numpy as np

from . import _checks, _core, _progress
from ._core import Experiment
from ._common import _fixed_attributes, _physical_parameter, _with_model
from ._progress import Progress

if TYPE_CHECKING:
    import pandas
    import xarray

#: What a curve follows (``follow=``), as ``stickslip curve --follow`` takes it.
FOLLOW = ("grazing", "fold", "period-doubling", "neimark-sacker")


class Curve:
    """A curve of special points in two parameters (``stickslip.curve``): one entry per point
    in order along the curve, the columns of ``stickslip curve``'s CSV with the same names,
    the same numbers and in the same order (``columns``; the library's curve table gives
    them: ``<over>, <vary>, y, v, period, stops_per_period, turns, mu1_re, mu1_im, mu2_re,
    mu2_im, largest_multiplier, stability, arclength, special``). ``curve[name]`` is a
    column, and so is the attribute of that name (``curve.w``, ``curve.beta``,
    ``curve.largest_multiplier``). ``to_dict()`` is exactly the JSON of ``stickslip curve
    --json``. Everything is dimensionless.

    Attributes:
        follow: 'grazing', 'fold', 'period-doubling' or 'neimark-sacker'; border: for a
            grazing curve the event that appears ('turn-at-limit', 'slide-touches-rest',
            'release-tangential'), else None.
        over: the parameter the curve is followed over (Q, its first column); vary: the one
            that follows it (P, the second column).
        columns: the column names, in the CSV's order.
        orbit_period: the orbits' period in drive periods (the report's ``period``; the
            attribute ``period`` is the CSV's column).
        start: dict of the start point (index, over, vary, y, v).
        codim2: list of dicts, the codimension-two points in order along the curve (kind
            'cusp', 'fold-grazing', 'flip-grazing', '1:1-resonance', ...; over, vary, y, v,
            width (bounds their error), located, before, after).
        stability_changes: list of dicts (after_point, over, vary, from, to).
        begin, end: dicts saying why the curve ends each way (``reason`` and details);
            begin_text, end_text: the same in words.
        experiment: what was run.
    """

    def __init__(self, experiment: Experiment, data: Dict[str, Any]) -> None:
        self.experiment = experiment
        r: Dict[str, Any] = data["report"]
        self._report = r
        self._columns: Dict[str, Any] = {
            name: (np.asarray(values, dtype=str) if isinstance(values, list) else values)
            for name, values in data["columns"].items()
        }
        self.columns: List[str] = list(self._columns)
        self.follow: str = r["follow"]
        self.border = r["border"]
        self.over: str = r["over"]
        self.vary: str = r["vary"]
        self.orbit_period: int = r["period"]
        self.start: Dict[str, Any] = dict(r["start"])
        self.codim2: List[Dict[str, Any]] = copy.deepcopy(r["codim2"])
        self.stability_changes: List[Dict[str, Any]] = copy.deepcopy(r["stability_changes"])
        self.begin: Dict[str, Any] = dict(r["begin"])
        self.end: Dict[str, Any] = dict(r["end"])
        self.begin_text: str = r["begin_text"]
        self.end_text: str = r["end_text"]

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self._columns[name]
        except KeyError:
            raise KeyError(f"no column {name!r}: the columns are {', '.join(self.columns)}") \
                from None

    def __getattr__(self, name: str) -> np.ndarray:
        columns = self.__dict__.get("_columns", {})
        if name in columns:
            return columns[name]
        raise AttributeError(f"'Curve' object has no attribute {name!r}")

    def __len__(self) -> int:
        return len(self._columns[self.over])

    def __iter__(self) -> Iterator[str]:
        return iter(self.columns)

    @property
    def multipliers(self) -> np.ndarray:
        """The Floquet multipliers as a complex (points, 2) array, the larger first."""
        return np.stack([self["mu1_re"] + 1j * self["mu1_im"],
                         self["mu2_re"] + 1j * self["mu2_im"]], axis=-1)

    def to_dict(self) -> Dict[str, Any]:
        """The summary as ``stickslip curve --json`` prints it (follow, border, over, vary,
        period, points, start, codim2, stability_changes, begin, end, begin_text,
        end_text; a new dict of plain values)."""
        return copy.deepcopy(self._report)

    def to_pandas(self) -> "pandas.DataFrame":
        """A ``pandas.DataFrame``, one row per point, with the CSV's columns in its order:
        what ``pandas.read_csv`` reads from ``stickslip curve --out`` (an empty ``special``
        cell is '' here).

        Raises:
            ModuleNotFoundError: without pandas (``pip install 'stickslip[pandas]'``).
        """
        pd = _checks.optional_module("pandas", "pandas", "Curve.to_pandas()")
        return pd.DataFrame({name: self[name] for name in self.columns})

    def to_xarray(self) -> "xarray.Dataset":
        """An ``xarray.Dataset`` of the curve along the dimension ``point`` (in order along
        the curve): the two parameters (named after them) and ``arclength`` as coordinates
        (for a physical experiment ``f_Hz`` beside ``w``, ``U_V`` or ``F_N`` beside
        ``beta``), the CSV's other columns as variables, the codimension-two points along
        the dimension ``codim2`` (``codim2_kind``, ``codim2_<over>``, ``codim2_<vary>``,
        ``codim2_y``, ``codim2_v``, ``codim2_width``), and as attributes the fixed inputs,
        what the curve follows, the orbits' period, why it begins and ends (``begin``,
        ``end`` as JSON, ``begin_text``, ``end_text``) and the package version.

        Raises:
            ModuleNotFoundError: without xarray (``pip install 'stickslip[xarray]'``).
        """
        xr = _checks.optional_module("xarray", "xarray", "Curve.to_xarray()")
        names = _core.PARAMETER_LONG_NAMES
        axes = (self.over, self.vary)
        coords: Dict[str, Any] = {
            name: ("point", self[name], {"units": "1", "long_name": names[name]})
            for name in axes
        }
        coords["arclength"] = ("point", self["arclength"],
                               {"units": "1", "long_name": "arclength in (y, y', "
                                f"{self.over}, {self.vary}) from the first point"})
        scales = self.experiment.scales()
        if scales is not None:
            for name in axes:
                if name in ("w", "beta"):
                    physical, factor, units = _physical_parameter(name, scales)
                    coords[physical] = ("point", self[name] * factor, units)
        data: Dict[str, Any] = {
            name: ("point", self[name]) for name in self.columns
            if name not in axes and name != "arclength"
        }
        data["codim2_kind"] = ("codim2", np.asarray([str(c["kind"]) for c in self.codim2],
                                                    dtype=str),
                               {"long_name": "what meets at the codimension-two point"})
        for field in (self.over, self.vary, "y", "v", "width"):
            key = {self.over: "over", self.vary: "vary"}.get(field, field)
            data[f"codim2_{field}"] = ("codim2", np.asarray([c[key] for c in self.codim2],
                                                            dtype=np.float64))
        attrs: Dict[str, Any] = dict(_fixed_attributes(self.experiment, list(axes)))
        attrs["title"] = f"stickslip: a {self.follow} curve in ({self.over}, {self.vary})"
        attrs["follow"] = self.follow
        if self.border is not None:
            attrs["border"] = self.border
        attrs["orbit_period"] = int(self.orbit_period)
        attrs["begin"] = json.dumps(self.begin)
        attrs["end"] = json.dumps(self.end)
        attrs["begin_text"] = self.begin_text
        attrs["end_text"] = self.end_text
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def __repr__(self) -> str:
        codim2 = ", ".join(f"{c['kind']} at ({c['over']:.6g}, {c['vary']:.6g})"
                           for c in self.codim2) or "none"
        over = self[self.over]
        return (f"<stickslip.Curve: {self.follow} of period-{self.orbit_period} orbits in "
                f"({self.over}, {self.vary}), {len(self)} points, {self.over} from "
                f"{over[0]:.6g} to {over[-1]:.6g}; codimension-two points: {codim2}; "
                f"ends: {self.end_text}>")


def curve(experiment: Experiment, follow: str, vary: str, vary_to: float, over: str,
          start: float, to: float, *, max_points: int = 5000, max_step: float = 0.1,
          progress: Progress = None) -> Curve:
    """Follow a special point of a periodic orbit in two parameters (as ``stickslip
    curve``): the curve in (``over``, ``vary``) along which the orbit has a fold (a
    multiplier at +1), a period doubling (at −1), a Neimark–Sacker point (a complex pair on
    the unit circle) or a grazing (a stop appears or disappears).

    The start: the orbit the motion settles on at the experiment's point is continued in
    ``vary`` towards ``vary_to`` until its first special point of the followed kind; that
    point is then followed by pseudo-arclength steps on its extended system (the orbit with
    its defining condition, exact derivatives of the strobe map) over ``over`` from the
    experiment's value towards ``to``, and towards ``start`` too when the experiment's value
    lies between them. Along the curve: where the orbits' stability apart from the followed
    multiplier changes, the codimension-two points (a cusp of folds, a fold or period
    doubling meeting a grazing, 1:1 and 1:2 resonances, fold-flip), each located, and why it
    ends. The piecewise-linear diode model (PWL) with any friction law: Coulomb's (the exact
    model), which has no Neimark–Sacker point (det M < 1 on every orbit: 'neimark-sacker'
    raises ValueError saying why; see docs/bifurcation.md), or the Stribeck or cubic law on
    a belt (the stiff solver's strobe map with its sensitivities), whose folds, period
    doublings and Neimark–Sacker points are followed ('grazing' raises ValueError naming the
    law). Everything is dimensionless.

    Args:
        experiment: a ``stickslip.Experiment`` with values of both parameters (its point is
            where the search starts; its initial state picks the orbit settled on).
        follow: 'grazing', 'fold', 'period-doubling' or 'neimark-sacker'.
        vary: the parameter continued to find the start, which then follows the curve (P):
            'w', 'beta', 'zeta' or 'mu_s'; with the Stribeck or cubic law also 'vb' and the
            law's own ('vs', 'delta', 'eta'; 'k1', 'k3').
        vary_to: the value of ``vary`` the search for the start heads for.
        over: the parameter the curve is followed over (Q), another of the four.
        start: one end of the range of ``over`` (the experiment's value must lie between
            ``start`` and ``to``).
        to: the end of the range of ``over`` the curve heads for.
        max_points: most points of the curve, each way (2 to 10⁷; default 5000).
        max_step: largest step of arclength in (y, y', over, vary) (> 0, at most 10;
            default 0.1).
        progress: True for a progress bar (tqdm), a callable ``progress(done, total)``
            (points, of max_points) or a tqdm bar's ``update``.

    Returns:
        A ``Curve``: the CSV's columns as numpy arrays (``curve[name]``), ``codim2``,
        ``end``, ``to_dict()`` (= ``stickslip curve --json``), ``to_pandas()`` and
        ``to_xarray()``.

    Raises:
        ValueError: bad input (``vary`` equal to ``over``: ``invalid vary: must differ from
            over``), Shockley diodes, a Neimark–Sacker point with Coulomb's law (the model
            has none), a grazing with the Stribeck or cubic law, no special point of the kind between the experiment's point and
            ``vary_to`` (the message names the kind and the range searched); with the
            library's message. KeyboardInterrupt: Ctrl-C.

    Example:
        >>> exp = stickslip.Experiment.paper(w=1.2, beta=3.0)
        >>> g = stickslip.curve(exp, "grazing", "beta", 0.5, "w", start=1.2, to=1.3)
        >>> g.border, g.columns[:2], g.end["reason"]
        ('turn-at-limit', ['w', 'beta'], 'boundary')
        >>> bc = stickslip.boundary(exp.zeta, g.w)[1]   # the exact β_c(w)
        >>> bool(np.max(np.abs(g.beta - bc)) < 1e-8)
        True
    """
    experiment = _with_model(experiment, None)
    for name, value in (("follow", follow), ("vary", vary), ("over", over)):
        if not isinstance(value, str):
            raise TypeError(f"{name} must be a string, got {value!r}")
    vary_to = _checks.number("vary_to", vary_to)
    start = _checks.number("start", start)
    to = _checks.number("to", to)
    max_points = _checks.integer("max_points", max_points, "two-parameter")
    max_step = _checks.number("max_step", max_step)
    with _progress.reporter(progress, "curve", "points") as callback:
        data = _core.curve(experiment, follow, vary, vary_to, over, start, to, max_points,
                           max_step, callback)
    return Curve(experiment, data)


__all__: Sequence[str] = ("FOLLOW", "Curve", "curve")
