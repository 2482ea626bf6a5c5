"""Benchmark driver: runs every workload in stickslip and in each peer, in one invocation,
computes accuracy against the exact solution, and prints the tables (see bench/README.md).

Run through bench/run, which installs the peers and builds the stickslip runner first.
"""

import argparse
import datetime
import json
import math
import os
import platform
import shutil
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PEERS = os.path.join(ROOT, "bench", "peers")
RUNNER = os.path.join(ROOT, "target", "release", "examples", "bench_workloads")

# The paper's circuit: zeta = (R + R_D) sqrt(C/L) / 2 with R + R_D = 71 ohm (Circuit::paper()).
ZETA = 71.0 * math.sqrt(0.02e-6 / 11.5e-3) / 2.0
FIG6 = [(0.9, 1.6), (0.6, 1.2), (0.7, 1.2), (0.7, 1.0)]
FIG3 = [(0.29, 2.14), (0.95, 2.14), (1.43, 2.14)]
TIGHT = {"method": "DOP853", "rtol": 1e-13, "atol": 1e-15}

# ngspice settings for workload (c): SPICE's defaults, and two tighter ones.
NGSPICE_SETTINGS = [
    ("ngspice default", {}, 200, "trap"),
    ("ngspice reltol 1e-6", {"reltol": 1e-6, "abstol": 1e-13, "vntol": 1e-10}, 1000, "trap"),
    ("ngspice reltol 1e-7", {"reltol": 1e-7, "abstol": 1e-14, "vntol": 1e-11}, 2000, "trap"),
    # stickslip::shockley::netlist as it is: default tolerances, TMAX = T/1000, every point
    # written out.
    ("ngspice on `stickslip netlist`", None, None, "trap"),
]
# stickslip's Shockley solver: (rtol, max_step); None keeps the library's max_step (0.25, for
# an accurate cubic dense output); a longer one pays off at loose tolerances.
SHOCKLEY_SETTINGS = [(1e-2, None), (1e-2, 1.0), (1e-3, None), (1e-3, 1.0), (1e-4, None),
                     (1e-5, None), (1e-6, None), (1e-8, None), (1e-10, None)]


class Failure(Exception):
    pass


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def run_json(cmd, job=None, env=None):
    """Run a command that prints one JSON document; feed `job` as JSON on stdin."""
    proc = subprocess.run(
        cmd,
        input=None if job is None else json.dumps(job),
        capture_output=True,
        text=True,
        env=env,
        cwd=ROOT,
    )
    if proc.returncode != 0:
        raise Failure(f"{' '.join(cmd[:3])} failed ({proc.returncode}): {proc.stderr[-2000:]}")
    return json.loads(proc.stdout)


def peer(name, job):
    return run_json([sys.executable, os.path.join(PEERS, name)], job)["results"]


def runner(args, threads=None):
    env = dict(os.environ)
    if threads is not None:
        env["RAYON_NUM_THREADS"] = str(threads)
    return run_json([RUNNER] + [str(a) for a in args], env=env)


def loadavg():
    try:
        return os.getloadavg()
    except OSError:
        return (float("nan"),) * 3


def machine():
    info = {"platform": platform.platform(), "python": platform.python_version()}
    try:
        with open("/proc/cpuinfo") as fh:
            names = [l.split(":", 1)[1].strip() for l in fh if l.startswith("model name")]
        info["cpu"] = names[0] if names else platform.processor()
    except OSError:
        info["cpu"] = platform.processor()
    info["cores"] = os.cpu_count()
    try:
        with open("/proc/meminfo") as fh:
            kb = int(fh.readline().split()[1])
        info["memory_gib"] = round(kb / 2**20, 1)
    except (OSError, ValueError, IndexError):
        pass
    import scipy

    info["numpy"] = np.__version__
    info["scipy"] = scipy.__version__
    for tool, cmd in [("rustc", ["rustc", "--version"]), ("ngspice", ["ngspice", "--version"])]:
        try:
            out = subprocess.run(cmd, capture_output=True, text=True).stdout
            info[tool] = next((l.strip("* ").strip() for l in out.splitlines() if "ngspice-" in l or "rustc" in l), out.strip())
        except OSError:
            info[tool] = None
    return info


# ---------------------------------------------------------------- classification


