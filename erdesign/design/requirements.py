r"""The requirements file of ``erdesign design``: what the damper must do, its envelope, and the free geometry.

The file (docs/cli.md, "erdesign design") has a ``[fluid]`` table exactly as a damper file and a
``[design]`` table.  Every dimensional value is a string with a unit; unknown keys are errors that name the key.
The keys beyond the contract are listed below and in docs/design.md.

``[design]``
    ``configuration`` ("valve" or "mixed"), ``objective`` (a key of :data:`~erdesign.design.figures.OBJECTIVES`,
    default ``"min_fluid_volume"``), one or more ``[[design.point]]`` tables, and the optional tables
    ``[design.limits]``, ``[design.bounds]`` (required), ``[design.envelope]`` and ``[design.search]``.
``[[design.point]]``
    ``velocity`` (> 0), ``field`` (the control, default 0), ``min_force``, ``min_dynamic_range`` and, beyond the
    contract, ``max_zero_field_force`` (a ceiling on the passive force).  At least one requirement per point.
``[design.limits]``
    ``max_outer_diameter``, ``max_length``, ``max_pressure``, ``laminar`` (contract), and ``min_gap`` (the
    manufacturable minimum gap), ``max_field`` (default: 4 kV/mm for an ER fluid, 250 kA/m for an MR fluid given
    in A/m, Butz and von Stryk (2002) Table 1 "maximum field"; none for other controls) and ``max_voltage``
    (electrode voltage E h across the gap, ER fluids only; Butz and von Stryk (2002) Table 1 gives 2 to 5 kV for typical supplies).
``[design.bounds]``
    ``gap``, ``duct_length``, ``duct_mean_diameter`` (valve only), ``piston_diameter``, ``rod_diameter``:
    ``[low, high]`` or a single value (fixed); ``ducts``: ``[low, high]`` whole numbers or one (default 1; valve
    only).
``[design.envelope]`` (all optional; the envelope model of :mod:`erdesign.design.envelope`)
    ``stroke`` (default 50 mm), ``wall`` (wall allowance of the cylinder, default 5 mm), ``head_length`` (valve
    piston head, default 20 mm), ``end_allowance`` (each end cap with seal and bearing, default 25 mm),
    ``duct_placement`` (valve: ``"beside"`` the cylinder as in Makris Fig 1, default, or ``"around"`` it).
``[design.coil]`` (an MR damper whose piston head carries the coil; docs/magnetics.md, "Design with the coil")
    Present: the design also sizes the poles and the coil, the yield stress at each point follows each candidate's
    magnetic circuit (:mod:`erdesign.design.coil`), and every point's ``field`` is the coil current (A).  The
    ``[fluid]`` table then names an MR ``material`` with a B-H curve and gives no ``yield_stress``,
    ``reference_field`` or ``yield_exponent``.  Keys: the bounds ``turns`` (whole numbers), ``wire_diameter``,
    ``core_diameter``, ``pole_length``, ``housing_outer_diameter`` (each ``[low, high]`` or one value), ``steel``
    (default ``"steel-1018"``), and the limits ``supply_voltage`` (I R at every point), ``max_current_density``
    (default ``"5 A/mm^2"``), ``max_fill_factor`` (copper, default 0.6), ``allow_saturation`` (default false: no
    part of the circuit past the knee of its B-H curve at any point's current), ``max_power`` and
    ``max_time_constant`` (at the first point's current).  Objectives ``min_coil_power`` and
    ``min_time_constant`` (Gavin, Hoagg and Dobossy 2001) need it.
``[design.search]`` (all optional)
    ``samples`` (default 131072), ``sampling`` (``"sobol"`` or ``"lhs"``), ``seed`` (default 0),
    ``chunk`` (candidates evaluated at once, default 65536), ``refine`` (default true), ``designs`` (how many to
    return, default 10), ``pareto`` (two or three figures of :data:`~erdesign.design.figures.FIGURES`, default
    ``["dynamic_range", "fluid_volume", "outer_diameter"]``; see docs/design.md for why not controllable force,
    dynamic range and fluid volume, which a valve damper ties together), ``active_tolerance`` (relative margin below
    which a constraint counts as active, default 0.01), ``gap_tolerance`` and ``length_tolerance`` (the grid the
    returned dimensions are rounded to, then re-checked: default ``"0.01 mm"`` for the gap, ``"0.1 mm"`` for the
    other lengths; ``"0 mm"`` keeps six significant figures) and ``secondary`` (the objective that breaks ties
    of the objective, default per objective: :data:`~erdesign.design.search.SECONDARY`).

Example
-------
>>> req = requirements_from_dict({
...     "fluid": {"material": "makris-zeolite-silicone"},
...     "design": {"configuration": "valve",
...                "point": [{"velocity": "1 in/s", "field": "3 kV/mm", "min_force": "5 kN"}],
...                "bounds": {"gap": ["0.5 mm", "2 mm"], "duct_length": ["20 mm", "150 mm"],
...                           "duct_mean_diameter": ["5 mm", "40 mm"], "piston_diameter": "33.4 mm",
...                           "rod_diameter": "11.25 mm"}}})
>>> req.objective, req.points[0].min_force, req.bounds["piston_diameter"], req.limits.max_field
('min_fluid_volume', 5000.0, (0.0334, 0.0334), 4000000.0)
>>> requirements_from_dict({"fluid": {}, "desing": {}})
Traceback (most recent call last):
...
erdesign.design.requirements.RequirementsError: requirements: desing: unknown key; allowed keys: name, fluid, design
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from ..damper.files import parse_fluid_table, read_toml
from ..errors import ErdesignError
from ..fluid import Fluid
from ..geometry import CONFIGURATIONS
from ..units import to_si
from .figures import FIGURES, OBJECTIVES

__all__ = [
    "Requirements",
    "DesignPoint",
    "Limits",
    "Envelope",
    "SearchSettings",
    "RequirementsError",
    "read_requirements",
    "requirements_from_dict",
    "load_example_requirements",
    "example_requirements_names",
    "VARIABLES",
    "COIL_VARIABLES",
    "CoilDesign",
    "FIELD_LIMITS",
    "DUCT_PLACEMENTS",
]

#: The free geometric variables, in the order of the sampler's columns (the keys of ``[design.bounds]``).
VARIABLES = ("gap", "duct_length", "duct_mean_diameter", "piston_diameter", "rod_diameter", "ducts")

#: The free variables of the coil (``[design.coil]``), after :data:`VARIABLES` in a candidate's columns.
COIL_VARIABLES = ("turns", "wire_diameter", "core_diameter", "pole_length", "housing_outer_diameter")

#: Objectives that need ``[design.coil]``.
COIL_OBJECTIVES = ("min_coil_power", "min_time_constant")

#: Default figures of ``[design.coil]``: current density [A/m^2] (an engineering rule for a coil without forced
#: cooling, erdesign's choice, not from a source: state your own) and copper fill factor [-] (round enamelled wire
#: wound by machine reaches 0.5-0.7).
DEFAULT_CURRENT_DENSITY = 5e6
DEFAULT_FILL_FACTOR = 0.6

_COIL_KEYS = COIL_VARIABLES + ("steel", "supply_voltage", "max_current_density", "max_fill_factor",
                               "allow_saturation", "max_power", "max_time_constant")

#: Default field limits by kind of control, SI: Butz and von Stryk (2002), Table 1, "maximum field":
#: ca. 4 kV/mm for ER fluids (dielectric breakdown) and ca. 250 kA/m for MR fluids (magnetic saturation).
FIELD_LIMITS = {"electric field": 4.0e6, "magnetic field": 250.0e3}

#: Where the valve ducts sit: beside the cylinder (Makris Fig 1: external bypass tubes) or around it (one
#: concentric annulus outside the cylinder tube).
DUCT_PLACEMENTS = ("beside", "around")

SAMPLINGS = ("sobol", "lhs")

#: Most candidates a search may sample (about a minute per 2**20 on one core; the Sobol sampler stops at 2**30),
#: the most it takes without a warning, and the largest chunk evaluated at once (memory: ~1 kB per candidate).
MAX_SAMPLES, PLAUSIBLE_SAMPLES, MAX_CHUNK = 2**24, 2**21, 2**20

_TOP_KEYS = ("name", "fluid", "design")
_DESIGN_KEYS = ("configuration", "objective", "point", "limits", "bounds", "envelope", "search", "coil")
_POINT_KEYS = ("velocity", "field", "min_force", "min_dynamic_range", "max_zero_field_force")
_LIMIT_KEYS = ("max_outer_diameter", "max_length", "max_pressure", "laminar", "min_gap", "max_field", "max_voltage")
_ENVELOPE_KEYS = ("stroke", "wall", "head_length", "end_allowance", "duct_placement")
_SEARCH_KEYS = ("samples", "sampling", "seed", "chunk", "refine", "designs", "pareto", "active_tolerance",
                "gap_tolerance", "length_tolerance", "secondary")


@dataclass(frozen=True)
class CoilDesign:
    """The ``[design.coil]`` table, SI: the fluid's magnetic material, the steel, and the coil's limits."""

    material: str
    """MR fluid of the materials database (B-H curve and yield curve against field strength)."""
    steel: str = "steel-1018"
    supply_voltage: float | None = None
    """Largest I R, [V]."""
    max_current_density: float = DEFAULT_CURRENT_DENSITY
    """[A/m^2]."""
    max_fill_factor: float = DEFAULT_FILL_FACTOR
    allow_saturation: bool = False
    max_power: float | None = None
    """[W], at the first point's current."""
    max_time_constant: float | None = None
    """[s], L/R at the first point's current."""


