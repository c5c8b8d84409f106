"""Read damper files (TOML, docs/file_formats.md) into :class:`~erdesign.damper.Damper` objects.

Every problem is a :class:`~erdesign.errors.DamperFileError` whose message starts with the file name and names the
key (``makris.toml: geometry.gap: expected a length ...``).  Unknown keys are errors, so that a misspelt key is never
silently ignored.

Example
-------
>>> d = load_example("makris")
>>> d.geometry.configuration, round(d.geometry.gap * 1e3, 4), d.seal_friction
('valve', 0.8, 112.0)
"""

from __future__ import annotations

import os

import sys
from importlib import resources
import warnings
from pathlib import Path
from typing import Any, Mapping

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from typing import Annotated

from pydantic import BeforeValidator

from .. import materials
from ..errors import DamperFileError, ErdesignError, PlausibilityWarning
from ..examples import bundled_file
from ..limits import (
    MAX_TOML_BYTES,
    decode_text,
    is_path_like,
    nested_too_deeply,
    read_input_bytes,
    refuse_binary,
    size_text,
)
from ..fluid import Fluid
from ..fluid.fluid import control_kind
from ..geometry import CONFIGURATIONS, Geometry
from ..schema import Length, Number, PositiveWholeNumber, Table, Text, choice, field, quantity, validate
from ..units import Q_, same_dimension, to_si
from .accumulator import ROD_KINDS, AccumulatorTable, accumulator_from_table, accumulator_table
from .damper import Damper

__all__ = [
    "load_damper",
    "damper_file_path",
    "damper_from_dict",
    "read_toml",
    "parse_toml_bytes",
    "load_example",
    "example_names",
    "parse_fluid_table",
    "GEOMETRY_KEYS",
    "FLUID_KEYS",
    "POWER_LAW_KEYS",
    "coil_fluid",
    "COIL_CURRENT_SPAN",
    "damper_spec",
]


# ------------------------------------------------------------------------------------- the schema, declared once
def _control(value: Any) -> Any:
    """A control with its unit: an electric or magnetic field, a flux density, a coil current or a driver voltage."""
    if isinstance(value, bool) or not isinstance(value, (str, int, float)):
        raise ValueError(f"expected a value with a unit as a string, got {value!r}")
    try:
        control_kind(value, "\x00")
    except ErdesignError as exc:
        raise ValueError(str(exc).removeprefix("\x00: ")) from None
    return value


Control = Annotated[
    Any,
    BeforeValidator(_control),
    "control with its unit: electric field (kV/mm), magnetic field (kA/m, T), coil current (A) or driver voltage (V)",
]


class GeometryTable(Table):
    """``[geometry]`` of a damper file."""

    configuration: choice(*CONFIGURATIONS) = field(
        '"valve": the piston pushes the fluid through stationary annular ducts (Makris et al. 1996); "mixed": '
        "the piston head is the moving inner electrode, flow and shear in the gap around it (Kamath and Wereley "
        "1997)"
    )
    duct_length: Length = field('L, length of each duct; for "mixed": length of the piston head (electrode)')
    duct_mean_diameter: Length = field(
        'd, mean diameter of the annulus; for "mixed" it may be omitted (it is '
        'piston_diameter + gap) and must agree when given; required for "valve"',
        default=None,
    )
    gap: Length = field("h, width of the annular gap")
    piston_diameter: Length = field('Dp, piston diameter (for "mixed": the head, inner electrode)')
    rod_diameter: Length = field("dr, rod diameter (the same on both sides for a double-ended rod)")
    ducts: PositiveWholeNumber = field("number of parallel ducts (valve only)", default=1)
    rod: choice(*ROD_KINDS) = field(
        '"double": a rod on both sides of the piston; "single": one rod, with a gas accumulator ([accumulator])',
        default="double",
    )


