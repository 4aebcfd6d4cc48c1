"""ltikit's Python package against python-control, in one run (docs/PERFORMANCE.md).

    python examples/python/bench.py            # needs: pip install ./python control

1. call overhead: ``G.poles()`` of a second-order plant (factored at the first call);
2. poles + step_info + margins of 1 000 random order-4 plants, one at a time (each loop builds
   the model and reads one number of each result), ltikit against the same python-control
   loop: three interleaved runs, timed by CPU time and by the wall clock;
3. ``lk.batch`` of 10 000 plants (the analysis with step metrics, plus margins) against the
   python-control loop's time per plant.
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


def main() -> None:
    import control

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


if __name__ == "__main__":
    main()