class RequirementsError(ErdesignError):
    """A requirements file is malformed or self-contradictory; the message names the key."""


@dataclass(frozen=True)
class DesignPoint:
    """One operating point the damper must meet, SI.

    Attributes
    ----------
    velocity : float
        Piston velocity, [m/s], > 0.
    field : float
        Control (SI unit of the fluid's control: V/m, A/m, T, A or V).
    min_force : float or None
        Least total force (with seal friction) at ``velocity`` and ``field``, [N].
    min_dynamic_range : float or None
        Least F(v, E) / F(v, 0), [-].
    max_zero_field_force : float or None
        Largest force at ``velocity`` with no field, [N] (beyond the contract).
    """

    velocity: float
    field: float = 0.0
    min_force: float | None = None
    min_dynamic_range: float | None = None
    max_zero_field_force: float | None = None


@dataclass(frozen=True)
class Limits:
    """Limits every design must respect, SI; None: no limit."""

    max_outer_diameter: float | None = None
    """Outer diameter of the cylinder (bore + 2 wall), [m]."""
    max_length: float | None = None
    """Body length of the envelope model, [m]."""
    max_pressure: float | None = None
    """Pressure drop across the piston, at field and at zero field, [Pa]."""
    laminar: bool = False
    """Reynolds number (Makris eq 1) below 2300 at every point, at field and at zero field."""
    min_gap: float | None = None
    """Manufacturable minimum gap, [m]."""
    max_field: float | None = None
    """Largest control the fluid takes (SI unit of the control)."""
    max_voltage: float | None = None
    """Largest electrode voltage E h, [V] (ER only)."""


