"""Routh–Hurwitz and Jury tables with the exact stabilising gains, against closed forms (the
Routh array by hand, the Jury conditions of a second-order polynomial) and numpy's roots."""

import math

import numpy as np
import pytest

import ltikit as lk


def test_routh_table_by_hand():
    # s³ + s² + 2s + 8 = (s + 2)(s² − s + 4): rows [1 2], [1 8], [2 − 8 = −6], [8]
    r = lk.tf([1], [1, 1, 2, 8]).routh()
    np.testing.assert_array_equal(r.rows, [[1, 2], [1, 8], [-6, 0], [8, 0]])
    assert r.powers == [3, 2, 1, 0]
    assert (r.rhp, r.axis, r.lhp) == (2, 0, 1) and r.exact and not r.stable
    roots = np.roots([1, 1, 2, 8])
    assert r.rhp == int(np.sum(roots.real > 0))


def test_routh_stable_gains_closed_form():
    # 1/(s(s + 1)(s + 2)): s³ + 3s² + 2s + K is stable for 0 < K < 6 (Routh: 3·2 > K)
    g = lk.tf([1], [1, 3, 2, 0])
    (lo, hi), = g.routh().stable_gains
    assert lo == pytest.approx(0, abs=1e-12) and hi == pytest.approx(6, rel=1e-12)
    # at K = 6 the loop has the axis pair ±j√2: s³ + 3s² + 2s + 6 = (s + 3)(s² + 2)
    r = g.routh(gain=6)
    np.testing.assert_array_equal(r.polynomial, [1, 3, 2, 6])
    assert (r.rhp, r.axis, r.lhp) == (0, 2, 1)
    assert g.routh(gain=3).stable and not g.routh(gain=7).stable
    assert "stable_gains" not in g.routh(gains=False)


def test_routh_of_factors():
    g = lk.zpk([], [-1, -2, -3], 1.0)
    # (s + 1)(s + 2)(s + 3) + K = s³ + 6s² + 11s + 6 + K: stable for −6 < K < 60
    (lo, hi), = g.routh().stable_gains
    assert lo == pytest.approx(-6, rel=1e-12) and hi == pytest.approx(60, rel=1e-12)


def test_jury_second_order_conditions():
    # z² − 1.2 z + 0.5 + 0.5 K: |0.5 + 0.5 K| < 1, 1 − 1.2 + 0.5 + 0.5 K > 0 → −0.6 < K < 1
    g = lk.tf([0.5], [1, -1.2, 0.5], dt=1)
    j = g.jury()
    assert (j.inside, j.on, j.outside) == (2, 0, 0) and j.stable and j.exact
    (lo, hi), = j.stable_gains
    assert lo == pytest.approx(-0.6, rel=1e-12) and hi == pytest.approx(1.0, rel=1e-12)
    assert j.rows[0].tolist() == [1, -1.2, 0.5] and len(j.rows[2]) == 2
    # K = 1: z² − 1.2 z + 1, both roots on the unit circle
    k1 = g.jury(gain=1)
    assert (k1.inside, k1.on, k1.outside) == (0, 2, 0) and not k1.stable
    roots = np.roots([1, -1.2, 1.0])
    np.testing.assert_allclose(np.abs(roots), 1, rtol=1e-14)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: lk.tf([1], [1, 1], dt=0.1).routh(), "jury"),
        (lambda: lk.tf([1], [1, 1]).jury(), "routh"),
        (lambda: lk.ss([[-1]], [[1]], [[1]]).routh(), "state-space"),
        (lambda: lk.tf([1], [1, 1], delay=0.5).routh(), "dead time"),
        (lambda: lk.tf([1], [1, 1]).routh(gain=math.nan), "finite"),
        (lambda: lk.tf([1], [1, 1]).routh(gain="x"), "number"),
        (lambda: lk.tf([0], [1, 1]).routh(), "zero numerator"),
    ],
)
def test_bad_inputs(call, match):
    with pytest.raises(lk.LtiError, match=match):
        call()
