"""``erdesign report DAMPER.toml [--velocity-range V1 V2] [--field E ...] [--out report.html] [--format md]
[--figures DIR [--figure-format svg]]``."""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import click

from .._util import check_output_path
from ..damper.files import load_damper
from ..errors import ErdesignError, OutputPathError
from ..report import build_report, write_report
from ..report.export import IMAGES_NEED
from .main import WholeNumber, cli, emit_json
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
  erdesign report makris.toml --figures figures     (also figures/makris-1996-force.png, ...; needs kaleido)
  erdesign report makris.toml --vary "geometry.gap=+-2.5 %" --vary "fluid.viscosity=+-10 %"
"""


def default_report_path(damper_name: str, damper_file: str, fmt: str) -> Path:
    """``<damper name>-report.html`` (or ``.md``) in the current folder; the file's stem when it has no name.

    >>> default_report_path("makris-1996", "examples/makris.toml", "html").name
    'makris-1996-report.html'
    >>> default_report_path("", "/data/my damper.toml", "md").name
    'my-damper-report.md'
    >>> len(default_report_path("x" * 200_000, "d.toml", "html").name)
    112
    """
    stem = re.sub(r"[^A-Za-z0-9_-]+", "-", damper_name or Path(damper_file).stem).strip("-.") or "damper"
    stem = stem[:100].rstrip("-.")  # a file name has at most 255 bytes: a long damper name is cut
    return Path(f"{stem}-report.{fmt}")


@cli.command(epilog=_EXAMPLES)
@click.argument("damper_file", metavar="DAMPER.toml")
@click.option(
    "--velocity-range",
    nargs=2,
    default=None,
    metavar="LOW HIGH",
    help='Lowest and highest piston velocity of the curves, e.g. "0 mm/s" "50 mm/s".',
)
@click.option(
    "--field",
    "fields",
    multiple=True,
    help='A control to evaluate (repeat the option), e.g. "3 kV/mm"; zero is always added.',
)
@click.option(
    "--design-velocity",
    default=None,
    help='Velocity of the design point, e.g. "25 mm/s" (default: the highest velocity).',
)
@click.option(
    "--design-field", default=None, help='Control of the design point, e.g. "3 kV/mm" (default: the largest control).'
)
@click.option("--amplitude", default=None, help='Amplitude of the sine loops, e.g. "10 mm" (default 10 mm).')
@click.option(
    "--frequency",
    default=None,
    help="Frequency of the sine loops (default: the peak velocity is the highest velocity).",
)
@click.option(
    "--out",
    default=None,
    metavar="FILE",
    help="Report file to write (.html or .md); default <damper name>-report.html in this folder.",
)
@click.option(
    "--format",
    "fmt",
    type=click.Choice(["html", "md"]),
    default=None,
    help="html (self-contained, interactive plots) or md; default from the --out suffix.",
)
@click.option(
    "--figures",
    "figures_dir",
    default=None,
    metavar="DIR",
    help="Also write each figure of the report as an image file into DIR (made if missing): "
    "<damper name>-<figure>.png. Needs the optional package kaleido and a Chrome or Chromium on "
    "the machine.",
)
@click.option(
    "--figure-format",
    type=click.Choice(["png", "svg"]),
    default="png",
    show_default=True,
    help="Image format of --figures.",
)
@click.option(
    "--vary",
    "vary",
    multiple=True,
    metavar="SPEC",
    help='A tolerance as erdesign tolerance takes it (repeat), e.g. "geometry.gap=+-2.5 %": the report then '
    "shows the spread of the force at the design point and its Sobol indices.",
)
@click.option(
    "--tolerance-samples",
    default=10000,
    show_default=True,
    type=WholeNumber(min=1),
    help="Monte-Carlo samples of the --vary study.",
)
@click.option("--force", is_flag=True, help="Overwrite the report file (and figure files) if they exist.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (file written, checks) on stdout.")
def report(
    damper_file: str,
    velocity_range: tuple[str, str] | None,
    fields: tuple[str, ...],
    design_velocity: str | None,
    design_field: str | None,
    amplitude: str | None,
    frequency: str | None,
    out: str | None,
    fmt: str | None,
    figures_dir: str | None,
    figure_format: str,
    vary: tuple[str, ...],
    tolerance_samples: int,
    force: bool,
    as_json: bool,
) -> None:
    """Write a self-contained engineering report on a damper (inputs, results, equations, checks, plots)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # read for the control's unit only; build_report reports the warnings
        damper = load_damper(damper_file)
    unit = damper.fluid.control_unit
    if out is None:
        path = default_report_path(damper.name, damper_file, fmt or "html")
    else:
        path = Path(out)
    path, fmt = check_output_path(
        path, force=force, inputs={"the damper file": damper_file}, formats=REPORT_SUFFIXES, fmt=fmt
    )
    folder = None if figures_dir is None else _figure_folder(figures_dir)
    rep = build_report(
        damper_file,
        velocity_range=None
        if velocity_range is None
        else tuple(quantity_option(v, "m/s", "--velocity-range") for v in velocity_range),
        fields=None if not fields else [quantity_option(f, unit, "--field") for f in fields],
        design_velocity=None
        if design_velocity is None
        else quantity_option(design_velocity, "m/s", "--design-velocity"),
        design_field=None if design_field is None else quantity_option(design_field, unit, "--design-field"),
        amplitude=None if amplitude is None else quantity_option(amplitude, "m", "--amplitude"),
        frequency=None if frequency is None else quantity_option(frequency, "Hz", "--frequency"),
        tolerances=vary,
        tolerance_samples=tolerance_samples,
    )
    images: dict[Path, bytes] = {}
    if folder is not None:
        # every image is drawn (and every name checked) before anything is written: a missing kaleido or
        # browser, or a file that exists, leaves no half-written output
        stem = re.sub(r"[^A-Za-z0-9_-]+", "-", damper.name or Path(damper_file).stem).strip("-.") or "damper"
        names = [folder / f"{stem}-{f.key}.{figure_format}" for f in rep.figures]
        for name in names if folder.is_dir() else ():  # a folder still to make holds no file
            check_output_path(
                name, force=force, inputs={"the damper file": damper_file, "the report": path}, option="--figures"
            )
        from ..report.export import figure_images

        images = dict(zip(names, figure_images(rep.figures, figure_format).values()))
    path = write_report(rep, path, fmt, overwrite=force, option="--out")
    if folder is not None:
        from ..output import write_output

        folder.mkdir(exist_ok=True)
        for name, data in images.items():
            write_output(name, data, overwrite=force, option="--figures")
    checks = [
        {"check": c.key, "status": c.status, "value": None if c.value is None else c.value.text, "detail": c.detail}
        for c in rep.checks
    ]
    if as_json:
        emit_json(
            {
                "out": str(path),
                "format": fmt,
                "bytes": Path(path).stat().st_size,
                "figures": [str(n) for n in images],
                "warnings": rep.warnings,
                "checks": checks,
            }
        )
        return
    point = f"{rep.setting('velocity_design').value.text} and {rep.setting('field_design').value.text}"
    click.echo(
        f"wrote {path} ({fmt}, {Path(path).stat().st_size / 1e6:.2g} MB) at the design point {point}: "
        f"{len(checks) - rep.warnings} checks pass or info, {rep.warnings} warn"
    )
    for c in rep.checks:
        click.echo(f"  {c.status:<4}  {c.name}" + (f": {c.value.text}" if c.value is not None else ""))
    if images:
        click.echo(f"wrote {len(images)} figures ({figure_format}) into {folder}: " + ", ".join(n.name for n in images))


def _figure_folder(figures_dir: str) -> Path:
    """The folder of ``--figures``: an existing folder, or one to make in an existing folder; and kaleido must be
    importable (checked before the report is built, so that its absence costs nothing)."""
    folder = Path(figures_dir)
    if str(figures_dir).strip() == "":
        raise OutputPathError("--figures: empty folder name")
    if folder.exists() and not folder.is_dir():
        raise OutputPathError(f"--figures {folder}: is a file; give a folder")
    if not folder.exists() and not (folder.parent if str(folder.parent) else Path(".")).is_dir():
        raise OutputPathError(f"--figures {folder}: the folder {folder.parent} does not exist")
    try:
        import kaleido  # noqa: F401
    except ImportError:
        raise ErdesignError(f"--figures: kaleido is not installed; {IMAGES_NEED}") from None
    return folder
