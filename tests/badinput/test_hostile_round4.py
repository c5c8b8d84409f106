"""Hostile input, fourth round (issue 27): cases the three earlier rounds had not written - units as typed in other
scripts and on other keyboards ('31.5 mil', '1 ℃', '0.8 ㎜', '7000 mPas', 'N-s/m'), numbers too small to compute
with, a named pipe as an input file, API arguments of the wrong kind (text, booleans, complex numbers, dates, masked
arrays), CSV headers of other shapes, a TOML file with classic-Mac line ends, implausible reference fields and yield
exponents, and the app's uploads.  Each ends in one readable line naming the argument, key, file or line (exit 1 or
2), or, when possible but implausible, in a warning naming it; inputs are never changed.  The commands run in-process.
"""

from __future__ import annotations

import math
import os
import shutil
import signal
import warnings
from contextlib import contextmanager
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest

import erdesign
from erdesign import Q_, Measurement
from erdesign.errors import ErdesignError, PlausibilityWarning
from erdesign.units import to_si

from .corpus import _F, EXAMPLES, GOOD_RECORD, MAKRIS, REQUIREMENTS, record
from .test_hostile_cli import _argv, _one_line_error, _run


# ------------------------------------------------------------------------------------------ values with units
@pytest.mark.parametrize(
    "text, unit, expected",
    [
        ("31.5 mil", "m", 31.5 * 25.4e-6),  # pint's 'mil' is an angle: "expected a length, got ... (a plain number)"
        ("31.5 mils", "m", 31.5 * 25.4e-6),
        ("1000 mil/s", "m/s", 0.0254),
        ("0.8 \u339c", "m", 0.8e-3),  # SQUARE MM: "write the value in ASCII digits"
        ("800 \u339b", "m", 0.8e-3),  # SQUARE MU M
        ("20 \u2103", "K", 293.15),  # DEGREE CELSIUS
        ("20 \u00baC", "K", 293.15),  # a masculine ordinal typed for the degree sign: "unknown unit"
        ("20 \u02daC", "K", 293.15),  # RING ABOVE
        ("-0 mm", "m", 0.0),
        ("0e5 m", "m", 0.0),
    ],
)
def test_units_typed_on_other_keyboards_are_read_as_meant(text, unit, expected):
    assert to_si(text, unit, "x") == pytest.approx(expected, rel=1e-12, abs=0.0)


@pytest.mark.parametrize(
    "text, unit, said",
    [
        ("1e-400 N", "N", "too small to compute with"),  # read as 0 N (a seal friction of none)
        ("1e-320 m/s", "m/s", "too small to compute with"),  # a subnormal: digits lost, 1e-320 m/s sized silently
        ("1 N/m-s", "N*s/m", "a '-' after '/'"),  # 'N-s/m' is read as N*s/m (round 6)
        ("7000 mPas", "Pa*s", "'Pas' reads as pascals: write 'Pa*s'"),  # German 'mPas', read as millipascals
        ("1 \u2032", "m", "its unit in plain letters"),  # PRIME: was "write the value in ASCII digits"
        ("\u0663 mm", "m", "in ASCII digits"),
        ("0x10 mm", "m", "a hexadecimal number"),
        ("1 e3 N", "N", "a space inside the number"),
    ],
)
def test_slips_in_values_are_refused_naming_the_argument(text, unit, said):
    with pytest.raises(ErdesignError) as info:
        to_si(text, unit, "x")
    message = str(info.value)
    assert message.startswith("x: ") and said in message and "ParserHelper" not in message, message


