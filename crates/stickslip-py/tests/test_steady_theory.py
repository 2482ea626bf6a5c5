"""stickslip.steady against `stickslip steady --json --xy`, stickslip.theory against
`stickslip theory --json`, stickslip.boundary against `stickslip theory --curve boundary`."""

from __future__ import annotations

import numpy as np
import pytest

import stickslip
from stickslip import Experiment

from conftest import assert_same, numbers, read_csv

STEADY = [
    (Experiment.paper(w=0.7, beta=1.2), ["--preset", "paper", "--w", 0.7, "--beta", 1.2], {}),
    (Experiment.paper(w=0.95, beta=2.14), ["--preset", "paper", "--w", 0.95, "--beta", 2.14], {}),
    (Experiment(zeta=0.02, w=0.33, beta=3.0, mu_s=1.4, phi=1.0),
     ["--zeta", 0.02, "--w", 0.33, "--beta", 3.0, "--mu-s", 1.4, "--phi", 1.0],
     {"max_period": 8, "max_periods": 3000}),
    (Experiment(w=0.7, beta=1.0), ["--w", 0.7, "--beta", 1.0], {"tolerance": 1e-9}),
    (Experiment.paper(w=0.6, beta=1.2), ["--preset", "paper", "--w", 0.6, "--beta", 1.2],
     {"harmonics": 9, "accelerate": False}),
    (Experiment.paper(diode="shockley", w=0.95, beta=2.14),
     ["--preset", "paper", "--model", "shockley", "--w", 0.95, "--beta", 2.14], {}),
]
FLAGS = {"max_period": "--max-period", "max_periods": "--max-periods",
         "tolerance": "--tolerance", "harmonics": "--harmonics"}


@pytest.mark.parametrize("case", range(len(STEADY)))
def test_to_dict_is_the_tools_json(cli, tmp_path, case):
    experiment, flags, options = STEADY[case]
    extra = []
    for name, value in options.items():
        extra += ["--no-extrapolation"] if name == "accelerate" else [FLAGS[name], value]
    xy = tmp_path / "xy.csv"
    expected = cli.json("steady", *flags, *extra, "--xy", xy)
    s = stickslip.steady(experiment, **options)
    assert s.to_dict() == expected
    assert list(s.to_dict()) == list(expected)  # the same keys in the same order
    # Attributes, the lists as numpy arrays.
    assert s.motion_class == expected["class"] and s.period == expected["period"]
    assert_same(s.harmonics, expected["harmonics"], "harmonics")
    assert_same(s.current_harmonics, expected["current_harmonics"], "current harmonics")
    # The X-Y data and the recorded cycle, as the tool's --xy CSV (tau, drive, y, v).
    table = read_csv(xy)
    assert_same(s.trace.tau, numbers(table["tau"]), "tau")
    assert_same(s.xy[0], numbers(table["drive"]), "drive")
    assert_same(s.xy[1], numbers(table["y"]), "y")
    assert_same(s.trace.v, numbers(table["v"]), "v")
    assert len(s.trace) == s.samples_per_period * s.recorded_periods


def test_steady_errors():
    e = Experiment.paper(w=0.7, beta=1.2)
    with pytest.raises(ValueError, match=r"^invalid max_period = 65: must be from 1 to 64$"):
        stickslip.steady(e, max_period=65)
    with pytest.raises(ValueError, match=r"^invalid tolerance = -1: must be > 0 and < 1$"):
        stickslip.steady(e, tolerance=-1)
    with pytest.raises(ValueError, match=r"^invalid samples_per_period = 100: must be a power"):
        stickslip.steady(e, samples_per_period=100)
    with pytest.raises(TypeError, match="unknown option 'tol'"):
        stickslip.steady(e, tol=1e-3)
    with pytest.raises(ValueError, match="^missing drive frequency: give w"):
        stickslip.steady(Experiment.paper(beta=1.2))


THEORY = [
    (Experiment(zeta=0.0468, w=0.9, beta=2.0), ["--zeta", 0.0468, "--w", 0.9, "--beta", 2.0]),
    (Experiment.paper(w=0.95, beta=2.14), ["--preset", "paper", "--w", 0.95, "--beta", 2.14]),
    (Experiment(zeta=0.0468, w=0.3, beta=1.07), ["--zeta", 0.0468, "--w", 0.3, "--beta", 1.07]),
    (Experiment(zeta=0.0, w=1.0, beta=2.0), ["--zeta", 0.0, "--w", 1.0, "--beta", 2.0]),
    (Experiment(zeta=0.1, w=1.3, beta=2.5, mu_s=1.3),
     ["--zeta", 0.1, "--w", 1.3, "--beta", 2.5, "--mu-s", 1.3]),
]


@pytest.mark.parametrize("case", range(len(THEORY)))
def test_theory_is_the_tools_json(cli, case):
    experiment, flags = THEORY[case]
    assert stickslip.theory(experiment) == cli.json("theory", *flags)


def test_theory_needs_the_pwl_model(cli):
    with pytest.raises(ValueError) as raised:
        stickslip.theory(Experiment.paper(w=0.95, beta=2.14, diode="shockley"))
    assert str(raised.value) == (
        "the theory covers the piecewise-linear diode (Coulomb friction) model, not Shockley "
        "diodes"
    )
    with pytest.raises(ValueError, match="^missing drive amplitude"):
        stickslip.theory(Experiment(w=0.9))


@pytest.mark.parametrize("mu_s", [1.0, 1.5])
def test_boundary_is_the_tools_curve(cli, tmp_path, mu_s):
    out = tmp_path / "boundary.csv"
    cli.run("theory", "--zeta", 0.0468, "--mu-s", mu_s, "--curve", "boundary", "--w-min", 0.05,
            "--w-max", 3, "--steps", 300, "--out", out)
    table = read_csv(out)
    w = numbers(table["w"])
    paper, exact = stickslip.boundary(0.0468, w, mu_s=mu_s)
    expected_paper = numbers(table["beta_c_paper"])
    expected_exact = numbers(table["beta_c_exact"])
    # NaN exactly where the tool leaves the cell empty (no boundary there).
    assert np.array_equal(np.isnan(paper), np.isnan(expected_paper))
    assert np.array_equal(np.isnan(exact), np.isnan(expected_exact))
    assert_same(paper, expected_paper, "paper")
    assert_same(exact, expected_exact, "exact")
    assert np.isfinite(exact).sum() > 250


def test_boundary_broadcasts():
    w = np.linspace(0.2, 2.0, 12).reshape(3, 4)
    paper, exact = stickslip.boundary(0.05, w)
    assert paper.shape == exact.shape == (3, 4)
    zetas = np.array([[0.02], [0.05], [0.1]])
    p2, e2 = stickslip.boundary(zetas, w[0], mu_s=1.0)
    assert p2.shape == (3, 4)
    for k, zeta in enumerate(zetas[:, 0]):
        paper_k, exact_k = stickslip.boundary(zeta, w[0])
        assert_same(p2[k], paper_k, "broadcast ζ, paper")
        assert_same(e2[k], exact_k, "broadcast ζ, exact")
    assert not np.array_equal(e2[0], e2[2])
    with pytest.raises(ValueError, match=r"^invalid w = -1: must be finite and from 1e-5 to 1e5 \(docs/limits\.md\)$"):
        stickslip.boundary(0.05, [0.5, -1.0])
    with pytest.raises(ValueError, match=r"^invalid mu_s = 0.5: must be finite and from 1 to 1e9 \(docs/limits\.md\)$"):
        stickslip.boundary(0.05, 1.0, mu_s=0.5)