@dataclass(frozen=True)
class Envelope:
    """Parameters of the envelope model (:mod:`erdesign.design.envelope`), SI."""

    stroke: float = 0.050
    """Full piston stroke, [m]."""
    wall: float = 0.005
    """Wall allowance of the cylinder (and of an outer duct tube), [m]."""
    head_length: float = 0.020
    """Length of the valve damper's piston head, [m] (mixed: the head is the electrode, length L)."""
    end_allowance: float = 0.025
    """Length of each end cap with its seal and bearing, [m]."""
    duct_placement: str = "beside"
    """Valve only: ``"beside"`` or ``"around"`` the cylinder."""


@dataclass(frozen=True)
class SearchSettings:
    """How the design space is searched and what is returned."""

    samples: int = 2**17
    sampling: str = "sobol"
    seed: int = 0
    chunk: int = 2**16
    refine: bool = True
    designs: int = 10
    pareto: tuple[str, ...] = ("dynamic_range", "fluid_volume", "outer_diameter")
    active_tolerance: float = 0.01
    gap_tolerance: float = 1e-5
    """Grid the returned gap is rounded to, [m] (0: six significant figures)."""
    length_tolerance: float = 1e-4
    """Grid the other returned lengths are rounded to, [m] (0: six significant figures)."""
    secondary: str | None = None
    """Objective that breaks ties of the objective (None: the default of the objective)."""


