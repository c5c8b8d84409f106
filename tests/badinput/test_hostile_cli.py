"""Issue 27: hostile input on the command line - devices and spreadsheets as records, look-alike signs and separators
in options and files, absurd currents, zero amplitudes, deep nesting, gigantic names - ends in one readable line
naming the argument, file or line (exit 1 or 2), never an internal error, a traceback, binary on the terminal or a
changed input.  The commands run in-process (:func:`erdesign.cli.main.main`), as in test_cli_corpus.py.
"""

from __future__ import annotations

import re
import shutil
import time
import zipfile

import pytest

from erdesign.cli.main import main
from erdesign.errors import MESSAGE_LIMIT

from .corpus import EXAMPLES, GOOD_RECORD, MAKRIS


def _run(capsys, args):
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


def _one_line_error(code, out, err, *needles):
    assert code in (1, 2), (code, out, err)
    assert "Traceback" not in err and "internal error" not in err.lower(), err
    lines = [line for line in err.splitlines() if line.strip() and not line.startswith("warning:")]
    assert len(lines) == 1, err
    line = lines[0]
    assert len(line) <= MESSAGE_LIMIT + 60 and line.isprintable(), line
    for needle in needles:
        assert needle in line, (needle, line)
    return line


def _xlsx(path):
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("[Content_Types].xml", "<?xml version='1.0'?><Types/>" * 40)
        z.writestr("xl/worksheets/sheet1.xml", "<row><c>1.0</c></row>" * 2000)
    return path


@pytest.fixture
def files(tmp_path):
    """The input files of the cases, and their bytes to check they are never changed."""
    made = {
        "damper": shutil.copy(EXAMPLES / "makris.toml", tmp_path / "d.toml"),
        "record": tmp_path / "m.csv",
        "xlsx": _xlsx(tmp_path / "renamed.csv"),
        "uminus": tmp_path / "uminus.toml",
        "nested": tmp_path / "nested.toml",
        "digits": tmp_path / "digits.toml",
        "longname": tmp_path / "longname.toml",
        "er_in_kam": tmp_path / "er_kam.toml",
        "comma_csv": tmp_path / "comma.csv",
        "deep_json": tmp_path / "deep.json",
        "xlsx_json": _xlsx(tmp_path / "p.json"),
    }
    made["deep_json"].write_text('{"parameters": ' + "[" * 100_000 + "]" * 100_000 + "}")
    made["record"].write_text(GOOD_RECORD)
    made["uminus"].write_text(MAKRIS.replace('gap = "0.8 mm"', 'gap = "\u22120.8 mm"'))
    made["nested"].write_text(MAKRIS.replace("[fluid]", "[fluid]\nx = " + "[" * 5000 + "]" * 5000, 1))
    made["digits"].write_text(MAKRIS.replace('viscosity = "7 Pa*s"', 'viscosity = "7_000 mPa*s"', 1))
    made["longname"].write_text(MAKRIS.replace('name = "makris-1996"', 'name = "' + "x" * 200_000 + '"'))
    made["er_in_kam"].write_text(
        MAKRIS.replace("[fluid]", '[fluid]\nmaterial = "lord-versaflo-er100"', 1).replace(
            'reference_field = "3 kV/mm"', 'reference_field = "40 kA/m"', 1
        )
    )
    made["comma_csv"].write_text(GOOD_RECORD.replace("\n0.02,", "\n0,02,", 1))
    assert 'viscosity = "7_000 mPa*s"' in made["digits"].read_text()
    return tmp_path, made


MR_COIL = str(EXAMPLES / "mr_coil.toml")

