"""``erdesign simulate MEASUREMENT.csv --model NAME --params P [--json] [--out forces.csv]`` (docs/cli.md).

Runs a model with given parameters on a record's motion and control and scores it.  P is a JSON file written by
``erdesign identify --json``, a list ``"name=value unit, ..."`` or a published set of the model (``spencer1997``).
With ``--motion "sine 10 mm 2 Hz"`` instead of a record, runs it on that generated motion (``--field E``) and reports
the energy per cycle, C_eqv and the energy per unit active fluid volume (:mod:`erdesign.simulation.generated`).
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
  erdesign simulate --model kamath_wereley_4 --params kamath_wereley1997_case2 --motion "sine 1 mm 10 Hz"
  erdesign simulate --model physics --damper kamath_wereley1997 --params "viscosity_factor=1" \
      --motion "sine 1 mm 10 Hz" --field "3 kV/mm"
"""


@cli.command(epilog=_EXAMPLES)
@click.argument("measurement_file", metavar="[MEASUREMENT.csv]", required=False)
@click.option("--model", "model_name", required=True, help="Registry name (see 'erdesign models').")
@click.option(
    "--params",
    "params",
    required=True,
    metavar="P",
    help='identify --json output file, "name=value unit, ...", or a published set (e.g. spencer1997).',
)
@click.option("--damper", default=None, metavar="DAMPER.toml", help="Damper file, for --model physics.")
@click.option("--effects", default="", help="Comma-separated effects, for --model physics.")
@click.option(
    "--control-reference",
    default=None,
    metavar="Q",
    help="Control that maps to u = 1 for per-unit coefficients given without a control unit "
    "(default: the rule identify uses, a power of ten near the record's largest |control|).",
)
@click.option("--exclude-clipped", is_flag=True, help="Score without the force samples at a flat top or bottom.")
@click.option(
    "--motion",
    default=None,
    metavar='"sine X0 f [N cycles]"',
    help='Run on a generated sine instead of a measurement, e.g. "sine 10 mm 2 Hz".',
)
@click.option("--field", default=None, metavar="E", help="Constant control of --motion (default 0).")
@click.option(
    "--active-volume",
    default=None,
    metavar="V",
    help="Active fluid volume for the energy per unit volume of --motion (physics: from the geometry).",
)
@click.option(
    "--out",
    default=None,
    metavar="FORCES.csv",
    help="Write the simulated force as a measurement CSV (motion, control and the model's force).",
)
@click.option("--force", "overwrite", is_flag=True, help="Let --out replace an existing file.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a report.")
def simulate(
    measurement_file: str | None,
    model_name: str,
    params: str,
    damper: str | None,
    effects: str,
    control_reference: str | None,
    exclude_clipped: bool,
    motion: str | None,
    field: str | None,
    active_volume: str | None,
    out: str | None,
    overwrite: bool,
    as_json: bool,
) -> None:
    """Run a model with given parameters on a measurement and score it (ESR and more)."""
    from pathlib import Path

    from ..data.measurement import read_measurement, write_measurement
    from ..errors import ErdesignError
    from ..identification.identify import resolve_parameters
    from ..identification.identify import simulate as run_model
    from ..models.registry import get_model

    from .._util import check_output_path

    if (measurement_file is None) == (motion is None):
        raise click.UsageError('give a MEASUREMENT.csv or --motion "sine X0 f" (one of them)')
    if measurement_file is not None and (field is not None or active_volume is not None):
        raise click.UsageError("--field and --active-volume apply to --motion (a measurement has its own control)")
    if out is not None:
        out, _ = check_output_path(
            out,
            force=overwrite,
            formats={".csv": "csv"},
            inputs={
                "the measurement file": measurement_file,
                "the parameter file": params if Path(params).exists() else None,
            },
        )
    options = {}
    if model_name == "physics":
        if damper is None:
            raise click.UsageError("--model physics needs --damper DAMPER.toml (the damper whose physics is run)")
        options = {"damper": damper, "effects": tuple(e for e in effects.split(",") if e)}
    elif damper is not None or effects:
        raise click.UsageError("--damper and --effects apply to --model physics only")
    model = get_model(model_name, **options)
    if motion is not None:
        _on_motion(model, model_name, params, motion, field, active_volume, control_reference, out, overwrite, as_json)
        return
    record = read_measurement(measurement_file, require_force=False)  # a test plan (erdesign doe) has no force
    try:
        values, source, notes = resolve_parameters(
            model, params, record, control_reference=control_reference, where="--params"
        )
    except ErdesignError as exc:
        raise ErdesignError(as_flags(str(exc))) from None
    sim = run_model(model, record, values, exclude_clipped=exclude_clipped, source=source)
    if out is not None:
        write_measurement(
            out,
            record.with_force(sim.force),
            units={"force": "N"},
            comment=f"erdesign simulate: model {model_name}, parameters {params}, on {Path(measurement_file).name}",
            overwrite=overwrite,
            option="--out",
        )
    reference = _reference_text(model, record)
    params_text = {name: model.parameter(name).format(v) for name, v in sim.values.items()}
    warnings = [as_flags(w) for w in (*notes, *(sim.warnings or []))]
    if as_json:
        emit_json(
            {
                "model": model_name,
                "esr": json_number(sim.metrics["esr"]),
                "parameters": params_text,
                "r_squared": json_number(sim.metrics["r_squared"]),
                "rms_residual_N": json_number(sim.metrics["rms_residual_N"]),
                "peak_residual_N": json_number(sim.metrics["peak_residual_N"]),
                "samples": len(record),
                "samples_scored": sim.metrics["samples_scored"],
                "clipped_samples": sim.clipped,
                "excluded_samples": sim.excluded,
                "parameter_set": {"kind": source.kind, "name": source.label, "source": source.source or None},
                "control_reference": reference,
                "parameters_si": {k: float(v) for k, v in sim.values.items()},
                "warnings": warnings,
            }
        )
        return
    for w in warnings:
        click.echo(f"warning: {w}", err=True)
    m = sim.metrics
    lines = [
        f"{model.title or model_name} on {record.name} ({len(record)} samples) with {source.label}"
        + (f" ({source.source})" if source.source else ""),
        f"  ESR {m['esr']:.4g}   R^2 {m['r_squared']:.4g}   RMS residual {m['rms_residual_N']:.4g} N   "
        f"peak residual {m['peak_residual_N']:.4g} N"
        + (f"   ({sim.excluded} clipped samples left out)" if sim.excluded else "")
        if m["esr"] is not None
        else f"  no force column (a test plan): peak model force {float(abs(sim.force).max()):.4g} N, not scored",
    ]
    if reference is not None:
        lines.append(f"  control: u = {record.control_kind} / {reference}")
    width = max(len(k) for k in params_text)
    lines += [f"  {k:<{width}}  {v}" for k, v in params_text.items()]
    if out is not None:
        lines.append(f"  simulated force written to {out}")
    click.echo("\n".join(lines))