# ------------------------------------------------------------------------------------------ the command line
_RECORD_BODY = GOOD_RECORD.splitlines()[1:]
_FILES = {
    "mil.toml": MAKRIS.replace('gap = "0.8 mm"', 'gap = "31.5 mil"'),
    "thou.toml": MAKRIS.replace('gap = "0.8 mm"', 'gap = "31.5 thou"'),
    "cr.toml": MAKRIS.replace("\n", "\r"),  # classic Mac OS line ends: "Found invalid character '\r'"
    "seal.toml": MAKRIS.replace('seal_friction = "112 N"', 'seal_friction = "1e-400 N"'),  # read as 0 N
    "ref.toml": MAKRIS.replace('reference_field = "3 kV/mm"', 'reference_field = "1e-300 kV/mm"'),
    "ref_low.toml": MAKRIS.replace('reference_field = "3 kV/mm"', 'reference_field = "3 V/mm"'),
    "exp.toml": MAKRIS.replace("yield_exponent = 2.0", "yield_exponent = 1e-300"),
    "req_range.toml": REQUIREMENTS.replace("min_dynamic_range = 1.9", "min_dynamic_range = 0.5"),
    "kN.csv": GOOD_RECORD.replace("force [N]", "force [\uff4bN]"),  # fullwidth k: an internal error
    "x0.csv": "time [s],displacement [mm],force [N],x0 [m]\n" + "\n".join(r + ",0" for r in _RECORD_BODY) + "\n",
    "bom.csv": GOOD_RECORD.replace("displacement [mm]", "\ufeffdisplacement [mm]"),
    "const.csv": record(F=np.full_like(_F, 5.0)),  # "esr: the measured force is constant" naming no file
    "pipes.csv": GOOD_RECORD.replace(",", "|"),
    "unix.csv": record(
        t=np.arange(0, 2.0, 0.002) + 1.7e9
    ),  # "beyond any damper record; check the column's unit"  # was "unknown unit 's]|displacement [mm]|force [N'"
    "req_inf.toml": REQUIREMENTS.replace("min_dynamic_range = 1.9", "min_dynamic_range = inf"),  # searched for
}


@pytest.fixture
def files(tmp_path):
    made = {"damper": shutil.copy(EXAMPLES / "makris.toml", tmp_path / "d.toml"), "record": tmp_path / "m.csv"}
    made["record"].write_text(GOOD_RECORD)
    for name, text in _FILES.items():
        made[name.replace(".", "_")] = tmp_path / name
        made[name.replace(".", "_")].write_text(text, encoding="utf-8", newline="")
    for name in ("pipe.toml", "pipe.csv"):
        made[name.replace(".", "_")] = tmp_path / name
        os.mkfifo(tmp_path / name)
    return tmp_path, made


@contextmanager
def _no_hang(seconds=20):
    """A named pipe as input waited for a writer for ever: a regression fails instead of hanging the suite."""

    def stop(*_):
        raise TimeoutError("the command waited on its input")

    old = signal.signal(signal.SIGALRM, stop)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


