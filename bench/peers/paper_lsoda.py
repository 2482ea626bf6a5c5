"""Peer 1, "the paper's method": scipy.integrate.odeint (LSODA) on
y'' + 2 zeta y' + y + sgn(y') = beta cos(w t) with no stick logic, default tolerances.

Without stick logic the integrator chatters at every stop (sgn(y') flips from step to step
while the true velocity stays 0); whatever it returns, including failures such as "Excess
work done on this call", is recorded as the result, with LSODA's own message, the time it
reached, and the samples up to there (odeint leaves the rest of its output uninitialised). Extra job options: "rtol", "atol",
"mxstep" (default: odeint's defaults, rtol = atol = 1.49012e-8, mxstep 0 = 500).
"""

import time
import warnings

import numpy as np
from scipy.integrate import odeint

from common import read_job, sample_grid, write_answer


def rhs(s, t, zeta, w, beta):
    y, v = s
    return [v, beta * np.cos(w * t) - 2.0 * zeta * v - y - np.sign(v)]


def main():
    job = read_job()
    zeta, spp = job["zeta"], job["samples_per_period"]
    kwargs = {}
    for key in ("rtol", "atol", "mxstep"):
        if key in job:
            kwargs[key] = job[key]
    results = []
    for p in job["points"]:
        w, beta = p["w"], p["beta"]
        _, grid = sample_grid(np, w, p["periods"], spp)
        with warnings.catch_warnings():
            # odeint's ODEintWarning repeats the message returned in `info`.
            warnings.simplefilter("ignore")
            start = time.perf_counter()
            sol, info = odeint(
                rhs, [0.0, 0.0], grid, args=(zeta, w, beta), full_output=True, **kwargs
            )
            wall = time.perf_counter() - start
        ok = info["message"] == "Integration successful."
        # After a failure odeint leaves the rest of its output uninitialised: the rows are
        # valid up to the last output time that LSODA actually reached (tcur >= t_out).
        valid = grid.size
        failed_at = None
        counted = grid.size - 2  # the info entry of the last output step
        if not ok:
            reached = info["tcur"] >= grid[1:]
            first_miss = int(np.argmin(reached)) if not reached.all() else grid.size - 1
            valid = first_miss + 1
            failed_at = float(info["tcur"][first_miss])
            counted = first_miss  # (odeint fills in the counters of the failing step too)
        last = valid - 1
        r = {
            "w": w,
            "beta": beta,
            "periods": p["periods"],
            "wall_s": wall,
            "ok": ok,
            "message": info["message"],
            "failed_at_tau": failed_at,
            "valid_samples": valid,
            "events": None,
            "work": {
                "nfev": int(info["nfe"][counted]),
                "njev": int(info["nje"][counted]),
                "steps": int(info["nst"][counted]),
            },
            "final": [float(sol[last, 0]), float(sol[last, 1])],
        }
        if job.get("keep_samples", True):
            r["y"], r["v"] = sol[:valid, 0].tolist(), sol[:valid, 1].tolist()
        results.append(r)
    write_answer("paper-odeint-lsoda", kwargs, results)


if __name__ == "__main__":
    main()