@dataclass(frozen=True)
class Requirements:
    """A parsed requirements file (SI).  Build it with :func:`read_requirements` or :func:`requirements_from_dict`.

    ``bounds`` maps each name of :data:`VARIABLES` to ``(low, high)`` in SI (``ducts`` as whole numbers); for a
    mixed damper ``duct_mean_diameter`` is ``None`` (it is ``piston_diameter + gap``).
    """

    fluid: Fluid
    seal_friction: float
    fluid_table: Mapping[str, Any]
    configuration: str
    objective: str
    points: tuple[DesignPoint, ...]
    bounds: Mapping[str, tuple[float, float] | None]
    limits: Limits = field(default_factory=Limits)
    envelope: Envelope = field(default_factory=Envelope)
    search: SearchSettings = field(default_factory=SearchSettings)
    name: str = ""
    coil: CoilDesign | None = None
    """``[design.coil]``: the head's coil is designed too (None: a damper without a coil)."""

    @property
    def variables(self) -> tuple[str, ...]:
        """The candidate's variables in column order: :data:`VARIABLES`, then :data:`COIL_VARIABLES` with a coil."""
        return VARIABLES + COIL_VARIABLES if self.coil is not None else VARIABLES

    def with_search(self, **changes: Any) -> "Requirements":
        """Copy with some search settings changed (``req.with_search(samples=4096, refine=False)``)."""
        search = dataclasses.replace(self.search, **changes)
        _check_search(search, "design.search")
        return dataclasses.replace(self, search=search)

    @property
    def free_variables(self) -> tuple[str, ...]:
        """Names of the variables whose bounds are a range (low < high)."""
        return tuple(k for k in self.variables
                     if self.bounds.get(k) is not None and self.bounds[k][0] < self.bounds[k][1])


# ---------------------------------------------------------------------------------------------------- parsing
def read_requirements(path: str | Path) -> Requirements:
    """Read a requirements file (TOML); errors name the file and the key."""
    return requirements_from_dict(read_toml(path), source=str(path))


def example_requirements_names() -> list[str]:
    """Names of the requirements files shipped in examples/requirements/ (``makris_requirements``, ...)."""
    folder = resources.files("erdesign.examples") / "requirements"
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".toml"))


def load_example_requirements(name: str = "makris_requirements") -> Requirements:
    """One of the requirements files shipped in examples/requirements/, by name.

    Examples
    --------
    >>> load_example_requirements("mr_requirements").configuration
    'mixed'
    """
    if name not in example_requirements_names():
        raise RequirementsError(f"example: unknown requirements example {name!r}; available: "
                                f"{', '.join(example_requirements_names())}")
    with resources.as_file(resources.files("erdesign.examples") / "requirements" / f"{name}.toml") as path:
        return requirements_from_dict(read_toml(path), source=f"examples/requirements/{name}.toml")


def requirements_from_dict(data: Mapping[str, Any], *, source: str = "requirements") -> Requirements:
    """:class:`Requirements` from the parsed content of a requirements file.  ``source`` prefixes errors."""
    try:
        return _parse(data)
    except ErdesignError as exc:
        raise RequirementsError(f"{source}: {exc}") from None


def _table(value: Any, where: str, allowed: tuple[str, ...]) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise RequirementsError(f"{where}: expected a table, got {value!r}")
    for key in value:
        if key not in allowed:
            prefix = f"{where}." if where else ""
            raise RequirementsError(f"{prefix}{key}: unknown key; allowed keys: {', '.join(allowed)}")
    return value


def _quantity(table: Mapping[str, Any], key: str, unit: str, where: str, *, positive: bool = True):
    if key not in table:
        return None
    name = f"{where}.{key}"
    value = table[key]
    if not isinstance(value, str):
        raise RequirementsError(f"{name}: expected a value with a unit as a string (e.g. \"1 {unit}\"), got {value!r}")
    si = to_si(value, unit, name)
    if positive and not si > 0:
        raise RequirementsError(f"{name}: must be positive, got {value!r}")
    return si


def _number(table: Mapping[str, Any], key: str, where: str, *, kind: type = float, low: float | None = None):
    if key not in table:
        return None
    value = table[key]
    ok = not isinstance(value, bool) and (isinstance(value, int) if kind is int else isinstance(value, (int, float)))
    if not ok:
        what = "a whole number" if kind is int else "a plain number"
        raise RequirementsError(f"{where}.{key}: expected {what}, got {value!r}")
    if low is not None and not value >= low:
        raise RequirementsError(f"{where}.{key}: must be >= {low:g}, got {value!r}")
    return kind(value)


