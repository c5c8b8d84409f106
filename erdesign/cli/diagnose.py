"""``erdesign diagnose MEASUREMENT.csv --damper DAMPER.toml [--effects a,b] [--json]``: find the missing effect."""

from __future__ import annotations

import shlex

import click

from ..damper.files import load_damper
from ..data.measurement import check_against_damper, read_measurement
from ..diagnosis.diagnose import diagnose as run_diagnosis
from .main import cli, emit_json

__all__ = ["diagnose", "next_command"]

_EXAMPLES = """
\b
Examples:
  erdesign diagnose test.csv --damper makris.toml
  erdesign diagnose test.csv --damper makris.toml --effects seal_friction
  erdesign diagnose test.csv --damper makris.toml --json > diagnosis.json
"""


def next_command(measurement: str, damper_file: str, effects: list[str] | tuple[str, ...], verdict: str,
                 named: tuple[str, ...]) -> str | None:
    """The command that adds the effect(s) the diagnosis named and diagnoses again, or None when nothing is named.

    >>> next_command("my test.csv", "d.toml", [], "missing_effect", ("seal_friction",))
    "erdesign diagnose 'my test.csv' --damper d.toml --effects seal_friction"
    >>> next_command("t.csv", "d.toml", ["seal_friction"], "nothing_missing", ())
    """
    if verdict != "missing_effect" or not named:
        return None
    chosen = list(dict.fromkeys([*effects, *named]))
    return (f"erdesign diagnose {shlex.quote(measurement)} --damper {shlex.quote(damper_file)} "
            f"--effects {shlex.quote(','.join(chosen))}")


@cli.command(epilog=_EXAMPLES)
@click.argument("measurement", metavar="MEASUREMENT.csv")
@click.option("--damper", "damper_file", required=True, metavar="DAMPER.toml", help="Damper file (geometry, fluid).")
@click.option("--effects", default="", help="Effects already in the model, comma separated.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a report.")
def diagnose(measurement: str, damper_file: str, effects: str, as_json: bool) -> None:
    """Calibrate the physics baseline, show where it fails and rank the effects that could be missing.

    The verdict is a missing effect, nothing missing (the residual is at the noise floor) or unexplained (no
    effect of the library explains the residual); each is a result, not an error, so the exit code is 0.  After a
    missing effect the report ends with the command that adds it and diagnoses again.
    """
    damper = load_damper(damper_file)
    record = read_measurement(measurement)
    check_against_damper(record, damper)  # issue 15: a unit mistake is named before a fit absorbs it
    result = run_diagnosis(damper, record, effects)
    if as_json:
        emit_json(result.as_json())
        return
    click.echo(result.report())
    named = tuple(result.pair) or ((result.missing_effect,) if result.missing_effect else ())
    given = [e.strip() for e in effects.split(",") if e.strip()]
    command = next_command(measurement, damper_file, given, result.verdict, named)
    if command:
        click.echo(f"\nnext: add {' and '.join(named)} and diagnose again:\n  {command}")
