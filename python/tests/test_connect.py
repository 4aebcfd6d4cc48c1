"""Dead times on zpk and ss models, and systems joined by named signals (lk.connect,
lk.diagram) — against closed forms and python-control's feedback / interconnect."""

import math

import numpy as np
import pytest

import ltikit as lk


def sorted_roots(r):
    r = np.asarray(r, dtype=complex)
    return r[np.lexsort((r.imag, r.real))]


def test_zpk_delay_as_tf_delay():
    w = np.logspace(-1, 1, 9)
    g = lk.zpk([], [-1], 1.0, delay=0.5)
    h = lk.tf([1], [1, 1], delay=0.5)
    np.testing.assert_allclose(g.freq(w).phase_deg, h.freq(w).phase_deg, rtol=1e-13)
    # closed form: the phase of e^(-0.5 s)/(s + 1) is −atan ω − 0.5 ω (radians)
    np.testing.assert_allclose(
        g.freq(w).phase_deg, np.degrees(-np.arctan(w) - 0.5 * w), rtol=1e-13
    )
    t = np.array([0.0, 0.25, 0.5, 1.5])
    # step: 0 before the delay, then 1 − e^(−(t − 0.5))
    np.testing.assert_allclose(g.step(t).y, [0, 0, 0, 1 - math.exp(-1)], atol=1e-15)


def test_discrete_zpk_delay_is_poles_at_zero():
    g = lk.zpk([], [0.5], 1.0, dt=0.1, delay=0.2)
    assert sorted(abs(p) for p in g.poles()) == [0, 0, 0.5]


def test_ss_delay_on_every_input():
    g = lk.ss([[-1]], [[1]], [[1]], delay=0.5)
    t = np.array([0.0, 0.4, 1.5])
    np.testing.assert_allclose(g.step(t).y, [0, 0, 1 - math.exp(-1)], atol=1e-15)
    w = np.array([0.5, 2.0])
    np.testing.assert_allclose(g.freq(w).phase_deg, np.degrees(-np.arctan(w) - 0.5 * w), rtol=1e-13)
    with pytest.raises(lk.LtiError, match="dead time"):
        g.lqr(1, 1)


def test_connect_unity_feedback_closed_form():
    p = lk.tf([1], [1, 1])
    t = lk.connect({"P": (p, "e", "y")}, inputs="r", outputs="y", sums={"e": "r - y"})
    np.testing.assert_allclose(t.poles(), [-2], rtol=1e-15)
    assert t.dc_gain() == pytest.approx(0.5, rel=1e-15)
    assert t.signals == {"inputs": ["r"], "outputs": ["y"], "states": ["P.x1"]}


def test_connect_against_python_control():
    control = pytest.importorskip("control")
    # PI controller and a second-order plant with a disturbance input d at the plant input;
    # outputs y and u
    c = lk.pid(kp=2.0, ki=1.0)
    p = lk.tf([4], [1, 0.8, 4])
    t = lk.connect(
        {"C": (c, "e", "v"), "P": (p, "u", "y")},
        inputs=["r", "d"],
        outputs=["y", "u"],
        sums={"e": "r - y", "u": "v + d"},
    )
    assert t.shape == (2, 2)
    cc = control.tf([2, 1], [1, 0], inputs="e", outputs="v")
    pc = control.tf([4], [1, 0.8, 4], inputs="u", outputs="y")
    se = control.summing_junction(inputs=["r", "-y"], output="e")
    su = control.summing_junction(inputs=["v", "d"], output="u")
    tc = control.interconnect([cc, pc, se, su], inputs=["r", "d"], outputs=["y", "u"])
    np.testing.assert_allclose(sorted_roots(t.poles()), sorted_roots(tc.poles()), rtol=1e-12)
    w = np.logspace(-1, 1, 7)
    np.testing.assert_allclose(t.freq(w).response, tc.frequency_response(w).complex, rtol=1e-12)
    # the closed loop from r to y: 4(2s + 1)/(s³ + 0.8 s² + 12 s + 4)
    np.testing.assert_allclose(
        sorted_roots(t[0, 0].poles()), sorted_roots(np.roots([1, 0.8, 12, 4])), rtol=1e-12
    )


