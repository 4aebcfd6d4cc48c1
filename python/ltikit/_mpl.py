"""matplotlib drawing for :class:`ltikit.System` (imported only when asked)."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np


def _pyplot() -> Any:
    try:
        import matplotlib.pyplot as plt
    except ImportError:  # pragma: no cover - depends on the environment
        from . import LtiError

        raise LtiError(
            "matplotlib is not installed: pip install matplotlib (or use bode_png/step_png)"
        ) from None
    return plt


def plot_bode(sys: Any, ax: Any = None, w: Optional[Any] = None) -> Any:
    """|G| in dB over the phase in degrees, log frequency axis; returns (ax_mag, ax_phase)."""
    fr = sys.freq(w)
    if ax is None:
        plt = _pyplot()
        _, ax = plt.subplots(2, 1, sharex=True)
    ax_mag, ax_phase = ax
    ax_mag.semilogx(fr.w, fr.magnitude_db, label=sys.name)
    ax_mag.set_ylabel("magnitude [dB]")
    ax_mag.grid(True, which="both")
    ax_phase.semilogx(fr.w, fr.phase_deg, label=sys.name)
    ax_phase.set_ylabel("phase [deg]")
    ax_phase.set_xlabel("frequency [rad/s]")
    ax_phase.grid(True, which="both")
    return ax_mag, ax_phase


def plot_step(sys: Any, ax: Any = None, t: Optional[Any] = None) -> Any:
    """The step response y(t); returns the axes."""
    r = sys.step(t)
    if ax is None:
        plt = _pyplot()
        _, ax = plt.subplots()
    ax.plot(r.t, r.y, label=sys.name)
    if r.final_value is not None and np.isfinite(r.final_value):
        ax.axhline(r.final_value, linestyle=":", color="gray")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("y")
    ax.grid(True)
    return ax
