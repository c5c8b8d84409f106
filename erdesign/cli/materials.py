"""``erdesign materials [--json]``: the fluids of the materials database, with their laws and ranges."""

from __future__ import annotations

import click

from .. import materials as _materials
from .main import cli, emit_json

__all__ = ["materials_command"]


_EXAMPLES = """
\b
Examples:
  erdesign materials
  erdesign materials --json
"""


@cli.command("materials", epilog=_EXAMPLES)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a table.")
def materials_command(as_json: bool) -> None:
    """List the fluids of the materials database (name it in a damper file: material = "...")."""
    items = [_materials.summary(name) for name in _materials.names()]
    if as_json:
        emit_json({"materials": items})
        return
    width = max(len(m["name"]) for m in items)
    for m in items:
        fluid = m["fluid"]
        law = m["yield_curve"]["description"] if m["yield_curve"] else (f"power law, n = {fluid['yield_exponent']}")
        field = m["range"].get("field")
        click.echo(
            f"{m['name']:<{width}}  {m['kind']}  tau_y {fluid['yield_stress']} at {fluid['reference_field']}"
            f", eta {fluid['viscosity']}, rho {fluid['density']}"
        )
        click.echo(f"{'':<{width}}      {law}; range " + (f"{field[0]} to {field[1]}" if field else "not stated"))
