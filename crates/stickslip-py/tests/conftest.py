"""Shared fixtures: the command-line tool of the same workspace, run on the same inputs as the
package, is the reference for every function."""

from __future__ import annotations

import csv
import inspect
import json
import os
import pathlib
import signal
import subprocess
import sys
import threading
import time
from typing import Any, Callable, Dict, List, Optional

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]
TARGET = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")).resolve()
CLI = pathlib.Path(os.environ.get("STICKSLIP_CLI", TARGET / "release" / "stickslip"))


# The Ctrl-C tests interrupt this process (and the scripts it starts) as a terminal would. A
# test run started in the background of a shell begins with SIGINT ignored, and Python then
# leaves it ignored: give it Python's own handler, as an interactive session has it.
if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)


class Cli:
    """The ``stickslip`` binary built from this workspace."""

    def __init__(self, path: pathlib.Path) -> None:
        self.path = path

    def run(self, *args: object) -> str:
        """Standard output of ``stickslip ARGS``; a failure shows its standard error."""
        done = subprocess.run([str(self.path), *map(str, args)], capture_output=True, text=True)
        if done.returncode != 0:
            raise AssertionError(f"stickslip {' '.join(map(str, args))} failed: {done.stderr}")
        return done.stdout

    def json(self, *args: object):
        return json.loads(self.run(*args, "--json"))

    def error(self, *args: object) -> str:
        """The one-line error of a command that must fail."""
        done = subprocess.run([str(self.path), *map(str, args)], capture_output=True, text=True)
        assert done.returncode != 0, f"stickslip {args} succeeded"
        lines = [l for l in done.stderr.splitlines() if l.startswith("error: ")]
        assert len(lines) == 1, done.stderr
        return lines[0][len("error: "):]


@pytest.fixture(scope="session")
def cli() -> Cli:
    if not CLI.is_file():
        pytest.fail(
            f"the stickslip binary is missing at {CLI}: the Python tests compare with it; "
            "build it with `cargo build --release -p stickslip-cli` (scripts/test does)"
        )
    return Cli(CLI)


def read_csv(path: pathlib.Path) -> Dict[str, List[str]]:
    """A CSV file as columns of text."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    return {name: [row[k] for row in body] for k, name in enumerate(header)}


def numbers(column: List[str]) -> np.ndarray:
    """A CSV column as floats; an empty cell is NaN (a value that does not exist)."""
    return np.array([float(x) if x != "" else np.nan for x in column])


def assert_same(actual, expected, what: str = "") -> None:
    """The same numbers: the package and the tool run the same library code, so they agree
    exactly; the issue asks for 1e-12, and this checks that, then bit-identity."""
    actual = np.asarray(actual, dtype=np.float64)
    expected = np.asarray(expected, dtype=np.float64)
    assert actual.shape == expected.shape, f"{what}: shape {actual.shape} != {expected.shape}"
    np.testing.assert_allclose(actual, expected, rtol=1e-12, atol=1e-12, err_msg=what)
    np.testing.assert_array_equal(actual, expected, err_msg=what)



class Interrupt:
    """SIGINT (Ctrl-C) to this process after ``seconds``, sent from a timer thread, with the
    process's CPU time (all its threads, ``time.process_time``) at the moment it is sent."""

    def __init__(self, seconds: float) -> None:
        self.cpu_at_signal: Optional[float] = None
        self.timer = threading.Timer(seconds, self._send)
        self.timer.start()

    def _send(self) -> None:
        self.cpu_at_signal = time.process_time()
        os.kill(os.getpid(), signal.SIGINT)

    def cancel(self) -> None:
        self.timer.cancel()

    def cpu_since_signal(self) -> float:
        """The CPU time this process has spent since the signal: the work done after it, which
        a loaded machine does not stretch (it stretches the wall time)."""
        assert self.cpu_at_signal is not None, "the signal was not sent"
        return time.process_time() - self.cpu_at_signal


def interrupt_after(seconds: float) -> Interrupt:
    """Send SIGINT (Ctrl-C) to this process after ``seconds`` (see ``Interrupt``)."""
    return Interrupt(seconds)


def assert_runs_beside(function: Callable[..., Any], *args: Any, **kwargs: Any) -> Any:
    """While ``function(*args, progress=..., **kwargs)`` computes in another thread, this
    thread runs Python code: polling, it finds that thread inside ``function``'s call into the
    library (its innermost frame ``function``'s own, not a progress callback) between the
    first and the last progress call, with no progress call while it looks. A library that
    kept the GIL while it computes would let this thread run only in the progress callbacks or
    before and after the call. The order of events is read, not the clock: this thread polls
    until it has seen that or the computation has ended, however slowly a loaded machine runs
    either (up to five computations). Returns the computation's result."""
    code = inspect.unwrap(function).__code__
    for _ in range(5):
        last = [(0, 0, None)]  # (progress calls, done, total) at the latest call
        result = {}

        def progress(done, total):
            last[0] = (last[0][0] + 1, done, total)

        def work():
            result["value"] = function(*args, progress=progress, **kwargs)

        worker = threading.Thread(target=work)
        worker.start()
        seen = False
        while not seen and worker.is_alive():
            before = last[0]
            frame = sys._current_frames().get(worker.ident)
            after = last[0]
            _, done, total = after
            seen = (before == after and frame is not None and frame.f_code is code
                    and total is not None and 0 < done < total)
            time.sleep(0.0005)
        worker.join()
        assert "value" in result, f"{function.__name__} ended without a result"
        calls, done, total = last[0]
        assert done == total, f"the last progress call reported {done} of {total}"
        if seen:
            return result["value"]
    pytest.fail(f"in five runs of {function.__name__} this thread never ran while the other "
                f"was inside the library between two progress calls (the last run made {calls} "
                "progress calls: a run of a few polls, 50 ms each, would show too little)")
