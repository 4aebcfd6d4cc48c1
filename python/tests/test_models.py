"""Building models: tf, zpk, ss, textbook models, plant files, controllers; repr; channels;
operators. Reference values are closed forms derived in the comments."""

import math
import pickle

import numpy as np
import pytest

import ltikit as lk


def test_tf_repr_is_the_text_reports_line():
    assert repr(lk.tf([4], [1, 0.8, 4])) == "G(s) = 4 / (s^2 + 0.8 s + 4)"


def test_lists_tuples_and_numpy_arrays_are_the_same_model():
    a = lk.tf([4], [1, 0.8, 4])
    b = lk.tf((4,), np.array([1.0, 0.8, 4.0]))
    c = lk.tf(np.float64(4), [np.int64(1), np.float64(0.8), 4])
    for g in (b, c):
        np.testing.assert_array_equal(g.poles(), a.poles())


def test_poles_complex_array_repeated_roots_repeated_with_multiplicities():
    # s^2 + 2 s + 1 = (s + 1)^2: a double pole, exactly
    g = lk.tf([1], [1, 2, 1])
    p = g.poles()
    assert p.dtype == np.complex128
    np.testing.assert_array_equal(p, [-1, -1])
    assert g.pole_multiplicities() == [(-1 + 0j, 2)]


def test_underdamped_poles_closed_form():
    # s^2 + 0.8 s + 4: -0.4 ± j sqrt(4 - 0.16)
    p = lk.tf([4], [1, 0.8, 4]).poles()
    np.testing.assert_allclose(p, [-0.4 + 1j * math.sqrt(3.84), -0.4 - 1j * math.sqrt(3.84)], rtol=1e-15)


def test_zpk_keeps_the_multiplicities_as_given():
    # (s + 1)^20 exactly: a 20-fold pole coefficients could not carry
    g = lk.zpk([], [-1] * 20, 1.0)
    assert g.pole_multiplicities() == [(-1 + 0j, 20)]
    assert g.dc_gain() == 1.0
    assert repr(g) == "G(s) = 1 / (s + 1)^20"


def test_zpk_repr_factored_form():
    # 3 (s + 1)^2 / (s (s^2 + 2 s + 5)): the library's factored text
    g = lk.zpk([-1, -1], [-1 + 2j, -1 - 2j, 0], 3.0)
    assert repr(g) == "G(s) = 3 (s + 1)^2 / (s (s^2 + 2 s + 5))"


def test_ss_siso_dc_gain():
    # x'' + 0.8 x' + 4 x = 4 u: dc gain -C A^-1 B + D = 1
    g = lk.ss([[0, 1], [-4, -0.8]], [[0], [4]], [[1, 0]], 0)
    assert abs(g.dc_gain() - 1.0) < 1e-14
    assert g.shape == (1, 1)


def test_mimo_channels_by_indexing():
    # two decoupled first-order states: y1 = u1/(s+1), y2 = 2 u2/(s+3)
    g = lk.ss([[-1, 0], [0, -3]], [[1, 0], [0, 2]], [[1, 0], [0, 1]])
    assert g.shape == (2, 2)
    # a channel's poles are A's eigenvalues; the mode u1 does not reach is cancelled
    np.testing.assert_array_equal(g[0, 0].poles(), [-1, -3])
    np.testing.assert_array_equal(g[0, 0].analyze().cancelled, [-3])
    np.testing.assert_array_equal(g[1, 1].analyze().cancelled, [-1])
    assert abs(g[1, 1].dc_gain() - 2.0 / 3.0) < 1e-14
    assert g[0, 1].dc_gain() == 0.0  # no path from u2 to y1
    # the whole model's poles are A's eigenvalues; SISO-only analyses still ask for a channel
    np.testing.assert_array_equal(g.poles(), [-1, -3])
    with pytest.raises(lk.LtiError, match="choose a channel"):
        g.margins()
    with pytest.raises(lk.LtiError, match="does not exist"):
        g[2, 0]


def test_textbook_model_with_parameters():
    # M y'' + C y' + K y = f: 1/(s^2 + 0.4 s + 4), dc gain 1/K
    g = lk.model("spring-mass-damper", M=1, C=0.4, K=4)
    assert abs(g.dc_gain() - 0.25) < 1e-15
    np.testing.assert_allclose(np.sort_complex(g.poles()),
                               np.sort_complex(np.roots([1, 0.4, 4])), rtol=1e-14)
    assert "spring-mass-damper" in lk.models()
    assert "lattice" in lk.models()


