#!/usr/bin/env python3
"""Zero-order-hold discretisations G(z) of a few continuous transfer functions to 30 digits,
for tests/c2d_tf_reference.rs (issue 20: the ZOH numerator at a short period is
ill-conditioned; ltikit's coefficients are measured against these).

    python3 tests/data/c2d_tf_reference.py > tests/data/c2d_tf_reference.json   # mpmath, numpy

Each plant's coefficients are float64 values (written with repr: exact round trip) and ARE
the model: the order-8 plant of benches/compare/inputs.toml (den = prod(s^2 + 2 zeta wn s +
wn^2), num = 100 (s + 3)(s + 0.5), multiplied out in float64 by numpy) and small plants with
a triple and a quadruple pole, a pole at 0, a direct feed-through and widely spread poles.
With mpmath at 50 digits: the controllable canonical realisation (A, B, C, D) of the float coefficients, the
exponential of the augmented matrix [[A T, B T], [0, 0]] = [[Phi, Gamma], [0, 1]]
(mpmath.expm), the denominator det(zI - Phi) and the numerator
det(zI - Phi + Gamma C) + (D - 1) det(zI - Phi) by Faddeev-LeVerrier, both monic-normalised
(descending powers of z), printed to 30 significant digits.
"""
import json

import mpmath as mp
import numpy as np

mp.mp.dps = 50


def order8():
    den = np.array([1.0])
    for wn, z in [(1.0, 0.1), (2.0, 0.3), (5.0, 0.5), (10.0, 0.7)]:
        den = np.polymul(den, [1.0, 2.0 * z * wn, wn * wn])
    num = np.array([1.0])
    for z in [-3.0, -0.5]:
        num = np.polymul(num, [1.0, -z])
    return [100.0 * c for c in num], list(den)


PLANTS = [
    ("order8_T0.01", *order8(), 0.01),
    ("order8_T0.1", *order8(), 0.1),
    ("lightly_damped_with_zero", [1.0, 3.0], [1.0, 0.4, 4.0], 0.05),
    ("triple_pole", [1.0], [1.0, 3.0, 3.0, 1.0], 0.1),
    ("quadruple_pole_with_zeros", [1.0, 0.0, 4.0], [1.0, 4.0, 6.0, 4.0, 1.0], 0.05),
    ("integrator_and_lag", [1.0], [1.0, 2.0, 0.0], 0.1),
    ("biproper", [2.0, 3.0, 1.0], [1.0, 0.5, 2.0], 0.2),
    # 1e3 / ((s + 0.01)(s + 100)(s^2 + 2s + 50)) multiplied out in float64
    ("spread_poles", [1e3], list(np.polymul(np.polymul([1.0, 0.01], [1.0, 100.0]), [1.0, 2.0, 50.0])), 0.01),
]


def charpoly(m):
    """Coefficients (descending, monic) of det(zI - m) by Faddeev-LeVerrier."""
    n = m.rows
    c = [mp.mpf(1)]
    mk = mp.zeros(n, n)
    for k in range(1, n + 1):
        mk = m * mk + c[-1] * mp.eye(n)
        ck = -sum(((m * mk)[i, i] for i in range(n)), mp.mpf(0)) / k
        c.append(ck)
    return c


def zoh(num, den, t):
    num = [mp.mpf(x) for x in num]
    den = [mp.mpf(x) for x in den]
    n = len(den) - 1
    lead = den[0]
    a_ = [x / lead for x in den]
    b_ = [mp.mpf(0)] * (n + 1 - len(num)) + [x / lead for x in num]
    d = b_[0]
    a = mp.zeros(n, n)
    for j in range(n):
        a[0, j] = -a_[j + 1]
    for i in range(1, n):
        a[i, i - 1] = 1
    c = mp.zeros(1, n)
    for j in range(n):
        c[0, j] = b_[j + 1] - a_[j + 1] * d
    aug = mp.zeros(n + 1, n + 1)
    for i in range(n):
        for j in range(n):
            aug[i, j] = a[i, j] * t
    aug[0, n] = t  # B = e1
    e = mp.expm(aug)
    phi = e[0:n, 0:n]
    gam = e[0:n, n:n + 1]
    dz = charpoly(phi)
    cl = charpoly(phi - gam * c)
    nz = [cl[i] + (d - 1) * dz[i] for i in range(n + 1)]
    return nz, dz


def main():
    out = []
    for name, num, den, t in PLANTS:
        nz, dz = zoh(num, den, mp.mpf(t))
        out.append({
            "name": name,
            "num": [float(x) for x in num],
            "den": [float(x) for x in den],
            "dt": t,
            "num_z": [mp.nstr(x, 30) for x in nz],
            "den_z": [mp.nstr(x, 30) for x in dz],
        })
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
