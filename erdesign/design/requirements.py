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
erdesign.design.requirements.RequirementsError: requirements: desing: unknown key (did you mean 'design'?); allowed keys: name, fluid, design
"""

from __future__ import annotations

import dataclasses
import numbers
import re
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from typing import Annotated

from pydantic import BeforeValidator

from ..damper.damper import check_piston_velocity
from ..damper.files import Control, FluidTable, parse_fluid_table, read_toml
from ..errors import ErdesignError, PlausibilityWarning
from ..examples import bundled_file
from ..fluid import Fluid
from ..geometry import CONFIGURATIONS, MAX_DUCTS
from ..magnetics.coil import PLAUSIBLE_SUPPLY_VOLTAGE
from ..schema import Flag, Number, Table, Text, checked, choice, quantity, validate, whole_number
from ..schema import field as key
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
#: Longest stroke [m] of the envelope taken without a warning (car dampers 0.1-0.3 m, large seismic dampers ~1 m).
PLAUSIBLE_STROKE = 2.0
#: Largest min_dynamic_range taken without a warning: ER and MR dampers reach 2 to about 100 (Butz and von Stryk
#: 2002); a thousand is a unit or a typing slip.
PLAUSIBLE_DYNAMIC_RANGE = 1e3


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
        return tuple(
            k for k in self.variables if self.bounds.get(k) is not None and self.bounds[k][0] < self.bounds[k][1]
        )


# ---------------------------------------------------------------------------------------------------- parsing
def read_requirements(path: str | Path) -> Requirements:
    """Read a requirements file (TOML); errors name the file and the key.  Where no such file exists, the name of
    a bundled example (``makris_requirements``, ...: :func:`example_requirements_names`) loads that example, and so
    does its documented path ``examples/requirements/makris_requirements.toml``."""
    if isinstance(path, str) and not Path(path).exists() and path in example_requirements_names():
        return load_example_requirements(path)
    return requirements_from_dict(read_toml(bundled_file(path) or path), source=str(path))


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
        raise RequirementsError(
            f"example: unknown requirements example {name!r}; available: {', '.join(example_requirements_names())}"
        )
    with resources.as_file(resources.files("erdesign.examples") / "requirements" / f"{name}.toml") as path:
        return requirements_from_dict(read_toml(path), source=f"examples/requirements/{name}.toml")


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
            raise RequirementsError(
                f'{name}: expected ["low unit", "high unit"] or one value with a unit, got {value!r}'
            )
        text = items[0] if len(items) == 1 else ""
        ends = re.fullmatch(r"\s*([^-\u2013]+?)\s*(?:-|\u2013|\.\.|\bto\b)\s*([\d.].*)", text)
        if ends and re.search(r"\d", ends[1]):  # '0.5 mm - 2 mm' was "a '-' between units"
            raise RequirementsError(
                f'{name}: {text!r} is a range as one text; write it as a list: ["{ends[1]}", "{ends[2]}"]'
            )
        lo, hi = (to_si(v, "m", name) for v in (items[0], items[-1]))
    if not lo > 0:
        raise RequirementsError(f"{name}: must be positive, got {items[0]!r}")
    if lo > hi:
        raise RequirementsError(f"{name}: low {items[0]!r} is above high {items[-1]!r}")
    return lo, hi


def _whole_range(value: Any, name: str) -> tuple[float, float]:
    return _range(value, name, whole=True)


def _tables(value: Any) -> Any:
    return [value] if isinstance(value, Mapping) else value


# ------------------------------------------------------------------------------------- the schema, declared once
def _q(unit: str, sign: str = "", dimension: str = "", plausible: tuple[float, float, str] | None = None) -> Any:
    """A quantity of a requirements file: always text (a bare number is refused as such); outside ``plausible``
    (low, high, whose range it is) it is warned (:func:`erdesign.schema.implausible`)."""
    return quantity(unit, sign, dimension, text=True, plausible=plausible)


# The ranges real dampers take (SI), outside which a requirement is warned as a likely unit mistake: forces from a
# haptic knob's newton to the 400 kN of the largest seismic MR dampers; a body from a centimetre to a few metres;
# hydraulic pressures up to 2000 bar; ER supplies up to 100 kV; a coil's supply, power and current density as
# the drives of damper coils have them.
_FORCE = (0.1, 1e6, "the force of any damper")
_BODY = (5e-3, 5.0, "the size of any damper")
_PRESSURE = (1e3, 2e8, "the pressure in any damper")


Length = _q("m", "positive")
#: A free variable's range: ``["low unit", "high unit"]`` or one value (fixed); read as ``(low, high)`` in SI.
LengthRange = checked(_range, '["low", "high"] lengths with units, or one (fixed)')
#: A whole-number variable's range: ``[low, high]`` or one number.
WholeRange = checked(_whole_range, "[low, high] whole numbers, or one (fixed)")


def _positive(value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"expected a number, got {value!r}")
    if not value > 0:
        raise ValueError(f"must be positive, got {value!r}")
    if value == float("inf"):  # TOML's inf: a requirement no design meets, searched for all the same
        raise ValueError(f"expected a finite number, got {value!r}")
    return value


def _figure_list(value: Any) -> Any:
    if not isinstance(value, list):
        raise ValueError(f"expected a list of two or three figure names, got {value!r}")
    return value


PositiveNumber = Annotated[Any, BeforeValidator(_positive), "number > 0"]
FigureList = Annotated[Any, BeforeValidator(_figure_list), "list of two or three figure names"]


class PointTable(Table):
    """One ``[[design.point]]``: an operating point and what the damper must do there (at least one requirement)."""

    velocity: _q("m/s", "positive") = key("piston velocity")
    field: Control = key("the control (with [design.coil]: the coil current), default 0", default=None)
    min_force: _q("N", "positive", plausible=_FORCE) = key(
        "least total force (with seal friction) at velocity and field", default=None
    )
    min_dynamic_range: PositiveNumber = key("least force at field / force at zero field, at velocity", default=None)
    max_zero_field_force: _q("N", "positive", plausible=_FORCE) = key(
        "largest force at velocity with no field (beyond the contract)", default=None
    )


class LimitsTable(Table):
    """``[design.limits]``: what every design must respect (all optional)."""

    max_outer_diameter: _q("m", "positive", plausible=_BODY) = key(
        'cylinder outer diameter: piston diameter + 2 x wall (valve ducts "around": the outer tube)', default=None
    )
    max_length: _q("m", "positive", plausible=_BODY) = key(
        "body length of the envelope model (docs/design.md)", default=None
    )
    max_pressure: _q("Pa", "positive", plausible=_PRESSURE) = key(
        "pressure drop across the piston, at field and at zero field", default=None
    )
    laminar: Flag = key("Reynolds number (Makris et al. 1996, eq 1) below 2300 at every point", default=False)
    min_gap: _q("m", "positive", plausible=(1e-6, 1e-2, "the gap of any damper")) = key(
        "manufacturable minimum gap (at most the largest gap of [design.bounds])", default=None
    )
    max_field: Control = key(
        "largest control the fluid takes (default: 4 kV/mm ER, 250 kA/m MR; Butz and von Stryk 2002, Table 1)",
        default=None,
    )
    max_voltage: _q("V", "positive", plausible=(1.0, 1e5, "the supply of any ER damper")) = key(
        "largest electrode voltage E h across the gap (ER only)", default=None
    )


class EnvelopeTable(Table):
    """``[design.envelope]``: the envelope model of :mod:`erdesign.design.envelope` (all optional)."""

    stroke: _q("m", "positive") = key("full piston stroke (default 50 mm)", default=None)
    wall: _q("m", "non-negative", plausible=(0.0, 0.2, "the wall of any damper")) = key(
        "wall allowance of the cylinder (default 5 mm)", default=None
    )
    head_length: _q("m", "non-negative", plausible=(0.0, 1.0, "the piston head of any damper")) = key(
        "valve piston head length (default 20 mm)", default=None
    )
    end_allowance: _q("m", "non-negative", plausible=(0.0, 1.0, "the end cap of any damper")) = key(
        "each end cap with seal and bearing (default 25 mm)", default=None
    )
    duct_placement: choice(*DUCT_PLACEMENTS) = key(
        'valve: ducts "beside" the cylinder (Makris Fig 1) or one annulus "around" it', default="beside"
    )


class BoundsTable(Table):
    """``[design.bounds]``: the free variables, each ``[low, high]`` or one value (fixed)."""

    gap: LengthRange = key("h")
    duct_length: LengthRange = key("L")
    duct_mean_diameter: LengthRange = key("d (valve only: a mixed damper's is piston_diameter + gap)", default=None)
    piston_diameter: LengthRange = key("Dp")
    rod_diameter: LengthRange = key("dr")
    ducts: WholeRange = key("parallel ducts (valve only)", default=1)


class SearchTable(Table):
    """``[design.search]``: how the design space is searched (all optional; docs/design.md)."""

    samples: whole_number(1) = key("candidates sampled", default=SearchSettings.samples)
    sampling: choice(*SAMPLINGS) = key("the sampler", default=SearchSettings.sampling)
    seed: whole_number(0) = key("seed of the sampler", default=SearchSettings.seed)
    chunk: whole_number(1024) = key("candidates evaluated at once", default=SearchSettings.chunk)
    refine: Flag = key("refine the best designs locally", default=SearchSettings.refine)
    designs: whole_number(1) = key("how many designs to return", default=SearchSettings.designs)
    pareto: FigureList = key("figures of the Pareto front (erdesign.design.figures.FIGURES)", default=None)
    active_tolerance: Number = key(
        "relative margin below which a constraint counts as active", default=SearchSettings.active_tolerance
    )
    gap_tolerance: _q("m") = key("grid the returned gap is rounded to, 0 to 10 mm (default 0.01 mm)", default=None)
    length_tolerance: _q("m") = key(
        "grid the other returned lengths are rounded to, 0 to 10 mm (default 0.1 mm)", default=None
    )
    secondary: choice(*OBJECTIVES) = key("objective that breaks ties (default: per objective)", default=None)


class CoilTable(Table):
    """``[design.coil]``: the coil of an MR head designed too (docs/magnetics.md, "Design with the coil")."""

    turns: WholeRange = key("turns of the coil")
    wire_diameter: LengthRange = key("copper wire diameter")
    core_diameter: LengthRange = key("steel core under the winding")
    pole_length: LengthRange = key("axial length of each pole")
    housing_outer_diameter: LengthRange = key("outer diameter of the steel cylinder")
    steel: Text = key("steel of the materials database", default="steel-1018")
    supply_voltage: _q("V", "positive", plausible=PLAUSIBLE_SUPPLY_VOLTAGE) = key(
        "largest I R at every point", default=None
    )
    max_current_density: _q(
        "A/m^2", "positive", "current density", plausible=(1e4, 1e8, "any copper winding (0.01 to 100 A/mm^2)")
    ) = key("current density limit (default 5 A/mm^2)", default=None)
    max_fill_factor: Number = key("copper fill factor limit, in (0, 0.9] (default 0.6)", default=None)
    allow_saturation: Flag = key("allow a part of the circuit past the knee of its B-H curve", default=False)
    max_power: _q("W", "positive", plausible=(1e-3, 1e5, "the power of any damper coil")) = key(
        "coil power at the first point's current", default=None
    )
    max_time_constant: _q("s", "positive", plausible=(1e-6, 100.0, "the time constant of any damper coil")) = key(
        "L/R at the first point's current", default=None
    )


class DesignTable(Table):
    """``[design]`` of a requirements file."""

    configuration: choice(*CONFIGURATIONS) = key('"valve" or "mixed", as in the damper file')
    objective: choice(*OBJECTIVES) = key("what the ranking minimises or maximises", default="min_fluid_volume")
    point: Annotated[list[PointTable], BeforeValidator(_tables), "list of tables"] = key(
        "one or more [[design.point]] tables"
    )
    limits: LimitsTable = key("[design.limits]", default=None)
    bounds: BoundsTable = key("[design.bounds]: the free variables and their ranges")
    envelope: EnvelopeTable = key("[design.envelope]", default=None)
    search: SearchTable = key("[design.search]", default=None)
    coil: CoilTable = key("[design.coil]: the head's coil is designed too", default=None)


class RequirementsFile(Table):
    """A requirements file (TOML) of ``erdesign design``."""

    name: Text = key("free text", default="")
    fluid: FluidTable = key('exactly as in a damper file (or material = "...")')
    design: DesignTable = key("what the damper must do, its envelope and its free geometry")


def requirements_from_dict(data: Mapping[str, Any], *, source: str = "requirements") -> Requirements:
    """:class:`Requirements` from the parsed content of a requirements file.  ``source`` prefixes errors."""
    try:
        return _parse(data)
    except ErdesignError as exc:
        raise RequirementsError(f"{source}: {exc}") from None


def _si(value: Any, unit: str, name: str) -> float | None:
    """A value the schema checked, in SI (None stays None)."""
    return None if value is None else float(to_si(value, unit, name))


def _parse(data: Mapping[str, Any]) -> Requirements:
    if isinstance(data, Mapping) and "geometry" in data and "design" not in data:
        raise RequirementsError(
            "a damper file ([geometry]), not a requirements file ([design]); give it to erdesign size, fit or report"
        )
    spec = validate(RequirementsFile, data, error=RequirementsError)
    design = spec.design
    fluid_table = dict(data["fluid"])
    coil = None
    if design.coil is not None:
        fluid, seal_friction, coil, coil_bounds = _parse_coil(design.coil, fluid_table)
    else:
        fluid, seal_friction = parse_fluid_table(fluid_table, "fluid")
    configuration, objective = design.configuration, design.objective
    if objective in COIL_OBJECTIVES and coil is None:
        raise RequirementsError(f"design.objective: {objective!r} needs a [design.coil] table (the coil to design)")
    if not design.point:
        raise RequirementsError("design.point: expected one or more [[design.point]] tables, got []")
    points = _parse_points(design.point, fluid)
    limits = _parse_limits(design.limits or LimitsTable(), fluid)
    envelope = _parse_envelope(design.envelope or EnvelopeTable(), configuration)
    bounds = _parse_bounds(design.bounds, configuration, envelope)
    if coil is not None:
        if bounds["ducts"] != (1, 1):
            raise RequirementsError("design.bounds.ducts: a coil sits in a head with one annular gap (ducts = 1)")
        bounds.update(coil_bounds)
    if limits.min_gap is not None and limits.min_gap > bounds["gap"][1]:
        raise RequirementsError(
            f"design.limits.min_gap: {limits.min_gap * 1e3:g} mm is above the largest gap of "
            f"design.bounds.gap ({bounds['gap'][1] * 1e3:g} mm): no design can meet both; lower "
            "min_gap or widen the gap's bounds"
        )
    search = _parse_search(design.search or SearchTable())
    return Requirements(
        fluid=fluid,
        seal_friction=seal_friction,
        fluid_table=fluid_table,
        configuration=configuration,
        objective=objective,
        points=points,
        bounds=bounds,
        limits=limits,
        envelope=envelope,
        search=search,
        name=spec.name,
        coil=coil,
    )


def _parse_coil(table: CoilTable, fluid_table: Mapping[str, Any]):
    """The fluid (controlled by the coil current), seal friction, :class:`CoilDesign` and the coil's bounds."""
    from .. import materials
    from ..damper.files import POWER_LAW_KEYS

    where = "design.coil"
    for k in POWER_LAW_KEYS:
        if k in fluid_table:
            raise RequirementsError(
                f"fluid.{k}: not allowed with [design.coil]: each candidate's magnetic circuit "
                "gives the yield stress at the point's coil current"
            )
    name = fluid_table.get("material")
    if not isinstance(name, str):
        raise RequirementsError(
            "fluid.material: missing; with [design.coil] the fluid's B-H and yield curves come "
            "from the materials database"
        )
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
    if table.steel not in materials.steel_names():
        raise RequirementsError(
            f"{where}.steel: unknown steel {table.steel!r}; known steels: {', '.join(materials.steel_names())}"
        )
    fill = table.max_fill_factor
    if fill is not None and not 0 < fill <= 0.9:
        raise RequirementsError(f"{where}.max_fill_factor: must lie in (0, 0.9], got {fill!r}")
    J = _si(table.max_current_density, "A/m^2", f"{where}.max_current_density")
    coil = CoilDesign(
        material=name,
        steel=table.steel,
        supply_voltage=_si(table.supply_voltage, "V", f"{where}.supply_voltage"),
        max_current_density=DEFAULT_CURRENT_DENSITY if J is None else J,
        max_fill_factor=DEFAULT_FILL_FACTOR if fill is None else float(fill),
        allow_saturation=table.allow_saturation,
        max_power=_si(table.max_power, "W", f"{where}.max_power"),
        max_time_constant=_si(table.max_time_constant, "s", f"{where}.max_time_constant"),
    )
    return fluid, seal_friction, coil, {k: getattr(table, k) for k in COIL_VARIABLES}


