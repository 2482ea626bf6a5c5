"""A block on a moving belt from Python: the dimensionless keyword vb, a sweep of the belt
speed up and down (hysteresis) and a map over (vb, mu_s), each point against a steady state
computed on its own, and the CLI's sweep CSV."""

from __future__ import annotations

import numpy as np
import pytest

import stickslip
from stickslip import Experiment

from conftest import numbers, read_csv

#: The damped Coulomb belt without a drive: a stick-slip cycle from rest at a slow belt,
#: steady sliding (stable at every belt speed) at a fast one.
BELT = dict(zeta=0.05, mu_s=1.5)


def test_the_dimensionless_model_takes_a_belt_and_a_circuit_refuses_one():
    s = stickslip.steady(Experiment(vb=0.5, zeta=0, mu_s=1.5))
    # The undamped belt's closed form: a circle of radius √((μs − 1)² + vb²) about y = 1.
    radius = np.hypot(0.5, 0.5)
    assert s.motion_class == "stick-slip-cycle"
    assert abs(s.to_dict()["y_max"] - (1 + radius)) < 1e-12
    with pytest.raises(ValueError, match="vb belongs to a block on a moving belt"):
        Experiment.paper(w=0.5, beta=1.0, vb=0.3)


def test_a_map_over_belt_speed_and_mu_s_is_each_points_steady_state():
    vb, mu_s = [0.1, 0.4, 0.7, 1.0], [1.2, 1.5, 2.0]
    m = stickslip.phase_diagram(Experiment(zeta=0.05), vb=vb, mu_s=mu_s)
    assert m.dims == ("vb", "mu_s") and m.motion_class.shape == (4, 3)
    for i, v in enumerate(vb):
        for j, mu in enumerate(mu_s):
            alone = stickslip.steady(Experiment(zeta=0.05, vb=v, mu_s=mu))
            assert m.motion_class[i, j] == alone.motion_class, (v, mu)
    # Both kinds of motion are in the map: slow belts and high static friction stick.
    assert m.motion_class[0, 2] == "stick-slip-cycle"
    assert m.motion_class[3, 0] == "steady-sliding"
    # The report and the dataset name the keys, as the CLI's CSV does.
    assert list(m.to_dict()["points"][0])[:3] == ["vb", "mu_s", "class"]
    assert m.to_dict()["points"][1]["mu_s"] == 1.5
    ds = m.to_xarray()
    assert ds.motion_class.dims == ("vb", "mu_s")


def test_a_sweep_of_the_belt_speed_is_the_tools_and_shows_hysteresis(cli, tmp_path):
    out = tmp_path / "sweep.csv"
    cli.run("sweep", "--zeta", 0.05, "--mu-s", 1.5, "--over", "vb", "--from", 0.1, "--to", 1,
            "--steps", 4, "--direction", "both", "--out", out)
    table = read_csv(out)
    s = stickslip.sweep(Experiment(**BELT), "vb", numbers(table["vb"])[:4], direction="both")
    assert np.array_equal(s.value, numbers(table["vb"]))
    assert list(s.motion_class) == table["class"]
    assert list(s.direction) == table["direction"]
    # The first step starts from rest, as a steady state of its own does; the down leg
    # arrives at the slow belt sliding steadily, where the up leg found the cycle.
    assert s.motion_class[0] == stickslip.steady(Experiment(vb=0.1, **BELT)).motion_class
    assert s.motion_class[0] == "stick-slip-cycle" and s.motion_class[-1] == "steady-sliding"
    sliding = stickslip.steady(Experiment(vb=0.1, y0=1.0, v0=0.0, **BELT))
    assert sliding.motion_class == "steady-sliding"
    # The columns of the amplitude against belt speed are the CSV's, number for number.
    for name in ("amplitude", "y_max", "y_min", "cycle_period_tau", "stick_fraction"):
        assert np.array_equal(s[name], numbers(table[name]), equal_nan=True), name
    assert np.all(np.isnan(s.cycle_period_s))
    first = stickslip.steady(Experiment(vb=0.1, **BELT)).to_dict()
    assert s.amplitude[0] == pytest.approx(0.5 * (first["y_max"] - first["y_min"]), abs=1e-12)
    assert s.cycle_period_tau[0] == pytest.approx(first["cycle_period_tau"], abs=1e-12)
    assert s.amplitude[0] > 0.1 and s.amplitude[-1] == 0.0
    assert s.to_dict()["points"][0]["stick_fraction"] == s.stick_fraction[0]
    ds = s.to_xarray()
    assert ds.amplitude.dims == ("direction", "vb")
    # The hysteresis: at the slowest belt the up leg's cycle, the down leg's sliding.
    assert ds.amplitude.sel(direction="up", vb=0.1) > 0.1
    assert ds.amplitude.sel(direction="down", vb=0.1) == 0.0