class FluidTable(Table):
    """``[fluid]`` of a damper file (and of a requirements file)."""

    material: Text = field(
        "name of a material of the materials database (docs/materials.md): its values are the "
        "defaults, the keys given here override them",
        default=None,
    )
    viscosity: quantity("Pa*s") = field("eta_0, plastic viscosity at zero field", default=None)
    yield_stress: quantity("Pa") = field("tau_ref, yield stress at reference_field", default=None)
    reference_field: Control = field("control at which yield_stress holds", default=None)
    yield_exponent: Number = field("n in tau_y = yield_stress * (E / reference_field) ** n", default=None)
    density: quantity("kg/m^3") = field("rho, density of the fluid", default=None)
    viscosity_at_reference_field: quantity("Pa*s") = field(
        "plastic viscosity at reference_field (default: viscosity)", default=None
    )
    shear_modulus: quantity("Pa") = field("G, pre-yield shear modulus (Makris et al. 1996, eq 8)", default=None)
    seal_friction: quantity("N", "non-negative") = field(
        "F_s, Coulomb friction of the seals (Makris et al. 1996, eq 14)", default=None
    )


class DamperFile(Table):
    """A damper file (TOML): docs/file_formats.md."""

    name: Text = field("free text naming the damper", default="")
    geometry: GeometryTable = field("the ducts, the piston and the rod")
    fluid: FluidTable = field("the fluid and the seals")
    coil: dict = field("the coil of an MR damper whose control is the coil current (docs/magnetics.md)", default=None)
    accumulator: AccumulatorTable = field("the gas accumulator of a single-ended rod", default=None)


GEOMETRY_KEYS = tuple(GeometryTable.model_fields)
FLUID_KEYS = tuple(FluidTable.model_fields)
_TOP_KEYS = tuple(DamperFile.model_fields)
#: [fluid] keys a damper with a [coil] may not give: the magnetic circuit gives the yield stress at each current.
_COIL_COMPUTED_KEYS = ("yield_stress", "yield_exponent")
#: The tabulated law tau_y(I) of a damper with a [coil] spans 0 to this many times the rated current.
COIL_CURRENT_SPAN = 3.0
_REQUIRED_FLUID = ("viscosity", "yield_stress", "reference_field", "yield_exponent", "density")


def parse_toml_bytes(raw: bytes, label: str) -> dict:
    """The table of a TOML file's bytes (a file's, an upload's), or a :class:`DamperFileError` naming ``label``: the
    one parser of erdesign's TOML input.  Larger than :data:`~erdesign.limits.MAX_TOML_BYTES`, binary, UTF-16 or not
    UTF-8, nested too deeply, a number of thousands of digits or invalid TOML is one line; line ends of a lone CR
    (classic Mac OS) are read as line ends (TOML knows LF and CRLF only)."""
    if len(raw) > MAX_TOML_BYTES:
        raise DamperFileError(
            f"{label}: larger than {size_text(MAX_TOML_BYTES)}, the most erdesign reads as a TOML file; thin or split "
            "the file"
        )
    try:
        refuse_binary(raw, label, "a TOML file")
        text = decode_text(raw, label, "a TOML file")
        if "\r" in text:
            text = text.replace("\r\n", "\n").replace("\r", "\n")
        return tomllib.loads(text)
    except ErdesignError as exc:
        raise DamperFileError(str(exc)) from None
    except RecursionError:
        raise DamperFileError(nested_too_deeply(label)) from None
    except tomllib.TOMLDecodeError as exc:
        raise DamperFileError(f"{label}: invalid TOML: {exc}{_toml_hint(text, str(exc))}") from None
    except ValueError as exc:  # beyond the parser's limits: an integer of more than 4300 digits
        detail = "a number of thousands of digits" if "digits" in str(exc) else str(exc)
        raise DamperFileError(f"{label}: invalid TOML: {detail}") from None


_CURLY_QUOTES = "\u201c\u201d\u201e\u2018\u2019\u201a\u00ab\u00bb"


