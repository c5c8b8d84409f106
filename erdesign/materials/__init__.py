"""The materials database: one TOML file per fluid in this folder, each value with its units, source and range.

This folder is installed as the package ``erdesign.materials``.  A damper file's ``[fluid]`` table may name a
material (``material = "makris-zeolite-silicone"``) and override any of its values (docs/materials.md).

File layout (``<name>.toml``)::

    name = "..."                 # must equal the file name
    kind = "ER"                  # "ER" or "MR"
    description = "..."
    [fluid]                      # keys of a damper file's [fluid] table, values with units: the power-law
    viscosity = "7 Pa*s"         # summary (exact at reference_field) that a damper file may override
    ...
    [yield_curve]                # optional richer law of tau_y(E): law = "power" | "saturating" | "carlson" |
    law = "carlson"              # "table" (erdesign.fluid.field_laws.field_law_from_dict); fit_range is the range the
    fit_range = ["0 kA/m", "250 kA/m"]   # power-law summary of [fluid] was fitted on
    [range]                      # where the values hold: field, temperature, shear_rate, each [low, high]
    field = ["0 kA/m", "250 kA/m"]
    [spread]                     # optional: published spread [low, high] of [fluid] values (typical fluids)
    [sources]                    # for each value of [fluid] (and yield_curve, range, spread): where it comes from,
    viscosity = "makris1996: section 3, 0.001 psi s"   # naming a reference key
    [[references]]               # key, citation, date (of the document or its revision), optional note
    key = "makris1996"
    [verification.yield_stress]  # optional: how far each curve or value was checked against its source
    status = "verified"          # "verified" | "replaced" | "not verified" (VERIFICATION_STATUSES)
    source = "makris1996"        # a reference key
    location = "section 2.3"     # where in the source (table, equation, figure, block); needed unless not verified
    found_at = "..."             # where the text was read (repository + path + commit, page address, seed copy)
    searched = "..."             # "not verified" only: what was searched without finding a citable source

MR fluids may also give their magnetisation curve (``[magnetization]``: ``law = "carlson"`` with
``volume_fraction``, or ``law = "table"``; :func:`erdesign.magnetics.bh.bh_curve_from_dict`), which the magnetic
circuit of a damper with a ``[coil]`` needs.

Steels (the core, poles and housing of an MR damper's magnetic circuit) are files named ``steel-<grade>.toml`` with
``kind = "steel"``, a ``[magnetization]`` table, ``[sources]`` and ``[[references]]`` and no ``[fluid]``; they are
listed by :func:`steel_names` and read by :func:`load_steel` / :func:`steel_curve`, not by :func:`names`.

Functions: :func:`names`, :func:`load` (the checked record), :func:`fluid_values` (its ``[fluid]`` table),
:func:`material_fluid` (what a damper file takes from it: values, yield curve, field range) and :func:`summary`
(the JSON of ``erdesign materials --json``).
"""

from __future__ import annotations

import sys
from collections.abc import Mapping
from importlib import resources
from pathlib import Path
from typing import Any, NamedTuple

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from .._pint import pint  # not `import pint`: erdesign/_pint.py
from ..errors import ErdesignError, did_you_mean
from ..fluid.field_laws import FieldLaw, control_unit_of, field_law_from_dict
from ..units import Q_, parse_quantity, to_si

__all__ = [
    "names",
    "load",
    "fluid_values",
    "steel_names",
    "load_steel",
    "steel_curve",
    "magnetization_curve",
    "material_fluid",
    "MaterialFluid",
    "summary",
    "check_record",
    "read_material_file",
    "parse_quantity",
    "MATERIAL_KEYS",
    "MATERIAL_FLUID_KEYS",
    "RANGE_KEYS",
    "VERIFICATION_STATUSES",
    "VERIFICATION_KEYS",
]

MATERIAL_KEYS = (
    "name",
    "kind",
    "description",
    "fluid",
    "yield_curve",
    "magnetization",
    "range",
    "spread",
    "sources",
    "references",
    "verification",
)
STEEL_KEYS = ("name", "kind", "description", "magnetization", "sources", "references", "verification")
_STEEL_REQUIRED = ("name", "kind", "description", "magnetization", "sources", "references")
#: Outcomes of checking a value against its source: "verified" (it matches a citable source that was read),
#: "replaced" (it was changed to a citable source that was read) or "not verified" (no citable source was found).
VERIFICATION_STATUSES = ("verified", "replaced", "not verified")
#: Keys of one ``[verification.<key>]`` table.
VERIFICATION_KEYS = ("status", "source", "location", "found_at", "agrees_with", "searched", "note")
_STEEL_PREFIX = "steel-"
MATERIAL_FLUID_KEYS = (
    "viscosity",
    "yield_stress",
    "reference_field",
    "yield_exponent",
    "density",
    "viscosity_at_reference_field",
    "shear_modulus",
)
_REQUIRED_FLUID = ("viscosity", "yield_stress", "reference_field", "yield_exponent", "density")
_FLUID_SI = {
    "viscosity": "Pa*s",
    "yield_stress": "Pa",
    "density": "kg/m^3",
    "viscosity_at_reference_field": "Pa*s",
    "shear_modulus": "Pa",
}
#: Validity ranges a material may state, with the SI unit of each ("field" takes the unit of the control).
RANGE_KEYS = {"field": None, "temperature": "K", "shear_rate": "1/s"}
_REFERENCE_KEYS = ("key", "citation", "date", "note")


