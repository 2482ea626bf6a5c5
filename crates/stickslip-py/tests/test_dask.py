"""stickslip.dask: the same maps as Dask tasks, bit-identical to the local call, on Dask's
local threads, on a LocalCluster of worker processes, and on a real cluster: a `dask
scheduler` and two `dask worker` processes started as a deployment would start them."""

from __future__ import annotations

import io
import os
import pathlib
import signal
import socket
import subprocess
import sys
import time

import numpy as np
import pytest

import stickslip
import stickslip.dask
from stickslip import Experiment

distributed = pytest.importorskip("distributed", reason="the Dask tests need dask[distributed]")

W = np.linspace(0.1, 2.5, 30)
BETA = np.linspace(0.5, 4.0, 20)


def assert_identical(a: stickslip.PhaseDiagram, b: stickslip.PhaseDiagram) -> None:
    assert a.dims == b.dims and a.shape == b.shape
    for name in stickslip.PhaseDiagram.FIELDS:
        x, y = getattr(a, name), getattr(b, name)
        assert x.dtype == y.dtype, name
        # Bit-identical, not merely close.
        assert x.tobytes() == y.tobytes(), name
    for d in a.dims:
        assert np.array_equal(a.coords[d], b.coords[d])


@pytest.fixture(scope="module")
def local_map():
    return stickslip.phase_diagram(Experiment.paper(), w=W, beta=BETA)


def test_threaded_scheduler_without_a_client(local_map):
    for chunks in [(7, 9), 4, "auto", (30, 20), (1, 1)]:
        m = stickslip.dask.phase_diagram(Experiment.paper(), chunks=chunks, w=W, beta=BETA)
        assert_identical(m, local_map)


# A map of the largest Lyapunov exponent where every kind of cell shows: chaotic, periodic,
# decided contracting, rest (ζ = 0, μs = 3: the chaos map's window).
EXPONENT_W = np.linspace(0.2, 0.6, 12)
EXPONENT_BETA = np.linspace(3.0, 14.0, 10)


@pytest.fixture(scope="module")
def local_exponent_map():
    return stickslip.phase_diagram(Experiment(zeta=0, mu_s=3), lyapunov=True, w=EXPONENT_W,
                                   beta=EXPONENT_BETA)


def assert_same_exponents(a: stickslip.PhaseDiagram, b: stickslip.PhaseDiagram) -> None:
    assert_identical(a, b)
    for name in stickslip.PhaseDiagram.EXPONENT_FIELDS:
        x, y = getattr(a, name), getattr(b, name)
        assert x is not None and y is not None, name
        assert x.dtype == y.dtype == np.float64, name
        assert x.tobytes() == y.tobytes(), name


def test_an_exponent_map_on_dask_threads_is_the_threaded_one(local_exponent_map):
    m = local_exponent_map
    # The window holds chaos and periodic orbits (exact exponents, error 0).
    assert m.counts()["chaotic"] > 0 and np.any(m.lambda1_error == 0), m.counts()
    for chunks in [(5, 3), (12, 10), (1, 1)]:
        d = stickslip.dask.phase_diagram(Experiment(zeta=0, mu_s=3), lyapunov=True,
                                         chunks=chunks, w=EXPONENT_W, beta=EXPONENT_BETA)
        assert_same_exponents(d, m)
    # Without lyapunov=True there are no exponents, as locally.
    plain = stickslip.dask.phase_diagram(Experiment(zeta=0, mu_s=3), chunks=(6, 5),
                                         w=EXPONENT_W, beta=EXPONENT_BETA)
    assert plain.lambda1 is None and plain.lambda1_error is None


def test_progress_counts_the_points_of_finished_blocks(local_cluster):
    calls = []
    m = stickslip.dask.phase_diagram(Experiment.paper(), chunks=(6, 20), client=local_cluster,
                                     progress=lambda done, total: calls.append((done, total)),
                                     w=W, beta=BETA)
    assert calls and calls[-1] == (600, 600), calls
    assert all(t == 600 for _, t in calls)
    assert [d for d, _ in calls] == sorted({d for d, _ in calls}), calls
    assert all(d % 120 == 0 for d, _ in calls), calls
    # On Dask's threads, and a tqdm bar's update (given the points since its last call).
    tqdm = pytest.importorskip("tqdm")
    with tqdm.tqdm(file=io.StringIO()) as bar:
        stickslip.dask.phase_diagram(Experiment.paper(), chunks=(10, 20), progress=bar.update,
                                     w=W, beta=BETA)
        assert (bar.n, bar.total) == (600, 600)
    assert m.shape == (30, 20)