def _parse_points(tables: list[PointTable], fluid: Fluid) -> tuple[DesignPoint, ...]:
    points = []
    for i, table in enumerate(tables, start=1):
        where = f"design.point[{i}]"
        field_value = 0.0
        if table.field is not None:
            field_value = fluid.field_si(table.field, f"{where}.field")
            if field_value < 0:
                raise RequirementsError(f"{where}.field: must not be negative, got {table.field!r}")
        point = DesignPoint(
            velocity=check_piston_velocity(_si(table.velocity, "m/s", f"{where}.velocity"), f"{where}.velocity"),
            field=field_value,
            min_force=_si(table.min_force, "N", f"{where}.min_force"),
            min_dynamic_range=None if table.min_dynamic_range is None else float(table.min_dynamic_range),
            max_zero_field_force=_si(table.max_zero_field_force, "N", f"{where}.max_zero_field_force"),
        )
        if point.min_dynamic_range is not None and point.min_dynamic_range <= 1.0:
            # the force at a control over the force at none is >= 1 for any fluid: the requirement asks nothing
            warnings.warn(
                f"{where}.min_dynamic_range: {point.min_dynamic_range:g} is met by every damper (the dynamic range, "
                "the force at the control over the force at none, is at least 1); check the value",
                PlausibilityWarning,
                stacklevel=2,
            )
        if point.min_dynamic_range is not None and point.min_dynamic_range > PLAUSIBLE_DYNAMIC_RANGE:
            warnings.warn(
                f"{where}.min_dynamic_range: {point.min_dynamic_range:g} is beyond the dynamic range of any damper "
                f"(ER and MR dampers reach 2 to about 100; at most {PLAUSIBLE_DYNAMIC_RANGE:g} here); check the value",
                PlausibilityWarning,
                stacklevel=2,
            )
        if point.min_force is None and point.min_dynamic_range is None and point.max_zero_field_force is None:
            raise RequirementsError(
                f"{where}: states no requirement (give min_force, min_dynamic_range or max_zero_field_force)"
            )
        points.append(point)
    return tuple(points)