#: (id, arguments with {name} placeholders for the files fixture, texts the error line must hold)
ERROR_CASES = [
    ("fit /dev/zero", ["fit", "/dev/zero", "--damper", "{damper}"], ["/dev/zero", "binary"]),
    ("identify /dev/zero", ["identify", "/dev/zero", "--model", "bingham"], ["/dev/zero", "not a regular file"]),
    ("fit a renamed xlsx", ["fit", "{xlsx}", "--damper", "{damper}"], ["renamed.csv", "spreadsheet"]),
    ("identify a renamed xlsx", ["identify", "{xlsx}", "--model", "bingham"], ["renamed.csv", "spreadsheet"]),
    ("fit decimal comma", ["fit", "{comma_csv}", "--damper", "{damper}"], ["line 12", "decimal comma"]),
    ("size unicode-minus gap", ["size", "{uminus}", "--velocity", "1 in/s"], ["geometry.gap", "must be positive"]),
    ("size nested TOML", ["size", "{nested}", "--velocity", "1 in/s"], ["nested.toml", "nested too deeply"]),
    (
        "size digit separator in the file",
        ["size", "{digits}", "--velocity", "1 in/s"],
        ["fluid.viscosity", "digit separator", "'7000 mPa*s'"],
    ),
    ("size velocity en dash", ["size", "{damper}", "--velocity", "\u20131 in/s"], ["velocity", "en dash"]),
    ("size velocity decimal comma", ["size", "{damper}", "--velocity", "1,5 in/s"], ["velocity", "'1.5 in/s'"]),
    ("size velocity list", ["size", "{damper}", "--velocity", "1, 2 in/s"], ["velocity", "','"]),
    (
        "size field digit separator",
        ["size", "{damper}", "--velocity", "1 in/s", "--field", "3_000 V/mm"],
        ["field", "digit separator"],
    ),
    (
        "size bare number with a digit separator",
        ["size", "{damper}", "--velocity", "1_0"],
        ["velocity", "digit separator"],
    ),  # float() read it as 10 m/s
    (
        "size bare number in arabic-indic digits",
        ["size", "{damper}", "--velocity", "\u0661"],
        ["velocity", "ARABIC-INDIC DIGIT ONE"],
    ),
    (
        "magnetics bare number with a digit separator",
        ["magnetics", MR_COIL, "--current", "1_0"],
        ["--current", "digit separator"],
    ),
    ("size field bare unit", ["size", "{damper}", "--velocity", "1 in/s", "--field", "kV/mm"], ["field", "no number"]),
    (
        "size velocity control character",
        ["size", "{damper}", "--velocity", "1\x1b[2J in/s"],
        ["velocity", "control character"],
    ),
    (
        "report amplitude 0",
        ["report", "{damper}", "--amplitude", "0 mm", "--out", "{tmp}/a.html"],
        ["amplitude: must be positive, got '0 mm'"],
    ),
    (
        "report frequency 0",
        ["report", "{damper}", "--frequency", "0 Hz", "--out", "{tmp}/f.html"],
        ["frequency: must be positive"],
    ),
    (
        "report amplitude unicode minus",
        ["report", "{damper}", "--amplitude", "\u221210 mm", "--out", "{tmp}/u.html"],
        ["amplitude: must be positive"],
    ),
    ("magnetics 1e6 A", ["magnetics", MR_COIL, "--current", "1e6 A"], ["current", "A/mm^2", "melts"]),
    ("magnetics trailing comma", ["magnetics", MR_COIL, "--current", "1,2, A"], ["--current", "'A'", "no number"]),
    ("magnetics empty item", ["magnetics", MR_COIL, "--current", "1,,2 A"], ["--current", "empty item"]),
    ("magnetics digit separator", ["magnetics", MR_COIL, "--current", "1_5 A"], ["--current", "digit separator"]),
    (
        "simulate params deeply nested JSON",
        ["simulate", "{record}", "--model", "bingham", "--params", "{deep_json}"],
        ["--params", "deep.json", "nested too deeply"],
    ),
    (
        "simulate params a spreadsheet",
        ["simulate", "{record}", "--model", "bingham", "--params", "{xlsx_json}"],
        ["--params", "zip archive"],
    ),
    (
        "simulate params en dash",
        ["simulate", "{record}", "--model", "bingham", "--params", "f_c=\u2013100 N"],
        ["f_c", "en dash"],
    ),
]


def _argv(args, tmp, made):
    subs = {f"{{{k}}}": str(v) for k, v in made.items()} | {"{tmp}": str(tmp)}
    out = []
    for a in args:
        for k, v in subs.items():
            a = a.replace(k, v)
        out.append(a)
    return out


@pytest.mark.parametrize("case", ERROR_CASES, ids=[c[0] for c in ERROR_CASES])
def test_hostile_command_lines_end_in_one_line(case, files, capsys):
    _, args, needles = case
    tmp, made = files
    before = {p: p.read_bytes() for p in made.values()}
    start = time.perf_counter()
    code, out, err = _run(capsys, _argv(args, tmp, made))
    _one_line_error(code, out, err, *needles)
    assert time.perf_counter() - start < 60
    assert {p: p.read_bytes() for p in made.values()} == before
    assert not list(tmp.glob("*.html"))


def test_a_200k_character_damper_name_gives_a_short_report_name(files, capsys, monkeypatch):
    """A 200k-character damper name made a 200,052-character error line (the report's file name from it); the
    default name is cut to a file name the system takes, and every line printed stays readable."""
    tmp, made = files
    monkeypatch.chdir(tmp)
    code, out, err = _run(capsys, ["report", made["longname"], "--json"])
    assert code == 0, err[:500]
    written = [p for p in tmp.glob("*-report.html")]
    assert len(written) == 1 and len(written[0].name) == 112
    assert all(len(line) <= MESSAGE_LIMIT + 60 for line in err.splitlines())


def test_an_er_material_driven_in_ka_per_m_is_warned(files, capsys):
    tmp, made = files
    code, out, err = _run(capsys, ["size", made["er_in_kam"], "--velocity", "1 in/s", "--json"])
    assert code == 0
    assert re.search(
        r"^warning: fluid.reference_field: '40 kA/m' is a magnetic field, but material "
        r"'lord-versaflo-er100' is an ER fluid",
        err,
        re.M,
    ), err


def test_a_60_s_hole_in_time_is_said_by_identify(files, capsys):
    import numpy as np

    from .corpus import _t, record

    tmp, made = files
    path = tmp / "gap.csv"
    path.write_text(record(t=np.where(_t > 1.0, _t + 60.0, _t)))
    code, out, err = _run(capsys, ["identify", path, "--model", "bingham", "--json"])
    assert code == 0
    assert re.search(r"^warning: gap.csv: time: the time column has 1 hole \(60 s missing", err, re.M), err
