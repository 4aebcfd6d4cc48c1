#!/usr/bin/env python3
"""The 18-state dense realisation of tests/ss_margins.rs and its margins to 40 digits.

    python3 tests/data/dense18_reference.py > tests/data/dense18.json   # numpy, mpmath

The plant: nine second-order sections, lightly (zeta = 0.02) and heavily (zeta = 0.8) damped
in turn, omega_n = 0.3 * 100**(i/8), each lightly damped one with a lightly damped zero pair
just above it (omega_z = 1.1 omega_n, zeta_z = 0.05), dc gain 4, relative degree 10; realised as
a cascade of sections (each with states x and x'/omega_n, so that no state is much larger than
another) and hidden behind a dense similarity T = I + 0.5 R (R
uniform in [-1, 1) from xorshift64, seed 0x5eed0001), all in float64. The stored matrices
(17 significant digits: exact round trip) ARE the model: the reference margins are computed
from them with mpmath at 40 digits (G(jw) = c (jwI - A)^-1 b + d by LU), each crossing by
findroot from a sign change on a 2500-point log grid over [1e-2, 1e3].
"""
import json

import mpmath as mp
import numpy as np

mp.mp.dps = 40
MASK = (1 << 64) - 1


def xorshift(seed):
    while True:
        seed ^= (seed << 13) & MASK
        seed ^= seed >> 7
        seed ^= (seed << 17) & MASK
        yield (seed >> 11) / float(1 << 53) * 2.0 - 1.0


def model():
    secs = []
    for i in range(9):
        wn = 0.3 * 100.0 ** (i / 8.0)
        zeta = 0.02 if i % 2 == 0 else 0.8
        secs.append((wn, zeta))
    # cascade of scaled sections (states x and x'/wn, so every state is of the size of the
    # input), section i driven by the output of section i-1; the lightly damped sections carry
    # a lightly damped zero pair just above their poles (w_z = 1.1 w_n, zeta_z = 0.05), the
    # others none: G_i = (w_n/w_z)^2 (s^2 + 2 zeta_z w_z s + w_z^2)/(s^2 + 2 zeta w_n s + w_n^2)
    # = k (1 + ((a1 - b1) s + (a0 - b0))/den), realised with a feedthrough k
    n = 18
    a = np.zeros((n, n)); b = np.zeros((n, 1)); c = np.zeros((1, n)); d = np.zeros((1, 1))
    # the section's own (A, B, C, D), then the series connection with what came before
    for i, (wn, zeta) in enumerate(secs):
        ai = np.array([[0.0, wn], [-wn, -2.0 * zeta * wn]])
        bi = np.array([[0.0], [wn]])
        if zeta < 0.1:
            wz, zz = 1.1 * wn, 0.05
            k = (wn / wz) ** 2
            a1, a0, b1, b0 = 2 * zz * wz, wz * wz, 2 * zeta * wn, wn * wn
            ci = k * np.array([[(a0 - b0) / wn ** 2, (a1 - b1) / wn]])
            di = np.array([[k]])
        else:
            ci = np.array([[1.0, 0.0]]); di = np.array([[0.0]])
        if i == 0:
            a[:2, :2] = ai; b[:2] = bi; c[:, :2] = ci; d = di
            continue
        k0 = 2 * i
        # x_i' = A_i x_i + B_i (C_prev x_prev + D_prev u); y = C_i x_i + D_i (C_prev x_prev + D_prev u)
        a[k0:k0 + 2, k0:k0 + 2] = ai
        a[k0:k0 + 2, :k0] = bi @ c[:, :k0]
        b[k0:k0 + 2] = bi @ d
        c_new = np.zeros((1, n)); c_new[:, :k0] = di @ c[:, :k0]; c_new[:, k0:k0 + 2] = ci
        c = c_new; d = di @ d
    c = 4.0 * c; d = 4.0 * d
    rng = xorshift(0x5EED0001)
    t = np.array([[(1.0 if i == j else 0.0) + 0.5 * next(rng) for j in range(n)] for i in range(n)])
    ti = np.linalg.inv(t)
    return t @ a @ ti, t @ b, c @ ti, d


