"""Small helpers shared by the kernels and the commands (not part of the public API)."""

from __future__ import annotations

import os
import unicodedata
from pathlib import Path
from typing import Iterable, Mapping

import numpy as np

from .errors import ErdesignError, OutputPathError
from .output import _NAME_MAX as NAME_MAX
from .output import _tilde_hint as tilde_hint
from .output import exists_message, refuse_odd_name, refuse_read_only, refuse_symlink

__all__ = ["scalar_or_array", "check_output_path", "si_array", "broadcast_named"]


def scalar_or_array(x):
    """A Python float for 0-d input, the numpy array otherwise (keeps doctests and JSON output plain)."""
    arr = np.asarray(x)
    return float(arr) if arr.ndim == 0 else arr


def si_array(value, name: str, *, finite: bool = True) -> np.ndarray:
    """A public SI argument as a float array, or an :class:`~erdesign.errors.ErdesignError` naming ``name``: not
    numbers (text, None, objects), a pint quantity where SI magnitudes are expected (its unit would be dropped), or
    NaN / infinity when ``finite``.

    >>> si_array([0.1, float("nan")], "v")
    Traceback (most recent call last):
    ...
    erdesign.errors.ErdesignError: v: element 1 is nan; give finite numbers (SI)
    """
    if hasattr(value, "units") and hasattr(value, "magnitude"):
        raise ErdesignError(
            f"{name}: expected SI numbers, got a quantity in {value.units:~P}; pass "
            f"value.to(unit).magnitude or use the unit-aware function"
        )
    if type(value).__name__ == "DataFrame" and hasattr(value, "columns"):  # its columns were taken as more values
        raise ErdesignError(
            f"{name}: a DataFrame of {len(value.columns)} column(s); pass one column, e.g. df[{str(value.columns[0])!r}]"
        )
    if np.ma.isMaskedArray(value) and np.ma.getmaskarray(value).any():  # asarray drops the mask: hidden values
        at = int(np.flatnonzero(np.ma.getmaskarray(value).ravel())[0])
        raise ErdesignError(
            f"{name}: element {at} is masked; give the values to use (numpy.ma.compressed() drops the masked ones)"
        )
    if isinstance(value, (bytes, bytearray, memoryview)):  # a bytearray was read as its bytes' codes (97 for 'a')
        raise ErdesignError(f"{name}: expected a number or an array of numbers (SI), got {_shown(value)}")
    # numpy reads text ('0.1', b'0.1'), True, dates and complex numbers (dropping the imaginary part) as floats
    try:
        kind = "O" if value is None else np.asarray(value).dtype.kind
    except (TypeError, ValueError):  # a ragged list
        kind = "O"
    if kind in "USObMmc" and (kind != "O" or value is None or _holds_non_numbers(value)):
        what = {"b": "true/false", "M": "a date", "m": "a time span", "c": "complex numbers"}.get(kind)
        raise ErdesignError(
            f"{name}: expected a number or an array of numbers (SI), got {f'{what}: ' if what else ''}{_shown(value)}"
        )
    try:
        arr = np.asarray(value, dtype=float)
    except OverflowError:  # an integer beyond any float (10**400)
        raise ErdesignError(f"{name}: {_shown(value)} is beyond the largest float; give finite numbers (SI)") from None
    except (TypeError, ValueError):
        raise ErdesignError(f"{name}: expected a number or an array of numbers (SI), got {_shown(value)}") from None
    if finite:
        bad = ~np.isfinite(arr)
        if np.any(bad):
            where = f"element {int(np.flatnonzero(bad.ravel())[0])} is" if arr.ndim else "it is"
            raise ErdesignError(f"{name}: {where} {arr.ravel()[bad.ravel()][0]}; give finite numbers (SI)")
    return arr


def _shown(value) -> str:
    """``value`` for an error message: its type and the first 60 characters of its repr on one line (made only when
    a message needs it: the repr of an array of a few hundred numbers costs more than the check itself)."""
    shown = " ".join(repr(value).split())
    return f"{type(value).__name__} {shown[:60]}{'...' if len(shown) > 60 else ''}"


def _holds_non_numbers(value) -> bool:
    """True for an object array or sequence holding anything but real numbers (Decimal and Fraction are numbers)."""
    import numbers
    from decimal import Decimal

    try:
        items = np.asarray(value, dtype=object).ravel()[:1000]
    except (TypeError, ValueError):  # a ragged list
        return True
    return any(
        isinstance(v, (bool, np.bool_)) or not isinstance(v, (numbers.Real, Decimal)) or np.ndim(v) for v in items
    )


