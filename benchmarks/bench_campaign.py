"""Benchmark: campaigns on the executor (issue 24) - throughput on 2 workers against serial, and what the executor
costs per task.  Not a test: timings depend on the machine and its load.

Run:  python benchmarks/bench_campaign.py [--part batch|tolerance|design|scheduler|all] [--workers 2]

Parts (each prints its own baseline, measured in the same run, and ratios to it):

* ``design`` - candidates per second of :func:`erdesign.design.design` without refinement (chunks made, evaluated
  and summarised on the workers, summaries merged in the caller) serially, on a local pool of ``--workers``
  processes and on a Dask ``LocalCluster`` of ``--workers`` single-threaded worker processes: the valve damper of
  examples/requirements/makris_requirements.toml (``--n`` candidates) and the mixed-mode MR damper of
  mr_requirements.toml (``--mixed`` candidates, a bracketed root per element).  The pools are started and warmed
  up before the timed runs; their start-up is printed apart.  The results are checked identical to serial.
* ``scheduler`` - the overhead of the executors with empty tasks: tasks per second of ``--tasks`` no-op tasks
  (``client.map(noop, range(N))`` then ``client.gather``) on the Dask LocalCluster, the same through
  :class:`erdesign.executor.DaskExecutor` (as_completed, one BLAS thread set per call), the round-trip latency of
  one task (submit, wait for the result, ``--round-trips`` times), and the same two figures for the local process
  pool.  These are the per-task costs of docs/scale.md's projection to many workers.

* ``batch`` - records per second of :func:`erdesign.campaign.batch.run_batch` (``erdesign batch``) identifying
  (Bingham), fitting and diagnosing ``--records`` / ``--diagnose-records`` one-cycle truth-rig records of Makris's
  damper, serially and on a warmed-up local pool; the tables are checked identical (``seconds`` apart).
* ``tolerance`` - Monte-Carlo samples per second of :func:`erdesign.campaign.tolerance.tolerance_study` on a valve
  and a mixed-mode damper, serially and on the pool; quantiles checked identical.

Parts plug in by name in :data:`PARTS`.
"""

from __future__ import annotations

import argparse
import functools
import json
import logging
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np


def _noop(x):
    return x


def _timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def _local_cluster(workers: int, malloc_default: bool = False):
    """A LocalCluster of single-threaded worker processes.  ``malloc_default``: without the
    ``MALLOC_TRIM_THRESHOLD_=65536`` Dask's nannies set in their workers' environment by default
    (``distributed.nanny.pre-spawn-environ``): it also freezes glibc's mmap threshold at 128 KiB, so that every
    numpy array above it is a fresh mmap and its pages faulted in again (measured: 4.5 x the CPU time of a chunk of
    16384 valve candidates)."""
    import dask
    import distributed

    environ = {} if malloc_default else dask.config.get("distributed.nanny.pre-spawn-environ")
    if malloc_default:  # a nanny of an earlier LocalCluster set it in this process's environment too
        os.environ.pop("MALLOC_TRIM_THRESHOLD_", None)
    with dask.config.set({"distributed.nanny.pre-spawn-environ": environ}):
        cluster = distributed.LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            host="127.0.0.1",
            silence_logs=40,
        )
    return cluster, distributed.Client(cluster, set_as_default=False)


# --------------------------------------------------------------------------------------------------------- design
def part_design(args) -> None:
    from erdesign.design import design, load_example_requirements
    from erdesign.executor import DaskExecutor, PoolExecutor, SerialExecutor

    cases = [
        ("valve (makris_requirements)", "makris_requirements", args.n),
        ("mixed (mr_requirements)", "mr_requirements", args.mixed),
    ]
    cases = [c for c in cases if c[2] > 0]
    reqs = {
        label: load_example_requirements(name).with_search(samples=n, chunk=args.chunk, refine=False)
        for label, name, n in cases
    }
    warm = {label: r.with_search(samples=min(r.search.samples, 4 * args.chunk)) for label, r in reqs.items()}

    (pool, t_pool) = _timed(lambda: PoolExecutor(args.workers))
    _, t_pool_start = _timed(lambda: design(next(iter(warm.values())), executor=pool))
    (cluster, client), t_dask_start = _timed(lambda: _local_cluster(args.workers))
    cluster2, client2 = _local_cluster(args.workers, malloc_default=True)
    dask, dask2 = DaskExecutor(client), DaskExecutor(client2)
    executors = (("local pool", pool), ("Dask LocalCluster", dask), ("  malloc default", dask2))
    for r in warm.values():  # imports and caches of every worker
        for _, ex in executors:
            design(r, executor=ex)
        design(r)
    print(
        f"design sweep, chunk {args.chunk:,}, no refinement, {args.workers} workers; start-up: local pool "
        f"{t_pool + t_pool_start:.2f} s (first sweep included), Dask LocalCluster {t_dask_start:.2f} s; "
        "'malloc default': a LocalCluster without Dask's MALLOC_TRIM_THRESHOLD_"
    )
    try:
        for label, r in reqs.items():
            n = r.search.samples
            reference, t_serial = _timed(functools.partial(design, r, executor=SerialExecutor()))
            rows = [("serial", t_serial, True)]
            for name, ex in executors:
                result, t = _timed(functools.partial(design, r, executor=ex))
                rows.append((name, t, json.dumps(result.as_json()) == json.dumps(reference.as_json())))
            print(f"  {label}: {n:,} candidates, {-(-n // args.chunk)} chunks, {reference.feasible_count:,} feasible")
            for name, t, same in rows:
                print(
                    f"    {name:<18} {n / t / 1e3:9.1f} k candidates/s  ({t:6.2f} s)  x{t_serial / t:4.2f} "
                    f"of serial  {'same result' if same else 'DIFFERENT RESULT'}"
                )
    finally:
        pool.close()
        for c in (client, cluster, client2, cluster2):
            c.close()