_SIZE = ["--velocity", "1 in/s"]
_PIPE = "not a regular file (a named pipe)"
ERROR_CASES = [
    # a named pipe (mkfifo) as the input file: every command waited for ever
    ("size a named pipe", ["size", "{pipe_toml}", *_SIZE], ["pipe.toml", _PIPE]),
    ("fit a named pipe", ["fit", "{pipe_csv}", "--damper", "{damper}"], ["pipe.csv", _PIPE]),
    ("fit damper a named pipe", ["fit", "{record}", "--damper", "{pipe_toml}"], ["pipe.toml", _PIPE]),
    ("design a named pipe", ["design", "{pipe_toml}", "--out", "{tmp}/o.csv"], ["pipe.toml", _PIPE]),
    ("report a named pipe", ["report", "{pipe_toml}", "--out", "{tmp}/o.html"], ["pipe.toml", _PIPE]),
    (
        "batch manifest a named pipe",
        ["batch", "fit", "--manifest", "{pipe_csv}", "--damper", "{damper}", "--out", "{tmp}/o.csv"],
        ["--manifest", _PIPE],
    ),
    # the sample-count limit named the library's arguments ('duration, rate'), not the options
    (
        "doe duration 1e6 s",
        ["doe", "--programme", "rp", "--duration", "1e6 s", "--out", "{tmp}/o.csv"],
        ["--duration, --rate: 500,000,000 samples"],
    ),
    ("vehicle duration 1e6 s", ["vehicle", "--damper", "{damper}", "--duration", "1e6 s"], ["--duration, --dt: "]),
    (
        "doe control range reversed",
        ["doe", "--programme", "dsfs+icps", "--control-range", "1.6 A, 0.2 A", "--out", "{tmp}/o.csv"],
        ["--control-range: need a finite low below the high"],
    ),
    # a negative seed: numpy's "expected non-negative integer" as an internal error
    ("doe seed -1", ["doe", "--programme", "rp", "--seed", "-1", "--out", "{tmp}/o.csv"], ["'--seed'", "-1"]),
    ("vehicle seed -1", ["vehicle", "--damper", "{damper}", "--seed", "-1"], ["'--seed'", "-1"]),
    # numbers too small to compute with: read as 0, or sized at 1e-320 m/s without a word
    ("size velocity 1e-320", ["size", "{damper}", "--velocity", "1e-320 m/s"], ["velocity", "too small"]),
    ("size seal 1e-400 N", ["size", "{seal_toml}", *_SIZE], ["fluid.seal_friction", "too small"]),
    (
        "report amplitude 1e-320 mm",  # was "frequency: value must be finite, got inf Hz"
        ["report", "{damper}", "--amplitude", "1e-320 mm", "--out", "{tmp}/o.html"],
        ["amplitude", "too small"],
    ),
    # the other kind of TOML file: "design: unknown key; allowed keys: name, geometry, ..."
    ("size a requirements file", ["size", "{req_range_toml}", *_SIZE], ["a requirements file ([design])"]),
    ("design a damper file", ["design", "{damper}", "--out", "{tmp}/o.csv"], ["d.toml: a damper file ([geometry])"]),
    (
        "report amplitude 1 km",
        ["report", "{damper}", "--amplitude", "1 km", "--out", "{tmp}/o.html"],
        ["amplitude: 1000 m"],
    ),
    # a reference field of 1e-300 kV/mm: overflow warnings from numpy, NaN in the table, an internal error in --json
    (
        "size reference field 1e-300 kV/mm",
        ["size", "{ref_toml}", *_SIZE, "--field", "3 kV/mm", "--json"],
        ["fluid.reference_field: 1e-300 kV/mm is below any electric field"],
    ),
    # measurement headers: a fullwidth letter in the unit was an internal error; a name with a digit was told to
    # have "its unit in square brackets", which it had
    ("fit fullwidth unit", ["fit", "{kN_csv}", "--damper", "{damper}"], []),  # only: no internal error
    ("fit unknown column x0", ["fit", "{x0_csv}", "--damper", "{damper}"], ["column 4 (x0): unknown column"]),
    ("fit constant force", ["fit", "{const_csv}", "--damper", "{damper}"], ["const.csv: force: constant (5 N)"]),
    ("fit Unix time", ["fit", "{unix_csv}", "--damper", "{damper}"], ["column 1 (time [s]): starts at 1.7e+09 s"]),
    ("fit columns between '|'", ["fit", "{pipes_csv}", "--damper", "{damper}"], ["line 1", "separated by '|'"]),
    (
        "design min_dynamic_range inf",
        ["design", "{req_inf_toml}", "--out", "{tmp}/o.csv"],
        ["design.point[1].min_dynamic_range: expected a finite number, got inf"],
    ),
    # hostile output names: "[Errno 36] File name too long: '<the whole path>'", naming no option; a direction
    # override was written (a listing shows 'acsv.exe.csv' as 'aexe.vsc.csv')
    ("out name of 300 bytes", ["doe", "--programme", "E5", "--out", "{tmp}/" + "x" * 300 + ".csv"], ["--out", "304"]),
    ("out direction override", ["doe", "--programme", "E5", "--out", "{tmp}/a\u202ecsv.exe.csv"], ["--out", "\\u202e"]),
]