def _on_motion(
    model, model_name, params, motion, field, active_volume, control_reference, out, overwrite, as_json
) -> None:
    """The model on a generated sine: force, energy per cycle, C_eqv, energy per unit active fluid volume."""
    from ..data.measurement import write_measurement
    from ..errors import ErdesignError
    from ..fluid import CONTROL_UNITS, control_kind
    from ..identification.identify import resolve_parameters
    from ..simulation.generated import parse_motion, run_on_motion
    from ..units import Q_, to_si

    kind, level, unit = None, 0.0, None
    if model_name == "physics":
        fluid = model.damper.fluid
        kind, level, unit = fluid.control, fluid.field_si(field, "--field"), fluid.field_unit
    elif field is not None:
        kind = control_kind(field, "--field")
        level = float(to_si(field, CONTROL_UNITS[kind], "--field"))
        unit = f"{Q_(field).units:~P}" if isinstance(field, str) and not _plain(field) else CONTROL_UNITS[kind]
    spec = parse_motion(motion, level, unit)
    from ..data.measurement import Measurement

    m = spec.motion
    probe = Measurement(m.time, m.displacement, None, m.velocity, m.acceleration, m.control, kind, name=m.description)
    try:
        values, source, notes = resolve_parameters(
            model, params, probe, control_reference=control_reference, where="--params"
        )
    except ErdesignError as exc:
        raise ErdesignError(as_flags(str(exc))) from None
    volume = None
    if active_volume is not None:
        volume = float(to_si(active_volume, "m^3", "--active-volume"))
    elif model_name == "physics":
        volume = model.damper.geometry.active_fluid_volume
    run = run_on_motion(model, values, spec, control_kind=kind, active_volume=volume)
    if out is not None:
        write_measurement(
            out,
            run.record,
            units={"force": "N"},
            comment=f"erdesign simulate: model {model_name}, parameters {params}, on {m.description}",
            overwrite=overwrite,
            option="--out",
        )
    warnings = [as_flags(w) for w in notes]
    params_text = {name: model.parameter(name).format(v) for name, v in model.check_values(values).items()}
    if as_json:
        emit_json(
            {
                "model": model_name,
                "motion": m.description,
                "parameters": params_text,
                "parameter_set": {"kind": source.kind, "name": source.label, "source": source.source or None},
                "amplitude_m": run.amplitude,
                "frequency_Hz": run.frequency,
                "samples": len(run.record),
                "peak_force_N": json_number(run.peak_force),
                "energy_per_cycle_J": json_number(run.energy_per_cycle),
                "equivalent_damping_N_s_per_m": json_number(run.equivalent_damping),
                "active_volume_m3": run.active_volume,
                "energy_per_active_volume_J_per_m3": None
                if run.energy_per_active_volume is None
                else json_number(run.energy_per_active_volume),
                "warnings": warnings,
            }
        )
        return
    for w in warnings:
        click.echo(f"warning: {w}", err=True)
    lines = [
        f"{model.title or model_name} on {m.description} with {source.label}"
        + (f" ({source.source})" if source.source else ""),
        (
            f"  peak force {run.peak_force:.4g} N   energy per cycle {run.energy_per_cycle:.4g} J   "
            f"C_eqv {run.equivalent_damping:.4g} N s/m (last cycle; Kamath and Wereley 1997 eqs 1-2)"
        ),
    ]
    if run.energy_per_active_volume is not None:
        lines.append(
            f"  energy per unit active fluid volume {run.energy_per_active_volume / 1e3:.4g} kJ/m^3 "
            f"(active volume {run.active_volume * 1e6:.4g} cm^3; Kamath and Wereley 1997 Fig 6)"
        )
    if out is not None:
        lines.append(f"  motion and simulated force written to {out}")
    click.echo("\n".join(lines))


def _plain(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _reference_text(model, record) -> str | None:
    if not model.uses_control or record.control_kind is None:
        return None
    from ..fluid import CONTROL_UNITS
    from ..units import Q_, format_quantity

    return format_quantity(Q_(model.control_reference, CONTROL_UNITS[record.control_kind]).to_compact())
