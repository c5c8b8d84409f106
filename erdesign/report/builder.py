r"""Build the content of an engineering report on a damper: inputs, derived quantities, equations, checks, figures.

:func:`build_report` gathers everything a report shows into a :class:`Report` of plain records; the rendering
(:mod:`erdesign.report.render`) only lays them out.  Every number in a :class:`Report` is a
:class:`~erdesign.report.formatting.Shown`, made by the one helper :func:`~erdesign.report.formatting.show`.

Defaults when the caller gives none:

* controls: 0, 1/3, 2/3 and 1 times the fluid's reference field (zero is always added);
* velocity range: 0 to :math:`v_\text{max}`, the smaller of :math:`30\,F_y(E_\text{ref})/C` (thirty times the
  velocity at which the zero-field viscous force equals the yield force) and the velocity at which the zero-field
  Reynolds number reaches 230 (a tenth of the laminar limit), rounded up to 1, 2 or 5 times a power of ten;
* design point: ``design_velocity`` (default: the top of the velocity range, which is widened to contain it) and
  ``design_field`` (default: the largest control); the report's "Design point" section is :func:`design_point_rows`,
  the rows the app's Size page shows;
* sine: amplitude 10 mm, frequency such that the peak velocity is the top of the velocity range.

The validity checks of the design (section 4) are :func:`erdesign.damper.validity.validity_checks`: physics of
the damper, not of the report; they are re-exported here with :class:`Check` and their limits.

The optional measurement section is rendered only when :class:`MeasurementComparison` or an error history
(:class:`ErrorHistoryStep` items, or ``(step, effect, esr)`` tuples) is given.
"""

from __future__ import annotations

import dataclasses
import datetime
import math
import warnings
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from dataclasses import field as dc_field
from pathlib import Path
from typing import Any

import numpy as np

from .. import materials
from ..damper import CRITICAL_REYNOLDS, Damper
from ..damper.damper import check_piston_velocity
from ..damper.curves import ForceVelocityCurves, SineLoops, force_velocity_curves, sine_loops
from ..damper.files import damper_file_path, damper_from_dict, read_toml
from ..damper.validity import PLUG_FRACTION_LIMIT, SEAL_SHARE_LIMIT, Check, validity_checks
from ..errors import ErdesignError, ValidityWarning
from ..formatting import control_label, esr_shown
from ..units import Q_, parse_quantity, positive_si, to_si
from .equations import Equation, equations_for
from .formatting import Shown, pick_unit, show

__all__ = [
    "Report",
    "Row",
    "InputRow",
    "Check",
    "Table",
    "FigureSpec",
    "MeasurementComparison",
    "tolerance_figures",
    "ErrorHistoryStep",
    "build_report",
    "design_point_rows",
    "validity_checks",
    "report_grid",
    "default_velocity_max",
    "report_units",
    "compare_designs",
    "relative_change",
    "with_baseline",
    "PLUG_FRACTION_LIMIT",
    "SEAL_SHARE_LIMIT",
    "DEFAULT_AMPLITUDE",
]

#: Sine amplitude of the loops when none is given.
DEFAULT_AMPLITUDE = "10 mm"
_VELOCITY_POINTS = 81
_TABLE_POINTS = 11

# Display of the SI units of each input key of a damper file.
_GEOMETRY_SI = {"duct_length": "m", "duct_mean_diameter": "m", "gap": "m", "piston_diameter": "m", "rod_diameter": "m"}
_FLUID_SI = {
    "viscosity": "Pa*s",
    "yield_stress": "Pa",
    "density": "kg/m^3",
    "viscosity_at_reference_field": "Pa*s",
    "shear_modulus": "Pa",
    "seal_friction": "N",
}


@dataclass(frozen=True)
class Row:
    """A labelled quantity."""

    key: str
    label: str
    value: Shown
    note: str = ""


@dataclass(frozen=True)
class InputRow:
    """One input: as given (text) and in SI, and where it came from."""

    section: str
    key: str
    given: str
    si: Shown | None
    origin: str


@dataclass(frozen=True)
class Table:
    """A table of quantities: column headers (name and unit) and rows of :class:`Shown`."""

    key: str
    columns: tuple[str, ...]
    rows: tuple[tuple[Shown, ...], ...]


@dataclass(frozen=True)
class FigureSpec:
    """A figure: its plotly figure (HTML) and a table of sampled values (Markdown)."""

    key: str
    title: str
    figure: Any
    table: Table | None
    caption: str = ""


@dataclass(frozen=True)
class MeasurementComparison:
    """A measurement compared with the model (the diagnosis work fills this in; all optional but ``esr``).

    Attributes
    ----------
    label : str
        What was measured (file name, test).
    esr : float
        ESR of the model against the measurement (Vivas-López et al., eq 7), [-].
    samples : int or None
        Samples the ESR and the RMS error are computed on (a diagnosis: those it judged).
    rms_error : quantity or None
        RMS of F - F_model (a force) on those samples.
    peak_force_measured, peak_force_model : quantity or None
        Largest |F| of the measurement and the model (forces).
    displacement, velocity, force_measured, force_model : array or None
        SI arrays [m, m/s, N, N] for the loop figure (all four or none).
    notes : str
    """

    label: str
    esr: float
    samples: int | None = None
    rms_error: Any = None
    peak_force_measured: Any = None
    peak_force_model: Any = None
    displacement: Any = None
    velocity: Any = None
    force_measured: Any = None
    force_model: Any = None
    notes: str = ""
    verdict: str = ""
    """The diagnosis' verdict (``"missing_effect"``, ``"nothing_missing"``, ``"unexplained"``), or empty."""
    reason: str = ""
    """The verdict in words, as the diagnosis gives it."""
    noise_floor_esr: float | None = None
    """ESR that the measurement noise alone would leave on the same samples, [-]."""
    parameters: tuple = ()
    """The calibrated parameters as :func:`erdesign.report.fit.parameter_rows` shows them (value, ± 1σ, ±,
    initial, bounds, status)."""
    statistics: tuple = ()
    """:func:`erdesign.report.fit.statistics_rows` of the calibration."""
    correlations: tuple = ()
    """:func:`erdesign.report.fit.correlation_rows` of the calibration."""


