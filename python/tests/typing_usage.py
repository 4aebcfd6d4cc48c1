"""Checked by mypy in CI (not a test module): the public API's types as a user sees them."""

from typing import List, Optional, Tuple

import numpy as np

import ltikit as lk


def usage() -> None:
    g: lk.System = lk.tf([4], [1, 0.8, 4])
    h: lk.System = lk.zpk([], [-1, -2], 2.0) * g + 1.0
    t: lk.System = h.feedback(lk.pid(kp=1.0, ki=0.5), sign=-1)
    p: np.ndarray = t.poles()
    m: List[Tuple[complex, int]] = g.pole_multiplicities()
    a: lk.Analysis = g.analyze()
    order: int = a.order
    s: lk.Stability = g.is_stable()
    ok: bool = bool(s)
    r: lk.TimeResponse = g.step(np.linspace(0, 10, 11))
    tt, yy = r
    fr: lk.FrequencyResponse = g.freq()
    mg: lk.Margins = g.margins()
    gm: Optional[float] = mg.gain_margin
    results: List[lk.Analysis] = lk.batch([g, h])
    dt: Optional[float] = lk.tf([1], [1, -0.5], dt=0.1).dt
    shape: Tuple[int, int] = lk.ss([[-1]], [[1]], [[1]]).shape
    ch: lk.System = lk.model("spring-mass-damper", M=1.0)[0, 0]
    g.bode_png("/tmp/x.png", size=(400, 300))
    try:
        lk.tf([1], [])
    except lk.LtiError as e:
        msg: str = str(e)
    di: lk.System = lk.ss([[0, 1], [0, 0]], [[0], [1]], [[1, 0]])
    reg: lk.Regulator = di.lqr(np.eye(2), 1)
    k: np.ndarray = reg.K
    est: lk.Estimator = di.lqe(1, 1, noise="inputs")
    lqg: lk.Lqg = di.lqg(np.eye(2), 1, 1, 1, noise="inputs")
    loop: lk.System = di.feedback(lqg.controller)
    pl: lk.Placement = di.place([-1 + 1j, -1 - 1j])
    mimo: lk.System = lk.ss(np.diag([-1.0, -2.0]), np.eye(2), np.eye(2))
    wa: lk.Analysis = mimo.analyze()
    sa: lk.StateSpaceAnalysis = lk.StateSpaceAnalysis(mimo._m.whole_analysis())
    zs: lk.ZeroStructure = mimo.zero_structure()
    dcm = mimo.dc_gain()
    ir: lk.TimeResponse = di.initial([1.0, 0.0], np.linspace(0, 1, 5))
    fo: lk.TimeResponse = mimo.response(np.ones((3, 2)), [0.0, 0.5, 1.0], x0=[1.0, 0.0])
    rt: lk.RouthTable = g.routh(gain=2.0)
    jt: lk.JuryTable = lk.tf([1], [1, -0.5], dt=0.1).jury(gains=False)
    zd: lk.System = lk.zpk([], [-1.0], 1.0, delay=0.5)
    sd: lk.System = lk.ss([[-1.0]], [[1.0]], [[1.0]], delay=0.5)
    cl: lk.System = lk.connect({"P": (g, "e", "y")}, inputs="r", outputs="y", sums={"e": "r - y"})
    names: List[str] = cl.signals["states"]
    dg: lk.System = lk.diagram({"inputs": ["r"], "outputs": ["y"],
                                "blocks": {"P": {"system": g, "input": "r", "output": "y"}}})
    hinf: lk.PeakGain = g.hinf_norm()
    h2: float = float(g.h2_norm())
    gr: lk.Gramian = g.gram("c")
    hsv: np.ndarray = g.hsv()
    red: lk.Reduction = g.balred(order=1)
    sv: np.ndarray = g.sigma([0.1, 1.0])
    x: lk.MatrixSolution = lk.lyap([[-1]], [[1]])
    ric: lk.RiccatiSolution = lk.care([[0, 1], [0, 0]], [[0], [1]], np.eye(2), 1)
    k2: lk.Regulator = lk.lqr([[0, 1], [0, 0]], [[0], [1]], np.eye(2), 1)
    print(p, m, order, ok, tt, yy, fr, gm, results, dt, shape, ch, msg)
    print(k, est, loop, pl, hinf, h2, gr, hsv, red, sv, x, ric, k2, g.eval(1j))
