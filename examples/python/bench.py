"""ltikit's Python package against python-control, in one run (docs/PERFORMANCE.md).

    python examples/python/bench.py            # needs: pip install ./python control

1. call overhead: ``G.poles()`` of a second-order plant (factored at the first call);
2. poles + step_info + margins of 1 000 random order-4 plants, one at a time, ltikit against
   the same python-control loop;
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
    lk_sys = [lk.tf(n, d) for n, d in data]
    ct_sys = [control.tf(n, d) for n, d in data]

    def lk_loop() -> None:
        for n, d in data:
            s = lk.tf(n, d)
            s.poles()
            s.step_info()
            s.margins()

    ct_failed = []

    def ct_loop() -> None:
        for s in ct_sys:
            s.poles()
            try:
                control.step_info(s)
            except (IndexError, ValueError):  # python-control's grid missed the 90 % rise
                ct_failed.append(s)
            control.margin(s)

    t0 = time.perf_counter()
    ct_loop()
    t_ct_loop = time.perf_counter() - t0
    t_lk_loop = min(timeit.repeat(lk_loop, number=1, repeat=3))
    print(f"1000 order-4 plants, poles + step_info + margins, one at a time: ltikit {t_lk_loop * 1e3:.0f} ms, python-control {t_ct_loop * 1e3:.0f} ms ({len(ct_failed)} step_info failures): {t_ct_loop / t_lk_loop:.0f}x")

    big = plants(10_000, seed=2)
    big_sys = [lk.tf(n, d) for n, d in big]
    t0 = time.perf_counter()
    out = lk.batch(big_sys)
    t_batch = time.perf_counter() - t0
    errors = sum(1 for a in out if "error" in a)
    per_ct = t_ct_loop / 1000
    print(f"lk.batch of 10 000 plants: {t_batch * 1e3:.0f} ms ({errors} errors); python-control loop at {per_ct * 1e3:.2f} ms/plant = {per_ct * 1e4:.1f} s: {per_ct * 1e4 / t_batch:.0f}x")
    del lk_sys


if __name__ == "__main__":
    main()
