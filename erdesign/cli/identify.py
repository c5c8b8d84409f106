"""``erdesign identify MEASUREMENT.csv --model NAME [--damper DAMPER.toml] [--json]`` (docs/cli.md),
with the options of identification at real-data scale: ``--starts``, ``--max-time``, ``--decimate``,
``--exclude-clipped``, ``--validate OTHER.csv``, ``--fix``, progress on stderr; ``--joint`` for one parameter set
from several records; and the Quiroz (2022) files read as they are published (``--format``)."""

from __future__ import annotations

import click

from .main import NumberRange, WholeNumber, as_flags, cli, emit_json

__all__ = ["identify"]


_EXAMPLES = """
\b
Examples:
  erdesign identify REC.csv --model bingham
  erdesign identify ransim_u.csv --model bouc_wen_modified --exclude-clipped --max-time 60
  erdesign identify A.csv B.csv --model bouc_wen_modified --joint --validate C.csv
  erdesign identify REC.csv --model physics --damper examples/makris.toml --effects seal_friction
"""


@cli.command(epilog=_EXAMPLES)
@click.argument("measurement_files", nargs=-1, required=True, metavar="MEASUREMENT.csv...")
@click.option("--model", "model_name", required=True, help="Registry name (see 'erdesign models').")
@click.option("--damper", default=None, help="Damper file, for --model physics.")
@click.option("--effects", default="", help="Comma-separated effects, for --model physics.")
@click.option(
    "--joint",
    is_flag=True,
    help="One parameter set from all the records (e.g. one per coil current); the report gives the ESR of each.",
)
@click.option(
    "--format",
    "fmt",
    default="auto",
    show_default=True,
    type=click.Choice(["auto", "csv", "quiroz", "quiroz-mat"]),
    help="How to read the files: a measurement CSV, a Quiroz (2022) preprocessed sinusoid "
    "<amp>mm<freq>Hz<current>A.txt, or Quiroz's validacion.mat (one record per current); 'auto' "
    "decides by the file.",
)
@click.option(
    "--fix", "fix", default=None, metavar='"name=value unit, ..."', help="Hold these parameters at the values given."
)
@click.option(
    "--starts",
    default=4,
    show_default=True,
    type=WholeNumber(1, 100),
    help="Most local starts; the extra ones run only when the first fails.",
)
@click.option(
    "--max-time",
    default=None,
    type=NumberRange(min=0.1),
    metavar="SECONDS",
    help="Stop after this wall time with the best point found so far.",
)
@click.option(
    "--decimate",
    default=1,
    show_default=True,
    type=WholeNumber(1, 1000),
    metavar="K",
    help="Fit on every K-th sample only (scores on all samples).",
)
@click.option("--exclude-clipped", is_flag=True, help="Leave force samples at a flat top or bottom out of the fit.")
@click.option(
    "--validate",
    "validate",
    multiple=True,
    metavar="OTHER.csv",
    help="Score the identified set on another record (repeatable; read with --format).",
)
@click.option(
    "--projection/--no-projection",
    default=None,
    help="Solve the parameters the force is affine in by linear least squares inside the fit (variable "
    "projection); default: the model's choice (on for all but bouc_wen).",
)
@click.option("--quiet", is_flag=True, help="No progress lines on stderr.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a report.")
def identify(
    measurement_files: tuple[str, ...],
    model_name: str,
    damper: str | None,
    effects: str,
    joint: bool,
    fmt: str,
    fix: str | None,
    starts: int,
    max_time: float | None,
    decimate: int,
    exclude_clipped: bool,
    validate: tuple[str, ...],
    projection: bool | None,
    quiet: bool,
    as_json: bool,
) -> None:
    """Identify a model's parameters from a measurement (simulation from rest at the first sample)."""
    from ..data.readers import read_records
    from ..errors import ErdesignError
    from ..identification.identify import (
        choose_control_reference,
        control_reference_text,
        fit_report,
        identify_joint,
        joint_json,
        joint_report,
        result_json,
    )
    from ..identification.identify import identify as identify_model
    from ..identification.identify import simulate as run_model
    from ..models.published import parse_parameter_list, parse_parameter_values
    from ..models.registry import get_model

    records = [r for path in measurement_files for r in read_records(path, fmt, "MEASUREMENT")]
    others = [r for path in validate for r in read_records(path, fmt, "--validate")]  # bad files fail before a fit
    if len(records) > 1 and not joint:
        raise click.UsageError(
            f"{len(records)} records given ({', '.join(r.name or '?' for r in records[:3])}"
            f"{', ...' if len(records) > 3 else ''}): add --joint for one parameter set from all "
            "of them, or give one record"
        )
    options = {}
    if model_name == "physics":
        if joint:
            raise click.UsageError("--joint applies to the models of the registry, not to --model physics")
        options = {"damper": damper, "effects": tuple(e for e in effects.split(",") if e)}
    elif damper is not None or effects:
        raise click.UsageError("--damper and --effects apply to --model physics only")
    if joint and decimate != 1:
        raise click.UsageError("--decimate applies to a single record, not to --joint")
    model = get_model(model_name, **options)
    kinds = {r.control_kind for r in records}
    if len(kinds) > 1:
        raise click.UsageError(
            f"the records mix control columns ({', '.join(str(k) for k in kinds)}): a joint fit "
            "needs one kind of control"
        )
    kind = records[0].control_kind
    fixed = {}
    if fix:
        choose_control_reference(model, records)
        try:
            fixed = parse_parameter_values(
                model,
                parse_parameter_list(fix, "--fix"),
                control_kind=kind,
                control_reference=model.control_reference,
                where="--fix",
            )
        except ErdesignError as exc:
            message = str(exc)
            raise ErdesignError(message if message.startswith("--fix") else f"--fix: {message}") from None

    def progress(message: str) -> None:
        if not quiet:
            click.echo(f"identify: {message}", err=True)

    if joint:
        result = identify_joint(
            model, records, fixed=fixed, max_time=max_time, exclude_clipped=exclude_clipped, progress=progress
        )
    else:
        result = identify_model(
            model,
            records[0],
            starts=starts,
            max_time=max_time,
            decimate=decimate,
            exclude_clipped=exclude_clipped,
            progress=progress,
            fixed=fixed,
            projection=projection,
        )
    model = result.model  # the fitted copy, with the records' control reference (the caller's model is not changed)
    result.message = as_flags(result.message)
    result.warnings = [as_flags(w) for w in result.warnings]
    validation = [
        (other.name, run_model(model, other, result.values, exclude_clipped=exclude_clipped).metrics)
        for other in others
    ]
    # Field-dependent models work with the dimensionless control u = control / reference; the parameters that
    # multiply u (slopes) are per unit u, so the reference is part of their meaning and is reported with them.
    reference = control_reference_text(model, kind)
    if as_json:
        emit_json((joint_json if joint else result_json)(result, model_name, reference, validation))
        return
    click.echo((joint_report if joint else fit_report)(result, validation))
    if reference is not None:
        click.echo(
            f"  control: u = {kind} / {reference}; coefficients that multiply u (or u^2) are per unit u (per u^2)"
        )
