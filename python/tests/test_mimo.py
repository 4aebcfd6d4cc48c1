"""Whole-model analysis of MIMO state-space models (no channel indexing) and initial states:
against python-control (``poles``, ``zeros``, ``dcgain``, ``frequency_response``,
``step_response``, ``impulse_response``, ``forced_response``, ``initial_response``) and closed
forms."""

import numpy as np
import pytest

import ltikit as lk

control = pytest.importorskip("control")

# A coupled, stable 3-state model with 2 inputs, 2 outputs and a feedthrough.
A = [[-1, 1, 0], [0, -2, 1], [0, 0, -3]]
B = [[1, 0], [0, 1], [1, 1]]
C = [[1, 0, 0], [0, 1, 1]]
D = [[0, 0], [0, 0.5]]

# ControlSystems.jl's 3-output, 2-input example (the README's): zeros 4 and −3, normal rank 2,
# infinite zeros of orders 1 and 1, one left Kronecker index 1.
A3 = [[-2, -6, 3, -7, 6], [0, -5, 4, -4, 8], [0, 2, 0, 2, -2], [0, 6, -3, 5, -6], [0, -2, 2, -2, 5]]
B3 = [[-2, 7], [-8, -5], [-3, 0], [1, 5], [-8, 0]]
C3 = [[0, -1, 2, -1, -1], [1, 1, 1, 0, -1], [0, 3, -2, 3, -1]]


def sorted_roots(r):
    r = np.asarray(r, dtype=complex)
    return r[np.lexsort((r.imag, r.real))]


@pytest.fixture
def both():
    return lk.ss(A, B, C, D), control.ss(A, B, C, D)


def test_poles_zeros_dc_gain_stability(both):
    g, c = both
    np.testing.assert_allclose(sorted_roots(g.poles()), sorted_roots(c.poles()), atol=1e-14)
    # square 2×2: python-control's zeros are the pencil's generalised eigenvalues
    np.testing.assert_allclose(sorted_roots(g.zeros()), sorted_roots(c.zeros()), rtol=1e-12)
    # closed form: det G(s) = 0 at s² + 9 s + 17 = 0
    np.testing.assert_allclose(sorted_roots(g.zeros()), sorted_roots(np.roots([1, 9, 17])), rtol=1e-13)
    np.testing.assert_allclose(g.dc_gain(), control.dcgain(c), rtol=1e-14)
    assert g.dc_gain().shape == (2, 2)
    s = g.is_stable()
    assert bool(s) and s.bibo_stable and s.channels_bibo_stable.all()


def test_non_square_zeros_and_kronecker_structure():
    g = lk.ss(A3, B3, C3)
    np.testing.assert_allclose(sorted_roots(g.zeros()), [-3, 4], atol=1e-12)
    z = g.zero_structure()
    assert z.normal_rank == 2
    assert z.infinite_orders == [1, 1]
    assert z.left_indices == [1] and z.right_indices == []
    assert [k for _, k in z.multiplicities] == [1, 1]


def test_transmission_zeros_leave_decoupling_zeros_out():
    # (s + 1)/((s + 1)(s + 2)) realised with the cancelling mode: one invariant zero −1 of the
    # realisation (the analysis's), no transmission zero
    g = lk.ss([[-3, -2], [1, 0]], [[1], [0]], [[1, 1]])
    assert g.zeros().size == 0 or g.is_siso()  # SISO: the factored form's zeros
    assert g.zero_structure().zeros.size == 0
    a = g.analyze(whole=True)
    assert len(a.invariant_zeros) == 1
    assert a.invariant_zeros[0][0] == pytest.approx(-1, abs=1e-14)
    assert a.minimal_order == 1


def test_whole_analysis(both):
    g, _ = both
    a = g.analyze()
    assert isinstance(a, lk.StateSpaceAnalysis)
    assert (a.n, a.m, a.p) == (3, 2, 2)
    np.testing.assert_allclose(sorted_roots(a.poles), [-3, -2, -1], atol=1e-14)
    assert a.minimal_order == 3
    assert a.controllability.rank == 3 and a.observability.rank == 3
    assert a.internally_stable
    np.testing.assert_allclose(a.dc_gain, g.dc_gain(), rtol=0)
    assert a.bibo_stable.shape == (2, 2)


def test_integrator_channel_has_infinite_dc_gain():
    g = lk.ss([[0, 0], [0, -1]], [[1, 0], [0, 1]], [[1, 0], [0, 1]])
    dc = g.dc_gain()
    assert np.isinf(dc[0, 0]) and dc[1, 1] == pytest.approx(1.0, rel=1e-15)
    assert not g.is_stable()


