"""Example damper files (TOML), requirements and measurements, installed with the package as ``erdesign.examples``.

Load one with :func:`erdesign.load_example` (``load_example("makris")``) or give its name or its path to the command
line.  The documentation writes them as ``examples/makris.toml``, ``examples/requirements/...`` and
``examples/measurements/...``: where no such file exists (an installed package, a copy of the repository without its
``examples`` link), :func:`bundled_file` finds the file the package ships, so those commands work from any folder.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path, PurePath

__all__ = ["bundled_file"]


def bundled_file(path: str | Path) -> Path | None:
    """The shipped file that a relative path ``examples/<file>`` names, when no file exists at ``path``; else None.

    >>> import os, tempfile
    >>> here, empty = os.getcwd(), tempfile.TemporaryDirectory()
    >>> os.chdir(empty.name)                     # a folder without an examples/ of its own
    >>> bundled_file("examples/requirements/makris_requirements.toml").name
    'makris_requirements.toml'
    >>> bundled_file("examples/no_such_file.toml") is None, bundled_file("elsewhere/makris.toml") is None
    (True, True)
    >>> os.chdir(here); empty.cleanup()
    """
    given = PurePath(path)
    parts = given.parts
    if given.is_absolute() or len(parts) < 2 or parts[0] != "examples" or ".." in parts or Path(path).exists():
        return None  # (exists() last: it raises for a name with a NUL or of more than 255 bytes, left to the reader)
    found = resources.files(__name__).joinpath(*parts[1:])
    return Path(str(found)) if found.is_file() else None
