"""Shared pieces of the Python peers: the job format, the sample grid, the stick exit.

Every peer reads one JSON job on standard input and prints one JSON document on standard
output. A job looks like

    {"zeta": 0.0468..., "mu_s": 1.0, "samples_per_period": 20, "keep_samples": true,
     "points": [{"w": 0.9, "beta": 1.6, "periods": 300}, ...], ...peer options...}

and the answer is {"peer": ..., "options": {...}, "results": [one object per point]}.
Each result holds the wall time of the solver calls alone ("wall_s", time.perf_counter;
interpreter start-up, imports and JSON I/O excluded), work counters, and the samples
(y, v at the grid below) when asked for.
"""

import json
import math
import sys

TAU = 2.0 * math.pi


def read_job():
    return json.load(sys.stdin)


def write_answer(peer, options, results):
    json.dump({"peer": peer, "options": options, "results": results}, sys.stdout)
    sys.stdout.write("\n")


def sample_grid(np, w, periods, samples_per_period):
    """The grid of the Rust side (stickslip::solver::grid): t_end * (k / n), k = 0..n."""
    t_end = periods * (TAU / w)
    n = int(round(periods * samples_per_period))
    return t_end, t_end * (np.arange(n + 1) / n)


def stick_exit(theta, y, beta, w, mu_s):
    """Local time and direction at which a stop at y, starting at drive phase theta, ends:
    the first outward crossing of beta*cos(psi) - y = +-mu_s (closed form, as a careful
    user would write it). Returns (math.inf, 0.0) when the stop lasts for ever."""
    if beta == 0.0:
        return math.inf, 0.0
    up = (y + mu_s) / beta
    down = (y - mu_s) / beta
    if up <= -1.0:
        return 0.0, 1.0
    if down >= 1.0:
        return 0.0, -1.0
    best = (math.inf, 0.0)
    if up < 1.0:
        d = (TAU - math.acos(up) - theta) % TAU
        if d > TAU - 1e-12:
            d = 0.0
        best = (d, 1.0)
    if down > -1.0:
        d = (math.acos(down) - theta) % TAU
        if d > TAU - 1e-12:
            d = 0.0
        if d < best[0]:
            best = (d, -1.0)
    return best[0] / w, best[1]
