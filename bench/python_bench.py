"""The Python package's benchmarks (run by bench/python; numbers in BENCHMARKS.md):

(a) a 400 × 400 map from Python against the same map through the library (Grid::run in
    crates/stickslip/examples/library_timing.rs), runs interleaved, medians and their ratio;
(b) a 1000 × 1000 map as Dask tasks on a cluster of two single-threaded worker processes
    against one, and the machine's load around each run;
(c) a 10^6-sample trajectory returned to numpy against the same run in the library, and the
    cost of one copy of its arrays for scale.

Every ratio comes from the same invocation. Timing is reported, never enforced."""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import time

import numpy as np

import stickslip
import stickslip.dask

ROOT = pathlib.Path(__file__).resolve().parents[1]
TARGET = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")).resolve()
EXAMPLE = TARGET / "release" / "examples" / "library_timing"


def library(*args: object) -> dict:
    out = subprocess.run([str(EXAMPLE), *map(str, args)], check=True, capture_output=True,
                         text=True).stdout
    return json.loads(out)


def load() -> float:
    return os.getloadavg()[0]


def map_in_python_and_library(n: int, repeats: int) -> dict:
    """The same map through the package and through the library (runs interleaved): wall time
    and CPU time (all threads; the work done, which other work on the machine disturbs far
    less than the wall time)."""
    w, beta = np.linspace(0.1, 2.5, n), np.linspace(0.5, 4.0, n)
    rust, python, rust_cpu, python_cpu, loads = [], [], [], [], []
    counts = None
    for _ in range(repeats):
        loads.append(load())
        r = library("map", n)
        rust.append(r["seconds"])
        rust_cpu.append(r["cpu_seconds"])
        started, cpu = time.perf_counter(), time.process_time()
        m = stickslip.phase_diagram(stickslip.Experiment.paper(), w=w, beta=beta)
        python.append(time.perf_counter() - started)
        python_cpu.append(time.process_time() - cpu)
        counts = m.counts()
        if counts != r["counts"]:
            raise SystemExit(f"the two maps differ: Python {counts}, library {r['counts']}")
    return {
        "grid": f"{n} x {n}",
        "library_s": rust,
        "python_s": python,
        "library_cpu_s": rust_cpu,
        "python_cpu_s": python_cpu,
        "library_median_s": statistics.median(rust),
        "python_median_s": statistics.median(python),
        "ratio_python_over_library": statistics.median(python) / statistics.median(rust),
        "ratio_of_minima": min(python) / min(rust),
        "cpu_ratio_python_over_library": statistics.median(python_cpu) / statistics.median(rust_cpu),
        "threads": r["threads"],
        "load_average": loads,
        "counts": counts,
    }


def machine_parallelism() -> float:
    """What two processes gain from running together right now: the time of two fixed Python
    busy loops one after the other over their time side by side (2 on two idle cores; about 1
    when other work holds the cores)."""
    loop = "x = 0\nfor i in range(20_000_000):\n    x += i\n"

    def timed(concurrent: bool) -> float:
        started = time.perf_counter()
        if concurrent:
            procs = [subprocess.Popen([sys.executable, "-c", loop]) for _ in range(2)]
            for p in procs:
                p.wait()
        else:
            for _ in range(2):
                subprocess.run([sys.executable, "-c", loop], check=True)
        return time.perf_counter() - started

    return timed(False) / timed(True)


