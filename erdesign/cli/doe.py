"""``erdesign doe --programme NAME [options] --out plan.csv [--json]`` (docs/cli.md): a test programme of
Vivas-López et al. (n.d.) Table 1 written as a measurement file without force (time, displacement, control).

The signals are made by :mod:`erdesign.simulation.programmes`; this module parses options and writes the file.
"""

from __future__ import annotations

import click

from .main import SEED, as_flags, cli, emit_json, json_number

__all__ = ["doe"]

_EXAMPLES = """
\b
Examples:
  erdesign doe --programme E5 --control-range "0.5 kV/mm, 4 kV/mm" --out e5.csv
  erdesign doe --programme dsfs+icps --control-range "0.2 A, 1.6 A" --rate "1 kHz" --out plan.csv
  erdesign doe --programme rp --amplitudes "2 mm, 4 mm, 8 mm" --duration "30 s" --seed 3 --out rp.csv --json
"""


def _quantities(text: str, si_unit: str | None, option: str) -> list:
    """The comma-separated quantities of an option; each checked for the dimension of ``si_unit``."""
    from ..errors import ErdesignError
    from ..units import to_si

    items = [s.strip() for s in text.split(",") if s.strip()]
    if not items:
        raise ErdesignError(f'{option}: empty; give values with units, e.g. "1 mm, 8 mm"')
    return [to_si(s, si_unit, option) for s in items]


def _control_range(text: str) -> tuple[tuple[float, float], str, str]:
    """(low, high) SI, the control kind and the unit given, from ``"LOW, HIGH"``."""
    from ..errors import ErdesignError
    from ..fluid import CONTROL_UNITS, control_kind
    from ..units import to_si

    items = [s.strip() for s in text.split(",") if s.strip()]
    if len(items) != 2:
        raise ErdesignError(f'--control-range {text!r}: give the low and the high control, e.g. "0.5 kV/mm, 4 kV/mm"')
    kind = control_kind(items[1], "--control-range")
    low, high = (to_si(s, CONTROL_UNITS[kind], "--control-range") for s in items)
    from ..units import Q_

    return (low, high), kind, f"{Q_(items[1]).units:~P}"