@dataclass(frozen=True)
class ErrorHistoryStep:
    """One step of a diagnosis: the effect added at that step and the ESR after refitting, [-]."""

    step: int
    effect: str
    esr: float


@dataclass(frozen=True)
class Report:
    """Everything a report shows (see the module notes).  Render with :func:`erdesign.report.render_html` or
    :func:`erdesign.report.render_markdown`."""

    title: str
    source: str
    generated: str
    version: str
    configuration: str
    notes: tuple[str, ...]
    settings: tuple[Row, ...]
    inputs: tuple[InputRow, ...]
    material: Mapping[str, Any] | None
    derived: tuple[Row, ...]
    design_table: Table
    sine_table: Table
    equations: tuple[Equation, ...]
    checks: tuple[Check, ...]
    figures: tuple[FigureSpec, ...]
    comparison: Mapping[str, Any] | None
    history: tuple[ErrorHistoryStep, ...]
    sweep: ForceVelocityCurves = dc_field(repr=False)
    """The force-velocity curves behind the figures (the field keeps its name: it is the report's API)."""
    loops: SineLoops = dc_field(repr=False)
    design_point: tuple[Row, ...] = ()
    """The design point (:func:`design_point_rows`): velocity, control and the figures the Size page shows."""
    validity_messages: tuple[str, ...] = ()
    """Validity warnings the library gave building the damper and sizing it (as the app shows them)."""
    magnetics: Mapping[str, Any] | None = None
    """A damper with a ``[coil]``: the magnetic circuit (:func:`magnetic_section`): ``rows`` (coil, saturation,
    power and time constant at the rated current) and ``table`` (the circuit at each control)."""
    baseline: Mapping[str, Any] | None = None
    """A design compared with a pinned baseline (:func:`compare_designs`): ``name``, ``inputs`` (the inputs that
    differ, as typed) and ``rows`` (the design point of both, with the relative change)."""

    @property
    def warnings(self) -> int:
        """Number of checks that warn."""
        return sum(c.status == "warn" for c in self.checks)

    def setting(self, key: str) -> Row:
        """The settings row ``key`` (``"velocity_design"``, ``"field_design"``, ``"amplitude"`` ...)."""
        for row in self.settings:
            if row.key == key:
                return row
        raise KeyError(key)


def _nice_ceiling(x: float) -> float:
    """Smallest 1, 2 or 5 times a power of ten that is >= x."""
    e = math.floor(math.log10(x))
    for m in (1.0, 2.0, 5.0, 10.0):
        if m * 10.0**e >= x * (1 - 1e-12):
            return m * 10.0**e
    return 10.0 ** (e + 1)  # pragma: no cover


def default_velocity_max(damper: Damper) -> float:
    """Top of the default velocity range, [m/s] (module notes)."""
    fluid = damper.fluid
    C = damper.damping_constant_si()
    v_yield = float(damper.yield_force_si(fluid.reference_field)) / C
    s = damper.state(1.0, 0.0)
    v_laminar = 0.1 * CRITICAL_REYNOLDS / float(s.reynolds)  # Re is proportional to v at zero field
    return _nice_ceiling(min(30.0 * v_yield, v_laminar))


def _as_history(history: Iterable[Any] | None) -> tuple[ErrorHistoryStep, ...]:
    out = []
    for i, item in enumerate(history or ()):
        step = item if isinstance(item, ErrorHistoryStep) else ErrorHistoryStep(*item)
        if isinstance(step.step, bool) or not isinstance(step.step, (int, np.integer)):
            raise ErdesignError(f"history[{i}].step: expected a whole number, got {step.step!r}")
        if not (isinstance(step.esr, (int, float)) and math.isfinite(step.esr) and step.esr >= 0):
            raise ErdesignError(f"history[{i}].esr: expected a finite number >= 0, got {step.esr!r}")
        out.append(ErrorHistoryStep(int(step.step), str(step.effect), float(step.esr)))
    return tuple(out)


def _inputs(
    data: Mapping[str, Any] | None, damper: Damper, origin: str = "damper file"
) -> tuple[tuple[InputRow, ...], dict | None]:
    """Input rows from a damper file's content (as given, in SI, origin); the material record if one is named."""
    rows: list[InputRow] = []
    fluid = damper.fluid
    control = fluid.control_unit
    if data is None:  # a Damper built in Python: show its SI values
        g = damper.geometry
        for key, unit in _GEOMETRY_SI.items():
            rows.append(InputRow("geometry", key, "", show(Q_(getattr(g, key), unit), unit, name=key), "Python"))
        for key in ("viscosity", "yield_stress", "density"):
            rows.append(
                InputRow(
                    "fluid", key, "", show(Q_(getattr(fluid, key), _FLUID_SI[key]), _FLUID_SI[key], name=key), "Python"
                )
            )
        rows.append(
            InputRow(
                "fluid",
                "reference_field",
                "",
                show(Q_(fluid.reference_field, control), control, name="reference_field"),
                "Python",
            )
        )
        return tuple(rows), None
    geometry = data.get("geometry", {})
    for key, value in geometry.items():
        unit = _GEOMETRY_SI.get(key)
        if key == "ducts":
            si = show(float(value), "", name="geometry.ducts")
        else:
            si = show(Q_(to_si(value, unit, f"geometry.{key}"), unit), unit, name=f"geometry.{key}") if unit else None
        rows.append(InputRow("geometry", key, str(value), si, origin))
    table = dict(data.get("fluid", {}))
    record = None
    merged: dict[str, tuple[Any, str]] = {}
    if "material" in table:
        record = materials.load(table["material"])
        for key, value in record["fluid"].items():
            merged[key] = (value, f"material {table['material']}")
    for key, value in table.items():
        if key != "material":
            merged[key] = (value, origin)
    for key, (value, origin) in merged.items():
        if key == "yield_exponent":
            si = show(float(value), "", name=f"fluid.{key}")
        elif key == "reference_field":
            si = show(Q_(to_si(value, control, f"fluid.{key}"), control), control, name=f"fluid.{key}")
        else:
            unit = _FLUID_SI[key]
            si = show(Q_(to_si(value, unit, f"fluid.{key}"), unit), unit, name=f"fluid.{key}")
        rows.append(InputRow("fluid", key, str(value), si, origin))
    return tuple(rows), record


