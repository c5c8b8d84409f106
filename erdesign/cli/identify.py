"""``erdesign identify MEASUREMENT.csv --model NAME [--damper DAMPER.toml] [--json]`` (CONTRACTS.md section 3),
with the options of identification at real-data scale: ``--starts``, ``--max-time``, ``--decimate``,
``--exclude-clipped``, ``--validate OTHER.csv`` and progress on stderr."""

from __future__ import annotations

import click

from .main import cli, emit_json

__all__ = ["identify"]


@cli.command()
@click.argument("measurement_file", metavar="MEASUREMENT.csv")
@click.option("--model", "model_name", required=True, help="Registry name (see 'erdesign models').")
@click.option("--damper", default=None, help="Damper file, for --model physics.")
@click.option("--effects", default="", help="Comma-separated effects, for --model physics.")
@click.option("--starts", default=4, show_default=True, type=click.IntRange(1, 100),
              help="Most local starts; the extra ones run only when the first fails.")
@click.option("--max-time", default=None, type=click.FloatRange(min=0.1), metavar="SECONDS",
              help="Stop after this wall time with the best point found so far.")
@click.option("--decimate", default=1, show_default=True, type=click.IntRange(1, 1000), metavar="K",
              help="Fit on every K-th sample only (scores on all samples).")
@click.option("--exclude-clipped", is_flag=True, help="Leave force samples at a flat top or bottom out of the fit.")
@click.option("--validate", "validate", multiple=True, metavar="OTHER.csv",
              help="Score the identified set on another record (repeatable).")
@click.option("--quiet", is_flag=True, help="No progress lines on stderr.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a report.")
def identify(measurement_file: str, model_name: str, damper: str | None, effects: str, starts: int,
             max_time: float | None, decimate: int, exclude_clipped: bool, validate: tuple[str, ...], quiet: bool,
             as_json: bool) -> None:
    """Identify a model's parameters from a measurement (simulation from rest at the first sample)."""
    from ..fluid import CONTROL_UNITS
    from ..identify import fit_report, result_json
    from ..identify import identify as identify_model
    from ..identify import simulate as run_model
    from ..measurement import read_measurement
    from ..models.registry import get_model
    from ..units import Q_, format_quantity

    record = read_measurement(measurement_file)
    others = [read_measurement(p) for p in validate]  # read first: a bad file fails before a long fit
    options = {}
    if model_name == "physics":
        options = {"damper": damper, "effects": tuple(e for e in effects.split(",") if e)}
    elif damper is not None or effects:
        raise click.UsageError("--damper and --effects apply to --model physics only")
    model = get_model(model_name, **options)

    def progress(message: str) -> None:
        if not quiet:
            click.echo(f"identify: {message}", err=True)

    result = identify_model(model, record, starts=starts, max_time=max_time, decimate=decimate,
                            exclude_clipped=exclude_clipped, progress=progress)
    validation = []
    for path, other in zip(validate, others):
        sim = run_model(model, other, result.values, exclude_clipped=exclude_clipped)
        validation.append((path, sim.metrics))
    # Field-dependent models work with the dimensionless control u = control / reference; the parameters that
    # multiply u (slopes) are per unit u, so the reference is part of their meaning and is reported with them
    # (docs/models.md: the power of ten at or below the record's largest |control|).
    reference = None
    if model.uses_control and record.control_kind is not None and model_name != "physics":
        reference = format_quantity(Q_(model.control_reference, CONTROL_UNITS[record.control_kind]).to_compact())
    if as_json:
        emit_json(result_json(result, model_name, reference, validation))
        return
    click.echo(fit_report(result, validation))
    if reference is not None:
        click.echo(f"  control: u = {record.control_kind} / {reference}; coefficients that multiply u (or u^2) "
                   "are per unit u (per u^2)")
