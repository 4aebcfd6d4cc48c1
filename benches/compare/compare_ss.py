#!/usr/bin/env python3
"""State-space timings of ltikit against python-control (without Slycot), in one run.

    python3 benches/compare/compare_ss.py   # in a virtual environment with control, scipy, numpy

The model is the seed's periodic lattice (N = 128, omega0 = 1, 256 states), force on
particle 1, displacement of particle 6 — built here with numpy exactly as
`ltikit::lti::lattice` builds it (checked: the script compares G(j*0.5) with the closed form).
ltikit's side is `cargo run --release --example bench_ss_json` (medians, seconds). Printed:
each operation's medians and the ratio python/ltikit — for the lattice as built (ltikit
recognises its second-order structure) and with its states interleaved (the general path).
"""
import json
import os
import subprocess
import sys
import time

import numpy as np
import control as ct

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
N, OUT = 128, 6


def lattice():
    n = N
    a = np.zeros((2 * n, 2 * n))
    for i in range(n):
        a[i, n + i] = 1.0
        a[n + i, i] = -2.0
        a[n + i, (i + 1) % n] += 1.0
        a[n + i, (i - 1) % n] += 1.0
    b = np.zeros((2 * n, 1)); b[n, 0] = 1.0
    c = np.zeros((1, 2 * n)); c[0, OUT - 1] = 1.0
    return ct.ss(a, b, c, np.zeros((1, 1)))


MASK = (1 << 64) - 1


def random_dense():
    """benches/common/ss.rs `random_dense`: A = R/16 - I (256x256), b, c; xorshift64 from
    0x5eed0256, uniform in [-1, 1), filled row by row A, b, c (the same doubles)."""
    n, seed = 256, 0x5EED0256
    vals = []
    for _ in range(n * n + 2 * n):
        seed ^= (seed << 13) & MASK
        seed ^= seed >> 7
        seed ^= (seed << 17) & MASK
        vals.append((seed >> 11) / float(1 << 53) * 2.0 - 1.0)
    a = np.array(vals[:n * n]).reshape(n, n) / 16.0 - np.eye(n)
    b = np.array(vals[n * n:n * n + n]).reshape(n, 1)
    c = np.array(vals[n * n + n:]).reshape(1, n)
    return ct.ss(a, b, c, np.zeros((1, 1)))