# ------------------------------------------------------------------------------------------------------ scheduler
def part_scheduler(args) -> None:
    from erdesign.executor import DaskExecutor, PoolExecutor

    n, m = args.tasks, args.round_trips
    print(
        f"executor overhead with empty tasks, {args.workers} workers: {n:,} tasks for the rates, "
        f"{m} round trips for the latency"
    )
    (cluster, client), t_start = _timed(lambda: _local_cluster(args.workers))
    try:
        client.gather(client.map(_noop, range(100), pure=False))  # warm up
        _, t_map = _timed(lambda: client.gather(client.map(_noop, range(n), pure=False)))
        dask = DaskExecutor(client)
        dask.map(_noop, range(100))
        _, t_ex = _timed(lambda: dask.map(_noop, range(n)))
        lat = []
        for i in range(m):
            t0 = time.perf_counter()
            client.submit(_noop, i, pure=False).result()
            lat.append(time.perf_counter() - t0)
        print(f"  Dask LocalCluster (started in {t_start:.2f} s):")
        print(f"    client.map + gather     {n / t_map:9.0f} tasks/s  ({1e3 * t_map / n:6.3f} ms per task)")
        print(f"    DaskExecutor.map        {n / t_ex:9.0f} tasks/s  ({1e3 * t_ex / n:6.3f} ms per task)")
        print(
            f"    round trip of one task  median {1e3 * np.median(lat):6.2f} ms, "
            f"95th percentile {1e3 * np.percentile(lat, 95):6.2f} ms"
        )
    finally:
        client.close()
        cluster.close()
    pool = PoolExecutor(args.workers)
    try:
        _, t_start = _timed(lambda: pool.map(_noop, range(100)))
        _, t_pool = _timed(lambda: pool.map(_noop, range(n)))
        raw = pool._get_pool()
        lat = []
        for i in range(m):
            t0 = time.perf_counter()
            raw.submit(_noop, i).result()
            lat.append(time.perf_counter() - t0)
    finally:
        pool.close()
    print(f"  local process pool (started in {t_start:.2f} s, first 100 tasks included):")
    print(
        f"    PoolExecutor.map        {n / t_pool:9.0f} tasks/s  ({1e3 * t_pool / n:6.3f} ms per task)  "
        f"x{t_map / t_pool:5.1f} the Dask rate"
    )
    print(
        f"    round trip of one task  median {1e3 * np.median(lat):6.2f} ms, "
        f"95th percentile {1e3 * np.percentile(lat, 95):6.2f} ms"
    )


# ---------------------------------------------------------------------------------------------------------- batch
def _truth_records(folder: Path, n: int) -> list[str]:
    """``n`` one-cycle records (100 Hz, 101 samples) of Makris's damper from the independent truth rig, each with
    its own noise seed (the records of tests/test_batch.py)."""
    from erdesign import load_example
    from erdesign.data.measurement import write_measurement
    from erdesign.simulation.rig import sine
    from erdesign.simulation.truthrig import TruthDamper, simulate_truth

    damper = load_example("makris")
    motion = sine(0.01, 1.0, damper.fluid.reference_field, cycles=1, rate=100)
    truth = TruthDamper(damper, {}, viscosity_factor=1.05, yield_stress_factor=0.95)
    paths = []
    for i in range(n):
        path = folder / f"r{i:04d}.csv"
        write_measurement(path, simulate_truth(truth, motion, seed=i, name=path.name).measured)
        paths.append(str(path))
    return paths


