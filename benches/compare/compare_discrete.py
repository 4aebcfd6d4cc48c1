#!/usr/bin/env python3
"""Discrete-time timings of ltikit against scipy (and python-control), in one run (issue 20).

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install control scipy numpy
    /tmp/venv/bin/python benches/compare/compare_discrete.py [--runs N] [--json FILE]

Inputs (identical on both sides): the seed's 256-state lattice, built here with numpy exactly
as compare_ss.py builds it (and checked against the modal closed form); the order-8 plant of
compare.py; the periods, the sample count and the order-8 discrete plant G(z) of the
`[discrete]` table of inputs.toml. ltikit's side is `cargo run --release --example
bench_discrete_json` (medians, seconds; it also returns its coefficients and step samples,
which this script checks against scipy's). With `--runs N` both sides are repeated N times;
the table shows the median of the per-run times and of the per-run ratios python/ltikit.
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import time
import tomllib
import warnings

import numpy as np
import scipy
import scipy.signal as sig
import control as ct

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from compare import median_time, order8  # noqa: E402  (the shared timing scheme and plant)
from compare_ss import N, OUT  # noqa: E402

with open(os.path.join(HERE, "inputs.toml"), "rb") as _f:
    DISC = tomllib.load(_f)["discrete"]


def lattice_abcd():
    """compare_ss.py's lattice as plain arrays (A, B, C, D)."""
    from compare_ss import lattice
    s = lattice()
    return np.asarray(s.A), np.asarray(s.B), np.asarray(s.C), np.asarray(s.D)


def python_timings():
    a, b, c, d = lattice_abcd()
    k = np.arange(N)  # the model check of compare_ss.py: G(j 0.5) against the modal sum
    exact = np.sum(np.cos(2 * np.pi * k * (OUT - 1) / N) / (-0.25 + (2 * np.sin(np.pi * k / N)) ** 2)) / N
    got = (c @ np.linalg.solve(0.5j * np.eye(2 * N) - a, b) + d)[0, 0]
    assert abs(got - exact) < 1e-9 * abs(exact), (got, exact)
    num, den = order8()
    numz, denz, dtz, n = DISC["num_z"], DISC["den_z"], DISC["dt_z"], DISC["samples"]
    g = ct.tf(num, den)
    gz = ct.tf(numz, denz, dtz)
    tz = np.arange(n) * dtz
    out = {
        "c2d_lattice": median_time(lambda: sig.cont2discrete((a, b, c, d), DISC["dt_lattice"], method="zoh"), 5, 0.5),
        "c2d_tf_order8": median_time(lambda: sig.cont2discrete((num, den), DISC["dt_order8"], method="zoh")),
        "ct_sample_system_order8": median_time(lambda: ct.sample_system(g, DISC["dt_order8"], method="zoh")),
        "dstep_order8": median_time(lambda: sig.dstep((numz, denz, dtz), n=n), 5),
        "ct_step_discrete_order8": median_time(lambda: ct.step_response(gz, T=tz), 5),
    }
    nd, dd, _ = sig.cont2discrete((num, den), DISC["dt_order8"], method="zoh")
    _, (y,) = sig.dstep((numz, denz, dtz), n=n)
    values = {"c2d_num": np.squeeze(nd), "c2d_den": np.asarray(dd), "dstep_y": np.squeeze(y)}
    return out, values


def ltikit_run():
    cmd = ["cargo", "run", "--quiet", "--release", "--example", "bench_discrete_json"]
    res = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True)
    return json.loads(res.stdout)


def max_rel(a, b):
    """Max |a − b| / |b| over the coefficients (leading zeros of b dropped, as ltikit drops
    them), and the same with the denominator the largest |b| (for a numerator whose
    coefficients are differences of nearly equal numbers)."""
    b = np.trim_zeros(np.asarray(b, float), "f")
    a = np.asarray(a, float)
    if len(a) != len(b):
        return float("nan"), float("nan")
    d = np.abs(a - b)
    return float(np.max(d / np.abs(b))), float(np.max(d) / np.max(np.abs(b)))


