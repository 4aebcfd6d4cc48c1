"""lk.batch: many plants on all cores with the GIL released, equal to one at a time; and the
dask example's partitioning on a LocalCluster of 2 workers (skipped without dask)."""

import pathlib
import sys
import threading
import time

import numpy as np
import pytest

import ltikit as lk

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python"


def random_plants(n, seed):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        poles = -rng.uniform(0.1, 10.0, 4)
        out.append(lk.tf([rng.uniform(0.5, 2.0)], np.poly(poles)))
    return out


def test_batch_equals_one_at_a_time():
    plants = random_plants(200, 1) + [lk.tf([1], [1, 0])]
    got = lk.batch(plants)
    assert len(got) == len(plants)
    for p, a in zip(plants, got):
        want = p.analyze()
        for key in want.keys():
            assert _same(a[key], want[key]), key
        m = p.margins()
        assert a.margins == m if a.margins is not None else a.margins_note


def _same(a, b):
    if isinstance(a, np.ndarray):
        return np.array_equal(a, b)
    return a == b


def test_batch_reports_errors_in_place():
    mimo = lk.ss([[-1, 0], [0, -2]], [[1, 0], [0, 1]], [[1, 0], [0, 1]])
    got = lk.batch([lk.tf([1], [1, 1]), mimo])
    assert got[0].order == 1
    assert "choose a channel" in got[1].error


def test_batch_releases_the_gil():
    # while the batch runs, a Python thread keeps counting
    plants = random_plants(3000, 2)
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(1)
            time.sleep(0.001)

    th = threading.Thread(target=count)
    th.start()
    lk.batch(plants)
    done.set()
    th.join()
    assert len(ticks) > 5


def test_dask_local_cluster_equals_single_process():
    pytest.importorskip("dask.distributed")
    from dask.distributed import Client, LocalCluster

    # the example is imported from examples/python, and the workers (spawned processes
    # inherit sys.path) import it from there too
    sys.path.insert(0, str(EXAMPLES))
    try:
        import dask_batch

        n = 10_000
        with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster, Client(cluster) as client:
            distributed = dask_batch.run(client, n, partitions=8, seed=5, timeout=600)
    finally:
        sys.path.remove(str(EXAMPLES))
    single = dask_batch.summarise(dask_batch.analyse_partition(dask_batch.plants_of(n, 5, 0, n)))
    assert len(single["stable"]) == n
    for key in single:
        np.testing.assert_array_equal(distributed[key], single[key], err_msg=key)
