"""Property tests (hypothesis, skipped when it is not installed)."""

import numpy as np
import pytest

import ltikit as lk

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

# integer roots with multiplicities up to 3: np.poly's coefficients are exact integers
roots = st.dictionaries(st.integers(-6, 6), st.integers(1, 3), min_size=1, max_size=4)


@settings(max_examples=60, deadline=None)
@given(roots)
def test_integer_roots_come_back_with_their_multiplicities(r):
    poles = [float(p) for p, m in r.items() for _ in range(m)]
    g = lk.tf([1], np.poly(poles))
    got = sorted((z.real, m) for z, m in g.pole_multiplicities())
    assert got == sorted((float(p), m) for p, m in r.items())
    assert all(z.imag == 0 for z, _ in g.pole_multiplicities())


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(-5, -0.1), min_size=1, max_size=5), st.floats(0.1, 10))
def test_zpk_and_its_expanded_coefficients_agree_in_frequency(poles, k):
    z = lk.zpk([], poles, k)
    num, den = z.tfdata()
    g = lk.tf(num, den)
    w = np.logspace(-1, 1, 7)
    np.testing.assert_allclose(g.freq(w).response, z.freq(w).response, rtol=1e-9, atol=1e-300)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=3)), max_size=6))
def test_any_junk_gives_lti_error_or_a_model(den):
    try:
        lk.tf([1], den).poles()
    except lk.LtiError as e:
        assert "\n" not in str(e)
