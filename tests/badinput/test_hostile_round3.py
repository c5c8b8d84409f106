"""Hostile input, third round: cases of the classes of issue 27 that the team had not written - expressions in
values, misspelt keys and names (a did-you-mean hint naming the closest one is expected), a BOM before a TOML
file, absurd speeds, strokes and sample counts.  Each ends in one readable line naming the argument, key or file
(exit 1 or 2) or, when the value is possible but implausible, in a warning naming it; inputs are never changed.
The commands run in-process, as in test_hostile_cli.py.
"""

from __future__ import annotations

import shutil

import pytest

from .corpus import _F, EXAMPLES, GOOD_RECORD, MAKRIS, REQUIREMENTS, _x, record
from .test_hostile_cli import _argv, _one_line_error, _run

#: (id, what the file holds, name of the file) for the files fixture
_FILES = {
    "gap_expression": MAKRIS.replace('gap = "0.8 mm"', 'gap = "0.8 mm * 2"'),  # read as 1.6 mm
    "gap_two_numbers": MAKRIS.replace('gap = "0.8 mm"', 'gap = "0.8 mm 2"'),  # read as 1.6 mm
    "gap_fraction": MAKRIS.replace('gap = "0.8 mm"', 'gap = "1/2 mm"'),  # read as 0.5 mm
    "misspelt_viscosity": MAKRIS.replace("viscosity =", "viscosty ="),
    "misspelt_table": MAKRIS.replace("[geometry]", "[geomtry]"),
    "key_case": MAKRIS.replace("gap =", "Gap ="),
    "configuration_case": MAKRIS.replace('configuration = "valve"', 'configuration = "Valve"'),
    "material_case": MAKRIS.replace("[fluid]", '[fluid]\nmaterial = "Lord-MRF-132DG"'),
    "req_misspelt": REQUIREMENTS.replace("max_length =", "max_lenght ="),
    "req_placement": REQUIREMENTS.replace('duct_placement = "beside"', 'duct_placement = "besid"'),
    "req_stroke0": REQUIREMENTS.replace('stroke = "50 mm"', 'stroke = "0 mm"'),
    "req_stroke10": REQUIREMENTS.replace('stroke = "50 mm"', 'stroke = "10 m"'),
    "req_ducts": REQUIREMENTS.replace("ducts = [1, 4]", "ducts = [1, 100000000]"),
    "seal_1e9": MAKRIS.replace('seal_friction = "112 N"', 'seal_friction = "1e9 N"'),
}
_HEADER = "time [s],displacement [mm],force [N]"
_CSV = {
    "tiny_force": record(F=_F * 1e-320),  # identify: ZeroDivisionError (an internal error)
    "tiny_stroke": record(x=_x * 1e-300),  # "in a unit 1000 x larger it would be 8e-297 mm, a plausible stroke"
    "spaces": GOOD_RECORD.replace(",", " "),  # "unknown unit 's] displacement [mm] force [N'"
    "forse": GOOD_RECORD.replace("force [N]", "forse [N]"),
    "comment_only": _HEADER + "\n# no data\n",  # numpy's "input contained no data: <_io.StringIO ...>" leaked
}
#: files in another encoding than UTF-8 (bytes)
_BYTES = {
    "latin1": MAKRIS.replace('name = "makris-1996"', 'name = "D\u00e4mpfer"').encode("latin-1"),
    "utf16": MAKRIS.encode("utf-16"),
    "latin1_csv": GOOD_RECORD.replace("displacement [mm]", "displacement [\u00b5m]").encode("latin-1"),
    "bom_damper": "\ufeff".encode() + MAKRIS.encode(),
    "bom_requirements": "\ufeff".encode() + REQUIREMENTS.encode(),
}