def _material_section(record: Mapping[str, Any] | None, damper: Damper) -> dict | None:
    if record is None:
        return None
    fluid = damper.fluid
    return {
        "name": record["name"],
        "kind": record["kind"],
        "description": record["description"],
        "law": fluid.yield_law.describe(fluid.field_unit),
        "law_in_use": (
            "the material's yield curve"
            if fluid.field_law is not None
            else "the power law of [fluid] (the damper file sets yield_stress, reference_field or yield_exponent)"
            if "yield_curve" in record
            else "the power law of [fluid]"
        ),
        "range": {k: " to ".join(v) for k, v in record.get("range", {}).items()},
        "references": [f"{r['key']}: {r['citation']} ({r['date']})" for r in record["references"]],
    }


def _field_table(
    key: str,
    x_label: str,
    x: np.ndarray,
    x_si: str,
    x_kind: str,
    curves: ForceVelocityCurves,
    values: np.ndarray,
    si_unit: str,
    kind: str,
    skip_zero: bool = False,
) -> Table:
    """A table of a figure's values at up to 11 of its points: x column, one column per control."""
    idx = np.unique(np.linspace(0, x.size - 1, min(_TABLE_POINTS, x.size)).round().astype(int))
    x_unit = pick_unit(Q_(x, x_si), x_kind)
    y_unit = pick_unit(Q_(values, si_unit), kind) if kind else ""
    keep = [i for i, E in enumerate(curves.field) if not (skip_zero and E == 0)]
    labels = [curves.field_labels()[i] for i in keep]
    unit_text = f" [{Q_(1.0, y_unit).units:~P}]" if y_unit else ""
    columns = (f"{x_label} [{Q_(1.0, x_unit).units:~P}]",) + tuple(f"{lab}{unit_text}" for lab in labels)
    rows = []
    for j in idx:
        row = [show(Q_(x[j], x_si), x_unit, name=x_label)]
        for i in keep:
            value = values[i, j]
            row.append(show(Q_(value, si_unit) if si_unit else float(value), y_unit, name=f"{key}[{i}, {j}]"))
        rows.append(tuple(row))
    return Table(key, columns, tuple(rows))


def _loop_table(loops: SineLoops) -> Table:
    """A sine's loops at 12 instants of the cycle (phases 15, 45, ... 345 degrees): x, v, the force per control."""
    r0 = loops.responses[0]
    n = r0.time.size - 1
    idx = ((2 * np.arange(12) + 1) * n) // 24
    x_unit = pick_unit(Q_(loops.amplitude, "m"), "length")
    v_unit = pick_unit(Q_(r0.velocity, "m/s"), "velocity")
    F_all = Q_(np.concatenate([r.force for r in loops.responses]), "N")
    f_unit = pick_unit(F_all, "force")
    fu = f"{Q_(1.0, f_unit).units:~P}"
    columns = (f"displacement x [{Q_(1.0, x_unit).units:~P}]", f"velocity v [{Q_(1.0, v_unit).units:~P}]") + tuple(
        f"{label} [{fu}]" for label in loops.field_labels()
    )
    rows = tuple(
        (
            show(Q_(r0.displacement[j], "m"), x_unit, name="displacement"),
            show(Q_(r0.velocity[j], "m/s"), v_unit, name="velocity"),
        )
        + tuple(show(Q_(r.force[j], "N"), f_unit, name="force") for r in loops.responses)
        for j in idx
    )
    return Table("sine_loops", columns, rows)


def report_grid(
    damper: Damper,
    velocity_range: Sequence[Any] | None,
    fields: Sequence[Any] | None,
    design_velocity: Any = None,
    design_field: Any = None,
) -> tuple[np.ndarray, np.ndarray, float, float]:
    """The velocities and controls a report (and the app's Size page) evaluates, and the design point.

    Returns ``(v, E, v_design, E_design)``, SI: ``v`` the sweep velocities (the range, widened to contain the design
    velocity, which is one of the points), ``E`` the controls (zero, ``fields`` and the design control, sorted,
    no repeats), the design velocity and the design control.  Arguments as :func:`build_report` takes them.
    """
    fluid = damper.fluid
    control = fluid.control_unit
    if fields is None:
        E = fluid.reference_field * np.array([0.0, 1 / 3, 2 / 3, 1.0])
    else:
        E = np.array([to_si(f, control, f"field[{i}]") for i, f in enumerate(fields)], dtype=float)
    E_design = (
        float(np.max(np.abs(E))) if design_field is None else abs(float(to_si(design_field, control, "design field")))
    )
    E = np.unique(np.concatenate([[0.0], np.abs(E), [E_design]]))
    if fields is not None or design_field is not None:
        fluid.check_field(E, "field")
    if velocity_range is None:
        v_lo, v_hi = 0.0, default_velocity_max(damper)
    else:
        if len(velocity_range) != 2:
            raise ErdesignError("velocity_range: expected two velocities (lowest, highest)")
        v_lo, v_hi = (
            float(check_piston_velocity(to_si(v, "m/s", f"velocity_range[{i}]"), f"velocity_range[{i}]"))
            for i, v in enumerate(velocity_range)
        )
        if not (0 <= v_lo < v_hi):
            raise ErdesignError(f"velocity_range: need 0 <= lowest < highest, got {v_lo:g} m/s to {v_hi:g} m/s")
    if design_velocity is None:
        v_design = v_hi
    else:
        v_design = abs(float(to_si(design_velocity, "m/s", "design velocity")))
        if not v_design > 0:
            raise ErdesignError(f"design velocity: must be positive, got {design_velocity!r}")
        v_lo, v_hi = min(v_lo, v_design), max(v_hi, v_design)
    v = np.unique(np.concatenate([np.linspace(v_lo, v_hi, _VELOCITY_POINTS), [v_design]]))
    return v, E, v_design, E_design