def test_an_exponent_map_on_worker_processes_is_the_threaded_one(local_cluster,
                                                                  local_exponent_map):
    d = stickslip.dask.phase_diagram(Experiment(zeta=0, mu_s=3), lyapunov=True, chunks=(3, 10),
                                     client=local_cluster, w=EXPONENT_W, beta=EXPONENT_BETA)
    assert_same_exponents(d, local_exponent_map)
    stack = stickslip.dask.sweep_grid(Experiment(zeta=0), lyapunov=True, client=local_cluster,
                                      mu_s=[3.0], w=EXPONENT_W, beta=EXPONENT_BETA)
    assert stack.lambda1 is not None
    assert stack.lambda1[0].tobytes() == local_exponent_map.lambda1.tobytes()
    # The workers' own Ctrl-C handling is back once the map is done.
    handlers = local_cluster.run(lambda: str(signal.getsignal(signal.SIGINT)))
    assert all("SIG_IGN" not in h for h in handlers.values()), handlers


def test_inputs_are_checked_before_any_task():
    with pytest.raises(ValueError, match=r"^invalid w = 0: must be finite and from 1e-5 to 1e5 \(docs/limits\.md\)$"):
        stickslip.dask.phase_diagram(Experiment.paper(), chunks=(2, 2), w=[0.0, 1.0], beta=[1.0])
    with pytest.raises(ValueError, match="^invalid chunks"):
        stickslip.dask.phase_diagram(Experiment.paper(), chunks=(0, 3), w=W, beta=BETA)
    with pytest.raises(TypeError, match="takes 3 or 4 parameter arrays"):
        stickslip.dask.sweep_grid(Experiment.paper(), w=W, beta=BETA)
    with pytest.raises(ValueError, match=r"^invalid mu_s = 0.5: must be finite and from 1 to 1e9 \(docs/limits\.md\)$"):
        stickslip.dask.sweep_grid(Experiment.paper(), mu_s=[1.0, 0.5], w=W, beta=BETA)


@pytest.fixture(scope="module")
def local_cluster():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0", host="127.0.0.1") as cluster:
        with distributed.Client(cluster) as client:
            yield client


def test_local_cluster(local_cluster, local_map):
    m = stickslip.dask.phase_diagram(Experiment.paper(), chunks=(4, 20), client=local_cluster,
                                     w=W, beta=BETA)
    assert_identical(m, local_map)
    # With the client as Dask's default (client=None).
    m = stickslip.dask.phase_diagram(Experiment.paper(), w=W, beta=BETA)
    assert_identical(m, local_map)


def test_sweep_grid_is_a_map_per_outer_value(local_cluster):
    mu_s = np.array([1.0, 1.3, 2.0])
    stack = stickslip.dask.sweep_grid(Experiment.paper(), chunks=(8, 8), client=local_cluster,
                                      mu_s=mu_s, w=W, beta=BETA)
    assert stack.dims == ("mu_s", "w", "beta") and stack.shape == (3, 30, 20)
    for k, m in enumerate(mu_s):
        local = stickslip.phase_diagram(Experiment.paper(mu_s=m), w=W, beta=BETA)
        for name in stickslip.PhaseDiagram.FIELDS:
            assert np.array_equal(getattr(stack, name)[k], getattr(local, name)), name
    # Static friction above kinetic changes the map.
    assert not np.array_equal(stack.class_code[0], stack.class_code[2])
    ds = stack.to_xarray()
    assert ds["motion_class"].dims == ("mu_s", "w", "beta")
    assert ds["mu_s"].attrs["long_name"] == stickslip.PARAMETERS["mu_s"]
    assert "mu_s" not in ds.attrs


