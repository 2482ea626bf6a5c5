"""stickslip.orbit against `stickslip orbit --json`, stickslip.lyapunov against `stickslip
lyapunov --json`, chaos in steady states and maps against the tool, errors, Ctrl-C."""

from __future__ import annotations

import math
import threading

import numpy as np
import pytest

import stickslip
from stickslip import Experiment

from conftest import assert_runs_beside, assert_same, interrupt_after, numbers, read_csv

CHAOTIC = dict(zeta=0, mu_s=3, w=0.33, beta=9)


CHAOTIC_FLAGS = ["--zeta", 0, "--mu-s", 3, "--w", 0.33, "--beta", 9]

ORBITS = [
    # Automatically, from the steady state: the paper's circuit, two stops per period.
    (Experiment.paper(w=0.7, beta=1.2), {}, ["--preset", "paper", "--w", 0.7, "--beta", 1.2]),
    # A sliding orbit with a complex pair of multipliers, dimensionless.
    (Experiment(zeta=0.0468, w=0.9, beta=1.6), {}, ["--zeta", 0.0468, "--w", 0.9, "--beta", 1.6]),
    # Unstable orbits in a chaotic window, from a guess after a transient; period 2 lands on
    # the period-1 orbit.
    (Experiment(**CHAOTIC), dict(period=1, transient=2000),
     CHAOTIC_FLAGS + ["--period", 1, "--transient", 2000]),
    (Experiment(**CHAOTIC), dict(period=2, transient=2000),
     CHAOTIC_FLAGS + ["--period", 2, "--transient", 2000]),
    # The period-3 orbit at w = 0.40 with other search settings.
    (Experiment(zeta=0, mu_s=3, w=0.4, beta=9), dict(max_period=8, max_periods=4000),
     ["--zeta", 0, "--mu-s", 3, "--w", 0.4, "--beta", 9, "--max-period", 8, "--max-periods",
      4000]),
    # Shockley diodes: the stiff solver's orbit with its variational Jacobian (two stops).
    (Experiment.paper(diode="shockley", w=0.7, beta=1.2), {},
     ["--preset", "paper", "--model", "shockley", "--w", 0.7, "--beta", 1.2]),
]


@pytest.mark.parametrize("case", range(len(ORBITS)))
def test_orbit_is_the_tools_json(cli, case):
    experiment, arguments, flags = ORBITS[case]
    expected = cli.json("orbit", *flags)
    o = stickslip.orbit(experiment, **arguments)
    assert o.to_dict() == expected
    assert list(o.to_dict()) == list(expected)
    # Attributes: numpy arrays of the same numbers.
    assert o.period == expected["period"] and o.least_period == expected["least_period"]
    mu = np.array([complex(m["re"], m["im"]) for m in expected["multipliers"]])
    assert_same(o.multipliers.real, mu.real, "re")
    assert_same(o.multipliers.imag, mu.imag, "im")
    assert_same(o.moduli, np.abs(mu), "moduli")
    assert o.monodromy.shape == (2, 2)
    assert_same(o.monodromy, expected["monodromy"], "monodromy")
    assert o.stable == (o.stability == "stable") == (abs(o.multipliers[0]) < 1)
    assert list(o.events["kind"]) == [e["kind"] for e in expected["events"]]
    assert_same(o.events["tau"], [e["tau"] for e in expected["events"]], "event times")
    assert_same(o.stops["duration"], [s["duration"] for s in expected["stops"]], "stops")
    # The exponent is that of the largest multiplier.
    assert math.isclose(o.lambda1,
                        math.log(o.moduli[0]) / (o.period * o.drive_period), rel_tol=1e-12)


def test_orbit_facts():
    unstable = stickslip.orbit(Experiment(**CHAOTIC), 1, transient=2000)
    assert unstable.stability == "unstable" and unstable.lambda1 > 0
    twice = stickslip.orbit(Experiment(**CHAOTIC), 2, transient=2000)
    assert (twice.period, twice.least_period) == (2, 1)
    assert math.isclose(twice.moduli[0], unstable.moduli[0] ** 2, rel_tol=1e-8)
    # The orbit that stops has a multiplier 0 (to rounding).
    stick = stickslip.orbit(Experiment.paper(w=0.7, beta=1.2))
    assert stick.moduli[1] < 1e-12 and stick.stops_per_period == 2.0
    assert len(stick.stops) == 2 and stick.stops.dtype == stickslip.STOP_DTYPE