ROWS = [
    ("c2d ZOH, 256-state lattice", "c2d_lattice", "c2d_lattice", "scipy cont2discrete((A,B,C,D))"),
    ("c2d ZOH, order-8 TF", "c2d_tf_order8", "c2d_tf_order8", "scipy cont2discrete((num,den))"),
    ("c2d ZOH, order-8 TF (python-control)", "c2d_tf_order8", "ct_sample_system_order8", "ct.sample_system"),
    ("c2d ZOH, order-8 factored (poles e^pT)", "c2d_factored_order8", "c2d_tf_order8", "scipy cont2discrete((num,den))"),
    ("discrete step, order 8, 1e5 samples", "dstep_order8", "dstep_order8", "scipy dstep"),
    ("discrete step, order 8, 1e5 (from the TF)", "dstep_tf_order8", "dstep_order8", "scipy dstep"),
    ("discrete step, order 8, 1e5 (python-control)", "dstep_order8", "ct_step_discrete_order8", "ct.step_response"),
    ("closed form y[k] + recursion, 1e5 samples", "closed_form_order8", "dstep_order8", "scipy dstep"),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=1)
    ap.add_argument("--json", help="also write every run's timings to this file")
    args = ap.parse_args()
    warnings.simplefilter("ignore", sig.BadCoefficients)
    print(f"machine: {platform.machine()} {platform.processor() or ''}, {os.cpu_count()} cpus, "
          f"Python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}, "
          f"python-control {ct.__version__}")
    runs = []
    for k in range(args.runs):
        lt = ltikit_run()
        if lt["plant_z_den"] != list(map(float, DISC["den_z"])) or \
                lt["plant_z_num"] != list(map(float, np.trim_zeros(np.array(DISC["num_z"]), "f"))):
            sys.exit("the discrete plants differ between ltikit and inputs.toml")
        py, values = python_timings()
        runs.append({"ltikit": {k: v for k, v in lt.items() if isinstance(v, float)}, "python": py})
        print(f"run {k + 1}/{args.runs} done", file=sys.stderr)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(runs, f, indent=1)

    def med(xs):
        return float(np.median(xs))

    def fmt(s):
        return f"{s * 1e3:9.3f}ms" if s >= 1e-3 else f"{s * 1e6:9.1f}us"

    print(f"\n{len(runs)} run(s); medians of per-run times and of per-run ratios python/ltikit")
    print(f"\n{'operation':46} {'ltikit':>11} {'python':>11} {'ratio':>8}  reference")
    for label, lk, pk, ref in ROWS:
        a = med([r["ltikit"][lk] for r in runs])
        b = med([r["python"][pk] for r in runs])
        ratios = [r["python"][pk] / r["ltikit"][lk] for r in runs]
        print(f"{label:46} {fmt(a)} {fmt(b)} {med(ratios):7.1f}x  {ref}"
              f"  (runs {', '.join(f'{x:.1f}' for x in ratios)})")
    # accuracy (last run)
    rn, an = max_rel(lt["c2d_tf_order8_num"], values["c2d_num"])
    rd, _ = max_rel(lt["c2d_tf_order8_den"], values["c2d_den"])
    y, yp = np.array(lt["dstep_y"]), values["dstep_y"]
    print("\naccuracy:")
    print(f"  c2d order-8 TF vs scipy: denominator max rel. coefficient difference {rd:.2e}; "
          f"numerator {rn:.2e} (relative to its largest coefficient {an:.2e})")
    print(f"  discrete step vs scipy dstep: max |dy| / max |y| = {np.max(np.abs(y - yp)) / np.max(np.abs(yp)):.2e}")
    print(f"  closed form vs recursion (ltikit, 1e5 samples): max |dy| / max |y| = "
          f"{lt['closed_form_error'] / lt['closed_form_max_abs_y']:.2e}")


if __name__ == "__main__":
    sys.exit(main())
