"""``erdesign magnetics DAMPER.toml --current I [--json]``: the magnetic circuit of an MR damper at coil current(s).

``--current`` takes one current (``"2 A"``, or a number in A) or several separated by commas (``"0.5,1,2 A"`` or
``"0.5 A,1 A,2 A"``).  With one current the JSON holds exactly the keys of docs/file_formats.md, [coil]; with
several, each of those keys holds a list (one value per current; ``coil_resistance_ohm`` and ``limiting_part`` stay
single values) and ``current_A`` lists the currents.
"""

from __future__ import annotations

import click

from ..errors import ErdesignError, one_line
from ..magnetics import load_magnetic_circuit
from ..units import Q_, parse_quantity, plain_number
from .main import cli, emit_json

__all__ = ["magnetics", "parse_currents"]


def parse_currents(text: str) -> list[float]:
    """Currents [A] from ``"2 A"``, ``"2"``, ``"0.5,1,2 A"`` or ``"500 mA, 1 A"``; an error naming --current."""
    parts = [p.strip() for p in text.split(",")]
    if not any(parts):
        raise ErdesignError(f"--current: expected a current such as '2 A', got {text!r}")
    if not all(parts):
        raise ErdesignError(
            f"--current: {text!r} has an empty item (two commas in a row, or one at an end); give "
            "currents separated by commas, e.g. '0.5,1,2 A'"
        )
    unit = None
    last = parts[-1].split()
    if len(last) > 1:
        unit = " ".join(last[1:])
    out = []
    for p in parts:
        number = plain_number(p)
        q = Q_(number, unit or "A") if number is not None else parse_quantity(p, "--current")
        try:
            out.append(float(q.to("A").magnitude))
        except Exception:  # noqa: BLE001
            raise ErdesignError(f"--current: {p!r} is not a current (expected a value in A)") from None
    return out


_EXAMPLES = """
\b
Examples:
  erdesign magnetics examples/mr_coil.toml --current "2 A"
  erdesign magnetics examples/mr_coil.toml --current "0.5 A, 1 A, 2 A" --json
"""


@cli.command(epilog=_EXAMPLES)
@click.argument("damper_file", metavar="DAMPER.toml")
@click.option("--current", required=True, help='Coil current, e.g. "2 A"; several separated by commas: "0.5,1,2 A".')
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (SI units) instead of a table.")
def magnetics(damper_file: str, current: str, as_json: bool) -> None:
    """Magnetic circuit of an MR damper with a [coil]: gap flux density, yield stress, coil R, L, L/R, power."""
    circuit = load_magnetic_circuit(damper_file)
    currents = parse_currents(current)
    report = circuit.at(currents[0] if len(currents) == 1 else currents)
    if as_json:
        emit_json(report.as_json())
        return
    click.echo(_table(circuit, circuit.at(currents)))


def _table(circuit, r) -> str:
    head = circuit.head
    lines = [
        f"{one_line(circuit.name or 'damper', 120)}: {head.turns} turns of {head.wire_diameter * 1e3:.3g} mm copper, "
        f"R = {r.coil_resistance.to('ohm').magnitude:.4g} ohm (20 degC), fill factor {head.fill_factor:.2f}; "
        f"steel {circuit.steel.name}, fluid {circuit.fluid.name}",
        f"gap {head.gap * 1e3:.3g} mm over 2 x {head.pole_length * 1e3:.3g} mm poles; saturates first: "
        f"{r.limiting_part or 'nothing'}"
        + (f" (at {r.part_knee_currents[r.limiting_part].to('A').magnitude:.3g} A)" if r.limiting_part else "")
        + f"; knee of B_gap(I) at {r.knee_current.to('A').magnitude:.3g} A",
        "",
    ]
    cols = ["I [A]", "B_gap [T]", "H_gap [kA/m]", "tau_y [kPa]", "L [H]", "L/R [ms]", "P [W]", "J [A/mm2]", "saturated"]
    rows = []
    for i in range(len(r.current.magnitude)):
        rows.append(
            [
                f"{r.current.magnitude[i]:.4g}",
                f"{r.gap_flux_density.magnitude[i]:.4g}",
                f"{r.gap_field.to('kA/m').magnitude[i]:.4g}",
                f"{r.yield_stress.to('kPa').magnitude[i]:.4g}",
                f"{r.inductance.to('H').magnitude[i]:.4g}",
                f"{r.time_constant.to('ms').magnitude[i]:.4g}",
                f"{r.power.to('W').magnitude[i]:.4g}",
                f"{r.current_density.to('A/mm^2').magnitude[i]:.3g}",
                "yes" if r.saturated[i] else "no",
            ]
        )
    widths = [max(len(c), *(len(row[j]) for row in rows)) for j, c in enumerate(cols)]
    lines.append("  ".join(c.rjust(w) for c, w in zip(cols, widths)))
    lines += ["  ".join(v.rjust(w) for v, w in zip(row, widths)) for row in rows]
    return "\n".join(lines)