def test_orbit_errors(cli):
    with pytest.raises(ValueError, match="^the steady state found no period in 5000"):
        stickslip.orbit(Experiment(**CHAOTIC))
    with pytest.raises(ValueError, match="^invalid period = 0: must be from 1 to 1000$"):
        stickslip.orbit(Experiment(**CHAOTIC), 0)
    with pytest.raises(ValueError, match="^invalid transient = -1"):
        stickslip.orbit(Experiment(**CHAOTIC), 1, transient=-1)
    with pytest.raises(ValueError, match="^invalid tolerance = 0"):
        stickslip.orbit(Experiment(**CHAOTIC), 1, tolerance=0)
    with pytest.raises(TypeError, match="unknown option 'tol'"):
        stickslip.orbit(Experiment(**CHAOTIC), tol=1)
    with pytest.raises(ValueError, match="^missing drive amplitude"):
        stickslip.orbit(Experiment.paper(w=0.7))


LYAPUNOV = [
    (Experiment(**CHAOTIC), dict(transient=500, periods=4000, blocks=10),
     CHAOTIC_FLAGS + ["--transient", 500, "--periods", 4000, "--blocks", 10]),
    (Experiment.paper(w=0.9, beta=1.6), dict(transient=200, periods=400),
     ["--preset", "paper", "--w", 0.9, "--beta", 1.6, "--transient", 200, "--periods", 400]),
    (Experiment.paper(w=0.7, beta=1.2), dict(transient=100, periods=1000, significance=3),
     ["--preset", "paper", "--w", 0.7, "--beta", 1.2, "--transient", 100, "--periods", 1000,
      "--significance", 3]),
    # Shockley diodes: the stiff solver's tangent dynamics; λ2 stays finite.
    (Experiment.paper(diode="shockley", w=0.7, beta=1.2), dict(transient=100, periods=400),
     ["--preset", "paper", "--model", "shockley", "--w", 0.7, "--beta", 1.2, "--transient",
      100, "--periods", 400]),
]


@pytest.mark.parametrize("case", range(len(LYAPUNOV)))
def test_lyapunov_is_the_tools_json(cli, case):
    experiment, arguments, flags = LYAPUNOV[case]
    expected = cli.json("lyapunov", *flags)
    c = stickslip.lyapunov(experiment, **arguments)
    assert c.to_dict() == expected
    assert list(c.to_dict()) == list(expected)
    assert c.motion_class == expected["class"]
    assert_same(c.block_means, expected["block_means"], "block means")
    assert c.lambda1 == expected["lambda1"]
    if expected["lambda2"] is None:
        assert c.lambda2 == -math.inf and "stopped" in c.lambda2_reason
    else:
        assert c.lambda2 == expected["lambda2"] and c.lambda2_reason is None


