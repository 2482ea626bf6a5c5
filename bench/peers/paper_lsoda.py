"""Peer 1, "the paper's method": scipy.integrate.odeint (LSODA) on
y'' + 2 zeta y' + y + sgn(y') = beta cos(w t) with no stick logic, default tolerances.

Without stick logic the integrator chatters through every stop (sgn(y') flips at each
step); whatever it returns, including failures such as "Excess work done on this call",
is recorded as the result, with LSODA's own message. Extra job options: "rtol", "atol",
"mxstep" (default: odeint's defaults, rtol = atol = 1.49012e-8, mxstep 0 = 500).
"""

import contextlib
import io
import os
import sys
import tempfile
import time

import numpy as np
from scipy.integrate import odeint

from common import read_job, sample_grid, write_answer


def rhs(s, t, zeta, w, beta):
    y, v = s
    return [v, beta * np.cos(w * t) - 2.0 * zeta * v - y - np.sign(v)]


@contextlib.contextmanager
def captured_fd2():
    """LSODA's Fortran warnings go to file descriptor 2 directly: capture them."""
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile(mode="w+b") as tmp:
        os.dup2(tmp.fileno(), 2)
        box = {}
        try:
            yield box
        finally:
            sys.stderr.flush()
            os.dup2(saved, 2)
            os.close(saved)
            tmp.seek(0)
            box["text"] = tmp.read().decode("utf-8", "replace")


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
        with captured_fd2() as box, contextlib.redirect_stderr(io.StringIO()):
            start = time.perf_counter()
            sol, info = odeint(
                rhs, [0.0, 0.0], grid, args=(zeta, w, beta), full_output=True, **kwargs
            )
            wall = time.perf_counter() - start
        ok = info["message"] == "Integration successful."
        warnings = [line.strip() for line in box.get("text", "").splitlines() if line.strip()]
        # Distinct warning texts, in order (LSODA repeats them for every failing output step).
        distinct = list(dict.fromkeys(w_.split(" t ")[0] for w_ in warnings if "lsoda--" in w_))
        r = {
            "w": w,
            "beta": beta,
            "periods": p["periods"],
            "wall_s": wall,
            "ok": ok,
            "message": info["message"],
            "warnings": len([x for x in warnings if "lsoda--" in x]),
            "warning_texts": distinct[:4],
            "events": None,
            "work": {
                "nfev": int(info["nfe"][-1]),
                "njev": int(info["nje"][-1]),
                "steps": int(info["nst"][-1]),
            },
            "final": [float(sol[-1, 0]), float(sol[-1, 1])],
        }
        if job.get("keep_samples", True):
            r["y"], r["v"] = sol[:, 0].tolist(), sol[:, 1].tolist()
        results.append(r)
    write_answer("paper-odeint-lsoda", kwargs, results)


if __name__ == "__main__":
    main()
