"""ltikit's Python package against python-control, in one run (docs/PERFORMANCE.md).

    python examples/python/bench.py            # needs: pip install ./python control

1. call overhead: ``G.poles()`` of a second-order plant (factored at the first call);
2. poles + step_info + margins of 1 000 random order-4 plants, one at a time (each loop builds
   the model and reads one number of each result), ltikit against the same python-control
   loop: three interleaved runs, timed by CPU time and by the wall clock;
3. ``lk.batch`` of 10 000 plants (the analysis with step metrics, plus margins) against the
   python-control loop's time per plant;
4. the later calls one at a time against their python-control counterparts (``--calls`` runs
   only these): lqr, H∞ and H2 norms, c2d, MIMO poles/zeros/dc gain/frequency response/step,
   initial and forced responses with x0, connect.
"""

from __future__ import annotations

import os

# One thread each: python-control's scipy/numpy calls must not spin BLAS threads against the
# other core (that made its loop 2.7 s or 7.4 s from one run to the next on 2 shared cores).
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import time
import timeit
import warnings

import numpy as np

import ltikit as lk


def plants(n: int, seed: int = 1) -> list:
    """n random order-4 plants: k/((s + p1)…(s + p4)), p uniform in [0.1, 10]."""
    rng = np.random.default_rng(seed)
    return [([rng.uniform(0.5, 2.0)], np.poly(-rng.uniform(0.1, 10.0, 4))) for _ in range(n)]


def best(f, number: int, repeat: int = 5) -> float:
    """Seconds per call, the best of ``repeat`` runs of ``number`` calls."""
    return min(timeit.repeat(f, number=number, repeat=repeat)) / number


def timed(f) -> tuple:
    """(wall seconds, CPU seconds of this process) of one call of f."""
    w0, c0 = time.perf_counter(), time.process_time()
    f()
    return time.perf_counter() - w0, time.process_time() - c0


