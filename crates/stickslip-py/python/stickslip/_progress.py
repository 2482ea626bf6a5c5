"""The ``progress=`` argument of every long computation: a progress bar, or a callable.

- ``progress=True`` draws a tqdm bar on standard error (``pip install 'stickslip[progress]'``),
  closed when the computation ends, however it ends.
- A callable of two arguments is called as ``progress(done, total)``: the units done so far
  (points, steps, drive periods, iterations) and how many there are.
- A callable of one argument, such as a tqdm bar's ``update``, is called with the units done
  since its last call (``bar.update(n)``); a bar made without a ``total`` gets the
  computation's.
- ``None`` or ``False``: no progress.

Every call comes from the calling thread, at most about every 50 ms and once at the end; an
exception raised by the callable stops the computation and propagates.
"""

from __future__ import annotations

import contextlib
import inspect
from typing import Any, Callable, Iterator, Optional, Union, cast

from . import _checks

#: What ``progress=`` takes: True (a tqdm bar), a callable ``progress(done, total)``, a
#: callable of one argument given the units done since its last call (a tqdm bar's
#: ``update``), or None.
Progress = Union[bool, Callable[[int, int], Any], Callable[[int], Any], None]

#: What the compiled core calls: ``callback(done, total)``.
Callback = Callable[[int, int], Any]


def _takes_one_argument(function: Callable[..., Any]) -> bool:
    """Whether ``function`` takes a single positional argument (``bar.update(n=1)``) rather
    than two (``progress(done, total)``). A callable whose signature cannot be read (some
    built-ins) is taken to take two."""
    try:
        parameters = list(inspect.signature(function).parameters.values())
    except (TypeError, ValueError):
        return False
    if any(p.kind is inspect.Parameter.VAR_POSITIONAL for p in parameters):
        return False
    positional = [p for p in parameters if p.kind in (inspect.Parameter.POSITIONAL_ONLY,
                                                      inspect.Parameter.POSITIONAL_OR_KEYWORD)]
    if not positional:
        raise TypeError(f"progress must take the units done (one argument, as a tqdm bar's "
                        f"update) or (done, total), but {function!r} takes no positional "
                        "argument")
    return len(positional) == 1


def _increments(update: Callable[[int], Any]) -> Callback:
    """``update(n)`` with the units done since the last call (what a tqdm bar's ``update``
    takes); a bar without a total is given the computation's."""
    bar = getattr(update, "__self__", None)
    reported = 0

    def callback(done: int, total: int) -> None:
        nonlocal reported
        if bar is not None and getattr(bar, "total", 0) is None:
            bar.total = total
        if done > reported:
            update(done - reported)
            reported = done

    return callback


@contextlib.contextmanager
def reporter(progress: Progress, what: str, unit: str) -> Iterator[Optional[Callback]]:
    """The callback to hand to the compiled core for ``progress`` (None: no progress), as a
    context: a bar of ``progress=True`` is closed when the context ends.

    Args:
        progress: the argument as given.
        what: the computation, for the bar's description and for messages ("phase_diagram").
        unit: what is counted ("points", "steps", "periods", "iterations").

    Raises:
        TypeError: ``progress`` is neither a bool, None nor a callable.
        ModuleNotFoundError: ``progress=True`` without tqdm, naming the extra.
    """
    if progress is None or progress is False:
        yield None
        return
    if progress is True:
        tqdm = _checks.optional_module("tqdm", "progress", f"{what}(progress=True)")
        bars: list = []

        def bar_callback(done: int, total: int) -> None:
            if not bars:
                bars.append(tqdm.tqdm(total=total, desc=what, unit=f" {unit}",
                                      dynamic_ncols=True, leave=True))
            bar = bars[0]
            if done > bar.n:
                bar.update(done - bar.n)

        try:
            yield bar_callback
        finally:
            for bar in bars:
                bar.close()
        return
    if isinstance(progress, (bool, int, float, str, bytes)) or not callable(progress):
        raise TypeError(f"progress must be True (a progress bar), a callable progress(done, "
                        f"total), a tqdm bar's update, or None; got {progress!r}")
    if _takes_one_argument(progress):
        yield _increments(cast(Callable[[int], Any], progress))
    else:
        yield cast(Callback, progress)