def test_the_stribeck_and_cubic_laws_are_keywords_and_bad_laws_a_value_error():
    base = Experiment(zeta=0.05, mu_s=1.5, vb=0.3)
    s = stickslip.steady(base.replace(friction_law="stribeck", vs=0.5))
    assert s.motion_class == "stick-slip-cycle"
    cubic = stickslip.steady(base.replace(friction_law="cubic", k1=1.0, k3=0.4))
    assert cubic.motion_class == "stick-slip-cycle"
    with pytest.raises(ValueError, match="vs"):
        base.replace(friction_law="stribeck", vs=0.0)
    with pytest.raises(ValueError, match="delta"):
        base.replace(friction_law="stribeck", vs=0.1, delta=-1.0)
    # μs − k1 s + k3 s³ with k1 = 5, k3 = 0.1 goes negative (from s ≈ 0.3 on).
    with pytest.raises(ValueError, match="k1"):
        base.replace(friction_law="cubic", k1=5.0, k3=0.1)
    with pytest.raises(ValueError, match="a circuit has no belt and no friction law"):
        Experiment.paper(w=0.5, beta=1.0, friction_law="stribeck", vs=0.1)


#: Stribeck's and the cubic law on a belt, forced.
SMOOTH_LAWS = [dict(friction_law="stribeck", vs=0.3), dict(friction_law="cubic", k1=0.5, k3=0.5)]


@pytest.mark.parametrize("law", SMOOTH_LAWS, ids=["stribeck", "cubic"])
def test_orbit_and_lyapunov_take_the_smooth_laws(law):
    e = Experiment(zeta=0.05, w=1.0, beta=2.0, mu_s=1.5, vb=0.3).replace(**law)
    o = stickslip.orbit(e)
    assert o.period == 1
    assert stickslip.lyapunov(e, transient=50, periods=100).lambda1 < 0.0


@pytest.mark.parametrize("law", SMOOTH_LAWS, ids=["stribeck", "cubic"])
def test_continuation_takes_the_smooth_laws(law):
    over_w = Experiment(zeta=0.05, beta=2.0, mu_s=1.5, vb=0.3).replace(**law)
    branch = stickslip.continuation(over_w, "w", 1.0, 1.1)
    assert len(branch) > 2
    assert branch.value[0] == pytest.approx(1.0)
    assert branch.value[-1] == pytest.approx(1.1)


@pytest.mark.parametrize("law", SMOOTH_LAWS, ids=["stribeck", "cubic"])
def test_the_other_stability_tools_refuse_the_smooth_laws_with_a_value_error(law):
    e = Experiment(zeta=0.05, w=1.0, beta=2.0, mu_s=1.5, vb=0.3).replace(**law)
    over_w = Experiment(zeta=0.05, beta=2.0, mu_s=1.5, vb=0.3).replace(**law)
    unset = Experiment(zeta=0.05, mu_s=1.5, vb=0.3).replace(**law)
    coulomb_only = "follow Coulomb's friction law so far"
    calls = [
        lambda: stickslip.bifurcation(over_w, "w", [1.0, 1.05], points=10, transient=10,
                                      first_transient=10),
        lambda: stickslip.basins(e, (-1.0, 1.0), (-1.0, 1.0), 3),
        lambda: stickslip.phase_diagram(unset, lyapunov=True, w=[0.5, 1.0], beta=[1.0, 2.0]),
        lambda: stickslip.curve(e, "fold", "beta", 1.2, "w", 0.8, 1.0),
    ]
    for call in calls:
        with pytest.raises(ValueError, match=coulomb_only):
            call()
    with pytest.raises(ValueError, match="the theory"):
        stickslip.theory(e)


def test_the_coulomb_belts_orbit_and_exponent_are_computed():
    e = Experiment(zeta=0.05, w=1.0, beta=2.0, mu_s=1.5, vb=0.5)
    o = stickslip.orbit(e)
    assert o.period == 1
    assert stickslip.lyapunov(e, transient=50, periods=200).lambda1 < 0.0
