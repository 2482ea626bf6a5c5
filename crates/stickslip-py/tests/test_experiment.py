"""stickslip.Experiment: constructors, attributes, replace, TOML files, convert, errors,
pickling."""

from __future__ import annotations

import copy
import pickle

import numpy as np
import pytest

import stickslip
from stickslip import Experiment

PAPER_TOML = """\
[circuit]
L = "11.5m"
C = 0.02e-6
R = 68
U_t = 0.7
R_D = 3.0
[drive]
U = 1.498
f = "9.97k"
phi = 0.25
[model]
mu_s = 1.2
"""


def test_dimensionless_values_and_defaults():
    e = Experiment(zeta=0.05, w=0.7, beta=1.2)
    assert (e.zeta, e.w, e.beta, e.phi, e.mu_s, e.y0, e.v0) == (0.05, 0.7, 1.2, 0.0, 1.0, 0.0, 0.0)
    assert (e.model, e.system) == ("pwl", "dimensionless")
    # Without ζ: the paper's circuit's damping.
    assert Experiment(w=1.0, beta=1.0).zeta == Experiment.paper().zeta
    # The drive may be left for a sweep or a map.
    assert Experiment(zeta=0.1).w is None and Experiment(zeta=0.1).beta is None


def test_the_paper_circuit_and_the_same_parts_agree():
    paper = Experiment.paper(w=0.7, beta=1.2)
    assert round(paper.zeta, 6) == 0.046816
    parts = Experiment.circuit(L="11.5m", C="20n", R=68, U_t=0.7, R_D=3, w=0.7, beta=1.2)
    assert parts.zeta == paper.zeta and parts.system == "circuit"
    # Different origins describe themselves differently.
    assert str(paper).startswith("circuit (preset paper)")
    assert str(parts).startswith("circuit (flags)")
    assert paper != parts


def test_physical_drive_and_mechanics(cli):
    exp = Experiment.paper(f=9.97e3, U=1.498)
    expected = cli.json("convert", "--preset", "paper", "--freq", "9.97k", "--amplitude", 1.498)
    assert exp.convert() == expected
    mech = Experiment.mechanics(m=2, k=8, gamma=0.4, F0=0.5, F=1, omega=1.8)
    assert (mech.w, mech.beta, mech.system) == (0.9, 2.0, "mechanics")
    expected = cli.json("convert", "--mass", 2, "--stiffness", 8, "--damping", 0.4,
                        "--friction", 0.5, "--amplitude", 1, "--omega", 1.8)
    assert mech.convert() == expected


def test_from_toml_matches_the_tool(cli, tmp_path):
    path = tmp_path / "exp.toml"
    path.write_text(PAPER_TOML)
    exp = Experiment.from_toml(path)
    assert exp.convert() == cli.json("convert", "--config", path)
    assert (exp.phi, exp.mu_s) == (0.25, 1.2)
    assert str(exp).startswith(f"circuit ({path})")
    assert Experiment.from_toml(str(path)) == exp
    # Steady state from the file: the same as the tool's.
    assert stickslip.steady(exp).to_dict() == cli.json("steady", "--config", path)