def test_diagram_dict_like_a_diagram_file():
    d = lk.diagram(
        {
            "inputs": ["r"],
            "outputs": ["y"],
            "blocks": {
                "C": {"controller": "pi:kp=2,ki=1", "input": "e", "output": "u"},
                "P": {"num": [1], "den": [1, 1], "input": "u", "output": "y"},
            },
            "sums": {"e": "r - y"},
        }
    )
    # L = (2s + 1)/(s(s + 1)): s² + 3s + 1
    np.testing.assert_allclose(sorted_roots(d.poles()), sorted_roots(np.roots([1, 3, 1])), rtol=1e-14)
    assert d.dc_gain() == pytest.approx(1.0, rel=1e-14)
    s = lk.diagram({"inputs": "r", "outputs": "y",
                    "blocks": {"G": {"system": lk.zpk([], [-3], 3.0), "input": "r", "output": "y"}}})
    assert s.dc_gain() == pytest.approx(1.0, rel=1e-15)


def test_connect_pickles():
    import pickle

    t = lk.connect({"P": (lk.tf([1], [1, 1]), "e", "y")}, "r", "y", {"e": "r - y"})
    np.testing.assert_array_equal(pickle.loads(pickle.dumps(t)).poles(), t.poles())


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: lk.connect({"P": (lk.tf([1], [1, 1]), "e", "y")}, "r", "y"), "`e`"),
        (lambda: lk.connect({"P": (lk.tf([1], [1, 1]), "r", "y"), "Q": (lk.tf([1], [1, 2]), "r", "y")}, "r", "y"), "`y`"),
        (lambda: lk.connect({"P": (lk.tf([1], [1, 1]), ["a", "b"], "y")}, ["a", "b"], "y"), "inputs"),
        (lambda: lk.connect({"P": (lk.tf([1], [1, 1], delay=1), "r", "y")}, "r", "y"), "dead time"),
        (lambda: lk.connect({"P": (lk.tf([1], [1, 1]), "r", "y"), "Q": (lk.tf([1], [1, 1], dt=0.1), "y", "z")}, "r", "z"), "discrete-time"),
        (lambda: lk.connect({"P": (lk.zpk([], [-1], 1.0, delay=1), "r", "y")}, "r", "y"), "dead time"),
        (lambda: lk.connect({"K": (lk.tf([1], [1]), "e", "y")}, "r", "y", {"e": "r + y"}), "not well posed"),
        (lambda: lk.connect({"P": (3, "r", "y")}, "r", "y"), "block `P`"),
        (lambda: lk.connect({"P": (lk.tf([1], [1, 1]), "r", "y")}, "r", "y", {"e": "r -"}), "sum"),
        (lambda: lk.connect({"P": (lk.tf([1], [1, 1]), 5, "y")}, "r", "y"), "signal name"),
        (lambda: lk.diagram({"inputs": ["r"], "outputs": ["y"], "blocks": {"P": {"input": "r", "output": "y"}}}), "exactly one"),
        (lambda: lk.diagram({"inputs": ["r"], "outputs": ["y"], "blocks": {}, "wires": 1}), "unknown diagram key"),
        (lambda: lk.diagram({"inputs": ["r"], "outputs": ["y"], "blocks": {"C": {"controller": "pid:kq=1", "input": "r", "output": "y"}}}), "kq"),
        (lambda: lk.zpk([], [-1], 1.0, delay=-1), "delay"),
        # sampled inputs through a dead time: refused, not simulated without it
        (lambda: lk.tf([1], [1, 1], delay=1).response([1, 1, 1], [0, 1, 2]), "dead times"),
        (lambda: lk.zpk([], [-1], 1.0, delay=1).response([1, 1, 1], [0, 1, 2]), "dead times"),
        (lambda: lk.ss([[-1]], [[1]], [[1]], delay=math.nan), "delay"),
        (lambda: lk.zpk([], [0.5], 1.0, dt=0.1, delay=0.15), "period"),
    ],
)
def test_bad_inputs(call, match):
    with pytest.raises(lk.LtiError, match=match):
        call()
