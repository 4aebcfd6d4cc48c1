"""Bad inputs: one LtiError (a ValueError) with one line naming the problem; never a panic
across the boundary, never a crashed interpreter."""

import math

import numpy as np
import pytest

import ltikit as lk


def one_line(e: pytest.ExceptionInfo) -> str:
    msg = str(e.value)
    assert "\n" not in msg and msg
    return msg


def test_lti_error_is_a_value_error():
    assert issubclass(lk.LtiError, ValueError)


@pytest.mark.parametrize(
    "num, den, words",
    [
        ([1], [[1, 2], [3]], "`den` must be a list of numbers"),  # ragged
        ([1], ["a", 2], "`den` must be a list of numbers"),  # not numeric
        ([1], "1 2", "`den` must be a list of numbers (found a string)"),
        ([1], [[1, 2], [3, 4]], "`den` must be a flat list"),
        ([1], [], "`den`: no numbers given"),
        ([], [1, 2], "`num`: no numbers given"),
        ([1], [1, math.nan], "coefficient 1 of the denominator is NaN"),
        ([1], [1, math.inf], "coefficient 1 of the denominator is inf"),
        ([math.nan], [1, 1], "coefficient 0 of the numerator is NaN"),
        ([1], [0, 0], "denominator"),
        ([1], [1j, 1], "`den` must be a list of numbers"),
    ],
)
def test_bad_coefficients(num, den, words):
    with pytest.raises(lk.LtiError) as e:
        lk.tf(num, den)
    assert words in one_line(e)


def test_too_high_an_order_names_the_limit():
    with pytest.raises(lk.LtiError) as e:
        lk.tf([1], np.ones(300))
    assert "200" in one_line(e)


def test_unknown_model_and_parameter():
    with pytest.raises(lk.LtiError) as e:
        lk.model("no-such-model")
    assert "no-such-model" in one_line(e)
    with pytest.raises(lk.LtiError) as e:
        lk.model("spring-mass-damper", Q=1)
    assert "Q" in one_line(e)
    with pytest.raises(lk.LtiError) as e:
        lk.model("spring-mass-damper", M="heavy")
    assert "`M` must be a number" in one_line(e)
    with pytest.raises(lk.LtiError):
        lk.model("spring-mass-damper", M=-1)


def test_bad_matrices():
    with pytest.raises(lk.LtiError) as e:
        lk.ss([[0, 1], [-4]], [[0], [1]], [[1, 0]])
    assert "`a`" in one_line(e)
    with pytest.raises(lk.LtiError) as e:
        lk.ss([[0, 1], [-4, -0.8]], [[0], [1], [2]], [[1, 0]])
    one_line(e)
    with pytest.raises(lk.LtiError) as e:
        lk.ss([[0, math.nan], [-4, -0.8]], [[0], [1]], [[1, 0]])
    one_line(e)
    with pytest.raises(lk.LtiError):
        lk.ss(np.zeros((2, 2, 2)), [[0], [1]], [[1, 0]])


def test_bad_zpk():
    with pytest.raises(lk.LtiError) as e:
        lk.zpk([], [-1 + 1j], 1.0)  # no conjugate partner
    assert "conjugate" in one_line(e)
    with pytest.raises(lk.LtiError):
        lk.zpk([], [-1], math.nan)


def test_bad_dt_and_times():
    with pytest.raises(lk.LtiError):
        lk.tf([1], [1, 1], dt=-1)
    with pytest.raises(lk.LtiError):
        lk.tf([1], [1, 1], dt=True)
    g = lk.tf([1], [1, 1])
    with pytest.raises(lk.LtiError):
        g.step([0, math.nan])
    with pytest.raises(lk.LtiError):
        g.response([1, 2, 3], [0, 1])  # sizes differ
    with pytest.raises(lk.LtiError):
        g.response("sin:-1", [0, 1])
    with pytest.raises(lk.LtiError):
        g.response("wobble", [0, 1])
    with pytest.raises(lk.LtiError):
        g.freq([-1.0])


def test_missing_plant_file():
    with pytest.raises(lk.LtiError) as e:
        lk.plant("/no/such/plant.toml")
    assert "plant.toml" in one_line(e)


def test_operators_with_nonsense_and_mixed_domains():
    g = lk.tf([1], [1, 1])
    with pytest.raises(lk.LtiError):
        g * "x"  # type: ignore[operator]
    with pytest.raises(lk.LtiError):
        g * lk.tf([1], [1, -0.5], dt=0.1)


def test_bad_channel_index():
    g = lk.tf([1], [1, 1])
    with pytest.raises(lk.LtiError):
        g[0, 1]
    with pytest.raises(lk.LtiError):
        g["a", 0]  # type: ignore[index]


def test_plot_to_a_bad_path(tmp_path):
    g = lk.tf([1], [1, 1])
    with pytest.raises(lk.LtiError):
        g.bode_png(str(tmp_path / "no" / "such" / "dir" / "x.png"))
    with pytest.raises(lk.LtiError):
        g.bode_png(str(tmp_path / "x.png"), size=(5, 100000))


def test_a_rust_panic_becomes_lti_error():
    with pytest.raises(lk.LtiError) as e:
        lk._core.panic_for_test()
    assert "internal error" in one_line(e)
    # and the interpreter goes on
    assert lk.tf([1], [1, 1]).dc_gain() == 1.0


def test_batch_rejects_non_models():
    with pytest.raises(lk.LtiError):
        lk.batch([lk.tf([1], [1, 1]), 3])  # type: ignore[list-item]


def test_huge_arrays_are_refused_before_they_are_copied():
    g = lk.tf([1], [1, 1])
    with pytest.raises(lk.LtiError) as e:
        g.step(np.zeros(2_000_001))
    assert one_line(e) == "`t`: 2000001 exceeds the limit of 1 000 000 sample points (MAX_POINTS)"
    with pytest.raises(lk.LtiError) as e:
        g.freq(np.ones(10**7))
    assert "`w`" in one_line(e)
    with pytest.raises(lk.LtiError) as e:
        lk.tf([1], np.ones(10**6))
    assert "maximum order 200" in one_line(e)
    # leading zeros do not count
    assert lk.tf([1], [0.0] * 300 + [1, 1]).dc_gain() == 1.0
