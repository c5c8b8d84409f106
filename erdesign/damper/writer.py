"""Write damper files (TOML, docs/file_formats.md) that every reader loads again, whatever text they hold.

:func:`damper_toml` makes the text of a damper file from its content (:func:`erdesign.damper.files.damper_spec`,
or a design's spec in the app); :func:`save_damper` writes it through :mod:`erdesign.output` (whole or not at all,
never over an existing file without ``overwrite``).  Every string - the damper's name, every value, a key that is
not a bare TOML key, and the comment lines - is escaped (:func:`toml_string`), so a name with a quote, a backslash,
a line break, DEL (U+007F) or any other control character is written as an escape and reads back to the same name.

>>> text = damper_toml({"name": 'a "quoted"\\x7f name', "geometry": {"configuration": "valve"}})
>>> print(text.splitlines()[2])
name = "a \\"quoted\\"\\u007F name"
>>> from erdesign.damper.files import tomllib
>>> tomllib.loads(text)["name"] == 'a "quoted"\\x7f name'
True
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ErdesignError

__all__ = ["toml_string", "toml_key", "damper_toml", "save_damper", "DAMPER_TABLES"]

#: The tables of a damper file, in the order they are written.
DAMPER_TABLES = ("geometry", "fluid", "coil", "accumulator")

_ESCAPES = {'"': '\\"', "\\": "\\\\", "\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f", "\r": "\\r"}
#: What a TOML basic string may not hold raw (TOML 1.0, "String"): the quote, the backslash and the control
#: characters U+0000-U+001F and U+007F; the C1 controls U+0080-U+009F are allowed but escaped too, to stay visible.
_NEEDS_ESCAPE = re.compile(r'["\\\x00-\x1f\x7f-\x9f]')
_SURROGATE = re.compile(r"[\ud800-\udfff]")
_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")
#: Comments may hold no control character but tab (TOML 1.0, "Comment").
_COMMENT_FORBIDDEN = re.compile(r"[\x00-\x08\x0a-\x1f\x7f]")


def _no_surrogate(text: str, where: str) -> None:
    bad = _SURROGATE.search(text)
    if bad:
        raise ErdesignError(
            f"{where}: holds the lone surrogate U+{ord(bad.group()):04X}, which is not a character "
            "and cannot be written to a (UTF-8) file"
        )


def toml_string(text: str, where: str = "value") -> str:
    """``text`` as a TOML basic string (in double quotes) that reads back to ``text``.

    >>> print(toml_string('tab\\there, "quote", back\\\\slash, DEL\\x7f, NUL\\x00'))
    "tab\\there, \\"quote\\", back\\\\slash, DEL\\u007F, NUL\\u0000"
    """
    _no_surrogate(text, where)
    return '"' + _NEEDS_ESCAPE.sub(lambda m: _ESCAPES.get(m.group()) or _unicode_escape(m), text) + '"'


def toml_key(key: str, where: str = "key") -> str:
    """A TOML key: bare when it can be (``duct_length``), else quoted (:func:`toml_string`)."""
    return key if _BARE_KEY.fullmatch(key) else toml_string(key, where)


def _unicode_escape(match: re.Match) -> str:
    return f"\\u{ord(match.group()):04X}"


def _comment_line(line: str) -> str:
    _no_surrogate(line, "comment")
    return f"# {_COMMENT_FORBIDDEN.sub(_unicode_escape, line)}".rstrip()


def _toml_value(value: Any, where: str) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        x = float(value)
        if not math.isfinite(x):
            raise ErdesignError(f"{where}: cannot write {x!r} to a damper file")
        text = repr(x)
        return text if any(c in text for c in ".en") else text + ".0"
    if isinstance(value, str):
        return toml_string(value, where)
    raise ErdesignError(f"{where}: cannot write {value!r} ({type(value).__name__}) to a damper file")


def damper_toml(spec: Mapping[str, Any], *, comment: str = "") -> str:
    """The damper file (TOML text) of a damper spec: ``name``, ``[geometry]``, ``[fluid]`` and the optional
    ``[coil]`` and ``[accumulator]``, values as given, every string escaped (:func:`toml_string`).

    Parameters
    ----------
    spec : mapping
        The content of a damper file (values as strings with units, ``ducts`` and ``yield_exponent`` numbers).
    comment : str
        Written as ``#`` comment lines at the top (what the file is, the design point it was sized for); a
        control character in it is written as its ``\\uXXXX`` text (a TOML comment cannot hold one).

    Raises
    ------
    ErdesignError
        A key outside the damper file's tables, or a value TOML cannot hold, naming it.
    """
    lines = [_comment_line(line) for line in (comment or "damper file written by erdesign").splitlines()]
    lines.append("")
    unknown = [k for k in spec if k not in ("name", *DAMPER_TABLES)]
    if unknown:
        raise ErdesignError(
            f"{unknown[0]}: not a key of a damper file (name, [geometry], [fluid], [coil], [accumulator])"
        )
    if "name" in spec:
        lines.append(f"name = {_toml_value(str(spec['name']), 'name')}")
    for table in DAMPER_TABLES:
        values = spec.get(table)
        if values is None:
            continue
        lines += ["", f"[{table}]"]
        lines += [
            f"{toml_key(str(key), f'{table}.{key}')} = {_toml_value(value, f'{table}.{key}')}"
            for key, value in values.items()
        ]
    return "\n".join(lines) + "\n"


def save_damper(
    damper: Any, path: str | Path, *, comment: str = "", overwrite: bool = False, option: str = "path"
) -> Path:
    """Write ``damper`` (a :class:`~erdesign.damper.Damper` of a power-law fluid, or a damper spec as
    :func:`~erdesign.damper.files.damper_spec` makes it) as a damper file that :func:`load_damper` reads back to the
    same damper.  Written whole or not at all; an existing ``path`` only with ``overwrite`` (:mod:`erdesign.output`).

    Returns the path written.
    """
    from ..output import write_output
    from .damper import Damper
    from .files import damper_spec

    spec = damper_spec(damper) if isinstance(damper, Damper) else damper
    if not isinstance(spec, Mapping):
        raise ErdesignError(f"damper: expected a Damper or the content of a damper file, got {type(damper).__name__}")
    return write_output(path, damper_toml(spec, comment=comment), overwrite=overwrite, option=option)