def test_toml_errors_carry_the_library_message(cli, tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("[circuit]\nL = 1e-3\nQ = 3\n")
    with pytest.raises(ValueError) as raised:
        Experiment.from_toml(path)
    assert str(raised.value) == cli.error("convert", "--config", path)
    assert str(raised.value).startswith(f"{path}, line 3, [circuit] Q: unknown field `Q`")
    with pytest.raises(OSError, match="cannot read experiment file"):
        Experiment.from_toml(tmp_path / "missing.toml")


def test_replace_overlays_and_removes():
    e = Experiment.paper(w=0.7, beta=1.2)
    assert e.replace(beta=2.0).beta == 2.0 and e.replace(beta=2.0).w == 0.7
    # A quantity given in another form replaces the old one.
    f = e.replace(f=1e4)
    assert f.w == pytest.approx(1e4 * 2 * np.pi / 65938.0473395787, rel=1e-12)
    assert "w" not in f.to_dict() and f.to_dict()["f"] == 1e4
    # None removes a value (the drive frequency, in every form).
    assert f.replace(w=None).w is None
    assert e.replace(diode="shockley").model == "shockley"
    assert e.replace(R=100).zeta > e.zeta
    # The original is unchanged.
    assert e.beta == 1.2


def test_values_with_si_prefixes():
    a = Experiment.circuit(L="11.5mH", C="0.02u", R="68ohm", U_t="0.7V", R_D=3)
    b = Experiment.circuit(L=11.5e-3, C=0.02e-6, R=68, U_t=0.7, R_D=3)
    assert a == b and hash(a) == hash(b)


def test_errors_are_value_errors_with_the_library_message():
    cases = [
        (lambda: Experiment(w=-1), "invalid w = -1: must be finite and from 1e-5 to 1e5 (docs/limits.md)"),
        (lambda: Experiment(mu_s=0.5), "invalid mu_s = 0.5: must be finite and from 1 to 1e9 (docs/limits.md)"),
        (lambda: Experiment(zeta=float("nan")), "invalid zeta = NaN: must be finite and from 0 to 1e4 (docs/limits.md)"),
        (lambda: Experiment.circuit(L=1e-3, C=1e-9, R=1, U_t=0.7),
         "a circuit description needs R_D (or use the preset paper)"),
        (lambda: Experiment.paper(zeta=0.1),
         "zeta conflicts with a physical description (ζ follows from its parts); change R instead"),
        (lambda: Experiment(w=1, beta=1).replace(U=1.0),
         "U is a physical value: also describe the system (the preset paper, a circuit or a "
         "mechanical oscillator)"),
        (lambda: Experiment(w=1).replace(diode="shockley"),
         "the Shockley diode model needs a circuit description (e.g. the paper preset)"),
        (lambda: Experiment.paper(L=-1), "invalid L = -1: must be finite and > 0 (henry)"),
        (lambda: Experiment.paper(w=0.7).convert(),
         "missing drive amplitude: give beta (U/U_t), or U with a physical description"),
        (lambda: Experiment(w=1, beta=1).convert(),
         "convert needs a physical description: Experiment.paper(), .circuit(), .shockley(), "
         ".mechanics() or .from_toml()"),
        (lambda: Experiment.paper(L="abc"),
         "invalid L: 'abc' is not a number (plain, or with an SI prefix such as 20n, 11.5m, 9.9k)"),
        (lambda: Experiment.paper(diode="spice"),
         "invalid diode 'spice': must be 'pwl' (exact solver) or 'shockley' (stiff solver)"),
    ]
    for make, message in cases:
        with pytest.raises(ValueError) as raised:
            make()
        assert str(raised.value) == message


def test_unknown_keywords_and_wrong_types_are_type_errors():
    with pytest.raises(TypeError, match="unknown experiment keyword 'Q'"):
        Experiment.paper(Q=3)
    with pytest.raises(TypeError, match="unknown experiment keyword 'frequency'"):
        Experiment.paper(w=0.7).replace(frequency=3)
    with pytest.raises(TypeError, match="w must be a number"):
        Experiment(w=[1, 2])
    with pytest.raises(TypeError, match="not a bool"):
        Experiment(w=True)


def test_pickling_round_trips_every_kind(tmp_path):
    path = tmp_path / "exp.toml"
    path.write_text(PAPER_TOML)
    for e in [
        Experiment(zeta=0.05, w=0.7, beta=1.2, phi=0.3, mu_s=1.5, y0=0.2, v0=-0.1),
        Experiment.paper(w=0.95, beta=2.14),
        Experiment.paper(diode="shockley", Is=1e-8),
        Experiment.mechanics(m=2, k=8, gamma=0.4, F0=0.5, F=1, omega=1.8),
        Experiment.from_toml(path),
        Experiment.paper(),
    ]:
        for protocol in range(2, pickle.HIGHEST_PROTOCOL + 1):
            back = pickle.loads(pickle.dumps(e, protocol=protocol))
            assert back == e and hash(back) == hash(e) and str(back) == str(e)
            assert type(back) is Experiment
        assert copy.deepcopy(e) == e
        assert Experiment.from_json(e.to_json()) == e
        assert Experiment.from_dict(e.to_dict()).to_dict() == e.to_dict()
    # A pickled experiment computes the same.
    e = Experiment.paper(w=0.7, beta=1.2)
    back = pickle.loads(pickle.dumps(e))
    assert stickslip.steady(back).to_dict() == stickslip.steady(e).to_dict()
    with pytest.raises(ValueError, match="not an experiment's JSON"):
        Experiment.from_json("{")


def test_repr_evaluates_back():
    e = Experiment.paper(w=0.7, beta=1.2, diode="pwl")
    assert eval(repr(e), {"stickslip": stickslip}) == e


def test_shockley_constructor():
    s = Experiment.shockley(L=11.5e-3, C=20e-9, R=68, U_t=0.7, w=0.95, beta=2.14)
    assert s.model == "shockley"
    # ζ of the resistance only (the diodes' resistance is in their law).
    assert s.zeta == pytest.approx(68 / 2 * (20e-9 / 11.5e-3) ** 0.5, rel=1e-14)
    assert Experiment.paper(diode="shockley", w=0.95, beta=2.14).zeta == s.zeta
