"""50-digit references for the state-space models of ControlSystems.jl's own tests.

The models are copied verbatim from ControlSystems.jl, lib/ControlSystemsBase/test/
test_analysis.jl (commit b2b7dc43): `marginplottest` (18 states, "MARGIN"), the case "that
requires negative frequencies" (issue 1045, 4 states), the "System with RHP poles and zeros but
stable in closed loop" (6 states) and the "Difficult test case for zeros" (4 states). This script
reads them from controlsystems_ss.json and prints, with mpmath at 50 digits on the stored
doubles: every phase crossing (Im G(jw) = 0) with its gain margin -1/Re G, the gain crossing
(|G(jw)| = 1) with its phase margin, and the transmission zeros of the difficult model (roots of
N(s) = det(sI - A)·G(s), interpolated at n + 1 points). tests/ss_suites.rs holds the values.

Run: python tests/data/controlsystems_ss_reference.py   (needs mpmath)
"""
import json
import os

import mpmath as mp

mp.mp.dps = 50
HERE = os.path.dirname(os.path.abspath(__file__))
MODELS = json.load(open(os.path.join(HERE, "controlsystems_ss.json")))


def g(v, s):
    a = mp.matrix(v["a"])
    n = a.rows
    m = mp.matrix(n, n)
    for i in range(n):
        for j in range(n):
            m[i, j] = (s if i == j else 0) - a[i, j]
    x = mp.lu_solve(m, mp.matrix([r[0] for r in v["b"]]))
    return sum(v["c"][0][i] * x[i] for i in range(n)) + v["d"][0][0]


def crossings(name, phase_guesses, gain_guess):
    v = MODELS[name]
    print(name)
    for w0 in phase_guesses:
        w = mp.mpf(0) if w0 == 0 else mp.findroot(lambda w: mp.im(g(v, 1j * w)), w0)
        print("  phase crossing w =", mp.nstr(w, 20), " gain margin", mp.nstr(-1 / mp.re(g(v, 1j * w)), 20))
    w = mp.findroot(lambda w: abs(g(v, 1j * w)) - 1, gain_guess)
    ph = mp.degrees(mp.arg(g(v, 1j * w)))
    pm = 180 + ph if ph < 0 else ph - 180
    print("  gain crossing w =", mp.nstr(w, 20), " phase margin", mp.nstr(pm, 20))


crossings("marginplottest", [0.9787, 21.96], 3.4834)
crossings("negative_frequency", [0, 1.2311], 0.383)
crossings("rhp_stable_loop", [1.02, 15.62], 7.813)

v = MODELS["difficult_zeros"]
n = len(v["a"])
pts = [mp.mpf(k) - mp.mpf(n) / 2 + mp.mpf("0.37") for k in range(n + 1)]
vals = [mp.det(mp.eye(n) * s - mp.matrix(v["a"])) * g(v, s) for s in pts]
# Newton interpolation, then monomial coefficients (descending).
coef = list(vals)
for j in range(1, n + 1):
    for i in range(n, j - 1, -1):
        coef[i] = (coef[i] - coef[i - 1]) / (pts[i] - pts[i - j])
poly = [mp.mpf(0)] * (n + 1)  # ascending
for k in range(n, -1, -1):
    # poly = poly·(x − pts[k]) + coef[k]
    new = [mp.mpf(0)] * (n + 1)
    for i in range(n):
        new[i + 1] += poly[i]
        new[i] -= poly[i] * pts[k]
    new[0] += coef[k]
    poly = new
while abs(poly[-1]) < mp.mpf(10) ** -40 * max(abs(c) for c in poly):
    poly.pop()
roots = mp.polyroots(list(reversed(poly)), maxsteps=200, extraprec=200)
print("difficult_zeros zeros:", [mp.nstr(r, 20) for r in roots])