@cli.command(epilog=_EXAMPLES)
@click.option(
    "--programme",
    required=True,
    metavar="NAME",
    help="E1-E5 (Vivas-López et al. Table 1), a displacement signal (rp, dsfs) or DISPLACEMENT+ACTUATION "
    "(actuation: sc, icps, prbs), e.g. dsfs+prbs.",
)
@click.option(
    "--control-range",
    default="0.5 kV/mm, 4 kV/mm",
    show_default=True,
    metavar='"LOW, HIGH"',
    help="Low and high control of the actuation signal: field, current or voltage (the paper's PWM duty "
    "10 % and 80 %).",
)
@click.option(
    "--amplitudes",
    default=None,
    metavar="LIST",
    help='DSFS: first and last amplitude ("8 mm, 1 mm"); RP: peak of each segment ("1 mm, 8 mm").',
)
@click.option(
    "--frequencies",
    default=None,
    metavar="LIST",
    help='DSFS: first and last frequency ("0.5 Hz, 14.5 Hz"); RP: the band ("0.1 Hz, 3 Hz").',
)
@click.option("--duration", default=None, help='RP: length of the record, e.g. "20 s".')
@click.option("--rate", default="500 Hz", show_default=True, help="Sampling rate.")
@click.option("--seed", default=0, show_default=True, type=SEED, help="Seed of the random signals (RP, ICPS, PRBS).")
@click.option("--out", required=True, metavar="PLAN.csv", help="Measurement CSV to write (no force column).")
@click.option("--force", "overwrite", is_flag=True, help="Let --out replace an existing file.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a summary.")
def doe(
    programme: str,
    control_range: str,
    amplitudes: str | None,
    frequencies: str | None,
    duration: str | None,
    rate: str,
    seed: int,
    out: str,
    overwrite: bool,
    as_json: bool,
) -> None:
    """Write a test programme (RP, DSFS; SC, ICPS, PRBS actuation; E1-E5) as a record to play."""
    import numpy as np

    from .._util import check_output_path
    from ..errors import ErdesignError
    from ..data.measurement import CONTROL_COLUMNS, Measurement, write_measurement
    from ..simulation.programmes import EXPERIMENTS, ProgrammeError
    from ..simulation.programmes import programme as make_programme
    from ..units import to_si

    path, _ = check_output_path(out, force=overwrite, formats={".csv": "csv"})
    key = programme.strip().lower()
    disp = EXPERIMENTS[key].displacement if key in EXPERIMENTS else key.partition("+")[0]
    has_control = key in EXPERIMENTS or "+" in key
    options: dict = {}
    if amplitudes is not None:
        A = _quantities(amplitudes, "m", "--amplitudes")
        if disp == "dsfs":
            if len(A) != 2:
                raise ProgrammeError('--amplitudes: DSFS takes the first and the last amplitude, e.g. "8 mm, 1 mm"')
            options["amplitude_range"] = tuple(A)
        else:
            options["amplitudes"] = tuple(A)
    if frequencies is not None:
        f = _quantities(frequencies, "Hz", "--frequencies")
        if len(f) != 2:
            raise ProgrammeError('--frequencies: give two frequencies, e.g. "0.5 Hz, 14.5 Hz"')
        options["frequency_range" if disp == "dsfs" else "band"] = tuple(f)
    if duration is not None:
        if disp != "rp":
            raise ProgrammeError("--duration: applies to the road profile (rp); a DSFS lasts its steps' cycles")
        options["duration"] = to_si(duration, "s", "--duration")
    (low, high), kind, control_unit = _control_range(control_range) if has_control else ((None, None), None, None)
    try:
        motion = make_programme(
            programme,
            control_range=(low, high) if has_control else None,
            rate=to_si(rate, "Hz", "--rate"),
            seed=seed,
            displacement_options=options,
        )
    except ErdesignError as exc:  # the library names its arguments; the message names the options
        raise type(exc)(as_flags(str(exc))) from None
    record = Measurement.from_arrays(
        motion.time,
        motion.displacement,
        control=motion.control if has_control else None,
        control_kind=kind,
        velocity=motion.velocity,
        name=path.name,
    )
    units = {
        "displacement": "mm",
        **({} if kind is None else {next(c for c, kinds in CONTROL_COLUMNS.items() if kind in kinds): control_unit}),
    }
    write_measurement(
        path,
        record,
        units=units,
        comment=f"erdesign doe --programme {programme}: {motion.description}\n"
        "a test plan (no force): play the displacement and the control",
        overwrite=overwrite,
        option="--out",
    )
    summary = {
        "programme": key.upper(),
        "description": motion.description,
        "samples": len(record),
        "duration_s": json_number(record.duration),
        "rate_Hz": json_number(record.sample_rate),
        "peak_displacement_m": json_number(float(np.max(np.abs(record.displacement)))),
        "peak_velocity_m_per_s": json_number(float(np.max(np.abs(record.velocity)))),
        "control_kind": kind,
        "control_levels": None if kind is None else len(np.unique(record.control)),
        "control_min": None if kind is None else json_number(float(record.control.min())),
        "control_max": None if kind is None else json_number(float(record.control.max())),
        "out": str(path),
    }
    if as_json:
        emit_json(summary)
        return
    control = (
        ""
        if kind is None
        else f", control {control_range.split(',')[0].strip()} to {control_range.split(',')[1].strip()}"
    )
    click.echo(
        f"{motion.description}\n  {summary['samples']} samples over "
        f"{record.duration:.4g} s, peak {summary['peak_displacement_m'] * 1e3:.4g} mm, "
        f"{summary['peak_velocity_m_per_s']:.4g} m/s{control}\n  written to {path}"
    )