def design_point_rows(
    damper: Damper, velocity: float, field: float, units: Mapping[str, str] | None = None
) -> tuple[Row, ...]:
    """The design point as the app's Size page shows it and the report prints it: :meth:`Damper.size` at
    ``velocity`` [m/s] and ``field`` (SI unit of the control), each figure in the unit of the current unit system.

    ``units`` fixes the unit of a kind (``{"force": "kN"}``): a report shows every force in one unit
    (:func:`report_units`); the other kinds get the unit :func:`pick_unit` chooses for the value.

    Row keys: ``velocity``, ``field``, ``force``, ``zero_field_force``, ``dynamic_range``, ``pressure_drop``,
    ``yield_force``, ``damping_constant``, ``reynolds``, ``plug_fraction``, ``flow_rate``, ``piston_area``.
    """
    fluid = damper.fluid
    r = damper.size(velocity=Q_(velocity, "m/s"), field=Q_(field, fluid.control_unit))
    fixed = dict(units or {})

    def q(key: str, label: str, value: Any, kind: str, note: str = "") -> Row:
        unit = fixed.get(kind) or pick_unit(value, kind)
        return Row(key, label, show(value, unit, name=label), note)

    dyn = float("nan") if r.dynamic_range is None else r.dynamic_range
    c_note = "Makris eq 15, zero field" if damper.geometry.configuration == "valve" else "Newtonian mixed mode"
    return (
        q("velocity", "design velocity v", r.velocity, "velocity"),
        Row("field", control_label(fluid.control, "design"), show(r.field, fluid.field_unit, name="design control")),
        q(
            "force",
            "force F",
            r.force,
            "force",
            "quasi-steady force at the design velocity and control, with the seal friction (Makris eq 14)",
        ),
        q("zero_field_force", "zero-field force F(0)", r.zero_field_force, "force"),
        Row("dynamic_range", "dynamic range F(E)/F(0)", show(dyn, "", name="dynamic range")),
        q("pressure_drop", "pressure drop Δp", r.pressure_drop, "pressure"),
        q("yield_force", "yield force Fy", r.yield_force, "force", "controllable force of the fluid"),
        q("damping_constant", "damping constant C", r.damping_constant, "damping", c_note),
        Row(
            "reynolds",
            "Reynolds number Re",
            show(r.reynolds, "", name="Reynolds number"),
            "Makris eq 1; laminar below 2300",
        ),
        Row(
            "plug_fraction",
            "plug fraction",
            show(r.plug_fraction, "", name="plug fraction"),
            "plug thickness over gap: 1 = blocked",
        ),
        q("flow_rate", "flow rate Q", r.flow_rate, "flow", "volume the piston displaces per second"),
        q("piston_area", "piston area A_p", r.piston_area, "area"),
    )


def report_units(curves: ForceVelocityCurves) -> dict[str, str]:
    """The one unit of each force and pressure a report prints (design point, tables, comparison), chosen from the
    largest of its force-velocity curves (:func:`pick_unit`), so that one quantity never reads 190.8 N in one
    section and 0.1908 kN in another.

    >>> from erdesign import load_example
    >>> from erdesign.damper.curves import force_velocity_curves
    >>> report_units(force_velocity_curves(load_example("makris"), np.linspace(0, 0.05, 11), [0.0, 3e6]))
    {'force': 'kN', 'pressure': 'MPa'}
    """
    return {
        "force": pick_unit(Q_(np.asarray(curves.force), "N"), "force"),
        "pressure": pick_unit(Q_(np.asarray(curves.pressure_drop), "Pa"), "pressure"),
    }


