"""The package as a researcher tries it: every limit of the library (and of the command-line
tool) enforced before any work, integer arguments taken one way everywhere, errors that name
the parameter and what it allows, optional dependencies that say which extra installs them,
trajectories as xarray and pandas, physical units on sweeps and maps, and the paper's
'static' rule with the stops beside it."""

from __future__ import annotations

import os
import pathlib
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import stickslip
import stickslip.dask
from stickslip import Experiment

xr = pytest.importorskip("xarray", reason="the xarray tests need xarray (a test extra)")
pd = pytest.importorskip("pandas", reason="the pandas tests need pandas (a test extra)")


# --- Limits and sizes, before any work -------------------------------------------------------


def test_a_run_past_the_time_range_is_refused_as_the_tool_refuses_it(cli):
    expected = cli.error("simulate", "--w", "1e-5", "--beta", "1.2", "--periods", "7000")
    assert "at most 6835 periods" in expected
    with pytest.raises(ValueError) as raised:
        stickslip.simulate(Experiment(w=1e-5, beta=1.2), periods=7000)
    assert str(raised.value) == expected
    # Just inside the range it runs (stopped at once: the check is not the run).
    just_inside = stickslip.simulate(Experiment(w=1e-5, beta=1.2), periods=1,
                                     samples_per_period=1)
    assert len(just_inside) == 2


def test_sizes_are_refused_up_front():
    e = Experiment(zeta=0.0, w=0.6, beta=3.269, mu_s=3.0)
    for steps in (10**6, (2, 2001), 2001):
        with pytest.raises(ValueError, match=r"^invalid steps = \d+: must be from 1 to 2000$"):
            stickslip.basins(e, y0=(-8, 8), v0=(-8, 8), steps=steps)
    # The library refuses them too (for any front end), before any work.
    with pytest.raises(ValueError, match=r"^invalid steps = 2001: must be from 1 to 2000 along "
                                         r"each axis \(docs/limits\.md\)$"):
        stickslip._core.basins(e, (-8.0, 8.0), (-8.0, 8.0), (2001, 2), None, 1000, 16, 1000)
    big = np.linspace(0.1, 2.5, 100_000)

    # Refused before any point is computed (a 1e10-point map would take days): a point done
    # would be reported to the progress callback, which fails the test at once.
    def computed(done, total):
        raise AssertionError(f"{done} of {total} points computed before the refusal")

    with pytest.raises(ValueError, match=r"^invalid points = 10000000000: a grid holds at most 1e8 "
                                         r"points \(e\.g\. 10000 × 10000; docs/limits\.md\)$"):
        stickslip.phase_diagram(Experiment.paper(), w=big, beta=np.linspace(0.5, 4, 100_000),
                                progress=computed)
    with pytest.raises(ValueError, match="a grid holds at most 1e8 points"):
        stickslip.dask.phase_diagram(Experiment.paper(), w=big, beta=big)