class MaterialFluid(NamedTuple):
    """What a damper file takes from a material (:func:`material_fluid`)."""

    name: str
    values: dict
    """The ``[fluid]`` table (strings with units, and the exponent)."""
    yield_curve: FieldLaw | None
    """The material's richer law of the yield stress, or None (the power law of ``values``)."""
    field_range: tuple[str, str] | None
    """``[range] field`` as given (strings with units), or None."""


def names() -> list[str]:
    """Names of the fluids in the database (the steels are listed by :func:`steel_names`)."""
    return sorted(
        p.name[:-5]
        for p in resources.files(__name__).iterdir()
        if p.name.endswith(".toml") and not p.name.startswith(_STEEL_PREFIX)
    )


def steel_names() -> list[str]:
    """Names of the steels in the database (``steel-1018``, ...)."""
    return sorted(
        p.name[:-5]
        for p in resources.files(__name__).iterdir()
        if p.name.endswith(".toml") and p.name.startswith(_STEEL_PREFIX)
    )


def _pair(value: Any, name: str, si_unit: str) -> tuple[float, float]:
    if not (isinstance(value, list) and len(value) == 2):
        raise ErdesignError(f"{name}: expected [low, high], got {value!r}")
    lo, hi = (
        Q_(float(v), "")
        if isinstance(v, (int, float)) and not isinstance(v, bool)
        else parse_quantity(v, f"{name}[{i}]")
        for i, v in enumerate(value)
    )
    try:
        lo_si, hi_si = lo.to(si_unit).magnitude, hi.to(si_unit).magnitude
    except pint.errors.DimensionalityError:
        raise ErdesignError(f"{name}: expected values convertible to {si_unit}, got {value!r}") from None
    if not lo_si <= hi_si:
        raise ErdesignError(f"{name}: low must not exceed high, got {value!r}")
    if si_unit == "K" and not lo_si >= 0:
        raise ErdesignError(
            f"{name}: {value[0]!r} is below absolute zero ({lo_si:.6g} K); a temperature in degC or degF needs its unit"
        )
    return float(lo_si), float(hi_si)


def check_record(record: Mapping[str, Any], where: str) -> None:
    """Check a material record (a parsed TOML file); the error names ``where`` and the key at fault."""
    unknown = [k for k in record if k not in MATERIAL_KEYS]
    if unknown:
        raise ErdesignError(f"{where}: {unknown[0]}: unknown key; allowed keys: {', '.join(MATERIAL_KEYS)}")
    for key in ("name", "kind", "description", "fluid", "sources", "references"):
        if key not in record:
            raise ErdesignError(f"{where}: {key}: missing")
    if record["kind"] not in ("ER", "MR"):
        raise ErdesignError(f'{where}: kind: expected "ER" or "MR", got {record["kind"]!r}')
    fluid = record["fluid"]
    for key in fluid:
        if key not in MATERIAL_FLUID_KEYS:
            raise ErdesignError(f"{where}: fluid.{key}: unknown key; allowed keys: {', '.join(MATERIAL_FLUID_KEYS)}")
    for key in _REQUIRED_FLUID:
        if key not in fluid:
            raise ErdesignError(f"{where}: fluid.{key}: missing")
    try:
        control = control_unit_of(fluid["reference_field"], "fluid.reference_field")
        for key, unit in _FLUID_SI.items():
            if key in fluid:
                to_si(fluid[key], unit, f"fluid.{key}")
        if "yield_curve" in record:
            field_law_from_dict(record["yield_curve"], control_unit=control)
            if "fit_range" not in record["yield_curve"]:
                raise ErdesignError("yield_curve.fit_range: missing (the range of the power-law summary of [fluid])")
            _pair(record["yield_curve"]["fit_range"], "yield_curve.fit_range", control)
        if "magnetization" in record:
            if record["kind"] != "MR":
                raise ErdesignError("magnetization: only MR fluids have a magnetisation curve")
            from ..magnetics.bh import bh_curve_from_dict

            bh_curve_from_dict(record["magnetization"], name=record["name"])
        for key, value in record.get("range", {}).items():
            if key not in RANGE_KEYS:
                raise ErdesignError(f"range.{key}: unknown key; allowed keys: {', '.join(RANGE_KEYS)}")
            _pair(value, f"range.{key}", RANGE_KEYS[key] or control)
        for key, value in record.get("spread", {}).items():
            if key not in MATERIAL_FLUID_KEYS:
                raise ErdesignError(f"spread.{key}: unknown key; allowed: the keys of [fluid]")
            _pair(value, f"spread.{key}", "" if key == "yield_exponent" else (_FLUID_SI.get(key) or control))
    except ErdesignError as exc:
        raise type(exc)(f"{where}: {exc}") from None
    _check_references(record, where)
    _check_verification(record, where)
    sources = record["sources"]
    for key in list(fluid) + [k for k in ("yield_curve", "magnetization", "range", "spread") if k in record]:
        if key not in sources:
            raise ErdesignError(f"{where}: sources.{key}: missing (every value needs its source)")