def _toml_hint(text: str, message: str) -> str:
    """What the parser's words ("Cannot overwrite a value", "Invalid value") mean on the line they name: a key given
    twice, quotes a word processor curled, a key with a letter of another script or an invisible space."""
    import re
    import unicodedata

    at = re.search(r"at line (\d+)", message)
    lines = text.split("\n")
    if at is None or not 1 <= int(at[1]) <= len(lines):
        return ""
    line = lines[int(at[1]) - 1]
    key = line.split("=", 1)[0].strip(" \t")
    if "Cannot declare" in message:
        return "; a table given twice (a second [table] header, or a dotted key 'table.key' that made it already)"
    if "Cannot overwrite a value" in message and "=" in line:
        return f"; the key {key!r} is given twice (or a dotted key meets a value of that name): keep one"
    curly = next((c for c in line if c in _CURLY_QUOTES), None)
    if curly is not None:
        return f"; the line has the curly quote {curly!r} (a word processor's): write straight quotes '\"'"
    odd = next((c for c in key if not c.isascii()), None) if "=" in line else None
    if odd is not None:
        return (
            f"; the key {key!r} holds {odd!r} ({unicodedata.name(odd, 'unnamed')}, U+{ord(odd):04X}): write keys in "
            "ASCII letters, digits, '_' and '-'"
        )
    return ""


def read_toml(path: str | Path) -> dict:
    """Parse a TOML file; a missing file or a syntax error is a :class:`DamperFileError` naming the file."""
    if not is_path_like(path):
        raise DamperFileError(
            f"path: expected the name of a TOML file (a str or Path), got {type(path).__name__} {path!r:.60}"
        )
    if not os.fspath(path).strip():  # Path("") is the current folder: ".: is a directory"
        raise DamperFileError(f"path: an empty file name {os.fspath(path)!r}; give the name of a TOML file")
    path = Path(path)
    try:
        return parse_toml_bytes(read_input_bytes(path, MAX_TOML_BYTES, "a TOML file"), str(path))
    except ErdesignError as exc:
        raise DamperFileError(str(exc)) from None
    except FileNotFoundError:
        raise DamperFileError(f"{path}: no such file") from None
    except IsADirectoryError:
        raise DamperFileError(f"{path}: is a directory, expected a TOML file") from None
    except OSError as exc:  # a symbolic link loop, no permission: was "[Errno 40] Too many levels of ..."
        raise DamperFileError(f"{path}: cannot be read ({exc.strerror or exc})") from None


#: Largest seal friction [N] taken without a warning: the seals of large seismic dampers rub a few kN (Makris et
#: al. 1996: 112 N).
PLAUSIBLE_SEAL_FRICTION = 1e5

#: Keys of a damper file's [fluid] table that define the power law; giving any of them replaces a material's curve.
POWER_LAW_KEYS = ("yield_stress", "reference_field", "yield_exponent")


