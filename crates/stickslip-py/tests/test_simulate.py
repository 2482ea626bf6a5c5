"""stickslip.simulate against `stickslip simulate` (its trajectory and event CSVs)."""

from __future__ import annotations

import numpy as np
import pytest

import stickslip
from stickslip import Experiment

from conftest import assert_same, numbers, read_csv

CASES = [
    # (experiment, the same description as flags, periods, samples per period)
    (Experiment.paper(w=0.7, beta=1.2), ["--preset", "paper", "--w", 0.7, "--beta", 1.2], 30, 200),
    (Experiment(zeta=0.05, w=0.6, beta=1.2, phi=0.4, mu_s=1.3, y0=0.5, v0=-0.2),
     ["--zeta", 0.05, "--w", 0.6, "--beta", 1.2, "--phi", 0.4, "--mu-s", 1.3, "--y0", 0.5,
      "--v0", -0.2], 12.5, 37),
    (Experiment.mechanics(m=2, k=8, gamma=0.4, F0=0.5, F=1, omega=1.8),
     ["--mass", 2, "--stiffness", 8, "--damping", 0.4, "--friction", 0.5, "--amplitude", 1,
      "--omega", 1.8], 10, 50),
    (Experiment.paper(diode="shockley", w=0.95, beta=2.14),
     ["--preset", "paper", "--model", "shockley", "--w", 0.95, "--beta", 2.14], 4, 40),
]


@pytest.mark.parametrize("case", range(len(CASES)))
def test_the_same_trajectory_and_events_as_the_tool(cli, tmp_path, case):
    experiment, flags, periods, samples = CASES[case]
    out, events = tmp_path / "trace.csv", tmp_path / "events.csv"
    cli.run("simulate", *flags, "--periods", periods, "--samples-per-period", samples,
            "--out", out, "--events", events)
    expected = read_csv(out)
    run = stickslip.simulate(experiment, periods, samples_per_period=samples)
    assert list(expected) == list(run.columns)
    assert len(run) == len(expected["tau"]) == int(np.ceil(periods * samples)) + 1
    for column in run.columns:
        if column == "phase":
            assert list(run.phase_labels()) == expected["phase"]
        else:
            assert_same(run[column], numbers(expected[column]), column)
    expected_events = read_csv(events)
    assert_same(run.events["tau"], numbers(expected_events["tau"]), "event tau")
    assert_same(run.events["y"], numbers(expected_events["y"]), "event y")
    assert list(run.events["kind"]) == expected_events["kind"]
    assert run.phase.dtype == np.int8 and run.events.dtype == stickslip.EVENT_DTYPE


def test_model_argument_switches_the_solver(cli, tmp_path):
    out = tmp_path / "trace.csv"
    cli.run("simulate", "--preset", "paper", "--model", "shockley", "--w", 0.95, "--beta", 2.14,
            "--periods", 2, "--out", out)
    run = stickslip.simulate(Experiment.paper(w=0.95, beta=2.14), 2, model="shockley")
    assert run.experiment.model == "shockley"
    assert_same(run.uc_V, numbers(read_csv(out)["uc_V"]), "uc_V")


def test_arrays_come_without_a_copy():
    run = stickslip.simulate(Experiment(zeta=0.05, w=0.7, beta=1.2), 50, 100)
    for column in ("tau", "y", "v", "drive"):
        a = run[column]
        # A numpy array over the library's own buffer (numpy's PySliceContainer), not a copy.
        assert not a.flags.owndata and type(a.base).__name__ == "PySliceContainer"
        assert a.flags.c_contiguous and a.flags.aligned and a.dtype == np.float64


def test_progress_is_reported_in_drive_periods():
    seen = []
    stickslip.simulate(Experiment(zeta=0.05, w=0.7, beta=1.2), 2000, 100,
                       progress=lambda done, total: seen.append((done, total)))
    assert seen and seen[-1] == (2001, 2001)
    assert all(a[0] <= b[0] for a, b in zip(seen, seen[1:]))


def test_bad_runs_raise_value_errors():
    e = Experiment(zeta=0.05, w=0.7, beta=1.2)
    with pytest.raises(ValueError, match=r"^invalid periods = 0: must be finite and > 0$"):
        stickslip.simulate(e, 0)
    with pytest.raises(ValueError, match=r"^invalid samples_per_period = 0: must be from 1 to 5e7"):
        stickslip.simulate(e, 1, 0)
    with pytest.raises(ValueError, match=r"^invalid samples_per_period = -3: must be from 1 to 5e7"):
        stickslip.simulate(e, 1, -3)
    with pytest.raises(ValueError, match="periods × samples_per_period must be at most 5e7"):
        stickslip.simulate(e, 1e6, 100)
    with pytest.raises(ValueError, match="^missing drive amplitude: give beta"):
        stickslip.simulate(Experiment.paper(w=0.7), 1)
    with pytest.raises(ValueError, match="^invalid model 'spice'"):
        stickslip.simulate(e, 1, model="spice")
    with pytest.raises(TypeError, match="expected a stickslip.Experiment"):
        stickslip.simulate({"w": 1}, 1)