def magnetic_section(damper: Damper, currents: np.ndarray) -> dict | None:
    """The magnetic section of a damper with a ``[coil]`` (None without one): rows at the rated current and a table
    at each control [A].  Every number comes from :meth:`erdesign.magnetics.api.MagneticCircuit.at`."""
    law = damper.fluid.field_law
    circuit = getattr(law, "circuit", None)
    if circuit is None or not hasattr(circuit, "at"):
        return None
    I_r = law.rated_current
    r = circuit.at(I_r)
    head = circuit.head
    knees = {k: v for k, v in r.part_knee_currents.items() if math.isfinite(v.m_as("A"))}
    first = min(knees, key=lambda k: knees[k].m_as("A")) if knees else None
    rows = [
        Row("coil_turns", "turns N", show(float(head.turns), "", name="turns")),
        Row("wire_diameter", "wire diameter (bare copper)", show(Q_(head.wire_diameter, "m"), "mm", name="wire")),
        Row(
            "fill_factor",
            "copper fill factor",
            show(head.fill_factor, "", name="fill factor"),
            "round wire: 0.5-0.7 in practice, 0.907 at most",
        ),
        Row(
            "coil_resistance",
            "coil resistance R (20 °C)",
            show(r.coil_resistance, "ohm", name="resistance"),
            "IACS copper, mean turn length",
        ),
        Row("rated_current", "rated current I (reference field)", show(r.current, "A", name="rated current")),
        Row("gap_flux_density", "gap flux density B_g at I", show(r.gap_flux_density, "T", name="B_g")),
        Row("gap_field", "gap field H_g at I", show(r.gap_field, "kA/m", name="H_g")),
        Row(
            "yield_stress_rated",
            "yield stress τ_y at I",
            show(r.yield_stress, pick_unit(r.yield_stress, "pressure"), name="yield stress"),
            "the fluid's yield curve at H_g",
        ),
        Row("inductance", "inductance L = λ/I at I", show(r.inductance, "mH", name="inductance")),
        Row(
            "time_constant",
            "time constant L/R at I",
            show(r.time_constant, "ms", name="time constant"),
            "prior of the field_lag effect",
        ),
        Row(
            "response_time",
            "current rise time to 63 % (driver)",
            show(Q_(law.response_time(), "s"), "ms", name="rise time"),
            "L/R without a driver; with coil.supply_voltage, the forced rise",
        ),
        Row("power", "coil power I²R at I", show(r.power, "W", name="power")),
        Row("voltage", "coil voltage IR at I", show(r.voltage, "V", name="voltage")),
        Row(
            "current_density",
            "current density at I",
            show(r.current_density, "A/mm^2", name="current density"),
            "a coil without forced cooling: about 5 A/mm² or less",
        ),
        Row("knee_current", "knee of B_g(I) (slope halved)", show(r.knee_current, "A", name="knee")),
    ]
    if first is not None:
        rows.append(
            Row(
                "limiting_part",
                f"current at which the {first.replace('_', ' ')} saturates first",
                show(knees[first], "A", name="knee of the part"),
                f"{first}: the part that reaches the knee of its B-H curve at the lowest current",
            )
        )
    rows += [
        Row(
            "leakage_fraction",
            "leakage: core flux not crossing the gap at I",
            show(float(r.leakage_fraction), "percent", name="leakage"),
        ),
    ]
    at = circuit.at(np.asarray(currents, dtype=float))
    tau_unit = pick_unit(at.yield_stress, "pressure")  # one unit for the column, the unit system's
    columns = (
        "current I [A]",
        "B_g [T]",
        "H_g [kA/m]",
        f"τ_y [{tau_unit}]",
        "L [mH]",
        "L/R [ms]",
        "power [W]",
        "saturated",
    )
    table_rows = []
    for i in range(np.size(at.current.magnitude)):
        table_rows.append(
            (
                show(at.current[i], "A", name="current"),
                show(at.gap_flux_density[i], "T", name="B_g"),
                show(at.gap_field[i], "kA/m", name="H_g"),
                show(at.yield_stress[i], tau_unit, name="yield stress"),
                show(at.inductance[i], "mH", name="inductance"),
                show(at.time_constant[i], "ms", name="L/R"),
                show(at.power[i], "W", name="power"),
                Shown(
                    "yes" if at.saturated[i] else "no",
                    "yes" if at.saturated[i] else "no",
                    "",
                    float(at.saturated[i]),
                    "dimensionless",
                ),
            )
        )
    return {
        "rows": tuple(rows),
        "table": Table("magnetics", columns, tuple(table_rows)),
        "saturated": bool(r.saturated),
        "limiting_part": first,
        "steel": getattr(circuit.steel, "name", ""),
        "fluid": getattr(circuit.fluid, "name", ""),
    }


def tolerance_figures(
    damper: Damper, tolerances: Sequence[Any], velocity: float, field: float, samples: int = 10000
) -> list[FigureSpec]:
    """The histogram of the force and the tornado chart of its Sobol indices under ``tolerances`` at a design point
    (:func:`erdesign.campaign.tolerance.tolerance_study`, seed 0), with the quantiles of every output as the
    table."""
    from ..campaign.tolerance import OUTPUTS, tolerance_study
    from . import plots

    r = tolerance_study(damper, tolerances, velocity=float(velocity), field=float(field), samples=int(samples))
    caption = (
        f"{r.count} samples, "
        + "; ".join(v.describe() for v in r.study.variations)
        + (f"; {r.rejected} non-physical draws drawn again" if r.rejected else "")
    )
    columns, units = ["quantile [%]"], {}
    for key in OUTPUTS:
        name, _, si_unit, kind = plots.TOLERANCE_OUTPUTS[key]
        values = Q_(np.array([r.quantiles[key][q] for q in ("1", "99")]), si_unit)
        units[key] = pick_unit(values, kind) if kind else ""
        columns.append(f"{name} [{Q_(1.0, units[key]).units:~P}]" if units[key] else name)
    table = Table(
        "tolerance",
        tuple(columns),
        tuple(
            (
                show(float(q), "", name="quantile"),
                *(
                    show(Q_(r.quantiles[key][q], plots.TOLERANCE_OUTPUTS[key][2]), units[key], name=key)
                    for key in OUTPUTS
                ),
            )
            for q in ("1", "5", "50", "95", "99")
        ),
    )
    force = {k: s for k, s in r.sensitivity["force_N"].items() if s["first"] is not None}
    sobol = (
        Table(
            "tornado",
            tuple(f"{index} {name}" for name in force for index in ("S1", "ST")),
            (
                tuple(
                    show(float(s[index]), "", name=f"{index} {name}")
                    for name, s in force.items()
                    for index in ("first", "total")
                ),
            ),
        )
        if force
        else None
    )
    return [
        FigureSpec(
            "tolerance", "Spread of the force under tolerances", plots.tolerance_histogram_figure(r), table, caption
        ),
        FigureSpec(
            "tornado",
            "What drives the spread of the force (Sobol indices)",
            plots.sensitivity_tornado_figure(r),
            sobol,
            f"first-order and total Sobol indices of the force, {r.sobol_base} base samples (docs/tolerance.md)",
        ),
    ]