def classify(y, v, beta, spp, tail_periods, tail_sticks):
    """Motion class over the last `tail_periods` periods, one rule for every solver: static
    when the amplitude is below beta/100 (the paper's criterion); else stick when a stop
    happened in the tail (the solver's own stop events; `tail_sticks` None: a sample with
    |y'| < 1e-6); a stick motion is periodic when the stroboscopic samples (one per period)
    repeat with a period p <= 16 to 1e-8 relative."""
    y, v = np.asarray(y), np.asarray(v)
    n_tail = int(tail_periods * spp)
    ty, tv = y[-n_tail - 1:], v[-n_tail - 1:]
    if 0.5 * (ty.max() - ty.min()) < 0.01 * beta:
        return "static"
    stick = tail_sticks > 0 if tail_sticks is not None else bool((np.abs(tv) < 1e-6).any())
    if not stick:
        return "sliding"
    strobes = np.stack([ty[::spp], tv[::spp]], axis=1)
    scale = max(1.0, float(np.abs(strobes).max()))
    for p in range(1, 17):
        if len(strobes) > 2 * p + 1:
            d = np.abs(strobes[-p - 1:] - strobes[-2 * p - 1:-p]).max()
            if d <= 1e-8 * scale:
                return "periodic stick"
    return "non-periodic stick"


# ---------------------------------------------------------------- workload (a)


def workload_a(points, periods, spp, tail):
    """One trajectory per point from rest, sampled at `spp` per period, in every solver."""
    log(f"(a) {len(points)} trajectories of {periods} periods, {spp} samples per period")
    pts = [{"w": w, "beta": b, "periods": periods} for w, b in points]
    base = {"zeta": ZETA, "samples_per_period": spp, "keep_samples": True, "points": pts,
            "tail_periods": tail}
    common = ["--periods", periods, "--samples-per-period", spp, "--zeta", repr(ZETA),
              "--tail", tail]
    exact = []
    for w, b in points:
        point = ["trajectory", "--w", w, "--beta", b] + common
        exact.append((runner(point), runner(point + ["--sampling", "sample-at"])))
    log("    stickslip done")
    peers = [
        ("paper: odeint LSODA, defaults", "paper_lsoda.py", {}),
        ("careful: solve_ivp DOP853 1e-10", "careful_scipy.py",
         {"method": "DOP853", "rtol": 1e-10, "atol": 1e-12}),
        ("careful: solve_ivp LSODA 1e-10", "careful_scipy.py",
         {"method": "LSODA", "rtol": 1e-10, "atol": 1e-12}),
        ("check: solve_ivp DOP853 1e-13", "careful_scipy.py", TIGHT),
    ]
    results = {}
    for label, script, opts in peers:
        results[label] = peer(script, dict(base, **opts))
        log(f"    {label} done")
    rows = []
    for i, (w, b) in enumerate(points):
        ex, ex_at = exact[i]
        ye, ve = np.array(ex["y"]), np.array(ex["v"])
        n = len(ye)
        check = np.array(results["check: solve_ivp DOP853 1e-13"][i]["y"])
        bound = float(np.abs(check - ye).max())
        self_diff = float(np.abs(np.array(ex_at["y"]) - ye).max())
        ex_class = classify(ye, ve, b, spp, tail, ex["tail_events"]["stick"])
        for label, r, note in [
            ("stickslip exact", ex,
             f"|Δy| to the DOP853 1e-13 check: {bound:.1e}; dense vs sample_at: {self_diff:.1e}"),
            ("stickslip exact, sample_at", ex_at, "the library's solver::sample_at driver"),
        ]:
            rows.append({
                "point": [w, b], "solver": label, "wall_s": r["wall_s"]["median"],
                "wall_min_s": r["wall_s"]["min"], "repeats": r["wall_s"]["repeats"],
                "events": r["stats"]["events"], "evals": r["stats"]["evaluations"],
                "steps": r["stats"]["steps"], "err_max": None, "err_final": None,
                "error_bound": bound, "class": ex_class, "ok": True, "note": note,
                "stickslip": True,
            })
        for label, _, _ in peers:
            r = results[label][i]
            y, v = np.array(r["y"]), np.array(r["v"])
            m = len(y)
            err = float(np.abs(y - ye[:m]).max()) if m else float("nan")
            fin = None
            if r["ok"]:
                fin = float(max(abs(r["final"][0] - ex["final"][0]),
                                abs(r["final"][1] - ex["final"][1])))
            events = sum(r["events"].values()) if r["events"] is not None else None
            tail_sticks = r["tail_events"]["stick"] if r["events"] is not None else None
            cls = classify(y, v, b, spp, tail, tail_sticks) if r["ok"] else "failed"
            note = ""
            if not r["ok"]:
                note = (f"{r['message']} at τ = {r['failed_at_tau']:.3g} "
                        f"(period {r['failed_at_tau'] * w / (2 * math.pi):.2f} of {periods}); "
                        f"error over the {m} samples before")
            rows.append({
                "point": [w, b], "solver": label, "wall_s": r["wall_s"], "wall_min_s": None,
                "repeats": 1, "events": events, "evals": r["work"]["nfev"],
                "steps": r["work"]["steps"], "err_max": err, "err_final": fin,
                "error_bound": None, "class": cls, "ok": r["ok"], "note": note,
                "stickslip": False,
            })
    return rows