def map_on_a_cluster(n: int) -> dict:
    from distributed import Client, LocalCluster

    w, beta = np.linspace(0.1, 2.5, n), np.linspace(0.5, 4.0, n)
    runs = {}
    reference = None
    for workers in (1, 2, 1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster, Client(cluster) as client:
            before = load()
            started = time.perf_counter()
            m = stickslip.dask.phase_diagram(stickslip.Experiment.paper(), client=client,
                                             w=w, beta=beta)
            seconds = time.perf_counter() - started
            runs.setdefault(workers, []).append(
                {"seconds": seconds, "load_before": before, "load_after": load()})
            if reference is None:
                reference = m.class_code
            elif not np.array_equal(reference, m.class_code):
                raise SystemExit("the cluster's maps differ between runs")
            print(f"  {workers} worker(s): {seconds:.1f} s (load {before:.1f} -> {load():.1f})",
                  file=sys.stderr)
    one = min(r["seconds"] for r in runs[1])
    two = min(r["seconds"] for r in runs[2])
    parallelism = machine_parallelism()
    print(f"  two busy processes side by side: {parallelism:.2f}x", file=sys.stderr)
    return {
        "machine_parallelism": parallelism,
        "grid": f"{n} x {n}",
        "runs": runs,
        "one_worker_best_s": one,
        "two_workers_best_s": two,
        "speedup": one / two,
        "task_seconds": stickslip.dask.TASK_SECONDS,
        "cores": os.cpu_count(),
    }


def trajectory_to_numpy(periods: float, samples: int, repeats: int) -> dict:
    """The cost of handing a trajectory to numpy: measured inside the call (the compiled core
    times the library's run and the conversion of its result to numpy arrays), plus the
    package's wrapping into a Trajectory, against one copy of the arrays; and, for scale, the
    whole call against the library's run in a process of its own."""
    experiment = stickslip.Experiment(w=0.7, beta=1.2)
    library_runs, python, inside, converting, wrapping, copy = [], [], [], [], [], []
    for _ in range(repeats):
        # Each library run repeats the call five times in its process, each on a thread of its
        # own as the package does.
        r = library("simulate", periods, samples, 5)
        library_runs.extend(r["seconds"])
        # The previous run is freed outside the timed call, as the library side frees its own.
        run = copies = data = None
        started = time.perf_counter()
        data = stickslip._core.simulate(experiment, float(periods), samples, None)
        middle = time.perf_counter()
        run = stickslip.Trajectory(experiment, data)
        ended = time.perf_counter()
        python.append(ended - started)
        wrapping.append(ended - middle)
        inside.append(data["_seconds"][0])
        converting.append(data["_seconds"][1])
        started = time.perf_counter()
        copies = [np.array(run[c], copy=True) for c in ("tau", "y", "v", "drive", "phase")]
        copy.append(time.perf_counter() - started)
        assert len(run) == r["samples"] and len(copies[0]) == r["samples"]
    # The float columns are numpy arrays over the library's own buffers.
    owned = all(type(run[c].base).__name__ == "PySliceContainer" for c in ("tau", "y", "v", "drive"))
    returning = [c + w for c, w in zip(converting, wrapping)]
    return {
        "samples": len(run),
        "events": len(run.events),
        "bytes": int(sum(run[c].nbytes for c in ("tau", "y", "v", "drive", "phase"))),
        "float_columns_without_copy": owned,
        "library_run_in_the_call_s": inside,
        "converting_s": converting,
        "wrapping_s": wrapping,
        "one_copy_s": copy,
        "python_call_s": python,
        "library_process_s": library_runs,
        "returning_median_s": statistics.median(returning),
        "one_copy_median_s": statistics.median(copy),
        "returning_over_one_copy": statistics.median(returning) / statistics.median(copy),
        "returning_over_run": statistics.median(returning) / statistics.median(inside),
        "python_call_min_s": min(python),
        "library_process_min_s": min(library_runs),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--smoke", action="store_true", help="tiny workloads (seconds)")
    parser.add_argument("--only", action="append", choices=["a", "b", "c"])
    parser.add_argument("--out", type=pathlib.Path,
                        help="where to write every number [target/bench/python.json, or "
                             "python-smoke.json with --smoke]")
    args = parser.parse_args()
    if args.out is None:
        args.out = TARGET / "bench" / ("python-smoke.json" if args.smoke else "python.json")
    only = set(args.only or ["a", "b", "c"])
    results = {
        "machine": {"cores": os.cpu_count(), "load_average_start": os.getloadavg(),
                    "python": sys.version.split()[0], "stickslip": stickslip.__version__},
    }
    if "a" in only:
        print("(a) 400 x 400 map: Python against the library ...", file=sys.stderr)
        results["a"] = map_in_python_and_library(40 if args.smoke else 400, 1 if args.smoke else 5)
        a = results["a"]
        print(f"(a) {a['grid']}: library {a['library_median_s']:.3f} s, Python "
              f"{a['python_median_s']:.3f} s (medians): wall ratio {a['ratio_python_over_library']:.3f}, "
              f"of the fastest runs {a['ratio_of_minima']:.3f}; CPU time ratio "
              f"{a['cpu_ratio_python_over_library']:.3f}")
    if "b" in only:
        print("(b) 1000 x 1000 map on 1 and 2 single-threaded workers ...", file=sys.stderr)
        results["b"] = map_on_a_cluster(60 if args.smoke else 1000)
        b = results["b"]
        print(f"(b) {b['grid']}: 1 worker {b['one_worker_best_s']:.1f} s, 2 workers "
              f"{b['two_workers_best_s']:.1f} s: speed-up {b['speedup']:.2f} (two busy "
              f"processes on this machine at the same time: {b['machine_parallelism']:.2f}x)")
    if "c" in only:
        print("(c) a 10^6-sample trajectory to numpy ...", file=sys.stderr)
        results["c"] = trajectory_to_numpy(50 if args.smoke else 5000, 200, 3 if args.smoke else 10)
        c = results["c"]
        print(f"(c) {c['samples']} samples: returning to numpy {c['returning_median_s'] * 1e3:.2f} ms "
              f"(median) = {c['returning_over_one_copy']:.2f} of one copy of the arrays "
              f"({c['one_copy_median_s'] * 1e3:.2f} ms for {c['bytes'] / 1e6:.0f} MB) and "
              f"{c['returning_over_run']:.3f} of the run; float columns without a copy: "
              f"{c['float_columns_without_copy']}; whole call {c['python_call_min_s'] * 1e3:.1f} ms "
              f"against the library's {c['library_process_min_s'] * 1e3:.1f} ms (fastest runs)")
    results["machine"]["load_average_end"] = os.getloadavg()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(results, indent=2))
    print(f"every number in {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