def test_every_count_has_the_tools_range():
    e = Experiment.paper(w=0.7, beta=1.2)
    cases = [
        (lambda: stickslip.steady(e, max_periods=0), "max_periods = 0: must be from 1 to 1e8"),
        (lambda: stickslip.steady(e, max_periods=2**70),
         f"max_periods = {2**70}: must be from 1 to 1e8"),
        (lambda: stickslip.steady(e, max_period=65), "max_period = 65: must be from 1 to 64"),
        (lambda: stickslip.steady(e, lyapunov_periods=10),
         "lyapunov_periods = 10: must be 0 (off) or from 20 to 1e8"),
        (lambda: stickslip.steady(e, harmonics=0), "harmonics = 0: must be from 1 to 256"),
        (lambda: stickslip.simulate(e, 1, samples_per_period=0),
         "samples_per_period = 0: must be from 1 to 5e7 (and periods × samples_per_period at "
         "most 5e7)"),
        (lambda: stickslip.simulate(e, 1, samples_per_period=10**8),
         "samples_per_period = 100000000: must be from 1 to 5e7 (and periods × "
         "samples_per_period at most 5e7)"),
        (lambda: stickslip.simulate(e, 2, samples_per_period=3 * 10**7),
         "samples = 60000000: periods × samples_per_period must be at most 5e7"),
        (lambda: stickslip.orbit(e, period=0), "period = 0: must be from 1 to 1000"),
        (lambda: stickslip.orbit(e, max_iterations=2**64),
         f"max_iterations = {2**64}: must be from 1 to 1000"),
        (lambda: stickslip.lyapunov(e, blocks=5), "blocks = 5: must be even and from 4 to 10000"),
        (lambda: stickslip.lyapunov(e, periods=10), "periods = 10: must be from blocks (20) to 1e9"),
        (lambda: stickslip.bifurcation(e, "w", [0.5, 0.6], points=2_000_000),
         "points = 2000000: must be from 1 to 1000000"),
        (lambda: stickslip.bifurcation(e, "w", [0.5, 0.6], transient=2**63),
         f"transient = {2**63}: must be from 0 to 1e8 drive periods"),
        (lambda: stickslip.continuation(e, "beta", 1.2, 1.3, max_points=1),
         "max_points = 1: must be from 2 to 10000000"),
        (lambda: stickslip.phase_diagram(e, w=[0.5], beta=[1.0], threads=-1),
         "threads = -1: must be from 1 to 1024"),
        (lambda: stickslip.basins(Experiment(zeta=0.0, w=0.6, beta=3.3, mu_s=3.0), (-1, 1),
                                  (-1, 1), steps=2, threads=0),
         "threads = 0: must be from 1 to 1024"),
    ]
    for call, message in cases:
        with pytest.raises(ValueError) as raised:
            call()
        assert str(raised.value) == f"invalid {message}", message


# --- Integer arguments -----------------------------------------------------------------------


def test_integer_arguments_take_integers_only_everywhere():
    """The rule (docs/python.md): a count is an int or a numpy integer; a float is refused
    even when integral (100.0, 1e4), and so is a bool, with a TypeError naming the argument."""
    e = Experiment.paper(w=0.7, beta=1.2)
    m = Experiment(zeta=0.0, w=0.6, beta=3.3, mu_s=3.0)
    calls = {
        "samples_per_period": lambda v: stickslip.simulate(e, 1, samples_per_period=v),
        "max_periods": lambda v: stickslip.steady(e, max_periods=v),
        "harmonics": lambda v: stickslip.steady(e, harmonics=v),
        "max_period": lambda v: stickslip.sweep(e, "w", [0.7], max_period=v),
        "lyapunov_periods": lambda v: stickslip.phase_diagram(e, w=[0.7], beta=[1.2],
                                                              lyapunov_periods=v),
        "threads": lambda v: stickslip.phase_diagram(e, w=[0.7], beta=[1.2], threads=v),
        "transient": lambda v: stickslip.orbit(e, period=1, transient=v),
        "blocks": lambda v: stickslip.lyapunov(e, blocks=v),
        "points": lambda v: stickslip.bifurcation(m, "w", [0.6], points=v),
        "steps": lambda v: stickslip.basins(m, (-1, 1), (-1, 1), steps=v),
        "max_points": lambda v: stickslip.continuation(e, "beta", 1.2, 1.3, max_points=v),
    }
    # None means "the default" for threads and the steady-state options.
    none_is_default = {"threads", "max_periods", "harmonics", "max_period", "lyapunov_periods"}
    for name, call in calls.items():
        for bad in (2.9, 100.0, 1e4, True, "100", None):
            if bad is None and name in none_is_default:
                continue
            with pytest.raises(TypeError, match=f"^{name} must be an integer, got ") as raised:
                call(bad)
            if bad in (100.0, 1e4):
                assert f"(write {int(bad)}: counts are integers, not floats)" in str(raised.value)
    # Python ints and numpy integers of any width are accepted.
    a = stickslip.simulate(e, 2, samples_per_period=np.int16(50))
    b = stickslip.simulate(e, 2, samples_per_period=50)
    assert len(a) == len(b) == 101 and np.array_equal(a.y, b.y)
    assert stickslip.steady(e, max_periods=np.uint64(3000)).period == 1
    # periods of simulate is a length of time, not a count: any number.
    assert len(stickslip.simulate(e, 2.5, samples_per_period=10)) == 26