def _parse_limits(table: LimitsTable, fluid: Fluid) -> Limits:
    where = "design.limits"
    max_field = FIELD_LIMITS.get(fluid.control)
    if table.max_field is not None:
        max_field = fluid.field_si(table.max_field, f"{where}.max_field")
        if not max_field > 0:
            raise RequirementsError(f"{where}.max_field: must be positive, got {table.max_field!r}")
    max_voltage = _si(table.max_voltage, "V", f"{where}.max_voltage")
    if max_voltage is not None and fluid.control != "electric field":
        raise RequirementsError(
            f"{where}.max_voltage: applies to an ER fluid controlled by an electric field "
            f"(this fluid's control is a {fluid.control})"
        )
    return Limits(
        max_outer_diameter=_si(table.max_outer_diameter, "m", f"{where}.max_outer_diameter"),
        max_length=_si(table.max_length, "m", f"{where}.max_length"),
        max_pressure=_si(table.max_pressure, "Pa", f"{where}.max_pressure"),
        laminar=table.laminar,
        min_gap=_si(table.min_gap, "m", f"{where}.min_gap"),
        max_field=max_field,
        max_voltage=max_voltage,
    )


def _parse_envelope(table: EnvelopeTable, configuration: str) -> Envelope:
    where = "design.envelope"
    defaults = Envelope()
    values = {
        k: getattr(defaults, k) if getattr(table, k) is None else _si(getattr(table, k), "m", f"{where}.{k}")
        for k in ("stroke", "wall", "head_length", "end_allowance")
    }
    if "duct_placement" in table.model_fields_set and configuration != "valve":
        raise RequirementsError(f"{where}.duct_placement: applies to the valve configuration only")
    if values["stroke"] > PLAUSIBLE_STROKE:
        import warnings

        from ..errors import PlausibilityWarning

        warnings.warn(
            f"{where}.stroke: {values['stroke']:g} m is beyond the stroke of any damper ({PLAUSIBLE_STROKE:g} m); "
            "check the value and its unit",
            PlausibilityWarning,
            stacklevel=4,
        )
    return Envelope(duct_placement=table.duct_placement, **values)