def _choice(table: Mapping[str, Any], key: str, where: str, choices, default=None):
    value = table.get(key, default)
    if value is None:
        raise RequirementsError(f"{where}.{key}: missing (one of {', '.join(map(repr, choices))})")
    if value not in choices:
        raise RequirementsError(f"{where}.{key}: must be one of {', '.join(map(repr, choices))}, got {value!r}")
    return value


def _parse(data: Mapping[str, Any]) -> Requirements:
    data = _table(data, "", _TOP_KEYS)
    for key in ("fluid", "design"):
        if key not in data:
            raise RequirementsError(f"[{key}]: missing table")
    name = data.get("name", "")
    if not isinstance(name, str):
        raise RequirementsError(f"name: expected text, got {name!r}")
    if not isinstance(data["fluid"], Mapping):
        raise RequirementsError(f"fluid: expected a table, got {data['fluid']!r}")
    fluid_table = dict(data["fluid"])
    design = _table(data["design"], "design", _DESIGN_KEYS)
    coil = None
    if "coil" in design:
        fluid, seal_friction, coil, coil_bounds = _parse_coil(design["coil"], fluid_table)
    else:
        fluid, seal_friction = parse_fluid_table(fluid_table, "fluid")
    configuration = _choice(design, "configuration", "design", CONFIGURATIONS)
    objective = _choice(design, "objective", "design", tuple(OBJECTIVES), default="min_fluid_volume")
    if objective in COIL_OBJECTIVES and coil is None:
        raise RequirementsError(f"design.objective: {objective!r} needs a [design.coil] table (the coil to design)")

    points = _parse_points(design.get("point"), fluid)
    limits = _parse_limits(design.get("limits", {}), fluid)
    envelope = _parse_envelope(design.get("envelope", {}), configuration)
    if "bounds" not in design:
        raise RequirementsError("design.bounds: missing table (the free variables and their ranges)")
    bounds = _parse_bounds(design["bounds"], configuration, envelope)
    if coil is not None:
        if bounds["ducts"] != (1, 1):
            raise RequirementsError("design.bounds.ducts: a coil sits in a head with one annular gap (ducts = 1)")
        bounds.update(coil_bounds)
    if limits.min_gap is not None and limits.min_gap > bounds["gap"][1]:
        raise RequirementsError(f"design.limits.min_gap: {limits.min_gap * 1e3:g} mm is above the largest gap of "
                                f"design.bounds.gap ({bounds['gap'][1] * 1e3:g} mm): no design can meet both; lower "
                                "min_gap or widen the gap's bounds")
    search = _parse_search(design.get("search", {}))
    return Requirements(fluid=fluid, seal_friction=seal_friction, fluid_table=fluid_table,
                        configuration=configuration, objective=objective, points=points, bounds=bounds,
                        limits=limits, envelope=envelope, search=search, name=name, coil=coil)


