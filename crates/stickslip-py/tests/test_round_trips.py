"""Round trips and reach: a map saved to netCDF comes back whole (PhaseDiagram.from_xarray),
a branch as a dataset, a physical experiment swept over its drive in Hz or volts."""

from __future__ import annotations

import numpy as np
import pytest

import stickslip
from stickslip import Experiment

xr = pytest.importorskip("xarray", reason="the round trips need xarray (a test extra)")
pytest.importorskip("netCDF4", reason="the round trips need netCDF4 (the netcdf extra)")


def assert_same_map(a: stickslip.PhaseDiagram, b: stickslip.PhaseDiagram) -> None:
    assert a.dims == b.dims and a.experiment == b.experiment and a.options == b.options
    for d in a.dims:
        assert a.coords[d].tobytes() == b.coords[d].tobytes(), d
    for name in stickslip.PhaseDiagram.FIELDS + stickslip.PhaseDiagram.EXPONENT_FIELDS:
        x, y = getattr(a, name), getattr(b, name)
        if x is None:
            assert y is None, name
            continue
        assert x.dtype == y.dtype, (name, x.dtype, y.dtype)
        assert x.tobytes() == y.tobytes(), name


@pytest.mark.parametrize("make", [
    lambda: stickslip.phase_diagram(Experiment.paper(mu_s=1.5), w=np.linspace(0.1, 2.5, 12),
                                    beta=np.linspace(0.5, 4, 9), max_periods=300),
    lambda: stickslip.phase_diagram(Experiment(zeta=0, mu_s=3), lyapunov=True,
                                    w=np.linspace(0.2, 0.6, 8), beta=np.linspace(3, 14, 7)),
    lambda: stickslip.phase_diagram(Experiment.mechanics(m=2, k=8, gamma=0.4, F0=0.5,
                                                         omega=1.8),
                                    beta=[1.0, 2.5], mu_s=[1.0, 1.5, 2.0]),
], ids=["circuit, no period somewhere", "exponents", "mechanics over beta and mu_s"])
def test_a_map_saved_to_netcdf_comes_back_whole(tmp_path, make):
    m = make()
    path = tmp_path / "map.nc"
    m.to_xarray().to_netcdf(path)
    with xr.open_dataset(path) as ds:
        assert ds["period"].dtype == np.int16
        back = stickslip.PhaseDiagram.from_xarray(ds)
    assert_same_map(back, m)
    # And from the dataset itself, without a file.
    assert_same_map(stickslip.PhaseDiagram.from_xarray(m.to_xarray()), m)


def test_a_map_with_no_period_found_keeps_minus_one(tmp_path):
    m = stickslip.phase_diagram(Experiment(zeta=0, mu_s=3), w=[0.33, 0.42], beta=[9.0],
                                max_periods=200, lyapunov_periods=0)
    assert -1 in m.period
    path = tmp_path / "map.nc"
    m.to_xarray().to_netcdf(path)
    with xr.open_dataset(path) as ds:
        assert ds["period"].dtype == np.int16 and -1 in ds["period"].values
    # A file of an older version, with -1 as the _FillValue (read back as float with NaN).
    old = m.to_xarray()
    old["period"].encoding["_FillValue"] = np.int16(-1)
    old.to_netcdf(tmp_path / "old.nc")
    with xr.open_dataset(tmp_path / "old.nc") as ds:
        assert ds["period"].dtype.kind == "f"
        assert stickslip.PhaseDiagram.from_xarray(ds).period.tobytes() == m.period.tobytes()


def test_a_stack_of_maps_comes_back(tmp_path):
    pytest.importorskip("distributed")
    import stickslip.dask

    stack = stickslip.dask.sweep_grid(Experiment.paper(), chunks=(5, 5), mu_s=[1.0, 1.5],
                                      w=np.linspace(0.1, 2.5, 10), beta=np.linspace(0.5, 4, 6))
    stack.to_xarray().to_netcdf(tmp_path / "stack.nc")
    with xr.open_dataset(tmp_path / "stack.nc") as ds:
        assert_same_map(stickslip.PhaseDiagram.from_xarray(ds), stack)


def test_what_is_not_a_map_is_refused():
    with pytest.raises(ValueError, match="not a map of stickslip"):
        stickslip.PhaseDiagram.from_xarray(xr.Dataset({"x": ("a", [1, 2])}))


def test_a_branch_as_a_dataset():
    exp = Experiment.paper(mu_s=1.5, w=0.9, y0=0.25, v0=2.1)
    b = stickslip.continuation(exp, "beta", 1.45, 1.25)
    ds = b.to_xarray()
    assert ds["y"].dims == ("point",) and len(ds["point"]) == len(b)
    assert np.array_equal(ds["beta"].values, b.value)
    assert np.array_equal(ds["arclength"].values, b.arclength)
    assert np.array_equal(ds["U_V"].values, b.value * exp.scales()["force"])
    assert ds["stable"].attrs["flag_meanings"] == "unstable stable"
    assert list(ds["stable"].values) == [int(s) for s in b.stable]
    for name in ("amplitude", "mu1_re", "mu2_im", "period", "turns", "stops_per_period"):
        assert np.array_equal(ds[name].values, getattr(b, name)), name
    kinds = [str(k) for k in ds["special_kind"].values]
    assert kinds == [s["kind"] for s in b.special] and "fold" in kinds
    assert np.array_equal(ds["special_value"].values, [s["value"] for s in b.special])
    assert ds.attrs["end_text"] == b.end_text and ds.attrs["mu_s"] == 1.5
    assert "beta" not in ds.attrs


def test_a_physical_experiment_sweeps_over_its_drive_in_hz_and_volts():
    exp = Experiment.paper(U=2.5)
    hz = np.linspace(5e3, 15e3, 9)
    by_hz = stickslip.sweep(exp, "f", hz, direction="up")
    w = np.array([exp.replace(f=f).w for f in hz])
    by_w = stickslip.sweep(exp, "w", w, direction="up")
    assert by_hz.over == "w"
    assert by_hz.value.tobytes() == w.tobytes()
    assert by_hz.gain.tobytes() == by_w.gain.tobytes()
    np.testing.assert_allclose(by_hz.f_Hz, hz, rtol=1e-12)
    volts = stickslip.sweep(Experiment.paper(f=9.97e3), "U", [1.0, 1.5, 2.0], direction="up")
    assert volts.over == "beta"
    np.testing.assert_allclose(volts.beta, np.array([1.0, 1.5, 2.0]) / 0.7, rtol=1e-12)
    with pytest.raises(ValueError, match="a sweep over 'f' needs a physical experiment"):
        stickslip.sweep(Experiment(beta=2), "f", [1e3])
    with pytest.raises(ValueError, match="f"):
        stickslip.sweep(exp, "f", [-1.0])