@pytest.fixture
def files(tmp_path):
    made = {"damper": shutil.copy(EXAMPLES / "makris.toml", tmp_path / "d.toml"), "record": tmp_path / "m.csv"}
    made["record"].write_text(GOOD_RECORD)
    for name, text in _FILES.items():
        made[name] = tmp_path / f"{name}.toml"
        made[name].write_text(text, encoding="utf-8")
    for name, text in _CSV.items():
        made[name] = tmp_path / f"{name}.csv"
        made[name].write_text(text)
    for name, data in _BYTES.items():
        made[name] = tmp_path / f"{name}.{'csv' if name.endswith('csv') else 'toml'}"
        made[name].write_bytes(data)
    return tmp_path, made


_SIZE = ["--velocity", "1 in/s"]
#: (id, arguments with {name} placeholders for the files fixture, texts the error line must hold)
ERROR_CASES = [
    # a value is one number, then its unit: pint evaluated the rest
    ("size velocity two numbers", ["size", "{damper}", "--velocity", "1 in/s 2"], ["velocity", "after the unit"]),
    ("size velocity times zero", ["size", "{damper}", "--velocity", "1 in/s * 0"], ["velocity", "after the unit"]),
    ("size velocity 2**1000", ["size", "{damper}", "--velocity", "2**1000 m/s"], ["velocity", "expression"]),
    ("size velocity brackets", ["size", "{damper}", "--velocity", "[1] m/s"], ["velocity", "one number"]),
    ("size gap expression", ["size", "{gap_expression}", *_SIZE], ["geometry.gap", "after the unit"]),
    ("size gap two numbers", ["size", "{gap_two_numbers}", *_SIZE], ["geometry.gap", "after the unit"]),
    ("size gap fraction", ["size", "{gap_fraction}", *_SIZE], ["geometry.gap", "a fraction as a decimal"]),
    # a misspelt key or name: the closest known one is named first
    ("size misspelt key", ["size", "{misspelt_viscosity}", *_SIZE], ["fluid.viscosty", "did you mean 'viscosity'?"]),
    ("size misspelt table", ["size", "{misspelt_table}", *_SIZE], ["geomtry", "did you mean 'geometry'?"]),
    ("size key in capitals", ["size", "{key_case}", *_SIZE], ["geometry.Gap", "did you mean 'gap'?"]),
    ("size choice in capitals", ["size", "{configuration_case}", *_SIZE], ["configuration", "did you mean 'valve'?"]),
    ("size material case", ["size", "{material_case}", *_SIZE], ["fluid.material", "did you mean 'lord-mrf-132dg'?"]),
    (
        "design misspelt limit",
        ["design", "{req_misspelt}", "--out", "{tmp}/o.csv"],
        ["design.limits.max_lenght", "did you mean 'max_length'?"],
    ),
    (
        "design misspelt choice",
        ["design", "{req_placement}", "--out", "{tmp}/o.csv"],
        ["design.envelope.duct_placement", "did you mean 'beside'?"],
    ),
    ("identify misspelt model", ["identify", "{record}", "--model", "bingam"], ["'bingam'", "did you mean 'bingham'?"]),
    (
        "simulate misspelt parameter",
        ["simulate", "{record}", "--model", "bingham", "--params", "f_cc=100 N"],
        ["'f_cc'", "did you mean 'f_c'?"],
    ),
    (
        "diagnose misspelt effect",
        ["diagnose", "{record}", "--damper", "{damper}", "--effects", "seal_frction"],
        ["'seal_frction'", "did you mean 'seal_friction'?"],
    ),
    (
        "tolerance misspelt key",
        ["tolerance", "{damper}", "--vary", "fluid.yeild_stress=+-5 %", *_SIZE, "--samples", "100"],
        ["--vary", "did you mean 'fluid.yield_stress'?"],
    ),
    # encodings: the line of the first byte that is not UTF-8, and UTF-16 named as such (it was 'a binary file')
    ("size Latin-1 file", ["size", "{latin1}", *_SIZE], ["latin1.toml: line 4: byte 0xe4 is not UTF-8", "Latin-1"]),
    ("size UTF-16 file", ["size", "{utf16}", *_SIZE], ["utf16.toml", "UTF-16", "save it as UTF-8"]),
    ("fit Latin-1 header", ["fit", "{latin1_csv}", "--damper", "{damper}"], ["latin1_csv.csv: line 1", "0xb5"]),
    # measurement files
    (
        "identify a subnormal force",
        ["identify", "{tiny_force}", "--model", "bingham", "--quiet"],
        ["tiny_force.csv: force: the force spans 7.86e-317 N", "[N]"],
    ),
    (
        "fit a subnormal stroke",
        ["fit", "{tiny_stroke}", "--damper", "{damper}"],
        ["tiny_stroke.csv: displacement: the piston moves 8e-303 m", "[mm]"],
    ),
    ("fit space separated", ["fit", "{spaces}", "--damper", "{damper}"], ["spaces.csv: line 1", "spaces"]),
    ("fit misspelt column", ["fit", "{forse}", "--damper", "{damper}"], ["column 3 (forse)", "did you mean 'force'?"]),
    # hostile output names: a line break or an escape sequence in the name was written as given
    ("report out with a newline", ["report", "{damper}", "--out", "{tmp}/a\nb.html"], ["--out", "'\\n'"]),
    ("design out with ESC", ["design", "{req_stroke10}", "--out", "{tmp}/o\x1b[2J.csv"], ["--out", "'\\x1b'"]),
    # NaN passed click's FloatRange (every comparison with NaN is false) and meant no time limit
    ("identify max-time nan", ["identify", "{record}", "--model", "bingham", "--max-time", "nan"], ["--max-time"]),
    (
        "batch save-every nan",
        ["batch", "fit", "{record}", "--damper", "{damper}", "--save-every", "nan"] + ["--out", "{tmp}/o.csv"],
        ["--save-every", "'nan' is not a number"],
    ),
    # a piston speed beyond any damper's: a unit mistake
    ("size velocity 1e5 m/s", ["size", "{damper}", "--velocity", "1e5 m/s"], ["velocity: 1e+05 m/s", "1000 m/s"]),
    ("size velocity speed of light", ["size", "{damper}", "--velocity", "1 c"], ["velocity", "beyond any piston"]),
    # requirements the search took without a word
    (
        "design stroke 0",
        ["design", "{req_stroke0}", "--out", "{tmp}/o.csv"],
        ["design.envelope.stroke: must be positive"],
    ),
    (
        "design 1e8 ducts",
        ["design", "{req_ducts}", "--out", "{tmp}/o.csv"],
        ["design.bounds.ducts: at most 10000 parallel ducts"],
    ),
    # sizes that asked for terabytes (MemoryError, an internal error) or filled the memory until the system killed
    # the process: a limit, said at once
    ("doe rate 1e9 Hz", ["doe", "--programme", "E5", "--rate", "1e9 Hz", "--out", "{tmp}/o.csv"], ["rate", "samples"]),
    (
        "doe duration 1e6 s",
        ["doe", "--programme", "rp", "--duration", "1e6 s", "--out", "{tmp}/o.csv"],
        ["--duration, --rate: 500,000,000 samples", "1,250,000"],
    ),
    (
        "vehicle duration 1e6 s",
        ["vehicle", "--damper", "{damper}", "--duration", "1e6 s"],
        ["--duration, --dt: 4,000,000,001 samples"],
    ),
    ("vehicle dt 1e-12 s", ["vehicle", "--damper", "{damper}", "--dt", "1e-12 s"], ["--duration, --dt", "larger dt"]),
    (
        "tolerance 1e9 samples",
        ["tolerance", "{damper}", "--vary", "fluid.yield_stress=+-15 %", *_SIZE, "--samples", "1000000000"],
        ["samples: 1,000,000,000", "16,777,216"],
    ),
    (
        "report 1e9 tolerance samples",
        ["report", "{damper}", "--out", "{tmp}/o.html", "--vary", "geometry.gap=+-1 %"]
        + ["--tolerance-samples", "1000000000"],
        ["samples: 1,000,000,000"],
    ),
]