def test_sweep_grid_over_two_outer_parameters(local_cluster):
    zeta, mu_s = np.array([0.02, 0.1]), np.array([1.0, 1.5])
    stack = stickslip.dask.sweep_grid(Experiment(), client=local_cluster, zeta=zeta, mu_s=mu_s,
                                      w=W[::3], beta=BETA[::2])
    assert stack.shape == (2, 2, 10, 10)
    for i, z in enumerate(zeta):
        for j, m in enumerate(mu_s):
            local = stickslip.phase_diagram(Experiment(zeta=z, mu_s=m), w=W[::3], beta=BETA[::2])
            assert np.array_equal(stack.class_code[i, j], local.class_code)
            assert np.array_equal(stack.gain[i, j], local.gain)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def real_cluster(tmp_path_factory):
    """`dask scheduler` and two single-threaded `dask worker` processes on 127.0.0.1, each a
    process of its own started from the command line, as on machines started by hand."""
    dask_cli = pathlib.Path(sys.executable).parent / "dask"
    if not dask_cli.is_file():
        pytest.fail(f"the dask command is missing next to {sys.executable}: pip install 'dask[distributed]'")
    logs = tmp_path_factory.mktemp("cluster")
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    processes = []

    def start(name, *args):
        log = open(logs / f"{name}.log", "w")
        processes.append((subprocess.Popen([str(dask_cli), *args], stdout=log,
                                           stderr=subprocess.STDOUT), log))

    start("scheduler", "scheduler", "--host", "127.0.0.1", "--port", str(port),
          "--dashboard-address", ":0", "--no-show")
    for k in range(2):
        start(f"worker{k}", "worker", address, "--host", "127.0.0.1", "--nthreads", "1",
              "--nworkers", "1", "--no-dashboard", "--name", f"worker{k}")
    client = None
    try:
        deadline = time.monotonic() + 60
        while client is None:
            try:
                client = distributed.Client(address, timeout=5, set_as_default=False)
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.5)
        client.wait_for_workers(2, timeout=60)
        yield client
    except Exception:
        for name in ["scheduler", "worker0", "worker1"]:
            print(f"--- {name}.log\n{(logs / f'{name}.log').read_text()}")
        raise
    finally:
        if client is not None:
            # Asks the scheduler to close the workers and itself, as `dask` would be shut down.
            client.shutdown()
            client.close()
        for proc, log in reversed(processes):
            if proc.poll() is None:
                try:
                    proc.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    proc.terminate()
        for proc, log in reversed(processes):
            try:
                proc.wait(timeout=20)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
            log.close()


def test_real_cluster(real_cluster, local_map):
    workers = real_cluster.scheduler_info()["workers"]
    assert len(workers) == 2
    assert all(w["nthreads"] == 1 for w in workers.values())
    # Small blocks, so that both workers compute some.
    m = stickslip.dask.phase_diagram(Experiment.paper(), chunks=(3, 20), client=real_cluster,
                                     w=W, beta=BETA)
    assert_identical(m, local_map)
    # Both workers computed blocks.
    blocks = real_cluster.run(
        lambda dask_worker: sum(1 for entry in dask_worker.state.log
                                if "_block_task" in str(entry[0]) and entry[1:3] == ("executing", "memory"))
    )
    assert len(blocks) == 2 and all(n > 0 for n in blocks.values()), blocks
    assert sum(blocks.values()) == 10
    stack = stickslip.dask.sweep_grid(Experiment.paper(), client=real_cluster,
                                      mu_s=[1.0, 1.5], w=W, beta=BETA)
    assert_identical(
        stickslip.PhaseDiagram(stack.experiment, ("w", "beta"), stack.coords, stack.options,
                               {n: getattr(stack, n)[0] for n in stickslip.PhaseDiagram.FIELDS}),
        local_map,
    )