def _parse_bounds(table: BoundsTable, configuration: str, envelope: Envelope) -> dict:
    where = "design.bounds"
    bounds: dict[str, tuple[float, float] | None] = {k: getattr(table, k) for k in VARIABLES[:-1]}
    if configuration == "mixed":
        if table.duct_mean_diameter is not None:
            raise RequirementsError(
                f"{where}.duct_mean_diameter: not a free variable of a mixed damper (it is "
                "piston_diameter + gap); remove it"
            )
    elif table.duct_mean_diameter is None:
        raise RequirementsError(f"{where}.duct_mean_diameter: missing ([low, high] or a single value)")
    ducts = table.ducts if "ducts" in table.model_fields_set else (1.0, 1.0)
    lo, hi = int(ducts[0]), int(ducts[1])
    if hi > MAX_DUCTS:
        raise RequirementsError(f"{where}.ducts: at most {MAX_DUCTS} parallel ducts, got {[lo, hi]!r}")
    if configuration == "mixed" and hi != 1:
        raise RequirementsError(f"{where}.ducts: a mixed damper has one gap (ducts must be 1), got {[lo, hi]!r}")
    if envelope.duct_placement == "around" and hi != 1:
        raise RequirementsError(
            f'{where}.ducts: one annulus fits around the cylinder (duct_placement = "around"), got {[lo, hi]!r}'
        )
    bounds["ducts"] = (lo, hi)
    lo_dr, hi_dp = bounds["rod_diameter"][0], bounds["piston_diameter"][1]
    if lo_dr >= hi_dp:
        raise RequirementsError(
            f"{where}.rod_diameter: the smallest rod ({lo_dr * 1e3:g} mm) is not smaller than "
            f"the largest piston ({hi_dp * 1e3:g} mm)"
        )
    if bounds["duct_mean_diameter"] is not None and bounds["gap"][0] >= bounds["duct_mean_diameter"][1]:
        raise RequirementsError(f"{where}.gap: the smallest gap is not smaller than the largest duct_mean_diameter")
    return bounds


