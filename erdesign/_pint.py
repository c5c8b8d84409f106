"""pint for erdesign, cheap to start (issue 26: ``erdesign size`` within 3x ``python -c "import numpy"``).

Two costs dominate a command's start-up, and both are pint's, not erdesign's:

* ``import pint`` imports ``dask.base`` whenever dask is installed (``pint.compat`` probes for it to support
  quantities wrapping dask arrays), about as much CPU as numpy itself, and bare ``scipy`` (which pint only notes
  as present); erdesign uses neither through pint, so :data:`pint` is imported with both hidden for that one
  import (a package already loaded is left alone).  Both import normally afterwards; only pint's dask-array methods
  (``Quantity.compute``, ``persist``, ``visualize``) are absent when erdesign imported pint first.
* building the registry parses pint's unit definitions (about 0.7 s); pint can cache the parsed definitions in a
  folder (``UnitRegistry(cache_folder=...)``, pint's *Caching* docs), after which building it costs some 50 ms.
  :func:`application_registry` does so in the user's cache folder (``~/.cache/erdesign/pint-<version>`` on Linux;
  the environment variable ``ERDESIGN_UNIT_CACHE`` names another folder to hold ``pint-<version>``, or ``off`` for
  none).  The cache is only a
  speed-up: a folder that cannot be created or written, or a damaged cache file, falls back to parsing the
  definitions as pint does by default (the files of a damaged cache are removed so that the next run writes them
  again; nothing else in the folder is touched).

Only :mod:`erdesign.units` (and the few modules that name ``pint`` types) import from here; every other module
gets its quantities from :mod:`erdesign.units`.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

__all__ = ["CACHE_ENV", "application_registry", "cache_folder", "pint"]

#: Environment variable naming the folder of the unit cache (``off``: no cache).
CACHE_ENV = "ERDESIGN_UNIT_CACHE"


#: Packages pint probes for at import (``pint.compat``) that erdesign never uses through pint.
_HIDDEN = ("dask", "scipy")


def _import_pint():
    if "pint" in sys.modules:
        import pint

        return pint
    hidden = [name for name in _HIDDEN if name not in sys.modules]
    for name in hidden:
        sys.modules[name] = None  # find_spec() is then None and `import` fails: pint.compat skips them
    try:
        import pint
    finally:
        for name in hidden:
            if name in sys.modules and sys.modules[name] is None:
                del sys.modules[name]
    return pint


pint = _import_pint()


def cache_folder() -> Path | None:
    """The folder of the unit-definition cache (None: no cache): a subfolder ``pint-<version>`` of
    ``ERDESIGN_UNIT_CACHE`` or of the user's cache folder for erdesign."""
    given = os.environ.get(CACHE_ENV)
    if given is not None and given.strip().lower() in ("", "off", "0", "no", "false"):
        return None
    if given is not None:
        base = Path(given)
    else:
        import platformdirs  # a dependency of pint

        base = platformdirs.user_cache_path("erdesign", appauthor=False)
    return base / f"pint-{pint.__version__}"


def _registry():
    folder = cache_folder()
    if folder is not None:
        try:
            return pint.UnitRegistry(cache_folder=folder, on_redefinition="raise")
        except OSError:
            pass  # not writable, a file in the way, disk full: no cache this time
        except Exception:  # noqa: BLE001  (a damaged cache file: pickle raises assorted errors)
            for stale in (*folder.glob("*.pickle"), *folder.glob("*.json")):  # only what pint wrote there
                stale.unlink(missing_ok=True)
    return pint.UnitRegistry(on_redefinition="raise")


def application_registry():
    """pint's application registry, built from the cache when nobody has built it yet.

    It stays pint's application registry (quantities pickle and unpickle through it, and mix with the user's own
    ``pint.get_application_registry()``): a registry the user set or already used is kept as it is.
    """
    app = pint.get_application_registry()
    if type(app.get()) is pint.registry.LazyRegistry:  # type() does not trigger the lazy build
        pint.set_application_registry(_registry())
    return app
