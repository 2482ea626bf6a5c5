"""stickslip.bifurcation, stickslip.basins and stickslip.continuation against `stickslip
bifurcation`, `stickslip basins` and `stickslip continue`; their errors, xarray, progress,
Ctrl-C and the GIL."""

from __future__ import annotations

import threading

import numpy as np
import pytest

import stickslip
from stickslip import Experiment

from conftest import assert_runs_beside, assert_same, interrupt_after, numbers, read_csv

# ζ = 0, μs = 3, β = 9: periodic and chaotic motions as w varies (the stability analysis).
CHAOS = ["--zeta", 0, "--mu-s", 3, "--beta", 9]
# A mirror pair of period-1 orbits with one stop per period coexist.
MIRROR = ["--zeta", 0, "--mu-s", 3, "--w", 0.6, "--beta", 3.269]
# The paper's circuit with μs = 1.5 at w = 0.9, from a moving state: a grazing and a fold.
BRANCH = ["--preset", "paper", "--mu-s", 1.5, "--w", 0.9, "--y0", 0.25, "--v0", 2.1]


def period_cells(column):
    """The CSV's period column with -1 for an empty cell, as the package codes it."""
    return np.array([int(x) if x != "" else -1 for x in column])


def test_bifurcation_is_the_tools_csv(cli, tmp_path):
    out = tmp_path / "bif.csv"
    cli.run("bifurcation", *CHAOS, "--over", "w", "--from", 0.25, "--to", 0.35, "--steps", 6,
            "--points", 40, "--transient", 100, "--first-transient", 500, "--out", out)
    table = read_csv(out)
    w = numbers(table["w"])
    values = w[: len(w) // 2][::40]
    assert len(values) == 6
    d = stickslip.bifurcation(Experiment(zeta=0.0, beta=9.0, mu_s=3.0), "w", values,
                              points=40, transient=100, first_transient=500)
    assert len(d) == 12 and d.y.shape == (12, 40)
    rows = d.rows()
    assert_same(rows["w"], w, "w")
    assert_same(rows["y"], numbers(table["y"]), "y")
    assert_same(rows["v"], numbers(table["v"]), "v")
    assert_same(rows["lambda1"], numbers(table["lambda1"]), "lambda1")
    assert list(rows["direction"]) == table["direction"]
    assert list(rows["class"]) == table["class"]
    assert list(rows["period"]) == list(period_cells(table["period"]))
    # The window holds periodic and chaotic values, so the comparison covers both.
    kinds = set(d.motion_class)
    assert {"periodic", "chaotic"} <= kinds, kinds
    # A period-p value has p distinct strobe points; a chaotic one many, and λ > 0.
    for k in range(len(d)):
        distinct = len(np.unique(np.round(d.y[k], 7)))
        if d.motion_class[k] == "periodic":
            assert distinct == d.period[k]
        if d.motion_class[k] == "chaotic":
            assert distinct > 30 and d.lambda1[k] > 0


def test_bifurcation_directions_xarray_and_errors():
    e = Experiment(zeta=0.0, beta=9.0, mu_s=3.0)
    values = np.linspace(0.25, 0.3, 4)
    both = stickslip.bifurcation(e, "w", values, points=20, transient=50)
    up = stickslip.bifurcation(e, "w", values, "up", points=20, transient=50)
    down = stickslip.bifurcation(e, "w", values, "down", points=20, transient=50)
    assert_same(both.y[:4], up.y, "the up leg of both is the up run")
    assert list(down.value) == list(values[::-1]) and set(down.direction) == {"down"}
    ds = both.to_xarray()
    assert ds["y"].dims == ("direction", "w", "point") and ds["y"].shape == (2, 4, 20)
    assert_same(ds["y"].sel(direction="down").values, both.y[4:][::-1], "down leg reordered")
    assert ds["motion_class"].attrs["flag_meanings"].split() == list(stickslip.ATTRACTOR_KINDS)
    assert ds.attrs["beta"] == 9.0 and ds.attrs["points"] == 20
    with pytest.raises(ValueError, match=r"^invalid points = 0: must be from 1 to 1000000$"):
        stickslip.bifurcation(e, "w", values, points=0)
    with pytest.raises(ValueError, match="^invalid direction 'sideways'"):
        stickslip.bifurcation(e, "w", values, "sideways")
    with pytest.raises(ValueError, match="^unknown parameter 'phi'"):
        stickslip.bifurcation(e, "phi", values)
    with pytest.raises(ValueError, match=r"^invalid w = 0: must be finite"):
        stickslip.bifurcation(e, "w", [0.0, 0.3])
    with pytest.raises(ValueError, match=r"^invalid transient = -1: must be from 0 to 1e8 drive periods$"):
        stickslip.bifurcation(e, "w", values, transient=-1)
    with pytest.raises(TypeError, match="^points must be an integer, got "):
        stickslip.bifurcation(e, "w", values, points=2.5)  # type: ignore[arg-type]


def test_basins_are_the_tools_csv_and_json(cli, tmp_path):
    out = tmp_path / "basins.csv"
    flags = [*MIRROR, "--y0-min", -8, "--y0-max", 8, "--v0-min", -8, "--v0-max", 8,
             "--steps", 15]
    summary = cli.json("basins", *flags, "--out", out)
    table = read_csv(out)
    e = Experiment(zeta=0.0, w=0.6, beta=3.269, mu_s=3.0)
    m = stickslip.basins(e, y0=(-8, 8), v0=(-8, 8), steps=15)
    assert m.shape == (15, 15)
    assert_same(np.repeat(m.y0, 15), numbers(table["y0"]), "y0")
    assert_same(np.tile(m.v0, 15), numbers(table["v0"]), "v0")
    assert list(m.attractor.ravel()) == list(period_cells(table["attractor"]))
    assert list(m.motion_class.ravel()) == table["class"]
    assert list(m.period.ravel()) == list(period_cells(table["period"]))
    assert m.to_dict() == summary
    assert [(a["class"], a["period"]) for a in m.attractors] == [("periodic", 1), ("periodic", 1)]
    assert sum(a["fraction"] for a in m.attractors) + m.undecided / 225 == pytest.approx(1.0)
    # Deterministic: any number of threads gives the same map.
    one = stickslip.basins(e, y0=(-8, 8), v0=(-8, 8), steps=15, threads=1)
    assert np.array_equal(one.attractor, m.attractor) and one.to_dict() == m.to_dict()


def test_basins_phase_steps_xarray_and_errors(cli):
    e = Experiment(zeta=0.0, w=0.6, beta=3.269, mu_s=3.0)
    m = stickslip.basins(e, y0=(-8, 8), v0=(-4, 4), steps=(6, 4), phase=1.0)
    assert m.shape == (6, 4) and m.to_dict()["model"]["phi"] == 1.0
    assert m.to_dict()["grid"] == {"y0_min": -8.0, "y0_max": 8.0, "v0_min": -4.0,
                                   "v0_max": 4.0, "steps": 6, "v0_steps": 4}
    assert m.experiment.phi == 1.0
    summary = cli.json("basins", *MIRROR, "--y0-min", -8, "--y0-max", 8, "--v0-min", -4,
                       "--v0-max", 4, "--steps", 6, "--phase", 1)
    square = stickslip.basins(e, y0=(-8, 8), v0=(-4, 4), steps=6, phase=1.0)
    assert square.to_dict() == summary
    ds = m.to_xarray()
    assert ds["attractor"].dims == ("y0", "v0") and ds.attrs["w"] == 0.6
    assert np.array_equal(ds["attractor"].values, m.attractor)
    with pytest.raises(ValueError, match=r"^invalid max_period = 0: must be from 1 to 64$"):
        stickslip.basins(e, y0=(-1, 1), v0=(-1, 1), steps=3, max_period=0)
    with pytest.raises(ValueError, match=r"^invalid lyapunov_periods = 4: must be from 8 to 1e7$"):
        stickslip.basins(e, y0=(-1, 1), v0=(-1, 1), steps=3, lyapunov_periods=4)
    with pytest.raises(ValueError, match="^missing drive"):
        stickslip.basins(Experiment(zeta=0.0, w=0.6), y0=(-1, 1), v0=(-1, 1), steps=3)
    # Shockley diodes: the stiff solver's cells, as the tool's.
    shockley = stickslip.basins(Experiment.paper(w=0.9, beta=1.6, diode="shockley"),
                                y0=(-1, 1), v0=(-1, 1), steps=3)
    assert shockley.to_dict() == cli.json(
        "basins", "--preset", "paper", "--model", "shockley", "--w", 0.9, "--beta", 1.6,
        "--y0-min", -1, "--y0-max", 1, "--v0-min", -1, "--v0-max", 1, "--steps", 3)
    assert [a["class"] for a in shockley.attractors] == ["periodic"]


def test_basins_method_is_the_tools_method(cli, tmp_path):
    # The mirror pair by both methods: the same cells and attractors (within Newton's
    # tolerance, the fixed points come from other starts); each as the tool's --method.
    e = Experiment(zeta=0.0, w=0.6, beta=3.269, mu_s=3.0)
    flags = [*MIRROR, "--y0-min", -8, "--y0-max", 8, "--v0-min", -8, "--v0-max", 8,
             "--steps", 10]
    by = {}
    for method in ["recurrence", "exhaustive"]:
        out = tmp_path / f"{method}.csv"
        summary = cli.json("basins", *flags, "--method", method, "--out", out)
        m = stickslip.basins(e, y0=(-8, 8), v0=(-8, 8), steps=10, method=method)
        assert m.to_dict() == summary
        assert list(m.attractor.ravel()) == list(period_cells(read_csv(out)["attractor"]))
        by[method] = m
    assert np.array_equal(by["recurrence"].attractor, by["exhaustive"].attractor)
    for a, b in zip(by["recurrence"].attractors, by["exhaustive"].attractors):
        assert (a["class"], a["period"], a["cells"], a["mirror"]) == \
            (b["class"], b["period"], b["cells"], b["mirror"])
        assert a["state"]["y"] == pytest.approx(b["state"]["y"], abs=1e-9)
    with pytest.raises(ValueError, match=r"^invalid method 'fast': must be 'recurrence' or "
                                         r"'exhaustive'$"):
        stickslip.basins(e, y0=(-1, 1), v0=(-1, 1), steps=3, method="fast")


def test_continuation_is_the_tools_csv_and_json(cli, tmp_path):
    out = tmp_path / "branch.csv"
    summary = cli.json("continue", *BRANCH, "--over", "beta", "--from", 1.45, "--to", 1.25,
                       "--out", out)
    table = read_csv(out)
    b = stickslip.continuation(Experiment.paper(mu_s=1.5, w=0.9, y0=0.25, v0=2.1), "beta",
                               start=1.45, to=1.25)
    assert len(b) == len(table["beta"]) > 50
    assert_same(b.value, numbers(table["beta"]), "beta")
    for name in ("y", "v", "amplitude", "stops_per_period", "mu1_re", "mu1_im", "mu2_re",
                 "mu2_im", "arclength"):
        assert_same(getattr(b, name), numbers(table[name]), name)
    assert list(b.period) == [int(x) for x in table["period"]]
    assert list(b.turns) == [int(x) for x in table["turns"]]
    assert [str(bool(s)).lower() for s in b.stable] == table["stable"]
    assert b.to_dict() == summary
    # What the branch shows: a grazing where the stops appear, then a fold where it turns
    # back and loses its stability.
    assert [s["kind"] for s in b.special] == ["grazing", "fold"]
    graze, fold = b.special
    assert graze["before"]["stops"] != graze["after"]["stops"]
    assert fold["before"]["stable"] and not fold["after"]["stable"]
    assert np.all(np.abs(b.multipliers[:, 0]) >= np.abs(b.multipliers[:, 1]) - 1e-15)


def test_shockley_continuation_and_bifurcation_are_the_tools(cli, tmp_path):
    # Shockley diodes: the stiff solver's strobe map, its Jacobian and ∂P/∂w from the
    # variational equations; the same numbers as the command's.
    shockley = Experiment.paper(diode="shockley", beta=3.61)
    model = ["--preset", "paper", "--model", "shockley", "--beta", 3.61]
    out = tmp_path / "branch.csv"
    summary = cli.json("continue", *model, "--over", "w", "--from", 1.2, "--to", 1.1,
                       "--out", out)
    table = read_csv(out)
    b = stickslip.continuation(shockley, "w", start=1.2, to=1.1)
    assert b.to_dict() == summary
    assert len(b) == len(table["w"]) > 10
    for name in ("y", "v", "mu1_re", "mu1_im", "arclength"):
        assert_same(getattr(b, name), numbers(table[name]), name)
    assert b.special == [] and all(b.stable)
    # μs is no parameter of the diode law.
    message = cli.error("continue", *model, "--w", 0.9, "--over", "mu-s", "--from", 1,
                        "--to", 1.5)
    with pytest.raises(ValueError) as e:
        stickslip.continuation(shockley.replace(w=0.9), "mu_s", start=1.0, to=1.5)
    assert str(e.value) == message and "mu_s" in message
    out = tmp_path / "bif.csv"
    cli.run("bifurcation", *model, "--over", "w", "--from", 1.0, "--to", 1.1, "--steps", 2,
            "--points", 20, "--transient", 100, "--out", out)
    table = read_csv(out)
    d = stickslip.bifurcation(shockley, "w", [1.0, 1.1], points=20, transient=100)
    rows = d.rows()
    assert_same(rows["y"], numbers(table["y"]), "y")
    assert_same(rows["lambda1"], numbers(table["lambda1"]), "lambda1")
    assert list(rows["class"]) == table["class"] == ["periodic"] * 80


def test_a_tiny_max_step_does_not_stall_on_a_stable_orbit():
    # A largest step of 1e-7 is a resolution, not an obstacle: the stable period-1 orbit goes
    # on at it until the points run out, as it does at 1e-5.
    e = Experiment(zeta=0.0, w=0.6, beta=3.269, mu_s=3.0, y0=4.9, v0=0.0)
    for max_step in (1e-5, 1e-7):
        b = stickslip.continuation(e, "w", start=0.6, to=0.7, max_step=max_step, max_points=200)
        assert b.to_dict()["end"]["reason"] == "max-points", max_step
        assert len(b) == 200
        assert all(b.stable)
        assert 150 * max_step < b.arclength[-1] <= 199 * max_step * (1 + 1e-9)


def test_continuation_errors():
    e = Experiment.paper(mu_s=1.5, w=0.9)
    # From rest below β = μs nothing moves: no orbit to continue.
    with pytest.raises(ValueError, match=r"comes to rest at beta = 1\.2: nothing to continue; "
                                         r"start from a moving state"):
        stickslip.continuation(e, "beta", start=1.2, to=1.4)
    moving = e.replace(y0=0.25, v0=2.1)
    with pytest.raises(ValueError, match=r"^invalid to = 1.45: must differ from the start value$"):
        stickslip.continuation(moving, "beta", start=1.45, to=1.45)
    with pytest.raises(ValueError, match=r"^invalid max_points = 1: must be from 2 to 10000000$"):
        stickslip.continuation(moving, "beta", start=1.45, to=1.25, max_points=1)
    with pytest.raises(ValueError, match=r"^invalid max_step = -1: must be finite and >= min_step$"):
        stickslip.continuation(moving, "beta", start=1.45, to=1.25, max_step=-1)
    with pytest.raises(ValueError, match="^unknown parameter 'L'"):
        stickslip.continuation(moving, "L", start=1.0, to=2.0)


@pytest.mark.parametrize("what", ["bifurcation", "basins", "continuation"])
def test_ctrl_c_stops_a_long_computation(what):
    assert threading.current_thread() is threading.main_thread()
    timer = interrupt_after(0.5)
    try:
        with pytest.raises(KeyboardInterrupt):
            if what == "bifurcation":
                stickslip.bifurcation(Experiment(zeta=0.0, beta=9.0, mu_s=3.0), "w",
                                      np.linspace(0.2, 0.55, 200000), points=200)
            elif what == "basins":
                stickslip.basins(Experiment(zeta=0.0, w=0.6, beta=3.269, mu_s=3.0),
                                 y0=(-8, 8), v0=(-8, 8), steps=2000)
            else:
                stickslip.continuation(Experiment.paper(mu_s=1.5, w=0.9, y0=0.25, v0=2.1),
                                       "beta", start=1.6, to=10.0, max_step=2e-6,
                                       max_points=5_000_000)
    finally:
        timer.cancel()
    # Stopped within a little work after the signal (each computation alone would take minutes of
    # CPU), counted in CPU time: not the wall time, which a loaded machine stretches.
    cpu = timer.cpu_since_signal()
    assert cpu < 5.0, f"{cpu:.1f} s of CPU after the signal"


def test_progress_and_other_threads_run_meanwhile():
    seen = []
    e = Experiment(zeta=0.0, w=0.6, beta=3.269, mu_s=3.0)
    stickslip.basins(e, y0=(-8, 8), v0=(-8, 8), steps=20,
                     progress=lambda done, total: seen.append((done, total)))
    assert seen[-1] == (400, 400)

    def stop(done, total):
        raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        stickslip.basins(e, y0=(-8, 8), v0=(-8, 8), steps=2000, progress=stop)
    # While a diagram runs in one thread, the main thread keeps running Python code (the
    # computation waits without the GIL): read from the order of events, not the clock.
    diagram = assert_runs_beside(stickslip.bifurcation, Experiment(zeta=0.0, beta=9.0, mu_s=3.0),
                                 "w", np.linspace(0.2, 0.55, 300), points=200)
    assert diagram.value.shape[0] >= 300
