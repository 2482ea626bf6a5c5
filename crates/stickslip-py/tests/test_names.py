"""One name per quantity: the result types take their columns from the library's report tables
(``_core.MAP_COLUMNS`` and the others, the CSV headers of the command-line tool), and every
name retired still works, with a ``DeprecationWarning`` that gives the name now."""

from __future__ import annotations

import numpy as np
import pytest

import stickslip
import stickslip._common
from stickslip import Experiment, _core

from conftest import read_csv

CHAOTIC = dict(zeta=0.0, mu_s=3.0, w=0.33, beta=9.0)


def same(old, new) -> bool:
    if isinstance(new, np.ndarray):
        return np.array_equal(np.asarray(old), new, equal_nan=new.dtype.kind == "f")
    return old == new or (old != old and new != new)


def retired(obj, pairs):
    """Each retired attribute warns, names its successor, and gives the same value."""
    for old, new in pairs:
        with pytest.warns(DeprecationWarning, match=rf"\.{old} is deprecated: its name is now "
                                                    rf"{new}"):
            value = getattr(obj, old)
        assert same(value, getattr(obj, new)), (old, new)


def retired_keys(obj, pairs):
    for old, new in pairs:
        with pytest.warns(DeprecationWarning, match=rf'\["{old}"\] is deprecated'):
            value = obj[old]
        assert same(value, obj[new]), (old, new)


def test_the_tables_columns_are_the_tools_csv_headers(cli, tmp_path):
    cli.run("phase-diagram", "--w-steps", 2, "--beta-steps", 2, "--out", tmp_path / "m.csv")
    assert list(read_csv(tmp_path / "m.csv")) == list(_core.MAP_COLUMNS)
    cli.run("phase-diagram", "--zeta", 0, "--mu-s", 3, "--w-steps", 2, "--beta-steps", 1,
            "--beta-min", 9, "--beta-max", 9, "--lyapunov-periods", 200, "--color", "lambda1",
            "--out", tmp_path / "l.csv")
    assert (list(read_csv(tmp_path / "l.csv"))
            == list(_core.MAP_COLUMNS) + list(_core.MAP_EXPONENT_COLUMNS))
    cli.run("sweep", "--zeta", 0.05, "--beta", 2, "--over", "w", "--from", 0.8, "--to", 1,
            "--steps", 2, "--out", tmp_path / "s.csv")
    assert list(read_csv(tmp_path / "s.csv")) == list(_core.SWEEP_COLUMNS)
    assert set(_core.SWEEP_COLUMNS) <= set(stickslip._common.SWEEP_COLUMNS)
    cli.run("bifurcation", "--zeta", 0, "--mu-s", 3, "--beta", 9, "--over", "w", "--from", 0.3,
            "--to", 0.31, "--steps", 2, "--points", 4, "--out", tmp_path / "b.csv")
    assert list(read_csv(tmp_path / "b.csv")) == ["w"] + list(_core.BIFURCATION_COLUMNS)
    assert list(_core.BIFURCATION_FIELDS) == ["value"] + list(_core.BIFURCATION_COLUMNS)
    cli.run("basins", "--zeta", 0, "--mu-s", 3, "--w", 0.6, "--beta", 3.269, "--y0-min", -8,
            "--y0-max", 8, "--v0-min", -8, "--v0-max", 8, "--steps", 2,
            "--out", tmp_path / "a.csv")
    assert list(read_csv(tmp_path / "a.csv")) == list(_core.BASIN_COLUMNS)
    assert "class" in _core.BASIN_COLUMNS and "lambda1" in _core.BIFURCATION_COLUMNS


def test_steady_state_names():
    s = stickslip.steady(Experiment(**CHAOTIC))
    assert s.motion_class == "chaotic" and s.lambda1 is not None
    assert s.gain1 is not None and s.gain1 == s.harmonics[0] / s.beta
    retired(s, [("motion", "motion_class"), ("stops_per_cycle", "stops_per_period"),
                ("lambda_per_tau", "lambda1"), ("error_per_tau", "lambda1_error"),
                ("lambda_per_period", "lambda1_per_period"),
                ("error_per_period", "lambda1_error_per_period")])
    report = s.to_dict()
    for name in ("class", "stops_per_period", "gain", "gain1", "lambda1", "lambda1_error"):
        assert name in report, name
    for name in ("stops_per_cycle", "lambda_per_tau", "error_per_tau"):
        assert name not in report, name


def test_undecided_is_one_name_everywhere():
    """A motion not decided within the budget is 'undecided' as a steady state (the paper's
    non-periodic class, 'nonperiodic-stick' before) and as an attractor ('unsettled' before)."""
    assert "undecided" in stickslip.MOTION_CLASSES and "undecided" in stickslip.ATTRACTOR_KINDS
    assert "nonperiodic-stick" not in stickslip.MOTION_CLASSES
    assert "unsettled" not in stickslip.ATTRACTOR_KINDS
    s = stickslip.steady(Experiment(**CHAOTIC), lyapunov_periods=0)
    assert s.motion_class == "undecided" and s.period is None


