"""Small helpers shared by the kernels and the commands (not part of the public API)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Iterable, Mapping

import numpy as np

from .errors import OutputPathError
from .output import exists_message, refuse_symlink

__all__ = ["scalar_or_array", "check_output_path"]


def scalar_or_array(x):
    """A Python float for 0-d input, the numpy array otherwise (keeps doctests and JSON output plain)."""
    arr = np.asarray(x)
    return float(arr) if arr.ndim == 0 else arr


def _same_file(a: Path, b: Path) -> bool:
    try:
        if a.exists() and b.exists():
            return os.path.samefile(a, b)
        return a.resolve() == b.resolve()
    except (OSError, RuntimeError):         # a symbolic link loop (RuntimeError before Python 3.13)
        return False


def check_output_path(out: str | Path, *, force: bool = False,
                      inputs: Iterable[str | Path | None] | Mapping[str, str | Path | None] = (),
                      formats: Mapping[str, str] | None = None, fmt: str | None = None,
                      option: str = "--out") -> tuple[Path, str | None]:
    """The file a command may write, and its format; an :class:`~erdesign.errors.OutputPathError` otherwise.

    The one rule of every command that writes a file (issue 15: never lose work):

    * never an input file of the same call, even with ``force`` (``inputs``: paths, or label -> path);
    * an existing file only with ``force`` (never a folder); a symbolic link (dangling, a loop, or not) only with
      ``force``, which replaces the link itself;
    * the format follows the suffix (``formats`` maps suffix -> format); a suffix not in ``formats`` is refused
      rather than written in another format, and so is a ``fmt`` asked for that the suffix contradicts;
    * the folder must exist.

    This is the early check (before a long computation); the writer (:func:`erdesign.output.atomic_output`) decides
    again when it creates the file, so a file made in between is never overwritten without ``force``.

    Returns ``(path, format)`` (``format`` None when ``formats`` is None).

    Examples
    --------
    >>> check_output_path("report.md", formats={".html": "html", ".md": "md"})
    (PosixPath('report.md'), 'md')
    >>> check_output_path("report.pdf", formats={".html": "html", ".md": "md"})
    Traceback (most recent call last):
    ...
    erdesign.errors.OutputPathError: --out report.pdf: cannot write a '.pdf' file; give a name ending in .html or .md
    """
    if out is None or str(out).strip() == "":
        raise OutputPathError(f"{option}: empty file name")
    path = Path(out)
    refuse_symlink(path, overwrite=force, option=option)
    named = inputs.items() if isinstance(inputs, Mapping) else (("an input file of this command", p) for p in inputs)
    for label, given in named:
        if given is not None and _same_file(path, Path(given)):
            raise OutputPathError(f"{option} {path}: that is {label} itself ({given}); an input is never "
                                  "overwritten, even with --force: choose another name")
    kind = None
    if formats is not None:
        suffix = path.suffix.lower()
        if suffix not in formats:
            allowed = " or ".join(dict.fromkeys(formats))
            raise OutputPathError(f"{option} {path}: cannot write a '{suffix or '(no suffix)'}' file; give a name "
                                  f"ending in {allowed}")
        kind = formats[suffix]
        if fmt is not None and fmt != kind:
            raise OutputPathError(f"{option} {path}: the suffix '{suffix}' says {kind}, --format says {fmt}; make "
                                  "them agree")
    if path.is_dir() and not path.is_symlink():
        raise OutputPathError(f"{option} {path}: is a folder; give a file name")
    if path.exists() and not force:
        raise OutputPathError(exists_message(path, option))
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise OutputPathError(f"{option} {path}: the folder {parent} does not exist")
    return path, kind