@pytest.mark.parametrize("case", ERROR_CASES, ids=[c[0] for c in ERROR_CASES])
def test_round4_command_lines_end_in_one_line(case, files, capsys):
    _, args, needles = case
    tmp, made = files
    before = {p: p.read_bytes() for p in made.values() if p.is_file()}
    with _no_hang():
        code, out, err = _run(capsys, _argv(args, tmp, made))
    if args[1] == "{kN_csv}":  # the unit is read as meant: the fit runs (it warns of a force 1000 x too large)
        assert code == 0 and "internal error" not in err, err
        return
    _one_line_error(code, out, err, *needles)
    assert {p: p.read_bytes() for p in made.values() if p.is_file()} == before
    assert not (tmp / "o.csv").exists() and not (tmp / "o.html").exists()


def test_a_gap_in_mil_is_a_thousandth_of_an_inch(files, capsys):
    """Makris's h = 0.0315 in written '31.5 mil' was refused as 'a plain number' (pint's mil is an angle)."""
    tmp, made = files
    outs = []
    for name in ("mil_toml", "thou_toml"):
        code, out, err = _run(capsys, ["size", made[name], *_SIZE, "--json"])
        assert code == 0, err
        outs.append(out)
    assert outs[0] == outs[1]


def test_a_damper_file_with_classic_mac_line_ends_reads_as_with_lf(files, capsys):
    tmp, made = files
    outs = []
    for name in ("damper", "cr_toml"):
        code, out, err = _run(capsys, ["size", made[name], *_SIZE, "--json"])
        assert code == 0, err
        outs.append(out)
    assert outs[0] == outs[1]


def test_an_invisible_character_in_a_header_name_is_dropped(files, capsys):
    tmp, made = files
    code, out, err = _run(capsys, ["fit", made["bom_csv"], "--damper", made["damper"], "--json"])
    assert code == 0, err


#: (id, arguments, the warning line's start): possible but implausible values, warned naming the key
WARNING_CASES = [
    ("yield exponent 1e-300", ["size", "{exp_toml}", *_SIZE], "warning: fluid.yield_exponent: 1e-300 is outside"),
    (
        "reference field 3 V/mm",
        ["size", "{ref_low_toml}", *_SIZE],
        "warning: fluid.reference_field: 3 V/mm is below the electric field",
    ),
    (
        "min_dynamic_range 0.5",
        ["design", "{req_range_toml}", "--out", "{tmp}/o.csv", "--json"],
        "warning: design.point[1].min_dynamic_range: 0.5 is met by every damper",
    ),
    ("velocity 0.5 um/s", ["size", "{damper}", "--velocity", "0.5 um/s"], "warning: velocity: 5e-07 m/s is below"),
]


@pytest.mark.parametrize("case", WARNING_CASES, ids=[c[0] for c in WARNING_CASES])
def test_round4_implausible_values_are_warned(case, files, capsys):
    _, args, start = case
    tmp, made = files
    code, out, err = _run(capsys, _argv(args, tmp, made))
    assert code == 0, err
    assert any(line.startswith(start) for line in err.splitlines()), err


# ------------------------------------------------------------------------------------------ the Python API
MAKRIS_DAMPER = erdesign.load_example("makris")
T = np.linspace(0.0, 2.0, 1000)
X = 4e-3 * np.sin(2 * np.pi * T)
DUCT = ("1 mL/s", "1.8 kPa", "13 Pa*s", "54.6 mm", "14.3 mm")