def random_stable(n: int, m: int, p: int, seed: int = 3) -> tuple:
    """A random stable (A, B, C, D): complex pole pairs with ζ in [0.05, 0.5] and ωn in
    [0.3, 10] (real when n is odd, one more pole), mixed by a random similarity."""
    rng = np.random.default_rng(seed)
    lam = np.zeros((n, n))
    for k in range(n // 2):
        w, z = 10 ** rng.uniform(-0.5, 1.0), rng.uniform(0.05, 0.5)
        i = 2 * k
        lam[i, i] = lam[i + 1, i + 1] = -z * w
        lam[i, i + 1], lam[i + 1, i] = w * np.sqrt(1 - z * z), -w * np.sqrt(1 - z * z)
    if n % 2:
        lam[-1, -1] = -rng.uniform(0.3, 3.0)
    t = np.eye(n) + rng.uniform(-1, 1, (n, n)) / np.sqrt(n)
    a = t @ lam @ np.linalg.inv(t)
    return a, rng.uniform(-1, 1, (n, m)), rng.uniform(-1, 1, (p, n)), 0.1 * rng.uniform(-1, 1, (p, m))


def calls() -> None:
    """Section 4: one call at a time, ltikit against python-control (best of 5 repeats)."""
    import control

    a, b, c, d = random_stable(8, 2, 2)
    g, gc = lk.ss(a, b, c, d), control.ss(a, b, c, d)
    q, r = np.eye(8), np.eye(2)
    num, den = [1.0, 3.0, 2.5], np.poly(-np.array([0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0]))
    h, hc = lk.tf(num, den), control.tf(num, den)
    w = np.logspace(-2, 2, 1000)
    t = np.linspace(0, 20, 2001)
    u = np.column_stack([np.sin(t), np.cos(0.5 * t)])
    x0 = np.ones(8)
    p1, p1c = lk.tf([4], [1, 0.8, 4]), control.tf([4], [1, 0.8, 4], inputs="u", outputs="y")
    k1, k1c = lk.pid(kp=2.0, ki=1.0), control.tf([2, 1], [1, 0], inputs="e", outputs="u")
    sj = control.summing_junction(inputs=["r", "-y"], output="e")
    rows = [
        ("lqr, 8 states, 2 inputs", lambda: g.lqr(q, r).K,
         lambda: control.lqr(a, b, q, r)[0], 200),
        ("H∞ norm, 8 states, 2×2 (python: norm(sys, 'inf', method='scipy'))",
         lambda: float(g.hinf_norm()), lambda: control.norm(gc, "inf", method="scipy"), 20),
        ("H2 norm, 8 states, 2×2", lambda: float(g.h2_norm()), lambda: control.norm(gc, 2), 200),
        ("c2d zoh, order-8 transfer function (python: sample_system)",
         lambda: h.c2d(0.01).poles(), lambda: control.sample_system(hc, 0.01).poles(), 200),
        ("MIMO poles (fresh model), 8 states, 2×2", lambda: lk.ss(a, b, c, d).poles(),
         lambda: control.ss(a, b, c, d).poles(), 200),
        ("MIMO transmission zeros, 8 states, 2×2", lambda: g.zeros(), lambda: gc.zeros(), 200),
        ("MIMO dc gain matrix (fresh model)", lambda: lk.ss(a, b, c, d).dc_gain(),
         lambda: control.dcgain(control.ss(a, b, c, d)), 200),
        ("MIMO frequency response, 2×2, 1000 ω", lambda: g.freq(w).response,
         lambda: gc.frequency_response(w).complex, 20),
        ("MIMO step response per input, 2×2, 2001 samples", lambda: g.step(t).y,
         lambda: control.step_response(gc, t).outputs, 20),
        ("forced response, 2 inputs, 2001 samples, x0", lambda: g.response(u, t, x0=x0).y,
         lambda: control.forced_response(gc, t, u.T, X0=x0).outputs, 20),
        ("initial response, 2001 samples", lambda: g.initial(x0, t).y,
         lambda: control.initial_response(gc, t, x0).outputs, 20),
        ("connect: PI loop around a 2nd-order plant (python: interconnect)",
         lambda: lk.connect({"C": (k1, "e", "u"), "P": (p1, "u", "y")}, "r", "y", {"e": "r - y"}),
         lambda: control.interconnect([k1c, p1c, sj], inputs="r", outputs="y"), 100),
    ]
    print("\ncall (best of 5)                                           ltikit        python-control   ratio")
    for name, f_lk, f_ct, number in rows:
        f_lk(), f_ct()  # warm (python-control's first calls import and cache)
        a_lk, a_ct = best(f_lk, number), best(f_ct, max(1, number // 4))
        print(f"  {name:<64s} {a_lk * 1e6:10.1f} µs {a_ct * 1e6:12.1f} µs {a_ct / a_lk:7.1f}x")


def main() -> None:
    import sys

    import control

    warnings.simplefilter("ignore")
    if "--calls" in sys.argv:
        calls()
        return

    warnings.simplefilter("ignore")
    print(f"ltikit {lk.__version__}, python-control {control.__version__}, numpy {np.__version__}, {os.cpu_count()} cores")

    g = lk.tf([4], [1, 0.8, 4])
    g.poles()
    c = control.tf([4], [1, 0.8, 4])
    t_lk = best(g.poles, 100_000)
    t_new = best(lambda: lk.tf([4], [1, 0.8, 4]).poles(), 10_000)
    t_ct = best(c.poles, 10_000)
    print(f"poles of a 2nd-order plant: ltikit {t_lk * 1e6:.2f} µs (factored), {t_new * 1e6:.1f} µs with tf(); python-control {t_ct * 1e6:.1f} µs")

    data = plants(1000)

    # Each loop reads one number of each result, as a caller would.
    def lk_loop() -> None:
        for n, d in data:
            s = lk.tf(n, d)
            s.poles()[0]
            s.step_info().rise_time
            s.margins().gain_margin

    ct_failed = []

    def ct_loop() -> None:
        for n, d in data:
            s = control.tf(n, d)
            s.poles()[0]
            try:
                control.step_info(s)["RiseTime"]
            except (IndexError, ValueError):  # python-control's grid missed the 90 % rise
                ct_failed.append(s)
            control.margin(s)[0]

    # Interleaved runs (python-control, then ltikit), each timed by the process's CPU time
    # as well as the wall clock: on a shared machine the other processes' load inflates the
    # wall time of whichever loop it hits, the CPU time of a single-threaded loop much less.
    ratios_cpu, ratios_wall, t_lk_runs, t_ct_runs, ct_walls = [], [], [], [], []
    for _ in range(3):
        ct_failed.clear()
        ct_wall, ct_cpu = timed(ct_loop)
        lk_wall, lk_cpu = timed(lk_loop)
        ratios_cpu.append(ct_cpu / lk_cpu)
        ratios_wall.append(ct_wall / lk_wall)
        t_lk_runs.append(lk_cpu)
        t_ct_runs.append(ct_cpu)
        ct_walls.append(ct_wall)
    print(
        "1000 order-4 plants, poles + step_info + margins, one at a time (3 interleaved runs): "
        f"ltikit {', '.join(f'{t * 1e3:.0f}' for t in t_lk_runs)} ms CPU, "
        f"python-control {', '.join(f'{t * 1e3:.0f}' for t in t_ct_runs)} ms CPU "
        f"({len(ct_failed)} step_info failures per run): "
        f"{float(np.median(ratios_cpu)):.1f}x CPU time (runs {', '.join(f'{r:.1f}' for r in ratios_cpu)}), "
        f"{float(np.median(ratios_wall)):.1f}x wall (runs {', '.join(f'{r:.1f}' for r in ratios_wall)})"
    )

    big = plants(10_000, seed=2)
    big_sys = [lk.tf(n, d) for n, d in big]
    t0 = time.perf_counter()
    out = lk.batch(big_sys)
    t_batch = time.perf_counter() - t0
    errors = sum(1 for a in out if "error" in a)
    per_ct = float(np.median(ct_walls)) / 1000  # wall time: the batch's is wall time too
    print(f"lk.batch of 10 000 plants: {t_batch * 1e3:.0f} ms ({errors} errors); python-control loop at {per_ct * 1e3:.2f} ms/plant = {per_ct * 1e4:.1f} s: {per_ct * 1e4 / t_batch:.0f}x")
    calls()


if __name__ == "__main__":
    main()
