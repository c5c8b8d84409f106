"""Limits on what erdesign reads, and the one reader of input files that enforces them.

A file given by mistake (``/dev/zero``, a video, a spreadsheet renamed to ``.csv``, a log of a day at 100 kHz) must
stop with a one-line message naming the file and the limit, quickly and without filling the memory; it must never
reach a parser that reads until the memory runs out or fails with an internal error.  The limits are far above
any damper file or damper test record:

==========================  ============  =====================================================================
limit                       value         what it bounds
==========================  ============  =====================================================================
:data:`MAX_RECORD_BYTES`    256 MB        a measurement file (60,000 rows of 4 columns take about 3 MB)
:data:`MAX_RECORD_ROWS`     10,000,000    the rows of a measurement (about 3 hours at 1 kHz), and the samples or time
                                          steps of a record or run erdesign makes (:func:`check_sample_count`)
:data:`MAX_CELL_CHARS`      1,000         one cell of a measurement (a number or a header ``name [unit]``)
:data:`MAX_TOML_BYTES`      1 MB          a damper or requirements file (the examples take about 2 kB)
:data:`MAX_VALUE_CHARS`     200           a value with a unit (``"0.8 mm"``)
==========================  ============  =====================================================================

Nesting is bounded by the parsers' own limit (Python's recursion limit): :func:`nested_too_deeply` is the message
the loaders give instead of a ``RecursionError``.
"""

from __future__ import annotations

import os
import stat

from .errors import ErdesignError

__all__ = [
    "MAX_CELL_CHARS",
    "MAX_RECORD_BYTES",
    "MAX_RECORD_ROWS",
    "MAX_TOML_BYTES",
    "MAX_VALUE_CHARS",
    "check_sample_count",
    "decode_text",
    "is_path_like",
    "nested_too_deeply",
    "read_input_bytes",
    "refuse_binary",
    "size_text",
]

MAX_RECORD_BYTES = 256 * 2**20
MAX_RECORD_ROWS = 10_000_000
MAX_CELL_CHARS = 1_000
MAX_TOML_BYTES = 2**20
MAX_VALUE_CHARS = 200

_CHUNK = 2**20


def size_text(n: int) -> str:
    """``n`` bytes as text (``"256 MB"``, ``"3.2 kB"``)."""
    for unit, scale in (("GB", 2**30), ("MB", 2**20), ("kB", 2**10)):
        if n >= scale:
            return f"{n / scale:.3g} {unit}"
    return f"{n} bytes"


def read_input_bytes(path: str | os.PathLike, limit: int, what: str, label: str | None = None) -> bytes:
    """The bytes of an input file, refused with a :class:`~erdesign.errors.ErdesignError` naming the file when it
    is larger than ``limit`` or holds NUL bytes (a binary file: a spreadsheet, an archive, ``/dev/zero``).

    A named pipe or a socket is refused before it is opened (opening a pipe waits for a writer, for ever); a pipe
    handed over by the shell (``/dev/fd/N``: process substitution) is read.  A
    regular file within ``limit`` is read in one piece; anything else (a device, a larger file) in chunks
    and never past ``limit``, so an endless device or a huge file stops at once, and its first chunk is checked for
    NUL bytes before any more is read.  ``what`` says what the file should be (``"a
    measurement CSV file"``) and ``label`` is how the message names the file (default: the path).
    OS errors (no such file, a folder, no permission) propagate for the caller to phrase.
    """
    label = str(path) if label is None else label
    if "\x00" in os.fspath(path):  # "embedded null byte", a ValueError from the system call
        raise ErdesignError(f"{label!r:.80}: the file name holds a NUL character; no file is named so")
    kind = os.stat(path).st_mode
    # opening a named pipe waits for a writer, for ever; a pipe the shell hands over (process substitution,
    # ``fit <(zcat rec.csv.gz)``: /dev/fd/N) has its writer already and is read as any stream
    handed_over = os.fspath(path).startswith(("/dev/fd/", "/proc/self/fd/", "/dev/stdin"))
    if (stat.S_ISFIFO(kind) and not handed_over) or stat.S_ISSOCK(kind):
        what_it_is = "a named pipe" if stat.S_ISFIFO(kind) else "a socket"
        raise ErdesignError(f"{label}: not a regular file ({what_it_is}); save the data to a file and give its name")
    chunks, total = [], 0
    with open(path, "rb") as fh:
        size = os.fstat(fh.fileno()).st_size  # 0 for a pipe or a device
        # a regular file within the limit in one read (reading it by chunks and joining them cost 20 x more);
        # anything else by chunks, never past the limit
        chunk = fh.read(size + 1 if 0 < size <= limit else _CHUNK)
        refuse_binary(chunk, label, what)
        while chunk:
            total += len(chunk)
            if total > limit:
                raise ErdesignError(
                    f"{label}: larger than {size_text(limit)}, the most erdesign reads as {what}; "
                    "thin or split the file"
                )
            chunks.append(chunk)
            chunk = fh.read(min(_CHUNK, limit + 1 - total))
    return chunks[0] if len(chunks) == 1 else b"".join(chunks)


