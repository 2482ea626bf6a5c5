"""stickslip.read_scope, read_amplitudes and fit: records synthesised by the package's exact
solver at R = 80 Ω, U_t = 0.6 V (not the paper's parts), written as Rigol and Keysight exports
with 8-bit quantisation and noise; the fit's to_dict() equals ``stickslip fit --json`` on the
same files, and recovers the parts; bad input raises ValueError naming the file."""

from __future__ import annotations

import math
import pathlib
from typing import List

import numpy as np
import pytest

import stickslip

TRUTH = dict(R=80.0, U_t=0.6, R_D=3.0)


def export(path: pathlib.Path, w: float, beta: float, keysight: bool, seed: int) -> None:
    """1200 samples over 3.4 drive periods of the steady state, quantised to 8 bits with a
    step of uniform noise."""
    exp = stickslip.Experiment.paper(w=w, beta=beta, **TRUTH)
    periods = 3.4
    spp = 1200 / periods
    settle = 60
    run = stickslip.simulate(exp, periods=settle + periods, samples_per_period=int(round(spp)))
    n = 1200
    t = run.t_s[-n:] - run.t_s[-n]
    u, uc = run.u_V[-n:], run.uc_V[-n:]
    rng = np.random.default_rng(seed)

    def q(v: np.ndarray) -> np.ndarray:
        step = 2.5 * np.max(np.abs(v)) / 256
        return np.round((v + 2 * step * (rng.random(len(v)) - 0.5)) / step) * step

    drive, resp = q(u), q(uc) + 0.01  # an offset of the u_C channel
    dt = t[1] - t[0]
    if keysight:
        lines = ["x-axis,1,2", "second,Volt,Volt"]
        lines += [f"{t[k]:.9e},{drive[k]:.6e},{resp[k]:.6e}" for k in range(n)]
    else:
        lines = ["X,CH1,CH2,Start,Increment,", f"Sequence,Volt,Volt,0.000000e+00,{dt:.6e}"]
        lines += [f"{k},{drive[k]:.6e},{resp[k]:.6e}," for k in range(n)]
    path.write_text("\n".join(lines) + "\n")


@pytest.fixture(scope="module")
def records(tmp_path_factory) -> List[pathlib.Path]:
    d = tmp_path_factory.mktemp("records")
    paths = [d / "a.csv", d / "b.csv"]
    export(paths[0], 0.29, 2.6, False, 1)
    export(paths[1], 0.95, 2.14, True, 2)
    return paths


def test_read_scope_gives_arrays_units_and_metadata(records):
    r = stickslip.read_scope(records[0])
    assert r.format == "rigol"
    assert len(r) == 1200 and r.t_s.dtype == np.float64
    assert list(r.channels) == ["CH1", "CH2"]
    assert r.drive_channel == "CH1" and r.response_channel == "CH2"
    assert r.units["CH1"] == "V"
    assert r.periods == 3
    f0 = stickslip.Experiment.paper(**TRUTH).convert()["f0"]
    assert r.freq_Hz == pytest.approx(0.29 * f0, rel=1e-3)
    assert r.sample_interval_s == pytest.approx(r.t_s[1] - r.t_s[0], rel=1e-6)
    assert r.resolution_V["CH1"] is not None and r.resolution_V["CH1"] > 0
    assert np.array_equal(r.drive, r.channels["CH1"])
    k = stickslip.read_scope(str(records[1]), drive="2", response="1")
    assert k.format == "keysight"
    assert (k.drive_channel, k.response_channel) == ("2", "1")


def test_fit_to_dict_equals_the_cli_json(cli, records):
    exp = stickslip.Experiment.paper()
    result = stickslip.fit(exp, data=[str(p) for p in records])
    expected = cli.json("fit", "--preset", "paper", "--data", records[0], "--data", records[1])
    assert result.to_dict() == expected
    # Recovery of the parts that made the records.
    assert result.parameters["resistance"] == pytest.approx(80.0, rel=0.01)
    assert result.parameters["ut"] == pytest.approx(0.6, rel=0.01)
    lo, hi = result.ci95["resistance"]
    assert lo < result.parameters["resistance"] < hi
    assert result.names == ("resistance", "ut")
    assert result.converged
    # Covariance, correlation and standard errors agree with each other.
    s = np.array([result.stderr[n] for n in result.names])
    assert np.allclose(np.diag(result.covariance), s**2, rtol=1e-12)
    assert np.allclose(result.covariance / np.outer(s, s), result.correlation, rtol=1e-9)
    # Residual arrays per record: model − measured, their RMS as reported.
    assert len(result.records) == 2
    for rec in result.records:
        assert np.allclose(rec.residual_V, rec.model_V - rec.measured_V, atol=1e-12)
        assert math.sqrt(np.mean(rec.residual_V**2)) == pytest.approx(rec.rms_residual_V,
                                                                      rel=1e-9)
        assert len(rec.t_s) == 1200 - rec.clipped
    # The fitted experiment carries the fitted values.
    assert result.exp.to_dict()["R"] == result.parameters["resistance"]
    assert result.exp.to_dict()["U_t"] == result.parameters["ut"]
    assert stickslip.steady(result.exp.replace(w=0.95, beta=2.14)).motion_class == "sliding"


