"""Norms, Gramians, Hankel singular values, balanced truncation and singular values; the
value at a complex point of a MIMO model; a diagram file through lk.plant. References: closed
forms, python-control (ct.norm without Slycot) and scipy."""

import math
import pathlib
import pickle

import numpy as np
import pytest

import ltikit as lk

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("zeta", [0.05, 0.1, 0.3, 0.6])
def test_hinf_of_the_second_order_lag_is_the_resonant_peak(zeta):
    # ‖1/(s² + 2ζs + 1)‖∞ = 1/(2ζ√(1 − ζ²)) at ω = √(1 − 2ζ²) (ζ < 1/√2)
    exact = 1.0 / (2 * zeta * math.sqrt(1 - zeta**2))
    n = lk.tf([1], [1, 2 * zeta, 1]).hinf_norm()
    assert n.lower <= exact * (1 + 1e-13) and exact <= n.upper * (1 + 1e-15)
    assert abs(n.value / exact - 1) < 1e-13 and float(n) == n.value
    assert n.relative_gap <= 1e-10 and n.infinite is None and n.norm == "H∞"
    assert abs(n.w - math.sqrt(1 - 2 * zeta**2)) < 1e-6


@pytest.mark.parametrize("a", [0.5, 1.0, 3.0, 40.0])
def test_h2_of_the_first_order_lag(a):
    # ‖1/(s + a)‖₂ = 1/√(2a)
    n = lk.tf([1], [1, a]).h2_norm()
    assert abs(n.value * math.sqrt(2 * a) - 1) < 1e-15 and n.infinite is None


def test_norms_against_python_control():
    ct = pytest.importorskip("control")
    A = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [-6.0, -11.0, -6.0]])
    B, C = np.array([[0.0], [0.0], [1.0]]), np.array([[2.0, 1.0, 0.0]])
    G = lk.ss(A, B, C, 0)
    ref = ct.ss(A, B, C, 0)
    assert abs(G.h2_norm().value / ct.norm(ref, 2) - 1) < 1e-12
    # python-control's H∞ without Slycot is a bisection to its tolerance 1e-6
    n = G.hinf_norm()
    assert abs(n.value / ct.norm(ref, "inf") - 1) < 1e-5
    # against a dense grid: no sampled gain above the certified upper bound
    w = np.logspace(-3, 3, 20001)
    peak = np.max(np.abs(G.freq(w).response))
    assert peak <= n.upper and n.lower <= n.upper * (1 + 1e-15)


def test_infinite_norms_say_why_and_linf_of_an_unstable_lag():
    unstable = lk.tf([1], [1, -1])
    h = unstable.hinf_norm()
    assert math.isinf(h.value) and "1" in h.infinite
    # |1/(jω − 1)| = 1/√(ω² + 1): peak 1 at ω = 0
    l = unstable.linf_norm()
    assert l.lower <= 1.0 <= l.upper and l.w == 0.0
    assert math.isinf(lk.tf([1, 0], [1, 3]).h2_norm().value)  # D ≠ 0
    assert "D" in lk.tf([1, 0], [1, 3]).h2_norm().infinite


def test_gramians_and_hankel_singular_values():
    sl = pytest.importorskip("scipy.linalg")
    # 1/(s + a): P = Q = 1/(2a), σ = 1/(2a)
    assert abs(lk.ss([[-2.0]], [[1.0]], [[1.0]]).gram("c").gramian[0, 0] - 0.25) < 1e-16
    assert abs(lk.tf([1], [1, 1]).hsv()[0] - 0.5) < 4e-16
    A = np.array([[-1.0, 0.5, 0.0], [0.0, -2.0, 1.0], [0.3, 0.0, -3.0]])
    B, C = np.array([[1.0], [0.0], [1.0]]), np.array([[1.0, 1.0, 0.0]])
    G = lk.ss(A, B, C)
    P = G.gram("c")
    Q = G.gram("observability")
    assert np.max(np.abs(P.gramian - sl.solve_continuous_lyapunov(A, -B @ B.T))) < 1e-14
    assert np.max(np.abs(Q.gramian - sl.solve_continuous_lyapunov(A.T, -C.T @ C))) < 1e-14
    assert np.max(np.abs(P.factor @ P.factor.T - P.gramian)) < 1e-15
    hsv = np.sqrt(np.sort(np.linalg.eigvals(P.gramian @ Q.gramian).real)[::-1])
    assert np.allclose(G.hsv(), hsv, rtol=1e-10)
    with pytest.raises(lk.LtiError) as e:
        G.gram("x")
    assert "c (controllability) or o (observability)" in str(e.value)


