"""Analyses against closed forms (the README tour's plants); each reference is derived in
the comment beside it."""

import math

import numpy as np
import pytest

import ltikit as lk

# 4/(s^2 + 0.8 s + 4): wn = 2, zeta = 0.2, wd = wn sqrt(1 - zeta^2)
WN, ZETA = 2.0, 0.2
WD = WN * math.sqrt(1 - ZETA**2)
SIGMA = ZETA * WN


@pytest.fixture
def g():
    return lk.tf([4], [1, 0.8, 4])


def test_analyze_carries_the_analyze_json_document(g):
    a = g.analyze()
    assert a.order == 2 and a.relative_degree == 2
    assert a.dc_gain == 1.0
    assert a.bibo_stable and a.internally_stable
    assert "decided exactly" in a.stability_reason
    assert a.structure == "exact"
    assert a.second_order["class"] == "underdamped"
    assert a.second_order.wd == pytest.approx(WD, rel=1e-15)
    assert a.modes[0].zeta == pytest.approx(ZETA, rel=1e-15)
    assert a.modes[0].time_constant == pytest.approx(1 / SIGMA, rel=1e-15)
    np.testing.assert_allclose(a.poles, [-SIGMA + 1j * WD, -SIGMA - 1j * WD], rtol=1e-15)
    # overshoot e^(-pi zeta / sqrt(1 - zeta^2)), peak at pi/wd
    si = a.step_info
    assert si.overshoot_percent == pytest.approx(100 * math.exp(-math.pi * ZETA / math.sqrt(1 - ZETA**2)), rel=1e-12)
    assert si.peak_time == pytest.approx(math.pi / WD, rel=1e-12)
    assert set(a.keys()) >= {"order", "relative_degree", "poles", "zeros", "zeros_at_infinity",
                             "cancelled", "near_cancellations", "dc_gain", "bibo_stable",
                             "internally_stable", "stability_reason", "structure",
                             "structure_note", "modes", "second_order", "step_info"}
    d = a.to_dict()
    assert d["step_info"]["steady_state"] == 1.0


def test_cancelled_unstable_mode_is_reported():
    # (s - 1)/(s^2 + s - 2) = (s - 1)/((s - 1)(s + 2)): reduced 1/(s + 2), the mode at 1 hidden
    g = lk.tf([1, -1], [1, 1, -2])
    a = g.analyze()
    np.testing.assert_array_equal(a.cancelled, [1])
    assert a.bibo_stable and not a.internally_stable
    s = g.is_stable()
    assert not s
    assert "cancelled pole at s = 1" in s.reason


def test_step_closed_form(g):
    # y(t) = 1 - e^(-sigma t) (cos wd t + sigma/wd sin wd t)
    t = np.linspace(0, 10, 101)
    r = g.step(t)
    want = 1 - np.exp(-SIGMA * t) * (np.cos(WD * t) + SIGMA / WD * np.sin(WD * t))
    np.testing.assert_allclose(r.y, want, atol=1e-14)
    tt, yy = r
    assert tt is r.t and yy is r.y
    assert r.final_value == 1.0
    assert "e^(-0.4 t)" in r.closed_form
    assert r.closed_form_error < 1e-13


def test_impulse_closed_form(g):
    # h(t) = (wn^2/wd) e^(-sigma t) sin wd t
    t = np.linspace(0, 5, 51)
    np.testing.assert_allclose(g.impulse(t).y, WN**2 / WD * np.exp(-SIGMA * t) * np.sin(WD * t), atol=1e-14)


def test_response_to_samples_matches_the_closed_form_of_a_ramp():
    # 1/(s + 1) driven by u = t: y = t - 1 + e^(-t) (first-order hold is exact for a ramp)
    g = lk.tf([1], [1, 1])
    t = np.linspace(0, 5, 201)
    np.testing.assert_allclose(g.response(t, t).y, t - 1 + np.exp(-t), atol=1e-13)
    np.testing.assert_allclose(g.response("ramp", t).y, t - 1 + np.exp(-t), atol=1e-14)


def test_automatic_time_grid(g):
    r = g.step()
    assert r.t[0] == 0 and len(r.t) == len(r.y) > 100


def test_step_info_and_its_refusal(g):
    si = g.step_info()
    assert si.rise_time > 0 and si.settling_time > si.rise_time
    with pytest.raises(lk.LtiError, match="does not settle"):
        lk.tf([1], [1, 0]).step_info()


def test_freq_magnitude_phase_complex(g):
    # G(jw) = 4/(4 - w^2 + 0.8 j w)
    w = np.logspace(-2, 2, 50)
    fr = g.freq(w)
    want = 4 / (4 - w**2 + 0.8j * w)
    np.testing.assert_allclose(fr.response, want, rtol=1e-13)
    np.testing.assert_allclose(fr.magnitude, abs(want), rtol=1e-14)
    # continuous phase: from 0 down to -180 degrees, never wrapped
    np.testing.assert_allclose(fr.phase_deg, -np.degrees(np.arctan2(0.8 * w, 4 - w**2)), atol=1e-12)
    ww, mag, ph = fr
    assert ww is fr.w