def build_report(
    source: str | Path | Damper | Mapping[str, Any],
    *,
    velocity_range: Sequence[Any] | None = None,
    fields: Sequence[Any] | None = None,
    amplitude: Any = None,
    frequency: Any = None,
    comparison: MeasurementComparison | None = None,
    history: Iterable[Any] | None = None,
    title: str | None = None,
    design_velocity: Any = None,
    design_field: Any = None,
    origin: str | None = None,
    baseline: Report | None = None,
    tolerances: Sequence[Any] = (),
    tolerance_samples: int = 10000,
) -> Report:
    """The content of an engineering report on a damper.

    Parameters
    ----------
    source : path, Damper or mapping
        A damper file (its values are shown as given and in SI), the content of one as a mapping (the app's design:
        values as typed), or a :class:`~erdesign.Damper`.
    velocity_range : (velocity, velocity), optional
        Lowest and highest piston velocity of the curves (quantities or strings, ``("0 mm/s", "50 mm/s")``).
        Default in the module notes.
    fields : sequence of controls, optional
        Controls to evaluate (quantities or strings of the fluid's kind); zero is added.  Default: 0, 1/3, 2/3, 1
        times the reference field.
    amplitude, frequency : quantity or str, optional
        The sine of the loops.  Default amplitude 10 mm and a frequency that gives the top velocity as peak.
    comparison : MeasurementComparison, optional
    history : iterable of ErrorHistoryStep or (step, effect, esr), optional
        Render the optional measurement section.
    title : str, optional
    design_velocity, design_field : quantity or str, optional
        The design point (default: the top of the velocity range and the largest control).
    origin : str, optional
        Where the inputs came from, for the inputs table (default ``"damper file"``, ``"Python"`` for a Damper).
    baseline : Report, optional
        The report of a baseline design (built alike, by this function): the report then compares this design
        with it (:func:`with_baseline`: a section and a figure).
    tolerances : sequence of str or Variation, optional
        Tolerances (``"geometry.gap=+-2.5 %"``, :func:`erdesign.campaign.tolerance.parse_variation`): the report then
        shows the spread of the force at the design point and its Sobol indices (:func:`tolerance_figures`).
    tolerance_samples : int
        Monte-Carlo samples of that study (seed 0).

    Returns
    -------
    Report
    """
    from .. import __version__
    from . import plots

    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        if isinstance(source, Damper):
            damper, data, where = source, None, source.name or "damper"
        elif isinstance(source, Mapping):
            data = dict(source)
            where = str(data.get("name") or "design")
            damper = damper_from_dict(data, source=where)
        else:
            data = read_toml(damper_file_path(source))
            damper = damper_from_dict(data, source=str(source))
            where = str(source)
        fluid, g = damper.fluid, damper.geometry
        control = fluid.control_unit

        # --- settings
        v, E, v_design, E_design = report_grid(damper, velocity_range, fields, design_velocity, design_field)
        design_point = design_point_rows(damper, v_design, E_design)
    messages = tuple(
        dict.fromkeys(" ".join(str(w.message).split()) for w in seen if issubclass(w.category, ValidityWarning))
    )
    for w in seen:  # hand the warnings on to the caller, as before
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    v_lo, v_hi = float(v[0]), float(v[-1])
    X0 = positive_si(amplitude if amplitude is not None else DEFAULT_AMPLITUDE, "m", "amplitude")
    f = positive_si(frequency, "Hz", "frequency") if frequency is not None else v_hi / (2 * math.pi * X0)
    if not f > 0:
        raise ErdesignError(
            "frequency: the default makes the peak velocity of the loops the top of the velocity "
            f"range, which is {v_hi:g} m/s; give a positive top velocity or a frequency"
        )

    sweep = force_velocity_curves(damper, v, E)
    loops = sine_loops(damper, X0, f, E)
    units_of = report_units(sweep)
    with warnings.catch_warnings():  # the same design point again, its warnings already taken above
        warnings.simplefilter("ignore")
        design_point = design_point_rows(damper, v_design, E_design, units_of)

    v_unit = pick_unit(Q_(v, "m/s"), "velocity")
    e_unit = fluid.field_unit
    dv_unit = pick_unit(Q_(v_design, "m/s"), "velocity")
    settings = [
        Row("velocity_design", "design velocity v", show(Q_(v_design, "m/s"), dv_unit, name="design velocity")),
        Row(
            "field_design",
            control_label(fluid.control, "design"),
            show(Q_(E_design, control), e_unit, name="design control"),
        ),
        Row("velocity_min", "lowest velocity of the curves", show(Q_(v_lo, "m/s"), v_unit, name="lowest velocity")),
        Row("velocity_max", "highest velocity of the curves", show(Q_(v_hi, "m/s"), v_unit, name="highest velocity")),
        Row("amplitude", "sine amplitude X0", show(Q_(X0, "m"), pick_unit(Q_(X0, "m"), "length"), name="amplitude")),
        Row("frequency", "sine frequency f", show(Q_(f, "Hz"), pick_unit(Q_(f, "Hz"), "frequency"), name="frequency")),
    ] + [Row(f"field_{i}", f"control {i + 1}", show(Q_(e, control), e_unit, name="control")) for i, e in enumerate(E)]

    inputs, record = _inputs(data, damper, origin or "damper file")

    # --- derived quantities
    Ap = Q_(g.piston_area, "m^2")
    C = damper.damping_constant()
    derived = [
        Row("piston_area", "piston area A_p", show(Ap, pick_unit(Ap, "area"), name="piston area"), "geometry"),
        Row("gap_ratio", "gap over mean diameter h/d", show(g.gap_ratio, "", name="h/d")),
        Row(
            "thin_gap_error",
            "thin-gap error of the Newtonian pressure drop",
            show(Q_(g.thin_gap_error, ""), "percent", name="thin-gap error"),
            "Bird, Stewart and Lightfoot eq 2.4-17",
        ),
        Row(
            "active_volume",
            "fluid volume between the electrodes",
            show(
                Q_(g.active_fluid_volume, "m^3"),
                pick_unit(Q_(g.active_fluid_volume, "m^3"), "volume"),
                name="active volume",
            ),
            "Kamath and Wereley (1997), section III.C",
        ),
        Row(
            "damping_constant",
            "damping constant C (zero field)",
            show(C, pick_unit(C, "damping"), name="C"),
            "Makris eq 15" if g.configuration == "valve" else "Newtonian mixed mode",
        ),
        Row(
            "seal_friction",
            "seal friction F_s",
            show(Q_(damper.seal_friction, "N"), units_of["force"], name="seal friction"),
            "Makris eq 14",
        ),
    ]

    # --- design table: the state at the design velocity, one row per control
    s = damper.state(np.full(E.shape, v_design), E)
    s0 = damper.state(v_design, 0.0)
    Fy = np.asarray(damper.yield_force_si(E), dtype=float) * np.ones_like(E)
    units = dict(
        tau=pick_unit(Q_(np.asarray(s.yield_stress), "Pa"), "pressure"),
        eta=pick_unit(Q_(np.asarray(s.viscosity), "Pa*s"), "viscosity"),
        dp=units_of["pressure"],
        F=units_of["force"],
    )

    def u(unit: str) -> str:
        return f"{Q_(1.0, unit).units:~P}"

    columns = (
        f"control [{u(e_unit)}]",
        f"yield stress τ_y [{u(units['tau'])}]",
        f"viscosity η [{u(units['eta'])}]",
        f"pressure drop Δp [{u(units['dp'])}]",
        f"force F [{u(units['F'])}]",
        "dynamic range F/F(0) [-]",
        "Reynolds number Re [-]",
        "plug fraction φ [-]",
        f"yield force F_y [{u(units['F'])}]",
    )
    design_rows = []
    for i, e in enumerate(E):
        dyn = float(s.force[i] / s0.force) if s0.force != 0 else float("nan")
        design_rows.append(
            (
                show(Q_(e, control), e_unit, name="control"),
                show(Q_(s.yield_stress[i], "Pa"), units["tau"], name="yield stress"),
                show(Q_(s.viscosity[i], "Pa*s"), units["eta"], name="viscosity"),
                show(Q_(s.pressure_drop[i], "Pa"), units["dp"], name="pressure drop"),
                show(Q_(s.force[i], "N"), units["F"], name="force"),
                show(dyn, "", name="dynamic range"),
                show(float(s.reynolds[i]), "", name="Reynolds number"),
                show(float(s.plug_fraction[i]), "", name="plug fraction"),
                show(Q_(Fy[i], "N"), units["F"], name="yield force"),
            )
        )
    design_table = Table("design", columns, tuple(design_rows))

    # --- sine table: energy per cycle and equivalent damping per control
    F_peak = Q_(np.array([np.abs(r.force).max() for r in loops.responses]), "N")
    U = Q_(np.array([r.energy_per_cycle for r in loops.responses]), "J")
    Ceq = Q_(np.array([r.equivalent_damping for r in loops.responses]), "N*s/m")
    fu, uu, cu = units_of["force"], pick_unit(U, "energy"), pick_unit(Ceq, "damping")
    sine_table = Table(
        "sine",
        (
            f"control [{u(e_unit)}]",
            f"peak force [{u(fu)}]",
            f"energy per cycle U [{u(uu)}]",
            f"equivalent damping C_eqv [{u(cu)}]",
        ),
        tuple(
            (
                show(Q_(e, control), e_unit, name="control"),
                show(F_peak[i], fu, name="peak force"),
                show(U[i], uu, name="energy per cycle"),
                show(Ceq[i], cu, name="C_eqv"),
            )
            for i, e in enumerate(E)
        ),
    )

    # --- figures
    figures = [
        FigureSpec(
            "pressure_drop",
            "Pressure drop versus velocity",
            plots.pressure_drop_figure(sweep),
            _field_table(
                "pressure_drop", "velocity v", v, "m/s", "velocity", sweep, sweep.pressure_drop, "Pa", "pressure"
            ),
        ),
        FigureSpec(
            "force",
            "Force versus velocity",
            plots.force_velocity_figure(sweep),
            _field_table("force", "velocity v", v, "m/s", "velocity", sweep, sweep.force, "N", "force"),
        ),
        FigureSpec(
            "dynamic_range",
            "Dynamic range versus velocity",
            plots.dynamic_range_figure(sweep),
            _field_table(
                "dynamic_range", "velocity v", v, "m/s", "velocity", sweep, sweep.dynamic_range, "", "", skip_zero=True
            ),
        ),
        FigureSpec(
            "sine_loops",
            "Force-displacement and force-velocity loops",
            plots.sine_loops_figure(loops),
            _loop_table(loops),
            "quasi-steady response to the sine of the settings (energy and C_eqv in the table of section 3)",
        ),
    ]

    if tolerances:
        figures += tolerance_figures(damper, tolerances, v_design, E_design, tolerance_samples)

    comparison_data = None
    steps = _as_history(history)
    if comparison is not None:
        comparison_data = _comparison(comparison, units_of["force"])
        if comparison_data.pop("has_loops"):
            figures.append(
                FigureSpec(
                    "measurement",
                    "Measurement and model",
                    plots.measured_loops_figure(
                        comparison.displacement, comparison.velocity, comparison.force_measured, comparison.force_model
                    ),
                    None,
                )
            )
    if steps:
        floor = None if comparison_data is None else comparison_data["noise_floor"]
        figures.append(
            FigureSpec("history", "Error history", plots.error_history_figure(steps, noise_floor=floor), None)
        )
    magnetics = magnetic_section(damper, E) if control == "A" else None
    if magnetics is not None:
        from ..magnetics.figures import circuit_curves, coil_curves_figure

        rated = fluid.field_law.rated_current
        curves = circuit_curves(damper, points=31)
        figures.insert(
            0,
            FigureSpec(
                "magnetics",
                "Gap flux density and yield stress against coil current",
                coil_curves_figure(curves, rated),
                Table(
                    "magnetics_curve",
                    ("current I [A]", "B_g [T]", f"τ_y [{pick_unit(curves.yield_stress, 'pressure')}]"),
                    tuple(
                        (
                            show(curves.current[i], "A", name="current"),
                            show(curves.gap_flux_density[i], "T", name="B_g"),
                            show(
                                curves.yield_stress[i], pick_unit(curves.yield_stress, "pressure"), name="yield stress"
                            ),
                        )
                        for i in range(0, np.size(curves.current.magnitude), 3)
                    ),
                ),
                "the reluctance network of the piston head (docs/magnetics.md)",
            ),
        )

    notes = [
        (
            f"flow model: {'exact annulus' if damper.uses_exact_annulus else 'thin gap'} "
            f"({g.configuration} configuration{'' if g.ducts == 1 else f', {g.ducts} ducts'})"
        ),
        f"field law: {fluid.yield_law.describe(fluid.field_unit)}",
        "quasi-steady: no fluid inertia, compressibility or pre-yield elasticity",
    ]
    report = Report(
        title=title or f"Damper report: {damper.name or Path(where).stem}",
        source=where,
        generated=datetime.date.today().isoformat(),
        version=__version__,
        configuration=g.configuration,
        notes=tuple(notes),
        settings=tuple(settings),
        inputs=inputs,
        material=_material_section(record, damper),
        derived=tuple(derived),
        design_table=design_table,
        sine_table=sine_table,
        equations=tuple(equations_for(damper)),
        checks=validity_checks(damper, sweep, E, v_design, E_design),
        figures=tuple(figures),
        comparison=comparison_data,
        history=steps,
        sweep=sweep,
        loops=loops,
        design_point=design_point,
        validity_messages=messages,
        magnetics=magnetics,
    )
    return report if baseline is None else with_baseline(report, baseline)


