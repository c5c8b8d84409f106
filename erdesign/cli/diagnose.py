"""``erdesign diagnose M1.csv [M2.csv ...] --damper DAMPER.toml [--effects a,b] [--exclude-clipped] [--force-noise F]
[--json]``: find the missing effect (several records of one damper are calibrated together)."""

from __future__ import annotations

import shlex
from typing import Sequence

import click

from ..damper.files import load_damper
from ..data.measurement import WARNED_AT_READ, read_for_damper
from ..diagnosis.diagnose import diagnose as run_diagnosis
from .main import cli, emit_json, exclude_clipped_option, executor_options

__all__ = ["diagnose", "next_command", "force_noise_option"]


def force_noise_option(text: str | None):
    """``--force-noise``: a force with its unit (``"5 N"``), positive; None when not given."""
    if text is None:
        return None
    from ..units import to_si

    value = to_si(text, "N", "--force-noise")
    if not value > 0:
        raise click.BadParameter(f"must be a positive force, got {text!r}", param_hint="--force-noise")
    return value


_EXAMPLES = """
\b
Examples:
  erdesign diagnose test.csv --damper makris.toml
  erdesign diagnose test.csv --damper makris.toml --effects seal_friction
  erdesign diagnose test.csv --damper makris.toml --json > diagnosis.json
  erdesign diagnose 10mm1Hz.csv 25mm0.5Hz.csv --damper my_damper.toml --force-noise "5 N"
"""


def next_command(
    measurement: str | Sequence[str],
    damper_file: str,
    effects: list[str] | tuple[str, ...],
    verdict: str,
    named: tuple[str, ...],
    options: Sequence[str] = (),
) -> str | None:
    """The command that adds the effect(s) the diagnosis named and diagnoses again, or None when nothing is named.

    >>> next_command("my test.csv", "d.toml", [], "missing_effect", ("seal_friction",))
    "erdesign diagnose 'my test.csv' --damper d.toml --effects seal_friction"
    >>> next_command("t.csv", "d.toml", ["seal_friction"], "nothing_missing", ())
    >>> next_command(["a.csv", "b.csv"], "d.toml", [], "missing_effect", ("field_lag", "leakage"), ["--exclude-clipped"])
    'erdesign diagnose a.csv b.csv --damper d.toml --effects field_lag,leakage --exclude-clipped'
    """
    if verdict != "missing_effect" or not named:
        return None
    chosen = list(dict.fromkeys([*effects, *named]))
    files = [measurement] if isinstance(measurement, str) else list(measurement)
    return " ".join(
        [
            "erdesign diagnose",
            *map(shlex.quote, files),
            "--damper",
            shlex.quote(damper_file),
            "--effects",
            shlex.quote(",".join(chosen)),
            *map(shlex.quote, options),
        ]
    )


@cli.command(epilog=_EXAMPLES)
@click.argument("measurements", metavar="MEASUREMENT.csv...", nargs=-1, required=True)
@click.option("--damper", "damper_file", required=True, metavar="DAMPER.toml", help="Damper file (geometry, fluid).")
@click.option("--effects", default="", help="Effects already in the model, comma separated.")
@exclude_clipped_option
@click.option(
    "--force-noise",
    default=None,
    metavar="F",
    help='The load cell\'s noise when known, e.g. "5 N" (otherwise estimated from the record).',
)
@executor_options(default_jobs="1")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a report.")
def diagnose(
    measurements: tuple[str, ...],
    damper_file: str,
    effects: str,
    exclude_clipped: bool,
    force_noise: str | None,
    executor: dict,
    as_json: bool,
) -> None:
    """Calibrate the physics baseline, show where it fails and rank the effects that could be missing.

    The verdict is a missing effect, nothing missing (the residual is at the noise floor) or unexplained (no
    effect of the library explains the residual); each is a result, not an error, so the exit code is 0.  After a
    missing effect the report ends with the command that adds it and diagnoses again.
    """
    damper = load_damper(damper_file)
    records = read_for_damper(measurements, damper)
    result = run_diagnosis(
        damper,
        records,
        effects,
        exclude_clipped=True if exclude_clipped else None,
        force_noise=force_noise_option(force_noise),
        **executor,
    )
    if as_json:
        emit_json(result.as_json())
        return
    click.echo(result.report(said=WARNED_AT_READ))
    named = tuple(result.missing_effects)
    given = [e.strip() for e in effects.split(",") if e.strip()]
    options = (["--exclude-clipped"] if exclude_clipped else []) + (
        ["--force-noise", force_noise] if force_noise else []
    )
    command = next_command(list(measurements), damper_file, given, result.verdict, named, options)
    if command:
        click.echo(f"\nnext: add {' and '.join(named)} and diagnose again:\n  {command}")