def test_progress_counts_iterations_and_its_exception_stops_the_fit(records):
    exp = stickslip.Experiment.paper()
    seen = []
    result = stickslip.fit(exp, data=[str(p) for p in records],
                           progress=lambda done, total: seen.append((done, total)))
    # As every call with progress: polled while the fit runs and told once at the end, the
    # iterations done of the most allowed (two passes of 50).
    assert seen and seen[-1] == (result.iterations, 100)
    assert all(a[0] <= b[0] for a, b in zip(seen, seen[1:]))
    assert result.jacobian == "exact"

    def stop(done, total):
        raise RuntimeError(f"stopped at {done} of {total}")

    with pytest.raises(RuntimeError, match=r"^stopped at \d+ of 100$"):
        stickslip.fit(exp, data=[str(p) for p in records], progress=stop)


def test_records_from_read_scope_and_channel_choice_match_the_cli(cli, records):
    exp = stickslip.Experiment.paper()
    data = [stickslip.read_scope(records[0], drive="CH1", response="CH2"),
            stickslip.read_scope(records[1])]
    per = stickslip.fit(exp, data=data, free="resistance,ut", per_record=True)
    expected = cli.json("fit", "--preset", "paper", "--data", records[0], "--data",
                        records[1], "--per-record")
    assert isinstance(per, list) and [r.to_dict() for r in per] == expected


def test_fit_of_a_table_matches_the_cli(cli, tmp_path):
    exp = stickslip.Experiment.paper(**TRUTH)
    f0 = exp.convert()["f0"]
    lines = ["freq_Hz,U_V,response_V"]
    for w in (0.3, 0.6, 0.95, 1.2, 1.43):
        for u in (1.3, 1.6, 2.0):
            s = stickslip.steady(exp.replace(w=w, beta=u / 0.6))
            lines.append(f"{w * f0:.6f},{u},{s.to_dict()['gain'] * u:.6f}")
    table = tmp_path / "gain.csv"
    table.write_text("\n".join(lines) + "\n")
    t = stickslip.read_amplitudes(table)
    assert len(t) == 15 and t.U_V[0] == 1.3 and t.direction[0] is None
    assert np.isnan(t.A1_V).all()
    result = stickslip.fit(stickslip.Experiment.paper(), data=[t])
    assert result.to_dict() == cli.json("fit", "--preset", "paper", "--gain-table", table)
    assert result.records == [] and len(result.rows) == 15
    assert result.parameters["resistance"] == pytest.approx(80.0, rel=0.01)
    assert result.parameters["ut"] == pytest.approx(0.6, rel=0.01)
    xr = pytest.importorskip("xarray")
    ds = result.to_xarray()
    assert isinstance(ds, xr.Dataset)
    assert np.allclose(ds["residual_V"], ds["model_V"] - ds["measured_V"])


def test_to_xarray_of_records(records):
    xr = pytest.importorskip("xarray")
    result = stickslip.fit(stickslip.Experiment.paper(), data=records)
    ds = result.to_xarray()
    assert isinstance(ds, xr.Dataset)
    n = sum(len(r.t_s) for r in result.records)
    assert ds.sizes["sample"] == n
    assert set(ds["file"].values) == {r.file for r in result.records}
    assert ds.attrs["resistance"] == result.parameters["resistance"]