@pytest.mark.parametrize("case", ERROR_CASES, ids=[c[0] for c in ERROR_CASES])
def test_round3_command_lines_end_in_one_line(case, files, capsys):
    _, args, needles = case
    tmp, made = files
    before = {p: p.read_bytes() for p in made.values()}
    code, out, err = _run(capsys, _argv(args, tmp, made))
    _one_line_error(code, out, err, *needles)
    assert {p: p.read_bytes() for p in made.values()} == before
    assert not (tmp / "o.csv").exists() and not (tmp / "o.html").exists()


def test_a_damper_file_with_a_bom_reads_as_without(files, capsys):
    """Notepad saves UTF-8 with a byte-order mark: it was 'invalid TOML: Invalid statement (at line 1, column 1)'."""
    tmp, made = files
    results = []
    for name in ("damper", "bom_damper"):
        code, out, err = _run(capsys, ["size", made[name], *_SIZE, "--json"])
        assert code == 0, err
        results.append(out)
    assert results[0] == results[1]


def test_a_requirements_file_with_a_bom_is_read(files, capsys):
    tmp, made = files
    code, out, err = _run(capsys, ["design", made["bom_requirements"], "--out", tmp / "o.csv", "--json"])
    assert code == 0, err
    assert (tmp / "o.csv").exists()