def parse_fluid_table(table: Mapping[str, Any], where: str = "fluid") -> tuple[Fluid, float]:
    """A :class:`Fluid` and the seal friction [N] from a ``[fluid]`` table (damper or requirements file).

    A ``material`` key takes the values of that material from the materials database (docs/materials.md); keys
    given here override them:

    * every key overrides the material's value of the same name;
    * the fluid follows the material's yield curve (``[yield_curve]``: saturating law or table) unless the table
      gives any of ``yield_stress``, ``reference_field``, ``yield_exponent``; then it follows the power law of the
      merged values (the table's, completed by the material's power-law summary);
    * the material's field range (``[range] field``) stays, unless ``reference_field`` changes the kind of control
      (a coil current instead of a magnetic field): asking for a control outside it warns.
    """
    table = validate(FluidTable, table, where, error=DamperFileError).given()
    field_law = None
    field_range = None
    material = ""
    if "material" in table:
        name = table.pop("material")
        try:
            spec = materials.material_fluid(name)
        except ErdesignError as exc:
            raise DamperFileError(f"{where}.material: {exc}") from None
        if not any(k in table for k in POWER_LAW_KEYS):
            field_law = spec.yield_curve
        table = {**spec.values, **table}
        material = name
        if spec.field_range is not None and same_dimension(spec.field_range[1], table["reference_field"]):
            field_range = spec.field_range
    missing = [k for k in _REQUIRED_FLUID if k not in table]
    if missing:
        raise DamperFileError(f"{where}.{missing[0]}: missing (required: {', '.join(_REQUIRED_FLUID)})")
    exponent = table["yield_exponent"]
    seal = table.get("seal_friction")
    seal_friction = 0.0 if seal is None else to_si(seal, "N", f"{where}.seal_friction")
    if seal_friction > PLAUSIBLE_SEAL_FRICTION:  # '1e9 N' was taken without a word
        warnings.warn(
            f"{where}.seal_friction: {seal_friction:.4g} N is beyond the seal friction of any damper "
            f"({PLAUSIBLE_SEAL_FRICTION:g} N); check the value and its unit",
            PlausibilityWarning,
            stacklevel=3,
        )
    fluid = Fluid.create(
        viscosity=table["viscosity"],
        yield_stress=table["yield_stress"],
        reference_field=table["reference_field"],
        yield_exponent=float(exponent),
        density=table["density"],
        viscosity_at_reference_field=table.get("viscosity_at_reference_field"),
        shear_modulus=table.get("shear_modulus"),
        name=material,
        field_law=field_law,
        field_range=field_range,
        material=material,
    )
    return fluid, seal_friction


def damper_from_dict(data: Mapping[str, Any], *, source: str = "damper", flow_model: str = "auto") -> Damper:
    """A :class:`Damper` from the parsed content of a damper file.  ``source`` prefixes error messages.

    The file is checked against its schema (:class:`DamperFile`: keys, types, units, signs) first; the relations
    between values (a rod thinner than the piston, a mixed damper's mean diameter) are the objects' own checks."""
    try:
        if isinstance(data, Mapping) and "design" in data and "geometry" not in data:
            raise DamperFileError(
                "a requirements file ([design]), not a damper file ([geometry]); give it to erdesign design"
            )
        spec = validate(DamperFile, data, error=DamperFileError)
        geo = spec.geometry.given()
        rod = geo.pop("rod", "double")
        geometry = Geometry.create(**geo)
        accumulator = None
        if spec.accumulator is not None:
            if rod != "single":
                raise DamperFileError(
                    "accumulator: a gas accumulator pushes on the rod only when the rod is "
                    'single-ended; add rod = "single" to [geometry]'
                )
            accumulator = accumulator_from_table(data["accumulator"])
        if spec.coil is not None:
            fluid, seal_friction = coil_fluid(data, geometry)
        else:
            fluid, seal_friction = parse_fluid_table(data["fluid"])
        return Damper(
            geometry=geometry,
            fluid=fluid,
            seal_friction=seal_friction,
            name=spec.name,
            flow_model=flow_model,
            rod=rod,
            accumulator=accumulator,
        )
    except ErdesignError as exc:
        raise type(exc)(f"{source}: {exc}") from None


