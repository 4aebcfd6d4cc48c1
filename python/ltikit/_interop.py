"""python-control and scipy.signal models to and from :class:`ltikit.System`."""

from __future__ import annotations

from typing import Any

import numpy as np

from . import LtiError, System, ss, tf, zpk


def _period(dt: Any) -> Any:
    """python-control's and scipy's dt: None/0 continuous, True unspecified, else seconds."""
    if dt is None or dt is False or (not isinstance(dt, bool) and dt == 0):
        return None
    if dt is True:
        raise LtiError("`dt`: the model's sampling period is unspecified (dt=True): give one")
    return float(dt)


def from_control(sys: Any) -> System:
    """A python-control TransferFunction or StateSpace (MIMO transfer functions through
    their state-space realisation)."""
    try:
        import control
    except ImportError:  # pragma: no cover - depends on the environment
        raise LtiError("python-control is not installed: pip install control") from None
    dt = _period(getattr(sys, "dt", None))
    if isinstance(sys, control.StateSpace):
        return ss(sys.A, sys.B, sys.C, sys.D, dt=dt)
    if isinstance(sys, control.TransferFunction):
        if sys.ninputs == 1 and sys.noutputs == 1:
            num, den = sys.num[0][0], sys.den[0][0]
            return tf(np.atleast_1d(num), np.atleast_1d(den), dt=dt)
        return from_control(control.ss(sys))
    raise LtiError(f"not a python-control model: {type(sys).__name__}")


def to_control(sys: System) -> Any:
    """The model as python-control sees it: a TransferFunction (given by coefficients or
    factors) or a StateSpace (given by matrices)."""
    try:
        import control
    except ImportError:  # pragma: no cover - depends on the environment
        raise LtiError("python-control is not installed: pip install control") from None
    dt = 0 if sys.dt is None else sys.dt
    if sys._m.is_state_space():
        a, b, c, d = sys.ssdata()
        return control.ss(a, b, c, d, dt)
    num, den = sys.tfdata()
    return control.tf(num, den, dt)


def from_scipy(sys: Any) -> System:
    """A scipy.signal lti/dlti: TransferFunction, ZerosPolesGain or StateSpace."""
    try:
        from scipy import signal
    except ImportError:  # pragma: no cover - depends on the environment
        raise LtiError("scipy is not installed: pip install scipy") from None
    dt = _period(getattr(sys, "dt", None))
    if isinstance(sys, signal.StateSpace):
        return ss(sys.A, sys.B, sys.C, sys.D, dt=dt)
    if isinstance(sys, signal.ZerosPolesGain):
        return zpk(sys.zeros, sys.poles, sys.gain, dt=dt)
    if isinstance(sys, signal.TransferFunction):
        return tf(sys.num, sys.den, dt=dt)
    raise LtiError(f"not a scipy.signal LTI model: {type(sys).__name__}")
