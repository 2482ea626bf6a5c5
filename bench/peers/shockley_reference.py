"""Reference for workload (c): the paper's circuit with Shockley diodes, in the dimensionless
form y'' + 2 zeta_R y' + y + D(y') = beta cos(w tau), integrated by LSODA (odeint, Fortran)
with the analytic Jacobian at a tight tolerance, from rest.

    D(v) = (n V_T / U_t) asinh(v (U_t / Z) / (2 I_s)) + (R_s / Z) v,
    zeta_R = R / (2 Z),  Z = sqrt(L/C),  V_T = k (27 C) / q,  U_t = 0.7 V (the unit of y).

The same law as ngspice's two anti-parallel diodes (up to R_s times the blocking diode's
reverse current, a few nV). Job options: "rtol" (default 1e-11), "atol" (default rtol/100);
per point "w", "beta", "periods" and "times": the dimensionless times at which to report
y and y' (sorted, within the run); without "times", 200 samples of the last period.
"""

import math
import time
import warnings

import numpy as np
from scipy.integrate import odeint

from common import TAU, read_job, write_answer

L, C, R = 11.5e-3, 0.02e-6, 68.0
U_T = 0.7
IS, N, RS = 4.352e-9, 1.906, 0.6458
BOLTZMANN, CHARGE = 1.380649e-23, 1.602176634e-19
V_THERMAL = BOLTZMANN * (27.0 + 273.15) / CHARGE
Z = math.sqrt(L / C)
ZETA_R = R / (2.0 * Z)
SCALE = N * V_THERMAL / U_T  # asinh amplitude, in units of y
KNEE = U_T / Z / (2.0 * IS)  # y' -> i / (2 I_s)
RES = RS / Z  # series resistance, dimensionless


def rhs(s, t, w, beta):
    y, v = s
    return [v, beta * math.cos(w * t) - y - 2.0 * ZETA_R * v - SCALE * math.asinh(KNEE * v) - RES * v]


def jac(s, t, w, beta):
    v = s[1]
    slope = SCALE * KNEE / math.sqrt(1.0 + (KNEE * v) ** 2) + RES
    return [[0.0, 1.0], [-1.0, -2.0 * ZETA_R - slope]]


def main():
    job = read_job()
    rtol = float(job.get("rtol", 1e-11))
    atol = float(job.get("atol", rtol * 1e-2))
    results = []
    for p in job["points"]:
        w, beta, periods = p["w"], p["beta"], p["periods"]
        period = TAU / w
        times = p.get("times")
        if times is None:
            times = ((periods - 1) * period + period * np.arange(201) / 200).tolist()
        grid = np.concatenate([[0.0], np.asarray(times, dtype=float)])
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            start = time.perf_counter()
            sol, info = odeint(
                rhs,
                [0.0, 0.0],
                grid,
                args=(w, beta),
                Dfun=jac,
                rtol=rtol,
                atol=atol,
                mxstep=10**8,
                full_output=True,
            )
            wall = time.perf_counter() - start
        results.append(
            {
                "w": w,
                "beta": beta,
                "periods": periods,
                "wall_s": wall,
                "ok": info["message"] == "Integration successful.",
                "message": info["message"],
                "work": {
                    "nfev": int(info["nfe"][-1]),
                    "njev": int(info["nje"][-1]),
                    "steps": int(info["nst"][-1]),
                },
                "tau": grid[1:].tolist(),
                "y": sol[1:, 0].tolist(),
                "v": sol[1:, 1].tolist(),
            }
        )
    write_answer("scipy-lsoda-reference", {"rtol": rtol, "atol": atol}, results)


if __name__ == "__main__":
    main()