def test_frequency_response(both):
    g, c = both
    w = np.logspace(-2, 2, 41)
    fr = g.freq(w)
    want = c.frequency_response(w)
    assert fr.magnitude.shape == (2, 2, 41)
    np.testing.assert_allclose(fr.response, want.complex, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(fr.magnitude, want.magnitude, rtol=1e-12, atol=1e-15)
    # channel by channel it is the SISO response of G[out, in]
    np.testing.assert_array_equal(fr.phase_deg[1, 0], g[1, 0].freq(w).phase_deg)
    auto = g.freq()
    assert auto.w.size == 1000 and auto.magnitude.shape == (2, 2, 1000)


def test_step_and_impulse_per_input(both):
    g, c = both
    t = np.linspace(0, 6, 61)
    s = g.step(t)
    assert s.y.shape == (2, 2, 61)
    np.testing.assert_allclose(s.y, control.step_response(c, t).outputs, atol=1e-12)
    i = g.impulse(t)
    np.testing.assert_allclose(i.y, control.impulse_response(c, t).outputs, atol=1e-12)
    # the final values are the dc gains
    far = g.step([0, 60]).y[:, :, -1]
    np.testing.assert_allclose(far, g.dc_gain(), rtol=1e-12)
    assert g.step().y.shape[:2] == (2, 2)


def test_forced_response_with_two_inputs(both):
    g, c = both
    t = np.linspace(0, 5, 201)
    u = np.column_stack([np.sin(2 * t), 1 - np.exp(-t)])
    r = g.response(u, t)
    assert r.y.shape == (2, 201)
    # first-order hold, as python-control's forced_response
    np.testing.assert_allclose(r.y, control.forced_response(c, t, u.T).outputs, atol=1e-12)


def test_initial_state(both):
    g, c = both
    t = np.linspace(0, 4, 41)
    x0 = [1.0, -1.0, 0.5]
    r = g.initial(x0, t)
    np.testing.assert_allclose(r.y, control.initial_response(c, t, x0).outputs, atol=1e-13)
    u = np.column_stack([np.cos(t), np.ones_like(t)])
    f = g.response(u, t, x0=x0)
    np.testing.assert_allclose(f.y, control.forced_response(c, t, u.T, X0=x0).outputs, atol=1e-12)
    # a step from x0 is the forced step plus the free response
    s = g.response("step", t, x0=x0)
    np.testing.assert_allclose(s.y, g.step(t).y + r.y[:, None, :], atol=1e-15)


def test_initial_state_siso_closed_form():
    # x' = -2 x, y = 3 x: y = 3 x0 e^(-2t)
    g = lk.ss([[-2]], [[1]], [[3]])
    t = np.linspace(0, 2, 11)
    np.testing.assert_allclose(g.initial([0.5], t).y, 1.5 * np.exp(-2 * t), rtol=1e-14)
    # with u = 1 from x0: y = 3 (1/2 + (x0 - 1/2) e^(-2t))
    y = g.response(np.ones_like(t), t, x0=[2.0]).y
    np.testing.assert_allclose(y, 3 * (0.5 + 1.5 * np.exp(-2 * t)), rtol=1e-13)
    y = g.response("step", t, x0=[2.0]).y
    np.testing.assert_allclose(y, 3 * (0.5 + 1.5 * np.exp(-2 * t)), rtol=1e-13)


def test_discrete_mimo_step():
    a = [[0.5, 0.1], [0, 0.8]]
    b = [[1, 0], [0, 1]]
    cc = [[1, 0], [0, 1]]
    g, c = lk.ss(a, b, cc, dt=0.1), control.ss(a, b, cc, 0, 0.1)
    t = np.arange(20) * 0.1
    np.testing.assert_allclose(g.step(t).y, control.step_response(c, t).outputs, atol=1e-14)
    x0 = [1, 1]
    np.testing.assert_allclose(g.initial(x0, t).y, control.initial_response(c, t, x0).outputs, atol=1e-14)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda g: g.response(np.ones((5, 3)), np.arange(5.0)), "shape"),
        (lambda g: g.response(np.ones(5), np.arange(5.0)), "shape"),
        (lambda g: g.response([[1, "x"]] * 2, [0, 1]), "array of numbers"),
        (lambda g: g.response("ramp", [0, 1]), "MIMO"),
        (lambda g: g.response("ramp", [0, 1], x0=[0, 0, 0]), "x0"),
        (lambda g: g.initial([1, 2], [0, 1]), "3 states"),
        (lambda g: g.initial([1, float("nan"), 0], [0, 1]), "initial state"),
        (lambda g: g.initial([1, 0, 0], [0, float("inf")]), "finite"),
        (lambda g: g.freq([-1.0]), "frequencies must be"),
        (lambda g: g.response(np.ones((2, 2)), [0, 1], hold="cubic"), "hold"),
    ],
)
def test_bad_inputs(both, call, match):
    g, _ = both
    with pytest.raises(lk.LtiError, match=match):
        call(g)


def test_initial_state_needs_state_space():
    with pytest.raises(lk.LtiError, match="state-space model"):
        lk.tf([1], [1, 1]).initial([1.0], [0, 1])
    with pytest.raises(lk.LtiError, match="state-space model"):
        lk.tf([1], [1, 1]).response([1, 1], [0, 1], x0=[1.0])


@pytest.mark.parametrize("dt", [None, 0.1])
def test_dc_gain_direct_equals_the_analysis(dt):
    # before the whole analysis exists the dc gain is solved directly (A clearly
    # nonsingular); the analysis (a minimal realisation per channel) gives the same values
    rng = np.random.default_rng(7)
    a = rng.uniform(-1, 1, (5, 5)) - (3.0 if dt is None else 0.0) * np.eye(5)
    if dt is not None:
        a *= 0.15  # spectral radius < 1
    b, c, d = rng.uniform(-1, 1, (5, 2)), rng.uniform(-1, 1, (3, 5)), rng.uniform(-1, 1, (3, 2))
    direct = lk.ss(a, b, c, d, dt=dt).dc_gain()
    g = lk.ss(a, b, c, d, dt=dt)
    via = g.analyze().dc_gain
    np.testing.assert_allclose(direct, via, rtol=1e-12)
    np.testing.assert_allclose(direct, control.dcgain(control.ss(a, b, c, d, 0 if dt is None else dt)), rtol=1e-12)
    assert direct.shape == (3, 2)
