"""Where independent tasks run: in this process, on a local process pool, or on a Dask distributed cluster.

Every loop of erdesign whose turns do not depend on each other (the records of a batch, diagnosis candidates,
multi-starts, chunks of a design search, tolerance samples) goes through one :class:`Executor`:

* :class:`SerialExecutor` - one task after another, in this process (``jobs=1``);
* :class:`PoolExecutor` - a local process pool (``jobs=N``; the default of the command line is all cores);
* :class:`DaskExecutor` - the workers of a Dask ``distributed`` cluster, given by its scheduler address
  (``scheduler="tcp://host:8786"``), a ``distributed.LocalCluster`` or a ``distributed.Client``.

The contract that makes them interchangeable: :meth:`Executor.map` returns the results **in the order of the
items**, whatever finished first, and a task receives everything it needs in its item (seeds included), so the
same call gives the same numbers on any executor and any number of workers.  Tasks must be picklable: a
module-level function, or a :func:`functools.partial` of one, with picklable items.

Each worker uses one BLAS thread (:mod:`threadpoolctl`): the workers already fill the cores, and erdesign's
matrices are small and tall, where a second thread per process only contends.

>>> from erdesign.executor import executor_for
>>> with executor_for(jobs=1) as ex:
...     ex.map(abs, [-2, 3, -5])
[2, 3, 5]
"""

from __future__ import annotations

import abc
import concurrent.futures
import contextlib
import multiprocessing
import os
import sys
from collections.abc import Callable, Iterable, Sequence
from typing import Any

from erdesign.errors import ErdesignError

__all__ = [
    "Executor",
    "SerialExecutor",
    "PoolExecutor",
    "DaskExecutor",
    "ExecutorError",
    "executor_for",
    "executor_scope",
    "default_jobs",
    "dask_worker_environ",
]

#: ``progress(done, total)``: called in the calling process after each finished task.
Progress = Callable[[int, int], None]


class ExecutorError(ErdesignError):
    """The executor cannot be set up (a bad ``jobs``, an unreachable scheduler, Dask not installed)."""


