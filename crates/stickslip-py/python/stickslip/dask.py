"""Stick-slip maps as Dask tasks, on a laptop or on a cluster.

``phase_diagram`` computes the same map as ``stickslip.phase_diagram`` and ``sweep_grid`` a
stack of maps (one for each value of one or more outer parameters), split into rectangular
blocks of grid points, one Dask task per block. Each task rebuilds the experiment from its
JSON, computes its block with the library's ``Grid::run_block`` on one thread, and returns
small numpy arrays; the blocks are put together on the client. Every point is computed on its
own, the same way whichever worker runs it, so the result is bit-identical to the local call.

- **Cluster**: whatever ``client`` points at (``distributed.Client("tcp://host:8786")``), or,
  with ``client=None``, Dask's current default: a ``distributed.Client`` if one was created,
  else the local threaded scheduler.
- **No oversubscription**: a task uses one thread (``threads=1``), so a worker computes as many
  blocks at once as it has threads: start workers with ``--nthreads`` equal to their cores
  (``dask worker ... --nthreads 8``), or one single-threaded worker process per core.
- **Task size**: ``chunks="auto"`` (the default) times a few points of the grid on the client
  (one thread) and sizes blocks to take about ``TASK_SECONDS`` (one second) each, and smaller
  when that would leave fewer than four tasks per worker thread; or give
  ``chunks=(rows, columns)`` per block, or an int (rows per block, all columns).
- **Exponents**: ``lyapunov=True`` maps the largest Lyapunov exponent of every point too (the
  maps that take minutes), bit-identical to ``stickslip.phase_diagram(..., lyapunov=True)``.
- **Progress**: ``progress=`` as for ``stickslip.phase_diagram`` (``True`` for a bar), counted
  in points as blocks finish.
- **Ctrl-C** raises one ``KeyboardInterrupt`` in the calling thread and prints nothing else:
  workers that share the terminal (a ``LocalCluster``'s processes, which receive its Ctrl-C
  too) ignore it while the map runs, and the calling thread cancels the tasks.

Needs ``dask[distributed]`` (``pip install "stickslip[dask]"``).

Example::

    import numpy as np
    from distributed import Client
    import stickslip, stickslip.dask

    client = Client("tcp://127.0.0.1:8786")            # or Client(n_workers=2, threads_per_worker=1)
    m = stickslip.dask.phase_diagram(stickslip.Experiment.paper(), client=client,
                                     w=np.linspace(0.1, 2.5, 1000), beta=np.linspace(0.5, 4, 1000))
    stack = stickslip.dask.sweep_grid(stickslip.Experiment.paper(), client=client,
                                      mu_s=[1.0, 1.2, 1.5], w=np.linspace(0.1, 2.5, 200),
                                      beta=np.linspace(0.5, 4, 200))
    stack.to_xarray()                                 # dims (mu_s, w, beta)
"""

from __future__ import annotations

import contextlib
import itertools
import os
import signal
import sys
import threading
import time
from typing import (Any, Callable, Dict, List, Literal, Optional, Sequence, Set, Tuple, Union,
                    overload)

import numpy as np

from . import _checks, _core, _progress
from ._api import _axes
from ._common import _with_model
from ._tables import PhaseDiagram
from ._core import Experiment
from ._progress import Progress

__all__ = ["phase_diagram", "sweep_grid", "TASK_SECONDS"]

#: How long a task of ``chunks="auto"`` should take, in seconds (as timed on the client).
TASK_SECONDS = 1.0

_DTYPES = {
    "motion": np.int8,
    "period": np.int16,
    "stops_per_cycle": np.float64,
    "gain": np.float64,
    "symmetric": np.bool_,
    "periods_to_settle": np.int64,
}
#: The arrays of a map of exponents, beside those above.
_EXPONENT_DTYPES = {"lyapunov": np.float64, "lyapunov_error": np.float64}

Chunks = Union[str, int, Tuple[int, int]]


def _fields(lyapunov: bool) -> Dict[str, Any]:
    """The arrays of a map, with their dtypes."""
    return {**_DTYPES, **(_EXPONENT_DTYPES if lyapunov else {})}


