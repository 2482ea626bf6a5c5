"""stickslip.fit of a mechanical oscillator on a belt with the Stribeck law's parameters free:
the committed records of docs/fit.md ("A belt's friction law", made by the test kit's
Runge–Kutta oracle at μs = 1.5, vs = 15 mm/s, η = 0.5 N·s/m), fitted from other starting
values, equal ``stickslip fit --json`` on the same files and cover the truth; a law's
parameter on an oscillator without that law raises ValueError."""

from __future__ import annotations

import pytest

import stickslip
from conftest import ROOT

RECORDS = [ROOT / "examples" / "fit" / "belt" / name for name in ("stick.csv", "fast.csv")]
OSCILLATOR = dict(m=0.5, k=200.0, gamma=0.8, F0=0.3, belt_speed=0.009)
FREE = ["mu-s", "stribeck-speed", "viscous-friction"]
TRUTH = {"mu-s": 1.5, "stribeck-speed": 0.015, "viscous-friction": 0.5}


def test_a_stribeck_belt_fit_recovers_the_law_and_matches_the_cli(cli):
    start = stickslip.Experiment.mechanics(
        **OSCILLATOR, friction_law="stribeck", stribeck_speed=0.0105,
        viscous_friction=0.25, mu_s=1.3)
    result = stickslip.fit(start, data=RECORDS, free=FREE)
    expected = cli.json(
        "fit", "--mass", 0.5, "--stiffness", 200, "--damping", 0.8, "--friction", 0.3,
        "--belt-speed", 0.009, "--friction-law", "stribeck", "--mu-s", 1.3,
        "--stribeck-speed", 0.0105, "--viscous-friction", 0.25,
        "--free", ",".join(FREE), "--data", RECORDS[0], "--data", RECORDS[1])
    assert result.to_dict() == expected
    assert result.names == tuple(FREE)
    assert result.jacobian == "central-differences" and result.converged
    for name, truth in TRUTH.items():
        lo, hi = result.ci95[name]
        assert lo <= truth <= hi, (name, lo, hi)


def test_a_stribeck_parameter_without_the_stribeck_law_raises_value_error():
    start = stickslip.Experiment.mechanics(**OSCILLATOR, mu_s=1.3)
    with pytest.raises(ValueError, match="stribeck-speed is a parameter of the stribeck "
                                         "friction law, and this oscillator's law is coulomb"):
        stickslip.fit(start, data=RECORDS, free="mu-s,stribeck-speed")


UNDRIVEN = ROOT / "examples" / "fit" / "undriven" / "stribeck.csv"


def test_an_undriven_belt_fit_recovers_the_law_and_matches_the_cli(cli):
    """The displacement alone of a self-excited Stribeck belt (docs/fit.md, "An undriven
    belt": the oracle's record at μs = 1.5, vs = 15 mm/s, η = 0.5 N·s/m)."""
    start = stickslip.Experiment.mechanics(
        **OSCILLATOR, friction_law="stribeck", stribeck_speed=0.012,
        viscous_friction=0.3, mu_s=1.4)
    result = stickslip.fit(start, data=[UNDRIVEN], free=FREE)
    expected = cli.json(
        "fit", "--mass", 0.5, "--stiffness", 200, "--damping", 0.8, "--friction", 0.3,
        "--belt-speed", 0.009, "--friction-law", "stribeck", "--mu-s", 1.4,
        "--stribeck-speed", 0.012, "--viscous-friction", 0.3,
        "--free", ",".join(FREE), "--data", UNDRIVEN)
    assert result.to_dict() == expected
    assert result.converged
    record = result.records[0]
    assert record.beta == 0 and record.amplitude_V == 0
    assert record.motion_class == "stick-slip-cycle" and record.periods == 3
    for name, truth in TRUTH.items():
        lo, hi = result.ci95[name]
        assert lo <= truth <= hi, (name, lo, hi)


def test_an_undriven_record_without_a_belt_raises_value_error():
    start = stickslip.Experiment.mechanics(m=0.5, k=200.0, gamma=0.8, F0=0.3, mu_s=1.4)
    with pytest.raises(ValueError, match=r"needs a moving belt \(--belt-speed\)"):
        stickslip.fit(start, data=[UNDRIVEN], free="mu-s")
    with pytest.raises(ValueError, match="has no drive and .* has one"):
        stickslip.fit(stickslip.Experiment.mechanics(**OSCILLATOR, mu_s=1.4),
                      data=[UNDRIVEN, RECORDS[0]], free="mu-s")


REST = ROOT / "examples" / "fit" / "undriven" / "rest.csv"
FAST = ROOT / "examples" / "fit" / "undriven" / "fast.csv"


def test_an_undriven_record_from_rest_shows_the_kinetic_level_and_matches_the_cli(cli):
    """The oracle's Coulomb belt started under the block at rest 0.3 mm behind the spring's
    rest length (docs/fit.md, "A record from rest": γ = 0.8 N·s/m, μs = 1.5, F0 = 0.3 N):
    F0 and μs fitted apart, as ``stickslip fit --from-rest`` does."""
    start = stickslip.Experiment.mechanics(m=0.5, k=200.0, gamma=0.6, F0=0.27,
                                           belt_speed=0.009, mu_s=1.35)
    free = ["friction", "mu-s", "damping"]
    result = stickslip.fit(start, data=[REST], free=free, from_rest=-3e-4)
    expected = cli.json(
        "fit", "--mass", 0.5, "--stiffness", 200, "--damping", 0.6, "--friction", 0.27,
        "--belt-speed", 0.009, "--mu-s", 1.35, "--free", ",".join(free),
        "--from-rest", -3e-4, "--data", REST)
    assert result.to_dict() == expected
    assert result.converged
    for name, truth in {"friction": 0.3, "mu-s": 1.5, "damping": 0.8}.items():
        lo, hi = result.ci95[name]
        assert lo <= truth <= hi, (name, lo, hi)
    assert not any(w["kind"] == "not-identified" for w in result.warnings)
    with pytest.raises(ValueError, match="from_rest is for records of an undriven belt"):
        stickslip.fit(start, data=RECORDS, free=free, from_rest=0.0)


def test_undriven_records_at_two_belt_speeds_match_the_cli(cli):
    start = stickslip.Experiment.mechanics(
        **OSCILLATOR, friction_law="stribeck", stribeck_speed=0.012,
        viscous_friction=0.3, mu_s=1.4)
    result = stickslip.fit(start, data=[UNDRIVEN, FAST], free=FREE,
                           belt_speeds=[None, 0.018])
    expected = cli.json(
        "fit", "--mass", 0.5, "--stiffness", 200, "--damping", 0.8, "--friction", 0.3,
        "--belt-speed", 0.009, "--friction-law", "stribeck", "--mu-s", 1.4,
        "--stribeck-speed", 0.012, "--viscous-friction", 0.3,
        "--free", ",".join(FREE), "--data", UNDRIVEN, "--data", f"{FAST}@0.018")
    assert result.to_dict() == expected
    for name, truth in TRUTH.items():
        lo, hi = result.ci95[name]
        assert lo <= truth <= hi, (name, lo, hi)
    with pytest.raises(ValueError, match="belt_speeds has 1 values for 2 records"):
        stickslip.fit(start, data=[UNDRIVEN, FAST], free=FREE, belt_speeds=[0.018])