def test_bad_input_raises_value_error_naming_the_file(tmp_path, records):
    bad = tmp_path / "bad.csv"
    text = records[1].read_text().replace("\n1.", "\n1.,garbage\n1.", 1)
    bad.write_text(text)
    with pytest.raises(ValueError, match=r"bad\.csv: line"):
        stickslip.read_scope(bad)
    with pytest.raises(ValueError, match=r"bad\.csv: line"):
        stickslip.fit(stickslip.Experiment.paper(), data=[bad])
    back = tmp_path / "back.csv"
    back.write_text("t,u,uc\n0,1,1\n2,1,1\n1,1,1\n")
    with pytest.raises(ValueError, match="back.csv"):
        stickslip.read_scope(back)
    gain = tmp_path / "gain.csv"
    gain.write_text("freq_Hz,U_V,response_V,phase\n1,1,1,1\n")
    with pytest.raises(ValueError, match='gain.csv: line 1: unknown column "phase"'):
        stickslip.read_amplitudes(gain)
    with pytest.raises(ValueError, match="missing.csv"):
        stickslip.read_scope(tmp_path / "missing.csv")
    with pytest.raises(ValueError, match='a.csv: no channel "CH7"'):
        stickslip.read_scope(records[0], drive="CH7")
    with pytest.raises(ValueError, match='unknown fit parameter "zeta"'):
        stickslip.fit(stickslip.Experiment.paper(), data=records, free=("zeta",))
    with pytest.raises(ValueError, match="no data"):
        stickslip.fit(stickslip.Experiment.paper(), data=[])


MECHANICS = dict(m=0.5, k=200.0, gamma=2.0, F0=0.3)


def mechanical_export(path: pathlib.Path, w: float, beta: float, seed: int) -> None:
    """A plain CSV ``time_s,F (N),r (m)`` of a mechanical oscillator's steady state: 2400
    samples over 3.4 drive periods, quantised to 8 bits with a step of uniform noise."""
    exp = stickslip.Experiment.mechanics(w=w, beta=beta, **MECHANICS)
    periods = 3.4
    n = 2400
    run = stickslip.simulate(exp, periods=60 + periods, samples_per_period=int(round(n / periods)))
    t = run.t_s[-n:] - run.t_s[-n]
    f, r = run.F_N[-n:], run.r_m[-n:]
    rng = np.random.default_rng(seed)

    def q(v: np.ndarray) -> np.ndarray:
        step = 2.5 * np.max(np.abs(v)) / 256
        return np.round((v + 2 * step * (rng.random(len(v)) - 0.5)) / step) * step

    drive, resp = q(f), q(r) + 1e-4  # an offset of the displacement channel
    lines = ["time_s,F (N),r (m)"]
    lines += [f"{t[k]:.9e},{drive[k]:.6e},{resp[k]:.6e}" for k in range(n)]
    path.write_text("\n".join(lines) + "\n")


def test_a_mechanical_fit_recovers_damping_and_friction_and_matches_the_cli(cli, tmp_path):
    paths = [tmp_path / "slow.csv", tmp_path / "near.csv"]
    mechanical_export(paths[0], 0.45, 2.6, 3)
    mechanical_export(paths[1], 0.95, 2.0, 4)
    start = stickslip.Experiment.mechanics(m=0.5, k=200.0, gamma=1.5, F0=0.4)
    result = stickslip.fit(start, data=paths)
    expected = cli.json("fit", "--mass", 0.5, "--stiffness", 200, "--damping", 1.5,
                        "--friction", 0.4, "--data", paths[0], "--data", paths[1])
    assert result.to_dict() == expected
    assert result.names == ("damping", "friction")
    assert result.units == {"drive": "N", "response": "m"}
    assert result.to_dict()["units"] == {"drive": "N", "response": "m"}
    for name, truth in (("damping", 2.0), ("friction", 0.3)):
        assert result.parameters[name] == pytest.approx(truth, rel=0.01)
        lo, hi = result.ci95[name]
        assert lo <= truth <= hi
    assert result.jacobian == "exact" and result.converged
    assert result.exp.to_dict()["gamma"] == result.parameters["damping"]
    assert result.exp.to_dict()["F0"] == result.parameters["friction"]
    # A circuit's parameter on a mechanical oscillator, and mechanical records on a circuit.
    with pytest.raises(ValueError, match="resistance is not a parameter of a mechanical "
                                         r"oscillator \(its parameters are damping, friction"):
        stickslip.fit(start, data=paths, free="resistance")
    with pytest.raises(ValueError, match="slow.csv: a circuit is fitted to voltages"):
        stickslip.fit(stickslip.Experiment.paper(), data=paths)