def relative_change(new: Shown | None, old: Shown | None) -> str:
    """The change of ``new`` against ``old`` in percent, ``"+12.3 %"``; empty where it is undefined (a value
    missing, of another unit, not finite, or ``old`` zero).

    >>> relative_change(show(Q_(6.6, "kN"), "kN", name="F"), show(Q_(6.0, "kN"), "kN", name="F"))
    '+10.0 %'
    """
    if (
        new is None
        or old is None
        or new.si_unit != old.si_unit
        or not math.isfinite(new.si)
        or not math.isfinite(old.si)
        or old.si == 0
    ):
        return ""
    return f"{100 * (new.si / old.si - 1):+.1f} %"


def compare_designs(report: Report, baseline: Report) -> dict:
    """This design beside a baseline design (both reports built alike): the inputs that differ, as typed, and the
    design point of both, each with the relative change of this design against the baseline
    (:func:`relative_change`, ``"+12.3 %"``; empty where undefined).

    Both reports' numbers are shown as they are (each :func:`show` of the library's values); nothing is recomputed.
    """

    def key(row: InputRow) -> str:
        return f"{row.section}.{row.key}"

    before = {key(r): r for r in baseline.inputs}
    now = {key(r): r for r in report.inputs}

    def given(rows: dict, k: str) -> str:
        return rows[k].given if k in rows else ""

    inputs = tuple(
        {
            "key": k,
            "baseline": given(before, k),
            "this": given(now, k),
            "change": relative_change(now[k].si if k in now else None, before[k].si if k in before else None),
        }
        for k in dict.fromkeys([*before, *now])
        if given(before, k) != given(now, k)
    )
    rows = []
    old = {r.key: r for r in baseline.design_point}
    for b in report.design_point:
        a = old.get(b.key)
        if a is None:
            continue
        rows.append(
            {
                "key": b.key,
                "label": b.label,
                "baseline": a.value,
                "this": b.value,
                "change": relative_change(b.value, a.value),
            }
        )
    name = baseline.title.removeprefix("Damper report: ")
    return {"name": name, "inputs": inputs, "rows": tuple(rows)}