def _parse_coil(table: Any, fluid_table: Mapping[str, Any]):
    """The fluid (controlled by the coil current), seal friction, :class:`CoilDesign` and the coil's bounds."""
    from .. import materials
    from ..damper.files import POWER_LAW_KEYS

    where = "design.coil"
    table = _table(table, where, _COIL_KEYS)
    for key in POWER_LAW_KEYS:
        if key in fluid_table:
            raise RequirementsError(f"fluid.{key}: not allowed with [design.coil]: each candidate's magnetic circuit "
                                    "gives the yield stress at the point's coil current")
    name = fluid_table.get("material")
    if not isinstance(name, str):
        raise RequirementsError("fluid.material: missing; with [design.coil] the fluid's B-H and yield curves come "
                                "from the materials database")
    try:
        materials.magnetization_curve(name)
        law = materials.material_fluid(name).yield_curve
    except ErdesignError as exc:
        raise RequirementsError(f"fluid.material: {exc}") from None
    if law is None or law.control_unit != "A/m":
        raise RequirementsError(f"fluid.material: {name!r} has no yield curve against field strength (A/m)")
    if "viscosity_at_reference_field" in fluid_table:
        raise RequirementsError("fluid.viscosity_at_reference_field: not supported with [design.coil]")
    # the fluid of the requirements is controlled by the current; its own yield law is not used (each candidate's
    # circuit gives the yield stress), so it carries the material's power-law summary at 1 A as a placeholder
    values = dict(fluid_table)
    spec = materials.material_fluid(name)
    values.update(yield_stress=spec.values["yield_stress"], reference_field="1 A", yield_exponent=1.0)
    fluid, seal_friction = parse_fluid_table(values, "fluid")
    steel = table.get("steel", "steel-1018")
    if not isinstance(steel, str) or steel not in materials.steel_names():
        raise RequirementsError(f"{where}.steel: unknown steel {steel!r}; known steels: "
                                f"{', '.join(materials.steel_names())}")
    allow = table.get("allow_saturation", False)
    if not isinstance(allow, bool):
        raise RequirementsError(f"{where}.allow_saturation: expected true or false, got {allow!r}")
    J = _quantity(table, "max_current_density", "A/m^2", where)
    fill = _number(table, "max_fill_factor", where)
    if fill is not None and not 0 < fill <= 0.9:
        raise RequirementsError(f"{where}.max_fill_factor: must lie in (0, 0.9], got {fill!r}")
    coil = CoilDesign(material=name, steel=steel, supply_voltage=_quantity(table, "supply_voltage", "V", where),
                      max_current_density=DEFAULT_CURRENT_DENSITY if J is None else J,
                      max_fill_factor=DEFAULT_FILL_FACTOR if fill is None else fill, allow_saturation=allow,
                      max_power=_quantity(table, "max_power", "W", where),
                      max_time_constant=_quantity(table, "max_time_constant", "s", where))
    bounds = {}
    for key in COIL_VARIABLES:
        name_k = f"{where}.{key}"
        if key not in table:
            raise RequirementsError(f"{name_k}: missing ([low, high] or a single value)")
        bounds[key] = _range(table[key], name_k, whole=key == "turns")
    return fluid, seal_friction, coil, bounds


def _range(value: Any, name: str, whole: bool = False) -> tuple[float, float]:
    """A design variable's range from ``[low, high]`` or one value: lengths with units, or whole numbers
    (``whole``); positive, low <= high."""
    items = value if isinstance(value, list) else [value]
    if whole:
        if not 1 <= len(items) <= 2 or not all(isinstance(v, int) and not isinstance(v, bool) for v in items):
            raise RequirementsError(f"{name}: expected [low, high] whole numbers or one, got {value!r}")
        lo, hi = float(items[0]), float(items[-1])
    else:
        if not 1 <= len(items) <= 2 or not all(isinstance(v, str) for v in items):
            raise RequirementsError(f"{name}: expected [\"low unit\", \"high unit\"] or one value with a unit, "
                                    f"got {value!r}")
        lo, hi = (to_si(v, "m", name) for v in (items[0], items[-1]))
    if not lo > 0:
        raise RequirementsError(f"{name}: must be positive, got {items[0]!r}")
    if lo > hi:
        raise RequirementsError(f"{name}: low {items[0]!r} is above high {items[-1]!r}")
    return lo, hi


def _parse_points(value: Any, fluid: Fluid) -> tuple[DesignPoint, ...]:
    if value is None:
        raise RequirementsError("design.point: missing (at least one [[design.point]] table)")
    if isinstance(value, Mapping):
        value = [value]
    if not isinstance(value, list) or not value:
        raise RequirementsError(f"design.point: expected one or more [[design.point]] tables, got {value!r}")
    points = []
    for i, table in enumerate(value, start=1):
        where = f"design.point[{i}]"
        table = _table(table, where, _POINT_KEYS)
        if "velocity" not in table:
            raise RequirementsError(f"{where}.velocity: missing")
        velocity = _quantity(table, "velocity", "m/s", where)
        field_value = 0.0
        if "field" in table:
            if not isinstance(table["field"], str):
                raise RequirementsError(f"{where}.field: expected a value with a unit as a string, "
                                        f"got {table['field']!r}")
            field_value = fluid.field_si(table["field"], f"{where}.field")
            if field_value < 0:
                raise RequirementsError(f"{where}.field: must not be negative, got {table['field']!r}")
        point = DesignPoint(
            velocity=velocity,
            field=field_value,
            min_force=_quantity(table, "min_force", "N", where),
            min_dynamic_range=_number(table, "min_dynamic_range", where),
            max_zero_field_force=_quantity(table, "max_zero_field_force", "N", where),
        )
        if point.min_dynamic_range is not None and not point.min_dynamic_range > 0:
            raise RequirementsError(f"{where}.min_dynamic_range: must be positive, got {point.min_dynamic_range!r}")
        if point.min_force is None and point.min_dynamic_range is None and point.max_zero_field_force is None:
            raise RequirementsError(f"{where}: states no requirement (give min_force, min_dynamic_range or "
                                    "max_zero_field_force)")
        points.append(point)
    return tuple(points)


