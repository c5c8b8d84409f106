"""``erdesign report DAMPER.toml [--velocity-range V1 V2] [--field E ...] --out report.html [--format md]``."""

from __future__ import annotations

import warnings
from pathlib import Path

import click

from ..damper_file import load_damper
from ..report import build_report, write_report
from .main import cli, emit_json, value_arg

__all__ = ["report"]


@cli.command()
@click.argument("damper_file", metavar="DAMPER.toml")
@click.option("--velocity-range", nargs=2, default=None, metavar="LOW HIGH",
              help='Lowest and highest piston velocity, e.g. "0 mm/s" "50 mm/s"; the highest is the design point.')
@click.option("--field", "fields", multiple=True,
              help='A control to evaluate (repeat the option), e.g. "3 kV/mm"; zero is always added.')
@click.option("--amplitude", default=None, help='Amplitude of the sine loops, e.g. "10 mm" (default 10 mm).')
@click.option("--frequency", default=None,
              help="Frequency of the sine loops (default: the peak velocity is the highest velocity).")
@click.option("--out", required=True, metavar="FILE", help="Report file to write (.html or .md).")
@click.option("--format", "fmt", type=click.Choice(["html", "md"]), default=None,
              help="html (self-contained, interactive plots) or md; default from the --out suffix.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (file written, checks) on stdout.")
def report(damper_file: str, velocity_range: tuple[str, str] | None, fields: tuple[str, ...], amplitude: str | None,
           frequency: str | None, out: str, fmt: str | None, as_json: bool) -> None:
    """Write a self-contained engineering report on a damper (inputs, results, equations, checks, plots)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")     # read for the control's unit only; build_report reports the warnings
        unit = load_damper(damper_file).fluid.control_unit
    rep = build_report(
        damper_file,
        velocity_range=None if velocity_range is None else tuple(value_arg(v, "m/s") for v in velocity_range),
        fields=None if not fields else [value_arg(f, unit) for f in fields],
        amplitude=None if amplitude is None else value_arg(amplitude, "m"),
        frequency=None if frequency is None else value_arg(frequency, "Hz"),
    )
    path = write_report(rep, out, fmt)
    fmt = fmt or ("md" if path.suffix.lower() in (".md", ".markdown") else "html")
    checks = [{"check": c.key, "status": c.status, "value": None if c.value is None else c.value.text,
               "detail": c.detail} for c in rep.checks]
    if as_json:
        emit_json({"out": str(path), "format": fmt, "bytes": Path(path).stat().st_size,
                   "warnings": rep.warnings, "checks": checks})
        return
    click.echo(f"wrote {path} ({fmt}, {Path(path).stat().st_size / 1e6:.2g} MB): "
               f"{len(checks) - rep.warnings} checks pass or info, {rep.warnings} warn")
    for c in rep.checks:
        click.echo(f"  {c.status:<4}  {c.name}" + (f": {c.value.text}" if c.value is not None else ""))