def read_material_file(path: str | Path, *, where: str | None = None) -> dict[str, Any]:
    """Read and check a material file anywhere on disk (to try a new material before adding it here).

    ``where`` names the file in error messages (default: the path).
    """
    from ..damper.files import read_toml  # the one TOML reader: limits, encodings, a named pipe refused

    path = Path(path)
    where = where or str(path)
    try:
        record = read_toml(path)
    except ErdesignError as exc:
        raise ErdesignError(str(exc).replace(str(path), where, 1)) from None
    check_record(record, where)
    if record["name"] != path.stem:
        raise ErdesignError(f"{where}: name: must equal the file name ({path.stem!r}), got {record['name']!r}")
    return record


def load(name: str) -> dict[str, Any]:
    """The whole record of a material (its TOML file as a dictionary), checked."""
    if name not in names():
        raise ErdesignError(
            f"unknown material {name!r}{did_you_mean(name, names())}; known materials: {', '.join(names())}"
        )
    with resources.as_file(resources.files(__name__) / f"{name}.toml") as path:
        return read_material_file(path, where=f"materials/{name}.toml")


def fluid_values(name: str) -> dict[str, Any]:
    """The ``[fluid]`` values of a material, as a damper file would give them."""
    return dict(load(name).get("fluid", {}))


def material_fluid(name: str) -> MaterialFluid:
    """What a damper file naming this material takes from it: values, yield curve and field range."""
    record = load(name)
    values = dict(record["fluid"])
    curve = None
    if "yield_curve" in record:
        curve = field_law_from_dict(
            record["yield_curve"], control_unit=control_unit_of(values["reference_field"], "fluid.reference_field")
        )
    field = record.get("range", {}).get("field")
    return MaterialFluid(name, values, curve, None if field is None else (field[0], field[1]))


def summary(name: str) -> dict[str, Any]:
    """A JSON-ready summary of a material: kind, control, values, yield law (with its power-law fit), ranges."""
    record = load(name)
    fluid = record["fluid"]
    control = control_unit_of(fluid["reference_field"], "fluid.reference_field")
    out: dict[str, Any] = {
        "name": record["name"],
        "kind": record["kind"],
        "description": record["description"],
        "control_unit": control,
        "fluid": dict(fluid),
        "yield_curve": None,
        "range": {k: list(v) for k, v in record.get("range", {}).items()},
        "references": [dict(r) for r in record["references"]],
        "verification": {k: dict(v) for k, v in record.get("verification", {}).items()},
    }
    if "yield_curve" in record:
        mf = material_fluid(name)
        lo, hi = _pair(record["yield_curve"]["fit_range"], "yield_curve.fit_range", control)
        fit = mf.yield_curve.fit(hi, lo, reference_field=to_si(fluid["reference_field"], control, "reference_field"))
        out["yield_curve"] = {
            "law": record["yield_curve"]["law"],
            "description": mf.yield_curve.describe(f"{Q_(fluid['reference_field']).units:~}"),
            "fit_range": list(record["yield_curve"]["fit_range"]),
            "power_law_exponent": round(fit.yield_exponent, 4),
            "power_law_max_relative_error": round(fit.max_relative_error, 4),
        }
    return out


def _check_references(record: Mapping[str, Any], where: str) -> None:
    refs = record["references"]
    if not (isinstance(refs, list) and refs):
        raise ErdesignError(f"{where}: references: expected a list of [[references]] tables")
    for i, ref in enumerate(refs):
        bad = [k for k in ref if k not in _REFERENCE_KEYS]
        if bad or not all(k in ref for k in ("key", "citation", "date")):
            raise ErdesignError(
                f"{where}: references[{i}]: needs key, citation and date (optional note)"
                + (f"; unknown key {bad[0]!r}" if bad else "")
            )