def test_every_textbook_model_builds_with_its_defaults():
    for name in lk.models():
        g = lk.model(name)
        assert g.name.startswith(name)


def test_plant_file(plants_dir):
    g = lk.plant(plants_dir / "spring-mass-damper.toml")
    # M = 1, C = 0.4, K = 4: wn = 2, zeta = 0.1
    a = g.analyze()
    assert a.second_order.wn == pytest.approx(2.0, rel=1e-15)
    assert a.second_order.zeta == pytest.approx(0.1, rel=1e-14)


def test_discrete_tf():
    g = lk.tf([0.5], [1, -0.5], dt=0.1)
    assert g.dt == 0.1
    assert repr(g) == "G(z) = 0.5 / (z - 0.5), dt = 0.1"
    # G(1) = 0.5 / 0.5
    assert g.dc_gain() == 1.0


def test_operators_series_parallel_feedback():
    g = lk.tf([1], [1, 1])
    h = lk.tf([2], [1, 3])
    # series: 2/((s+1)(s+3)); parallel: (s+3 + 2s+2)/((s+1)(s+3)) = (3s+5)/(...)
    s = g * h
    np.testing.assert_allclose(np.sort(s.poles().real), [-3, -1])
    assert s.dc_gain() == pytest.approx(2 / 3, rel=1e-15)
    p = g + h
    np.testing.assert_allclose(p.zeros(), [-5 / 3], rtol=1e-15)
    # unity negative feedback of 2/((s+1)(s+3)): s^2 + 4 s + 5 -> -2 ± j
    t = s.feedback(1)
    np.testing.assert_allclose(np.sort_complex(t.poles()), [-2 - 1j, -2 + 1j], atol=1e-15)
    assert (2 * g).dc_gain() == 2.0
    assert (g - g).dc_gain() == 0.0


def test_pid_on_the_spring_mass_damper():
    # C = 1 + 1/s + 0.5 s/(0.01 s + 1) (MATLAB's Tf form); closed loop dc gain 1 (integral action)
    c = lk.pid(kp=1, ki=1, kd=0.5, tf=0.01)
    g = lk.model("spring-mass-damper", M=1, C=0.4, K=4)
    t = (c * g).feedback()
    assert t.dc_gain() == pytest.approx(1.0, abs=1e-12)
    assert bool(t.is_stable())


def test_pickle_round_trip():
    g = lk.tf([4], [1, 0.8, 4])
    h = (g * lk.zpk([], [-2], 2.0)).feedback(0.5)
    for m in (g, h, lk.model("rc"), lk.ss([[-1]], [[1]], [[1]]), g.c2d(0.1), g.c2d(0.1).d2c()):
        r = pickle.loads(pickle.dumps(m))
        np.testing.assert_array_equal(r.poles(), m.poles())
        assert repr(r) == repr(m)


def test_tfdata_and_ssdata():
    g = lk.tf([4], [1, 0.8, 4])
    num, den = g.tfdata()
    np.testing.assert_array_equal(num, [4])
    np.testing.assert_array_equal(den, [1, 0.8, 4])
    a, b, c, d = g.ssdata()
    assert a.shape == (2, 2) and b.shape == (2, 1) and c.shape == (1, 2) and d.shape == (1, 1)


def test_every_public_name_has_a_docstring():
    import inspect

    missing = []
    for name in lk.__all__:
        obj = getattr(lk, name)
        if name == "__version__":
            continue
        if not (obj.__doc__ or "").strip():
            missing.append(name)
        if inspect.isclass(obj):
            for attr, member in vars(obj).items():
                if attr.startswith("_") or not (inspect.isfunction(member) or isinstance(member, property)):
                    continue
                if not (member.__doc__ or "").strip():
                    missing.append(f"{name}.{attr}")
    for attr in dir(lk._core.Model):
        if not attr.startswith("_") and not (getattr(lk._core.Model, attr).__doc__ or "").strip():
            missing.append(f"_core.Model.{attr}")
    for attr in dir(lk._core):
        member = getattr(lk._core, attr)
        if not attr.startswith("_") and callable(member) and not (member.__doc__ or "").strip():
            missing.append(f"_core.{attr}")
    assert missing == []
