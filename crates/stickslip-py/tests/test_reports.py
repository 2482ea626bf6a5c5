"""Every result's ``to_dict()`` is the library's report for its computation, with the report's
keys, and equals what the command-line tool writes for the same computation: its JSON
(``steady --json``) or its CSV, cell for cell (each CSV column is the key of the same name).
The report's names also reach the arrays (``result[name]``); the names retired warn
(tests/test_names.py)."""

from __future__ import annotations

import json
import math
from typing import Any, Dict, List

import numpy as np

import stickslip
from stickslip import Experiment

from conftest import read_csv

SWEEP_KEYS = ["value", "w", "beta", "zeta", "mu_s", "direction", "gain", "gain1", "peak", "A1",
              "A3", "class", "stops_per_period", "period", "phase_lag", "f_Hz", "amplitude",
              "y_max", "y_min", "cycle_period_tau", "cycle_period_s", "stick_fraction"]
MAP_KEYS = ["w", "beta", "class", "period", "stops_per_period", "gain"]
BIFURCATION_KEYS = ["value", "y", "v", "direction", "lambda1", "class", "period"]


def cell(value: Any) -> str:
    """A value as the tool's CSV writes it: Rust's `Display` of an f64 (compared as a number),
    an empty cell for None."""
    return "" if value is None else str(value)


def same_cells(values: List[Any], cells: List[str], what: str) -> None:
    """The report's values are the CSV's cells: numbers equal bit for bit, labels equal,
    None an empty cell (NaN: the cell `NaN`)."""
    assert len(values) == len(cells), f"{what}: {len(values)} values, {len(cells)} cells"
    for k, (value, text) in enumerate(zip(values, cells)):
        if value is None:
            assert text in ("", "NaN"), f"{what}[{k}]: None against {text!r}"
        elif isinstance(value, str):
            assert value == text, f"{what}[{k}]: {value!r} != {text!r}"
        else:
            assert float(text) == value, f"{what}[{k}]: {value!r} != {text!r}"


def plain_json(d: Dict[str, Any]) -> Dict[str, Any]:
    """The dict through JSON: what a report must survive unchanged (plain values only)."""
    return json.loads(json.dumps(d, allow_nan=False))


def test_steady_to_dict_is_the_tools_json(cli):
    flags = ["--preset", "paper", "--w", 0.95, "--beta", 2.14]
    expected = cli.json("steady", *flags)
    s = stickslip.steady(Experiment.paper(w=0.95, beta=2.14))
    report = s.to_dict()
    assert list(report) == list(expected)
    assert report == expected == plain_json(report)
    # The trace's columns under the report's names (SteadyTrace: tau, drive, y, v).
    assert len(s.trace.tau) == len(s.trace.drive) == len(s.trace.y) == len(s.trace.v) > 0


def test_simulate_to_dict_is_the_tools_csv(cli, tmp_path):
    flags = ["--preset", "paper", "--w", 0.7, "--beta", 1.2]
    out, events = tmp_path / "trace.csv", tmp_path / "events.csv"
    cli.run("simulate", *flags, "--periods", 3, "--samples-per-period", 50, "--out", out,
            "--events", events)
    table, event_table = read_csv(out), read_csv(events)
    report = stickslip.simulate(Experiment.paper(w=0.7, beta=1.2), 3,
                                samples_per_period=50).to_dict()
    assert list(report) == ["periods", "samples_per_period", "columns", *table, "events"]
    assert report["periods"] == 3 and report["samples_per_period"] == 50
    assert report["columns"] == list(table)
    for name, cells in table.items():
        same_cells(report[name], cells, name)
    assert [list(e) for e in report["events"]] == [["tau", "y", "kind"]] * len(report["events"])
    for name, cells in event_table.items():
        same_cells([e[name] for e in report["events"]], cells, f"event {name}")
    assert report == plain_json(report)


