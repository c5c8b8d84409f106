"""Hostile input, sixth round (issue 27): what the fifth round left (a CSV cell of 1e-400 read as 0, an option given
twice of which the last silently won, ``Q_(series)`` failing inside pint, 'N-s/m' refused, 'ips' unknown), then
classes no round had tried or had tried thinly: several records to ``diagnose`` (other rates and units, one empty,
one a copy of another, the same file twice), ``--force-noise`` values, damper files of single-ended dampers with a
gas accumulator, batch manifests (relative paths, absent files, a folder, a pattern), a reader that closes the pipe,
SIGTERM during a command, NUL bytes and very long lines in every text input, numbers written the way a locale
writes them, and the API fed lists of texts, true/false, complex numbers, 0-d arrays, dates and DataFrames.  Each
ends in one readable line naming the argument, key, file or line, or in a warning naming it; inputs are never
changed.  The commands run in-process but for the pipe and the batch under SIGTERM.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import threading
import time
import warnings
from pathlib import Path

import click
import numpy as np
import pandas as pd
import pytest

import erdesign
from erdesign import Q_, Measurement
from erdesign.errors import MESSAGE_LIMIT, ErdesignError, PlausibilityWarning
from erdesign.units import to_si

from .corpus import _F, _t, _x, EXAMPLES, GOOD_RECORD, MAKRIS, MAKRIS_FLUID, MAKRIS_GEOMETRY, record
from .test_hostile_cli import _one_line_error, _run

ROOT = Path(__file__).resolve().parents[2]
HEADER = "time [s],displacement [mm],force [N]"
BODY = GOOD_RECORD.splitlines()[1:]
SPENCER = (EXAMPLES / "spencer1997.toml").read_text()


def _lines(*lines: str) -> str:
    return "\n".join(lines) + "\n"


def _one_line(message: str) -> str:
    assert "\n" not in message and len(message) <= MESSAGE_LIMIT and message.isprintable(), message
    return message


# ====================================================================================== round 5's leftovers
# ------------------------------------------------------------------ 1. a number too small for a float in a CSV
@pytest.mark.parametrize(
    "row, where",
    [
        ("0.02,1,1e-400", "line 12, column 3 (force): '1e-400'"),
        ("0.02,-1e-400,3", "line 12, column 2 (displacement): '-1e-400'"),
        ("0.02,1,5E-0400", "line 12, column 3 (force): '5E-0400'"),
        ("0.02,1,2.5e-330", "line 12, column 3 (force): '2.5e-330'"),
        ("0.02,1,1e-9999", "line 12, column 3 (force): '1e-9999'"),
        ("0.02,1,\u22121e-400", "line 12, column 3 (force)"),  # a typeset minus
    ],
)
def test_a_number_too_small_for_a_float_is_refused_naming_line_and_column(row, where, tmp_path):
    """It was read as 0 without a word, on the fast path (pandas, pyarrow, numpy) and line by line alike."""
    path = tmp_path / "r.csv"
    text = _lines(HEADER, *BODY[:10], row, *BODY[11:])
    path.write_text(text)
    for quoted in (False, True):  # a quoted file goes to the line-by-line reader
        if quoted:
            path.write_text(_lines(HEADER, *('"' + r.replace(",", '","') + '"' for r in (*BODY[:10], row, *BODY[11:]))))
        with pytest.raises(ErdesignError) as info:
            erdesign.read_measurement(path)
        message = _one_line(str(info.value))
        assert where in message and "too small to compute with" in message and "read as 0" in message, message


def test_zeros_and_small_numbers_that_fit_are_read():
    """'0e-400' is 0, 1e-300 is 1e-300 and 1e-5 is 1e-5: only a number read as 0 though it is not is refused."""
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "r.csv"
        path.write_text(_lines(HEADER, *BODY[:10], "0.02,0e-400,1e-300", *BODY[11:]))
        m = erdesign.read_measurement(path)
        assert m.displacement[10] == 0.0 and m.force[10] == 1e-300


# ------------------------------------------------------------------ 2. an option given twice
def _one_value_options():
    """(command, flag, nargs) of every option of every command that takes one value (not a flag, not multiple)."""
    import importlib

    from erdesign.cli.main import COMMANDS, cli

    for module, _ in COMMANDS.values():
        importlib.import_module(f"erdesign.cli.{module}")
    for name in sorted(cli.commands):
        for p in cli.commands[name].params:
            if isinstance(p, click.Option) and not (p.multiple or p.count or p.is_flag) and p.name:
                yield name, max(p.opts, key=len), p.nargs


ONE_VALUE_OPTIONS = list(_one_value_options())


@pytest.mark.parametrize("command, flag, nargs", ONE_VALUE_OPTIONS, ids=[f"{c} {f}" for c, f, _ in ONE_VALUE_OPTIONS])
def test_an_option_that_takes_one_value_is_refused_twice(command, flag, nargs, capsys, tmp_path, monkeypatch):
    """``--damper a.toml --damper b.toml`` kept b.toml without a word (click keeps the last)."""
    monkeypatch.chdir(tmp_path)
    args = [command, flag, *["a"] * nargs, flag, *["b"] * nargs]
    code, out, err = _run(capsys, args)
    line = _one_line_error(code, out, err, f"{flag} is given more than once")
    assert code == 2 and line.startswith(f"erdesign {command}: "), line
    assert not list(tmp_path.iterdir())


def test_there_are_options_to_check_and_flags_and_lists_may_repeat(capsys):
    assert len(ONE_VALUE_OPTIONS) >= 80
    code, out, err = _run(capsys, ["size", "makris", "--velocity", "0.1 m/s", "--json", "--json"])
    assert code == 0, err
    code, out, err = _run(capsys, ["report", "makris", "--field", "1 kV/mm", "--field", "2 kV/mm", "--help"])
    assert code == 0, err


# ------------------------------------------------------------------ 3. pandas objects as magnitudes of Q_
M = erdesign.load_example("makris")
DUCT = ("1.8 kPa", "13 Pa*s", "54.6 mm", "14.3 mm", "0.8 mm")


def test_q_of_a_series_is_the_quantity_of_its_numbers():
    v = np.array([0.1, 0.2])
    frame = pd.DataFrame({"t": [0.0, 1.0], "v": v, "note": ["a", "b"]})
    expected = M.force(Q_(v, "m/s")).to("N").magnitude
    for series in (pd.Series(v), frame["v"], pd.Series(v, index=[9, 4]), pd.Series(v, dtype="Float64")):
        np.testing.assert_array_equal(M.force(Q_(series, "m/s")).to("N").magnitude, expected)
    dp = erdesign.bingham_pressure_drop(Q_(pd.Series([1.0, 2.0]), "mL/s"), *DUCT).to("Pa").magnitude
    np.testing.assert_array_equal(dp, erdesign.bingham_pressure_drop(Q_([1.0, 2.0], "mL/s"), *DUCT).to("Pa").magnitude)
    assert isinstance(Q_(frame["v"], "m/s"), Q_) and isinstance(Q_(1, "m"), erdesign.ureg.Quantity)
    assert Q_.from_list([Q_(1, "m"), Q_(2, "m")]).to("mm").magnitude.tolist() == [1000.0, 2000.0]


@pytest.mark.parametrize(
    "call, needles",
    [
        (lambda: Q_(pd.DataFrame({"v": [0.1], "F": [1.0]}), "m/s"), ["Q_: got a DataFrame of 2 column(s)", "'v'"]),
        (lambda: Q_(pd.DataFrame({"v": [0.1]}), "m/s"), ["give one column, e.g. Q_(frame['v'], 'm/s')"]),
        (lambda: M.force(Q_(pd.Series([0.1, None], dtype="Float64"), "m/s")), ["velocity:", "finite"]),
        (lambda: Q_(True, "m/s"), ["Q_: Invalid magnitude for Quantity: True"]),
        (lambda: Q_({"v": 1}, "m/s"), ["Q_:", "give a number or an array of numbers"]),
        (lambda: M.force(Q_(pd.Series([True, False]), "m/s")), ["velocity:", "true/false"]),
        (lambda: M.force(Q_(pd.Series(pd.to_datetime(["2024-01-01"])), "m/s")), ["velocity:"]),
    ],
    ids=["frame", "frame of one column", "nullable NA", "bool", "dict", "Series of bools", "Series of dates"],
)
def test_q_of_what_is_not_numbers_names_it(call, needles):
    with pytest.raises(ErdesignError) as info:
        call()
    message = _one_line(str(info.value))
    assert all(n in message for n in needles), message


# ------------------------------------------------------------------ 4. hyphen products, 5. 'ips'
@pytest.mark.parametrize(
    "text, same_as, unit",
    [
        ("1 N-s/m", "1 N*s/m", "N*s/m"),
        ("2.5 kN-s/m", "2.5 kN*s/m", "N*s/m"),
        ("1 lbf-s/in", "1 lbf*s/in", "N*s/m"),
        ("3 N-m", "3 N*m", "N*m"),
        ("3 kN-m", "3 kN*m", "N*m"),
        ("7 Pa-s", "7 Pa*s", "Pa*s"),
        ("7000 mPa-s", "7000 mPa*s", "Pa*s"),
        ("1 (N-s)/m", "1 N*s/m", "N*s/m"),
        ("1 N-s-m^-1", "1 N*s/m", "N*s/m"),
        ("1 ft-lbf", "1 ft*lbf", "N*m"),
        ("2 ips", "2 in/s", "m/s"),
        ("2 ips", "0.0508 m/s", "m/s"),
        ("1 lbf/ips", "1 lbf*s/in", "N*s/m"),
    ],
)
def test_hyphen_products_and_ips_are_read_as_meant(text, same_as, unit):
    assert to_si(text, unit, "x") == pytest.approx(to_si(same_as, unit, "x"), rel=1e-12)


@pytest.mark.parametrize(
    "text, unit, said",
    [
        ("1 N/m-s", "N*s/m", "a '-' after '/', which is ambiguous"),
        ("1 W/m-K", "W/m/K", "e.g. 'W/(m*K)'"),
        ("1 kg/m-s", "Pa*s", "e.g. 'kg/(m*s)'"),
        ("0.8 mm-0.9 mm", "m", "a range"),  # was "a power without '^'; write e.g. 'mm^-0'"
        ("1 mm-2 mm", "m", "a range"),
        ("1 N m-1 s", "N*s/m", "a power without '^'"),
        ("1 N- s/m", "N*s/m", "a '-' between units"),
        ("1 ips", "N", "expected a force"),
        ("1 IPS", "m/s", "x: unknown unit"),
    ],
)
def test_ambiguous_hyphens_are_refused_with_the_spelling(text, unit, said):
    with pytest.raises(ErdesignError) as info:
        to_si(text, unit, "x")
    message = _one_line(str(info.value))
    assert message.startswith("x: ") and said in message, message


def test_ips_on_the_command_line_and_in_a_record(capsys, tmp_path):
    a = _run(capsys, ["size", "makris", "--velocity", "1 ips", "--json"])
    b = _run(capsys, ["size", "makris", "--velocity", "1 in/s", "--json"])
    assert a[0] == 0 and a[1] == b[1], a
    path = tmp_path / "v.csv"
    path.write_text(
        record(
            "time [s],displacement [in],force [lbf],velocity [ips]",
            x=_x / 25.4,
            F=_F / 4.448,
            extra=[np.gradient(_x / 25.4, _t)],
        )
    )
    m = erdesign.read_measurement(path)
    np.testing.assert_allclose(m.velocity, np.gradient(_x, _t) * 1e-3, rtol=1e-9)


# ====================================================================================== round 6
# ------------------------------------------------------------------ several records to diagnose
@pytest.fixture
def recs(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    files = {
        "A.csv": GOOD_RECORD,
        "empty.csv": "",
        "header.csv": HEADER + "\n",
        "nul.csv": GOOD_RECORD.replace("\n0.02,", "\n0.02\x00,", 1),
        "dates.csv": _lines(
            HEADER, *(f"2024-01-01T00:00:{float(r.split(',')[0]):09.6f},{r.split(',', 1)[1]}" for r in BODY)
        ),
        "extra.csv": record(HEADER + ",comment", extra=[np.zeros_like(_t)]),
        "nan.csv": GOOD_RECORD.replace("\n0.02,", "\nNaN,", 1),
        "tiny.csv": GOOD_RECORD.replace("\n0,", "\n1e-400,", 1),
        "bigcell.csv": GOOD_RECORD.replace("\n0.02,", "\n0.02," + "1" * 5000 + ",", 1),
        "longline.csv": "# " + "x" * 300_000 + "\n" + GOOD_RECORD,
        "d.toml": MAKRIS,
    }
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    (tmp_path / "sub").mkdir()
    yield tmp_path
    for name, text in files.items():
        assert (tmp_path / name).read_text() == text, name


DIAGNOSE_ERRORS = [
    ("an empty file", ["A.csv", "empty.csv"], ["empty.csv: empty file"]),
    ("a header only", ["A.csv", "header.csv"], ["header.csv: 0 data rows"]),
    ("no such file", ["A.csv", "nope.csv"], ["nope.csv: no such file"]),
    ("a folder", ["A.csv", "sub"], ["sub: is a folder"]),
    ("an empty name", ["A.csv", ""], ["path: an empty file name ''"]),  # was ".: is a folder"
    ("a blank name", ["A.csv", "  "], ["path: an empty file name"]),
    ("a pattern that matched nothing", ["*.xyz"], ["*.xyz: no such file; a pattern", "not expanded"]),
    ("NUL bytes", ["A.csv", "nul.csv"], ["nul.csv: a binary file (it holds NUL bytes)"]),
    ("dates as time", ["dates.csv"], ["dates.csv: line 2, column 1 (time): '2024-01-01T00:00:00.000000'"]),
    ("a column without a unit", ["extra.csv"], ["extra.csv: line 1, column 4 ('comment')"]),
    ("NaN time", ["nan.csv"], ["nan.csv: line 12, column 1 (time): 'NaN' is not a finite number"]),
    ("an underflow", ["tiny.csv"], ["tiny.csv: line 2, column 1 (time): '1e-400' is too small"]),
    ("a 5000-digit cell", ["bigcell.csv"], ["bigcell.csv: line 12"]),
    ("the damper as a record", ["d.toml"], ["d.toml: line 4, column 1"]),
]


@pytest.mark.parametrize("case", DIAGNOSE_ERRORS, ids=[c[0] for c in DIAGNOSE_ERRORS])
def test_several_records_to_diagnose_name_the_bad_one(case, recs, capsys):
    _, records, needles = case
    code, out, err = _run(capsys, ["diagnose", *records, "--damper", "d.toml"])
    _one_line_error(code, out, err, *needles)


@pytest.mark.parametrize(
    "damper, needles",
    [("A.csv", ["A.csv: invalid TOML"]), ("", ["path: an empty file name"]), ("sub", ["sub: is a directory"])],
)
def test_a_bad_damper_for_several_records_is_named(damper, needles, recs, capsys):
    code, out, err = _run(capsys, ["diagnose", "A.csv", "A.csv", "--damper", damper])
    _one_line_error(code, out, err, *needles)


def test_a_record_given_twice_is_warned_naming_both(recs, capsys):
    """A.csv A.csv (or a copy under another name) counted twice in the calibration without a word."""
    shutil.copy(recs / "A.csv", recs / "copy.csv")
    code, out, err = _run(capsys, ["diagnose", "A.csv", "copy.csv", "A.csv", "--damper", "d.toml", "--json"])
    assert code == 0, err
    said = [line for line in err.splitlines() if "the same samples as" in line]
    assert said == [
        "warning: copy.csv (2): the same samples as A.csv (1): the record counts twice in the calibration; give each "
        "record once",
        "warning: A.csv (3): the same samples as A.csv (1): the record counts twice in the calibration; give each "
        "record once",
    ], err
    assert "Traceback" not in err and out.startswith("{")


def test_records_of_other_rates_and_units_are_not_called_copies():
    from erdesign.diagnosis.calibration import _as_records

    a = Measurement.from_arrays(_t, _x * 1e-3, _F, name="a.csv")
    half = Measurement.from_arrays(_t[::2], _x[::2] * 1e-3, _F[::2], name="half.csv")
    moved = Measurement.from_arrays(_t + 1.0, _x * 1e-3, _F, name="later.csv")
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        assert [r.name for r in _as_records([a, half, moved])] == ["a.csv", "half.csv", "later.csv"]
    with pytest.warns(PlausibilityWarning, match=r"^record 2: the same samples as record 1"):
        _as_records([Measurement.from_arrays(_t, _x, _F), Measurement.from_arrays(_t, _x, _F)])


# ------------------------------------------------------------------ --force-noise
FORCE_NOISE_ERRORS = [
    ("-5 N", "must be a positive force"),
    ("0 N", "must be a positive force"),
    ("-0 N", "must be a positive force"),
    ("5", "expected a force (a value with a unit such as 'N'), got '5' (a plain number)"),
    ("0", "a plain number"),
    ("5 N/m", "(a stiffness)"),
    ("5 N-m", "expected a force"),
    ("nan N", "value must be finite"),
    ("inf N", "value must be finite"),
    ("", "cannot read ''"),
    ("1e-400 N", "too small to compute with"),
    ("5 N N", "expected a force"),
    ("5 %", "a plain number"),
    ("5 kg", "(a mass)"),
    ("five N", "it has no number"),
    ("5 ips", "(a velocity)"),
    ("5,0 N", "a decimal comma"),
    ("1 000 N", "a space between digits"),
    ("5 N\x00", "control character"),
    ("5 N" + " " * 300, "too long"),
]


@pytest.mark.parametrize("value, said", FORCE_NOISE_ERRORS, ids=[repr(v[0])[:20] for v in FORCE_NOISE_ERRORS])
def test_force_noise_values_are_named(value, said, recs, capsys):
    code, out, err = _run(capsys, ["diagnose", "A.csv", "--damper", "d.toml", "--force-noise", value])
    _one_line_error(code, out, err, "--force-noise", said)


@pytest.mark.parametrize("value", ["5 kg", "-5 N", "nan N"])
def test_a_batchs_force_noise_is_named_before_any_record_runs(value, recs, capsys):
    code, out, err = _run(
        capsys, ["batch", "fit", "A.csv", "--damper", "d.toml", "--force-noise", value, "--out", "t.csv"]
    )
    _one_line_error(code, out, err, "--force-noise")
    assert not (recs / "t.csv").exists()


@pytest.mark.parametrize(
    "given, warned", [("5 kN", True), ("1e9 N", True), (5000.0, True), ("5 N", False), ("1e-12 N", False)]
)
def test_a_force_noise_above_the_forces_own_spread_is_warned(given, warned):
    """'5 kN' for '5 N' made every residual sit below the floor: "nothing missing", whatever was missing."""
    from erdesign.data.noise_floor import estimate_noise_floor

    rec = Measurement.from_arrays(_t, _x * 1e-3, _F, name="a.csv")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        floor = estimate_noise_floor(rec, force_noise=given)
    said = [str(w.message) for w in caught if issubclass(w.category, PlausibilityWarning)]
    assert floor.method == "given"
    if warned:
        assert len(said) == 1 and said[0].startswith("force_noise: ") and "in a.csv" in said[0], said
        assert "2980 N standard deviation" in said[0] and "is the unit right?" in said[0], said
    else:
        assert not said, said


def test_force_noise_as_a_0d_array_is_the_number_of_newtons():
    from erdesign.data.noise_floor import estimate_noise_floor

    rec = Measurement.from_arrays(_t, _x * 1e-3, _F)
    assert estimate_noise_floor(rec, force_noise=np.array(5.0)).esr == estimate_noise_floor(rec, force_noise=5.0).esr


def test_exclude_clipped_on_a_record_with_nothing_clipped_changes_nothing():
    from erdesign.data.findings import excluded_mask, find_data_problems

    rec = Measurement.from_arrays(_t, _x * 1e-3, _F)
    found = find_data_problems(rec, exclude_clipped=True)
    assert not any(f.kind == "clipped" for f in found)
    assert not excluded_mask(found, len(rec)).any()


# ------------------------------------------------------------------ single-ended dampers with an accumulator
def _spencer(old: str, new: str) -> str:
    assert old in SPENCER, old
    return SPENCER.replace(old, new, 1)


_PRE, _VOL, _N = 'precharge = "0.91 MPa"', 'gas_volume = "15.7 cm^3"', "polytropic_index = 1.4"
ACCUMULATOR_CASES = [
    ("no precharge", _spencer(_PRE, ""), "error", ["accumulator.precharge: missing"]),
    ("no gas volume", _spencer(_VOL, ""), "error", ["accumulator.gas_volume: missing"]),
    ("negative precharge", _spencer(_PRE, 'precharge = "-0.91 MPa"'), "error", ["accumulator.precharge: must be pos"]),
    ("zero precharge", _spencer(_PRE, 'precharge = "0 MPa"'), "error", ["accumulator.precharge: must be positive"]),
    ("zero volume", _spencer(_VOL, 'gas_volume = "0 cm^3"'), "error", ["accumulator.gas_volume: must be positive"]),
    ("negative volume", _spencer(_VOL, 'gas_volume = "-15.7 cm^3"'), "error", ["accumulator.gas_volume: must be"]),
    # 1e30 Pa and 1e-30 m^3 were only warned: the gas spring then swamped every force
    (
        "precharge 1e30 Pa",
        _spencer(_PRE, 'precharge = "1e30 Pa"'),
        "error",
        ["precharge: 1e+24 MPa is outside the pos"],
    ),
    ("precharge 1 Pa", _spencer(_PRE, 'precharge = "1 Pa"'), "error", ["accumulator.precharge: 1e-06 MPa is outside"]),
    ("volume 1e-30 m^3", _spencer(_VOL, 'gas_volume = "1e-30 m^3"'), "error", ["gas_volume: 1e-24 cm^3 is outside"]),
    ("volume 15.7 m^3", _spencer(_VOL, 'gas_volume = "15.7 m^3"'), "error", ["gas_volume: 1.57e+07 cm^3 is outside"]),
    ("precharge a force", _spencer(_PRE, 'precharge = "0.91 MN"'), "error", ["accumulator.precharge", "(a force)"]),
    ("precharge bare text", _spencer(_PRE, 'precharge = "0.91"'), "error", ["precharge", "(a plain number)"]),
    ("precharge a number", _spencer(_PRE, "precharge = 0.91"), "error", ["accumulator.precharge: 0.91 has no unit"]),
    ("precharge nan", _spencer(_PRE, 'precharge = "nan MPa"'), "error", ["accumulator.precharge", "finite"]),
    ("precharge decimal comma", _spencer(_PRE, 'precharge = "0,91 MPa"'), "error", ["precharge", "decimal comma"]),
    ("precharge grouped", _spencer(_PRE, 'precharge = "910 000 Pa"'), "error", ["precharge", "space between digits"]),
    ("volume a length", _spencer(_VOL, 'gas_volume = "15.7 cm"'), "error", ["accumulator.gas_volume", "(a length)"]),
    ("volume cm3", _spencer(_VOL, 'gas_volume = "15.7 cm3"'), "error", ["gas_volume", "'cm^3'"]),
    ("volume inf", _spencer(_VOL, 'gas_volume = "inf cm^3"'), "error", ["accumulator.gas_volume", "finite"]),
    ("index 0.5", _spencer(_N, "polytropic_index = 0.5"), "error", ["accumulator.polytropic_index: must lie"]),
    ("index text", _spencer(_N, 'polytropic_index = "1.4"'), "error", ["accumulator.polytropic_index: expected a"]),
    ("index nan", _spencer(_N, "polytropic_index = nan"), "error", ["accumulator.polytropic_index", "finite"]),
    ("index true", _spencer(_N, "polytropic_index = true"), "error", ["accumulator.polytropic_index"]),
    ("double rod", _spencer('rod = "single"', 'rod = "double"'), "error", ["accumulator: a gas accumulator pushes"]),
    ("no rod key", _spencer('rod = "single"', ""), "error", ['add rod = "single" to [geometry]']),
    ("rod Single", _spencer('rod = "single"', 'rod = "Single"'), "error", ["geometry.rod", "did you mean 'single'?"]),
    ("rod a number", _spencer('rod = "single"', "rod = 1"), "error", ["geometry.rod: must be one of"]),
    (
        "unknown key",
        _spencer("[accumulator]", '[accumulator]\ntemperature = "20 degC"'),
        "error",
        ["accumulator.temperature: unknown key"],
    ),
    ("[Accumulator]", _spencer("[accumulator]", "[Accumulator]"), "error", ["did you mean 'accumulator'?"]),
    ("a table inside", _spencer("[accumulator]", "[accumulator.gas]"), "error", ["accumulator.gas"]),
    ("a NUL byte", _spencer(_PRE, 'precharge = "0.91 MPa\x00"'), "error", ["a binary file (it holds NUL bytes)"]),
    ("precharge key twice", _spencer(_PRE, _PRE + "\n" + _PRE), "error", ["'precharge' is given twice"]),
    ("precharge 910 MPa", _spencer(_PRE, 'precharge = "910 MPa"'), "warning", ["accumulator.precharge: 910 MPa"]),
    ("volume 0.5 cm^3", _spencer(_VOL, 'gas_volume = "0.5 cm^3"'), "warning", ["accumulator.gas_volume: 0.5 cm^3"]),
    ("precharge in bar", _spencer(_PRE, 'precharge = "9.1 bar"'), "ok", []),
    ("precharge in psi", _spencer(_PRE, 'precharge = "132 psi"'), "ok", []),
    ("volume in mL", _spencer(_VOL, 'gas_volume = "15.7 mL"'), "ok", []),
    ("no [accumulator]", SPENCER.split("[accumulator]")[0], "ok", []),
]


@pytest.mark.parametrize("case", ACCUMULATOR_CASES, ids=[c[0] for c in ACCUMULATOR_CASES])
def test_accumulator_damper_files(case, tmp_path, capsys):
    _, text, expect, needles = case
    path = tmp_path / "sp.toml"
    path.write_text(text)
    code, out, err = _run(capsys, ["size", path, "--velocity", "0.1 m/s"])
    if expect == "error":
        _one_line_error(code, out, err, str(path), *needles)
    else:
        assert code == 0 and "Traceback" not in err, err
        warned = [line for line in err.splitlines() if line.startswith("warning:")]
        assert (len(warned) == 1 and all(n in warned[0] for n in needles)) if expect == "warning" else not warned, err
    assert path.read_text() == text


def test_an_accumulator_made_in_code_is_refused_beyond_the_possible():
    from erdesign.damper.accumulator import Accumulator

    with pytest.raises(ErdesignError, match=r"^accumulator\.precharge: 1e\+24 MPa is outside the possible range"):
        Accumulator(precharge=1e30, gas_volume=1e-5)
    with pytest.raises(ErdesignError, match=r"^accumulator\.gas_volume: 1e-24 cm\^3 is outside the possible range"):
        Accumulator(precharge=1e6, gas_volume=1e-30)
    assert Accumulator(precharge=1e6, gas_volume=1e-5).stiffness(0.01) > 0


# ------------------------------------------------------------------ batch manifests
@pytest.fixture
def batch_dir(tmp_path, monkeypatch):
    (tmp_path / "A.csv").write_text(GOOD_RECORD)
    (tmp_path / "d.toml").write_text(MAKRIS)
    (tmp_path / "sub").mkdir()
    shutil.copy(tmp_path / "A.csv", tmp_path / "sub" / "A.csv")
    monkeypatch.chdir(ROOT)  # the manifest's paths are relative to its folder, not to the current one
    return tmp_path


MANIFEST_ROW_ERRORS = [
    ("an absent file", "record\nnope.csv\n", "nope.csv: no such file"),
    ("a folder", "record\nsub\n", "sub: is a folder, expected a measurement CSV file"),
    ("a pattern", "record\n*.csv\n", "*.csv: no such file; a pattern ('*', '?') that matched no file?"),
    ("the manifest itself", "record\nm.csv\n", "m.csv: line 1, column 1 ('record')"),
    ("a tilde", "record\n~/A.csv\n", "~/A.csv: no such file"),
    ("a URL", "record\nhttps://example.com/A.csv\n", "https://example.com/A.csv: no such file"),
    ("a missing damper", "record,damper\nA.csv,none.toml\n", "none.toml: no such file"),
    ("a folder as damper", "record,damper\nA.csv,sub\n", "sub: is a directory, expected a TOML file"),
    ("an unknown effect", "record,effects\nA.csv,warp_drive\n", "unknown effect 'warp_drive'"),
]


@pytest.mark.parametrize("case", MANIFEST_ROW_ERRORS, ids=[c[0] for c in MANIFEST_ROW_ERRORS])
def test_a_bad_row_of_a_manifest_is_a_row_with_its_error(case, batch_dir, capsys):
    _, text, said = case
    (batch_dir / "m.csv").write_text(text)
    out = batch_dir / "t.csv"
    code, stdout, err = _run(
        capsys,
        [
            "batch",
            "fit",
            "--manifest",
            batch_dir / "m.csv",
            "--damper",
            batch_dir / "d.toml",
            "--out",
            out,
            "--jobs",
            "1",
        ],
    )
    assert code == 0 and "Traceback" not in err, err
    table = pd.read_csv(out)
    assert table.loc[0, "status"] == "error" and said in table.loc[0, "error"], table.loc[0, "error"]


def test_a_manifests_relative_paths_are_read_from_its_folder(batch_dir, capsys):
    (batch_dir / "m.csv").write_text("record\nA.csv\nsub/A.csv\n")
    code, _, err = _run(
        capsys,
        [
            "batch",
            "fit",
            "--manifest",
            batch_dir / "m.csv",
            "--damper",
            batch_dir / "d.toml",
            "--out",
            batch_dir / "t.csv",
            "--jobs",
            "1",
        ],
    )
    assert code == 0, err
    table = pd.read_csv(batch_dir / "t.csv")
    assert list(table["status"]) == ["ok", "ok"] and table["esr"][0] == table["esr"][1]


MANIFEST_ERRORS = [
    ("empty", "", ["has no 'record' column (columns: none)"]),
    ("a header only", "record\n", ["lists no record"]),
    ("NUL bytes", b"record\nA.csv\x00\n", ["a binary file (it holds NUL bytes)"]),
    ("a 2 MB line", "record\n" + "x" * 2_000_000 + ".csv\n", ["larger than 1 MB"]),
    ("Latin-1", "record\nA\xe9.csv\n".encode("latin-1"), ["line 2: byte 0xe9 is not UTF-8"]),
    ("UTF-16", "record\nA.csv\n".encode("utf-16"), ["UTF-16 text"]),
    ("an unnamed column", "record,\nA.csv,x\n", ["unknown column(s) ''"]),  # was "unknown column(s) ;"
    ("an unknown column", "record,notes\nA.csv,x\n", ["unknown column(s) 'notes'"]),
    ("an empty record", 'record\n""\n', ["line 2: empty 'record'"]),
]


@pytest.mark.parametrize("case", MANIFEST_ERRORS, ids=[c[0] for c in MANIFEST_ERRORS])
def test_a_bad_manifest_is_one_line(case, batch_dir, capsys):
    _, text, needles = case
    path = batch_dir / "m.csv"
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    code, out, err = _run(
        capsys, ["batch", "fit", "--manifest", path, "--damper", "d.toml", "--out", batch_dir / "t.csv"]
    )
    _one_line_error(code, out, err, "--manifest", *needles)
    assert not (batch_dir / "t.csv").exists()


@pytest.mark.parametrize(
    "args, needles",
    [
        (["--manifest", "{d}/none.csv"], ["--manifest: no such file"]),
        (["--manifest", "{d}"], ["--manifest", "cannot be read"]),
        (["{d}/A.csv", "--manifest", "{d}/A.csv"], ["not both"]),
        ([], ["give the records, or a manifest"]),
        (["{d}/A.csv", "--out", "{d}/t.txt"], ["must end in .csv or .parquet"]),
    ],
    ids=["no manifest file", "a folder as manifest", "records and a manifest", "nothing", "a .txt table"],
)
def test_batch_arguments_are_named(args, needles, batch_dir, capsys):
    args = [a.replace("{d}", str(batch_dir)) for a in args]
    out = [] if "--out" in args else ["--out", str(batch_dir / "t.csv")]
    code, stdout, err = _run(capsys, ["batch", "fit", *args, "--damper", "d.toml", *out])
    _one_line_error(code, stdout, err, *needles)


def _run_batch(*args, **kw):
    from erdesign.campaign.batch import run_batch

    return run_batch(*args, **kw)


@pytest.mark.parametrize(
    "kw, said",
    [
        # a text was a batch of its characters: records 'A', '.', 'c', 's', 'v', each "no such file"
        (dict(records="A.csv"), "records: expected a list of record files, got str 'A.csv'; for one, give ['A.csv']"),
        (dict(records=[None]), "records[0]: expected the name of a record file (a str or Path), got NoneType None"),
        (dict(records=["A.csv", Measurement.from_arrays(_t, _x, _F)]), "records[1]: expected the name"),
        (dict(records=["A.csv", ""]), "records[1]: expected the name of a record file"),
        (dict(records=["A.csv"], damper=M), "damper: expected the name of a damper file or of a bundled example"),
        (dict(records=["A.csv"], effects=True), "effects: expected effect names separated by commas"),
        (dict(records=["A.csv"], options=["exclude_clipped"]), "options: expected a mapping"),
        (dict(records=["A.csv"], jobs=True), "jobs must be a whole number >= 1, got True"),
    ],
    ids=["a text", "None", "a Measurement", "an empty name", "a Damper", "effects True", "options a list", "jobs True"],
)
def test_run_batch_names_its_arguments(kw, said, batch_dir):
    """Raw TypeErrors and AttributeErrors from inside Python before ("expected str, bytes or os.PathLike object")."""
    kw = {"damper": "makris", **kw}
    with pytest.raises(ErdesignError) as info:
        _run_batch("fit", **kw)
    message = _one_line(str(info.value))
    assert message.startswith(said), message


# ------------------------------------------------------------------ NUL bytes and very long lines in every input
def _requirements(text: str) -> str:
    return text


TEXT_INPUTS = [
    (
        "record NUL in a cell",
        "m.csv",
        GOOD_RECORD.replace("\n0.02,", "\n0.02\x00,", 1),
        ["fit", "{f}", "--damper", "makris"],
        ["a binary file (it holds NUL bytes)"],
    ),
    (
        "record NUL in the header",
        "m.csv",
        GOOD_RECORD.replace("force [N]", "force\x00 [N]"),
        ["fit", "{f}", "--damper", "makris"],
        ["a binary file"],
    ),
    (
        "record a 2000-character header cell",
        "m.csv",
        GOOD_RECORD.replace("force [N]", "force" + " " * 2000 + "[N]", 1),
        ["fit", "{f}", "--damper", "makris"],
        ["line 1, column 3", "characters"],
    ),
    (
        "record a 300000-character data line",
        "m.csv",
        _lines(HEADER, *BODY[:5], ",".join(["1"] * 150_000), *BODY[5:]),
        ["fit", "{f}", "--damper", "makris"],
        ["line 7: 150000 cells"],
    ),
    (
        "damper NUL",
        "d.toml",
        MAKRIS.replace('name = "makris-1996"', 'name = "m\x00"'),
        ["size", "{f}", "--velocity", "0.1 m/s"],
        ["a binary file"],
    ),
    (
        "damper a 2 MB comment",
        "d.toml",
        "# " + "x" * 2_000_000 + "\n" + MAKRIS,
        ["size", "{f}", "--velocity", "0.1 m/s"],
        ["larger than 1 MB"],
    ),
    (
        "damper a 100000-character value",
        "d.toml",
        MAKRIS.replace('gap = "0.8 mm"', 'gap = "' + "8" * 100_000 + ' mm"'),
        ["size", "{f}", "--velocity", "0.1 m/s"],
        ["geometry.gap", "too long"],
    ),
    (
        "requirements NUL",
        "r.toml",
        (EXAMPLES / "requirements" / "makris_requirements.toml").read_text() + "\x00",
        ["design", "{f}", "--out", "{d}/o.csv"],
        ["a binary file"],
    ),
    (
        "requirements a 2 MB comment",
        "r.toml",
        "# " + "x" * 2_000_000 + "\n",
        ["design", "{f}", "--out", "{d}/o.csv"],
        ["larger than"],
    ),
    (
        "params JSON NUL",
        "p.json",
        '{"parameters": {"c0": 1}}\x00',
        [
            "simulate",
            str(EXAMPLES / "measurements" / "makris_hidden_seal_friction.csv"),
            "--model",
            "bingham",
            "--params",
            "{f}",
        ],
        ["a binary file"],
    ),
]


@pytest.mark.parametrize("case", TEXT_INPUTS, ids=[c[0] for c in TEXT_INPUTS])
def test_nul_bytes_and_long_lines_in_text_inputs(case, tmp_path, capsys):
    _, name, text, args, needles = case
    path = tmp_path / name
    path.write_text(text)
    args = [a.replace("{f}", str(path)).replace("{d}", str(tmp_path)) for a in args]
    code, out, err = _run(capsys, args)
    _one_line_error(code, out, err, *needles)
    assert path.read_text() == text and sorted(p.name for p in tmp_path.iterdir()) == [name]


# ------------------------------------------------------------------ numbers as a locale writes them
LOCALE_VALUES = [
    ("1.234,5 N", "a ','"),
    ("1,5 N", "a decimal comma; write '1.5 N'"),
    ("1 234 N", "a space between digits"),
    ("1\u202f234 N", "a space between digits"),  # NARROW NO-BREAK SPACE: French grouping
    ("1\u00a0234 N", "a space between digits"),  # NO-BREAK SPACE
    ("1'234 N", "a digit separator"),  # Swiss grouping
    ("1_234 N", "a digit separator"),
    ("\u0661\u0662 N", "ASCII digits"),  # Arabic-Indic
    ("\u0967\u0968 N", "ASCII digits"),  # Devanagari
    ("1\u066b5 N", "ARABIC DECIMAL SEPARATOR"),
    ("\u20131 N", "not a minus sign"),  # an en dash
]


@pytest.mark.parametrize("text, said", LOCALE_VALUES, ids=[repr(v[0]) for v in LOCALE_VALUES])
def test_locale_numbers_in_values_are_refused_with_the_reason(text, said):
    with pytest.raises(ErdesignError) as info:
        to_si(text, "N", "seal_friction")
    message = _one_line(str(info.value))
    assert message.startswith("seal_friction: ") and said in message, message


@pytest.mark.parametrize(
    "row, needles",
    [
        ("0,02;1,5;3,0", None),  # a ';' file with decimal commas is read (the other rows below are the same)
        ("0,02;1.234,5;3", ["line 12", "thousands separator"]),
        ("0,02;1 234,5;3", ["line 12, column 2", "not a number"]),
        ("0,02;\u0661;3", ["line 12, column 2"]),
    ],
    ids=["decimal commas", "grouped with points", "grouped with spaces", "Arabic-Indic digit"],
)
def test_locale_numbers_in_a_record(row, needles, tmp_path):
    rows = [r.replace(",", ";").replace(".", ",") for r in BODY]
    path = tmp_path / "r.csv"
    text = _lines(HEADER.replace(",", ";"), *rows[:10], row, *rows[11:])
    path.write_text(text)
    if needles is None:
        assert erdesign.read_measurement(path).displacement[10] == pytest.approx(1.5e-3)
        return
    with pytest.raises(ErdesignError) as info:
        erdesign.read_measurement(path)
    message = _one_line(str(info.value))
    assert all(n in message for n in needles), message


@pytest.mark.parametrize(
    "key, value, said",
    [
        ("gap", '"0,8 mm"', "decimal comma"),
        ("seal_friction", '"1 112 N"', "a space between digits"),  # was "a number or an expression after the unit"
        ("seal_friction", '"1\u202f112 N"', "a space between digits"),
        ("yield_stress", '"1.800,5 Pa"', "has a ','"),
        ("duct_length", '"54\u066b6 mm"', "ARABIC DECIMAL SEPARATOR"),
    ],
)
def test_locale_numbers_in_a_damper_file(key, value, said, tmp_path, capsys):
    from .corpus import damper_with

    path = tmp_path / "d.toml"
    path.write_text(damper_with(key, value))
    code, out, err = _run(capsys, ["size", path, "--velocity", "0.1 m/s"])
    _one_line_error(code, out, err, f".{key}: ", said)


@pytest.mark.parametrize("velocity", ["0,1 m/s", "1 000 mm/s", "0\u066b1 m/s", "1'000 mm/s"])
def test_locale_numbers_on_the_command_line(velocity, capsys):
    code, out, err = _run(capsys, ["size", "makris", "--velocity", velocity])
    _one_line_error(code, out, err, "velocity")


# ------------------------------------------------------------------ the API fed what is not numbers
T = np.linspace(0.0, 2.0, 1000)
X = 4e-3 * np.sin(2 * np.pi * T)
REC = Measurement.from_arrays(T, X, M.force_si(np.gradient(X, T)))
DATES = np.datetime64("2024-01-01") + (T * 1e9).astype("timedelta64[ns]")
BINGHAM = erdesign.get_model("bingham")


def _diagnose(*args, **kw):
    from erdesign.diagnosis.diagnose import diagnose

    return diagnose(*args, **kw)


API_CASES = [
    # complex numbers: "has no unit; e.g. '(0.1+0j) m/s'" or "<Quantity((0.1+1j) ...)> is not a number"
    ("force complex", lambda: M.force(0.1 + 0j), ["velocity: expected a velocity (real numbers), got complex"]),
    ("force Q complex", lambda: M.force(Q_(0.1 + 1j, "m/s")), ["velocity:", "complex numbers"]),
    ("force complex array", lambda: M.force(np.array([0.1 + 1j])), ["velocity:", "complex numbers"]),
    ("force_si complex", lambda: M.force_si(0.1 + 0j), ["v:", "complex numbers"]),
    ("bingham Q complex", lambda: erdesign.bingham_pressure_drop(Q_(1 + 1j, "mL/s"), *DUCT), ["Q:", "complex"]),
    (
        "Geometry gap complex",
        lambda: erdesign.Geometry.create(**{**MAKRIS_GEOMETRY, "gap": Q_(0.8 + 0j, "mm")}),
        ["geometry.gap:", "complex"],
    ),
    (
        "Fluid density complex",
        lambda: erdesign.Fluid.create(**{**MAKRIS_FLUID, "density": Q_(1290 + 0j, "kg/m^3")}),
        ["fluid.density:", "complex"],
    ),
    (
        "Fluid exponent complex",
        lambda: erdesign.Fluid.create(**{**MAKRIS_FLUID, "yield_exponent": 2 + 0j}),
        ["fluid.yield_exponent:", "complex"],
    ),
    ("sine amplitude complex", lambda: M.sine_response(Q_(1 + 1j, "mm"), "1 Hz"), ["amplitude:", "complex"]),
    ("esr complex", lambda: erdesign.esr(REC.force + 0j, REC.force), ["F_measured:", "complex numbers"]),
    ("fit fixed complex", lambda: erdesign.fit(BINGHAM, REC, fixed={"c0": 1 + 0j}), ["fixed['c0']:", "complex"]),
    (
        "run_rig noise complex",
        lambda: erdesign.run_rig(M, erdesign.programme("rp"), force_noise=0.01 + 0j),
        ["force_noise:"],
    ),
    ("diagnose noise complex", lambda: _diagnose(M, REC, force_noise=5 + 0j), ["force_noise:", "complex"]),
    # true/false
    ("force list of bools", lambda: M.force([True, False]), ["velocity:", "got true/false"]),  # "has no unit"
    ("force bool array", lambda: M.force(np.array([True])), ["velocity:", "true/false"]),
    ("force bool", lambda: M.force(True), ["velocity: expected a velocity, got True"]),
    ("force_si bool", lambda: M.force_si(True), ["v:", "true/false"]),
    ("bingham tau bool", lambda: erdesign.bingham_pressure_drop("1 mL/s", True, *DUCT[1:]), ["tau_y:"]),
    ("Geometry ducts True", lambda: erdesign.Geometry.create(**MAKRIS_GEOMETRY, ducts=True), ["geometry.ducts"]),
    (
        "Fluid exponent True",
        lambda: erdesign.Fluid.create(**{**MAKRIS_FLUID, "yield_exponent": True}),
        ["fluid.yield_exponent"],
    ),
    ("sine cycles True", lambda: M.sine_response("1 mm", "1 Hz", cycles=True), ["cycles:"]),
    ("fit starts True", lambda: erdesign.fit(BINGHAM, REC, starts=True), ["starts:"]),
    ("from_arrays bool force", lambda: Measurement.from_arrays(T, X, X > 0), ["force:", "true/false"]),
    ("programme seed True", lambda: erdesign.programme("rp", seed=True), ["seed:"]),
    ("diagnose effects True", lambda: _diagnose(M, REC, effects=True), ["effects: expected effect names"]),  # TypeError
    ("diagnose exclude_clipped 'yes'", lambda: _diagnose(M, REC, exclude_clipped="yes"), ["exclude_clipped: must be"]),
    ("diagnose force_noise True", lambda: _diagnose(M, REC, force_noise=True), ["force_noise:"]),
    # lists of texts
    ("force list of texts", lambda: M.force(["0.1 m/s", "0.2 m/s"]), ["velocity: a sequence of texts"]),
    ("force_si list of texts", lambda: M.force_si(["0.1", "0.2"]), ["v: expected a number"]),
    (
        "Geometry gap list of texts",
        lambda: erdesign.Geometry.create(**{**MAKRIS_GEOMETRY, "gap": ["0.8 mm"]}),
        ["geometry.gap: a sequence of texts"],
    ),
    (
        "Fluid viscosity list of texts",
        lambda: erdesign.Fluid.create(**{**MAKRIS_FLUID, "viscosity": ["7 Pa*s"]}),
        ["fluid.viscosity: a sequence of texts"],
    ),
    (
        "annulus list of texts",
        lambda: erdesign.annulus_bingham_pressure_drop(
            ["1 mL/s"], "1.8 kPa", "13 Pa*s", "54.6 mm", "14.3 mm", "0.8 mm"
        ),
        ["Q: a sequence of texts"],
    ),
    ("sine field list of texts", lambda: M.sine_response("1 mm", "1 Hz", field=["1 kV/mm"]), ["field: a sequence"]),
    ("esr lists of texts", lambda: erdesign.esr(["1", "2"], ["1", "2"]), ["F_measured: expected a number"]),
    ("from_arrays texts", lambda: Measurement.from_arrays([str(t) for t in T], X), ["time: expected a number"]),
    ("equivalent_damping texts", lambda: erdesign.equivalent_damping(["1"], ["1"], ["1"]), ["energy: expected"]),
    ("diagnose a record and a text", lambda: _diagnose(M, [REC, "A.csv"]), ["record 2: expected a Measurement"]),
    ("load_damper a list", lambda: erdesign.load_damper(["makris"]), ["path: expected the name of a damper file"]),
    ("read_measurement a list", lambda: erdesign.read_measurement(["a.csv"]), ["path: expected the name"]),
    ("read_measurement ''", lambda: erdesign.read_measurement(""), ["path: an empty file name ''"]),
    ("load_damper ''", lambda: erdesign.load_damper(""), ["path: an empty file name ''"]),
    # dates and time spans
    ("from_arrays datetime64 time", lambda: Measurement.from_arrays(DATES, X), ["time:", "got a date"]),
    ("from_arrays timedelta64 time", lambda: Measurement.from_arrays(DATES - DATES[0], X), ["time:", "a time span"]),
    ("from_arrays pandas dates", lambda: Measurement.from_arrays(pd.Series(DATES), X), ["time:", "a date"]),
    ("force datetime64", lambda: M.force(np.array(["2024-01-01"], dtype="datetime64[ns]")), ["velocity:", "a date"]),
    ("force timedelta64", lambda: M.force(np.array([1, 2], dtype="timedelta64[ms]")), ["velocity:", "a time span"]),
    (
        "Geometry gap a date",
        lambda: erdesign.Geometry.create(**{**MAKRIS_GEOMETRY, "gap": np.datetime64("2024-01-01")}),
        ["geometry.gap:", "a date"],
    ),  # "e.g. '2024-01-01 m'"
    ("energy dates", lambda: erdesign.energy_per_cycle(DATES, X, X, 1.0), ["t:", "a date"]),
    ("esr dates", lambda: erdesign.esr(DATES, DATES), ["F_measured:", "a date"]),
    # 0-d arrays, containers and sizes
    ("force ragged", lambda: M.force([[0.1], [0.2, 0.3]]), ["velocity: a ragged sequence"]),  # a ValueError
    ("force_si 10**400", lambda: M.force_si(10**400), ["v:", "beyond the largest float"]),  # an OverflowError
    ("force 10**400", lambda: M.force(10**400), ["velocity:", "has no unit"]),
    ("force_si a bytearray", lambda: M.force_si(bytearray(b"ab")), ["v: expected a number"]),  # read as 97, 98 m/s
    ("force_si a memoryview", lambda: M.force_si(memoryview(b"ab")), ["v: expected a number"]),
    ("force a memoryview", lambda: M.force(memoryview(b"ab")), ["velocity: expected text or a quantity"]),
    ("from_arrays 0-d", lambda: Measurement.from_arrays(np.array(0.0), X), ["time: expected a 1-D array"]),
    ("esr 0-d", lambda: erdesign.esr(np.array(1.0), np.array(2.0)), ["F_measured: 1 sample"]),
    ("Geometry ducts 0-d", lambda: erdesign.Geometry.create(**MAKRIS_GEOMETRY, ducts=np.array(1)), ["geometry.ducts"]),
    ("programme seed 0-d", lambda: erdesign.programme("rp", seed=np.array(3)), ["seed: must be a whole number"]),
    ("get_model 0-d text", lambda: erdesign.get_model(np.array("bingham")), ["name: expected a model's name"]),
    ("force a set", lambda: M.force({0.1}), ["velocity:", "has no unit"]),
    ("force a dict", lambda: M.force({"v": 0.1}), ["velocity:"]),
    ("force a masked array", lambda: M.force_si(np.ma.masked_array([0.1, 0.2], mask=[0, 1])), ["v: element 1 is mas"]),
    # DataFrames with extra columns
    ("force_si a DataFrame", lambda: M.force_si(pd.DataFrame({"v": [0.1], "F": [1.0]})), ["v: a DataFrame of 2"]),
    (
        "esr a DataFrame",
        lambda: erdesign.esr(pd.DataFrame({"a": REC.force, "b": REC.force}), REC.force),
        ["F_measured: a DataFrame of 2 column(s); pass one column, e.g. df['a']"],
    ),
    ("from_arrays a DataFrame", lambda: Measurement.from_arrays(pd.DataFrame({"t": T, "x": X}), X), ["time: a Data"]),
    (
        "diagnose a DataFrame",
        lambda: _diagnose(M, pd.DataFrame({"time [s]": T, "displacement [m]": X})),
        ["record: expected a Measurement or a list of them, got DataFrame", "Measurement.from_arrays"],
    ),
    ("read_measurement a DataFrame", lambda: erdesign.read_measurement(pd.DataFrame({"t": T})), ["from_arrays"]),
    ("Q_ a DataFrame", lambda: M.force(Q_(pd.DataFrame({"v": [0.1], "w": [0.2]}), "m/s")), ["Q_: got a DataFrame"]),
    ("fit mask a DataFrame", lambda: erdesign.fit(BINGHAM, REC, mask=pd.DataFrame({"m": [True] * 1000})), ["mask:"]),
]


@pytest.mark.parametrize("case", API_CASES, ids=[c[0] for c in API_CASES])
def test_round6_api_names_the_argument(case, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _, call, needles = case
    with pytest.raises(ErdesignError) as info:
        call()
    message = _one_line(str(info.value))
    assert all(n in message for n in needles), message
    assert not list(tmp_path.iterdir())


def test_the_api_reads_what_is_numbers_as_numbers():
    """0-d arrays, a Series from a DataFrame with other columns, numpy text: the same numbers as plain floats."""
    frame = pd.DataFrame({"time": T, "x": X, "note": ["n"] * len(T), "F": REC.force})
    a = Measurement.from_arrays(frame["time"], frame["x"], frame["F"])
    np.testing.assert_array_equal(a.force, REC.force)
    assert M.force_si(np.array(0.1)) == M.force_si(0.1)
    assert M.force(np.array("0.1 m/s")).to("N").magnitude == M.force("0.1 m/s").to("N").magnitude
    assert M.force(Q_(np.array(0.1), "m/s")).to("N").magnitude == M.force("0.1 m/s").to("N").magnitude
    assert erdesign.energy_per_cycle(T, X, REC.force, np.array(1.0)) == erdesign.energy_per_cycle(T, X, REC.force, 1.0)


# ------------------------------------------------------------------ a reader that closes the pipe; SIGTERM
def _erdesign(*args, **kw):
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    return subprocess.Popen([sys.executable, "-m", "erdesign", *map(str, args)], env=env, **kw)


def test_a_reader_that_closes_the_pipe_ends_the_command_quietly():
    """``erdesign models --json | head -c 10``: exit 1 without a word (click's), as if the input were bad; now 141, the code
    of a process ended by SIGPIPE, with nothing on stderr."""
    import fcntl

    r, w = os.pipe()
    fcntl.fcntl(w, getattr(fcntl, "F_SETPIPE_SZ", 1031), 4096)  # less than the output: the writer meets the close
    p = _erdesign("models", "--json", stdout=w, stderr=subprocess.PIPE)
    os.close(w)
    assert len(os.read(r, 10)) == 10
    os.close(r)
    _, err = p.communicate(timeout=60)
    # 141 when a write meets the closed pipe; 0 when the system took the whole output before the close (the text
    # form ends in 141 on this machine, the JSON form, one write, in 0): never 1, never a word on stderr
    assert p.returncode in (0, 141) and err == b"", (p.returncode, err)
    p = _erdesign("models", stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    p.stdout.read(10)
    p.stdout.close()
    assert p.wait(timeout=60) in (0, 141) and p.stderr.read() == b""


def test_sigterm_during_a_write_leaves_no_file_and_says_so(tmp_path, capsys):
    """In-process: the whole command runs with SIGTERM raising SystemExit; 143, one line, nothing left."""
    from erdesign.cli.main import SIGTERM_EXIT

    out = tmp_path / "big.csv"
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGTERM))
    timer.start()
    try:
        code, stdout, err = _run(
            capsys, ["doe", "--programme", "rp", "--duration", "1200 s", "--rate", "1 kHz", "--out", out]
        )
    finally:
        timer.cancel()
    assert code == SIGTERM_EXIT == 143, err
    assert err.strip() == "erdesign: stopped (SIGTERM); no output file was left half-written"
    assert not list(tmp_path.iterdir())
    assert signal.getsignal(signal.SIGTERM) is signal.SIG_DFL


def test_sigterm_during_a_batch_on_a_pool_leaves_no_process_behind(tmp_path):
    """SIGTERM ended the command at once: its pool workers and fork server lived on, holding the terminal's pipes
    (a pipeline after it waited for ever).  Now the workers are stopped, the finished rows kept, exit 143."""
    for i in range(4):
        (tmp_path / f"r{i}.csv").write_text(GOOD_RECORD)
    p = _erdesign(
        "batch",
        "fit",
        *(tmp_path / f"r{i}.csv" for i in range(4)),
        "--damper",
        "makris",
        "--jobs",
        "2",
        "--out",
        tmp_path / "t.csv",
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    time.sleep(2.0)
    p.send_signal(signal.SIGTERM)
    try:
        _, err = p.communicate(timeout=30)  # the pipes close only when every process holding them has ended
    except subprocess.TimeoutExpired:
        p.kill()
        raise
    assert p.returncode in (0, 143) and b"Traceback" not in err, err
    assert not [f for f in os.listdir(tmp_path) if f.endswith(".tmp")]