def coil_fluid(data: Mapping[str, Any], geometry: Geometry) -> tuple[Fluid, float]:
    """The fluid of a damper file with a ``[coil]`` (docs/file_formats.md, [coil]), and its seal friction [N].

    The control is the coil current: ``fluid.reference_field`` is the rated current (in A) and ``fluid.material``
    names an MR fluid with a B-H curve and a yield curve against field strength.  The yield stress at any current
    follows the magnetic circuit (:mod:`erdesign.magnetics`): the fluid's law is the
    :class:`~erdesign.magnetics.law.CoilLaw` tau_y(H_g(I)), the gap field tabulated from 0 to
    :data:`COIL_CURRENT_SPAN` times the rated current (beyond it the circuit is solved, and asking for a current
    outside that range warns); its power-law summary (``yield_stress``, ``yield_exponent``) is fitted to it over
    (0, rated current], so the file must not give those two keys.
    """
    from ..magnetics import build_circuit, coil_from_table
    from ..magnetics.law import coil_law

    table = validate(FluidTable, data["fluid"], "fluid", error=DamperFileError).given()
    for key in _COIL_COMPUTED_KEYS:
        if key in table:
            raise DamperFileError(
                f"fluid.{key}: not allowed with a [coil]: the magnetic circuit gives the yield "
                "stress at each current (erdesign magnetics)"
            )
    if "material" not in table:
        raise DamperFileError(
            "fluid.material: missing; a damper with a [coil] takes the fluid's B-H and yield "
            "curves from the materials database"
        )
    if "reference_field" not in table:
        raise DamperFileError('fluid.reference_field: missing; with a [coil] it is the rated coil current, e.g. "2 A"')
    try:
        I_ref = to_si(table["reference_field"], "A", "fluid.reference_field")
    except ErdesignError as exc:
        raise DamperFileError(f"{exc} (with a [coil] the control is the coil current)") from None
    if not (isinstance(I_ref, float) and I_ref > 0):
        raise DamperFileError(
            f"fluid.reference_field: the rated current must be positive, got {table['reference_field']!r}"
        )
    if I_ref > 20.0:
        from ..errors import ValidityWarning

        warnings.warn(
            f"fluid.reference_field: a rated coil current of {I_ref:.3g} A is implausibly large for an "
            "MR damper coil; check the unit",
            ValidityWarning,
            stacklevel=3,
        )
    coil = coil_from_table(data["coil"])
    circuit = build_circuit(geometry, coil, table["material"], name=str(data.get("name", "")))
    if coil.supply_voltage is not None and not coil.supply_voltage > I_ref * circuit.resistance:
        raise DamperFileError(
            f"coil.supply_voltage: {coil.supply_voltage:.4g} V cannot drive the rated current "
            f"{I_ref:.4g} A (fluid.reference_field) through the coil's {circuit.resistance:.4g} ohm "
            f"(needs more than {I_ref * circuit.resistance:.4g} V)"
        )
    law = coil_law(circuit, COIL_CURRENT_SPAN * I_ref, I_ref, supply_voltage=coil.supply_voltage)
    fit = law.fit(I_ref)
    values = dict(table)
    values["yield_stress"] = f"{float(law.yield_stress(I_ref))!r} Pa"
    values["yield_exponent"] = float(fit.yield_exponent)
    with warnings.catch_warnings():  # the exponent is fitted to the circuit's saturating law, not the user's
        warnings.filterwarnings("ignore", r"fluid\.yield_exponent", PlausibilityWarning)
        fluid, seal_friction = parse_fluid_table(values)
    fluid = fluid.with_changes(field_law=law, field_range=(0.0, COIL_CURRENT_SPAN * I_ref))
    return fluid, seal_friction