# A map that runs for half a minute or more of CPU even on an idle machine (2.25e6 points of
# the paper's map), in blocks of a fraction of a second each: Ctrl-C comes mid-way.
CTRL_C_SCRIPT = """
import signal, sys, threading, time
import numpy as np
import dask, distributed  # imported before the map starts
import stickslip, stickslip.dask

def shielded():
    return signal.getsignal(signal.SIGINT) == signal.SIG_IGN

# 'started' once the map has begun: on a cluster, once its workers ignore the terminal's
# Ctrl-C (the map's first act; a Ctrl-C before it reaches workers that nothing shields).
def say_started(client):
    if client is not None:
        while not all(client.run(shielded).values()):
            time.sleep(0.01)
    print("started", flush=True)

def run(client):
    threading.Thread(target=say_started, args=(client,), daemon=True).start()
    if sys.argv[2] == "lyapunov":
        # The exponent map of the chaos window (minutes of CPU), in small blocks.
        stickslip.dask.phase_diagram(stickslip.Experiment(zeta=0, mu_s=3), client=client,
                                     chunks=(1, 4), lyapunov=True, progress=lambda d, t: None,
                                     w=np.linspace(0.2, 0.6, 150), beta=np.linspace(3, 14, 150))
    stickslip.dask.phase_diagram(stickslip.Experiment.paper(), client=client, chunks=(5, 1500),
                                 w=np.linspace(0.1, 2.5, 1500), beta=np.linspace(0.5, 4, 1500))

if __name__ == "__main__":
    if sys.argv[1] == "cluster":
        with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=True,
                                      dashboard_address=":0", host="127.0.0.1") as cluster, \\
                distributed.Client(cluster) as client:
            run(client)
    else:
        run(None)
"""


@pytest.mark.parametrize("scheduler,kind,after", [("cluster", "classes", 3.0),
                                                  ("threads", "classes", 3.0),
                                                  ("cluster", "lyapunov", 3.0),
                                                  ("cluster", "lyapunov", 0.5),
                                                  ("cluster", "lyapunov", 1.5)])
def test_ctrl_c_raises_one_keyboard_interrupt_and_prints_nothing_else(tmp_path, scheduler,
                                                                      kind, after):
    """Ctrl-C as a terminal sends it, SIGINT to every process of the foreground job (the
    script and the worker processes of its LocalCluster, which share its process group),
    during stickslip.dask.phase_diagram on a LocalCluster (a map of classes, and one of
    exponents with progress) and on Dask's local threads: one KeyboardInterrupt traceback on
    stderr and nothing else (before, asyncio printed a traceback per task, 'Task exception
    was never retrieved ... AllExit', and each worker process its own traceback and the
    nanny a warning), within a bounded time; the workers are idle when the cluster closes,
    so no worker reports a task cut short. Whenever the Ctrl-C comes (``after`` seconds: while
    the graph of 5700 blocks is built, while the scheduler takes it in, or while the blocks
    compute), the same holds."""
    script = tmp_path / "ctrl_c.py"
    script.write_text(CTRL_C_SCRIPT)
    # A process group of its own, as a terminal gives a job.
    child = subprocess.Popen([sys.executable, str(script), scheduler, kind],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             cwd=tmp_path, start_new_session=True)
    try:
        assert child.stdout is not None
        assert child.stdout.readline() == "started\n"
        time.sleep(after)
        assert child.poll() is None, "the map ended before Ctrl-C"
        if scheduler == "cluster":
            # The workers are in the job too (else the test would not be the terminal's).
            group = [pid for pid in map(int, filter(str.isdigit, os.listdir("/proc")))
                     if _process_group(pid) == child.pid]
            assert len(group) > 1, group
        os.killpg(child.pid, signal.SIGINT)
        interrupted = time.perf_counter()
        _, stderr = child.communicate(timeout=120)
        took = time.perf_counter() - interrupted
    finally:
        try:
            os.killpg(child.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        child.wait()
        for pipe in (child.stdout, child.stderr):
            if pipe is not None:
                pipe.close()
    assert child.returncode in (-signal.SIGINT, 128 + signal.SIGINT), (child.returncode, stderr)
    lines = stderr.strip().splitlines()
    assert stderr.count("Traceback") == 1 and lines[-1] == "KeyboardInterrupt", stderr
    for noise in ("Task exception was never retrieved", "AllExit", "WARNING", "ERROR",
                  "Exception"):
        assert noise not in stderr, stderr
    # A block lasts a few seconds here; the cluster's shutdown a few more.
    assert took < 60, f"{took:.1f} s from Ctrl-C to the end"


def _process_group(pid: int) -> int:
    """The process group of ``pid`` (-1 for a process gone)."""
    try:
        return os.getpgid(pid)
    except (ProcessLookupError, PermissionError):
        return -1
