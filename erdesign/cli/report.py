"""``erdesign report DAMPER.toml [--velocity-range V1 V2] [--field E ...] [--out report.html] [--format md]``."""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import click

from .._util import check_output_path
from ..damper_file import load_damper
from ..report import build_report, write_report
from .main import cli, emit_json
from .size import quantity_option

__all__ = ["report", "default_report_path", "REPORT_SUFFIXES"]

#: Suffix of the report file -> its format (any other suffix is refused: --out x.pdf must not write HTML).
REPORT_SUFFIXES = {".html": "html", ".htm": "html", ".md": "md", ".markdown": "md"}

_EXAMPLES = """
\b
Examples:
  erdesign report makris.toml                      (writes makris-1996-report.html here)
  erdesign report makris.toml --design-velocity "25 mm/s" --design-field "3 kV/mm"
  erdesign report makris.toml --velocity-range "0 in/s" "2 in/s" --field "1.5 kV/mm" --field "3 kV/mm"
  erdesign report makris.toml --format md --out makris.md --force
"""


def default_report_path(damper_name: str, damper_file: str, fmt: str) -> Path:
    """``<damper name>-report.html`` (or ``.md``) in the current folder; the file's stem when it has no name.

    >>> default_report_path("makris-1996", "examples/makris.toml", "html").name
    'makris-1996-report.html'
    >>> default_report_path("", "/data/my damper.toml", "md").name
    'my-damper-report.md'
    """
    stem = re.sub(r"[^A-Za-z0-9_-]+", "-", damper_name or Path(damper_file).stem).strip("-.") or "damper"
    return Path(f"{stem}-report.{fmt}")


@cli.command(epilog=_EXAMPLES)
@click.argument("damper_file", metavar="DAMPER.toml")
@click.option("--velocity-range", nargs=2, default=None, metavar="LOW HIGH",
              help='Lowest and highest piston velocity of the curves, e.g. "0 mm/s" "50 mm/s".')
@click.option("--field", "fields", multiple=True,
              help='A control to evaluate (repeat the option), e.g. "3 kV/mm"; zero is always added.')
@click.option("--design-velocity", default=None,
              help='Velocity of the design point, e.g. "25 mm/s" (default: the highest velocity).')
@click.option("--design-field", default=None,
              help='Control of the design point, e.g. "3 kV/mm" (default: the largest control).')
@click.option("--amplitude", default=None, help='Amplitude of the sine loops, e.g. "10 mm" (default 10 mm).')
@click.option("--frequency", default=None,
              help="Frequency of the sine loops (default: the peak velocity is the highest velocity).")
@click.option("--out", default=None, metavar="FILE",
              help="Report file to write (.html or .md); default <damper name>-report.html in this folder.")
@click.option("--format", "fmt", type=click.Choice(["html", "md"]), default=None,
              help="html (self-contained, interactive plots) or md; default from the --out suffix.")
@click.option("--force", is_flag=True, help="Overwrite the report file if it exists.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (file written, checks) on stdout.")
def report(damper_file: str, velocity_range: tuple[str, str] | None, fields: tuple[str, ...],
           design_velocity: str | None, design_field: str | None, amplitude: str | None, frequency: str | None,
           out: str | None, fmt: str | None, force: bool, as_json: bool) -> None:
    """Write a self-contained engineering report on a damper (inputs, results, equations, checks, plots)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")     # read for the control's unit only; build_report reports the warnings
        damper = load_damper(damper_file)
    unit = damper.fluid.control_unit
    if out is None:
        path = default_report_path(damper.name, damper_file, fmt or "html")
    else:
        path = Path(out)
    path, fmt = check_output_path(path, force=force, inputs={"the damper file": damper_file}, formats=REPORT_SUFFIXES, fmt=fmt)
    rep = build_report(
        damper_file,
        velocity_range=None if velocity_range is None else tuple(
            quantity_option(v, "m/s", "--velocity-range") for v in velocity_range),
        fields=None if not fields else [quantity_option(f, unit, "--field") for f in fields],
        design_velocity=None if design_velocity is None else quantity_option(design_velocity, "m/s",
                                                                             "--design-velocity"),
        design_field=None if design_field is None else quantity_option(design_field, unit, "--design-field"),
        amplitude=None if amplitude is None else quantity_option(amplitude, "m", "--amplitude"),
        frequency=None if frequency is None else quantity_option(frequency, "Hz", "--frequency"),
    )
    path = write_report(rep, path, fmt)
    checks = [{"check": c.key, "status": c.status, "value": None if c.value is None else c.value.text,
               "detail": c.detail} for c in rep.checks]
    if as_json:
        emit_json({"out": str(path), "format": fmt, "bytes": Path(path).stat().st_size,
                   "warnings": rep.warnings, "checks": checks})
        return
    point = f"{rep.setting('velocity_design').value.text} and {rep.setting('field_design').value.text}"
    click.echo(f"wrote {path} ({fmt}, {Path(path).stat().st_size / 1e6:.2g} MB) at the design point {point}: "
               f"{len(checks) - rep.warnings} checks pass or info, {rep.warnings} warn")
    for c in rep.checks:
        click.echo(f"  {c.status:<4}  {c.name}" + (f": {c.value.text}" if c.value is not None else ""))