def part_batch(args) -> None:
    import tempfile

    from erdesign.campaign.batch import run_batch
    from erdesign.executor import PoolExecutor, SerialExecutor

    def without_seconds(result):
        return [{k: v for k, v in row.items() if k != "seconds"} for row in result.rows]

    with tempfile.TemporaryDirectory() as tmp:
        counts = {"identify": args.records, "fit": args.records, "diagnose": args.diagnose_records}
        paths = _truth_records(Path(tmp), max(counts.values()))
        options = {"identify": {"model": "bingham"}, "fit": {}, "diagnose": {}}
        pool = PoolExecutor(args.workers)
        _, t_start = _timed(lambda: run_batch("fit", paths[: 2 * args.workers], damper="makris", executor=pool))
        print(
            f"batch of truth-rig records (Makris damper, 101 samples each), {args.workers} workers; local pool "
            f"started and warmed up in {t_start:.2f} s (not in the rates)"
        )
        try:
            for command, n in counts.items():
                if n <= 0:
                    continue
                kw = dict(damper="makris", options=options[command])
                serial, t_serial = _timed(lambda: run_batch(command, paths[:n], executor=SerialExecutor(), **kw))
                pooled, t_pool = _timed(lambda: run_batch(command, paths[:n], executor=pool, **kw))
                same = without_seconds(serial) == without_seconds(pooled)
                print(
                    f"  {command:<9} {n:5d} records: serial {n / t_serial:8.2f} records/s ({t_serial:7.1f} s), "
                    f"pool {n / t_pool:8.2f} records/s ({t_pool:7.1f} s)  x{t_serial / t_pool:4.2f} of serial  "
                    f"{'same table' if same else 'DIFFERENT TABLE'}; {t_serial / n * 1e3:8.1f} ms per record"
                )
        finally:
            pool.close()


# ------------------------------------------------------------------------------------------------------ tolerance
def part_tolerance(args) -> None:
    from erdesign import load_example
    from erdesign.campaign.tolerance import tolerance_study
    from erdesign.executor import PoolExecutor, SerialExecutor

    cases = [("valve (makris)", "makris", "0.1 m/s", 2e6), ("mixed (mr_mixed)", "mr_mixed", "0.1 m/s", None)]
    vary = ["geometry.gap=+-2.5 %", "fluid.viscosity=+-10 %", "fluid.yield_stress=+-15 %"]
    pool = PoolExecutor(args.workers)
    print(f"tolerance study, {args.samples:,} Monte-Carlo samples, no Sobol indices, {args.workers} workers")
    try:
        for label, name, v, E in cases:
            damper = load_example(name)
            field = E if E is not None else float(damper.fluid.reference_field)
            kw = dict(velocity=0.1, field=field, samples=args.samples, sensitivity=False, seed=1)
            tolerance_study(damper, vary, **{**kw, "samples": 2 * 65536}, executor=pool)  # warm the workers
            serial, t_serial = _timed(lambda: tolerance_study(damper, vary, **kw, executor=SerialExecutor()))
            pooled, t_pool = _timed(lambda: tolerance_study(damper, vary, **kw, executor=pool))
            same = serial.quantiles == pooled.quantiles
            print(
                f"  {label:<18} serial {args.samples / t_serial / 1e6:6.2f} M samples/s ({t_serial:6.2f} s), "
                f"pool {args.samples / t_pool / 1e6:6.2f} M samples/s  x{t_serial / t_pool:4.2f} of serial  "
                f"{'same quantiles' if same else 'DIFFERENT QUANTILES'}"
            )
    finally:
        pool.close()


#: Part name -> function(args): ``--part NAME`` runs one, ``--part all`` every one in this order.
PARTS = {
    "batch": part_batch,
    "tolerance": part_tolerance,
    "design": part_design,
    "scheduler": part_scheduler,
}


def main() -> None:
    logging.disable(logging.WARNING)  # the INFO lines of clusters closing
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--part", choices=[*PARTS, "all"], default="all")
    parser.add_argument("--workers", type=int, default=2, help="workers of the pool and of the LocalCluster")
    parser.add_argument("--n", type=int, default=2**21, help="valve-damper candidates of the design part")
    parser.add_argument("--mixed", type=int, default=2**17, help="mixed-mode candidates of the design part (0: skip)")
    parser.add_argument("--chunk", type=int, default=2**14, help="candidates per chunk (task) of the design part")
    parser.add_argument("--records", type=int, default=1000, help="records of the batch part (identify, fit)")
    parser.add_argument("--diagnose-records", type=int, default=1000, help="records of the batch part's diagnose")
    parser.add_argument("--samples", type=int, default=10**6, help="Monte-Carlo samples of the tolerance part")
    parser.add_argument("--tasks", type=int, default=5000, help="empty tasks of the scheduler part")
    parser.add_argument("--round-trips", type=int, default=200, help="one-task round trips of the scheduler part")
    args = parser.parse_args()
    for name, part in PARTS.items():
        if args.part in (name, "all"):
            part(args)


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
