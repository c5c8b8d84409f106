"""``erdesign tolerance DAMPER.toml --vary SPEC ... --velocity V [--field E] --samples N``: quantiles and Sobol
sensitivity of the design point under tolerances (the library is :mod:`erdesign.campaign.tolerance`)."""

from __future__ import annotations

import click

from ..errors import one_line
from .main import SEED, WholeNumber, cli, emit_json, executor_options, json_number
from .size import quantity_option

__all__ = ["tolerance"]

_EXAMPLES = """
\b
Examples:
  erdesign tolerance makris --vary "geometry.gap=0.8 mm +- 0.02 mm" --vary "fluid.viscosity=+-10 %"
      --vary "fluid.yield_stress=+-15 %" --velocity "1 in/s" --field "3 kV/mm" --samples 100000
  erdesign tolerance mr_valve --vary "uniform:geometry.gap=+-20 um" --velocity "0.1 m/s" --field "200 kA/m"
      --samples 1000000 --jobs 2 --json --out samples.parquet
"""

_LABELS = {
    "force_N": ("force", "kN", 1e3),
    "zero_field_force_N": ("zero-field force", "kN", 1e3),
    "dynamic_range": ("dynamic range", "", 1.0),
    "damping_constant_N_s_per_m": ("damping constant", "kN s/m", 1e3),
}


@cli.command(epilog=_EXAMPLES)
@click.argument("damper_file", metavar="DAMPER.toml")
@click.option(
    "--vary",
    "vary",
    multiple=True,
    required=True,
    metavar="SPEC",
    help='A tolerance: "KEY=VALUE +- DELTA" or "KEY=+-P %" (one standard deviation of a normal; prefix '
    '"uniform:" for a uniform spread of half-width DELTA).  Repeat for each value.',
)
@click.option("--velocity", required=True, help='Piston velocity with its unit, e.g. "1 in/s".')
@click.option("--field", default=None, help='Control: field, current or voltage, e.g. "3 kV/mm" (default 0).')
@click.option("--samples", default=100000, show_default=True, type=WholeNumber(), help="Monte-Carlo samples.")
@click.option("--seed", default=0, show_default=True, type=SEED, help="Seed: same seed, same numbers anywhere.")
@click.option(
    "--sobol-samples",
    "sobol_base",
    default=None,
    type=WholeNumber(),
    metavar="N",
    help="Base samples of the Sobol design (default: a power of two near SAMPLES / (inputs + 2)).",
)
@executor_options(default_jobs="all")
@click.option(
    "--out",
    default=None,
    metavar="SAMPLES.parquet",
    help="Write every sample (inputs and outputs, SI) to a .parquet or .csv file.",
)
@click.option("--force", "overwrite", is_flag=True, help="Let --out replace an existing file.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (SI units) instead of a table.")
def tolerance(
    damper_file: str,
    vary: tuple[str, ...],
    velocity: str,
    field: str | None,
    samples: int,
    seed: int,
    sobol_base: int | None,
    executor: dict,
    out: str | None,
    overwrite: bool,
    as_json: bool,
) -> None:
    """Spread of force, zero-field force, dynamic range and damping constant under tolerances, with Sobol indices."""
    from .._util import check_output_path
    from ..campaign.tolerance import (
        SAMPLE_FORMATS,
        parse_variation,
        tolerance_study,
        write_samples,
    )
    from ..damper.files import load_damper
    from ..units import to_si

    if samples < 1:
        raise click.BadParameter(f"must be a whole number >= 1, got {samples}", param_hint="--samples")
    if sobol_base is not None and (sobol_base < 2 or sobol_base & (sobol_base - 1)):
        raise click.BadParameter(f"must be a power of two >= 2, got {sobol_base}", param_hint="--sobol-samples")
    fmt = None
    if out is not None:
        out, fmt = check_output_path(
            out, force=overwrite, formats=SAMPLE_FORMATS, inputs={"the damper file": damper_file}
        )
    damper = load_damper(damper_file)
    variations = [parse_variation(spec, damper) for spec in vary]
    v = to_si(quantity_option(velocity, "m/s", "--velocity"), "m/s", "--velocity")
    E = damper.fluid.field_si(
        None if field is None else quantity_option(field, damper.fluid.control_unit, "--field"), "--field"
    )
    result = tolerance_study(
        damper,
        variations,
        velocity=float(v),
        field=float(E),
        samples=samples,
        seed=seed,
        sobol_base=sobol_base,
        keep_samples=out is not None,
        **executor,
    )
    if out is not None:
        write_samples(result, out, fmt, overwrite=overwrite, option="--out")
    if as_json:
        obj = result.as_json()
        for group in ("nominal", "mean", "std"):
            obj[group] = {k: json_number(x) for k, x in obj[group].items()}
        obj["quantiles"] = {k: {q: json_number(x) for q, x in qs.items()} for k, qs in obj["quantiles"].items()}
        obj["out"] = None if out is None else str(out)
        emit_json(obj)
        return
    click.echo(tolerance_table(result, str(out) if out is not None else None))


def tolerance_table(result, out: str | None = None) -> str:
    """The readable report of a study: inputs, quantiles of each output, Sobol indices."""
    study = result.study
    lines = [
        (
            f"{one_line(study.damper.name or 'damper', 120)} at {study.velocity:.4g} m/s, control {study.field:.4g} "
            f"{study.damper.fluid.control_unit}: {result.count} samples (seed {study.seed}, {result.executor}, "
            f"{result.seconds:.1f} s)"
        )
    ]
    lines += [f"  vary {v.describe()}" for v in study.variations]
    if result.rejected:
        lines.append(f"  {result.rejected} non-physical draws rejected and drawn again")
    lines.append("")
    head = f"{'output':<26}{'nominal':>10}" + "".join(f"{q + ' %':>10}" for q in ("1", "5", "50", "95", "99"))
    lines += [head, "-" * len(head)]
    for key, (label, unit, scale) in _LABELS.items():
        qs = result.quantiles[key]
        name = f"{label} [{unit}]" if unit else label
        lines.append(
            f"{name:<26}{result.nominal[key] / scale:>10.4g}"
            + "".join(f"{qs[q] / scale:>10.4g}" for q in ("1", "5", "50", "95", "99"))
        )
    if result.sensitivity:
        lines += [
            "",
            (
                f"Sobol indices, first-order / total (+- 95 % half-width; {result.sobol_base} base "
                f"samples, {result.sobol_evaluations} evaluations)"
            ),
        ]
        width = max(len(k) for k in study.keys) + 2
        for key, (label, _, _) in _LABELS.items():
            lines.append(f"  {label}")
            for name, s in result.sensitivity[key].items():
                if s["first"] is None:
                    lines.append(f"    {name:<{width}}does not vary")
                    continue
                lines.append(
                    f"    {name:<{width}}{s['first']:7.3f} +- {s['first_conf']:.3f}   "
                    f"{s['total']:7.3f} +- {s['total_conf']:.3f}"
                )
    if out is not None:
        lines += ["", f"samples written to {out}"]
    return "\n".join(lines)
