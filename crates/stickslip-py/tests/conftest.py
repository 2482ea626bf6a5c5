"""Shared fixtures: the command-line tool of the same workspace, run on the same inputs as the
package, is the reference for every function."""

from __future__ import annotations

import csv
import json
import os
import pathlib
import signal
import subprocess
from typing import Dict, List

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