def test_sweep_names():
    r = stickslip.sweep(Experiment.paper(beta=2.0), "w", [0.8, 0.9], harmonics=3)
    assert list(r.direction) == ["up", "up", "down", "down"]
    np.testing.assert_array_equal(r.gain1, r.A1 / r.beta)
    retired(r, [("leg", "direction"), ("motion", "class_code"),
                ("stops_per_cycle", "stops_per_period")])
    retired_keys(r, [("leg", "direction"), ("motion", "class_code")])
    with pytest.warns(DeprecationWarning, match=r"motion_labels\(\) is deprecated"):
        assert list(r.motion_labels()) == list(r.motion_class)
    assert list(r.motion_class) == list(np.asarray(r.labels)[r.class_code])
    ds = r.to_xarray()
    assert "motion_class" in ds and "gain1" in ds and "stops_per_period" in ds
    assert ds["gain"].dims[0] == "direction" and "leg" not in ds.dims


def test_map_names():
    m = stickslip.phase_diagram(Experiment(zeta=0.0, mu_s=3.0), w=[0.25, 0.33], beta=[9.0],
                                lyapunov=True, lyapunov_periods=200)
    retired(m, [("motion", "class_code"), ("stops_per_cycle", "stops_per_period"),
                ("lyapunov", "lambda1"), ("lyapunov_error", "lambda1_error"),
                ("lambda_error", "lambda1_error")])
    retired_keys(m, [("lambda", "lambda1"), ("lambda_error", "lambda1_error"),
                     ("motion", "class_code"), ("lyapunov", "lambda1")])
    with pytest.warns(DeprecationWarning, match=r"motion_labels\(\) is deprecated"):
        m.motion_labels()
    points = m.to_dict()["points"]
    assert all(list(p) == list(_core.MAP_COLUMNS) + list(_core.MAP_EXPONENT_COLUMNS)
               for p in points)
    assert [p["class"] for p in points] == list(m.motion_class.ravel())
    ds = m.to_xarray()
    assert {"motion_class", "lambda1", "lambda1_error", "stops_per_period"} <= set(ds)
    assert not {"motion", "lyapunov", "stops_per_cycle"} & set(ds)


def test_bifurcation_basin_orbit_and_lyapunov_names():
    e = Experiment(zeta=0.0, beta=9.0, mu_s=3.0)
    d = stickslip.bifurcation(e, "w", [0.25, 0.33], direction="up", points=20)
    retired(d, [("leg", "direction"), ("exponent", "lambda1"),
                ("exponent_error", "lambda1_error"), ("kind", "class_code")])
    retired_keys(d, [("lambda", "lambda1")])
    with pytest.warns(DeprecationWarning, match=r"kind_labels\(\) is deprecated"):
        assert list(d.kind_labels()) == list(d.motion_class)
    assert all(list(p) == list(_core.BIFURCATION_FIELDS) for p in d.to_dict()["points"])
    ds = d.to_xarray()
    assert {"lambda1", "motion_class"} <= set(ds) and "direction" in ds.dims

    b = stickslip.basins(Experiment(zeta=0.0, w=0.6, beta=3.269, mu_s=3.0), y0=(-8, 8),
                         v0=(-8, 8), steps=4)
    retired(b, [("kind", "class_code"), ("unsettled", "undecided")])
    with pytest.warns(DeprecationWarning, match=r"kind_labels\(\) is deprecated"):
        b.kind_labels()
    report = b.to_dict()
    assert "undecided" in report and "undecided_fraction" in report
    assert all({"class", "lambda1"} <= set(a) and "kind" not in a
               for a in report["attractors"])

    o = stickslip.orbit(Experiment(**CHAOTIC), period=1, transient=500)
    retired(o, [("exponent_per_tau", "lambda1"), ("exponent_per_period", "lambda1_per_period")])
    c = stickslip.lyapunov(Experiment(**CHAOTIC), transient=100, periods=400)
    retired(c, [("lambda_per_tau", "lambda1"), ("error_per_tau", "lambda1_error"),
                ("lambda_per_period", "lambda1_per_period"),
                ("error_per_period", "lambda1_error_per_period"),
                ("lambda2_per_tau", "lambda2"), ("lambda2_error_per_tau", "lambda2_error")])


def test_theory_names_its_gain_of_the_fundamental_gain1():
    t = stickslip.theory(Experiment(zeta=0.0468, w=0.95, beta=2.14))
    assert "gain1" in t["paper"] and "gain1" in t["exact"] and "gain" not in t["paper"]
    assert t["exact"]["gain1"] == t["exact"]["A1"] / 2.14