def default_jobs() -> int:
    """All the cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def _one_blas_thread() -> None:
    """Once per worker process: one BLAS / OpenMP thread.  numpy and scipy's linear algebra (each wheel brings its
    own OpenBLAS) are loaded first, because :mod:`threadpoolctl` limits only the libraries already loaded."""
    global _LIMITED
    if _LIMITED:
        return
    import scipy.linalg  # noqa: F401  (loads scipy's BLAS)
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1)
    _LIMITED = True


# Set once in a worker process by _one_blas_thread (a process-wide setting, like the BLAS's own thread count).
_LIMITED = False


def _call_with_one_blas_thread(fn: Callable, item: Any) -> Any:
    """A task on a Dask worker: the worker process is not ours to configure, so the first task of each process
    limits its BLAS threads (Dask's nanny usually starts workers with one thread already)."""
    _one_blas_thread()
    return fn(item)


def _check_address(address: str) -> None:
    """A scheduler address that is not ``[tcp://]host:port``, or where nothing listens, is a clear error here -
    before a ``distributed.Client`` is made, whose failed connection would print a traceback when collected."""
    import socket
    from urllib.parse import urlsplit

    text = address if "://" in address else f"tcp://{address}"
    parts = urlsplit(text)
    try:
        port = parts.port
    except ValueError:
        port = None
    if parts.scheme not in ("tcp", "tls") or not parts.hostname or port is None:
        raise ExecutorError(
            f"scheduler: {address!r} is not a Dask scheduler address (expected tcp://host:port, "
            "e.g. tcp://10.0.0.5:8786)"
        )
    if parts.scheme == "tcp":
        try:
            socket.create_connection((parts.hostname, port), timeout=10).close()
        except OSError as exc:
            raise ExecutorError(
                f"scheduler: cannot reach the Dask scheduler at {address} "
                f"({exc.strerror or exc}); is it running, and is the address right?"
            ) from None


class Executor(abc.ABC):
    """Runs ``fn(item)`` for every item; results in the order of the items (see the module docstring)."""

    #: How many tasks run at once.
    workers: int = 1
    #: A short description for logs and reports, e.g. ``"local pool of 2 processes"``.
    description: str = ""

    def map(self, fn: Callable[[Any], Any], items: Iterable[Any], *, progress: Progress | None = None) -> list:
        """``[fn(item) for item in items]``, run on this executor's workers.  An exception raised by a task is
        raised here (after the tasks already running have finished); callers that must not stop on one bad item
        (a batch of records) catch it inside the task."""
        items = list(items)
        results: list = [None] * len(items)
        for done, (i, result) in enumerate(self.imap(fn, items), start=1):
            results[i] = result
            if progress is not None:
                progress(done, len(items))
        return results

    @abc.abstractmethod
    def imap(self, fn: Callable[[Any], Any], items: Iterable[Any]):
        """Yields ``(index, result)`` as tasks finish (any order): for callers that save results as they come
        (``erdesign batch`` writes its table while it runs, so that a killed campaign can resume)."""

    def close(self) -> None:
        """Releases the workers (a pool's processes; never a cluster the caller gave)."""

    def __enter__(self) -> Executor:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"<{type(self).__name__}: {self.description}>"


class SerialExecutor(Executor):
    """One task after another in this process: the reference every other executor must match."""

    workers = 1
    description = "serial (this process)"

    def imap(self, fn, items):
        for i, item in enumerate(items):
            yield i, fn(item)


def _start_fork_server_on_this_erdesign() -> None:
    """Start the fork server (once per process) so that its preloaded erdesign is the one this process runs.

    The server is a new interpreter started in the current folder, which puts that folder first on its path and
    ignores this process's ``sys.path`` (CPython 3.11-3.12 take it but do not apply it).  Started from another
    folder - a batch run from its records' folder, as users type record names - it imported whichever erdesign that
    folder's path found first (an installed copy instead of the checkout under test), and every worker forked from
    it ran that code.  So the server starts with the folder holding this erdesign first on ``PYTHONPATH`` and, from
    Python 3.11 on, ``PYTHONSAFEPATH`` (the current folder not on its path).  A server already running is kept."""
    from multiprocessing import forkserver

    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    saved = {k: os.environ.get(k) for k in ("PYTHONPATH", "PYTHONSAFEPATH")}
    os.environ["PYTHONPATH"] = root + (os.pathsep + saved["PYTHONPATH"] if saved["PYTHONPATH"] else "")
    os.environ["PYTHONSAFEPATH"] = "1"
    try:
        forkserver.ensure_running()
    finally:
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v


#: Imported once by the fork server, so that its workers start with them: ``import erdesign`` alone loads little
#: (its modules are imported when first used), and a worker importing units, pint, the fluids, the effects' loops,
#: the fitting engine and the record reader (scipy.signal, 0.9 s alone) itself spent about 1.8 s of CPU before its
#: first task (a batch fit of six one-cycle records: 1.9 -> 0.3 s of CPU a worker; the server's start 0.6 -> 1.8 s,
#: once per process).
FORK_SERVER_PRELOAD = [
    "erdesign",
    "numpy",
    "scipy.optimize",
    "scipy.signal",
    "erdesign.damper",
    "erdesign.effects",
    "erdesign.identification.engine",
    "erdesign.data.measurement",
]


class PoolExecutor(Executor):
    """A local pool of ``jobs`` worker processes.

    Workers are started by a fork server that has imported erdesign's common modules once (``forkserver`` start
    method, :data:`FORK_SERVER_PRELOAD`), so a worker is ready in milliseconds and never inherits the threads of its
    parent (a Streamlit server, a Dask client) the way a plain ``fork`` would.  The pool starts on first use and is shut
    down by :meth:`close` (or the ``with`` block)."""

    def __init__(self, jobs: int):
        if isinstance(jobs, bool) or not isinstance(jobs, (int, float)) or int(jobs) != jobs or jobs < 1:
            raise ExecutorError(f"jobs must be a whole number >= 1, got {jobs!r}")
        self.workers = int(jobs)
        self.description = f"local pool of {self.workers} processes"
        self._pool: concurrent.futures.ProcessPoolExecutor | None = None

    def _get_pool(self) -> concurrent.futures.ProcessPoolExecutor:
        if self._pool is None:
            if sys.platform.startswith("linux") or sys.platform == "darwin":
                ctx = multiprocessing.get_context("forkserver")
                ctx.set_forkserver_preload(FORK_SERVER_PRELOAD)
                _start_fork_server_on_this_erdesign()
            else:  # Windows: spawn is the only method
                ctx = multiprocessing.get_context("spawn")
            self._pool = concurrent.futures.ProcessPoolExecutor(
                max_workers=self.workers, mp_context=ctx, initializer=_one_blas_thread
            )
        return self._pool

    def imap(self, fn, items):
        pool = self._get_pool()
        futures = {pool.submit(fn, item): i for i, item in enumerate(items)}
        try:
            for future in concurrent.futures.as_completed(futures):
                yield futures[future], future.result()
        finally:
            for future in futures:
                future.cancel()

    def close(self):
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None


class DaskExecutor(Executor):
    """The workers of a Dask ``distributed`` cluster.

    ``cluster`` is a scheduler address (``"tcp://host:8786"``), a ``distributed.LocalCluster`` (or any cluster
    object with a scheduler) or a ``distributed.Client``.  A client this executor opened is closed by
    :meth:`close`; a client or cluster the caller gave is left running.  The workers need erdesign installed (same
    version) and the data on paths they can read: see ``docs/scale.md``."""

    def __init__(self, cluster: Any):
        try:
            import distributed
        except ImportError:
            raise ExecutorError(
                "a Dask scheduler was given, but Dask distributed is not installed: pip install 'erdesign[distributed]'"
            ) from None
        self._own_client = not isinstance(cluster, distributed.Client)
        if isinstance(cluster, distributed.Client):
            self.client = cluster
        else:
            if isinstance(cluster, str):
                _check_address(cluster)
            try:
                self.client = distributed.Client(cluster, timeout="20s", set_as_default=False)
            except (OSError, TimeoutError, ValueError) as exc:
                raise ExecutorError(f"cannot reach the Dask scheduler {cluster!r}: {exc}") from None
        workers = self.client.scheduler_info().get("workers", {})
        self.workers = max(1, sum(w.get("nthreads", 1) for w in workers.values()))
        self.description = (
            f"Dask cluster at {self.client.scheduler.address} ({len(workers)} workers, {self.workers} threads)"
        )

    def imap(self, fn, items):
        from distributed import as_completed

        items = list(items)
        if not items:
            return
        futures = self.client.map(_call_with_one_blas_thread, [fn] * len(items), items, pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        try:
            for future in as_completed(futures, loop=self.client.loop):
                yield index[future.key], future.result()
        finally:
            self.client.cancel(futures)

    def close(self):
        if self._own_client:
            self.client.close()


def dask_worker_environ() -> dict[str, str]:
    """Environment for Dask worker processes (``distributed.nanny.pre-spawn-environ``) that keeps glibc's malloc
    from mapping and unmapping every large numpy array: Dask's default ``MALLOC_TRIM_THRESHOLD_`` of 64 KiB costs
    erdesign's tasks 30 % more CPU (measured in docs/scale.md).  Large trim and mmap thresholds restore the
    behaviour of a plain Python process."""
    return {"MALLOC_TRIM_THRESHOLD_": str(128 * 2**20), "MALLOC_MMAP_THRESHOLD_": str(64 * 2**20)}


def executor_for(
    executor: Executor | Any | None = None, *, jobs: int | None = None, scheduler: str | Any | None = None
) -> Executor:
    """The executor for a call's ``executor``, ``jobs`` and ``scheduler`` arguments.

    * an :class:`Executor` given is used as it is;
    * ``scheduler`` (an address, a ``LocalCluster`` or a ``Client``), or a Dask client / cluster given as
      ``executor``, -> :class:`DaskExecutor`;
    * else ``jobs``: 1 -> :class:`SerialExecutor`, N > 1 -> :class:`PoolExecutor`; ``None`` -> serial (a library
      call stays in its process unless asked; the command line passes all cores as its default).
    """
    if isinstance(executor, Executor):
        return executor
    if isinstance(jobs, bool):  # True was one job, False an error deep in the pool
        raise ExecutorError(f"jobs must be a whole number >= 1, got {jobs!r}")
    if executor is not None:
        scheduler = executor
    if scheduler is not None and scheduler != "":
        return DaskExecutor(scheduler)
    if jobs is None or jobs == 1:
        return SerialExecutor()
    return PoolExecutor(jobs)


@contextlib.contextmanager
def executor_scope(
    executor: Executor | Any | None = None, *, jobs: int | None = None, scheduler: str | Any | None = None
):
    """``with executor_scope(executor, jobs=..., scheduler=...) as ex:`` - :func:`executor_for`, closed at the end
    of the block only if it was made here (an :class:`Executor` the caller passed stays open for its next use)."""
    ex = executor_for(executor, jobs=jobs, scheduler=scheduler)
    try:
        yield ex
    finally:
        if ex is not executor:
            ex.close()


def chunks(n: int, size: int) -> list[tuple[int, int]]:
    """``[(start, stop), ...]`` covering ``range(n)`` in pieces of at most ``size``: the unit of work of a
    sampled study, so that the pieces (not the workers) fix the random streams."""
    if size < 1:
        raise ValueError("chunk size must be >= 1")
    return [(a, min(a + size, n)) for a in range(0, n, size)]


def ordered(results: Sequence) -> list:
    """Results of :meth:`Executor.imap` (``(index, value)`` pairs) in item order."""
    return [value for _, value in sorted(results, key=lambda pair: pair[0])]