# ---------------------------------------------------------------- workload (b)


def grid_values(lo, hi, steps):
    return [lo + (hi - lo) * (i / (steps - 1)) for i in range(steps)]


def coarse(cls):
    return "stick" if "stick" in cls else cls


def workload_b(n, periods, subsets, tail):
    """The n x n phase diagram (w 0.1-2.5, beta 0.5-4), every point from rest.

    stickslip: the library's steady::phase_diagram (each point until its stroboscopic map
    repeats), and a fixed `periods` per point for comparison. Peers: a regular sub-grid each
    (`subsets`: label, script, options, every, offset, periods, scales), with stickslip timed
    on exactly the same sub-grid and periods (fixed mode, one thread) for a measured ratio.
    The peers' full-grid times are extrapolated, and labelled so: every grid point takes the
    cost per period measured at the nearest sub-grid point, times the periods stickslip ran
    there (steady) or `periods` (fixed); a peer that fails in its first periods whatever the
    count (`scales` False) takes its time per point instead."""
    log(f"(b) {n} x {n} phase diagram")
    wv, bv = grid_values(0.1, 2.5, n), grid_values(0.5, 4.0, n)

    def grid_args(idx):
        return ["--zeta", repr(ZETA), "--w-from", wv[idx[0]], "--w-to", wv[idx[-1]],
                "--w-steps", len(idx), "--beta-from", bv[idx[0]], "--beta-to", bv[idx[-1]],
                "--beta-steps", len(idx)]

    everything = list(range(n))
    steady = runner(["phase-diagram", "--mode", "steady"] + grid_args(everything))
    steady_1 = runner(["phase-diagram", "--mode", "steady"] + grid_args(everything), threads=1)
    fixed_1 = runner(["phase-diagram", "--mode", "fixed", "--periods", periods, "--tail", tail,
                      "--min-repeats", 1, "--min-seconds", 0] + grid_args(everything),
                     threads=1)
    log(f"    stickslip, steady API: {steady['wall_s']['median'] * 1e3:.1f} ms on "
        f"{steady['threads']} threads, {steady_1['wall_s']['median'] * 1e3:.1f} ms on 1; "
        f"fixed {periods} periods: {fixed_1['wall_s']['median']:.2f} s on 1")
    periods_run = [p["periods_run"] for p in steady["points"]]
    fixed_classes = {(p["w"], p["beta"]): coarse(p["class"]) for p in fixed_1["points"]}
    same = sum(coarse(p["class"]) == fixed_classes.get((p["w"], p["beta"]))
               for p in steady["points"])
    out = {"n": n, "periods": periods, "tail": tail, "steady": summary_b(steady),
           "steady_1": summary_b(steady_1), "fixed_1": summary_b(fixed_1),
           "steady_periods_total": sum(periods_run), "steady_periods_max": max(periods_run),
           "classes": count_classes(steady["points"]),
           "steady_vs_fixed_same_class": same, "peers": []}
    for label, script, opts, every, offset, sub_periods, scales in subsets:
        idx = list(range(offset, n, every))
        sub_tail = min(tail, max(1, sub_periods // 2))
        ours = runner(["phase-diagram", "--mode", "fixed", "--periods", sub_periods, "--tail",
                       sub_tail] + grid_args(idx), threads=1)
        truth = [coarse(p["class"]) for p in ours["points"]]  # w-major, as `points` below
        points = [{"w": wv[i], "beta": bv[j], "periods": sub_periods} for i in idx for j in idx]
        res = peer(script, dict({"zeta": ZETA, "samples_per_period": 20, "keep_samples": True,
                                 "tail_periods": sub_tail, "points": points}, **opts))
        agree, failed, confusion = 0, 0, {}
        for r, want in zip(res, truth):
            if r["ok"]:
                sticks = r["tail_events"]["stick"] if r.get("events") else None
                got = coarse(classify(r["y"], r["v"], r["beta"], 20, sub_tail, sticks))
            else:
                got = "failed"
                failed += 1
            pair = f"{want} → {got}"
            confusion[pair] = confusion.get(pair, 0) + 1
            agree += got == want
        wall = sum(r["wall_s"] for r in res)
        # Extrapolation (not a measurement): cost per period at the nearest sub-grid point.
        cost = {}
        for k, r in enumerate(res):
            cost[(idx[k // len(idx)], idx[k % len(idx)])] = (
                r["wall_s"] / sub_periods if scales else r["wall_s"])
        nearest = [min(idx, key=lambda m: abs(m - i)) for i in range(n)]
        est_steady, est_fixed = 0.0, 0.0
        for i in range(n):
            for j in range(n):
                c = cost[(nearest[i], nearest[j])]
                est_steady += c * (periods_run[i * n + j] if scales else 1)
                est_fixed += c * (periods if scales else 1)
        out["peers"].append({
            "solver": label, "every": every, "offset": offset, "points": len(res),
            "periods": sub_periods, "wall_s": wall, "per_point_s": wall / len(res),
            "stickslip_wall_s": ours["wall_s"]["median"],
            "stickslip_repeats": ours["wall_s"]["repeats"],
            "evals": sum(r["work"]["nfev"] for r in res),
            "steps": sum(r["work"]["steps"] for r in res),
            "agree": agree, "failed": failed, "confusion": confusion,
            "extrapolated_steady_s": est_steady, "extrapolated_fixed_s": est_fixed,
        })
        log(f"    {label}: {len(res)} points x {sub_periods} periods in {wall:.1f} s "
            f"(stickslip on the same: {ours['wall_s']['median'] * 1e3:.2f} ms)")
    return out


def summary_b(r):
    return {"wall_s": r["wall_s"]["median"], "threads": r["threads"], "stats": r["stats"],
            "method": r["method"]}


def count_classes(points):
    counts = {}
    for p in points:
        counts[p["class"]] = counts.get(p["class"], 0) + 1
    return counts


# ---------------------------------------------------------------- workload (c)


def workload_c(points, periods, settings, shockley_settings):
    """The paper's circuit with Shockley diodes: ngspice against the stickslip stiff solver,
    both against a tight SciPy LSODA reference on the last period."""
    log(f"(c) Shockley diodes, {len(points)} points of {periods} periods")
    rows = []
    have_shockley = shockley_available()
    for w, b in points:
        runs = []
        for label, opts, spp, method in settings:
            point = {"w": w, "beta": b, "periods": periods}
            if opts is None:
                # The library's own netlist (stickslip::shockley::netlist), run as it is.
                lib = runner(["netlist", "--w", w, "--beta", b, "--periods", periods])
                point["netlist"] = lib["netlist"]
                spp = round(1 / lib["max_step_fraction"])
            # (The cheap settings are repeated: the median of 3 is steadier on a loaded
            # machine; the tight ones take seconds each and run once.)
            repeats = 3 if label in ("ngspice default", "ngspice on `stickslip netlist`") else 1
            r = peer("ngspice_peer.py", {"points": [point], "options": opts or {},
                                         "steps_per_period": spp, "method": method,
                                         "repeats": repeats})[0]
            r["label"] = label
            r["settings"] = {"options": opts, "tmax": f"T/{spp}", "method": method,
                             "repeats": repeats}
            runs.append(r)
        ours = []
        if have_shockley:
            for rtol, max_step in shockley_settings:
                extra = [] if max_step is None else ["--max-step", max_step]
                r = runner(["shockley", "--w", w, "--beta", b, "--periods", periods,
                            "--rtol", rtol] + extra)
                r["label"] = f"stickslip shockley rtol {rtol:g}" + (
                    "" if max_step is None else f", max_step {max_step:g}")
                r["rtol"] = rtol
                ours.append(r)
        times = set()
        for r in runs:
            if r["ok"]:
                times.update(r["last_period"]["tau"])
        for r in ours:
            times.update(r["last_period"]["tau"])
        job = {"points": [{"w": w, "beta": b, "periods": periods, "times": sorted(times)}]}
        ref = peer("shockley_reference.py", dict(job, rtol=1e-11))[0]
        # The reference's own error, estimated by the same run at a ten times looser rtol.
        looser = peer("shockley_reference.py", dict(job, rtol=1e-10))[0]
        ref_err = max(abs(a - c) for a, c in zip(ref["y"], looser["y"]))
        lookup = dict(zip(ref["tau"], ref["y"]))
        amp = max(abs(y) for y in ref["y"])

        def error(lp):
            return max(abs(y - lookup[t]) for t, y in zip(lp["tau"], lp["y"]))

        rows.append({"point": [w, b], "solver": "reference: SciPy LSODA 1e-11",
                     "wall_s": ref["wall_s"], "work": ref["work"], "err": None,
                     "reference_check": ref_err, "amplitude": amp,
                     "ok": ref["ok"] and looser["ok"], "stickslip": False})
        for r in ours:
            work = dict(r["stats"], newton=r["newton_iterations"])
            rows.append({"point": [w, b], "solver": r["label"], "wall_s": r["wall_s"]["median"],
                         "work": work, "err": error(r["last_period"]), "rtol": r["rtol"],
                         "amplitude": amp, "ok": True, "stickslip": True})
        for r in runs:
            if r["settings"]["repeats"] > 1:
                r["label"] += f" (median of {r['settings']['repeats']})"
            rows.append({"point": [w, b], "solver": r["label"], "wall_s": r["wall_s"],
                         "analysis_s": r["analysis_s"], "work": r["work"],
                         "err": error(r["last_period"]) if r["ok"] else None,
                         "amplitude": amp, "ok": r["ok"], "settings": r["settings"],
                         "stickslip": False})
        log(f"    w = {w}: done")
    return rows, have_shockley


def shockley_available():
    proc = subprocess.run([RUNNER, "shockley", "--help"], capture_output=True, text=True)
    return proc.returncode == 0


# ---------------------------------------------------------------- reporting helpers


def fmt_time(s):
    if s is None or (isinstance(s, float) and math.isnan(s)):
        return "–"
    if s < 1e-3:
        return f"{s * 1e6:.0f} µs"
    if s < 1.0:
        return f"{s * 1e3:.2f} ms"
    if s < 120.0:
        return f"{s:.2f} s"
    return f"{s / 60:.1f} min"


def fmt_num(x):
    return "–" if x is None else f"{x:,}".replace(",", " ")


def fmt_err(x):
    if x is None:
        return "–"
    if isinstance(x, float) and math.isnan(x):
        return "nan"
    return f"{x:.1e}"


def table(headers, rows):
    out = ["| " + " | ".join(headers) + " |", "|" + "|".join("---" for _ in headers) + "|"]
    for r in rows:
        out.append("| " + " | ".join(str(c) for c in r) + " |")
    return "\n".join(out)


def speedup(peer_s, ours_s):
    if not peer_s or not ours_s:
        return "–"
    return f"{peer_s / ours_s:,.0f}×".replace(",", " ")


def report_a(rows):
    headers = ["point (w, β)", "solver", "wall", "events", "RHS evals", "steps",
               "max error of y", "final error of (y, y')", "class", "speed-up", "note"]
    out = []
    ours = {tuple(r["point"]): r for r in rows if r["solver"] == "stickslip exact"}
    for r in rows:
        mine = ours[tuple(r["point"])]
        wall = fmt_time(r["wall_s"])
        if r["stickslip"]:
            wall += f" (median of {r['repeats']})"
        err = fmt_err(r["err_max"])
        if r["solver"] == "stickslip exact":
            err = f"≤ {r['error_bound']:.1e} ¹"
        out.append([f"({r['point'][0]}, {r['point'][1]})", r["solver"], wall,
                    fmt_num(r["events"]), fmt_num(r["evals"]), fmt_num(r["steps"]), err,
                    fmt_err(r["err_final"]), r["class"],
                    "" if r["solver"] == "stickslip exact" else speedup(r["wall_s"], mine["wall_s"]),
                    r["note"] if r["solver"] != "stickslip exact" else ""])
    return table(headers, out)


def targets_a(rows):
    """Target (a): >= 1000x faster than the careful SciPy solvers at equal or better accuracy
    (stickslip's error bound <= the peer's max error), per point where anything moves."""
    lines = []
    ok_all = True
    ours = {tuple(r["point"]): r for r in rows if r["solver"] == "stickslip exact"}
    for r in rows:
        if not r["solver"].startswith("careful"):
            continue
        mine = ours[tuple(r["point"])]
        if mine["events"] == 0:
            lines.append(f"- ({r['point'][0]}, {r['point'][1]}) {r['solver']}: nothing moves "
                         f"(static from rest): no integration in either; not counted")
            continue
        ratio = r["wall_s"] / mine["wall_s"]
        accurate = mine["error_bound"] <= r["err_max"]
        met = ratio >= 1000 and accurate
        ok_all &= met
        lines.append(f"- ({r['point'][0]}, {r['point'][1]}) vs {r['solver']}: {ratio:,.0f}× "
                     f"faster; error {mine['error_bound']:.1e} (bound) vs {r['err_max']:.1e}: "
                     f"{'met' if met else 'MISSED'}")
    return ok_all, lines


def report_b(b):
    n, periods = b["n"], b["periods"]
    st, st1, fx1 = b["steady"], b["steady_1"], b["fixed_1"]
    lines = [
        f"stickslip, all {n * n} points from rest, measured:",
        "",
        f"- `steady::phase_diagram` (the library's API): **{fmt_time(st['wall_s'])}** on "
        f"{st['threads']} threads, **{fmt_time(st1['wall_s'])}** on 1 thread; "
        f"{fmt_num(b['steady_periods_total'])} drive periods in all (at most "
        f"{b['steady_periods_max']} at one point), {fmt_num(st['stats']['events'])} events, "
        f"{fmt_num(st['stats']['evaluations'])} evaluations; classes "
        + ", ".join(f"{k} {v}" for k, v in sorted(b["classes"].items())) + ".",
        f"- a fixed {periods} periods per point, classified from the events of the last "
        f"{b['tail']}: **{fmt_time(fx1['wall_s'])}** on 1 thread "
        f"({fmt_num(fx1['stats']['events'])} events); the same coarse class as the steady "
        f"API at {b['steady_vs_fixed_same_class']} of {n * n} points.",
        "",
        "Peers on a sub-grid, stickslip (fixed periods, 1 thread) on exactly the same points "
        "and periods; full-grid times of the peers are **extrapolations**, not measurements (see BENCHMARKS.md):",
        "",
    ]
    headers = ["peer", "sub-grid × periods (measured)", "peer wall", "stickslip wall, same work",
               "speed-up (measured)", "classes agree with stickslip",
               "peer, full grid as steady API (extrapolated)", "speed-up vs steady API, 1 thread",
               f"peer, full grid × {periods} periods (extrapolated)",
               f"speed-up vs fixed {periods}, 1 thread"]
    rows = []
    for p in b["peers"]:
        side = int(round(math.sqrt(p["points"])))
        conf = ", ".join(f"{k} {v}" for k, v in sorted(p["confusion"].items()))
        if p["failed"] == p["points"]:
            none = "– (failed at every point: no diagram)"
            rows.append([
                p["solver"],
                f"{side}×{side} (every {p['every']}th from index {p['offset']}) × {p['periods']}",
                fmt_time(p["wall_s"]), fmt_time(p["stickslip_wall_s"]),
                speedup(p["wall_s"], p["stickslip_wall_s"]),
                f"{p['agree']}/{p['points']} ({conf})", none, "–", none, "–",
            ])
            continue
        rows.append([
            p["solver"],
            f"{side}×{side} (every {p['every']}th from index {p['offset']}) × {p['periods']}",
            fmt_time(p["wall_s"]), fmt_time(p["stickslip_wall_s"]),
            speedup(p["wall_s"], p["stickslip_wall_s"]),
            f"{p['agree']}/{p['points']} ({conf})",
            f"≈ {fmt_time(p['extrapolated_steady_s'])}",
            f"≈ {speedup(p['extrapolated_steady_s'], st1['wall_s'])}",
            f"≈ {fmt_time(p['extrapolated_fixed_s'])}",
            f"≈ {speedup(p['extrapolated_fixed_s'], fx1['wall_s'])}",
        ])
    return "\n".join(lines) + "\n" + table(headers, rows)


def report_c(rows, have_shockley):
    headers = ["point (w, β)", "solver", "wall", "ngspice analysis time", "work",
               "max error of y, last period", "relative to amplitude",
               "speed-up at matched accuracy"]
    out = []
    for r in rows:
        work = r["work"] or {}
        if "accepted" in work and work["accepted"] is None:
            wtxt = "– (the netlist prints no counters)"
        elif "accepted" in work:
            wtxt = (f"{fmt_num(int(work['accepted'] or 0))} accepted, "
                    f"{fmt_num(int(work['rejected'] or 0))} rejected, "
                    f"{fmt_num(int(work['iterations'] or 0))} Newton its")
        else:
            wtxt = ", ".join(f"{k} {fmt_num(v)}" for k, v in work.items())
        match = ""
        if r["solver"].startswith("ngspice") and r["ok"] and have_shockley:
            cands = [o for o in rows if o["point"] == r["point"] and o["stickslip"]
                     and o["err"] is not None and o["err"] <= r["err"]]
            if cands:
                best = min(cands, key=lambda o: o["wall_s"])
                match = f"{speedup(r['wall_s'], best['wall_s'])} (vs {best['solver']})"
            else:
                match = "no stickslip run as accurate"
        out.append([f"({r['point'][0]}, {r['point'][1]})", r["solver"], fmt_time(r["wall_s"]),
                    fmt_time(r.get("analysis_s")), wtxt,
                    (fmt_err(r["err"]) if r["ok"] else "failed") if "reference_check" not in r
                    else f"±{r['reference_check']:.0e} (vs rtol 1e-10)",
                    fmt_err(r["err"] / r["amplitude"]) if r["err"] is not None else "–", match])
    return table(headers, out)


def targets_c(rows):
    lines, ok_all = [], True
    for r in rows:
        if not (r["solver"].startswith("ngspice") and r["ok"]):
            continue
        cands = [o for o in rows if o["point"] == r["point"] and o["stickslip"]
                 and o["err"] <= r["err"]]
        if not cands:
            ok_all = False
            lines.append(f"- ({r['point'][0]}, {r['point'][1]}) {r['solver']}: no stickslip run "
                         f"as accurate (error {r['err']:.1e}): MISSED")
            continue
        best = min(cands, key=lambda o: o["wall_s"])
        ratio = r["wall_s"] / best["wall_s"]
        met = ratio >= 20
        ok_all &= met
        lines.append(f"- ({r['point'][0]}, {r['point'][1]}) {r['solver']} (error {r['err']:.1e})"
                     f" vs {best['solver']} (error {best['err']:.1e}): {ratio:,.0f}× faster: "
                     f"{'met' if met else 'MISSED'}")
    return ok_all, lines


# ---------------------------------------------------------------- main


class Checks:
    """Correctness checks of the run (agreement, no failures); never timings."""

    def __init__(self):
        self.passed = 0
        self.failures = []

    def check(self, ok, message):
        if ok:
            self.passed += 1
        else:
            self.failures.append(message)


def render(results):
    """The tables of a run, as Markdown (also from a saved results.json: --render)."""
    info = results["machine"]
    sections = []
    if "a" in results:
        rows = results["a"]
        _, lines = targets_a(rows)
        periods = results["sizes"]["a_periods"]
        sections.append(f"## (a) One trajectory of {periods} drive periods from rest, "
                        f"20 samples per period (Fig. 6 points, ζ = {ZETA:.10g})\n\n"
                        + report_a(rows) + "\n\n¹ stickslip's error: at most its largest "
                        "difference to the independent DOP853 run at rtol 1e-13.\n\n"
                        "Target ≥ 1000× at equal or better accuracy:\n\n" + "\n".join(lines))
    if "b" in results:
        b = results["b"]
        sections.append(f"## (b) {b['n']} × {b['n']} phase diagram, w 0.1–2.5, β 0.5–4\n\n"
                        + report_b(b))
    if "c" in results:
        rows, have = results["c"], results["c_have_shockley"]
        text = report_c(rows, have)
        if have:
            _, lines = targets_c(rows)
            text += "\n\nTarget ≥ 20× at matched accuracy:\n\n" + "\n".join(lines)
        else:
            text += ("\n\nThe stickslip side of (c) needs `stickslip::shockley` (not in this "
                     "build): only the peers ran.")
        sections.append(f"## (c) Shockley diodes, {results['sizes']['c_periods']} periods of "
                        f"the paper's circuit (Fig. 3 points)\n\n" + text)
    head = (f"# stickslip benchmark{' (smoke)' if results['smoke'] else ''}\n\n"
            f"Machine: {info['cpu']}, {info['cores']} cores, {info.get('memory_gib', '?')} GiB; "
            f"{info['platform']}; Python {info['python']}, NumPy {info['numpy']}, SciPy "
            f"{info['scipy']}; {info['ngspice']}; {info['rustc']}.\n"
            f"Load average (1, 5, 15 min) at start {tuple(round(x, 2) for x in info['load_start'])}, "
            f"at end {tuple(round(x, 2) for x in info['load_end'])}; harness "
            f"{info['harness_s']:.0f} s.\n"
            "Speed-up = peer wall time / stickslip wall time, both from this run.")
    return head + "\n\n" + "\n\n".join(sections) + "\n"


def run_checks(results):
    """Correctness checks: agreement with the exact solution and the references, no failed
    peer runs. No timing enters a check: the targets are reported, never enforced."""
    checks = Checks()
    for r in results.get("a", []):
        rows = results["a"]
        mine = next(o for o in rows
                    if o["point"] == r["point"] and o["solver"] == "stickslip exact")
        if r["solver"].startswith("careful"):
            checks.check(r["err_max"] <= 1e-6, f"(a) {r['solver']} at {r['point']}: error "
                         f"{r['err_max']:.2e} against stickslip (expected <= 1e-6)")
            checks.check(coarse(r["class"]) == coarse(mine["class"]),
                         f"(a) {r['solver']} at {r['point']}: class {r['class']}, "
                         f"stickslip {mine['class']}")
        if r["solver"] == "stickslip exact":
            checks.check(r["error_bound"] <= 1e-8, f"(a) stickslip at {r['point']}: differs "
                         f"by {r['error_bound']:.2e} from the DOP853 1e-13 check")
    for p in results.get("b", {}).get("peers", []):
        if p["solver"].startswith("careful"):
            # (Near the stick-slip boundary a class can legitimately flip with a 1e-10 error;
            # a wholesale disagreement is breakage.)
            checks.check(p["agree"] >= 0.75 * p["points"],
                         f"(b) {p['solver']}: classes agree with stickslip at only "
                         f"{p['agree']} of {p['points']} points")
    for r in results.get("c", []):
        if r["solver"].startswith("reference"):
            checks.check(r["ok"], f"(c) the reference at {r['point']} failed")
        elif r["solver"].startswith("ngspice"):
            checks.check(r["ok"], f"(c) {r['solver']} at {r['point']} failed")
            checks.check(r["ok"] and r["err"] <= 0.05 * r["amplitude"],
                         f"(c) {r['solver']} at {r['point']}: error {r['err']} against "
                         f"the reference (expected <= 5% of the amplitude)")
        elif r["stickslip"] and r["rtol"] <= 1e-6:
            checks.check(r["err"] <= 1e-4 * r["amplitude"],
                         f"(c) {r['solver']} at {r['point']}: error {r['err']:.2e} against "
                         f"the reference (expected <= 1e-4 of the amplitude)")
    return checks


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--smoke", action="store_true",
                    help="tiny workloads (under a minute): checks that everything runs and "
                         "agrees; no timing target is enforced")
    ap.add_argument("--out", default=os.path.join(ROOT, "target", "bench"),
                    help="directory for results.json and tables.md [default: target/bench]")
    ap.add_argument("--only", choices=["a", "b", "c"], action="append",
                    help="run only these workloads (repeatable)")
    ap.add_argument("--render", metavar="RESULTS_JSON",
                    help="print the tables of a saved results.json again, run nothing")
    args = ap.parse_args()
    if args.render:
        with open(args.render) as fh:
            print(render(json.load(fh)))
        return 0
    only = set(args.only or ["a", "b", "c"])
    os.makedirs(args.out, exist_ok=True)
    started = time.perf_counter()
    info = machine()
    info["load_start"] = loadavg()
    info["started"] = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")
    if args.smoke:
        a_points, a_periods, a_tail = FIG6[:2], 10, 5
        b_n, b_periods, b_tail = 8, 20, 10
        b_subsets = [("paper: odeint LSODA, defaults", "paper_lsoda.py", {}, 4, 1, 20, False),
                     ("careful: solve_ivp DOP853 1e-10", "careful_scipy.py",
                      {"method": "DOP853", "rtol": 1e-10, "atol": 1e-12}, 4, 1, 10, True)]
        c_points, c_periods = FIG3[1:2], 5
        c_settings = NGSPICE_SETTINGS[1:2] + NGSPICE_SETTINGS[3:]
        c_shockley = [(1e-6, None), (1e-8, None)]
    else:
        a_points, a_periods, a_tail = FIG6, 300, 50
        b_n, b_periods, b_tail = 40, 300, 50
        b_subsets = [
            ("paper: odeint LSODA, defaults", "paper_lsoda.py", {}, 5, 2, 300, False),
            ("careful: solve_ivp DOP853 1e-10", "careful_scipy.py",
             {"method": "DOP853", "rtol": 1e-10, "atol": 1e-12}, 5, 2, 60, True),
            ("careful: solve_ivp LSODA 1e-10", "careful_scipy.py",
             {"method": "LSODA", "rtol": 1e-10, "atol": 1e-12}, 10, 2, 60, True),
        ]
        c_points, c_periods, c_settings = FIG3, 300, NGSPICE_SETTINGS
        c_shockley = SHOCKLEY_SETTINGS
    results = {"machine": info, "smoke": args.smoke,
               "sizes": {"a_periods": a_periods, "c_periods": c_periods}}
    if "a" in only:
        results["a"] = workload_a(a_points, a_periods, 20, a_tail)
        results["target_a_met"] = targets_a(results["a"])[0]
    if "b" in only:
        results["b"] = workload_b(b_n, b_periods, b_subsets, b_tail)
    if "c" in only:
        results["c"], results["c_have_shockley"] = workload_c(c_points, c_periods, c_settings,
                                                              c_shockley)
        if results["c_have_shockley"]:
            results["target_c_met"] = targets_c(results["c"])[0]
    info["load_end"] = loadavg()
    info["harness_s"] = time.perf_counter() - started
    text = render(results)
    checks = run_checks(results)
    with open(os.path.join(args.out, "results.json"), "w") as fh:
        json.dump(results, fh, indent=1)
    with open(os.path.join(args.out, "tables.md"), "w") as fh:
        fh.write(text)
    print(text)
    print(f"results in {args.out}")
    for p in checks.failures:
        print(f"CHECK FAILED: {p}")
    print(f"bench: {checks.passed} passed, {len(checks.failures)} failed")
    return 1 if checks.failures else 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except Failure as exc:
        print(f"error: {exc}", file=sys.stderr)
        sys.exit(2)
