"""``erdesign identify MEASUREMENT.csv --model NAME [--damper DAMPER.toml] [--json]`` (CONTRACTS.md section 3)."""

from __future__ import annotations

import click

from ..fluid import CONTROL_UNITS
from ..identify import identify as identify_model
from ..measurement import read_measurement
from ..models.registry import get_model
from ..units import Q_, format_quantity
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
    # Field-dependent models work with the dimensionless control u = control / reference; the parameters that
    # multiply u (slopes) are per unit u, so the reference is part of their meaning and is reported with them.
    reference = None
    if model.uses_control and record.control_kind is not None and model_name != "physics":
        reference = format_quantity(Q_(model.control_reference, CONTROL_UNITS[record.control_kind]).to_compact())
    if as_json:
        # Exactly the contract's keys; the control reference follows a documented rule (docs/models.md: the power
        # of ten at or below the record's largest |control|) and is printed in the readable report.
        emit_json({"model": model_name, "esr": json_number(result.esr),
                   "parameters": result.parameters_with_units()})
        return
    click.echo(result.report())
    if reference is not None:
        click.echo(f"  control: u = {record.control_kind} / {reference}; coefficients that multiply u (or u^2) "
                   "are per unit u (per u^2)")
