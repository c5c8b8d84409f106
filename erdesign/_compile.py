"""The one way erdesign compiles its loops: :func:`njit`, numba's ``njit`` that still works where it cannot cache.

numba caches compiled code in the package's ``__pycache__`` or under the user's home folder.  When neither can be
written (a package installed read-only, a service account with no home, a sandbox), ``numba.njit(cache=True)``
fails when the function is decorated - ``cannot cache function ...: no locator available`` - so that merely
importing a model stops the program before any input is read.  :func:`njit` then compiles the function in memory
(the first call of each session pays the compile time again) and says so once in the log, not to the user: the
results are the same.  Put ``NUMBA_CACHE_DIR`` on a writable folder to keep the cache.
"""

from __future__ import annotations

import logging

__all__ = ["njit", "vectorize", "guvectorize"]

_log = logging.getLogger(__name__)


def _cached_or_in_memory(kind: str, signatures: tuple, options: dict):
    """The decorator ``numba.<kind>(*signatures, **options)``, compiling in memory when ``cache=True`` finds no
    folder it can write."""
    import numba  # imported on use: numba costs about a second at start-up

    make = getattr(numba, kind)

    def decorate(func):
        if not options.get("cache"):
            return make(*signatures, **options)(func)
        try:
            return make(*signatures, **options)(func)
        except RuntimeError as exc:
            if "no locator available" not in str(exc):
                raise
            _log.info(
                "numba cannot cache %s (no writable cache folder: set NUMBA_CACHE_DIR); compiling in memory",
                func.__qualname__,
            )
            return make(*signatures, **{**options, "cache": False})(func)

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
