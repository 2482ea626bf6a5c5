"""stickslip.curve against `stickslip curve`: the CSV's columns and numbers, the JSON summary,
the xarray and pandas shapes, the errors, Ctrl-C."""

from __future__ import annotations

import os
import signal
import threading

import numpy as np
import pytest

import stickslip
from stickslip import Experiment

from conftest import read_csv

# The grazing of the paper's sliding orbit (μs = 1) at w = 1.2: the exact stick-slip boundary.
GRAZING = (Experiment.paper(w=1.2, beta=3.0), ("grazing", "beta", 0.5, "w", 1.2, 1.3),
           ["--preset", "paper", "--w", 1.2, "--beta", 3])
# The fold of the orbit with two stops at μs = 1.5, both ways from w = 0.9.
FOLD = (Experiment.paper(mu_s=1.5, w=0.9, beta=1.45, y0=0.25, v0=2.1),
        ("fold", "beta", 1.2, "w", 0.8, 1.0),
        ["--preset", "paper", "--mu-s", 1.5, "--w", 0.9, "--beta", 1.45, "--y0", 0.25, "--v0",
         2.1])


def flags(spec):
    follow, vary, vary_to, over, start, to = spec
    return ["--follow", follow, "--vary", vary, "--vary-to", vary_to, "--over", over,
            "--from", start, "--to", to]


@pytest.mark.parametrize("case", [GRAZING, FOLD], ids=["grazing", "fold"])
def test_the_columns_are_the_tools_csv(cli, tmp_path, case):
    experiment, spec, model = case
    path = tmp_path / "c.csv"
    expected_json = cli.json("curve", *model, *flags(spec), "--out", path)
    csv = read_csv(path)
    c = stickslip.curve(experiment, *spec[:4], start=spec[4], to=spec[5])
    # The same columns in the same order, from the library's table.
    assert c.columns == list(csv)
    assert c.columns[:2] == [spec[3], spec[1]] and c.over == spec[3] and c.vary == spec[1]
    assert len(c) == len(csv["y"]) > 10
    for name, text in csv.items():
        column = c[name]
        if column.dtype.kind in "iu":
            assert [str(x) for x in column.tolist()] == text, name
        elif column.dtype.kind == "f":
            expected = np.array([float(x) if x else np.nan for x in text])
            # Bit for bit: the package and the tool run the same library code.
            np.testing.assert_array_equal(column, expected, err_msg=name)
        else:
            assert column.tolist() == text, name
    assert c.period.dtype == np.int64 and c.turns.dtype == np.int64
    assert set(c.stability) <= {"stable", "unstable", "neutral"}
    assert [s for s in c.special if s] == ["start"]
    # The summary is the tool's JSON.
    assert c.to_dict() == expected_json
    assert c.end == expected_json["end"] and c.end_text == expected_json["end_text"]
    assert c.start == expected_json["start"] and c.codim2 == expected_json["codim2"]
    assert c.special[c.start["index"]] == "start"
    np.testing.assert_array_equal(c.multipliers[:, 0].real, c.mu1_re)


def test_the_grazing_curve_is_the_exact_boundary():
    experiment, spec, _ = GRAZING
    c = stickslip.curve(experiment, *spec[:4], start=spec[4], to=spec[5])
    assert c.follow == "grazing" and c.border == "turn-at-limit"
    _, exact = stickslip.boundary(experiment.zeta, c.w)
    assert np.max(np.abs(c.beta - exact)) < 1e-8
    assert c.w.min() == 1.2 and c.w.max() == pytest.approx(1.3, abs=1e-12)