# --- Errors that name the parameter ----------------------------------------------------------


def test_errors_name_the_parameter():
    e = Experiment.paper()
    m = Experiment(zeta=0.0, w=0.6, beta=3.3, mu_s=3.0)
    with pytest.raises(TypeError, match=r"^y0 must be a \(smallest, largest\) pair of numbers, "
                                        r"e\.g\. y0=\(-8, 8\), got 5$"):
        stickslip.basins(m, y0=5, v0=(-1, 1))
    with pytest.raises(TypeError, match=r"^v0\[1\] must be a number, got 'x'$"):
        stickslip.basins(m, y0=(-1, 1), v0=(-1, "x"))
    with pytest.raises(TypeError, match=r"^w must be numbers \(an array of floats\), got \['a'\]$"):
        stickslip.phase_diagram(e, w=["a"], beta=[1.0])
    with pytest.raises(TypeError, match=r"^mu_s must be numbers \(an array of floats\), "
                                        r"got \[1, None\]$"):
        stickslip.boundary(0.05, [0.7, 0.8], mu_s=[1, None])
    with pytest.raises(TypeError, match=r"^values must be numbers \(an array of floats\)"):
        stickslip.sweep(Experiment.paper(beta=2.0), "w", "0.5 0.6")
    with pytest.raises(TypeError) as raised:
        stickslip.phase_diagram(e, gamma=[1, 2], beta=[1, 2])
    assert str(raised.value).startswith("phase_diagram() got an unknown keyword 'gamma' "
                                        "(the parameters: zeta, w, beta, mu_s, vb, vs, delta, eta, k1, k3; the options: ")
    with pytest.raises(TypeError, match=r"^stickslip\.dask\.sweep_grid\(\) got an unknown "
                                        r"keyword 'gamma'"):
        stickslip.dask.sweep_grid(e, gamma=[1, 2], w=[1.0], beta=[1.0])
    with pytest.raises(TypeError, match=r"^steady\(\) got an unknown option 'max_perods': the "
                                        r"options are tolerance, max_periods"):
        stickslip.steady(Experiment.paper(w=0.7, beta=1.2), max_perods=10)
    with pytest.raises(TypeError, match=r"^accelerate must be True or False, got 'no'$"):
        stickslip.steady(Experiment.paper(w=0.7, beta=1.2), accelerate="no")
    with pytest.raises(TypeError, match=r"^tolerance must be a number, got '1e-6'$"):
        stickslip.steady(Experiment.paper(w=0.7, beta=1.2), tolerance="1e-6")
    with pytest.raises(TypeError, match=r"^periods must be a number, got '10'$"):
        stickslip.simulate(Experiment.paper(w=0.7, beta=1.2), "10")


def test_from_toml_on_a_missing_file_is_file_not_found(tmp_path):
    missing = tmp_path / "nowhere.toml"
    with pytest.raises(FileNotFoundError, match="cannot read experiment file .*nowhere.toml"):
        Experiment.from_toml(missing)
    with pytest.raises(IsADirectoryError, match="cannot read experiment file"):
        Experiment.from_toml(tmp_path)


