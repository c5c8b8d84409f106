"""``erdesign diagnose MEASUREMENT.csv --damper DAMPER.toml [--effects a,b] [--json]``: find the missing effect."""

from __future__ import annotations

import click

from ..damper_file import load_damper
from ..diagnose import diagnose as run_diagnosis
from ..measurement import read_measurement
from .main import cli, emit_json

__all__ = ["diagnose"]


@cli.command()
@click.argument("measurement", metavar="MEASUREMENT.csv")
@click.option("--damper", "damper_file", required=True, metavar="DAMPER.toml", help="Damper file (geometry, fluid).")
@click.option("--effects", default="", help="Effects already in the model, comma separated.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a report.")
def diagnose(measurement: str, damper_file: str, effects: str, as_json: bool) -> None:
    """Calibrate the physics baseline, show where it fails and rank the effects that could be missing.

    The verdict is a missing effect, nothing missing (the residual is at the noise floor) or unexplained (no
    effect of the library explains the residual); each is a result, not an error, so the exit code is 0.
    """
    damper = load_damper(damper_file)
    record = read_measurement(measurement)
    result = run_diagnosis(damper, record, effects)
    if as_json:
        emit_json(result.as_json())
        return
    click.echo(result.report())
