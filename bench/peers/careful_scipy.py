"""Peer 2, "a careful SciPy user": scipy.integrate.solve_ivp on each sliding segment with the
friction sign held fixed, a terminal event at the velocity zero, and explicit stick phases.

At every velocity zero the stick condition |beta*cos(w*t) - y| <= mu_s is checked: a stop
is held (y' = 0, y fixed) until the force leaves [-mu_s, mu_s], found in closed form; a
turn starts a new segment in the other direction. Extra job options: "method" (DOP853,
LSODA, RK45, Radau, BDF), "rtol", "atol", "tail_periods" (events of the last this many
periods are also counted apart, for classification; default 50).
"""

import math
import time

import numpy as np
from scipy.integrate import solve_ivp

from common import TAU, read_job, sample_grid, stick_exit, write_answer


def rhs(t, s, zeta, w, beta, sign):
    return (s[1], beta * math.cos(w * t) - 2.0 * zeta * s[1] - s[0] - sign)


def velocity_zero(t, s, zeta, w, beta, sign):
    return sign * s[1]


velocity_zero.terminal = True
velocity_zero.direction = -1


def run_point(zeta, mu_s, w, beta, periods, spp, method, rtol, atol, tail):
    t_end, grid = sample_grid(np, w, periods, spp)
    tail_start = max(periods - tail, 0.0) * (TAU / w)
    ys = np.empty_like(grid)
    vs = np.empty_like(grid)
    counts = {"turn": 0, "stick": 0, "slip": 0}
    tail_counts = dict(counts)

    def count(kind):
        counts[kind] += 1
        if t >= tail_start:
            tail_counts[kind] += 1

    work = {"nfev": 0, "njev": 0, "nlu": 0, "steps": 0, "segments": 0}
    t, y, v = 0.0, 0.0, 0.0
    k = 0  # next grid index to fill
    force = beta - y
    if abs(force) <= mu_s:
        mode, sign = "stick", 0.0
    else:
        mode, sign = "slide", math.copysign(1.0, force)
    while t < t_end:
        if mode == "stick":
            exit_local, exit_sign = stick_exit((w * t) % TAU, y, beta, w, mu_s)
            t_next = min(t + exit_local, t_end)
            while k < grid.size and grid[k] <= t_next:
                ys[k], vs[k] = y, 0.0
                k += 1
            t = t_next
            if t >= t_end:
                break
            count("slip")
            mode, sign, v = "slide", exit_sign, 0.0
            continue
        sol = solve_ivp(
            rhs,
            (t, t_end),
            [y, v],
            method=method,
            rtol=rtol,
            atol=atol,
            events=velocity_zero,
            dense_output=True,
            args=(zeta, w, beta, sign),
        )
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed at t = {t}: {sol.message}")
        work["nfev"] += int(sol.nfev)
        work["njev"] += int(sol.njev)
        work["nlu"] += int(sol.nlu)
        work["steps"] += len(sol.sol.ts) - 1
        work["segments"] += 1
        if sol.status == 1:
            t_stop = float(sol.t_events[0][0])
            y_stop = float(sol.y_events[0][0][0])
        else:
            t_stop, y_stop = t_end, float(sol.y[0, -1])
        j = k
        while j < grid.size and grid[j] <= t_stop:
            j += 1
        if j > k:
            dense = sol.sol(grid[k:j])
            ys[k:j], vs[k:j] = dense[0], dense[1]
            k = j
        if sol.status != 1:
            y, v, t = y_stop, float(sol.y[1, -1]), t_end
            break
        t, y, v = t_stop, y_stop, 0.0
        force = beta * math.cos(w * t) - y
        if abs(force) <= mu_s:
            count("stick")
            mode = "stick"
        elif math.copysign(1.0, force) != sign:
            count("turn")
            sign = -sign
        # else: a tangential touch with the force still pushing onward: slide on.
    while k < grid.size:  # the end point itself, if the loop ended exactly on it
        ys[k], vs[k] = y, v
        k += 1
    return ys, vs, counts, tail_counts, work, (y, v)


def main():
    job = read_job()
    method = job.get("method", "DOP853")
    rtol = float(job.get("rtol", 1e-10))
    atol = float(job.get("atol", 1e-12))
    zeta, mu_s, spp = job["zeta"], job.get("mu_s", 1.0), job["samples_per_period"]
    tail = float(job.get("tail_periods", 50))
    results = []
    for p in job["points"]:
        start = time.perf_counter()
        ys, vs, counts, tail_counts, work, final = run_point(
            zeta, mu_s, p["w"], p["beta"], p["periods"], spp, method, rtol, atol, tail
        )
        wall = time.perf_counter() - start
        r = {
            "w": p["w"],
            "beta": p["beta"],
            "periods": p["periods"],
            "wall_s": wall,
            "ok": True,
            "message": "",
            "events": counts,
            "tail_periods": tail,
            "tail_events": tail_counts,
            "work": work,
            "final": list(final),
        }
        if job.get("keep_samples", True):
            r["y"], r["v"] = ys.tolist(), vs.tolist()
        results.append(r)
    write_answer(
        "careful-" + method.lower(), {"method": method, "rtol": rtol, "atol": atol}, results
    )


if __name__ == "__main__":
    main()