def test_lyapunov_verdicts_and_errors(cli):
    chaotic = stickslip.lyapunov(Experiment(**CHAOTIC), transient=500, periods=2000)
    assert chaotic.motion_class == "chaotic"
    assert chaotic.lambda1 > 4 * chaotic.lambda1_error
    sliding = stickslip.lyapunov(Experiment.paper(w=0.9, beta=1.6), transient=200, periods=400)
    # It has reached its period-1 sliding orbit: periodic, and contracting by its exponent.
    assert (sliding.motion_class, sliding.period, sliding.verdict) == ("periodic", 1, "contracting")
    assert sliding.stops_per_period == 0.0
    assert sliding.lambda2 < sliding.lambda1
    assert chaotic.period is None and chaotic.lambda2 == -math.inf
    assert chaotic.to_dict()["lambda2"] is None
    with pytest.raises(ValueError, match=r"^invalid blocks = 3: must be even and from 4 to 10000$"):
        stickslip.lyapunov(Experiment(**CHAOTIC), blocks=3)
    with pytest.raises(ValueError, match="^invalid periods = 10"):
        stickslip.lyapunov(Experiment(**CHAOTIC), periods=10)
    with pytest.raises(ValueError, match="^invalid transient = -1"):
        stickslip.lyapunov(Experiment(**CHAOTIC), transient=-1)
    with pytest.raises(ValueError, match="^a run of 1000001000 drive periods at w = 0.33 is too long"):
        stickslip.lyapunov(Experiment(**CHAOTIC), periods=10**9)
    # Shockley diodes: the exponent of the orbit the motion reached, λ2 finite.
    shockley = stickslip.lyapunov(Experiment.paper(diode="shockley", w=0.7, beta=1.2),
                                  transient=100, periods=400)
    orbit = stickslip.orbit(Experiment.paper(diode="shockley", w=0.7, beta=1.2))
    assert (shockley.motion_class, shockley.period) == ("periodic", 1)
    assert math.isclose(shockley.lambda1, orbit.lambda1, rel_tol=1e-6)
    assert math.isfinite(shockley.lambda2) and shockley.lambda2_reason is None


def test_lyapunov_reports_progress_in_drive_periods():
    seen = []
    stickslip.lyapunov(Experiment(**CHAOTIC), transient=0, periods=200000, blocks=20,
                       progress=lambda done, total: seen.append((done, total)))
    assert seen[-1] == (200000, 200000)
    assert all(a[0] < b[0] for a, b in zip(seen, seen[1:]))


def test_ctrl_c_stops_a_long_measurement():
    assert threading.current_thread() is threading.main_thread()
    timer = interrupt_after(0.5)
    try:
        with pytest.raises(KeyboardInterrupt):
            # 10^8 periods: minutes.
            stickslip.lyapunov(Experiment(**CHAOTIC), periods=10**8)
    finally:
        timer.cancel()
    # Stopped within a little work after the signal, counted in CPU time (not the wall time,
    # which a loaded machine stretches).
    cpu = timer.cpu_since_signal()
    assert cpu < 5.0, f"{cpu:.1f} s of CPU after the signal"
    # A long transient before Newton's method stops too.
    timer = interrupt_after(0.5)
    try:
        with pytest.raises(KeyboardInterrupt):
            stickslip.orbit(Experiment(**CHAOTIC), 1, transient=10**8)
    finally:
        timer.cancel()


def test_ctrl_c_stops_a_long_steady_state_search():
    """stickslip.steady stops on Ctrl-C like the other computations: a chaotic motion never
    repeats, so the search would run its 10^8 periods (minutes) without the interrupt."""
    assert threading.current_thread() is threading.main_thread()
    timer = interrupt_after(0.5)
    try:
        with pytest.raises(KeyboardInterrupt):
            stickslip.steady(Experiment(**CHAOTIC), max_periods=10**8, lyapunov_periods=0)
    finally:
        timer.cancel()
    # Stopped within a little work after the signal, counted in CPU time (not the wall time,
    # which a loaded machine stretches).
    cpu = timer.cpu_since_signal()
    assert cpu < 5.0, f"{cpu:.1f} s of CPU after the signal"


def test_the_measurement_runs_without_the_gil():
    """While a measurement runs in another thread, the main thread runs Python code (read
    from the order of events, not the clock: conftest's assert_runs_beside)."""
    c = assert_runs_beside(stickslip.lyapunov, Experiment(**CHAOTIC), transient=0,
                           periods=300000, fixed=True)
    assert c.motion_class == "chaotic"


