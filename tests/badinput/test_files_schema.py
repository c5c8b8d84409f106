"""The damper file's schema, declared once (erdesign.damper.files.DamperFile, pydantic 2): every bad table or value
is one line naming the dotted key (never pydantic's multi-line report), and docs/file_formats.md's key tables are
the schema's."""

from __future__ import annotations

import copy
import importlib.util
import re
from pathlib import Path

import pytest

from erdesign.damper.files import DamperFile, damper_from_dict, damper_spec, load_example
from erdesign.errors import DamperFileError, ErdesignError
from erdesign.schema import key_table

ROOT = Path(__file__).resolve().parents[2]
SPENCER = damper_spec(load_example("spencer1997"))  # has [accumulator] and rod = "single"


def _changed(path: str, value, spec=SPENCER) -> dict:
    """``spec`` with the value at the dotted ``path`` replaced (``...`` deletes it)."""
    data = copy.deepcopy(spec)
    *tables, key = path.split(".")
    where = data
    for t in tables:
        where = where[t]
    if value is ...:
        del where[key]
    else:
        where[key] = value
    return data


@pytest.mark.parametrize(
    "path, value, message",
    [
        ("geometry", "valve", r"^geometry: expected a table, got 'valve'$"),
        ("fluid", [1, 2], r"^fluid: expected a table, got \[1, 2\]$"),
        ("accumulator", 3, r"^accumulator: expected a table, got 3$"),
        ("coil", "big", r"^coil: expected a table, got 'big'$"),
        ("name", 3, r"^name: expected text, got 3$"),
        ("geometry", ..., r"^\[geometry\]: missing table$"),
        ("geometry.configuration", ..., r"^geometry.configuration: missing \('valve' or 'mixed'\)$"),
        ("geometry.configuration", 1, r"^geometry.configuration: must be one of 'valve', 'mixed', got 1$"),
        ("geometry.rod", "triple", r"^geometry.rod: must be one of 'double', 'single', got 'triple'$"),
        ("geometry.ducts", True, r"^geometry.ducts: expected a whole number, got True$"),
        ("geometry.ducts", 2.0, r"^geometry.ducts: expected a whole number, got 2.0$"),
        (
            "geometry.gap",
            ["1 mm"],
            r"^geometry.gap: expected a value with a unit as a string \(e.g. \"1 m\"\), got \['1 mm'\]$",
        ),
        ("geometry.gap", "1 s", r"^geometry.gap: expected a length .*got '1 s' \(a time\)$"),
        ("geometry.gap", "-1 mm", r"^geometry.gap: must be positive, got '-1 mm'$"),
        (
            "geometry.gap_width",
            "1 mm",
            r"^geometry.gap_width: unknown key in \[geometry\]; allowed keys: configuration, ",
        ),
        ("fluid.yield_exponent", "2", r"^fluid.yield_exponent: expected a number, got '2'$"),
        ("fluid.yield_exponent", False, r"^fluid.yield_exponent: expected a number, got False$"),
        ("fluid.seal_friction", "5 m", r"^fluid.seal_friction: expected a force"),
        ("fluid.seal_friction", "-5 N", r"^fluid.seal_friction: must not be negative, got '-5 N'$"),
        ("fluid.reference_field", "3 mm", r"^fluid.reference_field: expected an electric field"),
        ("fluid.density", {"value": 1}, r"^fluid.density: expected a value with a unit as a string"),
        ("fluid.material", 7, r"^fluid.material: expected text, got 7$"),
        ("accumulator.polytropic_index", "1.4", r"^accumulator.polytropic_index: expected a number, got '1.4'$"),
        ("accumulator.gas_volume", ..., r"^accumulator.gas_volume: missing$"),
        ("accumulator.precharge", "0 Pa", r"^accumulator.precharge: must be positive, got '0 Pa'$"),
        (
            "accumulator.volume",
            "1 l",
            r"^accumulator.volume: unknown key in \[accumulator\] \(did you mean 'gas_volume'\?\); allowed keys: precharge, ",
        ),
        ("colour", "red", r"^colour: unknown key; allowed keys: name, geometry, fluid, coil, accumulator$"),
    ],
)
def test_every_bad_key_is_one_line_naming_the_dotted_key(path, value, message):
    with pytest.raises(DamperFileError) as info:
        damper_from_dict(_changed(path, value), source="")
    text = str(info.value).removeprefix(": ")
    assert "\n" not in text and "pydantic" not in text and "validation error" not in text.lower()
    assert re.search(message, text), text


