"""The bad-input corpus of issue 15: malformed files and values, each with the field its message must name.

A case is ``(id, kind, payload, field, expect)``: ``kind`` says how it is fed (a damper file to ``erdesign size``, a
measurement file to ``erdesign fit``, a requirements file to ``erdesign design``, command-line arguments), ``field``
is a text the one-line message must contain (the key, column or option at fault) and ``expect`` is ``"error"``
(exit 1 or 2) or ``"warning"`` (exit 0 with a ``warning:`` line naming the field).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

EXAMPLES = Path(__file__).resolve().parents[2] / "erdesign" / "examples"
MAKRIS = (EXAMPLES / "makris.toml").read_text()
REQUIREMENTS = (EXAMPLES / "requirements" / "makris_requirements.toml").read_text()


#: Makris's damper (erdesign/examples/makris.toml) as the API's keyword arguments, for the API cases
MAKRIS_GEOMETRY = dict(
    configuration="valve",
    duct_length="54.6 mm",
    duct_mean_diameter="14.3 mm",
    gap="0.8 mm",
    piston_diameter="33.4 mm",
    rod_diameter="11.25 mm",
)
MAKRIS_FLUID = dict(
    viscosity="7 Pa*s", yield_stress="1.8 kPa", reference_field="3 kV/mm", yield_exponent=2.0, density="1290 kg/m^3"
)


def damper_with(key: str, value: str | None) -> str:
    """The Makris damper file with ``key = value`` (``value`` as TOML text; None: the line removed)."""
    line = re.compile(rf"^{key} = .*$", re.M)
    assert line.search(MAKRIS), key
    return line.sub("" if value is None else f"{key} = {value}", MAKRIS, count=1)


# ------------------------------------------------------------------------------------------ damper files
_BAD_LENGTHS = [
    '"0 mm"',
    '"-1 mm"',
    '"1e-300 m"',
    '"1e300 m"',
    '"abc"',
    '"3 kg"',
    '"nan mm"',
    '"inf mm"',
    "5",
    '""',
    "true",
    '"1 mm mm"',
    '"1e400 m"',
]
DAMPER_CASES = []
for key in ("duct_length", "duct_mean_diameter", "gap", "piston_diameter", "rod_diameter"):
    for value in _BAD_LENGTHS:
        if key == "rod_diameter" and value in ('"0 mm"', '"1e-300 m"'):
            continue  # no rod (or a vanishing one) is allowed
        DAMPER_CASES.append((f"{key}={value}", damper_with(key, value), f"geometry.{key}", "error"))
    DAMPER_CASES.append((f"{key} missing", damper_with(key, None), f"geometry.{key}", "error"))
DAMPER_CASES += [
    ("gap implausibly small", damper_with("gap", '"0.02 mm"'), "geometry.gap", "warning"),
    ("duct_length implausibly long", damper_with("duct_length", '"5 m"'), "geometry.duct_length", "warning"),
    ("gap not below d", damper_with("gap", '"20 mm"'), "geometry.gap", "error"),
    ("rod not below piston", damper_with("rod_diameter", '"40 mm"'), "geometry.rod_diameter", "error"),
    ("ducts 0", damper_with("ducts", "0"), "geometry.ducts", "error"),
    ("ducts -1", damper_with("ducts", "-1"), "geometry.ducts", "error"),
    ("ducts 1.5", damper_with("ducts", "1.5"), "geometry.ducts", "error"),
    ("ducts text", damper_with("ducts", '"2"'), "geometry.ducts", "error"),
    ("ducts bool", damper_with("ducts", "true"), "geometry.ducts", "error"),
    ("ducts 1e12", damper_with("ducts", "1000000000000"), "geometry.ducts", "error"),
    ("ducts 100", damper_with("ducts", "100"), "geometry.ducts", "warning"),
    ("configuration pump", damper_with("configuration", '"pump"'), "geometry.configuration", "error"),
    ("configuration number", damper_with("configuration", "3"), "geometry.configuration", "error"),
    ("configuration missing", damper_with("configuration", None), "geometry.configuration", "error"),
    ("unknown geometry key", MAKRIS.replace("ducts = 1", 'ducts = 1\nstroke = "5 mm"'), "geometry.stroke", "error"),
    ("misspelt key", MAKRIS.replace("gap =", "gapp ="), "geometry.gapp", "error"),
    ("no [geometry]", MAKRIS.replace("[geometry]", "[geometri]"), "geometri", "error"),
    ("name a number", MAKRIS.replace('name = "makris-1996"', "name = 3"), "name", "error"),
    ("invalid TOML", MAKRIS.replace('gap = "0.8 mm"', 'gap = "0.8 mm'), "invalid TOML", "error"),
]
_FLUID = {
    "viscosity": ['"0 Pa*s"', '"-7 Pa*s"', '"abc"', '"7 Pa"', '"1e30 Pa*s"', "7", '"nan Pa*s"'],
    "viscosity_at_reference_field": ['"0 Pa*s"', '"13 kg"', '"1e30 Pa*s"'],
    "yield_stress": ['"-1.8 kPa"', '"1.8 kg"', '"abc"', '"1e12 Pa"', '"inf Pa"'],
    "reference_field": ['"abc"', '"3 kg"', '"0 kV/mm"', '"-3 kV/mm"', '"1e9 kV/mm"', '"3 mm"'],
    "yield_exponent": ["-1", "0", "10", '"2"', "nan", "true"],
    "density": ['"1e30 kg/m^3"', '"-1 kg/m^3"', '"1290 kg"', '"0 kg/m^3"'],
    "shear_modulus": ['"-17 kPa"', '"17 kg"', '"0 kPa"'],
    "seal_friction": ['"-112 N"', '"112 kg"', '"abc"', "112"],
}
for key, values in _FLUID.items():
    for value in values:
        DAMPER_CASES.append((f"{key}={value}", damper_with(key, value), f"fluid.{key}", "error"))
DAMPER_CASES += [
    ("density implausible", damper_with("density", '"20000 kg/m^3"'), "fluid.density", "warning"),
    ("viscosity implausible", damper_with("viscosity", '"5000 Pa*s"'), "fluid.viscosity", "warning"),
    ("reference field implausible", damper_with("reference_field", '"50 kV/mm"'), "fluid.reference_field", "warning"),
    ("unknown material", MAKRIS.replace("[fluid]", '[fluid]\nmaterial = "unobtainium"'), "fluid.material", "error"),
    ("unknown fluid key", MAKRIS.replace("[fluid]", '[fluid]\ncolour = "grey"'), "fluid.colour", "error"),
]

# ------------------------------------------------------------------------------------------ measurement files
_t = np.arange(0, 2.0, 0.002)
_x = 4 * np.sin(2 * np.pi * _t)  # mm
_v = 8 * np.pi * np.cos(2 * np.pi * _t) * 1e-3  # m/s
_F = 112 * np.sign(_v) + 1.2e5 * _v + 800 * np.sign(_v)  # N, about what the Makris damper makes at 0 field


def record(columns: str = "time [s],displacement [mm],force [N]", t=_t, x=_x, F=_F, extra=None, sep=",") -> str:
    rows = [sep.join(f"{c:.10g}" for c in row) for row in zip(t, x, F, *(extra or []))]
    return columns.replace(",", sep) + "\n" + "\n".join(rows) + "\n"


GOOD_RECORD = record()
_lines = GOOD_RECORD.splitlines()


def _swap_line(i: int, text: str) -> str:
    lines = list(_lines)
    lines[i] = text
    return "\n".join(lines) + "\n"


MEASUREMENT_CASES = [
    (
        "no units",
        GOOD_RECORD.replace("time [s],displacement [mm],force [N]", "time,displacement,force"),
        "column 1",
        "error",
    ),
    ("unknown unit", GOOD_RECORD.replace("force [N]", "force [Nn]"), "force", "error"),
    ("force in kg", GOOD_RECORD.replace("force [N]", "force [kg]"), "force", "error"),
    ("displacement in s", GOOD_RECORD.replace("displacement [mm]", "displacement [s]"), "displacement", "error"),
    ("time in m", GOOD_RECORD.replace("time [s]", "time [m]"), "time", "error"),
    ("unknown column", GOOD_RECORD.replace("force [N]", "forse [N]"), "forse", "error"),
    ("missing force", record("time [s],displacement [mm],velocity [m/s]"), "force", "error"),
    ("twice a column", GOOD_RECORD.replace("force [N]", "time [s]"), "time", "error"),
    (
        "two controls",
        record(
            "time [s],displacement [mm],force [N],field [kV/mm],current [A]",
            extra=[np.zeros_like(_t), np.zeros_like(_t)],
        ),
        "control column",
        "error",
    ),
    (
        "field in kg",
        record("time [s],displacement [mm],force [N],field [kg]", extra=[np.zeros_like(_t)]),
        "field",
        "error",
    ),
    (
        "field of the wrong kind",
        record("time [s],displacement [mm],force [N],field [kA/m]", extra=[np.ones_like(_t)]),
        "field",
        "error",
    ),
    ("tab separated", record(sep="\t"), "tabs", "error"),
    ("';' and ',' in the header", GOOD_RECORD.replace("time [s],", "time [s];", 1), "both ';' and ','", "error"),
    ("empty file", "", "empty file", "error"),
    ("header only", "time [s],displacement [mm],force [N]\n", "data rows", "error"),
    ("four rows", "\n".join(_lines[:5]) + "\n", "at least 5", "error"),
    ("text cell", _swap_line(10, "0.018,abc,1.0"), "line 11, column 2 (displacement)", "error"),
    ("nan cell", _swap_line(10, "0.018,1.0,nan"), "line 11, column 3 (force)", "error"),
    ("inf cell", _swap_line(10, "0.018,1.0,inf"), "line 11, column 3 (force)", "error"),
    ("empty cell", _swap_line(10, "0.018,,1.0"), "line 11, column 2", "error"),
    ("missing cell", _swap_line(10, "0.018,1.0"), "line 11", "error"),
    ("extra cell", _swap_line(10, "0.018,1.0,2.0,3.0"), "line 11", "error"),
    ("time backwards", _swap_line(10, "0.001,1.0,2.0"), "time", "error"),
    ("time repeated", _swap_line(10, _lines[9]), "time", "error"),
    ("force x1e300", record(F=_F * 1e300), "force", "error"),
    ("displacement in km", GOOD_RECORD.replace("displacement [mm]", "displacement [km]"), "displacement", "error"),
    ("constant displacement", record(x=np.ones_like(_t)), "displacement", "error"),
    ("zero displacement", record(x=np.zeros_like(_t)), "displacement", "error"),
    (
        "field x1e12",
        record("time [s],displacement [mm],force [N],field [kV/mm]", extra=[np.full_like(_t, 3e12)]),
        "field",
        "error",
    ),
    ("binary", b"\xff\xfe\x00\x01\x02", "UTF-8", "error"),
    # warnings: the record is possible but something looks wrong (a unit mistake is named when likely)
    ("force in mN", GOOD_RECORD.replace("force [N]", "force [mN]"), "force", "warning"),
    ("force in kN", GOOD_RECORD.replace("force [N]", "force [kN]"), "force", "warning"),
    ("displacement in m", GOOD_RECORD.replace("displacement [mm]", "displacement [m]"), "displacement", "warning"),
    ("displacement in um", GOOD_RECORD.replace("displacement [mm]", "displacement [um]"), "displacement", "warning"),
    ("time in ms", GOOD_RECORD.replace("time [s]", "time [ms]"), "velocity", "warning"),
    ("time x1e-12", record(t=_t * 1e-12), "time", "warning"),
    ("few samples", record(t=_t[::50], x=_x[::50], F=_F[::50]), "time", "warning"),
    ("half a cycle", record(t=_t[:300], x=_x[:300], F=_F[:300]), "displacement", "warning"),
    (
        "velocity column contradicts",
        record("time [s],displacement [mm],force [N],velocity [m/s]", extra=[-3 * _v]),
        "velocity",
        "warning",
    ),
]
#: The cases whose message must name the likely factor-1000 unit mistake (issue 15, "Done when").
UNIT_MISTAKES = ("force in mN", "force in kN", "displacement in m", "displacement in um")

# ------------------------------------------------------------------------------------------ requirements files
_REQ = REQUIREMENTS + "\n" if "[design.search]" in REQUIREMENTS else REQUIREMENTS + "\n[design.search]\n"


def requirements_with(pattern: str, replacement: str) -> str:
    assert re.search(pattern, _REQ, re.M), pattern
    return re.sub(pattern, replacement, _REQ, count=1, flags=re.M)


def search_with(line: str) -> str:
    return _REQ.replace("[design.search]", f"[design.search]\n{line}", 1)


REQUIREMENTS_CASES = [
    ("samples 1e10", search_with("samples = 10000000000"), "design.search.samples", "error"),
    ("samples 0", search_with("samples = 0"), "design.search.samples", "error"),
    ("samples text", search_with('samples = "many"'), "design.search.samples", "error"),
    ("chunk 1e9", search_with("chunk = 1000000000"), "design.search.chunk", "error"),
    ("designs 1e6", search_with("designs = 1000000"), "design.search.designs", "error"),
    ("sampling unknown", search_with('sampling = "grid"'), "design.search.sampling", "error"),
    ("pareto unknown", search_with('pareto = ["beauty", "fluid_volume"]'), "design.search.pareto", "error"),
    ("unknown search key", search_with("speed = 3"), "design.search.speed", "error"),
    ("gap bound zero", requirements_with(r"^gap = .*$", 'gap = ["0 mm", "2 mm"]'), "design.bounds.gap", "error"),
    ("gap bound reversed", requirements_with(r"^gap = .*$", 'gap = ["2 mm", "0.5 mm"]'), "design.bounds.gap", "error"),
    ("gap bound unitless", requirements_with(r"^gap = .*$", "gap = [0.5, 2]"), "design.bounds.gap", "error"),
    ("gap bound mass", requirements_with(r"^gap = .*$", 'gap = ["0.5 kg", "2 kg"]'), "design.bounds.gap", "error"),
    ("ducts bound zero", requirements_with(r"^ducts = .*$", "ducts = [0, 4]"), "design.bounds.ducts", "error"),
    ("velocity negative", requirements_with(r"^velocity = .*$", 'velocity = "-1 in/s"'), "velocity", "error"),
    ("velocity unknown unit", requirements_with(r"^velocity = .*$", 'velocity = "1 blorp/s"'), "velocity", "error"),
    ("min_force mass", requirements_with(r"^min_force = .*$", 'min_force = "6 kg"'), "min_force", "error"),
    ("field impossible", requirements_with(r"^field = .*$", 'field = "1e9 kV/mm"'), "field", "error"),
    (
        "objective unknown",
        requirements_with(r"^objective = .*$", 'objective = "cheapest"'),
        "design.objective",
        "error",
    ),
    (
        "configuration unknown",
        requirements_with(r"^configuration = .*$", 'configuration = "pump"'),
        "design.configuration",
        "error",
    ),
    ("laminar text", requirements_with(r"^laminar = .*$", 'laminar = "yes"'), "design.limits.laminar", "error"),
    (
        "max_pressure negative",
        requirements_with(r"^max_pressure = .*$", 'max_pressure = "-1 MPa"'),
        "design.limits.max_pressure",
        "error",
    ),
    (
        "fluid density impossible",
        requirements_with(r"^\[fluid\]$", '[fluid]\ndensity = "1e30 kg/m^3"'),
        "fluid.density",
        "error",
    ),
]

# ------------------------------------------------------------------------------------------ command-line values
#: (id, arguments with {damper} {record} {req} {tmp} placeholders, field, expect)
OPTION_CASES = [
    ("size velocity text", ["size", "{damper}", "--velocity", "fast"], "velocity", "error"),
    ("size velocity mass", ["size", "{damper}", "--velocity", "3 kg"], "velocity", "error"),
    ("size velocity nan", ["size", "{damper}", "--velocity", "nan m/s"], "velocity", "error"),
    ("size velocity inf", ["size", "{damper}", "--velocity", "inf"], "velocity", "error"),
    ("size velocity empty", ["size", "{damper}", "--velocity", ""], "velocity", "error"),
    ("size velocity bare", ["size", "{damper}", "--velocity", "0.0254"], "--velocity", "warning"),
    ("size field text", ["size", "{damper}", "--velocity", "1 in/s", "--field", "strong"], "field", "error"),
    ("size field kind", ["size", "{damper}", "--velocity", "1 in/s", "--field", "3 kA/m"], "field", "error"),
    ("size field 1e9 kV/mm", ["size", "{damper}", "--velocity", "1 in/s", "--field", "1e9 kV/mm"], "field", "error"),
    ("size field 50 kV/mm", ["size", "{damper}", "--velocity", "1 in/s", "--field", "50 kV/mm"], "field", "warning"),
    ("size no file", ["size", "{tmp}/nothing.toml", "--velocity", "1 in/s"], "nothing.toml", "error"),
    ("size folder", ["size", "{tmp}", "--velocity", "1 in/s"], "directory", "error"),
    ("report out pdf", ["report", "{damper}", "--out", "{tmp}/r.pdf"], "--out", "error"),
    ("report out no suffix", ["report", "{damper}", "--out", "{tmp}/report"], "--out", "error"),
    ("report out the damper", ["report", "{damper}", "--out", "{damper}", "--force"], "--out", "error"),
    ("report out md as html", ["report", "{damper}", "--out", "{tmp}/r.md", "--format", "html"], "--format", "error"),
    ("report out exists", ["report", "{damper}", "--out", "{tmp}/keep.html"], "--force", "error"),
    ("report out folder", ["report", "{damper}", "--out", "{tmp}/sub.html"], "folder", "error"),
    ("report out missing folder", ["report", "{damper}", "--out", "{tmp}/no/such/r.html"], "--out", "error"),
    (
        "report velocity range text",
        ["report", "{damper}", "--out", "{tmp}/v.html", "--velocity-range", "a", "b"],
        "velocity",
        "error",
    ),
    ("report field mass", ["report", "{damper}", "--out", "{tmp}/f.html", "--field", "3 kg"], "field", "error"),
    ("design out the requirements", ["design", "{req}", "--out", "{req}", "--force"], "--out", "error"),
    ("design out exists", ["design", "{req}", "--out", "{tmp}/keep.csv"], "--force", "error"),
    ("design out txt", ["design", "{req}", "--out", "{tmp}/d.txt"], "--out", "error"),
    (
        "simulate out the record",
        ["simulate", "{record}", "--model", "bingham", "--params", "f_y=100 N", "--out", "{record}", "--force"],
        "--out",
        "error",
    ),
    (
        "simulate out exists",
        ["simulate", "{record}", "--model", "bingham", "--params", "f_y=100 N", "--out", "{tmp}/keep.csv"],
        "--force",
        "error",
    ),
    (
        "simulate out pdf",
        ["simulate", "{record}", "--model", "bingham", "--params", "f_y=100 N", "--out", "{tmp}/s.pdf"],
        "--out",
        "error",
    ),
    ("fit effects ,,", ["fit", "{record}", "--damper", "{damper}", "--effects", ",,"], "--effects", "error"),
    (
        "fit effects a,,b",
        ["fit", "{record}", "--damper", "{damper}", "--effects", "seal_friction,,fluid_inertia"],
        "--effects",
        "error",
    ),
    (
        "fit effects twice",
        ["fit", "{record}", "--damper", "{damper}", "--effects", "seal_friction,seal_friction"],
        "--effects",
        "error",
    ),
    ("diagnose effects ,,", ["diagnose", "{record}", "--damper", "{damper}", "--effects", ",,"], "--effects", "error"),
    ("fit record folder", ["fit", "{tmp}", "--damper", "{damper}"], "folder", "error"),
    ("fit damper missing", ["fit", "{record}", "--damper", "{tmp}/none.toml"], "none.toml", "error"),
    ("magnetics current text", ["magnetics", "{mr_coil}", "--current", "lots"], "--current", "error"),
    ("magnetics current empty", ["magnetics", "{mr_coil}", "--current", ","], "--current", "error"),
    ("magnetics current volt", ["magnetics", "{mr_coil}", "--current", "2 V"], "--current", "error"),
]
