"""Controller and estimator design (lqr, lqe, lqg, place) and the matrix equations (lyap,
dlyap, sylvester, care, dare): closed forms, python-control (its lqr, dlqr, lqe and place need
no Slycot) and scipy.linalg; bad inputs raise LtiError with the command line's message."""

import math
import pickle

import numpy as np
import pytest

import ltikit as lk

SQRT3 = math.sqrt(3.0)

# the double integrator ẍ = u, y = x
A2 = [[0.0, 1.0], [0.0, 0.0]]
B2 = [[0.0], [1.0]]
C2 = [[1.0, 0.0]]

# a third-order plant with a lightly damped pair, an unstable mode and two inputs
A3 = [[0.0, 1.0, 0.0], [-2.0, -0.3, 1.0], [0.5, 0.0, 0.4]]
B3 = [[0.0, 1.0], [1.0, 0.0], [0.0, 0.5]]
C3 = [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]


def double_integrator() -> lk.System:
    return lk.ss(A2, B2, C2, 0)


def test_double_integrator_lqr_is_one_root_three():
    # closed form: K = [1, √3], X = [[√3, 1], [1, √3]] (the CARE solved by hand)
    d = double_integrator().lqr(np.eye(2), 1)
    assert d.K.shape == (1, 2)
    assert abs(d.K[0, 0] - 1.0) < 1e-14 and abs(d.K[0, 1] - SQRT3) < 1e-14
    assert np.max(np.abs(d.X - [[SQRT3, 1.0], [1.0, SQRT3]])) < 1e-14
    # eig(A − BK): s² + √3 s + 1 = 0
    assert np.allclose(sorted(d.poles, key=lambda z: z.imag), [(-SQRT3 - 1j) / 2, (-SQRT3 + 1j) / 2], atol=1e-14)
    assert d.equation == "care" and d.residual < 1e-14
    # the free function on matrices, as python-control's ct.lqr(A, B, Q, R)
    f = lk.lqr(A2, B2, np.eye(2), [[1.0]])
    assert np.max(np.abs(f.K - [[1.0, SQRT3]])) < 1e-14


def test_lqr_against_python_control():
    ct = pytest.importorskip("control")
    Q, R = np.diag([1.0, 2.0, 3.0]), np.array([[1.0, 0.2], [0.2, 0.5]])
    S = np.array([[0.1, 0.0], [0.0, 0.1], [0.05, 0.0]])
    K, X, E = ct.lqr(np.array(A3), np.array(B3), Q, R, S)
    d = lk.ss(A3, B3, C3).lqr(Q, R, S)
    assert np.max(np.abs(d.K - K)) < 1e-11 * np.max(np.abs(K))
    assert np.max(np.abs(d.X - X)) < 1e-11 * np.max(np.abs(X))
    assert np.allclose(np.sort_complex(d.poles), np.sort_complex(E), rtol=1e-11)


def test_discrete_lqr_against_python_control_dlqr():
    ct = pytest.importorskip("control")
    A, B = np.array([[1.0, 0.1], [0.0, 1.0]]), np.array([[0.005], [0.1]])
    K, X, E = ct.dlqr(A, B, np.eye(2), 1.0)
    d = lk.ss(A, B, C2, 0, dt=0.1).lqr(1, 1)  # one number: that multiple of the identity
    assert d.equation == "dare"
    assert np.max(np.abs(d.K - K)) < 1e-11 * np.max(np.abs(K))
    assert np.max(np.abs(d.X - X)) < 1e-11 * np.max(np.abs(X))
    assert np.all(np.abs(d.poles) < 1)