def test_a_misspelt_key_is_named_not_the_key_it_leaves_missing():
    data = _changed("geometry.gap", ...)
    data["geometry"]["gapp"] = "1 mm"
    with pytest.raises(DamperFileError, match=r"^d.toml: geometry.gapp: unknown key"):
        damper_from_dict(data, source="d.toml")


def test_the_whole_file_must_be_a_table():
    with pytest.raises(ErdesignError, match="^d: file: expected a table, got None$"):
        damper_from_dict(None, source="d")


def test_a_valid_file_passes_the_schema_unchanged():
    spec = DamperFile.model_validate(SPENCER)
    assert spec.geometry.gap == SPENCER["geometry"]["gap"]  # kept as given; the objects convert to SI
    assert damper_from_dict(SPENCER) == load_example("spencer1997")


def test_the_key_tables_of_the_docs_are_the_schemas():
    spec = importlib.util.spec_from_file_location("make_key_tables", ROOT / "docs" / "make_key_tables.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    for doc in module.DOCS:
        text = doc.read_text(encoding="utf-8")
        assert module.render(text) == text, f"{doc.name} is out of date: run python docs/make_key_tables.py"
    text = (ROOT / "docs" / "file_formats.md").read_text(encoding="utf-8")
    for model in (
        "damper.files.DamperFile",
        "damper.files.GeometryTable",
        "damper.files.FluidTable",
        "damper.accumulator.AccumulatorTable",
        "design.requirements.RequirementsFile",
        "design.requirements.DesignTable",
        "design.requirements.PointTable",
        "design.requirements.LimitsTable",
        "design.requirements.BoundsTable",
        "design.requirements.EnvelopeTable",
        "design.requirements.SearchTable",
        "design.requirements.CoilTable",
        "magnetics.coil.CoilTable",
    ):
        assert f"<!-- keys: erdesign.{model} -->" in text
    table = key_table(DamperFile)
    assert all(f"| `{key}` |" in table for key in DamperFile.model_fields)


# ------------------------------------------------------------------------------ values a file cannot mean
REQUIREMENTS = {
    "fluid": {"material": "makris-zeolite-silicone"},
    "design": {
        "configuration": "valve",
        "point": [{"velocity": "1 in/s", "field": "3 kV/mm", "min_force": "5 kN"}],
        "limits": {"min_gap": "3 mm"},
        "bounds": {
            "gap": ["0.5 mm", "2 mm"],
            "duct_length": ["20 mm", "150 mm"],
            "duct_mean_diameter": ["5 mm", "40 mm"],
            "piston_diameter": "33.4 mm",
            "rod_diameter": "11.25 mm",
        },
    },
}


def test_min_gap_above_the_gap_bounds_is_refused_naming_both_keys():
    from erdesign.design.requirements import RequirementsError, requirements_from_dict

    with pytest.raises(
        RequirementsError,
        match=r"^r.toml: design.limits.min_gap: 3 mm is above the largest gap "
        r"of design.bounds.gap \(2 mm\)",
    ):
        requirements_from_dict(REQUIREMENTS, source="r.toml")
    inside = copy.deepcopy(REQUIREMENTS)
    inside["design"]["limits"]["min_gap"] = "1 mm"  # within the bounds: a constraint, accepted
    assert requirements_from_dict(inside).limits.min_gap == pytest.approx(1e-3)


@pytest.mark.parametrize(
    "low, message",
    [
        ("-300 degC", r"range.temperature: '-300 degC' is below absolute zero \(-26.85 K\)"),
        ("-10 K", r"range.temperature: '-10 K' is below absolute zero"),
    ],
)
def test_a_material_temperature_below_absolute_zero_is_refused(tmp_path, low, message):
    from erdesign.materials import read_material_file

    source = (ROOT / "erdesign" / "materials" / "lord-mrf-132dg.toml").read_text(encoding="utf-8")
    assert 'temperature = ["-40 degC", "130 degC"]' in source
    path = tmp_path / "m.toml"
    path.write_text(source.replace('temperature = ["-40 degC"', f'temperature = ["{low}"'), encoding="utf-8")
    with pytest.raises(ErdesignError, match=message):
        read_material_file(path)


# ----------------------------------------------------------------------------- the requirements file's schema
def _requirements(**design) -> dict:
    data = copy.deepcopy(REQUIREMENTS)
    data["design"].pop("limits")
    data["design"].update(design)
    return data


@pytest.mark.parametrize(
    "change, message",
    [
        ({"point": []}, r"^design.point: expected one or more \[\[design.point\]\] tables, got \[\]$"),
        (
            {"point": [{"velocity": "1 in/s", "min_force": "5 kN"}, {"min_force": "5 kN"}]},
            r"^design.point\[2\].velocity: missing$",
        ),
        ({"point": "fast"}, r"^design.point: expected a list of tables, got 'fast'$"),
        (
            {"point": [{"velocity": 0.0254, "min_force": "5 kN"}]},
            r"^design.point\[1\].velocity: expected a value with a unit as a string \(e.g. \"1 m/s\"\), got 0.0254$",
        ),
        (
            {"point": [{"velocity": "1 in/s", "min_dynamic_range": 0}]},
            r"^design.point\[1\].min_dynamic_range: must be positive, got 0$",
        ),
        ({"search": {"samples": "many"}}, r"^design.search.samples: expected a whole number, got 'many'$"),
        ({"search": {"chunk": 10}}, r"^design.search.chunk: must be >= 1024, got 10$"),
        (
            {"search": {"samplez": 10}},
            r"^design.search.samplez: unknown key in \[design.search\] \(did you mean 'samples'\?\); allowed keys: samples, ",
        ),
        ({"search": {"pareto": "force"}}, r"^design.search.pareto: expected a list of two or three figure names"),
        ({"limits": {"laminar": 1}}, r"^design.limits.laminar: expected true or false, got 1$"),
        ({"bounds": "wide"}, r"^design.bounds: expected a table, got 'wide'$"),
        ({"envelope": {"wall": "-1 mm"}}, r"^design.envelope.wall: must not be negative, got '-1 mm'$"),
        ({"objective": "cheap"}, r"^design.objective: must be one of 'min_fluid_volume', "),
    ],
)
def test_every_bad_requirement_is_one_line_naming_the_dotted_key(change, message):
    from erdesign.design.requirements import RequirementsError, requirements_from_dict

    with pytest.raises(RequirementsError) as info:
        requirements_from_dict(_requirements(**change), source="")
    text = str(info.value).removeprefix(": ")
    assert "\n" not in text and "pydantic" not in text and re.search(message, text), text


def test_a_bound_is_a_range_or_one_value_read_in_si():
    from erdesign.design.requirements import RequirementsError, requirements_from_dict

    bounds = {**REQUIREMENTS["design"]["bounds"], "gap": ["0.5 mm", "1 mm", "2 mm"]}
    with pytest.raises(RequirementsError, match=r"^r: design.bounds.gap: expected \[\"low unit\", \"high unit\"\]"):
        requirements_from_dict(_requirements(bounds=bounds), source="r")
    single = requirements_from_dict(_requirements(point={"velocity": "1 in/s", "min_force": "5 kN"}))
    assert single.bounds["piston_diameter"] == pytest.approx((0.0334, 0.0334))  # one value: fixed
    assert single.bounds["gap"] == pytest.approx((0.5e-3, 2e-3)) and single.bounds["ducts"] == (1, 1)
    assert len(single.points) == 1 and single.points[0].velocity == pytest.approx(0.0254)


def test_a_spec_built_in_python_may_hold_numpy_numbers():
    """A TOML file holds Python numbers only; a dict built by a script or the app may hold numpy ones."""
    import numpy as np

    data = _changed("geometry.ducts", np.int64(1))
    data["fluid"]["yield_exponent"] = np.float64(data["fluid"]["yield_exponent"])
    assert damper_from_dict(data) == load_example("spencer1997")