def test_sweep_to_dict_is_the_tools_csv(cli, tmp_path):
    out = tmp_path / "sweep.csv"
    cli.run("sweep", "--zeta", 0.05, "--w", 0.7, "--beta", 1.3, "--over", "mu-s", "--from", 1.0,
            "--to", 2.0, "--steps", 6, "--direction", "both", "--out", out)
    table = read_csv(out)
    values = [float(x) for x in table["mu_s"][:6]]
    result = stickslip.sweep(Experiment(zeta=0.05, w=0.7, beta=1.3), "mu_s", values,
                             direction="both", harmonics=3)
    report = result.to_dict()
    assert report["over"] == "mu_s" and report["direction"] == "both"
    assert all(list(p) == SWEEP_KEYS for p in report["points"])
    for name, cells in table.items():
        column = [p["value" if name == "mu_s" else name] for p in report["points"]]
        same_cells(column, cells, name)
    # The arrays under the report's names.
    assert list(result["direction"]) == list(result.direction) == table["direction"]
    assert list(result["class"]) == list(result.motion_class) == table["class"]
    np.testing.assert_array_equal(result["gain1"], result.gain1)
    np.testing.assert_array_equal(result.A1, result.harmonics[:, 0])
    np.testing.assert_array_equal(result["A3"], result.harmonics[:, 2])
    assert np.all(np.isnan(result.f_Hz))


def test_map_to_dict_is_the_tools_csv(cli, tmp_path):
    out = tmp_path / "map.csv"
    cli.run("phase-diagram", "--preset", "paper", "--w-min", 0.3, "--w-max", 1.5, "--w-steps",
            4, "--beta-min", 0.8, "--beta-max", 3, "--beta-steps", 3, "--out", out)
    table = read_csv(out)
    w = sorted({float(x) for x in table["w"]})
    beta = sorted({float(x) for x in table["beta"]})
    diagram = stickslip.phase_diagram(Experiment.paper(), w=w, beta=beta)
    report = diagram.to_dict()
    assert report["lyapunov"] is False
    assert all(list(p) == MAP_KEYS for p in report["points"])
    assert list(table) == MAP_KEYS
    for name, cells in table.items():
        same_cells([p[name] for p in report["points"]], cells, name)
    assert list(diagram["class"].ravel()) == table["class"]
    assert report == plain_json(report)


def test_map_to_dict_with_exponents_is_the_tools_csv(cli, tmp_path):
    out = tmp_path / "map.csv"
    flags = ["--zeta", 0, "--mu-s", 3, "--w-min", 0.25, "--w-max", 0.35, "--w-steps", 2,
             "--beta-min", 9, "--beta-max", 9, "--beta-steps", 1, "--lyapunov-periods", 200]
    cli.run("phase-diagram", *flags, "--color", "lambda1", "--out", out)
    table = read_csv(out)
    diagram = stickslip.phase_diagram(Experiment(zeta=0.0, mu_s=3.0), w=[0.25, 0.35], beta=[9.0],
                                      lyapunov=True, lyapunov_periods=200)
    report = diagram.to_dict()
    assert report["lyapunov"] is True
    assert all(list(p) == MAP_KEYS + ["lambda1", "lambda1_error"] for p in report["points"])
    for name, cells in table.items():
        same_cells([p[name] for p in report["points"]], cells, name)
    assert diagram["lambda1"] is diagram.lambda1
    assert diagram["lambda1_error"] is diagram.lambda1_error


def test_bifurcation_to_dict_is_the_tools_csv(cli, tmp_path):
    out = tmp_path / "bif.csv"
    cli.run("bifurcation", "--zeta", 0, "--mu-s", 3, "--beta", 9, "--over", "w", "--from", 0.25,
            "--to", 0.35, "--steps", 3, "--points", 8, "--transient", 100, "--first-transient",
            500, "--out", out)
    table = read_csv(out)
    w = [float(x) for x in table["w"]]
    values = w[: len(w) // 2][::8]
    d = stickslip.bifurcation(Experiment(zeta=0.0, beta=9.0, mu_s=3.0), "w", values, points=8,
                              transient=100, first_transient=500)
    report = d.to_dict()
    assert report["parameter"] == "w"
    assert all(list(p) == BIFURCATION_KEYS for p in report["points"])
    for name, cells in table.items():
        same_cells([p["value" if name == "w" else name] for p in report["points"]], cells, name)
    # The per-value arrays under the report's names.
    assert list(d["direction"]) == list(d.direction)
    np.testing.assert_array_equal(d["lambda1"], d.lambda1)
    assert list(d["class"]) == list(d.motion_class)
    assert all(math.isfinite(p["value"]) for p in report["points"])
