"""ltikit over a cluster: a million random order-4 plants analysed with dask.distributed.

Each partition is a range of plant indices; a worker builds its plants from the seed (so
nothing but integers travels to it), analyses them with ``lk.batch`` (all the worker's cores,
GIL released) and sends back a few numbers per plant (stability, dc gain, overshoot, gain
margin). The result is the same whatever the number of workers or partitions.

    python examples/python/dask_batch.py                 # a LocalCluster on this machine
    python examples/python/dask_batch.py --plants 10000 --scheduler tcp://HOST:8786

On a real cluster: start ``dask scheduler`` on one machine and ``dask worker
tcp://HOST:8786`` on each worker (every worker needs ``pip install ./python``), then pass
``--scheduler tcp://HOST:8786``.
"""

from __future__ import annotations

import argparse
import time
from typing import Any, Dict, List, Optional

import numpy as np

import ltikit as lk


def plants_of(n: int, seed: int, start: int, stop: int) -> List[lk.System]:
    """Plants ``start`` … ``stop - 1`` of ``n``: k/((s + p1)…(s + p4)), p uniform in
    [0.1, 10], k in [0.5, 2]; plant i depends only on (seed, i)."""
    out = []
    for i in range(start, stop):
        rng = np.random.default_rng([seed, i])
        poles = -rng.uniform(0.1, 10.0, 4)
        out.append(lk.tf([rng.uniform(0.5, 2.0)], np.poly(poles)))
    return out


def analyse_partition(plants: List[lk.System]) -> List[lk.Analysis]:
    """The batch analysis of one partition (on all of the worker's cores)."""
    return lk.batch(plants)


def summarise(results: List[lk.Analysis]) -> Dict[str, np.ndarray]:
    """A few numbers per plant: stable, dc gain, overshoot (%), gain margin (NaN: none)."""
    nan = float("nan")

    def get(x: Any) -> float:
        return nan if x is None else float(x)

    return {
        "stable": np.array([a.internally_stable for a in results], dtype=bool),
        "dc_gain": np.array([get(a.dc_gain) for a in results]),
        "overshoot": np.array(
            [get(a.step_info.overshoot_percent) if a.step_info else nan for a in results]
        ),
        "gain_margin": np.array([get(a.margins.gain_margin) if a.margins else nan for a in results]),
    }


def _partition(n: int, seed: int, start: int, stop: int) -> Dict[str, np.ndarray]:
    return summarise(analyse_partition(plants_of(n, seed, start, stop)))


def run(
    client: Any, n: int, partitions: int, seed: int, timeout: Optional[float] = None
) -> Dict[str, np.ndarray]:
    """Analyses ``n`` plants in ``partitions`` ranges on the client's workers; the per-plant
    numbers concatenated in plant order (``timeout`` seconds at most, then an error)."""
    from dask.distributed import wait

    edges = np.linspace(0, n, partitions + 1).astype(int)
    futures = [
        client.submit(_partition, n, seed, int(a), int(b), pure=False)
        for a, b in zip(edges[:-1], edges[1:])
    ]
    wait(futures, timeout=timeout)
    parts = client.gather(futures)
    return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plants", type=int, default=1_000_000)
    ap.add_argument("--partitions", type=int, default=100)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--scheduler", help="tcp://HOST:8786 of a running dask scheduler")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster workers")
    a = ap.parse_args()
    from dask.distributed import Client, LocalCluster

    if a.scheduler:
        client = Client(a.scheduler)
    else:
        client = Client(LocalCluster(n_workers=a.workers, threads_per_worker=1))
    t0 = time.perf_counter()
    r = run(client, a.plants, a.partitions, a.seed)
    dt = time.perf_counter() - t0
    print(f"{a.plants} plants in {dt:.1f} s ({a.plants / dt:.0f} plants/s)")
    print(f"stable: {r['stable'].mean():.3f}; median overshoot {np.nanmedian(r['overshoot']):.3g} %")
    client.close()


if __name__ == "__main__":
    main()
