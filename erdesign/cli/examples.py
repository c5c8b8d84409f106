"""``erdesign examples [--json]``: the bundled example dampers, whose names work wherever a damper file is asked
for (``erdesign size makris --velocity "0.1 m/s"``)."""

from __future__ import annotations

import click

from ..damper.files import example_names, load_example
from .main import cli, emit_json

__all__ = ["examples_command"]

_EXAMPLES = """
\b
Examples:
  erdesign examples
  erdesign diagnose test.csv --damper mr_valve
"""


@cli.command("examples", epilog=_EXAMPLES)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a table.")
def examples_command(as_json: bool) -> None:
    """List the bundled example dampers; their names work wherever a damper file is asked for."""
    items = []
    for name in example_names():
        damper = load_example(name)
        items.append({"name": name, "title": damper.name, "configuration": damper.geometry.configuration,
                      "source": f"examples/{name}.toml"})
    if as_json:
        emit_json({"examples": items})
        return
    width = max(len(i["name"]) for i in items)
    for i in items:
        click.echo(f"{i['name']:<{width}}  {i['configuration']:<6} {i['title']}")
