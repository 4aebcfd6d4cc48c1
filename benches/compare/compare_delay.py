#!/usr/bin/env python3
"""Dead time (issue 21): ltikit's exact delayed loops against python-control's Padé loops, in
one run — the accuracy table (step responses and margins) and the timings.

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install control scipy numpy
    /tmp/venv/bin/python benches/compare/compare_delay.py [--json FILE]

ltikit's side is `cargo run --release --example bench_delay_json`: for each PI loop around a
plant with a dead time it returns the exact closed-loop step at 10⁴ samples (method of steps),
its median time, the margins of L·e^(−sT) and the critical delay. Here python-control closes
the same loops with `pade(T, n)`, n = 3 and 10, and the script reports how far each Padé
loop's step response and margins are from the exact ones, and the time of its step response
on the same samples. ltikit's exact values themselves are checked against the delay
differential equation solved exactly (sympy, tests/delay_steps.rs) and against closed forms
(tests/delay.rs, tests/delay_stability.rs).
"""
import argparse
import json
import os
import subprocess
import time

import numpy as np
import control as ct

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def median_time(f, repeat=7):
    f()
    n = 1
    while True:
        t0 = time.perf_counter()
        for _ in range(n):
            f()
        if time.perf_counter() - t0 >= 0.1 or n > 10000:
            break
        n *= 4
    s = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(n):
            f()
        s.append((time.perf_counter() - t0) / n)
    return float(np.median(s))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--json")
    args = ap.parse_args()
    out = subprocess.run(
        ["cargo", "run", "--quiet", "--release", "--example", "bench_delay_json"],
        cwd=ROOT, check=True, capture_output=True, text=True,
    ).stdout
    loops = json.loads(out)
    rows = []
    for lp in loops:
        g = ct.tf(lp["num"], lp["den"])
        c = ct.tf([lp["kp"], lp["ki"]], [1, 0])
        t = np.array(lp["t"])
        y = np.array(lp["y"])
        for n in (3, 10):
            num, den = ct.pade(lp["delay"], n)
            loop = c * g * ct.tf(num, den)
            cl = ct.feedback(loop, 1)
            _, yp = ct.step_response(cl, t)
            gm, pm, wpc, wgc = ct.margin(loop)
            secs = median_time(lambda: ct.step_response(cl, t))
            rows.append({
                "loop": lp["name"], "pade": n,
                "step_max_error": float(np.max(np.abs(yp - y))),
                "gm_rel_error": abs(gm - lp["gain_margin"]) / lp["gain_margin"],
                "pm_error_deg": abs(pm - lp["phase_margin_deg"]),
                "python_step_seconds": secs,
                "ltikit_step_seconds": lp["step_seconds"],
            })
    print("| loop | Padé n | max |y_pade − y_exact| | GM rel. error | PM error (°) | python-control step | ltikit exact step | ratio |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['loop']} | {r['pade']} | {r['step_max_error']:.3g} | {r['gm_rel_error']:.3g} | "
              f"{r['pm_error_deg']:.3g} | {r['python_step_seconds']*1e3:.3g} ms | "
              f"{r['ltikit_step_seconds']*1e3:.3g} ms | {r['python_step_seconds']/r['ltikit_step_seconds']:.1f}× |")
    for lp in loops:
        print(f"{lp['name']}: exact GM {lp['gain_margin']:.10g} at {lp['phase_crossover']:.6g} rad/s, "
              f"PM {lp['phase_margin_deg']:.10g}° at {lp['gain_crossover']:.6g} rad/s, "
              f"delay margin {lp['delay_margin']:.10g} s, critical delay {lp['critical_delay']:.10g} s, "
              f"closed form vs march {lp['closed_form_error']:.2g}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"rows": rows}, f, indent=1)


if __name__ == "__main__":
    main()
