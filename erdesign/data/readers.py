"""The records in a file of any format erdesign reads: a measurement CSV or a file of a known data set.

:func:`read_records` is what ``erdesign identify`` and ``erdesign simulate`` read their files with (``--format``).
"""

from __future__ import annotations

from ..errors import ErdesignError
from ..limits import MAX_RECORD_BYTES, size_text
from .measurement import Measurement
from .quiroz import QUIROZ_FILE_NAME, read_quiroz_file, read_quiroz_mat

__all__ = ["read_records", "RECORD_FORMATS"]

#: Formats that :func:`read_records` knows.
RECORD_FORMATS = ("auto", "csv", "quiroz", "quiroz-mat")


def read_records(path, fmt: str = "auto", where: str = "MEASUREMENT") -> list[Measurement]:
    """The records in one file: a measurement CSV (docs/file_formats.md; one record), a Quiroz (2022)
    preprocessed sinusoid (:func:`read_quiroz_file`; one record) or Quiroz's validation ``.mat``
    (:func:`read_quiroz_mat`; one record per current).

    ``fmt`` "auto" decides by the file: ``.mat`` is Quiroz's validation file; a file whose first line that is not
    a ``#`` comment is numbers (no header with units) and whose name is ``<amp>mm<freq>Hz<current>A.txt`` is a
    Quiroz sinusoid; anything else is read as a measurement CSV.  Errors name ``where`` and the file.
    """
    from pathlib import Path
    from .measurement import read_measurement

    if fmt not in RECORD_FORMATS:
        raise ErdesignError(f"--format: {fmt!r} is not one of {', '.join(RECORD_FORMATS)}")
    path = Path(path)
    if not path.is_file():
        what = (
            "is a folder"
            if path.is_dir()
            else "is not a regular file (a device or a pipe)"
            if path.exists()
            else "no such file"
        )
        raise ErdesignError(f"{where}: {what} {path}" if what == "no such file" else f"{where}: {path} {what}")
    if path.stat().st_size > MAX_RECORD_BYTES:
        raise ErdesignError(
            f"{where}: {path} is larger than {size_text(MAX_RECORD_BYTES)}, the most erdesign reads "
            "as one record file; thin or split the file"
        )
    if fmt == "auto":
        if path.suffix.lower() == ".mat":
            fmt = "quiroz-mat"
        else:
            with open(path, "rb") as fh:
                head = fh.read(_SNIFF_BYTES)  # never a whole file: a line may be gigabytes long
            lines = head.decode("utf-8", "replace").splitlines()
            if len(head) == _SNIFF_BYTES and len(lines) > 1:
                lines = lines[:-1]  # cut by the read
            first = next((line.strip() for line in lines if line.strip() and not line.strip().startswith("#")), "")
            numeric = bool(first) and all(_is_number(tok) for tok in first.replace(",", " ").split())
            if numeric:
                import re

                if re.fullmatch(QUIROZ_FILE_NAME, path.stem) is None:
                    raise ErdesignError(
                        f"{where}: {path} has no header line with units (e.g. 'time [s],displacement "
                        "[mm],force [N]') and is not a Quiroz (2022) preprocessed file "
                        "(<amp>mm<freq>Hz<current>A.txt); see docs/case_studies/quiroz.md"
                    )
                fmt = "quiroz"
            else:
                fmt = "csv"
    try:
        if fmt == "quiroz":
            return [read_quiroz_file(path)]
        if fmt == "quiroz-mat":
            return read_quiroz_mat(path)
        return [read_measurement(path)]
    except ErdesignError as exc:  # the same class, with the argument named first
        raise type(exc)(f"{where}: {exc}") from None


#: Bytes read to decide the format of a file ("auto").
_SNIFF_BYTES = 65536


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True
