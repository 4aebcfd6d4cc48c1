"""Pictures: ltikit's own PNGs, and matplotlib axes when matplotlib is installed."""

import numpy as np
import pytest

import ltikit as lk

PNG = b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("kind", ["bode_png", "step_png", "pzmap_png", "nyquist_png", "rlocus_png"])
def test_pngs(tmp_path, kind):
    g = lk.tf([2], [1, 3, 2, 0]) if kind != "step_png" else lk.tf([4], [1, 0.8, 4])
    path = tmp_path / f"{kind}.png"
    getattr(g, kind)(str(path))
    assert path.read_bytes().startswith(PNG)


def test_png_options(tmp_path):
    path = tmp_path / "b.png"
    lk.tf([4], [1, 0.8, 4]).bode_png(str(path), w=np.logspace(-1, 1, 100), title="my plant", size=(400, 300))
    data = path.read_bytes()
    # width and height in the IHDR chunk
    assert int.from_bytes(data[16:20], "big") == 400 and int.from_bytes(data[20:24], "big") == 300


def test_discrete_pictures(tmp_path):
    g = lk.tf([0.5], [1, -0.5], dt=0.1)
    for kind in ("bode_png", "step_png", "pzmap_png"):
        p = tmp_path / f"{kind}.png"
        getattr(g, kind)(str(p))
        assert p.read_bytes().startswith(PNG)


def test_matplotlib_axes():
    mpl = pytest.importorskip("matplotlib")
    mpl.use("Agg")
    import matplotlib.pyplot as plt

    g = lk.tf([4], [1, 0.8, 4])
    a_mag, a_ph = g.plot_bode()
    assert len(a_mag.lines) == 1 and len(a_ph.lines) == 1
    ax = g.plot_step()
    assert len(ax.lines) >= 1
    fig, ax2 = plt.subplots()
    assert g.plot_step(ax2) is ax2
    plt.close("all")