def test_lqe_against_python_control():
    ct = pytest.importorskip("control")
    A, B, C = np.array([[0.0, 1.0], [-2.0, -3.0]]), np.array([[0.0], [1.0]]), np.array([[1.0, 0.0]])
    G = lk.ss(A, B, C, 0)
    # python-control's lqe(sys, QN, RN): the noise enters through B
    L, P, E = ct.lqe(ct.ss(A, B, C, 0), np.eye(1), np.eye(1))
    k = G.lqe(1, 1, noise="inputs")
    assert k.noise == "inputs"
    assert np.max(np.abs(k.L - L)) < 1e-11 * np.max(np.abs(L))
    assert np.max(np.abs(k.P - P)) < 1e-11 * np.max(np.abs(P))
    # lqe(A, G, C, QN, RN) with G = I: the noise on every state
    L, P, E = ct.lqe(A, np.eye(2), C, np.diag([1.0, 2.0]), np.eye(1))
    k = G.lqe(np.diag([1.0, 2.0]), 1, noise="states")
    assert np.max(np.abs(k.L - L)) < 1e-11 * np.max(np.abs(L))
    assert np.allclose(np.sort_complex(k.poles), np.sort_complex(E), rtol=1e-11)


def test_lqe_scalar_closed_form():
    # ẋ = −x + w, y = x + v, Qn = Rn = 1: P² + 2P − 1 = 0, L = P = √2 − 1
    k = lk.ss([[-1]], [[1]], [[1]]).lqe(1, 1, noise="states")
    assert abs(k.L[0, 0] - (math.sqrt(2) - 1)) < 1e-15


def test_lqg_controller_closes_the_loop_with_the_separated_poles():
    G = double_integrator()
    d = G.lqg(np.eye(2), 1, 1, 1, noise="inputs")
    assert isinstance(d.controller, lk.System) and d.controller.shape == (1, 1)
    T = G.feedback(d.controller)  # the controller maps y to −u: negative feedback
    expected = np.sort_complex(np.concatenate([d.regulator.poles, d.estimator.poles]))
    assert np.allclose(np.sort_complex(T.poles()), expected, atol=1e-9)
    assert bool(T.is_stable())
    # the controller pickles like any model
    back = pickle.loads(pickle.dumps(d.controller))
    assert np.allclose(back.ssdata()[0], d.controller.ssdata()[0], rtol=0, atol=0)


def test_place_against_closed_form_and_python_control():
    ct = pytest.importorskip("control")
    # s² + 3s + 2 → (s + 4)(s + 5) = s² + 9s + 20 needs K = [18, 6]
    A, B = [[0.0, 1.0], [-2.0, -3.0]], [[0.0], [1.0]]
    p = lk.ss(A, B, [[1.0, 0.0]]).place([-4, -5])
    assert np.max(np.abs(p.K - [[18.0, 6.0]])) < 1e-13
    assert np.max(np.abs(p.K - ct.place(A, B, [-4, -5]))) < 1e-12
    assert np.allclose(np.sort_complex(p.poles), [-5, -4], atol=1e-12)
    # double integrator, −1 ± 1j: K = [2, 2]
    q = double_integrator().place([-1 + 1j, -1 - 1j])
    assert np.max(np.abs(q.K - [[2.0, 2.0]])) < 1e-14 and q.relative_error < 1e-14


@pytest.mark.parametrize(
    "call, words",
    [
        (lambda G: G.lqr(np.eye(2), -1), "`r`"),
        (lambda G: G.lqr(np.eye(3), 1), "`q`"),
        (lambda G: G.lqr([[1, 2], [0, 1]], 1), "`q`"),
        (lambda G: G.lqr(np.eye(2), math.nan), "`r`"),
        (lambda G: G.lqe(1, 1, noise="both"), "`noise` 'both': write states (G = I) or inputs (G = B)"),
        (lambda G: G.place([-1]), "poles"),
        (lambda G: G.place([-1 + 1j, -2]), "conjugat"),
        (lambda G: lk.tf([1], [1, 1], delay=0.5).lqr(1, 1), "lqr: the plant has a dead time of 0.5 s"),
        (lambda G: lk.tf([2], [1]).lqr(1, 1), "no states"),
    ],
)
def test_bad_designs_raise_one_line(call, words):
    with pytest.raises(lk.LtiError) as e:
        call(double_integrator())
    msg = str(e.value)
    assert "\n" not in msg and words in msg, msg


