"""stickslip.sweep against `stickslip sweep`, stickslip.phase_diagram against `stickslip
phase-diagram`; misaligned inputs; xarray; Ctrl-C; the GIL."""

from __future__ import annotations

import inspect
import sys
import threading
import time

import numpy as np
import pytest

import stickslip
from stickslip import Experiment, _core

from conftest import assert_runs_beside, assert_same, interrupt_after, numbers, read_csv



def misaligned(values) -> np.ndarray:
    """A float64 array whose data starts one byte past an 8-byte boundary, as numpy arrays
    unpickled from pickle-5 buffers may on Dask workers."""
    values = np.asarray(values, dtype=np.float64)
    raw = np.zeros(values.nbytes + 16, dtype=np.uint8)
    start = 1 if raw.ctypes.data % 8 == 0 else 9 - raw.ctypes.data % 8
    a = raw[start:start + values.nbytes].view(np.float64)
    a[:] = values
    assert not a.flags.aligned
    return a


@pytest.mark.parametrize("over", ["w", "mu_s"])
def test_sweep_is_the_tools_csv(cli, tmp_path, over):
    out = tmp_path / "sweep.csv"
    if over == "w":
        flags = ["--preset", "paper", "--beta", 3.61, "--over", "w", "--from", 0.5, "--to", 1.5,
                 "--steps", 21]
        experiment = Experiment.paper(beta=3.61)
    else:
        flags = ["--zeta", 0.05, "--w", 0.7, "--beta", 1.3, "--over", "mu-s", "--from", 1.0,
                 "--to", 2.0, "--steps", 11]
        experiment = Experiment(zeta=0.05, w=0.7, beta=1.3)
    cli.run("sweep", *flags, "--direction", "both", "--out", out)
    table = read_csv(out)
    values = numbers(table[over])[: len(table[over]) // 2]
    # The tool reports A1 and A3 and so asks for 3 harmonics (the count sets the spectrum's
    # sampling, so the same count gives the same numbers).
    s = stickslip.sweep(experiment, over, values, direction="both", harmonics=3)
    assert len(s) == len(table["w"]) == 2 * len(values)
    assert list(s.direction) == table["direction"]
    assert list(s.motion_class) == table["class"]
    for name in ("w", "beta", "gain", "gain1", "stops_per_period"):
        assert_same(getattr(s, name), numbers(table[name]), name)
    assert_same(s.harmonics[:, 0], numbers(table["A1"]), "A1")
    assert_same(s.harmonics[:, 2], numbers(table["A3"]), "A3")
    assert_same(s.value, numbers(table[over]), over)


def test_sweep_directions_and_xarray():
    values = np.linspace(0.5, 1.5, 9)
    both = stickslip.sweep(Experiment.paper(beta=3.61), "w", values)
    up = stickslip.sweep(Experiment.paper(beta=3.61), "w", values, direction="up")
    down = stickslip.sweep(Experiment.paper(beta=3.61), "w", values, direction="down")
    assert_same(both.gain[:9], up.gain, "up leg")
    assert list(down.value) == list(values[::-1])
    ds = both.to_xarray()
    assert ds["gain"].dims == ("direction", "w")
    assert list(ds["direction"].values) == ["up", "down"]
    # The down leg is put in the order of the values.
    assert_same(ds["gain"].sel(direction="down").values, both.gain[9:][::-1], "down leg")
    assert_same(ds["w"].values, values, "w")
    assert ds["w"].attrs["long_name"] == stickslip.PARAMETERS["w"] and ds["w"].attrs["units"] == "1"
    assert ds["harmonics"].dims == ("direction", "w", "harmonic")
    assert ds.attrs["beta"] == 3.61 and ds.attrs["stickslip_version"] == stickslip.__version__
    with pytest.raises(ValueError, match="^invalid direction 'sideways'"):
        stickslip.sweep(Experiment.paper(beta=3.61), "w", values, direction="sideways")
    with pytest.raises(ValueError, match="^unknown parameter 'phi'"):
        stickslip.sweep(Experiment.paper(beta=3.61), "phi", values)
    with pytest.raises(ValueError, match=r"^invalid w = 0: must be finite and from 1e-5 to 1e5 \(docs/limits\.md\)$"):
        stickslip.sweep(Experiment.paper(beta=3.61), "w", [0.5, 0.0])


W60 = ["--w-min", 0.1, "--w-max", 2.5, "--w-steps", 60]
BETA40 = ["--beta-min", 0.5, "--beta-max", 4, "--beta-steps", 40]


@pytest.fixture(scope="module")
def tool_map(cli, tmp_path_factory):
    """The tool's 60 × 40 map of the paper's circuit: its axes and its columns."""
    out = tmp_path_factory.mktemp("map") / "map.csv"
    cli.run("phase-diagram", "--preset", "paper", *W60, *BETA40, "--out", out)
    table = read_csv(out)
    w = numbers(table["w"]).reshape(60, 40)
    beta = numbers(table["beta"]).reshape(60, 40)
    return w[:, 0].copy(), beta[0].copy(), table


def test_map_is_the_tools_csv(tool_map):
    w, beta, table = tool_map
    m = stickslip.phase_diagram(Experiment.paper(), w=w, beta=beta)
    assert m.dims == ("w", "beta") and m.class_code.shape == (60, 40)
    assert m.class_code.dtype == np.int8 and m.motion_class.shape == (60, 40)
    # Same classes at every point of the 60 × 40 map.
    assert list(m.motion_class.ravel()) == table["class"]
    period = np.array([int(p) if p else -1 for p in table["period"]]).reshape(60, 40)
    assert np.array_equal(m.period, period)
    assert_same(m.stops_per_period, numbers(table["stops_per_period"]).reshape(60, 40), "stops")
    assert_same(m.gain, numbers(table["gain"]).reshape(60, 40), "gain")
    assert set(m.counts().values()) != {0} and sum(m.counts().values()) == 2400
    # Several classes occur: the comparison means something.
    assert sum(1 for v in m.counts().values() if v) >= 3


def test_keyword_order_gives_the_axes(tool_map):
    w, beta, _ = tool_map
    a = stickslip.phase_diagram(Experiment.paper(), w=w[:12], beta=beta[:9])
    b = stickslip.phase_diagram(Experiment.paper(), beta=beta[:9], w=w[:12])
    assert b.dims == ("beta", "w") and b.motion_class.shape == (9, 12)
    for name in stickslip.PhaseDiagram.FIELDS:
        assert np.array_equal(getattr(a, name), getattr(b, name).T), name


def test_any_two_parameters_agree_with_steady_states():
    e = Experiment(w=0.8, beta=1.6)
    zeta = np.array([0.01, 0.05, 0.2])
    mu_s = np.array([1.0, 1.3, 2.0, 3.0])
    m = stickslip.phase_diagram(e, zeta=zeta, mu_s=mu_s, threads=1)
    for i, z in enumerate(zeta):
        for j, mu in enumerate(mu_s):
            s = stickslip.steady(e.replace(zeta=z, mu_s=mu))
            assert m.labels[m.class_code[i, j]] == m.motion_class[i, j] == s.motion_class
            assert m.gain[i, j] == s.gain and m.stops_per_period[i, j] == s.stops_per_period
            assert m.period[i, j] == (-1 if s.period is None else s.period)


def test_misaligned_and_strided_inputs_give_the_same_results():
    w = np.linspace(0.3, 2.0, 7)
    beta = np.linspace(0.8, 3.0, 5)
    reference = stickslip.phase_diagram(Experiment.paper(), w=w, beta=beta)
    for w_in, beta_in in [
        (misaligned(w), misaligned(beta)),
        (np.repeat(w, 2)[::2], beta[::-1][::-1]),  # strided views
        (list(w), tuple(beta)),
    ]:
        m = stickslip.phase_diagram(Experiment.paper(), w=w_in, beta=beta_in)
        for name in stickslip.PhaseDiagram.FIELDS:
            assert np.array_equal(getattr(m, name), getattr(reference, name)), name
        assert_same(m.coords["w"], w, "coordinates")
    s = stickslip.sweep(Experiment.paper(beta=2.0), "w", misaligned(w))
    assert_same(s.gain, stickslip.sweep(Experiment.paper(beta=2.0), "w", w).gain, "sweep")
    paper, exact = stickslip.boundary(misaligned([0.05, 0.05]), misaligned([0.7, 1.5]))
    assert_same(exact, stickslip.boundary(0.05, [0.7, 1.5])[1], "boundary")
    # The compiled core itself refuses misaligned arrays rather than misread them: the
    # package's np.require is what makes them work.
    with pytest.raises(ValueError, match="must be a contiguous, aligned float64 array"):
        _core.grid(Experiment.paper(), "w", misaligned(w), "beta", beta)


def test_map_to_xarray(tool_map):
    w, beta, _ = tool_map
    m = stickslip.phase_diagram(Experiment.paper(mu_s=1.2), w=w[:10], beta=beta[:8],
                                max_period=8)
    ds = m.to_xarray()
    assert ds["motion_class"].dims == ("w", "beta") and ds["motion_class"].dtype == np.int8
    # Every class by its code; the driven motion's five come first, their codes fixed.
    assert list(ds["motion_class"].attrs["flag_values"]) == list(range(8))
    assert (ds["motion_class"].attrs["flag_meanings"]
            == "sliding periodic-stick undecided static chaotic stick-slip-cycle "
               "pure-slip-cycle steady-sliding")
    for name in ("w", "beta"):
        assert ds[name].attrs == {"units": "1", "long_name": stickslip.PARAMETERS[name]}
    # -1 (no period found) is a value, not a fill value: netCDF gives the int16 back.
    assert "_FillValue" not in ds["period"].encoding and ds["period"].dtype == np.int16
    assert np.array_equal(ds["gain"].values, m.gain)
    assert ds.attrs["mu_s"] == 1.2 and "w" not in ds.attrs and "beta" not in ds.attrs
    assert ds.attrs["zeta"] == Experiment.paper().zeta
    assert ds.attrs["stickslip_version"] == stickslip.__version__
    assert ds.attrs["model"] == "pwl" and ds.attrs["experiment"].startswith("circuit (preset paper)")
    assert '"max_period": 8' in ds.attrs["steady_options"]
    assert Experiment.from_json(ds.attrs["experiment_json"]) == Experiment.paper(mu_s=1.2)


def test_map_errors():
    e = Experiment.paper()
    with pytest.raises(ValueError, match=r"^invalid w = 0: must be finite and from 1e-5 to 1e5 \(docs/limits\.md\)$"):
        stickslip.phase_diagram(e, w=[0.0, 1.0], beta=[1.0])
    with pytest.raises(TypeError, match="takes 2 parameter arrays"):
        stickslip.phase_diagram(e, w=[1.0])
    with pytest.raises(TypeError, match="takes 2 parameter arrays"):
        stickslip.phase_diagram(e, w=[1.0], beta=[1.0], mu_s=[1.0])
    with pytest.raises(TypeError, match=r"^phase_diagram\(\) got an unknown keyword 'harmonics'"):
        stickslip.phase_diagram(e, w=[1.0], beta=[1.0], harmonics=3)
    with pytest.raises(ValueError, match=r"^invalid threads = 0: must be from 1 to 1024$"):
        stickslip.phase_diagram(e, w=[1.0], beta=[1.0], threads=0)
    with pytest.raises(ValueError, match="must be a one-dimensional array"):
        stickslip.phase_diagram(e, w=[[1.0]], beta=[1.0])
    with pytest.raises(ValueError, match="^missing drive amplitude"):
        stickslip.phase_diagram(e, w=[1.0], zeta=[0.1])


# A map far too long to finish during the test: 2000 × 2000 points (minutes on any machine).
LONG = dict(w=np.linspace(0.1, 2.5, 2000), beta=np.linspace(0.5, 4.0, 2000))


@pytest.mark.parametrize("what", ["map", "sweep", "simulate"])
def test_ctrl_c_stops_a_long_computation(what):
    assert threading.current_thread() is threading.main_thread()
    timer = interrupt_after(0.5)
    try:
        with pytest.raises(KeyboardInterrupt):
            if what == "map":
                stickslip.phase_diagram(Experiment.paper(), **LONG)
            elif what == "sweep":
                stickslip.sweep(Experiment.paper(beta=2.0), "w", np.linspace(0.1, 2.5, 100000))
            else:
                # The stiff solver: minutes for 10^5 periods, in little memory.
                stickslip.simulate(Experiment.paper(diode="shockley", w=0.95, beta=2.14), 1e5, 10)
    finally:
        timer.cancel()
    # Stopped within a little work after the signal (the computation alone would take minutes of
    # CPU), counted in CPU time: not the wall time, which a loaded machine stretches.
    cpu = timer.cpu_since_signal()
    assert cpu < 5.0, f"{cpu:.1f} s of CPU after the signal"
    # Everything still works afterwards.
    assert stickslip.phase_diagram(Experiment.paper(), w=[0.9], beta=[1.6]).motion_class.shape == (1, 1)


def test_progress_callback_and_its_exceptions_stop_the_map():
    seen = []
    stickslip.phase_diagram(Experiment.paper(), w=np.linspace(0.2, 2, 30),
                            beta=np.linspace(0.5, 4, 30),
                            progress=lambda done, total: seen.append((done, total)))
    assert seen[-1] == (900, 900)

    def stop(done, total):
        raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        stickslip.phase_diagram(Experiment.paper(), progress=stop, **LONG)


# The GIL. A computation waits for its result without the GIL, so other Python threads run
# meanwhile. Three checks, all read from the order of events, none from the clock:
# 1. while one thread computes a map, the main thread runs: it finds the other thread inside
#    the library's call between two progress calls (conftest's assert_runs_beside);
# 2. two maps started together in two threads progress together: each reports progress
#    before the other ends (none, if a lock serialised them);
# 3. the same as 1 with the map in the main thread: a second thread that samples the main
#    thread's Python stack finds it inside the library's call between two progress calls,
#    where only the Rust computation runs; with the GIL held there, no other thread could run
#    at that moment.
#    (What two maps in two threads gain in time is a speed, for a benchmark, not a test.)
SECOND = dict(w=np.linspace(0.2, 2.4, 160), beta=np.linspace(0.6, 3.9, 160))


def test_other_python_threads_run_during_a_map():
    """While a map computes in another thread, the main thread runs (conftest's
    assert_runs_beside reads the order of events, not the clock)."""
    diagram = assert_runs_beside(stickslip.phase_diagram, Experiment.paper(), threads=1,
                                 **SECOND)
    assert diagram.motion_class.shape == (160, 160)


def test_two_maps_in_two_threads_progress_together():
    """Two maps in two threads compute at once: each reports progress while the other is
    still computing. The order of the progress calls is read, not the clock: a lock that
    serialised the library's maps would let one finish before the other reports any progress,
    however the machine is loaded (a share of the first map's wall time would race the
    scheduler). That the GIL is released in between is the next test's."""
    calls = []  # (map, fraction done) in the order of the calls
    lock = threading.Lock()

    def work(k):
        def progress(done, total):
            with lock:
                calls.append((k, done / total))

        stickslip.phase_diagram(Experiment.paper(), threads=1, progress=progress, **SECOND)

    threads = [threading.Thread(target=work, args=(k,)) for k in (0, 1)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    last = {k: max(i for i, (m, _) in enumerate(calls) if m == k) for k in (0, 1)}
    assert all(calls[last[k]][1] == 1.0 for k in (0, 1)), "each map reports its end"
    first = min((0, 1), key=lambda k: last[k])
    partial = [f for m, f in calls[: last[first]] if m == 1 - first and 0.0 < f < 1.0]
    assert partial, (
        f"map {1 - first} reported no progress before map {first} finished: "
        f"the maps ran one after the other ({len(calls)} calls)"
    )


def test_other_threads_run_while_the_map_computes_between_its_progress_calls():
    main = threading.get_ident()
    # The frame that calls into the library (stickslip.phase_diagram's own).
    code = inspect.unwrap(stickslip.phase_diagram).__code__
    for attempt in range(5):
        calls = [0]
        seen = []
        stop = threading.Event()

        def progress(done, total):
            calls[0] += 1

        def sample():
            while not stop.is_set():
                frame = sys._current_frames().get(main)
                if frame is not None and frame.f_code is code:
                    seen.append(calls[0])
                time.sleep(0.0005)

        sampler = threading.Thread(target=sample)
        sampler.start()
        try:
            stickslip.phase_diagram(Experiment.paper(), threads=1, progress=progress, **SECOND)
        finally:
            stop.set()
            sampler.join()
        assert calls[0] >= 3, calls
        # Between the first and the last progress call the main thread is in the library.
        inside = [c for c in seen if 0 < c < calls[0]]
        if inside:
            return
    pytest.fail(f"in five maps another thread never ran while the library computed: samples "
                f"at progress calls {seen[:20]} of {calls[0]}")
