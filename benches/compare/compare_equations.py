#!/usr/bin/env python3
"""Matrix-equation timings of ltikit against scipy (LAPACK), in one run.

    OPENBLAS_NUM_THREADS=1 python3 benches/compare/compare_equations.py   # venv with scipy, numpy

(One BLAS thread: on a loaded 2-core machine a multi-threaded BLAS made scipy 15x slower.)

The problems (n = 100): A = random(n, n; seed 11)*2/sqrt(n) - I (stable), B = random(n, 3;
seed 12), generated here with the same 64-bit LCG as benches/common/equations.rs (bit for bit);
lyap: A X + X A^T + B B^T = 0 (scipy.linalg.solve_continuous_lyapunov(A, -B B^T));
care: A^T X + X A - X B B^T X + I = 0 (scipy.linalg.solve_continuous_are(A, B, I, I)).
ltikit's side is `cargo run --release --example bench_equations_json` (medians, seconds).
Printed: both medians, the ratio ltikit/scipy, both relative residuals (same definition:
||residual||_F / sum of the Frobenius norms of the terms), and the agreement of X.
"""
import json
import os
import subprocess
import time

import numpy as np
import scipy.linalg as sl

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MASK = (1 << 64) - 1


def random(rows, cols, seed):
    state = seed
    out = np.empty((rows, cols))
    for j in range(cols):  # column by column, as nalgebra's from_fn
        for i in range(rows):
            state = (state * 6364136223846793005 + 1442695040888963407) & MASK
            out[i, j] = (state >> 11) / float(1 << 53) - 0.5
    return out


def problem(n):
    a = random(n, n, 11) * (2.0 / np.sqrt(n)) - np.eye(n)
    return a, random(n, 3, 12)


def median_time(fn, repeat=21):
    fn()
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter(); fn(); ts.append(time.perf_counter() - t0)
    return sorted(ts)[len(ts) // 2]


def fro(m):
    return np.linalg.norm(m, "fro")


def main():
    n = 100
    a, b = problem(n)
    q = b @ b.T
    x_l = sl.solve_continuous_lyapunov(a, -q)
    res_l = fro(a @ x_l + x_l @ a.T + q) / (fro(a @ x_l) + fro(x_l @ a.T) + fro(q))
    x_c = sl.solve_continuous_are(a, b, np.eye(n), np.eye(3))
    xb = x_c @ b
    quad = xb @ xb.T
    res_c = fro(a.T @ x_c + x_c @ a - quad + np.eye(n)) / (2 * fro(x_c @ a) + fro(quad) + fro(np.eye(n)))
    py = {
        "lyap": median_time(lambda: sl.solve_continuous_lyapunov(a, -q)),
        "care": median_time(lambda: sl.solve_continuous_are(a, b, np.eye(n), np.eye(3))),
    }
    out = subprocess.run(
        ["cargo", "run", "--quiet", "--release", "--example", "bench_equations_json"],
        cwd=ROOT, check=True, capture_output=True, text=True,
    ).stdout
    rs = json.loads(out)
    assert abs(rs["lyap_x00"] - x_l[0, 0]) < 1e-10 * abs(x_l[0, 0]), (rs["lyap_x00"], x_l[0, 0])
    assert abs(rs["care_x00"] - x_c[0, 0]) < 1e-10 * abs(x_c[0, 0]), (rs["care_x00"], x_c[0, 0])
    print(f"n = {n}, numpy {np.__version__}, scipy {__import__('scipy').__version__}")
    print(f"{'':8} {'ltikit [ms]':>12} {'scipy [ms]':>12} {'ltikit/scipy':>13} {'residual ltikit':>16} {'residual scipy':>15}")
    for key, res_py in (("lyap", res_l), ("care", res_c)):
        print(f"{key:8} {rs[key] * 1e3:12.3f} {py[key] * 1e3:12.3f} {rs[key] / py[key]:13.2f} "
              f"{rs[key + '_residual']:16.2e} {res_py:15.2e}")


if __name__ == "__main__":
    main()
