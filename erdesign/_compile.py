"""The one way erdesign compiles its loops: :func:`njit`, numba's ``njit`` that still works where it cannot cache,
and never compiles into the same cache at the same time as another process.

numba caches compiled code in the package's ``__pycache__`` or under the user's home folder.  When neither can be
written (a package installed read-only, a service account with no home, a sandbox), ``numba.njit(cache=True)``
fails when the function is decorated - ``cannot cache function ...: no locator available`` - so that merely
importing a model stops the program before any input is read.  :func:`njit` then compiles the function in memory
(the first call of each session pays the compile time again) and says so once in the log, not to the user: the
results are the same.  Put ``NUMBA_CACHE_DIR`` on a writable folder to keep the cache.

Two processes that compile the same cached function at once (parallel test workers, Dask workers, two commands
started together on a cold cache) can write its cache files from two different compiles; numba's cache of a
generalised ufunc is two files, and a mismatched pair crashes every later process that loads it with a segmentation
fault (numba issue #10128).  Every first compile of a cached function (loading from the cache, or compiling and
saving) therefore holds an inter-process lock: a lock file per user and cache folder, taken with ``fcntl.flock``.
The second process waits, then loads what the first saved.  Where ``flock`` is unavailable (Windows) or the lock
file cannot be made, compiles go unlocked, as numba's own do.
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import logging
import os
import tempfile
import threading
from pathlib import Path

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows: no flock, compiles go unlocked
    fcntl = None

__all__ = ["njit", "vectorize", "guvectorize", "cache_lock"]

_log = logging.getLogger(__name__)

#: The package folder: numba keeps the caches of erdesign's loops below it (``__pycache__``) or, with
#: ``NUMBA_CACHE_DIR``, in a tree under that folder.
_PACKAGE = Path(__file__).resolve().parent

#: One process-wide lock and its depth: a compile that compiles the functions it calls takes the lock again (the
#: lock file is taken once per process; a second ``flock`` on a new descriptor of the same file would wait on itself).
_thread_lock = threading.RLock()
_depth = 0
_held_file = None


def _lock_path() -> Path:
    """The lock file of this user and cache folder: in the temporary folder (writable where the cache may not be),
    named by the user id and a hash of the cache folder, so that users and separate caches never wait on each
    other."""
    folder = os.environ.get("NUMBA_CACHE_DIR") or str(_PACKAGE)
    key = hashlib.sha256(os.path.abspath(folder).encode("utf-8", "surrogateescape")).hexdigest()[:16]
    uid = os.getuid() if hasattr(os, "getuid") else 0
    return Path(tempfile.gettempdir()) / f"erdesign-numba-{uid}-{key}.lock"


@contextlib.contextmanager
def cache_lock():
    """Hold the inter-process lock of this user's numba cache of erdesign (re-entrant within a process).

    Taken around every first compile of a cached function; waits while another process compiles into the same
    cache.  Without ``fcntl`` or when the lock file cannot be opened, yields without locking."""
    global _depth, _held_file
    with _thread_lock:
        if _depth == 0 and fcntl is not None:
            try:
                handle = open(_lock_path(), "a+b")  # noqa: SIM115 - closed when the outermost hold ends
            except OSError as exc:
                _log.info("numba cache lock unavailable (%s); compiling without it", exc)
            else:
                try:
                    fcntl.flock(handle.fileno(), fcntl.LOCK_EX)
                except OSError as exc:  # a file system without locks
                    _log.info("numba cache lock unavailable (%s); compiling without it", exc)
                    handle.close()
                else:
                    _held_file = handle
        _depth += 1
        try:
            yield
        finally:
            _depth -= 1
            if _depth == 0 and _held_file is not None:
                handle, _held_file = _held_file, None
                fcntl.flock(handle.fileno(), fcntl.LOCK_UN)
                handle.close()


def _compiler_lock():
    """numba's own process-wide compiler lock, taken before :func:`cache_lock`: a thread holding the cache lock
    never waits for a thread that is compiling (which would in turn wait for the cache lock)."""
    from numba.core.compiler_lock import global_compiler_lock

    return global_compiler_lock


def _locked(compile_):
    """``Dispatcher.compile`` under the compiler lock and :func:`cache_lock`."""

    @functools.wraps(compile_)
    def compile(sig):
        with _compiler_lock(), cache_lock():
            return compile_(sig)

    return compile


def _cached_or_in_memory(kind: str, signatures: tuple, options: dict):
    """The decorator ``numba.<kind>(*signatures, **options)``, compiling in memory when ``cache=True`` finds no
    folder it can write, and under :func:`cache_lock` when it can."""
    import numba  # imported on use: numba costs about a second at start-up

    make = getattr(numba, kind)

    def decorate(func):
        if not options.get("cache"):
            return make(*signatures, **options)(func)
        try:
            with contextlib.ExitStack() as hold:
                if signatures:  # vectorize, guvectorize (and njit) with signatures compile here, at decoration
                    hold.enter_context(_compiler_lock())
                    hold.enter_context(cache_lock())
                compiled = make(*signatures, **options)(func)
        except RuntimeError as exc:
            if "no locator available" not in str(exc):
                raise
            _log.info(
                "numba cannot cache %s (no writable cache folder: set NUMBA_CACHE_DIR); compiling in memory",
                func.__qualname__,
            )
            return make(*signatures, **{**options, "cache": False})(func)
        if isinstance(compiled, numba.core.dispatcher.Dispatcher):
            # without signatures, njit compiles at the first call of each argument type
            compiled.compile = _locked(compiled.compile)
        return compiled

    return decorate


def njit(*args, **options):
    """``numba.njit`` with the same arguments (``@njit``, ``@njit(cache=True, nogil=True)``), falling back to an
    in-memory compile when ``cache=True`` finds no folder it can write."""
    if len(args) == 1 and callable(args[0]) and not options:
        return _cached_or_in_memory("njit", (), {})(args[0])
    return _cached_or_in_memory("njit", args, options)


def vectorize(*signatures, **options):
    """``numba.vectorize`` with the same fallback as :func:`njit`."""
    return _cached_or_in_memory("vectorize", signatures, options)


def guvectorize(*signatures, **options):
    """``numba.guvectorize`` with the same fallback as :func:`njit`."""
    return _cached_or_in_memory("guvectorize", signatures, options)