def with_baseline(report: Report, baseline: Report) -> Report:
    """``report`` with the comparison against ``baseline`` (:func:`compare_designs`) and the figure of both designs'
    force against velocity (this design solid, the baseline dashed) among its figures."""
    from . import plots

    b = baseline.sweep
    figure = FigureSpec(
        "baseline",
        "Force versus velocity: this design and the baseline",
        plots.force_velocity_figure(report.sweep, baseline=b),
        _field_table("baseline", "velocity v", b.velocity, "m/s", "velocity", b, b.force, "N", "force"),
        "the baseline's curves in the table; this design's in the figure 'Force versus velocity'",
    )
    return dataclasses.replace(report, baseline=compare_designs(report, baseline), figures=report.figures + (figure,))


def _comparison(c: MeasurementComparison, force_unit: str | None = None) -> dict:
    """Shown values of a measurement comparison (dimension-checked)."""
    if not (isinstance(c.esr, (int, float)) and math.isfinite(c.esr) and c.esr >= 0):
        raise ErdesignError(f"comparison.esr: expected a finite number >= 0, got {c.esr!r}")
    rows = [Row("esr", "ESR (Vivas-López et al., eq 7)", esr_shown(c.esr, name="comparison.esr"))]
    if c.noise_floor_esr is not None:
        rows.append(
            Row(
                "noise_floor_esr",
                "noise floor ESR (the same samples)",
                esr_shown(c.noise_floor_esr, name="comparison.noise_floor_esr"),
            )
        )
    if c.samples is not None:
        rows.append(Row("samples", "samples judged (ESR and RMS on these)", show(float(c.samples), "", name="samples")))
    for key, label, value in (
        ("rms_error", "RMS force error", c.rms_error),
        ("peak_force_measured", "peak force, measured", c.peak_force_measured),
        ("peak_force_model", "peak force, model", c.peak_force_model),
    ):
        if value is not None:
            q = parse_quantity(value, f"comparison.{key}") if isinstance(value, str) else value
            rows.append(Row(key, label, show(q, force_unit or pick_unit(q, "force"), name=f"comparison.{key}")))
    arrays = (c.displacement, c.velocity, c.force_measured, c.force_model)
    if any(a is not None for a in arrays) and not all(a is not None for a in arrays):
        raise ErdesignError("comparison: give displacement, velocity, force_measured and force_model together")
    if c.verdict and c.verdict not in VERDICTS:
        raise ErdesignError(f"comparison.verdict: expected one of {', '.join(VERDICTS)}, got {c.verdict!r}")
    return {
        "label": c.label,
        "rows": tuple(rows),
        "notes": c.notes,
        "has_loops": all(a is not None for a in arrays),
        "verdict": VERDICTS.get(c.verdict, ""),
        "reason": c.reason,
        "parameters": tuple(c.parameters),
        "statistics": tuple(c.statistics),
        "correlations": tuple(c.correlations),
        "noise_floor": c.noise_floor_esr,
    }


#: The diagnosis' verdicts (docs/cli.md) as the report words them.
VERDICTS = {
    "missing_effect": "a missing effect",
    "nothing_missing": "nothing missing (the residual is at the noise floor)",
    "unexplained": "unexplained (the residual stays above the noise floor and no effect of the library explains it)",
}
