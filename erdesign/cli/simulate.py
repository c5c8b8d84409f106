"""``erdesign simulate MEASUREMENT.csv --model NAME --params P [--json] [--out forces.csv]`` (docs/cli.md).

Runs a model with given parameters on a record's motion and control and scores it.  P is a JSON file written by
``erdesign identify --json``, a list ``"name=value unit, ..."`` or a published set of the model (``spencer1997``).
"""

from __future__ import annotations

import click

from .main import as_flags, cli, emit_json, json_number

__all__ = ["simulate"]


_EXAMPLES = """
\b
Examples:
  erdesign simulate ransim_u.csv --model bouc_wen_modified --params spencer1997
  erdesign simulate REC.csv --model bingham --params fitted.json --out forces.csv
  erdesign simulate REC.csv --model physics --damper examples/makris.toml \
      --params "viscosity_factor=1.1, yield_stress_factor=0.9"
"""


@cli.command(epilog=_EXAMPLES)
@click.argument("measurement_file", metavar="MEASUREMENT.csv")
@click.option("--model", "model_name", required=True, help="Registry name (see 'erdesign models').")
@click.option("--params", "params", required=True, metavar="P",
              help="identify --json output file, \"name=value unit, ...\", or a published set (e.g. spencer1997).")
@click.option("--damper", default=None, metavar="DAMPER.toml", help="Damper file, for --model physics.")
@click.option("--effects", default="", help="Comma-separated effects, for --model physics.")
@click.option("--control-reference", default=None, metavar="Q",
              help="Control that maps to u = 1 for per-unit coefficients given without a control unit "
                   "(default: the rule identify uses, a power of ten near the record's largest |control|).")
@click.option("--exclude-clipped", is_flag=True, help="Score without the force samples at a flat top or bottom.")
@click.option("--out", default=None, metavar="FORCES.csv",
              help="Write the simulated force as a measurement CSV (motion, control and the model's force).")
@click.option("--force", "overwrite", is_flag=True, help="Let --out replace an existing file.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a report.")
def simulate(measurement_file: str, model_name: str, params: str, damper: str | None, effects: str,
             control_reference: str | None, exclude_clipped: bool, out: str | None, overwrite: bool,
             as_json: bool) -> None:
    """Run a model with given parameters on a measurement and score it (ESR and more)."""
    from pathlib import Path

    from ..data.measurement import read_measurement, write_measurement
    from ..errors import ErdesignError
    from ..identification.identify import resolve_parameters
    from ..identification.identify import simulate as run_model
    from ..models.registry import get_model

    from .._util import check_output_path

    if out is not None:
        out, _ = check_output_path(out, force=overwrite, formats={".csv": "csv"},
                                   inputs={"the measurement file": measurement_file,
                                                   "the parameter file": params if Path(params).exists() else None})
    options = {}
    if model_name == "physics":
        if damper is None:
            raise click.UsageError("--model physics needs --damper DAMPER.toml (the damper whose physics is run)")
        options = {"damper": damper, "effects": tuple(e for e in effects.split(",") if e)}
    elif damper is not None or effects:
        raise click.UsageError("--damper and --effects apply to --model physics only")
    model = get_model(model_name, **options)
    record = read_measurement(measurement_file, require_force=False)     # a test plan (erdesign doe) has no force
    try:
        values, source, notes = resolve_parameters(model, params, record, control_reference=control_reference,
                                                   where="--params")
    except ErdesignError as exc:
        raise ErdesignError(as_flags(str(exc))) from None
    sim = run_model(model, record, values, exclude_clipped=exclude_clipped, source=source)
    if out is not None:
        write_measurement(out, record.with_force(sim.force), units={"force": "N"},
                          comment=f"erdesign simulate: model {model_name}, parameters {params}, on "
                                  f"{Path(measurement_file).name}", overwrite=overwrite, option="--out")
    reference = _reference_text(model, record)
    params_text = {name: model.parameter(name).format(v) for name, v in sim.values.items()}
    warnings = [as_flags(w) for w in (*notes, *(sim.warnings or []))]
    if as_json:
        emit_json({"model": model_name, "esr": json_number(sim.metrics["esr"]), "parameters": params_text,
                   "r_squared": json_number(sim.metrics["r_squared"]),
                   "rms_residual_N": json_number(sim.metrics["rms_residual_N"]),
                   "peak_residual_N": json_number(sim.metrics["peak_residual_N"]),
                   "samples": len(record), "samples_scored": sim.metrics["samples_scored"],
                   "clipped_samples": sim.clipped, "excluded_samples": sim.excluded,
                   "parameter_set": {"kind": source.kind, "name": source.label, "source": source.source or None},
                   "control_reference": reference, "parameters_si": {k: float(v) for k, v in sim.values.items()},
                   "warnings": warnings})
        return
    for w in warnings:
        click.echo(f"warning: {w}", err=True)
    m = sim.metrics
    lines = [f"{model.title or model_name} on {record.name} ({len(record)} samples) with {source.label}"
             + (f" ({source.source})" if source.source else ""),
             f"  ESR {m['esr']:.4g}   R^2 {m['r_squared']:.4g}   RMS residual {m['rms_residual_N']:.4g} N   "
             f"peak residual {m['peak_residual_N']:.4g} N"
             + (f"   ({sim.excluded} clipped samples left out)" if sim.excluded else "")
             if m["esr"] is not None else
             f"  no force column (a test plan): peak model force {float(abs(sim.force).max()):.4g} N, not scored"]
    if reference is not None:
        lines.append(f"  control: u = {record.control_kind} / {reference}")
    width = max(len(k) for k in params_text)
    lines += [f"  {k:<{width}}  {v}" for k, v in params_text.items()]
    if out is not None:
        lines.append(f"  simulated force written to {out}")
    click.echo("\n".join(lines))


def _reference_text(model, record) -> str | None:
    if not model.uses_control or record.control_kind is None:
        return None
    from ..fluid import CONTROL_UNITS
    from ..units import Q_, format_quantity
    return format_quantity(Q_(model.control_reference, CONTROL_UNITS[record.control_kind]).to_compact())
