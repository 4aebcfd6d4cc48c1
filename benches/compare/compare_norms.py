#!/usr/bin/env python3
"""H∞ norms: the reference values of tests/norms.rs and the timing against python-control.

    /path/to/venv/bin/python benches/compare/compare_norms.py   # numpy, scipy, control

The model is benches/common/norms.rs's random stable 2×2 model with 30 states (the same LCG,
rebuilt here). Reference: sigma_max(G(jw)) on 200 000 log-spaced frequencies in [1e-3, 1e3]
and every local maximum refined by scipy.optimize.minimize_scalar (bounded, xatol 1e-13),
G(jw) by numpy.linalg.solve. python-control without Slycot: control.norm(sys, 'inf',
method='scipy') (its Hamiltonian bisection); `linfnorm` and `hinfnorm` need Slycot.
ltikit's time: `cargo bench --bench ltikit -- norms` (divan, median).
"""
import math
import time
import warnings

import numpy as np
import scipy.optimize as so
import control as ct

MASK = (1 << 64) - 1


class Lcg:
    def __init__(self, seed):
        self.s = seed

    def next(self):
        self.s = (self.s * 6364136223846793005 + 1442695040888963407) & MASK
        return (self.s >> 11) * (1.0 / (1 << 53))


def random_stable(n, m, p, seed):
    r = Lcg(seed)
    lam = np.zeros((n, n))
    for k in range(n // 2):
        w = 10.0 ** (-1.0 + 2.0 * r.next())
        z = 0.005 + 0.2 * r.next()
        re, im = -z * w, w * math.sqrt(1.0 - z * z)
        i = 2 * k
        lam[i, i] = lam[i + 1, i + 1] = re
        lam[i, i + 1] = im
        lam[i + 1, i] = -im
    s = 1.0 / math.sqrt(n)
    t = np.eye(n)
    for i in range(n):
        for j in range(n):
            t[i, j] += (2.0 * r.next() - 1.0) * s

    def fill(rows, cols, scale):
        x = np.zeros((rows, cols))
        for i in range(rows):
            for j in range(cols):
                x[i, j] = scale * (2.0 * r.next() - 1.0)
        return x

    b = fill(n, m, 1.0)
    c = fill(p, n, 1.0)
    d = fill(p, m, 0.1)
    a = t @ lam @ np.linalg.inv(t)
    return a, b, c, d


def smax(a, b, c, d, w):
    n = a.shape[0]
    g = c @ np.linalg.solve(1j * w * np.eye(n) - a, b) + d
    return np.linalg.svd(g, compute_uv=False)[0]


def dense_peak(a, b, c, d, lo=-3, hi=3, points=200_000):
    w = np.logspace(lo, hi, points)
    n = a.shape[0]
    # diagonalise once for the grid (fast), refine with solves
    ev, v = np.linalg.eig(a)
    cv, vb = c @ v, np.linalg.solve(v, b)
    vals = np.empty(points)
    for k in range(0, points, 5000):
        ww = w[k:k + 5000]
        g = np.einsum('pi,wi,im->wpm', cv, 1.0 / (1j * ww[:, None] - ev[None, :]), vb) + d
        vals[k:k + 5000] = np.linalg.svd(g, compute_uv=False)[:, 0]
    best = (smax(a, b, c, d, 0.0), 0.0)
    for k in range(1, points - 1):
        if vals[k] >= vals[k - 1] and vals[k] >= vals[k + 1]:
            res = so.minimize_scalar(lambda x: -smax(a, b, c, d, x),
                                     bounds=(w[k - 1], w[k + 1]), method='bounded',
                                     options={'xatol': 1e-13 * w[k]})
            if -res.fun > best[0]:
                best = (-res.fun, res.x)
    return best


def main():
    a, b, c, d = random_stable(30, 2, 2, 1)
    peak, wpk = dense_peak(a, b, c, d)
    print(f"random 30-state 2x2 (seed 1): dense grid + refinement: {peak!r} at w = {wpk!r}")
    sys_ = ct.ss(a, b, c, d)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ts = []
        for _ in range(5):
            t0 = time.perf_counter()
            v = ct.norm(sys_, 'inf', tol=1e-10, method='scipy')
            ts.append(time.perf_counter() - t0)
    print(f"python-control norm(sys, 'inf', tol=1e-10, method='scipy'): {v!r}, "
          f"median {sorted(ts)[2] * 1e3:.2f} ms")
    try:
        ct.linfnorm(sys_)
    except Exception as e:  # noqa: BLE001
        print(f"python-control linfnorm: {type(e).__name__}: {e}")


if __name__ == "__main__":
    main()