def refuse_binary(head: bytes, label: str, what: str) -> None:
    """An :class:`~erdesign.errors.ErdesignError` naming ``label`` when the first bytes of an input (a file's, an
    upload's) are a zip archive (a spreadsheet), UTF-16 text or hold NUL bytes (a binary file): ``what`` says what
    the input should be."""
    if head.startswith(b"PK\x03\x04"):
        advice = "; save it as CSV (UTF-8)" if "CSV" in what else ""
        raise ErdesignError(f"{label}: a zip archive (an .xlsx or .ods spreadsheet?), not {what}{advice}")
    _refuse_utf16(head, label, what)
    if head.find(b"\x00", 0, _CHUNK) != -1:  # in the first chunk, whatever was read (no copy of it)
        raise ErdesignError(f"{label}: a binary file (it holds NUL bytes), not {what} (UTF-8 text)")


def _refuse_utf16(head: bytes, label: str, what: str) -> None:
    if head.startswith((b"\xff\xfe", b"\xfe\xff")):  # a byte-order mark of UTF-16 (or UTF-32)
        raise ErdesignError(
            f"{label}: UTF-16 text (Excel's 'Unicode Text', Notepad's 'Unicode'), not {what} in UTF-8; save it as UTF-8"
        )


def check_sample_count(n: float, what: str, advice: str, most: int = MAX_RECORD_ROWS) -> int:
    """``n`` (the samples or time steps a duration and a rate or step make) as an int, or an
    :class:`~erdesign.errors.ErdesignError` starting with ``what`` when it exceeds ``most`` (default
    :data:`MAX_RECORD_ROWS`; less for a record that is computed on a finer grid first): ``doe
    --rate "1e9 Hz"`` or ``vehicle --duration "1e6 s"`` asked for terabytes and ended in a MemoryError.

    >>> check_sample_count(4e9, "duration, rate", "shorten the duration or lower the rate")
    Traceback (most recent call last):
    ...
    erdesign.errors.ErdesignError: duration, rate: 4,000,000,000 samples, more than the 10,000,000 erdesign makes in one record (a unit mistake?); shorten the duration or lower the rate
    """
    if not n <= most:
        shown = f"{n:,.0f}" if n < 1e30 else f"{n:.3g}"
        raise ErdesignError(
            f"{what}: {shown} samples, more than the {most:,} erdesign makes in one record (a unit mistake?); {advice}"
        )
    return int(n)


def nested_too_deeply(label: str) -> str:
    """The message for a file whose nesting exceeds the parser's recursion limit."""
    return f"{label}: nested too deeply to read (arrays or tables inside one another hundreds of levels deep)"


def is_path_like(value) -> bool:
    """True for a str or os.PathLike (what the loaders take as a file name)."""
    return isinstance(value, (str, os.PathLike)) and not isinstance(value, bytes)


def decode_text(raw: bytes, label: str, what: str) -> str:
    """The text of an input file's bytes (UTF-8; a byte-order mark, as Notepad and Excel write it, is dropped), or
    an :class:`~erdesign.errors.ErdesignError` naming the file and the line of the first byte that is not UTF-8
    (a file saved as Latin-1 or Windows-1252: an accented letter, a micro sign).

    >>> decode_text(b"\\xef\\xbb\\xbfname = 1", "d.toml", "a TOML file")
    'name = 1'
    >>> decode_text(b"a = 1\\nname = 'D\\xe4mpfer'", "d.toml", "a TOML file")
    Traceback (most recent call last):
    ...
    erdesign.errors.ErdesignError: d.toml: line 2: byte 0xe4 is not UTF-8 (the file was saved as Latin-1 or Windows-1252?); save it as UTF-8 text, not a TOML file in another encoding
    """
    _refuse_utf16(raw, label, what)
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = raw.count(b"\n", 0, exc.start) + 1
        hint = " (the file was saved as Latin-1 or Windows-1252?)" if raw[exc.start] >= 0xA0 else ""
        raise ErdesignError(
            f"{label}: line {line}: byte 0x{raw[exc.start]:02x} is not UTF-8{hint}; save it as UTF-8 text, not "
            f"{what} in another encoding"
        ) from None
