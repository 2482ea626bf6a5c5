"""The checks every function applies to its arguments before any work, so that a bad
argument raises ``TypeError`` or ``ValueError`` naming the parameter and what it allows.

Integer arguments (counts of periods, points, steps, threads) accept integers only: a
Python ``int`` or a numpy integer (anything with ``__index__``, as ``range()`` and numpy's
shapes take), never a float, not even an integral one such as ``100.0`` or ``1e4``, and
never a ``bool``. The types are checked here; the ranges are the library's option table
(``_core.OPTIONS``), checked by the library with its words, before any work.
"""

from __future__ import annotations

import importlib
import operator
from types import ModuleType
from typing import Any, Dict, Iterable, Optional, Tuple

import numpy as np

from . import _core


def integer(name: str, value: Any, computation: Optional[str] = None) -> int:
    """``value`` as an ``int``; with ``computation`` (the option's group in the library's
    option table: 'simulate', 'steady', 'orbit', 'bifurcation', 'basins', 'continuation',
    'pool', ...), checked against the table's range for the option ``name``.

    Raises:
        TypeError: not an integer (a float, even an integral one, a bool, a string...).
        ValueError: out of range, with the library's message naming ``name``.
    """
    if isinstance(value, (bool, np.bool_)) or not hasattr(type(value), "__index__"):
        hint = ""
        if isinstance(value, (float, np.floating)) and float(value).is_integer():
            hint = f" (write {int(value)}: counts are integers, not floats)"
        raise TypeError(f"{name} must be an integer, got {value!r}{hint}")
    v = operator.index(value)
    if computation is not None:
        _core.check_option(computation, name, v)
    return v


def number(name: str, value: Any) -> float:
    """``value`` as a float (any real number; the library checks its range).

    Raises:
        TypeError: not a real number (a string, None, a bool, a complex number...).
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(
            value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a number, got {value!r}")
    return float(value)


def flag(name: str, value: Any) -> bool:
    """``value`` as a bool (True or False, or a numpy bool)."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False, got {value!r}")
    return bool(value)


def pair(name: str, value: Any) -> Tuple[float, float]:
    """``value`` as a (smallest, largest) pair of numbers."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) != 2:
        raise TypeError(f"{name} must be a (smallest, largest) pair of numbers, e.g. "
                        f"{name}=(-8, 8), got {value!r}")
    low, high = (number(f"{name}[{k}]", value[k]) for k in (0, 1))
    return low, high


def threads(value: Any) -> Optional[int]:
    """A pool's number of threads (None: one per core)."""
    return None if value is None else integer("threads", value, "pool")


def array(name: str, values: Any) -> np.ndarray:
    """``values`` (a number or an array of any shape) as float64."""
    if isinstance(values, (str, bytes)):
        raise TypeError(f"{name} must be numbers (an array of floats), got {values!r}")
    try:
        a = np.asarray(values)
        if a.dtype.kind not in "iuf":
            raise TypeError
        return np.asarray(a, dtype=np.float64)
    except (TypeError, ValueError):
        shown = repr(values)
        shown = shown if len(shown) <= 60 else shown[:57] + "..."
        raise TypeError(f"{name} must be numbers (an array of floats), got {shown}") from None


def values(name: str, values: Any) -> np.ndarray:
    """``values`` as a one-dimensional, C-contiguous, aligned float64 array (what the compiled
    core reads without a copy). Arrays that arrive misaligned (numpy arrays unpickled from
    pickle-5 buffers on Dask workers, or views into packed records) are copied aligned."""
    a = array(name, values)
    if a.ndim == 0:
        a = a.reshape(1)
    if a.ndim != 1:
        raise ValueError(f"{name} must be a one-dimensional array of values, got shape {a.shape}")
    if a.size == 0:
        raise ValueError(f"{name} must hold at least one value")
    return np.require(a, np.float64, ["C", "A"])


def option_names(spectrum: bool) -> Tuple[str, ...]:
    """The names of the steady-state options (with those of the spectrum), from the library's
    option table."""
    return tuple(_core.steady_option_kinds(spectrum))


def steady_options(options: Dict[str, Any], spectrum: bool, caller: str) -> Dict[str, Any]:
    """The options of the steady-state search, checked: known names, integers where counts,
    in the library's range (the library checks what depends on the experiment)."""
    known = _core.steady_option_kinds(spectrum)
    checked: Dict[str, Any] = {}
    for name, value in options.items():
        if name not in known:
            raise TypeError(f"{caller}() got an unknown option {name!r}: the options are "
                            f"{', '.join(known)}")
        if value is None:
            checked[name] = None
            continue
        kind = known[name]
        if kind == "count":
            checked[name] = integer(name, value, "steady")
        elif kind == "switch":
            checked[name] = flag(name, value)
        else:
            checked[name] = number(name, value)
    return checked


def unknown_keyword(caller: str, name: str, groups: Iterable[Tuple[str, Iterable[str]]]) -> None:
    """Raise the ``TypeError`` of an unknown keyword, listing what is known."""
    known = "; ".join(f"{what}: {', '.join(names)}" for what, names in groups)
    raise TypeError(f"{caller}() got an unknown keyword {name!r} ({known})")


def optional_module(module: str, extra: str, what: str) -> ModuleType:
    """Import an optional dependency, or say which extra installs it."""
    try:
        return importlib.import_module(module)
    except ModuleNotFoundError as e:
        if e.name != module:
            raise
        raise ModuleNotFoundError(
            f"{what} needs {module}, which is not installed: pip install 'stickslip[{extra}]' "
            f"(or pip install {module})", name=module) from None
