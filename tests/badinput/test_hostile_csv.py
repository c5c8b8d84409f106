"""Issue 27: hostile measurement files - sizes, encodings, exports of spreadsheets, look-alike numbers, holes in
time, impossible temperatures - are read correctly or refused with one line naming the file and the line, column or
limit; never an internal error, a silent wrong value, or a read that runs until the memory is gone."""

from __future__ import annotations

import time
import warnings
import zipfile

import numpy as np
import pytest

from erdesign import limits
from erdesign.data import measurement
from erdesign.data.measurement import MeasurementError, read_measurement
from erdesign.data.readers import read_records
from erdesign.errors import MESSAGE_LIMIT, PlausibilityWarning, one_line

from .corpus import GOOD_RECORD, _F, _t, _x, record

HEADER = "time [s],displacement [mm],force [N]"


def _write(tmp_path, content, name="m.csv"):
    path = tmp_path / name
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_bytes(content.encode("utf-8"))
    return path


def _refused(path, *needles):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(MeasurementError) as info:
            read_measurement(path)
    message = str(info.value)
    assert message.startswith(str(path)), message
    for needle in needles:
        assert needle in message, (needle, message)
    assert message == one_line(message) and len(message) < MESSAGE_LIMIT, message
    return message


# ------------------------------------------------------------------------------------------ read as meant
def _semicolon_export(text: str) -> str:
    """The record as a spreadsheet in a decimal-comma locale saves "CSV": ';' between cells, ',' as decimal mark."""
    return text.replace(",", ";").replace(".", ",")