def run_without(module: str, code: str) -> subprocess.CompletedProcess:
    """Run `code` in a fresh interpreter in which `module` cannot be imported."""
    prelude = f"import sys\nsys.modules[{module!r}] = None\n"
    return subprocess.run([sys.executable, "-c", prelude + textwrap.dedent(code)],
                          capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("module, extra, code", [
    ("xarray", "xarray", "stickslip.simulate(e, 1).to_xarray()"),
    ("xarray", "xarray", "stickslip.phase_diagram(e, w=[0.7], beta=[1.2]).to_xarray()"),
    ("xarray", "xarray", "stickslip.sweep(e, 'w', [0.7]).to_xarray()"),
    ("pandas", "pandas", "stickslip.simulate(e, 1).to_pandas()"),
])
def test_a_missing_optional_dependency_names_its_extra(module, extra, code):
    done = run_without(module, f"""
        import stickslip
        e = stickslip.Experiment.paper(w=0.7, beta=1.2)
        try:
            {code}
        except ModuleNotFoundError as error:
            assert error.name == {module!r}, error.name
            print(error)
        """)
    assert done.returncode == 0, done.stderr
    assert f"needs {module}, which is not installed: pip install 'stickslip[{extra}]'" \
        in done.stdout, done.stdout


# --- Trajectories as data sets ---------------------------------------------------------------


def test_trajectory_to_xarray_and_pandas():
    run = stickslip.simulate(Experiment.paper(w=0.7, beta=1.2), periods=3, samples_per_period=50)
    ds = run.to_xarray()
    assert ds["y"].dims == ("tau",) and np.array_equal(ds["tau"].values, run.tau)
    for name in ("y", "v", "drive", "phase", "uc_V", "i_A", "u_V"):
        assert np.array_equal(ds[name].values, run[name]), name
    assert np.array_equal(ds["t_s"].values, run.t_s) and ds["t_s"].attrs["units"] == "s"
    assert ds["uc_V"].attrs["units"] == "V" and ds["i_A"].attrs["units"] == "A"
    assert ds["phase"].attrs["flag_meanings"] == "slip- stick slip+"
    assert list(ds["phase"].attrs["flag_values"]) == [-1, 0, 1]
    assert ds.sizes["event"] == len(run.events)
    assert list(ds["event_kind"].values) == list(run.events["kind"])
    assert Experiment.from_json(ds.attrs["experiment_json"]) == run.experiment
    df = run.to_pandas()
    assert tuple(df.columns) == run.columns and len(df) == len(run)
    for name in run.columns:
        assert np.array_equal(df[name].to_numpy(), run[name]), name
    # Dimensionless: no physical columns, and the attribute says so.
    plain = stickslip.simulate(Experiment(w=0.7, beta=1.2), periods=1)
    assert tuple(plain.to_pandas().columns) == ("tau", "y", "v", "drive", "phase")
    assert "t_s" not in plain.to_xarray().coords
    with pytest.raises(AttributeError):
        plain.uc_V


# --- Physical units on sweeps and maps -------------------------------------------------------


def test_maps_and_sweeps_of_a_circuit_carry_physical_units():
    e = Experiment.paper()
    scales = e.scales()
    assert scales is not None and scales["force_unit"] == "V" and scales["position_unit"] == "V"
    assert scales["f0"] == pytest.approx(e.convert()["f0"], rel=1e-15)
    w, beta = np.linspace(0.5, 1.5, 4), np.linspace(1.0, 3.0, 3)
    ds = stickslip.phase_diagram(e, w=w, beta=beta, max_period=4).to_xarray()
    assert ds["f_Hz"].dims == ("w",) and ds["f_Hz"].attrs["units"] == "Hz"
    np.testing.assert_allclose(ds["f_Hz"].values, w * scales["f0"], rtol=1e-15)
    assert ds["U_V"].dims == ("beta",) and ds["U_V"].attrs["units"] == "V"
    np.testing.assert_allclose(ds["U_V"].values, beta * scales["force"], rtol=1e-15)
    # The paper's U_t = 0.7 V: β = 1 is 0.7 V, cross-checked against the tool's conversion.
    assert ds["U_V"].values[0] == pytest.approx(0.7 * beta[0], rel=1e-12)
    assert ds.attrs["f0_Hz"] == scales["f0"]
    # ds.sel by physical value works through the coordinate.
    assert ds.swap_dims({"w": "f_Hz"}).sel(f_Hz=ds["f_Hz"].values[1])["motion_class"].shape == (3,)

    s = stickslip.sweep(e.replace(beta=2.0), "w", w)
    sd = s.to_xarray()
    np.testing.assert_allclose(sd["f_Hz"].values, w * scales["f0"], rtol=1e-15)
    up = s.direction == "up"
    np.testing.assert_allclose(sd["peak_V"].sel(direction="up").values,
                               s.peak[up] * scales["position"], rtol=1e-15)
    assert sd["peak_V"].attrs["units"] == "V"
    np.testing.assert_allclose(sd["U_V"].sel(direction="up").values, 2.0 * scales["force"] * np.ones(4),
                               rtol=1e-15)
    # A bifurcation diagram of the circuit over w: Hz beside w.
    bd = stickslip.bifurcation(e.replace(beta=3.0), "w", [0.6, 0.7], direction="up", points=4,
                               transient=10, first_transient=10).to_xarray()
    np.testing.assert_allclose(bd["f_Hz"].values, [0.6 * scales["f0"], 0.7 * scales["f0"]],
                               rtol=1e-15)
    # A mechanical oscillator: newtons and metres.
    mech = Experiment.mechanics(m=1.0, k=100.0, gamma=0.5, F0=2.0)
    md = stickslip.sweep(mech.replace(w=0.8), "beta", [1.0, 2.0]).to_xarray()
    assert md["F_N"].attrs["units"] == "N" and "peak_m" in md
    np.testing.assert_allclose(md["F_N"].values, [2.0, 4.0], rtol=1e-15)
    # Dimensionless experiments have no physical coordinates.
    plain = stickslip.phase_diagram(Experiment(), w=w, beta=beta).to_xarray()
    assert "f_Hz" not in plain.coords and "U_V" not in plain.coords


def test_the_exponent_map_variable_is_an_attribute_name():
    m = stickslip.phase_diagram(Experiment(zeta=0.0, mu_s=3.0), w=[0.33], beta=[9.0],
                                lyapunov=True, lyapunov_periods=200)
    ds = m.to_xarray()
    assert np.array_equal(ds.lambda1.values, m.lambda1, equal_nan=True)
    assert np.array_equal(ds.lambda1_error.values, m.lambda1_error, equal_nan=True)
    assert "lambda" not in ds and "lyapunov" not in ds


# --- The static rule -------------------------------------------------------------------------


def test_static_is_the_papers_amplitude_rule_and_the_stops_stand_beside_it():
    e = Experiment.paper(w=2.0, beta=1.1)
    s = stickslip.steady(e)
    assert s.motion_class == "static" and s.stops_per_period == 2.0
    assert (s.y_max - s.y_min) / 2 < s.beta / 100
    m = stickslip.phase_diagram(Experiment.paper(), w=[2.0], beta=[1.1])
    assert m.motion_class[0, 0] == "static" and m.stops_per_period[0, 0] == 2.0
    w = stickslip.sweep(Experiment.paper(beta=1.1), "w", [2.0], direction="up")
    assert w.motion_class[0] == "static" and w.stops_per_period[0] == 2.0
    # Every docstring of a function or result that returns a class says what static means.
    for documented in (stickslip.steady, stickslip.sweep, stickslip.phase_diagram,
                       stickslip.SteadyState, stickslip.SweepResult, stickslip.PhaseDiagram,
                       stickslip.PhaseDiagram.to_xarray, stickslip.SweepResult.to_xarray):
        text = " ".join((documented.__doc__ or "").split())
        assert "the paper's" in text and "β/100" in text and "stops_per_period" in text, documented
    for documented in (stickslip.dask.phase_diagram, stickslip.dask.sweep_grid):
        text = " ".join((documented.__doc__ or "").split())
        assert "β/100" in text and "stops_per_period" in text, documented