def broadcast_named(**arrays) -> tuple[int, ...]:
    """The common shape of named arrays (numpy broadcasting), or an :class:`~erdesign.errors.ErdesignError` naming
    the first two arguments whose shapes do not fit.

    >>> broadcast_named(v=np.ones(3), field=np.ones(4))
    Traceback (most recent call last):
    ...
    erdesign.errors.ErdesignError: v and field: shapes (3,) and (4,) do not match (give arrays of one length, or a single value)
    """
    shapes = {k: np.shape(a) for k, a in arrays.items()}
    try:
        return np.broadcast_shapes(*shapes.values())
    except ValueError:
        pass
    names = list(shapes)
    for i, a in enumerate(names):
        for b in names[i + 1 :]:
            try:
                np.broadcast_shapes(shapes[a], shapes[b])
            except ValueError:
                raise ErdesignError(
                    f"{a} and {b}: shapes {shapes[a]} and {shapes[b]} do not match (give arrays of "
                    "one length, or a single value)"
                ) from None
    raise ErdesignError(f"{', '.join(names)}: shapes {', '.join(map(str, shapes.values()))} do not match")


def _same_file(a: Path, b: Path) -> bool:
    try:
        if a.exists() and b.exists():
            return os.path.samefile(a, b)
        return a.resolve() == b.resolve()
    except (OSError, RuntimeError):  # a symbolic link loop (RuntimeError before Python 3.13)
        return False


#: Unicode's direction controls (embeddings, overrides, isolates, marks): invisible, they reorder what is shown.
_BIDI_CONTROLS = frozenset("\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")


def check_output_path(
    out: str | Path,
    *,
    force: bool = False,
    inputs: Iterable[str | Path | None] | Mapping[str, str | Path | None] = (),
    formats: Mapping[str, str] | None = None,
    fmt: str | None = None,
    option: str = "--out",
) -> tuple[Path, str | None]:
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
    # 'a\nb.html' was written: a name that breaks every script and listing that meets it; a direction override
    # ('a\u202ecsv.exe.csv') makes a listing show another name than the file's
    bad = next((c for c in str(out) if unicodedata.category(c) == "Cc" or c in _BIDI_CONTROLS), None)
    if bad is not None:
        raise OutputPathError(
            f"{option} {str(out)!r:.80}: the file name holds the control character {bad!r}; give a plain name"
        )
    refuse_odd_name(out, option)
    path = Path(out)
    longest = max((len(part.encode("utf-8", "surrogateescape")) for part in path.parts), default=0)
    if longest > NAME_MAX:  # was "[Errno 36] File name too long: '...'" (the whole path), naming no option
        raise OutputPathError(
            f"{option} {str(out)[:60]!r}...: a name of {longest} bytes, more than the {NAME_MAX} a file system "
            "takes; give a shorter name"
        )
    refuse_symlink(path, overwrite=force, option=option)
    if path.is_dir() and not path.is_symlink():  # before the suffix: "cannot write a '(no suffix)' file"
        raise OutputPathError(f"{option} {path}: is a folder; give a file name")
    named = inputs.items() if isinstance(inputs, Mapping) else (("an input file of this command", p) for p in inputs)
    for label, given in named:
        if given is not None and _same_file(path, Path(given)):
            raise OutputPathError(
                f"{option} {path}: that is {label} itself ({given}); an input is never "
                "overwritten, even with --force: choose another name"
            )
    kind = None
    if formats is not None:
        suffix = path.suffix.lower()
        if suffix not in formats:
            allowed = " or ".join(dict.fromkeys(formats))
            raise OutputPathError(
                f"{option} {path}: cannot write a '{suffix or '(no suffix)'}' file; give a name ending in {allowed}"
            )
        kind = formats[suffix]
        if fmt is not None and fmt != kind:
            raise OutputPathError(
                f"{option} {path}: the suffix '{suffix}' says {kind}, --format says {fmt}; make them agree"
            )
    if path.is_dir() and not path.is_symlink():
        raise OutputPathError(f"{option} {path}: is a folder; give a file name")
    if path.exists() and not force:
        raise OutputPathError(exists_message(path, option))
    if force:
        refuse_read_only(path, option)
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise OutputPathError(f"{option} {path}: the folder {parent} does not exist{tilde_hint(parent)}")
    return path, kind
