"""Peer 3: ngspice on the paper's circuit with two anti-parallel 1N4148 diodes (Shockley law).

The netlist is the series circuit of the paper: a sinusoidal source U cos(Omega t), R = 68 ohm,
L = 11.5 mH, the diode pair, C = 0.02 uF (the capacitor to ground, so u_C = v(c)), starting
from rest (`uic`: u_C = 0, i = 0). Diodes: `.model D1N4148 D(Is=4.352n N=1.906 Rs=0.6458)`
at 27 C (SPICE's default). The transient runs over all periods but stores only the last one
(TSTART), so that output does not dominate the time.

Job options: "zeta" is ignored (the circuit fixes it); per point "w", "beta", "periods";
"options": a dict of .options (e.g. {"reltol": 1e-6}); "method" (trap or gear);
"steps_per_period": TMAX = T / this (and TSTEP the same); "repeats": run each netlist this
many times and report the median wall time (default 1). Or, per point, "netlist": a
complete netlist to run as it is (stickslip::shockley::netlist's, which writes every output
point of the run with `wrdata out.txt`); the rows of its last period are kept.
The wall time is that of the ngspice process (perf_counter around subprocess.run, so it
includes ngspice's start-up and netlist parsing); ngspice's own "Total analysis time" and its
time-point counters are reported too.
"""

import math
import os
import re
import subprocess
import tempfile
import time

from common import TAU, read_job, write_answer

L, C, R = 11.5e-3, 0.02e-6, 68.0
U_T = 0.7  # volts per unit of beta and of y (the paper's PWL turn-on voltage)
OMEGA0 = 1.0 / math.sqrt(L * C)


def netlist(w, beta, periods, steps_per_period, options, method, out_path):
    f = w * OMEGA0 / TAU
    period = 1.0 / f
    tmax = period / steps_per_period
    opts = " ".join(f"{k}={v!r}" if isinstance(v, float) else f"{k}={v}" for k, v in options.items())
    return f"""* stickslip bench: paper circuit, Shockley diodes, w = {w}, beta = {beta}
V1 in 0 SIN(0 {beta * U_T!r} {f!r} 0 0 90)
R1 in a {R!r}
L1 a b {L!r}
D1 b c D1N4148
D2 c b D1N4148
C1 c 0 {C!r}
.model D1N4148 D(Is=4.352n N=1.906 Rs=0.6458)
.options {opts} method={method}
.tran {tmax!r} {periods * period!r} {(periods - 1) * period!r} {tmax!r} uic
.control
run
set wr_singlescale
set wr_vecnames
option numdgt=17
wrdata {out_path} v(c) i(L1)
rusage all
quit 0
.endc
.end
"""


def stat(text, label):
    m = re.search(re.escape(label) + r"\s*=\s*([-+0-9.eE]+)", text)
    return float(m.group(1)) if m else None


def main():
    job = read_job()
    options = dict(job.get("options", {}))
    method = job.get("method", "trap")
    spp = job.get("steps_per_period", 200)
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for p in job["points"]:
            w, beta, periods = p["w"], p["beta"], p["periods"]
            cir = os.path.join(tmp, "bench.cir")
            out = os.path.join(tmp, "out.txt")
            with open(cir, "w") as fh:
                # (ngspice lower-cases the deck, so the output file is named relative to cwd.)
                fh.write(p.get("netlist") or netlist(w, beta, periods, spp, options, method,
                                                     "out.txt"))
            walls = []
            for _ in range(max(1, int(job.get("repeats", 1)))):
                start = time.perf_counter()
                proc = subprocess.run(
                    ["ngspice", "-b", "bench.cir"],
                    capture_output=True,
                    text=True,
                    cwd=tmp,
                    stdin=subprocess.DEVNULL,
                )
                walls.append(time.perf_counter() - start)
            wall = sorted(walls)[len(walls) // 2]
            text = proc.stdout + proc.stderr
            ok = proc.returncode == 0 and os.path.exists(out)
            r = {
                "w": w,
                "beta": beta,
                "periods": periods,
                "wall_s": wall,
                "walls_s": walls,
                "ok": ok,
                "message": "" if ok else text[-2000:],
                "analysis_s": stat(text, "Total analysis time (seconds)"),
                "work": {
                    "timepoints": stat(text, "Transient timepoints"),
                    "accepted": stat(text, "Accepted timepoints"),
                    "rejected": stat(text, "Rejected timepoints"),
                    "iterations": stat(text, "Transient iterations"),
                },
            }
            if ok:
                rows = []
                with open(out) as fh:
                    for line in fh:
                        parts = line.split()
                        try:
                            rows.append([float(x) for x in parts])
                        except ValueError:
                            continue  # the header line
                os.remove(out)
                # Only the last period (a netlist given as it is writes the whole run).
                t_last = (periods - 1) * TAU / (w * OMEGA0)
                rows = [row for row in rows if row[0] >= t_last * (1 - 1e-12)]
                omega0 = OMEGA0
                # Dimensionless: tau = omega0 t, y = u_C / U_t, y' = i sqrt(L/C) / U_t.
                z = math.sqrt(L / C)
                r["last_period"] = {
                    "tau": [row[0] * omega0 for row in rows],
                    "y": [row[1] / U_T for row in rows],
                    "v": [row[2] * z / U_T for row in rows],
                }
            results.append(r)
    write_answer("ngspice", {"options": options, "method": method, "steps_per_period": spp}, results)


if __name__ == "__main__":
    main()
