"""``erdesign identify MEASUREMENT.csv --model NAME [--damper DAMPER.toml] [--json]`` (CONTRACTS.md section 3)."""

from __future__ import annotations

import click

from ..identify import identify as identify_model
from ..measurement import read_measurement
from ..models.registry import get_model
from .main import cli, emit_json, json_number

__all__ = ["identify"]


@cli.command()
@click.argument("measurement_file", metavar="MEASUREMENT.csv")
@click.option("--model", "model_name", required=True, help="Registry name (see 'erdesign models').")
@click.option("--damper", default=None, help="Damper file, for --model physics.")
@click.option("--effects", default="", help="Comma-separated effects, for --model physics.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a report.")
def identify(measurement_file: str, model_name: str, damper: str | None, effects: str, as_json: bool) -> None:
    """Identify a model's parameters from a measurement (simulation from rest at the first sample)."""
    record = read_measurement(measurement_file)
    options = {}
    if model_name == "physics":
        options = {"damper": damper, "effects": tuple(e for e in effects.split(",") if e)}
    elif damper is not None or effects:
        raise click.UsageError("--damper and --effects apply to --model physics only")
    model = get_model(model_name, **options)
    result = identify_model(model, record)
    if as_json:
        emit_json({"model": model_name, "esr": json_number(result.esr),
                   "parameters": result.parameters_with_units()})
        return
    click.echo(result.report())