def _api_cases():
    m = MAKRIS_DAMPER
    return [
        # (id, call, texts the message must hold): numpy read these as numbers without a word
        ("force_si text", lambda: m.force_si("0.1"), ["v: expected a number", "'0.1'"]),
        ("force_si texts", lambda: m.force_si(["0.1", "0.2"]), ["v: expected a number"]),
        ("force_si bytes", lambda: m.force_si(b"0.1"), ["v: expected a number"]),
        ("force_si True", lambda: m.force_si(True), ["v:", "true/false"]),  # 1 m/s
        ("force_si field True", lambda: m.force_si(0.1, True), ["field:", "true/false"]),
        ("force_si complex", lambda: m.force_si(np.array([0.1 + 0.1j])), ["v:", "complex numbers"]),  # real part
        ("force_si date", lambda: m.force_si(np.datetime64("2020-01-01")), ["v:", "a date"]),  # 2.2e9 N
        ("force_si time span", lambda: m.force_si(np.timedelta64(1, "s")), ["v:", "a time span"]),
        ("force_si masked", lambda: m.force_si(np.ma.masked_array([0.1, 9.0], [0, 1])), ["v: element 1 is masked"]),
        ("esr booleans", lambda: erdesign.esr([True, False, True], [0.0, 0.0, 1.0]), ["F_measured:", "true/false"]),
        ("esr texts", lambda: erdesign.esr(["1", "2", "3"], [1.0, 2.0, 3.0]), ["F_measured: expected a number"]),
        ("esr no samples", lambda: erdesign.esr([], []), ["F_measured: 0 samples"]),  # "the force is constant"
        ("equivalent damping True", lambda: erdesign.equivalent_damping(True, 1.0, 0.01), ["energy:", "true/false"]),
        (
            "force masked quantity",
            lambda: m.force(Q_(np.ma.masked_array([1.0, 2.0], [0, 1]), "mm/s")),
            ["velocity: an array with masked elements"],
        ),
        # a gap wider than the annulus's mean diameter: a thin-gap pressure drop of 10 kPa, without a word
        ("thin gap h > d", lambda: erdesign.bingham_pressure_drop(*DUCT, "20 mm"), ["h: the gap (0.02 m)", "0.0143"]),
        ("programme seed -1", lambda: erdesign.programme("rp", seed=-1), ["seed: must be a whole number >= 0"]),
        # Measurement.from_arrays took booleans, text, complex numbers, dates and masked values as numbers
        ("from_arrays boolean force", lambda: Measurement.from_arrays(T, X, T > 1), ["force:", "true/false"]),
        ("from_arrays text time", lambda: Measurement.from_arrays([str(v) for v in T], X), ["time: expected a number"]),
        ("from_arrays complex", lambda: Measurement.from_arrays(T, X + 0j), ["displacement:", "complex numbers"]),
        ("from_arrays masked", lambda: Measurement.from_arrays(T, np.ma.masked_less(X, 0)), ["displacement: element"]),
        ("from_arrays dates", lambda: Measurement.from_arrays(T.astype("datetime64[s]"), X), ["time:", "a date"]),
        # a NUL in a file name: "ValueError: embedded null byte"; a 300-byte name: "[Errno 36] File name too long"
        ("load_damper NUL", lambda: erdesign.load_damper("d\x00.toml"), ["'d\\x00.toml'", "NUL"]),
        ("read_measurement NUL", lambda: erdesign.read_measurement("m\x00.csv"), ["'m\\x00.csv'", "NUL"]),
        ("load_damper long name", lambda: erdesign.load_damper("x" * 300 + ".toml"), ["cannot be read (File name"]),
        ("save_damper NUL", lambda: erdesign.save_damper(m, "d\x00.toml"), ["path 'd\\x00.toml'", "NUL"]),
        ("save_damper long name", lambda: erdesign.save_damper(m, "x" * 300 + ".toml"), ["path", "305 bytes"]),
        # fit(damper, record): "'Damper' object has no attribute 'require_force'"
        ("fit a damper", lambda: erdesign.fit(m, None), ["model: expected a model", "got Damper"]),
        ("fit a list", lambda: erdesign.fit(erdesign.get_model("bingham"), [1.0]), ["record: expected a Measurement"]),
        ("sine 1 m at 1 kHz", lambda: m.sine_response("1 m", "1 kHz"), ["amplitude, frequency: the peak speed: 6283"]),
        (
            "sine samples_per_cycle 8",  # "cycles must be a whole number >= 1 and samples_per_cycle >= 16"
            lambda: m.sine_response("1 mm", "1 Hz", samples_per_cycle=8),
            ["samples_per_cycle: must be a whole number >= 16, got 8"],
        ),
    ]


