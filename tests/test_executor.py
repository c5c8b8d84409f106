"""The executor seam (erdesign/executor.py): serial, local process pool and a Dask LocalCluster give the same
results in the same order; bad arguments are clear errors."""

import functools
import os

import numpy as np
import pytest

from erdesign.executor import DaskExecutor, ExecutorError, PoolExecutor, SerialExecutor, chunks, executor_for


def _seeded_mean(item):
    """A task whose result depends only on its item (seed, size) - never on which worker ran it."""
    seed, n = item
    return float(np.random.default_rng(seed).standard_normal(n).mean())


def _pid_and_square(x):
    return os.getpid(), x * x


def _fails_on_three(x):
    if x == 3:
        raise ValueError("item 3 is bad")
    return x


ITEMS = [(seed, 1000 + 7 * seed) for seed in range(23)]


def test_pool_gives_serial_results_in_item_order():
    serial = SerialExecutor().map(_seeded_mean, ITEMS)
    with PoolExecutor(2) as pool:
        seen = []
        pooled = pool.map(_seeded_mean, ITEMS, progress=lambda done, total: seen.append((done, total)))
        pids = {pid for pid, _ in pool.map(_pid_and_square, range(8))}
    assert pooled == serial  # bit-identical: the item fixes the random stream
    assert seen[-1] == (len(ITEMS), len(ITEMS)) and len(seen) == len(ITEMS)
    assert os.getpid() not in pids  # the tasks ran in worker processes


def test_task_error_reaches_the_caller():
    with pytest.raises(ValueError, match="item 3 is bad"):
        SerialExecutor().map(_fails_on_three, range(5))
    with PoolExecutor(2) as pool, pytest.raises(ValueError, match="item 3 is bad"):
        pool.map(_fails_on_three, range(5))


def test_partial_of_a_module_function_is_a_task():
    with PoolExecutor(2) as pool:
        assert pool.map(functools.partial(pow, 2), [1, 2, 10]) == [2, 4, 1024]


@pytest.mark.slow
def test_dask_local_cluster_gives_serial_results(dask_client):
    serial = SerialExecutor().map(_seeded_mean, ITEMS)
    ex = executor_for(dask_client)
    assert isinstance(ex, DaskExecutor) and ex.workers == 2
    assert ex.map(_seeded_mean, ITEMS) == serial
    with pytest.raises(ValueError, match="item 3 is bad"):
        ex.map(_fails_on_three, range(5))
    ex.close()  # a client the caller gave stays open
    assert dask_client.status == "running"


@pytest.mark.parametrize("jobs", [0, -2, 1.5, "two"])
def test_bad_jobs_is_named(jobs):
    with pytest.raises((ExecutorError, TypeError, ValueError), match="jobs"):
        executor_for(jobs=jobs)


def test_defaults_and_chunks():
    assert isinstance(executor_for(), SerialExecutor)
    assert isinstance(executor_for(jobs=3), PoolExecutor)
    assert chunks(10, 4) == [(0, 4), (4, 8), (8, 10)]
    assert sum(b - a for a, b in chunks(10**6 + 3, 65536)) == 10**6 + 3


@pytest.mark.parametrize(
    "address, message",
    [("nonsense", "not a Dask scheduler address"), ("tcp://127.0.0.1:9", "cannot reach the Dask scheduler")],
)
def test_bad_scheduler_address_is_a_clear_error(address, message):
    pytest.importorskip("distributed")
    with pytest.raises(ExecutorError, match=message):
        executor_for(scheduler=address)