def test_balanced_truncation_drops_the_fast_mode():
    # 1/(s + 1) + 0.01/(s + 10): the a priori bound 2σ₂ against the certified error
    G = lk.ss([[-1.0, 0.0], [0.0, -10.0]], [[1.0], [0.1]], [[1.0, 0.1]])
    r = G.balred(order=1)
    assert isinstance(r.reduced, lk.System) and r.order == 1 and r.states == 2
    assert r.reduced.ssdata()[0].shape == (1, 1)
    assert abs(r.bound - 2 * r.hsv[1]) < 1e-18 and r.bound < 1e-3
    assert r.error.lower <= r.bound * (1 + 1e-12)
    # the error is the H∞ norm of the difference, recomputed through the operators
    diff = (G - r.reduced).hinf_norm()
    assert abs(diff.value / r.error.value - 1) < 1e-6
    # by error bound: the smallest order whose bound is below it
    assert G.balred(error=1e-3).order == 1 and G.balred(error=1e-12).order == 2
    assert pickle.loads(pickle.dumps(r.reduced)).shape == (1, 1)


@pytest.mark.parametrize(
    "call, words",
    [
        (lambda: lk.tf([1], [1, 1]).balred(), "balred needs `order` or `error`"),
        (lambda: lk.tf([1], [1, 1]).balred(order=1, error=0.1), "not both"),
        (lambda: lk.tf([1], [1, 1]).balred(order=3), "exceeds the model's 1 states"),
        (lambda: lk.tf([1], [1, 1]).balred(order=-1), "`order` must be a whole number"),
        (lambda: lk.tf([1], [1, 1]).balred(error=-1), "error"),
        (lambda: lk.tf([1], [1, -1]).balred(order=1), "stable"),
        (lambda: lk.tf([1], [1, -1]).gram("c"), "stable"),
        (lambda: lk.tf([1], [1, 1]).sigma([-1.0]), "frequenc"),
        (lambda: lk.tf([1], [1, 1]).sigma([math.nan]), "frequenc"),
    ],
)
def test_bad_reductions_raise_one_line(call, words):
    with pytest.raises(lk.LtiError) as e:
        call()
    msg = str(e.value)
    assert "\n" not in msg and words in msg, msg


def test_sigma_of_decoupled_lags():
    # diag(1/(s + 1), 2/(s + 2)): σ = {2/|jω + 2|, 1/|jω + 1|}
    G = lk.ss(np.diag([-1.0, -2.0]), np.diag([1.0, 2.0]), np.eye(2))
    s = G.sigma([0.0, 2.0])
    assert s.shape == (2, 2)
    assert np.max(np.abs(s - [[1.0, 1.0], [math.sqrt(0.5), math.sqrt(0.2)]])) < 1e-15


def test_eval_of_a_mimo_model_and_at_a_pole():
    # ẋ = −x + u, y = [x; 2x + u]: G = [1/(s+1); 2/(s+1) + 1]
    G = lk.ss([[-1.0]], [[1.0]], [[1.0], [2.0]], [[0.0], [1.0]])
    g = G.eval(1.0)
    assert g.shape == (2, 1) and np.allclose(g, [[0.5], [2.0]], rtol=1e-15)
    assert np.allclose(G(1j), [[1 / (1j + 1)], [2 / (1j + 1) + 1]], rtol=1e-15)
    assert lk.tf([4], [1, 0.8, 4]).eval(1j) == pytest.approx(4 / (3 + 0.8j), rel=1e-15)
    with pytest.raises(lk.LtiError) as e:
        lk.tf([1], [1, 1]).eval(-1)
    assert "is at the pole" in str(e.value)
    with pytest.raises(lk.LtiError):
        lk.tf([1], [1, 1]).eval("x")


def test_a_diagram_file_is_a_plant():
    # the cascade's closed form (its comment: inner PI 6 + 20/s on v, outer P 3 on x, the
    # mass x'' + 0.4x' + 4x = F): X/R = (18s + 60)/(s³ + 6.4s² + 42s + 60)
    T = lk.plant(ROOT / "data" / "diagrams" / "smd_cascade.toml")
    assert T.shape == (1, 1)
    den = [1.0, 6.4, 42.0, 60.0]
    assert np.allclose(np.sort_complex(T.poles()), np.sort_complex(np.roots(den)), rtol=1e-12)
    assert abs(T.dc_gain() - 1.0) < 1e-12
    s = 0.3 + 2j
    assert T.eval(s) == pytest.approx((18 * s + 60) / np.polyval(den, s), rel=1e-12)
    assert bool(T.is_stable())
    n = T.hinf_norm()
    assert n.lower <= n.upper