def test_a_sine_response_of_a_billion_cycles_is_refused():
    from erdesign import load_example
    from erdesign.errors import ErdesignError

    with pytest.raises(ErdesignError, match=r"^cycles, samples_per_cycle: 64,000,000,001 samples"):
        load_example("makris").sine_response("1 mm", "1 Hz", cycles=10**9, samples_per_cycle=64)


#: (id, arguments, the warning line's start): possible but implausible values, warned naming the value
WARNING_CASES = [
    ("size 500 m/s", ["size", "{damper}", "--velocity", "500 m/s", "--json"], "warning: velocity: 500 m/s is beyond"),
    (
        "design point 500 m/s",
        ["design", "{req_fast}", "--out", "{tmp}/o.csv", "--json"],
        "warning: design.point[1].velocity: 500 m/s is beyond",
    ),
    ("seal friction 1e9 N", ["size", "{seal_1e9}", *_SIZE], "warning: fluid.seal_friction: 1e+09 N is beyond"),
    (
        "design stroke 10 m",
        ["design", "{req_stroke10}", "--out", "{tmp}/o.csv", "--json"],
        "warning: design.envelope.stroke: 10 m is beyond",
    ),
    (
        "report velocity range to 500 m/s",
        ["report", "{damper}", "--velocity-range", "0 m/s", "500 m/s", "--out", "{tmp}/o.html", "--json"],
        "warning: velocity_range[1]: 500 m/s is beyond",
    ),
]


@pytest.mark.parametrize("case", WARNING_CASES, ids=[c[0] for c in WARNING_CASES])
def test_round3_implausible_values_are_warned(case, files, capsys):
    _, args, start = case
    tmp, made = files
    made["req_fast"] = tmp / "fast.toml"
    made["req_fast"].write_text(REQUIREMENTS.replace('velocity = "1 in/s"', 'velocity = "500 m/s"'))
    code, out, err = _run(capsys, _argv(args, tmp, made))
    assert code == 0, err
    assert any(line.startswith(start) and "unit" in line for line in err.splitlines()), err


def test_a_record_of_a_header_and_a_comment_says_so_in_one_line(files, capsys):
    tmp, made = files
    code, out, err = _run(capsys, ["fit", made["comment_only"], "--damper", made["damper"]])
    assert code == 1 and err.strip() == f"error: {made['comment_only']}: 0 data rows; a record needs at least 5", err