def _parse_search(table: SearchTable) -> SearchSettings:
    where = "design.search"
    defaults = SearchSettings()
    values: dict[str, Any] = {
        k: getattr(table, k) for k in ("samples", "seed", "chunk", "designs", "sampling", "refine", "active_tolerance")
    }
    values["pareto"] = defaults.pareto if table.pareto is None else tuple(table.pareto)
    for k in ("gap_tolerance", "length_tolerance"):
        if getattr(table, k) is not None:
            grid = _si(getattr(table, k), "m", f"{where}.{k}")
            if not 0 <= grid <= 1e-2:
                raise RequirementsError(f"{where}.{k}: must lie between 0 and 10 mm, got {getattr(table, k)!r}")
            values[k] = grid
    if table.secondary is not None:
        values["secondary"] = table.secondary
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
    for name in ("samples", "designs"):
        if not (isinstance(getattr(search, name), int) and getattr(search, name) >= 1):
            raise RequirementsError(f"{where}.{name}: must be a whole number >= 1")
    if search.samples > MAX_SAMPLES:
        raise RequirementsError(
            f"{where}.samples: {search.samples} is more than the search takes (at most "
            f"{MAX_SAMPLES} = 2**24, hours of computing); narrow the bounds instead"
        )
    if search.samples > PLAUSIBLE_SAMPLES:
        import warnings

        from ..errors import PlausibilityWarning

        warnings.warn(
            f"{where}.samples: {search.samples} candidates take minutes to evaluate (the default is "
            f"{SearchSettings().samples})",
            PlausibilityWarning,
            stacklevel=3,
        )
    if search.designs > 1000:
        raise RequirementsError(f"{where}.designs: at most 1000 designs are returned, got {search.designs}")
    if not (isinstance(search.chunk, int) and 1024 <= search.chunk <= MAX_CHUNK):
        raise RequirementsError(f"{where}.chunk: must be a whole number from 1024 to {MAX_CHUNK}")