def _block_task(experiment_json: str, first: str, first_values: np.ndarray, second: str,
                second_values: np.ndarray, block: Tuple[int, int, int, int],
                options: Dict[str, Any], fixed: List[Tuple[str, float]],
                lyapunov: bool = False) -> Dict[str, np.ndarray]:
    """One Dask task: the block (row start, row end, column start, column end) of the grid,
    on one thread."""
    experiment = Experiment.from_json(experiment_json)
    # Arrays unpickled from pickle-5 buffers may be misaligned; the core reads aligned ones.
    first_values = np.require(first_values, np.float64, ["C", "A"])
    second_values = np.require(second_values, np.float64, ["C", "A"])
    data = _core.grid(experiment, first, first_values, second, second_values, options, 1,
                      block, fixed, None, lyapunov)
    return {name: data[name] for name in _fields(lyapunov)}


def _block_shape(chunks: Chunks, experiment: Experiment, first: str, v1: np.ndarray,
                 second: str, v2: np.ndarray, options: Dict[str, Any],
                 fixed: List[Tuple[str, float]], outer: int, threads: int,
                 lyapunov: bool) -> Tuple[int, int]:
    """Rows and columns per block; checks every input once on the client."""
    n1, n2 = len(v1), len(v2)
    # Builds the grid (checking the experiment, both axes and the options) and computes
    # nothing: bad input fails here, with the library's message, before any task runs.
    _core.grid(experiment, first, v1, second, v2, options, 1, (0, 0, 0, 0), fixed, None,
               lyapunov)
    if isinstance(chunks, str):
        if chunks != "auto":
            raise ValueError(f"invalid chunks {chunks!r}: 'auto', rows per block, or (rows, columns)")
        rows = np.unique(np.linspace(0, n1 - 1, min(n1, 4)).round().astype(int))
        cols = np.unique(np.linspace(0, n2 - 1, min(n2, 4)).round().astype(int))
        started = time.perf_counter()
        _core.grid(experiment, first, np.ascontiguousarray(v1[rows]), second,
                   np.ascontiguousarray(v2[cols]), options, 1, None, fixed, None, lyapunov)
        per_point = max((time.perf_counter() - started) / (len(rows) * len(cols)), 1e-7)
        # About TASK_SECONDS each, and at least four tasks per worker thread (so that the last
        # tasks, which finish at different times, are a small part of the whole).
        points = max(1, min(int(TASK_SECONDS / per_point),
                            (outer * n1 * n2) // (4 * max(threads, 1))))
        if points >= n2:
            return min(n1, points // n2), n2
        return 1, points
    if isinstance(chunks, (int, np.integer)) and not isinstance(chunks, bool):
        shape = (int(chunks), n2)
    elif isinstance(chunks, tuple) and len(chunks) == 2:
        for k in chunks:
            if isinstance(k, bool) or not isinstance(k, (int, np.integer)):
                raise TypeError(f"chunks must be 'auto', an integer or a (rows, columns) tuple "
                                f"of integers, not {chunks!r}")
        shape = (int(chunks[0]), int(chunks[1]))
    else:
        raise TypeError(f"chunks must be 'auto', an integer or a (rows, columns) tuple of "
                        f"integers, not {chunks!r}")
    if min(shape) < 1:
        raise ValueError(f"invalid chunks {chunks!r}: a block has at least one row and one column")
    return min(shape[0], n1), min(shape[1], n2)


def _default_client() -> Any:
    """Dask's default ``distributed.Client``, or None (Dask's local threads compute)."""
    if "distributed" not in sys.modules:
        return None  # no client can have been made (and importing it takes a second)
    try:
        from distributed import default_client

        return default_client()
    except (ImportError, ValueError):
        return None


def _worker_threads(client: Any) -> int:
    """Threads of the cluster that will compute: the client's workers, else this machine's
    cores (Dask's local threads)."""
    if client is None:
        return os.cpu_count() or 1
    return sum(client.nthreads().values()) or 1


class _CtrlC:
    """Ctrl-C while a map is sent to a cluster, taken where the map can act on it.

    Python raises ``KeyboardInterrupt`` wherever the main thread is when the signal comes; in
    the client that can be inside Dask's own code, such as the garbage collector's callback
    that ``distributed`` installs, where the exception is printed as "ignored" and lost (the
    map then runs on). While this context is entered (from the main thread, with Python's
    default handler in place), a Ctrl-C only marks itself, and :meth:`check` raises it at the
    map's own points: between blocks of the graph's construction and in the wait for the
    results. A second Ctrl-C raises at once (it ends the wait for the cancelled tasks)."""

    def __init__(self) -> None:
        self.pending = False
        self.previous: Any = None

    def __enter__(self) -> "_CtrlC":
        if (threading.current_thread() is threading.main_thread()
                and signal.getsignal(signal.SIGINT) is signal.default_int_handler):
            self.previous = signal.signal(signal.SIGINT, self._handle)
        return self

    def _handle(self, signum: int, frame: Any) -> None:
        if self.pending:
            raise KeyboardInterrupt
        self.pending = True

    def check(self) -> None:
        """Raise the Ctrl-C that came since the context was entered, if one did."""
        if self.pending:
            raise KeyboardInterrupt

    def __exit__(self, kind: Any, value: Any, traceback: Any) -> None:
        if self.previous is not None:
            signal.signal(signal.SIGINT, self.previous)
            self.previous = None
        if kind is None:
            self.check()


#: How often the calling thread looks whether the tasks are done (and lets Ctrl-C in).
_POLL_SECONDS = 0.05


def _gather(client: Any, futures: List[Any], points: List[int],
            callback: Optional[Callable[[int, int], Any]],
            ctrl_c: Optional[_CtrlC] = None) -> List[Any]:
    """The futures' results. The calling thread waits in ``time.sleep``, which Ctrl-C
    interrupts cleanly: the tasks are then cancelled and the one ``KeyboardInterrupt``
    propagates. (Waiting inside ``client.gather`` instead, the interrupted gather leaves one
    asyncio task per future whose ``AllExit`` exception is never retrieved, and asyncio
    prints a traceback for each.) ``callback(done, total)`` is told the points of the
    finished blocks (``points``: each future's) as they finish."""
    total = sum(points)
    reported = 0
    try:
        pending = list(range(len(futures)))
        while pending:
            pending = [k for k in pending if not futures[k].done()]
            done = total - sum(points[k] for k in pending)
            if callback is not None and done > reported:
                reported = done
                callback(done, total)
            if ctrl_c is not None:
                ctrl_c.check()
            if pending:
                time.sleep(_POLL_SECONDS)
        results: List[Any] = client.gather(futures)
        return results
    except BaseException:
        keys = {f.key for f in futures}
        # A Ctrl-C soon after the submission can come while the scheduler is still taking
        # the graph in: a cancel sent then finds no task to cancel (they would run after
        # all), and a cluster closed then logs the interrupted submission as an error.
        _wait_for_graph(client, keys)
        client.cancel(futures)
        _wait_for_running(client, keys)
        raise


def _known_keys(keys: Set[Any], dask_scheduler: Any = None) -> bool:
    """Whether the scheduler holds a task for each of ``keys`` (``client.run_on_scheduler``
    calls it)."""
    return all(key in dask_scheduler.tasks for key in keys)


def _wait_for_graph(client: Any, keys: Set[Any], timeout: float = 60.0) -> None:
    """Wait until the scheduler has taken in the tasks of ``keys``. A second Ctrl-C, or a
    scheduler that does not answer, ends the wait early."""
    deadline = time.monotonic() + timeout
    try:
        while time.monotonic() < deadline:
            if client.run_on_scheduler(_known_keys, keys):
                return
            time.sleep(_POLL_SECONDS)
    except BaseException:  # noqa: BLE001 - the first interrupt is the one that propagates
        return


def _executing_keys(dask_worker: Any) -> List[Any]:
    """The keys of the tasks a worker is running (``client.run`` calls it on each)."""
    return [ts.key for ts in dask_worker.state.executing]


def _wait_for_running(client: Any, keys: Set[Any], timeout: float = 60.0) -> None:
    """Wait until no task of ``keys`` runs on a worker any more (a block cannot be stopped
    half-way on a worker; it takes about ``TASK_SECONDS`` with ``chunks="auto"``), so that
    the workers are idle when the caller goes on, and a cluster closed right after (a
    ``with LocalCluster()`` block left by the ``KeyboardInterrupt``) closes no worker in the
    middle of a task, which the worker would report on stderr. A second Ctrl-C, or a worker
    that does not answer, ends the wait early."""
    deadline = time.monotonic() + timeout
    try:
        while time.monotonic() < deadline:
            running = client.run(_executing_keys)
            if not any(key in keys for worker in running.values() for key in worker):
                return
            time.sleep(_POLL_SECONDS)
    except BaseException:  # noqa: BLE001 - the first interrupt is the one that propagates
        return


def _terminal_job() -> Tuple[str, int, int]:
    """This process's machine (its boot id), session and process group: the processes a
    terminal's Ctrl-C reaches share all three."""
    try:
        with open("/proc/sys/kernel/random/boot_id") as f:
            machine = f.read().strip()
    except OSError:
        import socket

        machine = socket.gethostname()
    return machine, os.getsid(0), os.getpgrp()


def _shield_worker(job: Tuple[str, int, int], client_pid: int, shield: bool) -> bool:
    """On a worker (``client.run``): while ``shield``, ignore SIGINT if this worker is a
    process of the client's terminal job other than the client (a ``LocalCluster``'s worker
    processes, which the terminal's Ctrl-C reaches too, and whose tracebacks and warnings
    would follow ours); afterwards restore what was there. A worker elsewhere (``dask
    worker`` started by hand, another machine) is left alone. Whether it was shielded."""
    state = sys.modules[__name__].__dict__.setdefault("_SHIELDED", [])
    if shield:
        if (os.getpid() == client_pid or _terminal_job() != job
                or threading.current_thread() is not threading.main_thread()):
            return False
        state.append(signal.signal(signal.SIGINT, signal.SIG_IGN))
        return True
    if state and threading.current_thread() is threading.main_thread():
        previous = state.pop()
        if previous is not None:
            signal.signal(signal.SIGINT, previous)
        return True
    return False


def _shield(client: Any, shield: bool) -> None:
    """Shield the client's workers in this terminal job from its Ctrl-C (or stop)."""
    if client is None:
        return
    try:
        client.run(_shield_worker, _terminal_job(), os.getpid(), shield)
    except Exception:  # noqa: BLE001 - a worker that cannot say is left as it is
        pass


def _local_compute(tasks: List[Any], points: List[int],
                   callback: Optional[Callable[[int, int], Any]]) -> List[Any]:
    """The tasks on Dask's local threads, ``callback(done, total)`` told the points of the
    blocks as they finish (Dask's scheduler calls ``posttask`` from the calling thread)."""
    import dask
    from dask.callbacks import Callback

    if callback is None:
        return list(dask.compute(*tasks))
    sizes = {task.key: n for task, n in zip(tasks, points)}
    total = sum(points)
    done = [0]

    def posttask(key: Any, result: Any, dsk: Any, state: Any, worker_id: Any) -> None:
        if key in sizes:
            done[0] += sizes[key]
            callback(done[0], total)

    with Callback(posttask=posttask):
        return list(dask.compute(*tasks))


def _stack(experiment: Experiment, outer: Dict[str, np.ndarray], grid: Dict[str, np.ndarray],
           options: Dict[str, Any], chunks: Chunks, client: Any, lyapunov: bool,
           progress: Progress, what: str) -> PhaseDiagram:
    import dask

    (first, v1), (second, v2) = grid.items()
    n1, n2 = len(v1), len(v2)
    outer_names = list(outer)
    outer_shape = tuple(len(v) for v in outer.values())
    combinations = list(itertools.product(*(range(n) for n in outer_shape)))

    def fixed_at(index: Sequence[int]) -> List[Tuple[str, float]]:
        return [(name, float(outer[name][k])) for name, k in zip(outer_names, index)]

    if client is None:
        client = _default_client()
    # From here on, a Ctrl-C of the terminal is the client's alone (the graph of a large map
    # takes seconds to build: it may come then too), and taken at the map's own points.
    ctrl_c = _CtrlC() if client is not None else None
    with ctrl_c if ctrl_c is not None else contextlib.nullcontext():
        _shield(client, True)
        try:
            middle = combinations[len(combinations) // 2]
            rows, cols = _block_shape(chunks, experiment, first, v1, second, v2, options,
                                      fixed_at(middle), len(combinations), _worker_threads(client),
                                      lyapunov)
            for index in combinations:
                if index != middle:
                    # Checks each outer value (the grid is built, nothing is computed).
                    _core.grid(experiment, first, v1, second, v2, options, 1, (0, 0, 0, 0),
                               fixed_at(index), None, lyapunov)

            text = dask.delayed(experiment.to_json(), pure=True)
            first_values = dask.delayed(v1, pure=True)
            second_values = dask.delayed(v2, pure=True)
            task = dask.delayed(_block_task, pure=True)
            blocks = []
            tasks = []
            for index in combinations:
                for r0 in range(0, n1, rows):
                    for c0 in range(0, n2, cols):
                        if ctrl_c is not None:
                            ctrl_c.check()
                        block = (r0, min(r0 + rows, n1), c0, min(c0 + cols, n2))
                        blocks.append((index, block))
                        tasks.append(task(text, first, first_values, second, second_values, block,
                                          options, fixed_at(index), lyapunov))
            points = [(r1 - r0) * (c1 - c0) for _, (r0, r1, c0, c1) in blocks]
            with _progress.reporter(progress, what, "points") as callback:
                if client is None:
                    results = _local_compute(tasks, points, callback)
                else:
                    results = _gather(client, client.compute(tasks), points, callback,
                                      ctrl_c)
        finally:
            _shield(client, False)

    shape = outer_shape + (n1, n2)
    arrays: Dict[str, np.ndarray] = {
        name: np.empty(shape, dtype=dtype) for name, dtype in _fields(lyapunov).items()
    }
    for (index, (r0, r1, c0, c1)), result in zip(blocks, results):
        for name, array in arrays.items():
            array[index + (slice(r0, r1), slice(c0, c1))] = result[name].reshape(r1 - r0, c1 - c0)
    coords = dict(outer)
    coords.update(grid)
    return PhaseDiagram(experiment, outer_names + [first, second], coords, options, arrays)


@overload
def phase_diagram(experiment: Experiment, *, chunks: Chunks = ..., client: Any = ...,
                  model: Optional[str] = ..., progress: Progress = ...,
                  lyapunov: Literal[False] = ...,
                  **axes_and_options: Any) -> PhaseDiagram[None]: ...


@overload
def phase_diagram(experiment: Experiment, *, chunks: Chunks = ..., client: Any = ...,
                  model: Optional[str] = ..., progress: Progress = ...,
                  lyapunov: Literal[True], **axes_and_options: Any
                  ) -> PhaseDiagram[np.ndarray]: ...


@overload
def phase_diagram(experiment: Experiment, *, chunks: Chunks = ..., client: Any = ...,
                  model: Optional[str] = ..., progress: Progress = ..., lyapunov: bool = ...,
                  **axes_and_options: Any
                  ) -> PhaseDiagram[Optional[np.ndarray]]: ...


def phase_diagram(experiment: Experiment, *, chunks: Chunks = "auto", client: Any = None,
                  model: Optional[str] = None, progress: Progress = None,
                  lyapunov: bool = False, **axes_and_options: Any) -> PhaseDiagram[Any]:
    """``stickslip.phase_diagram`` computed as Dask tasks, bit-identical to it.

    Args:
        experiment: a ``stickslip.Experiment``; it needs no value of either parameter.
        chunks: 'auto' (blocks of about one second each, timed on the client), rows per
            block (all columns), or (rows, columns) per block.
        client: a ``distributed.Client``; None: Dask's default scheduler (a client created
            earlier, or local threads).
        model: 'pwl' or 'shockley' to use that diode law instead of the experiment's own.
        progress: True for a progress bar (tqdm), a callable ``progress(done, total)``
            (points of the blocks finished) or a tqdm bar's ``update``; called from the
            calling thread.
        lyapunov: also the largest Lyapunov exponent of every point (either law):
            arrays ``lyapunov`` and ``lyapunov_error`` per unit τ, as
            ``stickslip.phase_diagram(..., lyapunov=True)``.
        **axes_and_options: two parameter arrays (any two of zeta, w, beta, mu_s; the first
            keyword is the first axis), then options as for ``stickslip.steady`` (tolerance,
            max_periods, max_period, min_stop_fraction, accelerate, lyapunov_periods).

    Returns:
        A ``stickslip.PhaseDiagram`` of shape (len(first), len(second)): ``motion_class``
        (labels of ``MOTION_CLASSES``; 'static' is the paper's rule, an amplitude below β/100
        whether or not the motion stops) with ``stops_per_period`` beside it.

    Raises:
        ValueError: bad input (checked on the client before any task), a map of more than
            10⁸ points. TypeError: an unknown keyword (named) or an argument of the wrong
            type. KeyboardInterrupt: Ctrl-C cancels the tasks and raises once, with nothing
            else on stderr.

    Example:
        >>> import numpy as np, stickslip, stickslip.dask
        >>> m = stickslip.dask.phase_diagram(stickslip.Experiment.paper(), chunks=(10, 40),
        ...                                  w=np.linspace(0.1, 2.5, 60), beta=np.linspace(0.5, 4, 40))
        >>> m.motion_class.shape
        (60, 40)
    """
    experiment = _with_model(experiment, model)
    axes, options = _axes(axes_and_options, (2,), "stickslip.dask.phase_diagram")
    return _stack(experiment, {}, axes, options, chunks, client,
                  _checks.flag("lyapunov", lyapunov), progress, "phase_diagram")


@overload
def sweep_grid(experiment: Experiment, *, chunks: Chunks = ..., client: Any = ...,
               model: Optional[str] = ..., progress: Progress = ...,
               lyapunov: Literal[False] = ...,
               **axes_and_options: Any) -> PhaseDiagram[None]: ...


@overload
def sweep_grid(experiment: Experiment, *, chunks: Chunks = ..., client: Any = ...,
               model: Optional[str] = ..., progress: Progress = ...,
               lyapunov: Literal[True], **axes_and_options: Any
               ) -> PhaseDiagram[np.ndarray]: ...


@overload
def sweep_grid(experiment: Experiment, *, chunks: Chunks = ..., client: Any = ...,
               model: Optional[str] = ..., progress: Progress = ..., lyapunov: bool = ...,
               **axes_and_options: Any) -> PhaseDiagram[Optional[np.ndarray]]: ...


def sweep_grid(experiment: Experiment, *, chunks: Chunks = "auto", client: Any = None,
               model: Optional[str] = None, progress: Progress = None,
               lyapunov: bool = False, **axes_and_options: Any) -> PhaseDiagram[Any]:
    """A map of the last two parameters for each value of the others, as Dask tasks: for
    example a (w, β) map for each of 50 values of μs (three keyword arrays), or for each of 50
    values of μs and 20 of ζ (four). Each map equals ``stickslip.phase_diagram`` of the
    experiment with the outer values set.

    Args:
        experiment: a ``stickslip.Experiment``; it needs no value of the varied parameters.
        chunks, client, model, progress, lyapunov: as for ``phase_diagram``.
        **axes_and_options: three or four parameter arrays (of zeta, w, beta, mu_s) in the
            order of the result's dimensions, outer ones first, then options as for
            ``stickslip.steady``.

    Returns:
        A ``stickslip.PhaseDiagram`` whose arrays have one dimension per parameter, e.g.
        (len(mu_s), len(w), len(beta)); ``to_xarray()`` names them. ``motion_class``: labels
        of ``MOTION_CLASSES`` ('static' is the paper's rule, an amplitude below β/100 whether
        or not the motion stops), with ``stops_per_period`` beside it.

    Example:
        >>> s = stickslip.dask.sweep_grid(stickslip.Experiment.paper(), mu_s=[1.0, 1.5],
        ...                               w=np.linspace(0.1, 2.5, 30), beta=np.linspace(0.5, 4, 20))
        >>> s.dims, s.motion_class.shape
        (('mu_s', 'w', 'beta'), (2, 30, 20))
    """
    experiment = _with_model(experiment, model)
    axes, options = _axes(axes_and_options, (3, 4), "stickslip.dask.sweep_grid")
    names = list(axes)
    outer = {name: axes[name] for name in names[:-2]}
    grid = {name: axes[name] for name in names[-2:]}
    return _stack(experiment, outer, grid, options, chunks, client,
                  _checks.flag("lyapunov", lyapunov), progress, "sweep_grid")