def _parse_limits(table: Any, fluid: Fluid) -> Limits:
    where = "design.limits"
    table = _table(table, where, _LIMIT_KEYS)
    laminar = table.get("laminar", False)
    if not isinstance(laminar, bool):
        raise RequirementsError(f"{where}.laminar: expected true or false, got {laminar!r}")
    max_field = FIELD_LIMITS.get(fluid.control)
    if "max_field" in table:
        if not isinstance(table["max_field"], str):
            raise RequirementsError(f"{where}.max_field: expected a value with a unit as a string, "
                                    f"got {table['max_field']!r}")
        max_field = fluid.field_si(table["max_field"], f"{where}.max_field")
        if not max_field > 0:
            raise RequirementsError(f"{where}.max_field: must be positive, got {table['max_field']!r}")
    max_voltage = _quantity(table, "max_voltage", "V", where)
    if max_voltage is not None and fluid.control != "electric field":
        raise RequirementsError(f"{where}.max_voltage: applies to an ER fluid controlled by an electric field "
                                f"(this fluid's control is a {fluid.control})")
    return Limits(
        max_outer_diameter=_quantity(table, "max_outer_diameter", "m", where),
        max_length=_quantity(table, "max_length", "m", where),
        max_pressure=_quantity(table, "max_pressure", "Pa", where),
        laminar=laminar,
        min_gap=_quantity(table, "min_gap", "m", where),
        max_field=max_field,
        max_voltage=max_voltage,
    )


def _parse_envelope(table: Any, configuration: str) -> Envelope:
    where = "design.envelope"
    table = _table(table, where, _ENVELOPE_KEYS)
    defaults = Envelope()
    values = {}
    for key in ("stroke", "wall", "head_length", "end_allowance"):
        si = _quantity(table, key, "m", where, positive=False)
        if si is not None and si < 0:
            raise RequirementsError(f"{where}.{key}: must not be negative, got {table[key]!r}")
        values[key] = getattr(defaults, key) if si is None else si
    placement = _choice(table, "duct_placement", where, DUCT_PLACEMENTS, default="beside")
    if "duct_placement" in table and configuration != "valve":
        raise RequirementsError(f"{where}.duct_placement: applies to the valve configuration only")
    return Envelope(duct_placement=placement, **values)


def _parse_bounds(table: Any, configuration: str, envelope: Envelope) -> dict:
    where = "design.bounds"
    table = _table(table, where, VARIABLES)
    bounds: dict[str, tuple[float, float] | None] = {}
    for key in VARIABLES[:-1]:
        name = f"{where}.{key}"
        if key == "duct_mean_diameter" and configuration == "mixed":
            if key in table:
                raise RequirementsError(f"{name}: not a free variable of a mixed damper (it is piston_diameter + "
                                        "gap); remove it")
            bounds[key] = None
            continue
        if key not in table:
            raise RequirementsError(f"{name}: missing ([low, high] or a single value)")
        bounds[key] = _range(table[key], name)
    value = table.get("ducts", 1)
    items = value if isinstance(value, list) else [value]
    if not 1 <= len(items) <= 2 or not all(isinstance(v, int) and not isinstance(v, bool) for v in items):
        raise RequirementsError(f"{where}.ducts: expected [low, high] whole numbers or one, got {value!r}")
    lo, hi = items[0], items[-1]
    if lo < 1 or lo > hi:
        raise RequirementsError(f"{where}.ducts: expected 1 <= low <= high, got {value!r}")
    if configuration == "mixed" and hi != 1:
        raise RequirementsError(f"{where}.ducts: a mixed damper has one gap (ducts must be 1), got {value!r}")
    if envelope.duct_placement == "around" and hi != 1:
        raise RequirementsError(f"{where}.ducts: one annulus fits around the cylinder (duct_placement = "
                                f"\"around\"), got {value!r}")
    bounds["ducts"] = (lo, hi)
    lo_dr, hi_dp = bounds["rod_diameter"][0], bounds["piston_diameter"][1]
    if lo_dr >= hi_dp:
        raise RequirementsError(f"{where}.rod_diameter: the smallest rod ({lo_dr * 1e3:g} mm) is not smaller than "
                                f"the largest piston ({hi_dp * 1e3:g} mm)")
    if bounds["duct_mean_diameter"] is not None and bounds["gap"][0] >= bounds["duct_mean_diameter"][1]:
        raise RequirementsError(f"{where}.gap: the smallest gap is not smaller than the largest duct_mean_diameter")
    return bounds