def damper_spec(damper: Damper) -> dict:
    """The content of a damper file for ``damper`` (``name``, ``[geometry]``, ``[fluid]``, ``[accumulator]``),
    values as strings with SI units: :func:`erdesign.report.export.damper_toml` writes it, :func:`damper_from_dict`
    reads it back to the same damper.

    Only a fluid of the power law can be written this way; a fluid that follows a material's yield curve or a
    coil's magnetic circuit is an error (write the damper file's ``material`` / ``[coil]`` keys instead).

    >>> spec = damper_spec(load_example("spencer1997"))
    >>> spec["geometry"]["rod"], spec["accumulator"]["polytropic_index"]
    ('single', 1.4)
    >>> damper_from_dict(spec) == load_example("spencer1997")
    True
    """
    g, f = damper.geometry, damper.fluid
    if f.field_law is not None:
        raise DamperFileError(
            f"fluid: {damper.name or 'this damper'} follows "
            f"{'the yield curve of ' + f.material if f.material else 'a tabulated field law'}; "
            "only a power-law fluid can be written back as plain values"
        )
    geometry = {
        "configuration": g.configuration,
        "duct_length": f"{g.duct_length!r} m",
        "duct_mean_diameter": f"{g.duct_mean_diameter!r} m",
        "gap": f"{g.gap!r} m",
        "piston_diameter": f"{g.piston_diameter!r} m",
        "rod_diameter": f"{g.rod_diameter!r} m",
    }
    if g.configuration == "valve":
        geometry["ducts"] = g.ducts
    if damper.rod != "double":
        geometry["rod"] = damper.rod
    # the control in the unit it was given in (kV/mm stays kV/mm), so that the file reads back to the same fluid
    unit = f.field_unit
    reference = float(Q_(f.reference_field, f.control_unit).to(unit).magnitude)
    fluid = {
        "viscosity": f"{f.viscosity!r} Pa*s",
        "yield_stress": f"{f.yield_stress!r} Pa",
        "reference_field": f"{reference!r} {unit}",
        "yield_exponent": f.yield_exponent,
        "density": f"{f.density!r} kg/m^3",
    }
    if f.viscosity_at_reference_field is not None:
        fluid["viscosity_at_reference_field"] = f"{f.viscosity_at_reference_field!r} Pa*s"
    if f.shear_modulus is not None:
        fluid["shear_modulus"] = f"{f.shear_modulus!r} Pa"
    if damper.seal_friction:
        fluid["seal_friction"] = f"{damper.seal_friction!r} N"
    spec = {"name": damper.name, "geometry": geometry, "fluid": fluid}
    if damper.accumulator is not None:
        spec["accumulator"] = accumulator_table(damper.accumulator)
    return spec


def damper_file_path(path: str | Path) -> Path:
    """Where the damper file ``path`` is read from: the file itself when it exists; else the bundled example that
    the name (``makris``, ``mr_valve``, ...: :func:`example_names`) or the documented path (``examples/makris.toml``:
    :func:`erdesign.examples.bundled_file`) names; else ``path`` (whose reading then says "no such file").  The one
    rule every command that takes a damper file follows (CONTRACTS: bundled examples by name).

    >>> damper_file_path("makris").name, damper_file_path("no_such_damper.toml").name
    ('makris.toml', 'no_such_damper.toml')
    """
    if isinstance(path, str) and path in example_names() and not Path(path).exists():  # a name first: exists()
        return Path(str(resources.files("erdesign.examples") / f"{path}.toml"))  # raises for a NUL or a long name
    return bundled_file(path) or Path(path)


def load_damper(path: str | Path, *, flow_model: str = "auto") -> Damper:
    """Read a damper file (TOML, docs/file_formats.md); where no such file exists, the name of a bundled example
    (``makris``, ``mr_valve``, ...) or its documented path ``examples/makris.toml`` loads that example
    (:func:`damper_file_path`)."""
    if not is_path_like(path):
        raise DamperFileError(
            f"path: expected the name of a damper file (a str or Path), got {type(path).__name__} {path!r:.60}"
        )
    if not os.fspath(path).strip():
        raise DamperFileError(f"path: an empty file name {os.fspath(path)!r}; give the name of a damper file")
    by_name = isinstance(path, str) and path in example_names() and not Path(path).exists()
    source = f"examples/{path}.toml" if by_name else str(path)
    return damper_from_dict(read_toml(damper_file_path(path)), source=source, flow_model=flow_model)


def example_names() -> list[str]:
    """Names of the damper files shipped in examples/ (``makris``, ...)."""
    return sorted(p.name[:-5] for p in resources.files("erdesign.examples").iterdir() if p.name.endswith(".toml"))


def load_example(name: str = "makris") -> Damper:
    """One of the damper files shipped in examples/, by name (``"makris"`` is Makris et al.'s ER damper)."""
    if name not in example_names():
        raise ErdesignError(f"example: unknown example {name!r}; available: {', '.join(example_names())}")
    with resources.as_file(resources.files("erdesign.examples") / f"{name}.toml") as path:
        return damper_from_dict(read_toml(path), source=f"examples/{name}.toml")
