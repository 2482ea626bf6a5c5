"""The hand-written stubs match the compiled core (mypy's stubtest), and the package
type-checks against them (mypy), so that the stubs cannot drift from the code."""

from __future__ import annotations

import subprocess
import sys

import pytest

from conftest import TARGET

pytest.importorskip("mypy", reason="the typing tests need mypy (a test extra)")


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", *args], capture_output=True, text=True)


def test_stubs_match_the_compiled_core():
    done = run("mypy.stubtest", "stickslip._core")
    assert done.returncode == 0, done.stdout + done.stderr


def test_the_package_type_checks():
    # xarray and distributed are optional; their own types are not checked here.
    done = run("mypy", "-p", "stickslip", "--ignore-missing-imports",
               "--cache-dir", str(TARGET / "mypy-cache"))
    assert done.returncode == 0, done.stdout + done.stderr
