"""``erdesign examples [--json]``: the bundled example dampers, whose names work wherever a damper file is asked
for (``erdesign size makris --velocity "0.1 m/s"``), and the bundled requirements (``erdesign design
makris_requirements``)."""

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
  erdesign design makris_requirements --write-damper 1 best.toml
"""


@cli.command("examples", epilog=_EXAMPLES)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a table.")
def examples_command(as_json: bool) -> None:
    """List the bundled example dampers and requirements; their names work wherever such a file is asked for."""
    from ..design import example_requirements_names, load_example_requirements

    items = []
    for name in example_names():
        damper = load_example(name)
        items.append(
            {
                "name": name,
                "title": damper.name,
                "configuration": damper.geometry.configuration,
                "source": f"examples/{name}.toml",
            }
        )
    requirements = []
    for name in example_requirements_names():
        req = load_example_requirements(name)
        requirements.append(
            {
                "name": name,
                "title": req.name,
                "configuration": req.configuration,
                "source": f"examples/requirements/{name}.toml",
            }
        )
    if as_json:
        emit_json({"examples": items, "requirements": requirements})
        return
    width = max(len(i["name"]) for i in items + requirements)
    for i in items:
        click.echo(f"{i['name']:<{width}}  {i['configuration']:<6} {i['title']}")
    click.echo("requirements (erdesign design NAME):")
    for i in requirements:
        click.echo(f"{i['name']:<{width}}  {i['configuration']:<6} {i['title']}")