def _check_verification(record: Mapping[str, Any], where: str) -> None:
    """``[verification.<key>]``: for a key of ``[sources]``, the outcome of checking it against a reference.

    A value marked "verified" or "replaced" names where in the source it stands (``location``) and where that text
    was read (``found_at``); one marked "not verified" says what was searched (``searched``).
    """
    table = record.get("verification")
    if table is None:
        return
    if not isinstance(table, Mapping):
        raise ErdesignError(f"{where}: verification: expected tables [verification.<key>]")
    refs = {r["key"] for r in record["references"]}
    for key, entry in table.items():
        at = f"{where}: verification.{key}"
        if key not in record["sources"]:
            raise ErdesignError(f"{at}: not a key of [sources] (verification says how a sourced value was checked)")
        if not isinstance(entry, Mapping):
            raise ErdesignError(f"{at}: expected a table with {', '.join(VERIFICATION_KEYS)}")
        bad = [k for k in entry if k not in VERIFICATION_KEYS]
        if bad:
            raise ErdesignError(f"{at}.{bad[0]}: unknown key; allowed keys: {', '.join(VERIFICATION_KEYS)}")
        status = entry.get("status")
        if status not in VERIFICATION_STATUSES:
            raise ErdesignError(
                f"{at}.status: expected one of {', '.join(map(repr, VERIFICATION_STATUSES))}, got {status!r}"
            )
        if entry.get("source") not in refs:
            raise ErdesignError(
                f"{at}.source: expected a reference key ({', '.join(sorted(refs))}), got {entry.get('source')!r}"
            )
        needed = ("searched",) if status == "not verified" else ("location", "found_at")
        for k in needed:
            if not (isinstance(entry.get(k), str) and entry[k].strip()):
                raise ErdesignError(f"{at}.{k}: missing (a value marked {status!r} needs it)")
        extra = entry.get("agrees_with", [])
        if not (isinstance(extra, list) and all(isinstance(x, str) for x in extra)):
            raise ErdesignError(f"{at}.agrees_with: expected a list of strings")


def load_steel(name: str) -> dict[str, Any]:
    """The whole record of a steel (``steel-1018``), checked: keys, magnetisation curve, sources, references."""
    if name not in steel_names():
        raise ErdesignError(f"unknown steel {name!r}; known steels: {', '.join(steel_names())}")
    where = f"materials/{name}.toml"
    with resources.as_file(resources.files(__name__) / f"{name}.toml") as path:
        with open(path, "rb") as fh:
            record = tomllib.load(fh)
    unknown = [k for k in record if k not in STEEL_KEYS]
    if unknown:
        raise ErdesignError(f"{where}: {unknown[0]}: unknown key; allowed keys: {', '.join(STEEL_KEYS)}")
    for key in _STEEL_REQUIRED:
        if key not in record:
            raise ErdesignError(f"{where}: {key}: missing")
    if record["kind"] != "steel" or record["name"] != name:
        raise ErdesignError(f'{where}: kind must be "steel" and name {name!r}')
    if "magnetization" not in record["sources"]:
        raise ErdesignError(f"{where}: sources.magnetization: missing (every value needs its source)")
    _check_references(record, where)
    _check_verification(record, where)
    from ..magnetics.bh import bh_curve_from_dict

    try:
        bh_curve_from_dict(record["magnetization"], name=name)
    except ErdesignError as exc:
        raise ErdesignError(f"{where}: {exc}") from None
    return record


def steel_curve(name: str):
    """The :class:`~erdesign.magnetics.bh.BHCurve` of a steel of the database."""
    from ..magnetics.bh import bh_curve_from_dict

    record = load_steel(name)
    return bh_curve_from_dict(record["magnetization"], name=name, source=record["sources"]["magnetization"])


def magnetization_curve(name: str):
    """The :class:`~erdesign.magnetics.bh.BHCurve` of an MR fluid of the database; an error naming the material when
    its record has no ``[magnetization]``."""
    from ..magnetics.bh import bh_curve_from_dict

    record = load(name)
    if "magnetization" not in record:
        raise ErdesignError(
            f"material {name!r}: no [magnetization] (B-H curve) in materials/{name}.toml; the "
            f"magnetic circuit needs one (materials with one: "
            f"{', '.join(n for n in names() if 'magnetization' in load(n))})"
        )
    return bh_curve_from_dict(record["magnetization"], name=name, source=record["sources"]["magnetization"])
