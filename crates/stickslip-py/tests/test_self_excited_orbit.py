"""``stickslip.orbit`` without a drive on a belt (beta=0, vb != 0): the self-excited cycle
that ``steady`` settles on (its own period, class, multipliers, extremes, stick fraction),
or steady sliding with the eigenvalues of its linearisation; the CLI's JSON for the same
input."""

from __future__ import annotations

import math

import numpy as np
import pytest

import stickslip
from stickslip import Experiment

#: A damped Coulomb belt without a drive: a stick-slip cycle from rest.
STICK_SLIP = dict(zeta=0.05, mu_s=1.5, vb=0.3)
#: The cubic law about unstable steady sliding, started near it: a pure-slip cycle.
PURE_SLIP = dict(zeta=0.05, mu_s=1.5, vb=0.65, y0=1.25, v0=0.05, friction_law="cubic",
                 k1=0.5, k3=0.3)
#: The keywords of a friction law (``Experiment.replace`` takes them).
LAW_KEYS = {"friction_law", "k1", "k3"}


def belt(keys) -> Experiment:
    model = {k: v for k, v in keys.items() if k not in LAW_KEYS}
    law = {k: v for k, v in keys.items() if k in LAW_KEYS}
    return Experiment(**model).replace(**law) if law else Experiment(**model)


def flags(keys):
    return [x for k, v in keys.items() for x in (f"--{k.replace('_', '-')}", v)]


@pytest.mark.parametrize("keys", [STICK_SLIP, PURE_SLIP], ids=["stick-slip", "pure-slip"])
def test_the_orbit_is_steadys_cycle(keys, cli):
    e = belt(keys)
    o = stickslip.orbit(e)
    s = stickslip.steady(e).to_dict()
    assert isinstance(o, stickslip.SelfExcitedOrbit)
    assert o.motion_class == s["class"]
    assert abs(o.cycle_period_tau - s["cycle_period_tau"]) < 1e-8
    for key in ("y_max", "y_min", "stick_fraction"):
        assert abs(getattr(o, key) - s[key]) < 1e-8, key
    # A dimensionless model has no seconds.
    assert o.cycle_period_s is None
    # The trivial multiplier first; the cycle attracts.
    assert o.multipliers.dtype == np.complex128 and o.multipliers[0] == 1
    assert 0 <= o.multipliers[1].real < 1 and o.stability == "stable" and o.stable
    # The same as the command line's JSON, field for field.
    assert o.to_dict() == cli.json("orbit", "--beta", 0, *flags(keys))


def test_a_stick_slip_cycle_and_a_pure_slip_cycle():
    o = stickslip.orbit(belt(STICK_SLIP))
    assert (o.motion_class, o.section) == ("stick-slip-cycle", "stick-onset")
    assert o.multipliers.tolist() == [1, 0]
    assert o.release_y == 1.5 - 2 * 0.05 * 0.3
    assert o.summary.startswith("self-excited cycle, period 7.18283")
    p = stickslip.orbit(belt(PURE_SLIP))
    assert (p.motion_class, p.stick_fraction, p.release_y) == ("pure-slip-cycle", 0.0, None)
    assert 0 < p.multipliers[1].real < 1 and p.multipliers[1].imag == 0
    assert p.sliding_stability == "unstable" and p.sliding_damping < 0


def test_a_mechanical_belts_cycle_has_its_period_in_seconds():
    # m = 0.1 kg, k = 1000 N/m: ω0 = 100 rad/s.
    e = Experiment.mechanics(m=0.1, k=1000, gamma=0.5, F0=2, mu_s=1.4, belt_speed=0.02)
    o = stickslip.orbit(e)
    assert math.isclose(o.cycle_period_s, o.cycle_period_tau / 100, rel_tol=1e-12)


def test_steady_sliding_is_the_equilibrium_with_its_eigenvalues():
    o = stickslip.orbit(Experiment(zeta=0.05, mu_s=1.5, vb=2.0))
    assert o.motion_class == "steady-sliding"
    assert (o.cycle_period_tau, o.multipliers, o.section) == (None, None, None)
    assert o.stability == "stable" and o.sliding_stability == "stable"
    assert o.sliding_equilibrium == 1.0 and o.sliding_damping == 0.1
    for lam in o.sliding_eigenvalues:
        assert abs(lam * lam + o.sliding_damping * lam + 1) < 1e-14
    assert o.sliding_eigenvalues[0].real == o.sliding_growth_rate == -0.05


def test_a_period_is_refused_without_a_drive():
    with pytest.raises(ValueError, match=r"^invalid period = 1: must be left out on a belt without a drive"):
        stickslip.orbit(Experiment(**STICK_SLIP), period=1)