# ------------------------------------------------------------------------------------------ the Python API
def _api_cases():
    import math

    import numpy as np

    import erdesign
    from erdesign.data.metrics import equivalent_damping

    flow = ("1.8 kPa", "13 Pa*s", "54.6 mm", "14.3 mm", "0.8 mm")
    makris = erdesign.load_example("makris")
    return [
        # (id, call, the message's start): raw TypeErrors and unclear messages before
        ("flow rate None", lambda: erdesign.bingham_pressure_drop(None, *flow), "Q: expected a volumetric flow"),
        ("flow rate texts", lambda: erdesign.bingham_pressure_drop(["1 mL/s", "2 mL/s"], *flow), "Q: a sequence"),
        ("velocity None", lambda: makris.force(None), "velocity: expected a velocity, got None"),
        ("velocity texts", lambda: makris.size(["1 in/s"]), "velocity: a sequence of texts"),
        ("equivalent damping text", lambda: equivalent_damping("1 J", 1.0, 0.01), "energy: expected a number"),
        ("equivalent damping 0 Hz", lambda: equivalent_damping(1.0, 0.0, 0.01), "omega: must be positive"),
        ("equivalent damping nan", lambda: equivalent_damping(math.nan, 1.0, 0.01), "energy: it is nan"),
        ("programme rate text", lambda: erdesign.programme("rp", rate="fast"), "rate: cannot read 'fast'"),
        ("programme rate nan", lambda: erdesign.programme("rp", rate=math.nan), "rate: must be one positive"),
        ("programme rate array", lambda: erdesign.programme("rp", rate=np.ones(2)), "rate: must be one positive"),
        ("sine cycles True", lambda: makris.sine_response("1 mm", "1 Hz", cycles=True), "cycles: must be a whole"),
    ]


_API = _api_cases()


@pytest.mark.parametrize("case", _API, ids=[c[0] for c in _API])
def test_round3_api_names_the_argument(case):
    from erdesign.errors import ErdesignError

    _, call, start = case
    with pytest.raises(ErdesignError) as info:
        call()
    assert str(info.value).startswith(start), str(info.value)


def test_a_rate_with_its_unit_is_read():
    import erdesign

    a, b = erdesign.programme("rp", rate="1 kHz"), erdesign.programme("rp", rate=1000.0)
    assert a.time.size == b.time.size and a.time[1] == pytest.approx(1e-3)


@pytest.mark.parametrize("command", ["size", "tolerance"])
def test_a_name_with_control_characters_never_reaches_the_terminal_raw(command, tmp_path, capsys):
    """A damper named 'a<ESC>[2J<NUL>x<RIGHT-TO-LEFT OVERRIDE>evil' was printed raw at the head of the table: the
    terminal cleared, the line reversed."""
    path = tmp_path / "esc.toml"
    path.write_text(MAKRIS.replace('name = "makris-1996"', 'name = "a\\u001b[2J\\u0000x\\u202eevil"'))
    extra = ["--vary", "geometry.gap=+-1 %", "--samples", "100"] if command == "tolerance" else []
    code, out, err = _run(capsys, [command, path, *_SIZE, *extra])
    assert code == 0, err
    head = out.splitlines()[0]
    assert head.startswith("a\\x1b[2J\\x00x\\u202eevil") and head.isprintable(), head
    assert all(line.isprintable() for line in out.splitlines())


@pytest.mark.parametrize("command", [["size", "{loop}", *_SIZE], ["design", "{loop}", "--out", "{tmp}/o.csv"]])
def test_a_symlink_loop_as_the_input_file_is_named(command, tmp_path, capsys):
    """A TOML input that is a symbolic link to itself printed "[Errno 40] Too many levels of symbolic links"."""
    loop = tmp_path / "loop.toml"
    loop.symlink_to(loop.name)
    code, out, err = _run(capsys, _argv(command, tmp_path, {"loop": loop}))
    _one_line_error(code, out, err, f"{loop}: cannot be read (Too many levels of symbolic links)")
