"""``erdesign models [--json]``: the registry of damper models (docs/cli.md)."""

from __future__ import annotations

import click

from ..models.registry import describe_models
from .main import cli, emit_json

__all__ = ["models"]


_EXAMPLES = """
\b
Examples:
  erdesign models
  erdesign models --json
"""


@cli.command(epilog=_EXAMPLES)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a table.")
def models(as_json: bool) -> None:
    """List the damper models with their sources and parameters."""
    entries = describe_models()
    if as_json:
        emit_json({"models": entries})
        return
    width = max(len(e["name"]) for e in entries)
    for e in entries:
        params = ", ".join(f"{p['name']} [{p['unit'] or '-'}]" for p in e["parameters"]) or "(from the damper file)"
        click.echo(f"{e['name']:<{width}}  {e['source']}\n{'':<{width}}  {params}")