_API = _api_cases()


@pytest.mark.parametrize("case", _API, ids=[c[0] for c in _API])
def test_round4_api_names_the_argument(case):
    _, call, needles = case
    with pytest.raises(ErdesignError) as info:
        call()
    message = str(info.value)
    assert "\n" not in message and all(n in message for n in needles), message


def test_numbers_of_other_kinds_are_numbers():
    """Decimal, Fraction, numpy integers, a pandas Series and a 0-d array are numbers: the same force as a float."""
    import pandas as pd

    m = MAKRIS_DAMPER
    expected = m.force_si(0.1)
    for v in (Decimal("0.1"), Fraction(1, 10), np.float32(0.1), np.array(0.1)):
        assert m.force_si(v) == pytest.approx(expected, rel=1e-6)
    np.testing.assert_allclose(m.force_si(pd.Series([0.1, 0.2])), m.force_si(np.array([0.1, 0.2])))
    assert m.force_si(np.ma.masked_array([0.1, 0.2])).shape == (2,)  # nothing masked: taken
    assert erdesign.esr(np.array([1, 2, 3]), [1.0, 2.0, 3.0]) == 0.0


def test_a_sine_of_1e_300_hz_is_warned():
    """A period of 1e300 s was computed without a word."""
    with pytest.warns(PlausibilityWarning, match=r"^amplitude, frequency: the peak speed: 6\.283e-303 m/s is below"):
        MAKRIS_DAMPER.sine_response("1 mm", "1e-300 Hz")


def test_a_numpy_integer_is_a_whole_number_of_cycles():
    """`cycles=np.int64(2)` was refused as not a whole number."""
    a = MAKRIS_DAMPER.sine_response("1 mm", "1 Hz", cycles=np.int64(2))
    b = MAKRIS_DAMPER.sine_response("1 mm", "1 Hz", cycles=2)
    np.testing.assert_array_equal(a.force, b.force)


def test_an_annulus_as_wide_as_its_diameter_is_still_the_slit_formulas_dimensionless_form():
    """h = d is how the slit formulas are used without units (h = d = 1): still taken by the thin-gap kernels."""
    from erdesign.flow.bingham import bingham_pressure_drop

    assert math.isfinite(bingham_pressure_drop(1.0, 1.0, 1.0, 1.0, 1.0, 1.0))


def test_an_implausible_yield_exponent_is_warned_in_the_api():
    with pytest.warns(PlausibilityWarning, match=r"^fluid\.yield_exponent: 1e-300 is outside"):
        erdesign.Fluid.create(
            viscosity="7 Pa*s",
            yield_stress="1.8 kPa",
            reference_field="3 kV/mm",
            yield_exponent=1e-300,
            density="1290 kg/m^3",
        )


def test_a_reference_field_below_any_fluid_is_refused_in_the_api():
    with pytest.raises(ErdesignError, match=r"^fluid\.reference_field: 1e-300 kV/mm is below"):
        erdesign.Fluid.create(
            viscosity="7 Pa*s",
            yield_stress="1.8 kPa",
            reference_field="1e-300 kV/mm",
            yield_exponent=2.0,
            density="1290 kg/m^3",
        )


