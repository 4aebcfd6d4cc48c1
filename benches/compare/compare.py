#!/usr/bin/env python3
"""Side-by-side timing of ltikit against python-control and scipy, in one run on one machine.

Run by hand in a throwaway virtual environment (never a dependency of the crate):

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install control scipy numpy
    /tmp/venv/bin/python benches/compare/compare.py

It builds and runs `cargo run --release --example bench_json` (ltikit's timings of the same
operations on the same inputs, as JSON), times python-control / scipy / numpy in-process, and
prints a table of medians with the ratio python/ltikit. The batch case runs the real CLI,
`ltikit analyze --batch`, on 10 000 random stable plants written to a temporary JSONL file,
against a python-control loop doing poles + step_info + stability_margins per plant.
"""
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy
import scipy.signal as sig
import control as ct

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def median_time(fn, repeat=7, min_time=0.2):
    """Median seconds per call over `repeat` batches, each at least `min_time` long."""
    fn()  # warm up
    n = 1
    while True:
        t0 = time.perf_counter()
        for _ in range(n):
            fn()
        dt = time.perf_counter() - t0
        if dt >= min_time / 5 or n > 1_000_000:
            break
        n *= 4
    samples = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(n):
            fn()
        samples.append((time.perf_counter() - t0) / n)
    return float(np.median(samples))


# The shared test plants (ltikit's examples/bench_json.rs builds the same ones).
def order8():
    den = np.array([1.0])
    for w, z in [(1.0, 0.1), (2.0, 0.3), (5.0, 0.5), (10.0, 0.7)]:
        den = np.polymul(den, [1.0, 2 * z * w, w * w])
    num = 100.0 * np.polymul([1.0, 3.0], [1.0, 0.5])
    return num, den


def random_poly(deg, seed):
    rng = np.random.default_rng(seed)
    return rng.uniform(-1, 1, deg + 1)


def random_stable_plants(count, seed=1):
    rng = np.random.default_rng(seed)
    plants = []
    for i in range(count):
        n = int(rng.integers(2, 11))
        poles = []
        while len(poles) < n:
            if n - len(poles) >= 2 and rng.random() < 0.5:
                wn, zeta = rng.uniform(0.2, 10), rng.uniform(0.05, 0.95)
                re, im = -zeta * wn, wn * np.sqrt(1 - zeta**2)
                poles += [complex(re, im), complex(re, -im)]
            else:
                poles.append(complex(-rng.uniform(0.1, 10), 0))
        den = np.real(np.poly(poles))
        m = int(rng.integers(0, n))
        zeros = [-rng.uniform(0.1, 10) for _ in range(m)]
        zp = np.atleast_1d(np.real(np.poly(zeros)))
        num = zp * rng.uniform(0.5, 5) * den[-1] / zp[-1]  # dc gain in [0.5, 5]
        plants.append({"name": f"p{i}", "num": list(map(float, num)), "den": list(map(float, den))})
    return plants


def python_timings():
    out = {}
    for deg in (4, 10, 50):
        c = random_poly(deg, deg)
        out[f"roots_deg{deg}"] = median_time(lambda: np.roots(c))
    num, den = order8()
    g = ct.tf(num, den)
    for npts in (1000, 1_000_000):
        w = np.logspace(-2, 3, npts)
        def fr():
            resp = ct.frequency_response(g, w)
            return np.unwrap(np.angle(resp.complex))
        out[f"freq_order8_{npts}"] = median_time(fr, repeat=3 if npts > 10000 else 7)
    sys_ = sig.lti(num, den)
    for npts in (1000, 100_000):
        t = np.linspace(0, 60, npts)
        out[f"step_order8_{npts}"] = median_time(lambda: sig.step(sys_, T=t), repeat=5)
    out["residue_order8"] = median_time(lambda: sig.residue(num, den))
    out["step_info_order8"] = median_time(lambda: ct.step_info(g))
    def analyze():
        ct.poles(g); ct.zeros(g); ct.dcgain(g); ct.step_info(g); ct.stability_margins(g)
    out["analyze_order8"] = median_time(analyze)
    return out


def python_batch(plants):
    t0 = time.perf_counter()
    for p in plants:
        g = ct.tf(p["num"], p["den"])
        ct.poles(g)
        ct.step_info(g)
        ct.stability_margins(g)
    return time.perf_counter() - t0


def ltikit_timings():
    cmd = ["cargo", "run", "--quiet", "--release", "--example", "bench_json"]
    res = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True)
    return json.loads(res.stdout)


def ltikit_batch(path):
    subprocess.run(["cargo", "build", "--quiet", "--release"], cwd=ROOT, check=True)
    exe = os.path.join(ROOT, "target", "release", "ltikit")
    t0 = time.perf_counter()
    subprocess.run([exe, "analyze", "--batch", path], check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main():
    print(f"machine: {platform.machine()} {platform.processor() or ''}, {os.cpu_count()} cpus, "
          f"Python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}, "
          f"python-control {ct.__version__}")
    lt = ltikit_timings()
    py = python_timings()
    rows = [
        ("roots, degree 4", "roots_deg4", "numpy.roots"),
        ("roots, degree 10", "roots_deg10", "numpy.roots"),
        ("roots, degree 50", "roots_deg50", "numpy.roots"),
        ("freq. response + continuous phase, order 8, 1e3 w", "freq_order8_1000", "ct.frequency_response + np.unwrap"),
        ("freq. response + continuous phase, order 8, 1e6 w", "freq_order8_1000000", "ct.frequency_response + np.unwrap"),
        ("exact step response, order 8, 1e3 samples", "step_order8_1000", "scipy.signal.step"),
        ("exact step response, order 8, 1e5 samples", "step_order8_100000", "scipy.signal.step"),
        ("partial fractions, order 8", "residue_order8", "scipy.signal.residue"),
        ("step_info, order 8", "step_info_order8", "ct.step_info"),
        ("full analyze, order 8", "analyze_order8", "poles+zeros+dcgain+step_info+margins"),
    ]
    print(f"\n{'operation':52} {'ltikit':>11} {'python':>11} {'ratio':>8}  reference")
    for label, key, ref in rows:
        a, b = lt.get(key), py.get(key)
        if a is None or b is None:
            continue
        print(f"{label:52} {a*1e6:9.1f}us {b*1e6:9.1f}us {b/a:7.1f}x  {ref}")
    if "horner_order8_1000000" in lt:
        a, h = lt["freq_order8_1000000"], lt["horner_order8_1000000"]
        print(f"\nltikit frequency response vs a bare Horner loop (1e6 w): {a/h:.2f}x the loop's time")
    if "bode_png" in lt:
        print(f"one Bode PNG: {lt['bode_png']*1e3:.1f} ms")
    plants = random_stable_plants(10_000)
    with tempfile.NamedTemporaryFile("w", suffix=".jsonl", delete=False) as f:
        for p in plants:
            f.write(json.dumps(p) + "\n")
        path = f.name
    try:
        tb_lt = ltikit_batch(path)
        tb_py = python_batch(plants)
    finally:
        os.unlink(path)
    print(f"\nbatch: 10 000 random stable plants of order 2-10")
    print(f"  ltikit analyze --batch (all cores, incl. process start and JSON output): {tb_lt:.2f} s")
    print(f"  python-control loop (poles + step_info + stability_margins):            {tb_py:.2f} s")
    print(f"  ratio: {tb_py/tb_lt:.1f}x")


if __name__ == "__main__":
    sys.exit(main())