def main():
    a, b, c, d = model()
    # json writes shortest round-trip decimals: the stored numbers are these doubles exactly
    A = mp.matrix(a.tolist()); B = mp.matrix(b.tolist()); C = mp.matrix(c.tolist()); D = mp.mpf(d[0, 0])
    n = A.rows

    def g(w):
        m = mp.matrix(n, n)
        for i in range(n):
            for j in range(n):
                m[i, j] = -A[i, j]
            m[i, i] += mp.mpc(0, w)
        x = mp.lu_solve(m, B)
        return (C * x)[0, 0] + D

    g0 = abs(g(mp.mpf(0)))
    lnmag = lambda w: mp.log(abs(g(w)))
    # phase: continuous, unwrapped along a fine grid (the branch), exact at the crossings
    ws = [mp.mpf(10) ** (mp.mpf(-2) + 5 * mp.mpf(k) / 2499) for k in range(2500)]
    vals = [g(w) for w in ws]
    phase = []
    prev = None
    for v in vals:
        p = mp.arg(v)
        if prev is not None:
            p += 2 * mp.pi * mp.nint((prev - p) / (2 * mp.pi))
        phase.append(p); prev = p

    def roots(f, fs):
        out = []
        for k in range(len(ws) - 1):
            if fs[k] == 0 or (fs[k] > 0) != (fs[k + 1] > 0):
                out.append(mp.findroot(f, (ws[k], ws[k + 1]), solver='anderson'))
        return out

    lm = [mp.log(abs(v)) for v in vals]
    gains = roots(lnmag, lm)
    gain_crossings = []
    for w in gains:
        k = min(range(len(ws)), key=lambda i: abs(ws[i] - w))
        a_ = mp.arg(g(w)); ph = a_ + 2 * mp.pi * mp.nint((phase[k] - a_) / (2 * mp.pi))
        pm = 180 + ph * 180 / mp.pi
        pm = pm - 360 * mp.nint(pm / 360)
        gain_crossings.append({"w": float(w), "phase_margin_deg": float(pm)})
    # phase crossings: phase = (2j+1) pi
    phase_crossings = []
    for k in range(len(ws) - 1):
        ka = mp.ceil((phase[k] - mp.pi) / (2 * mp.pi)); kb = mp.ceil((phase[k + 1] - mp.pi) / (2 * mp.pi))
        if ka != kb:
            target = mp.pi * (2 * max(ka, kb) - 1)
            def f(w, target=target):
                d_ = mp.arg(g(w)) - target
                return d_ - 2 * mp.pi * mp.nint(d_ / (2 * mp.pi))
            w = mp.findroot(f, (ws[k], ws[k + 1]), solver='anderson')
            phase_crossings.append({"w": float(w), "gain_margin": float(1 / abs(g(w)))})
    level = mp.log(g0) - mp.mpf(3) / 20 * mp.log(10)
    bw = roots(lambda w: lnmag(w) - level, [x - level for x in lm])[0]
    dl = lambda w: mp.diff(lnmag, w)
    peaks = []
    for k in range(1, len(ws) - 1):
        if lm[k] > lm[k - 1] and lm[k] >= lm[k + 1]:
            peaks.append(mp.findroot(dl, (ws[k - 1], ws[k + 1]), solver='anderson'))
    wr = max(peaks, key=lambda w: abs(g(w)))
    out = {
        "source": "tests/data/dense18_reference.py (mpmath 40 digits on the stored matrices)",
        "a": a.tolist(), "b": b.tolist(), "c": c.tolist(), "d": d.tolist(),
        "gain_crossings": gain_crossings,
        "phase_crossings": phase_crossings,
        "bandwidth": float(bw),
        "resonant_frequency": float(wr),
        "resonant_peak": float(abs(g(wr)) / g0),
        "dc_gain": float(g0),
    }
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