def median_time(fn, repeat=5):
    fn()
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter(); fn(); ts.append(time.perf_counter() - t0)
    return sorted(ts)[len(ts) // 2]


def main():
    sys_ = lattice()
    w = np.logspace(-2, 1, 10_000)
    t = np.linspace(0, 100, 10_000)
    # The model check: the modal closed form at omega = 0.5.
    k = np.arange(N)
    exact = np.sum(np.cos(2 * np.pi * k * (OUT - 1) / N) / (-0.25 + (2 * np.sin(np.pi * k / N)) ** 2)) / N
    got = sys_(0.5j)
    assert abs(np.squeeze(got) - exact) < 1e-9 * abs(exact), (got, exact)
    py = {
        "eigenvalues": median_time(lambda: np.linalg.eigvals(sys_.A)),
        "freq_hessenberg_10k": median_time(lambda: ct.frequency_response(sys_, w), 3),
        "freq_response_mimo_10k": None,  # the same python timing, reported against the public entry (factored form + Bode kernel)
        "step_10k": median_time(lambda: ct.step_response(sys_, T=t), 3),
    }
    def poles_zeros():
        sys_.poles(); sys_.zeros()
    try:
        py["channel_factored"] = median_time(poles_zeros, 3)
        py["channel_factored_note"] = "poles() + zeros() (python-control has no minreal without Slycot)"
    except Exception as e:  # noqa: BLE001
        py["channel_factored"] = None
        py["channel_factored_note"] = f"not available without Slycot: {e}"
    out = subprocess.run(["cargo", "run", "--quiet", "--release", "--example", "bench_ss_json"],
                         cwd=ROOT, check=True, capture_output=True, text=True).stdout
    lt = json.loads(out)
    # the same binary with ltikit's threads capped at one (LTIKIT_NUM_THREADS): a channel's
    # factorisation runs its zeros' eigenproblem beside its poles' on a second core
    one = subprocess.run(["cargo", "run", "--quiet", "--release", "--example", "bench_ss_json"],
                         cwd=ROOT, check=True, capture_output=True, text=True,
                         env={**os.environ, "LTIKIT_NUM_THREADS": "1"}).stdout
    lt1 = json.loads(one)
    print(f"python-control {ct.__version__}, numpy {np.__version__}")
    print(f"{'operation':28} {'python (s)':>12} {'ltikit (s)':>12} {'ratio':>8}")
    py["freq_response_mimo_10k"] = py["freq_hessenberg_10k"]
    for key in ["eigenvalues", "channel_factored", "freq_hessenberg_10k", "freq_response_mimo_10k", "step_10k"]:
        p, l = py.get(key), lt[key]
        ratio = f"{p / l:8.1f}" if p else "     n/a"
        print(f"{key:28} {p if p else float('nan'):12.4g} {l:12.4g} {ratio}")
    # ltikit's general (Schur) path: the same model with interleaved states, against the same
    # python timings (python-control has no second-order path; state order does not matter
    # to it)
    print("general path (states interleaved, no second-order structure):")
    for key in ["eigenvalues", "channel_factored", "freq_response_mimo_10k", "step_10k"]:
        p, l = py.get(key), lt["general_" + key]
        ratio = f"{p / l:8.1f}" if p else "     n/a"
        print(f"  {key:26} {p if p else float('nan'):12.4g} {l:12.4g} {ratio}")
    print(f"{'freq_modal_sum_10k (ltikit)':28} {'':12} {lt['freq_modal_sum_10k']:12.4g}"
          f"   Hessenberg/modal = {lt['freq_hessenberg_10k'] / lt['freq_modal_sum_10k']:.1f}")
    print(f"{'freq_modal_eval_10k (ltikit)':28} {'':12} {lt['freq_modal_eval_10k']:12.4g}"
          f"   modal eval/modal sum = {lt['freq_modal_eval_10k'] / lt['freq_modal_sum_10k']:.2f}")
    print("channel_factored (python):", py["channel_factored_note"])
    # a random dense stable model without structure: python-control against ltikit's general path
    rnd = random_dense()
    y_end = ct.step_response(rnd, T=t).outputs[-1]
    assert abs(y_end - lt["random_step_y_end"]) <= 1e-9 * max(1.0, abs(y_end)), (y_end, lt["random_step_y_end"])
    def rnd_poles_zeros():
        rnd.poles(); rnd.zeros()
    pr = {
        "eigenvalues": median_time(lambda: np.linalg.eigvals(rnd.A)),
        "channel_factored": median_time(rnd_poles_zeros, 3),
        "step_10k": median_time(lambda: ct.step_response(rnd, T=t), 3),
    }
    print("random dense stable, 256 states (no structure):")
    for key in ["eigenvalues", "channel_factored", "step_10k"]:
        p, l = pr[key], lt["random_" + key]
        print(f"  {key:26} {p:12.4g} {l:12.4g} {p / l:8.1f}")
    p, l = pr["channel_factored"], lt1["random_channel_factored"]
    print(f"  {'channel_factored, 1 thread':26} {p:12.4g} {l:12.4g} {p / l:8.1f}")
    for key in ["real_schur_with_q", "schur_eigenvalues", "modal_form", "minimal_realization", "transmission_zeros"]:
        print(f"  {key + ' (ltikit)':26} {'':12} {lt['random_' + key]:12.4g}")
    print(f"max relative difference Hessenberg vs modal sum: {lt['freq_max_rel_diff_vs_modal']:.2e}")


if __name__ == "__main__":
    main()
