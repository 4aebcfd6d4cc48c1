#!/usr/bin/env python3
"""Side-by-side timing of ltikit against python-control and scipy, in one run on one machine.

Run by hand in a throwaway virtual environment (never a dependency of the crate):

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install control scipy numpy
    /tmp/venv/bin/python benches/compare/compare.py [--runs N] [--json FILE]

It builds and runs `cargo run --release --example bench_json` (ltikit's timings of the same
operations on the same inputs, as JSON), times python-control / scipy / numpy in-process, and
prints a table of medians with the ratio python/ltikit. The batch case runs the real CLI,
`ltikit analyze --batch`, on 10 000 random stable plants written to a temporary JSONL file,
against a python-control loop doing poles + step_info + stability_margins per plant.

Both sides read their inputs from `inputs.toml` beside this file (the fixed random
polynomials for the root finders and the order-8 plant); the ltikit side reports the order-8
coefficients it built and this script checks that they are bitwise the ones numpy built.
With `--runs N` everything (ltikit and python) is repeated N times and the table shows, per
row, the median of the per-run times and the median of the per-run ratios.
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
import tomllib

import numpy as np
import scipy
import scipy.signal as sig
import control as ct

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "inputs.toml"), "rb") as _f:
    INPUTS = tomllib.load(_f)


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
    """den = prod(s^2 + 2 zeta wn s + wn^2) over (wn, zeta) = (1, 0.1), (2, 0.3), (5, 0.5),
    (10, 0.7); num = 100 (s + 3)(s + 0.5)."""
    o = INPUTS["order8"]
    den = np.array([1.0])
    for w, z in o["den_pairs"]:
        den = np.polymul(den, [1.0, 2 * z * w, w * w])
    num = np.array([1.0])
    for z in o["num_zeros"]:
        num = np.polymul(num, [1.0, -z])
    return o["num_gain"] * num, den


def random_poly(deg):
    """The fixed polynomial of degree `deg` (numpy.random.default_rng(deg).uniform(-1, 1,
    deg + 1), written out in inputs.toml)."""
    return np.array(INPUTS["roots"][f"deg{deg}"])


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
        c = random_poly(deg)
        out[f"roots_deg{deg}"] = median_time(lambda: np.roots(c))
    num, den = order8()
    g = ct.tf(num, den)
    for npts in (1000, 1_000_000):
        w = np.logspace(-2, 3, npts)
        def fr():
            resp = ct.frequency_response(g, w)
            return np.unwrap(np.angle(resp.complex))
        out[f"freq_order8_{npts}"] = median_time(fr, repeat=5 if npts > 10000 else 7)
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
    """Seconds for the loop, and how many plants python-control's step_info failed on (its
    simulated horizon can end before the 90 % level is reached: IndexError); those plants
    still count with the time spent on them."""
    failed = 0
    t0 = time.perf_counter()
    for p in plants:
        g = ct.tf(p["num"], p["den"])
        ct.poles(g)
        try:
            ct.step_info(g)
        except (IndexError, ValueError):
            failed += 1
        ct.stability_margins(g)
    return time.perf_counter() - t0, failed


def ltikit_timings():
    cmd = ["cargo", "run", "--quiet", "--release", "--example", "bench_json"]
    res = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True)
    return json.loads(res.stdout)


def ltikit_batch(path, repeat=3):
    """Median wall time of `ltikit analyze --batch` over `repeat` runs (process start, JSON
    parsing and output included), and the number of error records in its output."""
    subprocess.run(["cargo", "build", "--quiet", "--release"], cwd=ROOT, check=True)
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    exe = os.path.join(target, "release", "ltikit")
    usage = subprocess.run([exe, "analyze", "--help"], capture_output=True, text=True).stdout
    if "--batch" not in usage:
        return None, None  # this tree's CLI has no batch mode
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = subprocess.run([exe, "analyze", "--batch", path], check=True,
                             capture_output=True, text=True)
        times.append(time.perf_counter() - t0)
    errors = sum(1 for line in res.stdout.splitlines() if '"error"' in line)
    return float(np.median(times)), errors


ROWS = [
    ("roots, degree 4", "roots_deg4", "numpy.roots"),
    ("roots, degree 10", "roots_deg10", "numpy.roots"),
    ("roots, degree 50", "roots_deg50", "numpy.roots"),
    ("freq. response + continuous phase, order 8, 1e3 w", "freq_order8_1000", "ct.frequency_response + np.unwrap"),
    ("freq. response + continuous phase, order 8, 1e6 w", "freq_order8_1000000", "ct.frequency_response + np.unwrap"),
    ("exact step response, order 8, 1e3 samples", "step_order8_1000", "scipy.signal.step"),
    ("exact step response, order 8, 1e5 samples", "step_order8_100000", "scipy.signal.step"),
    ("partial fractions, order 8", "residue_order8", "scipy.signal.residue"),
    ("step_info, order 8", "step_info_order8", "ct.step_info"),
    ("full analyze + margins, order 8", "analyze_order8", "poles+zeros+dcgain+step_info+margins"),
]


def one_run(plants, path):
    lt = ltikit_timings()
    num, den = order8()
    if lt.get("order8_num") != list(map(float, num)) or lt.get("order8_den") != list(map(float, den)):
        sys.exit(f"order-8 plants differ: ltikit {lt.get('order8_num')} / {lt.get('order8_den')}, "
                 f"numpy {list(num)} / {list(den)}")
    py = python_timings()
    tb_lt, lt_errors = ltikit_batch(path)
    if tb_lt is None:
        return {"ltikit": lt, "python": py, "batch": None}
    tb_py, py_failed = python_batch(plants)
    return {"ltikit": lt, "python": py, "batch": {"ltikit": tb_lt, "python": tb_py,
            "ltikit_error_records": lt_errors, "python_step_info_failures": py_failed}}


def med(xs):
    return float(np.median(xs))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=1, help="repeat the whole comparison N times")
    ap.add_argument("--json", help="also write every run's raw numbers to this file")
    args = ap.parse_args()
    print(f"machine: {platform.machine()} {platform.processor() or ''}, {os.cpu_count()} cpus, "
          f"Python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}, "
          f"python-control {ct.__version__}")
    plants = random_stable_plants(10_000)
    with tempfile.NamedTemporaryFile("w", suffix=".jsonl", delete=False) as f:
        for p in plants:
            f.write(json.dumps(p) + "\n")
        path = f.name
    runs = []
    try:
        for k in range(args.runs):
            runs.append(one_run(plants, path))
            print(f"run {k + 1}/{args.runs} done", file=sys.stderr)
    finally:
        os.unlink(path)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(runs, f, indent=1)

    def lt(key):
        return med([r["ltikit"][key] for r in runs])

    print(f"\n{len(runs)} run(s); medians of per-run times and of per-run ratios python/ltikit")
    print(f"\n{'operation':52} {'ltikit':>11} {'python':>11} {'ratio':>8}  reference")
    for label, key, ref in ROWS:
        if any(key not in r["ltikit"] or key not in r["python"] for r in runs):
            continue
        a, b = lt(key), med([r["python"][key] for r in runs])
        ratio = med([r["python"][key] / r["ltikit"][key] for r in runs])
        print(f"{label:52} {a*1e6:9.1f}us {b*1e6:9.1f}us {ratio:7.1f}x  {ref}")
    if "closed_form_order8" in runs[0]["ltikit"]:
        print(f"{'step closed form (partial fractions of G/s + y(t)), order 8':52} "
              f"{lt('closed_form_order8')*1e6:9.1f}us  (no python counterpart)")
    if "horner_order8_1000000" in runs[0]["ltikit"]:
        f = "freq_order8_1000000"
        rc = med([r["ltikit"][f] / r["ltikit"]["horner_order8_1000000"] for r in runs])
        print(f"\nbare f64 Horner loops over the same coefficients, 1e6 w:")
        print(f"  complex G only:                  {lt('horner_order8_1000000')*1e3:7.2f} ms"
              f"  (freq_response takes {rc:.2f}x its time)")
        if "horner_full_order8_1000000" in runs[0]["ltikit"]:
            rf = med([r["ltikit"][f] / r["ltikit"]["horner_full_order8_1000000"] for r in runs])
            print(f"  Horner + |G| + dB + atan2 phase: {lt('horner_full_order8_1000000')*1e3:7.2f} ms"
                  f"  (freq_response takes {rf:.2f}x its time)")
    if "bode_png" in runs[0]["ltikit"]:
        print(f"one Bode PNG (from the plant, 1000x700): {lt('bode_png')*1e3:.1f} ms")
    if any(r["batch"] is None for r in runs):
        print("\nbatch: skipped (this tree's ltikit has no `analyze --batch`)")
        return
    b_lt = med([r["batch"]["ltikit"] for r in runs])
    b_py = med([r["batch"]["python"] for r in runs])
    b_ratio = med([r["batch"]["python"] / r["batch"]["ltikit"] for r in runs])
    print(f"\nbatch: 10 000 random stable plants of order 2-10")
    print(f"  ltikit analyze --batch (all cores, incl. process start and JSON output): {b_lt:.3f} s"
          f"  ({runs[-1]['batch']['ltikit_error_records']} error records)")
    print(f"  python-control loop (poles + step_info + stability_margins):            {b_py:.2f} s"
          f"  (step_info failed on {runs[-1]['batch']['python_step_info_failures']} plants)")
    print(f"  ratio: {b_ratio:.1f}x")


if __name__ == "__main__":
    sys.exit(main())