def test_the_power_law_summary_of_a_coil_is_not_warned():
    """A coil's saturating circuit fits exponents below 0.3: computed, not typed, so not the user's to check."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        erdesign.load_example("mr_coil")


# ------------------------------------------------------------------------------------------ the app
def test_app_uploads_and_inputs(app):  # noqa: F811
    """One session through the pages: each hostile upload or value shows one message naming the file or field (never
    "Internal error"); the classic-Mac damper file is taken."""
    from .test_app_corpus import _clean

    def upload(name, data):
        app.file_uploader(key="size.upload").set_value((name, data, "application/toml")).run()

    upload("big.toml", (MAKRIS + "#" + "x" * (2 * 2**20)).encode())  # no limit in the app (1 MB for a file)
    _clean(app, "big.toml: larger than 1 MB")
    upload("int.toml", MAKRIS.replace("ducts = 1", "ducts = " + "9" * 5000).encode())  # "(ValueError)"
    _clean(app, "int.toml: invalid TOML: a number of thousands of digits")
    upload("cr.toml", MAKRIS.replace('"0.8 mm"', '"0.9 mm"').replace("\n", "\r").encode())
    assert not app.exception and not app.error, [e.value for e in app.error]
    assert app.text_input(key="size.geo.gap").value == "0.9 mm"

    good = app.text_input(key="size.fluid.reference_field").value
    app.text_input(key="size.fluid.reference_field").set_value("1e-300 kV/mm").run()  # "energy: it is nan"
    _clean(app, "fluid.reference_field")
    app.text_input(key="size.fluid.reference_field").set_value(good).run()
    good = app.text_input(key="size.fluid.yield_exponent").value
    for text in ("1_5", "\u0663"):  # float() read 15 and 3
        app.text_input(key="size.fluid.yield_exponent").set_value(text).run()
        _clean(app, "fluid.yield_exponent: expected a plain number")
    app.text_input(key="size.fluid.yield_exponent").set_value(good).run()
    assert not app.error

    app.switch_page("design.py").run()  # the requirement form's numbers: int() and float() read other scripts too
    for key, text, said in (
        (
            "designer.req.design.point.0.min_dynamic_range",
            "\u0663",
            "design.point[1].min_dynamic_range: expected a number",
        ),
        ("designer.req.design.bounds.ducts.1", "1_0", "design.bounds.ducts[2]: expected an integer"),
    ):
        good = app.text_input(key=key).value
        app.text_input(key=key).set_value(text).run()
        _clean(app, said)
        app.text_input(key=key).set_value(good).run()

    app.switch_page("compare.py").run()
    app.radio(key="cmp.source").set_value("upload a measurement CSV").run()
    for name, text, said in (
        ("k.csv", _FILES["kN.csv"], None),  # "Internal error: UndefinedUnitError"
        ("x" * 300 + ".csv", GOOD_RECORD, None),  # "Internal error: OSError: [Errno 36] File name too long"
        ("const.csv", _FILES["const.csv"], "force: constant"),
    ):
        app.file_uploader(key="cmp.upload").set_value((name, text.encode(), "text/csv")).run()
        assert not app.exception, [e.value for e in app.exception]
        messages = [e.value for e in app.error]
        assert not any("Internal error" in m for m in messages), messages
        if said:
            assert any(said in m for m in messages), messages
    app.switch_page("size.py").run()
    assert not app.exception


from .test_app_corpus import app  # noqa: E402, F401  (the module's AppTest fixture)


@pytest.mark.skipif(not os.path.isdir("/dev/fd"), reason="no /dev/fd on this system")
def test_a_pipe_handed_over_by_the_shell_is_read():
    """Process substitution (``erdesign fit <(zcat rec.csv.gz)``) hands the command /dev/fd/N, a pipe whose writer
    exists: it is read as a stream (only a named pipe in the file system, which waits for a writer, is refused)."""
    from erdesign.limits import read_input_bytes

    data = b"time [s],displacement [m],force [N]\n" + b"0,0,0\n" * 100
    r, w = os.pipe()
    try:
        os.write(w, data)
        os.close(w)
        w = None
        with _no_hang(10):
            assert read_input_bytes(f"/dev/fd/{r}", 10**6, "a measurement CSV file") == data
    finally:
        os.close(r)
        if w is not None:
            os.close(w)
