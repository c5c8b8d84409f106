"""``erdesign fit M1.csv [M2.csv ...] --damper DAMPER.toml [--effects a,b] [--exclude-clipped] [--json]``: calibrate
the physics damper (several records of one damper together)."""

from __future__ import annotations

import click

from ..damper.files import load_damper
from ..diagnosis.diagnose import calibrate, parameters_at_bounds
from ..data.measurement import WARNED_AT_READ, read_for_damper
from .diagnose import force_noise_option
from .main import cli, emit_json, exclude_clipped_option, json_number

__all__ = ["fit"]


_EXAMPLES = """
\b
Examples:
  erdesign fit examples/measurements/makris_hidden_seal_friction.csv --damper examples/makris.toml
  erdesign fit REC.csv --damper examples/makris.toml --effects seal_friction --json
"""


@cli.command(epilog=_EXAMPLES)
@click.argument("measurements", metavar="MEASUREMENT.csv...", nargs=-1, required=True)
@click.option("--damper", "damper_file", required=True, metavar="DAMPER.toml", help="Damper file (geometry, fluid).")
@click.option("--effects", default="", help="Effects to add to the baseline, comma separated (e.g. seal_friction).")
@exclude_clipped_option
@click.option(
    "--force-noise",
    default=None,
    metavar="F",
    help='The load cell\'s noise when known, e.g. "5 N" (accepted as by diagnose; the fit does not use it).',
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a report.")
def fit(
    measurements: tuple[str, ...],
    damper_file: str,
    effects: str,
    exclude_clipped: bool,
    force_noise: str | None,
    as_json: bool,
) -> None:
    """Calibrate the baseline of the damper (viscosity and yield-stress factors) plus the named effects.

    The fit and its ESR are judged on the samples ``erdesign diagnose`` judges, so both state the same ESR for the
    same effects."""
    damper = load_damper(damper_file)
    records = read_for_damper(measurements, damper)
    force_noise_option(force_noise)
    result = calibrate(damper, records, effects, exclude_clipped=True if exclude_clipped else None)
    for f in result.findings:
        if f.kind not in WARNED_AT_READ:  # those were warned about as the records were read
            click.echo(f"note: {f.kind}: {f.record}: {f.message}", err=True)
    if len(result.records) > 1:
        click.echo(
            "ESR per record: "
            + ", ".join(
                f"{r['name']} {r['esr']:.4g}" if r["esr"] is not None else f"{r['name']} -" for r in result.records
            ),
            err=True,
        )
    at_bounds = parameters_at_bounds(result)
    for text in at_bounds:
        click.echo(f"warning: the fit ends at a bound: {text}; the value is not an estimate", err=True)
    if as_json:
        # exactly the contract's keys (docs/cli.md): the bounds are said on stderr
        emit_json({"esr": json_number(result.esr), "parameters": result.parameters_with_units()})
        return
    click.echo(result.report())