def test_xarray_and_pandas_shapes(tmp_path, cli):
    experiment, spec, model = FOLD
    c = stickslip.curve(experiment, *spec[:4], start=spec[4], to=spec[5])
    ds = c.to_xarray()
    assert dict(ds.sizes) == {"point": len(c), "codim2": len(c.codim2)}
    # The two parameters and the arclength are coordinates, the rest of the CSV's columns
    # are variables; a physical experiment has the drive's frequency in Hz beside w.
    assert {"w", "beta", "arclength", "f_Hz", "U_V"} <= set(ds.coords)
    assert set(ds.data_vars) >= set(c.columns) - {"w", "beta", "arclength"}
    np.testing.assert_array_equal(ds["w"].values, c.w)
    np.testing.assert_array_equal(ds["largest_multiplier"].values, c.largest_multiplier)
    np.testing.assert_allclose(ds["f_Hz"].values, c.w * experiment.scales()["f0"], rtol=1e-15)
    assert ds.attrs["follow"] == "fold" and ds.attrs["orbit_period"] == c.orbit_period == c.to_dict()["period"]
    assert ds.attrs["end_text"] == c.end_text
    assert ds["codim2_kind"].dims == ("codim2",) and "codim2_w" in ds
    # pandas reads the tool's CSV to the same frame.
    pd = pytest.importorskip("pandas")
    path = tmp_path / "f.csv"
    cli.run("curve", *model, *flags(spec), "--out", path)
    frame = c.to_pandas()
    assert list(frame.columns) == c.columns
    pd.testing.assert_frame_equal(frame, pd.read_csv(path, keep_default_na=False,
                                                     dtype={"special": str}),
                                  check_exact=True)


def test_errors_name_the_value(cli):
    experiment, spec, model = FOLD
    # No period doubling between β = 1.45 and 1.44: the tool's one line.
    message = cli.error("curve", *model, *flags(("period-doubling", "beta", 1.44, "w", 0.8, 1)))
    with pytest.raises(ValueError) as caught:
        stickslip.curve(experiment, "period-doubling", "beta", 1.44, "w", start=0.8, to=1.0)
    assert str(caught.value) == message
    assert "no period doubling" in message and "beta from 1.45 towards 1.44" in message
    g = GRAZING[0]
    for kwargs, words in [
        (dict(follow="grazing", vary="beta", vary_to=0.5, over="w", start=1, to=1),
         "invalid to = 1"),
        # The two parameters named by their keywords, not the command line's flags.
        (dict(follow="grazing", vary="w", vary_to=0.5, over="w", start=1, to=2),
         r"^invalid vary: must differ from over$"),
        # The Coulomb model has no Neimark-Sacker point (docs/bifurcation.md).
        (dict(follow="neimark-sacker", vary="beta", vary_to=0.5, over="w", start=1, to=2),
         "has no Neimark–Sacker point"),
        (dict(follow="grazing", vary="beta", vary_to=3, over="w", start=1, to=2), "vary_to"),
        (dict(follow="grazing", vary="beta", vary_to=0.5, over="w", start=1.5, to=2),
         "between"),
        (dict(follow="touch", vary="beta", vary_to=0.5, over="w", start=1, to=2),
         "invalid follow 'touch'"),
        (dict(follow="grazing", vary="gamma", vary_to=0.5, over="w", start=1, to=2),
         "unknown parameter 'gamma'"),
        (dict(follow="grazing", vary="beta", vary_to=0.5, over="w", start=1, to=2,
              max_step=0), "max_step"),
        (dict(follow="grazing", vary="beta", vary_to=0.5, over="w", start=1, to=2,
              max_points=1), "max_points"),
    ]:
        with pytest.raises(ValueError, match=words):
            stickslip.curve(g, **kwargs)
    # Shockley diodes are refused as the tool refuses them.
    shockley = Experiment.paper(diode="shockley", w=1.2, beta=3.0)
    with pytest.raises(ValueError, match="piecewise-linear"):
        stickslip.curve(shockley, "grazing", "beta", 0.5, "w", start=1.0, to=2.0)
    with pytest.raises(TypeError, match="max_points must be an integer"):
        stickslip.curve(g, "grazing", "beta", 0.5, "w", start=1, to=2, max_points=10.0)


def test_progress_and_ctrl_c():
    seen = []
    experiment, spec, _ = GRAZING
    c = stickslip.curve(experiment, *spec[:4], start=spec[4], to=spec[5],
                        progress=lambda done, total: seen.append((done, total)))
    assert seen and seen[-1][0] >= len(c) - 1 and all(t > 0 for _, t in seen)
    # A grazing curve of thousands of small steps (half a minute): Ctrl-C stops it.
    assert threading.current_thread() is threading.main_thread()
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            stickslip.curve(Experiment(zeta=0, mu_s=3, w=0.27, beta=9), "grazing", "w", 0.34,
                            "beta", start=8.5, to=9.5)
    finally:
        timer.cancel()
