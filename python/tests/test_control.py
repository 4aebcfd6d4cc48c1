"""Results against python-control on a set of plants (skipped when python-control is not
installed). python-control finds roots with numpy (eigenvalues of the companion matrix) and
simulates the step with scipy, so the tolerances are theirs, not ltikit's."""

import numpy as np
import pytest

import ltikit as lk

control = pytest.importorskip("control")

PLANTS = [
    ([4], [1, 0.8, 4]),
    ([1, 3], [1, 3, 3, 1]),
    ([2], [1, 3, 2, 0]),
    ([1, 2], [1, 5, 9, 7, 2]),
    ([0.5, 1], [1, 2.2, 3.4, 2.1, 0.6]),
    ([10], [1, 11, 10]),
    ([1, -1], [1, 4, 6, 4]),
    ([3, 1, 2], [1, 6, 11, 6]),
]


def sorted_roots(r):
    r = np.asarray(r, dtype=complex)
    return r[np.lexsort((r.imag, r.real))]


@pytest.mark.parametrize("num, den", PLANTS)
def test_poles_zeros_dc_gain(num, den):
    g, c = lk.tf(num, den), control.tf(num, den)
    # numpy's roots scatter an m-fold root by ~eps^(1/m) (6e-6 for a triple one); ltikit's
    # are exact there, so the tolerance is numpy's
    tol = 1e-4 if max(m for _, m in g.pole_multiplicities()) > 1 else 1e-9
    np.testing.assert_allclose(sorted_roots(g.poles()), sorted_roots(c.poles()), atol=tol)
    np.testing.assert_allclose(sorted_roots(g.zeros()), sorted_roots(c.zeros()), atol=1e-9)
    want = control.dcgain(c)
    assert g.dc_gain() == pytest.approx(want, rel=1e-12) if np.isfinite(want) else np.isinf(g.dc_gain())


@pytest.mark.parametrize("num, den", PLANTS)
def test_frequency_response(num, den):
    g, c = lk.tf(num, den), control.tf(num, den)
    w = np.logspace(-2, 2, 200)
    resp = control.frequency_response(c, w)
    np.testing.assert_allclose(g.freq(w).magnitude, np.abs(resp.complex), rtol=1e-10)
    np.testing.assert_allclose(g.freq(w).response, resp.complex, rtol=1e-10, atol=1e-14)


@pytest.mark.parametrize("num, den", [p for p in PLANTS if p[1][-1] != 0])
def test_step_response(num, den):
    g, c = lk.tf(num, den), control.tf(num, den)
    t = np.linspace(0, 20, 401)
    want = control.step_response(c, t).outputs
    np.testing.assert_allclose(g.step(t).y, want, atol=1e-8)


@pytest.mark.parametrize("num, den", PLANTS)
def test_margins(num, den):
    g, c = lk.tf(num, den), control.tf(num, den)
    gm, pm, wcg, wcp = control.margin(c)
    m = g.margins()
    if np.isfinite(gm):
        assert m.gain_margin == pytest.approx(gm, rel=1e-6)
        assert m.phase_crossover == pytest.approx(wcg, rel=1e-6)
    else:
        assert m.gain_margin is None
    if np.isfinite(pm):
        assert m.phase_margin_deg == pytest.approx(pm, rel=1e-6)
        assert m.gain_crossover == pytest.approx(wcp, rel=1e-6)


@pytest.mark.parametrize("num, den", [p for p in PLANTS if p[1][-1] != 0])
def test_step_info(num, den):
    g, c = lk.tf(num, den), control.tf(num, den)
    want = control.step_info(c, T=np.linspace(0, 60, 600001))
    si = g.step_info()
    # python-control reads the metrics off samples (dt = 1e-4 here): 1e-3 relative
    assert si.overshoot_percent == pytest.approx(want["Overshoot"], abs=1e-3)
    assert si.peak == pytest.approx(want["Peak"], rel=1e-6)
    assert si.rise_time == pytest.approx(want["RiseTime"], abs=2e-4)
    assert si.settling_time == pytest.approx(want["SettlingTime"], abs=2e-4)


def test_round_trip_through_python_control():
    g = lk.tf([4], [1, 0.8, 4])
    c = g.to_control()
    assert isinstance(c, control.TransferFunction)
    back = lk.from_control(c)
    np.testing.assert_array_equal(back.poles(), g.poles())
    s = lk.ss([[0, 1], [-4, -0.8]], [[0], [4]], [[1, 0]])
    cs = s.to_control()
    assert isinstance(cs, control.StateSpace)
    np.testing.assert_allclose(sorted_roots(lk.from_control(cs).poles()), sorted_roots(g.poles()), atol=1e-14)
    d = lk.from_control(control.tf([0.5], [1, -0.5], 0.1))
    assert d.dt == 0.1


def test_from_scipy():
    signal = pytest.importorskip("scipy.signal")
    g = lk.from_scipy(signal.lti([4], [1, 0.8, 4]))
    assert g.dc_gain() == 1.0
    z = lk.from_scipy(signal.ZerosPolesGain([], [-1, -2], 2))
    assert z.dc_gain() == 1.0
    s = lk.from_scipy(signal.StateSpace([[0, 1], [-4, -0.8]], [[0], [4]], [[1, 0]], [[0]]))
    assert s.dc_gain() == pytest.approx(1.0, rel=1e-14)
    d = lk.from_scipy(signal.dlti([0.5], [1, -0.5], dt=0.1))
    assert d.dt == 0.1
