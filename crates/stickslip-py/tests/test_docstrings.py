"""The examples in the docstrings run and print what they say."""

from __future__ import annotations

import doctest

import numpy as np
import pytest

import stickslip
import stickslip._api
import stickslip._curve
import stickslip._stability
import stickslip._tables
import stickslip._trajectory
import stickslip._dynamics
import stickslip.dask
from stickslip import Experiment


def _examples(obj, name):
    finder = doctest.DocTestFinder(exclude_empty=True)
    globs = {"stickslip": stickslip, "Experiment": Experiment, "np": np}
    return finder.find(obj, name, globs=globs)


TESTS = (
    _examples(stickslip._api, "stickslip")
    + _examples(stickslip._trajectory, "stickslip")
    + _examples(stickslip._tables, "stickslip")
    + _examples(stickslip._stability, "stickslip")
    + _examples(stickslip._dynamics, "stickslip")
    + _examples(stickslip._curve, "stickslip")
    + _examples(stickslip.dask, "stickslip.dask")
    + _examples(Experiment, "stickslip.Experiment")
)


def test_every_public_function_and_constructor_has_an_example():
    named = {t.name.split(".")[-1] for t in TESTS if t.examples}
    for name in ["simulate", "steady", "theory", "boundary", "sweep", "phase_diagram", "orbit",
                 "lyapunov", "bifurcation", "basins", "continuation", "curve",
                 "sweep_grid", "paper", "circuit", "shockley", "mechanics", "from_toml",
                 "replace", "convert", "from_dict", "Experiment"]:
        assert name in named, f"{name} has no example in its docstring"


@pytest.mark.parametrize("test", [t for t in TESTS if t.examples], ids=lambda t: t.name)
def test_docstring_examples(test):
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    result = runner.run(test)
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples failed"