def test_steady_reports_chaos_as_the_tool_does(cli):
    slow = Experiment(zeta=0, mu_s=2.5, w=0.4227, beta=3.627)
    slow_flags = ["--zeta", 0, "--mu-s", 2.5, "--w", 0.4227, "--beta", 3.627]
    for experiment, flags, options, motion in [
        (Experiment(**CHAOTIC), CHAOTIC_FLAGS, {}, "chaotic"),
        # Newton's method finds its slow period-1 orbit; the plain iteration does not repeat
        # within the cap, and measures a contracting exponent.
        (slow, slow_flags, {}, "periodic-stick"),
        (slow, slow_flags + ["--no-extrapolation"], {"accelerate": False}, "undecided"),
    ]:
        expected = cli.json("steady", *flags, "--harmonics", 9)
        s = stickslip.steady(experiment, harmonics=9, **options)
        assert s.to_dict() == expected
        assert s.motion_class == motion
        assert s.lambda1 == expected.get("lambda1")
        assert s.verdict == expected.get("verdict")
    # Not measured, and a periodic motion: no exponent.
    off = stickslip.steady(Experiment(**CHAOTIC), lyapunov_periods=0)
    assert off.motion_class == "undecided" and off.lambda1 is None
    assert "lambda1" not in off.to_dict()
    assert stickslip.steady(Experiment.paper(w=0.7, beta=1.2)).verdict is None
    with pytest.raises(ValueError, match="^invalid lyapunov_periods = 10"):
        stickslip.steady(Experiment(**CHAOTIC), lyapunov_periods=10)


def test_map_of_exponents_is_the_tools_csv(cli, tmp_path):
    out = tmp_path / "map.csv"
    cli.run("phase-diagram", "--zeta", 0, "--mu-s", 3, "--w-min", 0.25, "--w-max", 0.4,
            "--w-steps", 4, "--beta-min", 2, "--beta-max", 9, "--beta-steps", 2, "--color",
            "lambda1", "--out", out)
    table = read_csv(out)
    # The tool's own axis values (a chaotic point's exponent depends on the last bit of w).
    w = np.unique(numbers(table["w"]))
    beta = np.unique(numbers(table["beta"]))
    m = stickslip.phase_diagram(Experiment(zeta=0, mu_s=3), w=w, beta=beta, lyapunov=True)
    assert list(m.motion_class.ravel()) == table["class"]
    assert "chaotic" in table["class"]
    assert_same(m.lambda1.ravel(), numbers(table["lambda1"]), "lambda1")
    assert_same(m.lambda1_error.ravel(), numbers(table["lambda1_error"]), "lambda1_error")
    # The codes of the classes never move (a new class is added last): chaotic is 4.
    assert stickslip.MOTION_CLASSES.index("chaotic") == 4
    assert m.counts()["chaotic"] == table["class"].count("chaotic")
    # Without the option, the same classes and no exponents.
    plain = stickslip.phase_diagram(Experiment(zeta=0, mu_s=3), w=w, beta=beta)
    assert plain.lambda1 is None
    np.testing.assert_array_equal(plain.class_code, m.class_code)
    # With Shockley diodes: the exponent of the stiff solver's orbit, as stickslip.orbit's.
    s = stickslip.phase_diagram(Experiment.paper(diode="shockley"), w=[0.9], beta=[2.0],
                                lyapunov=True)
    assert s.lambda1_error.ravel()[0] == 0.0
    orbit = stickslip.orbit(Experiment.paper(diode="shockley", w=0.9, beta=2.0))
    assert math.isclose(s.lambda1.ravel()[0], orbit.lambda1, rel_tol=1e-6)
    with pytest.raises(ValueError, match="lyapunov_periods must not be 0"):
        stickslip.phase_diagram(Experiment(zeta=0, mu_s=3), w=w, beta=beta, lyapunov=True,
                                lyapunov_periods=0)


def test_map_exponents_in_xarray():
    m = stickslip.phase_diagram(Experiment(zeta=0, mu_s=3), w=[0.25, 0.33], beta=[9.0],
                                lyapunov=True)
    ds = m.to_xarray()
    assert ds.lambda1.shape == (2, 1)
    attrs = ds["motion_class"].attrs
    assert attrs["flag_meanings"].split()[4] == "chaotic" and attrs["flag_values"][4] == 4
    assert ds.lambda1.values[1, 0] > 0 > ds.lambda1.values[0, 0]