def test_phase_is_continuous_past_minus_180():
    # 1/(s+1)^4: phase -4 atan(w), down to -360 degrees without a jump
    w = np.logspace(-2, 3, 400)
    ph = lk.zpk([], [-1] * 4, 1.0).freq(w).phase_deg
    np.testing.assert_allclose(ph, -4 * np.degrees(np.arctan(w)), atol=1e-11)


def test_margins_closed_form():
    # 2/(s^3 + 3 s^2 + 2 s): phase -180 at w = sqrt 2 where |G| = 1/3, so GM = 3
    m = lk.tf([2], [1, 3, 2, 0]).margins()
    assert m.gain_margin == pytest.approx(3.0, rel=1e-12)
    assert m.phase_crossover == pytest.approx(math.sqrt(2), rel=1e-12)
    assert m.gain_margin_db == pytest.approx(20 * math.log10(3), rel=1e-12)


def test_residue_double_and_triple_pole():
    # (s + 3)/(s + 1)^3 = 1/(s + 1)^2 + 2/(s + 1)^3
    r = lk.tf([1, 3], [1, 3, 3, 1]).residue()
    terms = sorted((k, c) for p, k, c in r.terms if abs(c) > 0)
    assert terms == [(2, 1 + 0j), (3, 2 + 0j)]


def test_nyquist_counts():
    # 2/(s (s+1)(s+2)): GM 3 > 1, closed loop stable: N = 0, Z = 0
    n = lk.tf([2], [1, 3, 2, 0]).nyquist()
    assert n.open_loop_rhp_poles == 0 and n.closed_loop_rhp_poles == 0
    assert n.s.dtype == np.complex128 and n.g.shape == n.s.shape
    # gain 6 (3x): on the stability boundary beyond; gain 12: two closed-loop RHP poles
    assert lk.tf([12], [1, 3, 2, 0]).nyquist().closed_loop_rhp_poles == 2


def test_rlocus_crossing_gain():
    # 1/(s (s+1)(s+2)): s^3 + 3 s^2 + 2 s + K crosses the axis at K = 6, w = sqrt 2
    rl = lk.tf([1], [1, 3, 2, 0]).rlocus()
    assert rl.branches.shape == (3, len(rl.gains))
    k = [c.gain for c in rl.crossings]
    assert any(abs(x - 6) < 1e-9 for x in k)


def test_discrete_step_closed_form():
    # y[k] = 1 - 0.5^k for G(z) = 0.5/(z - 0.5) (one-sample delay: y[0] = 0)
    g = lk.tf([0.5], [1, -0.5], dt=1.0)
    k = np.arange(10.0)
    np.testing.assert_allclose(g.step(k).y, 1 - 0.5**k, atol=1e-15)


def test_eval(g):
    assert g(1j) == pytest.approx(4 / (3 + 0.8j), rel=1e-15)


def test_c2d_zoh_closed_form_and_back():
    # ZOH of 1/(s + 1) with T: (1 - e^-T)/(z - e^-T)
    T = 0.1
    d = lk.tf([1], [1, 1]).c2d(T)
    assert d.dt == T
    np.testing.assert_allclose(d.poles(), [math.exp(-T)], rtol=1e-15)
    assert d.gain == pytest.approx(1 - math.exp(-T), rel=1e-14)
    assert d.dc_gain() == pytest.approx(1.0, rel=1e-14)
    back = d.d2c()
    assert back.dt is None
    np.testing.assert_allclose(back.poles(), [-1], rtol=1e-13)
    # a state-space model keeps its matrices: A_d = e^(A T)
    s = lk.ss([[-2.0]], [[1.0]], [[1.0]]).c2d(T, "tustin")
    a, b, c, dd = s.ssdata()
    assert s.dt == T and a.shape == (1, 1)
    # Tustin: z = (1 + s T/2)/(1 - s T/2) at s = -2
    np.testing.assert_allclose(s.poles(), [(1 - T) / (1 + T)], rtol=1e-14)
    with pytest.raises(lk.LtiError):
        lk.tf([1], [1, 1]).c2d(0.1, "wobble")
    with pytest.raises(lk.LtiError):
        lk.tf([1], [1, 1]).d2c()  # not discrete


def test_a_dead_time_is_kept_exact():
    # e^(−0.5 s)·2/(s + 1): |G| unchanged, phase −atan ω − 0.5 ω; the step is 0 before 0.5 s;
    # the phase margin 120° − √3·0.5 rad and the delay margin 2π/(3√3) − 0.5 (closed forms)
    import math
    g = lk.tf([2], [1, 1], delay=0.5)
    f = g.freq([1.0])
    assert abs(f.phase_deg[0] - math.degrees(-math.atan(1.0) - 0.5)) < 1e-12
    y = g.step(np.array([0.25, 1.5])).y
    assert y[0] == 0.0 and abs(y[1] - 2 * (1 - math.exp(-1.0))) < 1e-14
    m = g.margins()
    assert abs(m.phase_margin_deg - (120 - math.degrees(math.sqrt(3) * 0.5))) < 1e-10
    assert abs(m.delay_margin - (2 * math.pi / (3 * math.sqrt(3)) - 0.5)) < 1e-12
    with pytest.raises(lk.LtiError):
        lk.tf([1], [1, 1], delay=-1)
