"""``erdesign size DAMPER.toml --velocity V [--field E] [--json]``: the quasi-steady design point."""

from __future__ import annotations

import math
import warnings
from typing import Any

import click

from ..damper.files import load_damper
from ..errors import ErdesignWarning, one_line
from ..units import Q_, format_quantity, plain_number
from .main import cli, emit_json, json_number

__all__ = ["size", "quantity_option"]

_EXAMPLES = """
\b
Examples:
  erdesign size makris.toml --velocity "1 in/s" --field "3 kV/mm"
  erdesign size mr_valve.toml --velocity "50 mm/s" --field "200 kA/m" --json
  erdesign size mr_valve_current.toml --velocity "0.1 m/s" --field "1.5 A"
"""


def quantity_option(text: str, si_unit: str, option: str) -> Any:
    """A dimensional command-line value: a quantity string as given, or a bare number read in ``si_unit`` with a
    warning on stderr (a number without its unit is the commonest slip: ``--velocity 25`` meant mm/s).

    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as w:
    ...     warnings.simplefilter("always")
    ...     q = quantity_option("0.0254", "m/s", "--velocity")
    >>> q, str(w[0].message)
    (<Quantity(0.0254, 'meter / second')>, '--velocity 0.0254: a bare number, read as 0.0254 m/s; give the unit, e.g. "0.0254 m/s"')
    """
    value = plain_number(text)
    if value is None:
        return text
    if value != 0 and math.isfinite(value):  # 0 is 0 in any unit; NaN is an error of its own
        unit = f"{Q_(1.0, si_unit).units:~P}"
        warnings.warn(
            f'{option} {text}: a bare number, read as {text} {unit}; give the unit, e.g. "{text} {unit}"',
            ErdesignWarning,
            stacklevel=2,
        )
    return Q_(value, si_unit)


@cli.command(epilog=_EXAMPLES)
@click.argument("damper_file", metavar="DAMPER.toml")
@click.option(
    "--velocity",
    required=True,
    help='Piston velocity with its unit, e.g. "1 in/s" (a bare number is read in m/s, with a warning).',
)
@click.option("--field", default=None, help='Control: field, current or voltage, e.g. "3 kV/mm" (default 0).')
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (SI units) instead of a table.")
def size(damper_file: str, velocity: str, field: str | None, as_json: bool) -> None:
    """Quasi-steady design point of a damper at one piston velocity and control."""
    damper = load_damper(damper_file)
    r = damper.size(
        velocity=quantity_option(velocity, "m/s", "--velocity"),
        field=None if field is None else quantity_option(field, damper.fluid.control_unit, "--field"),
    )
    if as_json:
        out = r.as_json()
        out["dynamic_range"] = json_number(out["dynamic_range"])
        emit_json(out)
        return
    click.echo(_size_table(damper, r))


def _size_table(damper, r) -> str:
    g = damper.geometry

    def q(x, unit=None, digits=4):
        return format_quantity(x.to(unit) if unit else x.to_compact(), None, digits)

    config = f"{g.configuration}, {r.flow_model}, h/d = {r.gap_ratio:.3g}"
    rows = [
        ("piston area A_p", q(r.piston_area, "cm^2")),
        (
            "flow rate Q = v A_p",
            q(r.flow_rate, "mL/s") + (f"  ({q(r.flow_per_duct, 'mL/s')} per duct)" if g.ducts > 1 else ""),
        ),
        ("yield stress / viscosity", f"{q(r.yield_stress, 'kPa')} / {q(r.viscosity, 'Pa*s')}"),
        ("pressure drop", q(r.pressure_drop, "MPa")),
        ("force (with seal friction)", q(r.force)),
        ("zero-field force", q(r.zero_field_force)),
        (
            "dynamic range F(E)/F(0)",
            "undefined (zero-field force is 0)" if r.dynamic_range is None else f"{r.dynamic_range:.4g}",
        ),
        ("yield force of the fluid", q(r.yield_force)),
        ("seal friction", q(r.seal_friction, "N")),
        (
            "damping constant C (eq 15)" if g.configuration == "valve" else "damping constant C (zero field)",
            q(r.damping_constant, "kN*s/m"),
        ),
        ("Reynolds number (eq 1)", f"{r.reynolds:.4g} ({'laminar' if r.laminar else 'NOT laminar: > 2300'})"),
        ("plug fraction", f"{r.plug_fraction:.4g}"),
    ]
    width = max(len(k) for k, _ in rows)
    head = (
        f"{one_line(damper.name or 'damper', 120)} ({config})\n"
        f"at v = {format_quantity(r.velocity.to_compact())}, "
        f"control = {format_quantity(r.field.to(damper.fluid.field_unit))}"
    )
    return head + "\n" + "\n".join(f"  {k:<{width}}  {v}" for k, v in rows)
