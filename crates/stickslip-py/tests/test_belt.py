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
def test_bifurcation_basins_and_the_exponent_map_take_the_smooth_laws(law):
    e = Experiment(zeta=0.05, w=1.0, beta=2.0, mu_s=1.5, vb=0.3).replace(**law)
    over_w = Experiment(zeta=0.05, beta=2.0, mu_s=1.5, vb=0.3).replace(**law)
    unset = Experiment(zeta=0.05, mu_s=1.5, vb=0.3).replace(**law)
    # The period-1 orbit of `orbit` at w = 1 is what each tool finds there.
    o = stickslip.orbit(e)
    assert o.period == 1
    b = stickslip.bifurcation(over_w, "w", [1.0, 1.05], "up", points=10, transient=20,
                              first_transient=300)
    assert b.period[0] == 1
    assert abs(b.y[0][0] - o.state[0]) < 1e-8 * max(1.0, abs(o.state[0]))
    m = stickslip.basins(e, (-1.0, 1.0), (-1.0, 1.0), 3)
    assert m.undecided == 0 and (m.period == 1).all()
    state = m.attractors[0]["state"]
    assert abs(state["y"] - o.state[0]) < 1e-8 * max(1.0, abs(o.state[0]))
    p = stickslip.phase_diagram(unset, lyapunov=True, w=[0.9, 1.0], beta=[1.5, 2.0])
    assert abs(p.lambda1[1, 1] - o.lambda1) <= 1e-8 * abs(o.lambda1)


#: A Stribeck belt whose stick-slip branch over w folds near w = 0.9014 (at β = 1.45), and a
#: weakly forced cubic belt whose sliding orbit has a Neimark–Sacker point in vb near 0.509,
#: started from steady sliding (y = μ(vb), y' = 0).
STRIBECK_FOLD = (Experiment(zeta=0.05, w=0.7, beta=1.45, mu_s=1.5, vb=0.05)
                 .replace(friction_law="stribeck", vs=0.3, delta=2.0, eta=0.05),
                 ("fold", "w", 1.2, "beta", 1.44, 1.46), "w", (0.7, 1.2), "stribeck")
CUBIC_NS = (Experiment(zeta=0.05, w=0.7, beta=0.1, mu_s=1.5, vb=0.8, y0=1.5 - 0.4 + 0.5 * 0.8**3,
                       v0=0.0).replace(friction_law="cubic", k1=0.5, k3=0.5),
            ("neimark-sacker", "vb", 0.3, "w", 0.69, 0.71), "vb", (0.8, 0.3), "cubic")


@pytest.mark.parametrize("case", [STRIBECK_FOLD, CUBIC_NS], ids=["stribeck-fold", "cubic-ns"])
def test_curve_takes_the_smooth_laws_and_its_points_are_continuations_special_points(case):
    e, spec, vary, (start, to), law = case
    follow, _, _, over, lo, hi = spec
    c = stickslip.curve(e, *spec[:4], start=lo, to=hi)
    assert c.over == over and c.vary == vary and len(c) > 4
    assert c.end["reason"] == "boundary"
    mu = c.multipliers
    if follow == "fold":
        assert np.min(np.abs(mu - 1.0), axis=1).max() < 1e-8
    else:
        assert (np.abs(np.abs(mu) - 1.0).max() < 1e-8) and (mu[:, 0].imag != 0).all()
    # Each end against `continuation`'s special point at that value of `over`, found on its
    # own from the orbit settled on at the start of the search.
    for k in (0, len(c) - 1):
        b = stickslip.continuation(e.replace(**{over: float(c[over][k])}), vary, start, to,
                                   max_step=0.02)
        found = [s["value"] for s in b.special if s["kind"] == follow and s["located"]]
        assert found, b.special
        assert abs(found[0] - c[vary][k]) < 1e-8, (found[0], c[vary][k])
    # Grazing curves need the exact solver's events: refused in one line naming the law.
    with pytest.raises(ValueError, match=f"with the {law} law a curve follows"):
        stickslip.curve(e, "grazing", *spec[1:4], start=lo, to=hi)
    with pytest.raises(ValueError, match="the theory"):
        stickslip.theory(e)


def test_the_coulomb_belts_orbit_and_exponent_are_computed():
    e = Experiment(zeta=0.05, w=1.0, beta=2.0, mu_s=1.5, vb=0.5)
    o = stickslip.orbit(e)
    assert o.period == 1
    assert stickslip.lyapunov(e, transient=50, periods=200).lambda1 < 0.0