def test_uncontrollable_lqr_names_the_mode():
    # ẋ₁ = x₁ (unstable, no input reaches it), ẋ₂ = u
    with pytest.raises(lk.LtiError) as e:
        lk.ss([[1.0, 0.0], [0.0, 0.0]], [[0.0], [1.0]], [[1.0, 1.0]]).lqr(1, 1)
    assert "stabilis" in str(e.value)


# ---- the matrix equations against scipy.linalg (sign conventions documented) --------------

RNG = np.random.default_rng(22)
AS = np.array([[-3.0, 1.0, 0.0], [0.5, -2.0, 0.4], [0.0, -0.3, -1.0]])  # stable


def test_lyap_sign_convention_against_scipy():
    sl = pytest.importorskip("scipy.linalg")
    Q = RNG.standard_normal((3, 3))
    Q = Q @ Q.T
    s = lk.lyap(AS, Q)  # A X + X Aᵀ + Q = 0
    assert np.max(np.abs(s.X - sl.solve_continuous_lyapunov(AS, -Q))) < 1e-13 * np.max(np.abs(s.X))
    assert np.max(np.abs(AS @ s.X + s.X @ AS.T + Q)) < 1e-13 * np.max(np.abs(Q))
    assert s.residual < 1e-15 and s.condition >= 1


def test_dlyap_against_scipy():
    sl = pytest.importorskip("scipy.linalg")
    A = AS / 4
    Q = np.eye(3)
    s = lk.dlyap(A, Q)  # A X Aᵀ − X + Q = 0
    # measured: 4e-15 relative to max|X| (condition estimate 6.6)
    assert np.max(np.abs(s.X - sl.solve_discrete_lyapunov(A, Q))) < 1e-13 * np.max(np.abs(s.X))
    assert np.max(np.abs(A @ s.X @ A.T - s.X + Q)) < 1e-14 * np.max(np.abs(s.X))


def test_sylvester_against_scipy():
    sl = pytest.importorskip("scipy.linalg")
    B = np.array([[-1.0, 2.0], [0.0, -4.0]])
    C = RNG.standard_normal((3, 2))
    s = lk.sylvester(AS, B, C)
    assert np.max(np.abs(s.X - sl.solve_sylvester(AS, B, C))) < 1e-13


def test_care_and_dare_against_scipy():
    sl = pytest.importorskip("scipy.linalg")
    A, B = np.array(A3), np.array(B3)
    Q, R = np.eye(3), np.diag([1.0, 2.0])
    c = lk.care(A, B, Q, R)
    X = sl.solve_continuous_are(A, B, Q, R)
    assert np.max(np.abs(c.X - X)) < 1e-11 * np.max(np.abs(X))
    assert np.max(np.abs(c.K - np.linalg.solve(R, B.T @ X))) < 1e-10
    d = lk.dare(A / 2, B, Q, R)
    Xd = sl.solve_discrete_are(A / 2, B, Q, R)
    assert np.max(np.abs(d.X - Xd)) < 1e-11 * np.max(np.abs(Xd))
    assert np.all(np.abs(d.poles) < 1)


def test_equation_errors():
    with pytest.raises(lk.LtiError) as e:
        lk.lyap(A2, np.eye(2))  # λ = 0 twice: singular
    assert "no unique solution" in str(e.value)
    with pytest.raises(lk.LtiError) as e:
        lk.sylvester(AS, np.eye(2), np.ones((2, 2)))
    assert "\n" not in str(e.value) and "C" in str(e.value)
    with pytest.raises(lk.LtiError):
        lk.care(A2, B2, np.eye(2), [[0.0]])
    with pytest.raises(lk.LtiError):
        lk.lyap([[1, 2], [3]], np.eye(2))