def _parse_search(table: Any) -> SearchSettings:
    where = "design.search"
    table = _table(table, where, _SEARCH_KEYS)
    defaults = SearchSettings()
    values: dict[str, Any] = {}
    for key, low in (("samples", 1), ("seed", 0), ("chunk", 1024), ("designs", 1)):
        v = _number(table, key, where, kind=int, low=low)
        values[key] = getattr(defaults, key) if v is None else v
    values["sampling"] = _choice(table, "sampling", where, SAMPLINGS, default=defaults.sampling)
    refine = table.get("refine", defaults.refine)
    if not isinstance(refine, bool):
        raise RequirementsError(f"{where}.refine: expected true or false, got {refine!r}")
    values["refine"] = refine
    pareto = table.get("pareto", list(defaults.pareto))
    if not isinstance(pareto, list):
        raise RequirementsError(f"{where}.pareto: expected a list of two or three figure names, got {pareto!r}")
    values["pareto"] = tuple(pareto)
    tol = _number(table, "active_tolerance", where)
    values["active_tolerance"] = defaults.active_tolerance if tol is None else tol
    for key in ("gap_tolerance", "length_tolerance"):
        if key in table:
            try:
                grid = float(to_si(table[key], "m", f"{where}.{key}"))
            except ErdesignError as exc:
                raise RequirementsError(str(exc)) from None
            if not 0 <= grid <= 1e-2:
                raise RequirementsError(f"{where}.{key}: must lie between 0 and 10 mm, got {table[key]!r}")
            values[key] = grid
    if "secondary" in table:
        values["secondary"] = _choice(table, "secondary", where, tuple(OBJECTIVES))
    search = SearchSettings(**values)
    _check_search(search, where)
    return search


def _check_search(search: SearchSettings, where: str) -> None:
    if not 2 <= len(search.pareto) <= 3 or len(set(search.pareto)) != len(search.pareto):
        raise RequirementsError(f"{where}.pareto: expected two or three different figures, got {list(search.pareto)!r}")
    for name in search.pareto:
        if name not in FIGURES:
            raise RequirementsError(f"{where}.pareto: unknown figure {name!r}; known: {', '.join(FIGURES)}")
    if not 0 <= search.active_tolerance < 1:
        raise RequirementsError(f"{where}.active_tolerance: must lie in [0, 1), got {search.active_tolerance!r}")
    if search.sampling not in SAMPLINGS:
        raise RequirementsError(f"{where}.sampling: must be one of {', '.join(map(repr, SAMPLINGS))}")
    for key in ("samples", "designs"):
        if not (isinstance(getattr(search, key), int) and getattr(search, key) >= 1):
            raise RequirementsError(f"{where}.{key}: must be a whole number >= 1")
    if search.samples > MAX_SAMPLES:
        raise RequirementsError(f"{where}.samples: {search.samples} is more than the search takes (at most "
                                f"{MAX_SAMPLES} = 2**24, hours of computing); narrow the bounds instead")
    if search.samples > PLAUSIBLE_SAMPLES:
        import warnings

        from ..errors import PlausibilityWarning
        warnings.warn(f"{where}.samples: {search.samples} candidates take minutes to evaluate (the default is "
                      f"{SearchSettings().samples})", PlausibilityWarning, stacklevel=3)
    if search.designs > 1000:
        raise RequirementsError(f"{where}.designs: at most 1000 designs are returned, got {search.designs}")
    if not (isinstance(search.chunk, int) and 1024 <= search.chunk <= MAX_CHUNK):
        raise RequirementsError(f"{where}.chunk: must be a whole number from 1024 to {MAX_CHUNK}")