def _same_as_good(path):
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        m = read_measurement(path)
    np.testing.assert_allclose(m.time, _t, rtol=0, atol=1e-15)
    np.testing.assert_allclose(m.displacement, _x * 1e-3, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(m.force, _F, rtol=1e-9)
    return m


@pytest.mark.parametrize(
    "name, transform",
    [
        ("utf-8 BOM", lambda text: "\ufeff" + text),
        ("CRLF", lambda text: text.replace("\n", "\r\n")),
        ("CR only (old Mac)", lambda text: text.replace("\n", "\r")),
        ("BOM and CRLF (Excel 'CSV UTF-8')", lambda text: "\ufeff" + text.replace("\n", "\r\n")),
        ("comment lines", lambda text: "# exported 2026-11-26\n# rig 3\n" + text),
        ("blank lines", lambda text: text.replace("\n", "\n\n", 20)),
        ("spaces around cells", lambda text: text.replace(",", " , ")),
        ("unicode minus in cells", lambda text: text.replace("-", "\u2212")),
        ("';' export with decimal commas (European Excel 'CSV')", _semicolon_export),
        ("';' export, Excel's BOM and CRLF", lambda text: "\ufeff" + _semicolon_export(text).replace("\n", "\r\n")),
        ("';' export with '.' decimals", lambda text: text.replace(",", ";")),
        (
            "';' export with decimal commas and comment lines holding '.' and ','",
            lambda text: "# exported 26.11.2026, rig 3\n" + _semicolon_export(text),
        ),
        (
            "quoted cells",
            lambda text: (
                "\n".join(
                    [text.splitlines()[0]]
                    + [",".join(f'"{c}"' for c in line.split(",")) for line in text.splitlines()[1:]]
                )
                + "\n"
            ),
        ),
    ],
)
def test_files_that_are_read_as_meant(tmp_path, name, transform):
    _same_as_good(_write(tmp_path, transform(GOOD_RECORD)))


def test_header_units_in_other_forms(tmp_path):
    """Header units go through the one unit parser: a micro sign, a typeset middle dot and spaces are fine."""
    text = record("time [ms],displacement [\u00b5m],force [kN]", t=_t * 1e3, x=_x * 1e3, F=_F / 1e3)
    _same_as_good(_write(tmp_path, text))


# ------------------------------------------------------------------------------------------ refused, one line each
CASES = [
    # (id, content, texts the message must hold)
    (
        "';' and ',' in the header",
        GOOD_RECORD.replace("time [s],", "time [s];", 1),
        ["line 1", "both ';' and ','", "which one separates the columns"],
    ),
    (
        "';' export with decimal commas and a '.' (a thousands separator?)",
        "\n".join(
            line if not line.startswith("0,02;") else "0,02;1.234,5;100"
            for line in _semicolon_export(GOOD_RECORD).splitlines()
        )
        + "\n",
        ["line 12", "'1.234,5'", "thousands separator"],
    ),
    ("decimal comma in a comma file", GOOD_RECORD.replace("\n0.02,", "\n0,02,", 1), ["line 12", "decimal comma"]),
    (
        "quoted decimal comma",
        GOOD_RECORD.replace("\n0.02,", '\n"0,02",', 1),
        ["line 12, column 1 (time)", "write 0.02"],
    ),
    (
        "digit separator",
        "\n".join(line if not line.startswith("0.02,") else "0.02,4_446.6,100" for line in GOOD_RECORD.splitlines())
        + "\n",
        ["line 12, column 2 (displacement)", "'4_446.6' is not a number; a digit separator"],
    ),
    ("arabic-indic digits", GOOD_RECORD.replace("\n0.02,", "\n\u0660.02,", 1), ["line 12, column 1", "not a number"]),
    (
        "unknown unit in the header",
        GOOD_RECORD.replace("force [N]", "force [Nm2]"),
        ["line 1, column 3 (force)", "unknown unit"],
    ),
    (
        "en dash in a header unit",
        GOOD_RECORD.replace("force [N]", "force [N\u2013m]"),
        ["line 1, column 3 (force)", "not a minus sign"],
    ),
    (
        "header unit with a control character",
        GOOD_RECORD.replace("force [N]", "force [N\x07]"),
        ["line 1, column 3 (force)", "control character"],
    ),
    (
        "1 MB header cell",
        HEADER + "x" * 1_000_000 + "\n" + "\n".join(GOOD_RECORD.splitlines()[1:]) + "\n",
        ["line 1", "1,000 characters"],
    ),
    ("1 MB data cell", GOOD_RECORD.replace("\n0.02,", "\n" + "9" * 1_000_000 + ",", 1), ["line 12", "characters"]),
    (
        "100 kB header cell (below csv's own limit)",
        HEADER + "," + "y" * 100_000 + " [s]\n",
        ["line 1, column 4", "100,004 characters"],
    ),
    ("time backwards", GOOD_RECORD.replace("\n0.02,", "\n0.001,", 1), ["line 12, column 1 (time)", "increase"]),
    (
        "temperature below absolute zero",
        record(HEADER + ",temperature [K]", extra=[np.full_like(_t, -10.0)]),
        ["column 4 (temperature [K])", "below absolute zero"],
    ),
    (
        "temperature below absolute zero in degF",
        record(HEADER + ",temperature [degF]", extra=[np.full_like(_t, -500.0)]),
        ["temperature", "below absolute zero"],
    ),
    ("binary junk", b"\x00\x01\x02\x03" * 100, ["binary", "NUL"]),
    ("UTF-16 export", GOOD_RECORD.encode("utf-16"), ["UTF-16", "save it as UTF-8"]),
    ("latin-1 bytes", GOOD_RECORD.replace("force [N]", "force [N]").encode("utf-8") + b"\xe9\xff", ["UTF-8"]),
]


@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_hostile_files_are_refused_in_one_line(tmp_path, case):
    _, content, needles = case
    path = _write(tmp_path, content)
    before = path.read_bytes()
    _refused(path, *needles)
    assert path.read_bytes() == before


def test_a_renamed_spreadsheet_is_named_as_one(tmp_path):
    """The issue: a renamed .xlsx gave 2,191 characters of binary; now one short line that says what it is."""
    path = tmp_path / "data.csv"
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("[Content_Types].xml", "<?xml version='1.0'?><Types/>" * 40)
        z.writestr("xl/worksheets/sheet1.xml", "<row><c>1.0</c></row>" * 500)
    message = _refused(path, "zip archive", "spreadsheet", "CSV")
    assert len(message) < 200


# ------------------------------------------------------------------------------------------ limits
def test_dev_zero_stops_at_once():
    """`fit /dev/zero` read until the memory ran out; the first chunk already shows a binary file."""
    start = time.perf_counter()
    with pytest.raises(MeasurementError, match="binary"):
        read_measurement("/dev/zero")
    assert time.perf_counter() - start < 2.0


def test_files_beyond_the_byte_limit_are_refused_without_reading_them_whole(tmp_path, monkeypatch):
    monkeypatch.setattr(measurement, "MAX_RECORD_BYTES", 10_000)
    path = _write(tmp_path, GOOD_RECORD)
    assert path.stat().st_size > 10_000
    _refused(path, "larger than 9.77 kB")
    read = []
    real = limits.read_input_bytes

    def counting(p, limit, what, label=None):
        read.append(limit)
        return real(p, limit, what, label)

    monkeypatch.setattr(measurement, "read_input_bytes", counting)
    _refused(path, "larger than")
    assert read == [10_000]


def test_rows_beyond_the_row_limit_are_refused(tmp_path, monkeypatch):
    monkeypatch.setattr(measurement, "MAX_RECORD_ROWS", 500)
    _refused(_write(tmp_path, GOOD_RECORD), "1,001 lines", "500 rows")


def test_read_records_refuses_a_device_and_a_huge_file(tmp_path, monkeypatch):
    with pytest.raises(Exception, match="not a regular file"):
        read_records("/dev/zero")
    from erdesign.data import readers

    monkeypatch.setattr(readers, "MAX_RECORD_BYTES", 1000)
    with pytest.raises(Exception, match="larger than"):
        read_records(_write(tmp_path, GOOD_RECORD))


def test_one_line_of_a_gigabyte_is_not_read_to_sniff_the_format(tmp_path, monkeypatch):
    """The format is decided from the first 64 kB: a file that is one endless line is not read whole to find its
    first line (a 3 MB line stands for it here)."""
    path = _write(tmp_path, "9" * 3_000_000)
    with pytest.raises(Exception) as info:
        read_records(path)
    assert len(str(info.value)) < MESSAGE_LIMIT


# ------------------------------------------------------------------------------------------ warned
def test_a_hole_in_the_time_column_is_said_with_its_size(tmp_path):
    """A 60 s hole in the time column passed without a word; the reader says so through the one detector
    (erdesign.data.findings.find_time_problems)."""
    t = np.where(_t > 1.0, _t + 60.0, _t)
    with pytest.warns(PlausibilityWarning, match=r"time: the time column has 1 hole \(60 s missing") as seen:
        read_measurement(_write(tmp_path, record(t=t)))
    assert any("1-61 s" in str(w.message) for w in seen)


def test_temperature_in_degc_labelled_kelvin_is_named(tmp_path):
    text = record(HEADER + ",temperature [K]", extra=[np.full_like(_t, 25.0)])
    with pytest.warns(PlausibilityWarning, match="read as degC they would be 25 to 25 degC"):
        m = read_measurement(_write(tmp_path, text))
    assert m.temperature[0] == 25.0  # read as written: the warning says what to check


def test_a_plausible_temperature_is_silent(tmp_path):
    text = record(HEADER + ",temperature [degC]", extra=[np.full_like(_t, 40.0)])
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        m = read_measurement(_write(tmp_path, text))
    assert m.temperature[0] == pytest.approx(313.15)
