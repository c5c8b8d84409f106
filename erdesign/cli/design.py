"""``erdesign design REQUIREMENTS.toml [--json] [--out designs.csv]``: geometries that meet the requirements."""

from __future__ import annotations

import time

import click

from .._util import check_output_path
from ..damper.writer import save_damper
from ..design import design as run_design
from ..design import read_requirements
from ..errors import ErdesignError, one_line
from .main import cli, emit_json, executor_options

__all__ = ["design"]

_EXAMPLES = """
\b
Examples:
  erdesign design requirements.toml
  erdesign design requirements.toml --out designs.csv
  erdesign design requirements.toml --json > designs.json
  erdesign design requirements.toml --write-damper 1 best.toml     (then: erdesign size best.toml ...)
  erdesign design requirements.toml --jobs 4
  erdesign design requirements.toml --scheduler tcp://10.0.0.5:8786
\b
Rounding and ties ([design.search] of the requirements file):
  gap_tolerance = "0.01 mm"      length_tolerance = "0.1 mm"      secondary = "min_outer_diameter"
"""


@cli.command(epilog=_EXAMPLES)
@click.argument("requirements_file", metavar="REQUIREMENTS.toml")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (SI units) instead of a table.")
@click.option(
    "--out",
    "out",
    default=None,
    metavar="designs.csv",
    help="Also write the ranked designs, the Pareto front (and the nearest design when nothing is "
    "feasible) to a CSV file with units in the header.",
)
@click.option(
    "--write-damper",
    "write_damper",
    type=(int, str),
    default=None,
    metavar="N OUT.toml",
    help="Also write the design ranked N (1 is the best) as a damper file that every command loads.",
)
@click.option(
    "--force", is_flag=True, help="Let --out and --write-damper replace existing files (never the requirements file)."
)
@executor_options(default_jobs="1")
def design(
    requirements_file: str,
    as_json: bool,
    out: str | None,
    write_damper: tuple[int, str] | None,
    force: bool,
    executor: dict,
) -> None:
    """Feasible damper geometries ranked by the objective, or the conflicts when there are none."""
    inputs = {"the requirements file": requirements_file}
    if out is not None:  # checked before the search: a refused name must not cost a long run
        out, _ = check_output_path(out, force=force, inputs=inputs, formats={".csv": "csv"})
    req = read_requirements(requirements_file)
    damper_out = None
    if write_damper is not None:
        rank, damper_out = write_damper
        if not 1 <= rank <= req.search.designs:
            raise ErdesignError(
                f"--write-damper {rank}: the search returns designs 1 (the best) to "
                f"{req.search.designs} (design.search.designs of {requirements_file})"
            )
        damper_out, _ = check_output_path(
            damper_out,
            force=force,
            option="--write-damper",
            inputs={**inputs, "the --out file": out},
            formats={".toml": "toml"},
        )
    result = run_design(req, progress=_Progress(), **executor)
    if out is not None:
        result.write_csv(out, overwrite=force, option="--out")
    if as_json:
        emit_json(result.as_json())
    else:
        click.echo(_table(result))
    if damper_out is not None:  # after the table: when nothing is feasible its conflicts say why
        _write_damper(result, rank, damper_out, requirements_file, force)


def _write_damper(result, rank: int, path, requirements_file: str, force: bool) -> None:
    """The damper file of the design ranked ``rank``; a one-line error when the search returned no such design."""
    try:
        spec = result.damper_spec(rank)
    except ErdesignError as exc:
        raise ErdesignError(f"--write-damper {exc}") from None
    rec = result.design(rank)
    p = result.requirements.points[0]
    comment = (
        f"design {rank} of erdesign design {requirements_file} (objective {result.requirements.objective})\n"
        f"at point 1 (v = {p.velocity:.6g} m/s, field {rec['points'][0]['field']}): "
        f"force {rec['force_N']:.6g} N, zero-field force {rec['zero_field_force_N']:.6g} N"
    )
    save_damper(spec, path, comment=comment, overwrite=force, option="--write-damper")
    click.echo(f"design {rank} written to {path}", err=True)


class _Progress:
    """Progress of a long search on stderr: a line every few seconds once it has run for two."""

    def __init__(self, every: float = 5.0, after: float = 2.0):
        self.start = time.monotonic()
        self.next = self.start + after
        self.every = every

    def __call__(self, evaluated: int, total: int, feasible: int) -> None:
        now = time.monotonic()
        if now >= self.next and evaluated < total:
            click.echo(
                f"design: {evaluated} of {total} candidates evaluated ({100 * evaluated / total:.0f} %), "
                f"{feasible} feasible so far, {now - self.start:.0f} s",
                err=True,
            )
            self.next = now + self.every


def _geometry_cells(rec: dict) -> list[str]:
    g = rec["geometry"]

    def mm(key: str) -> str:
        return g[key].removesuffix(" mm") if key in g else "-"

    return [
        mm("gap"),
        mm("duct_length"),
        mm("duct_mean_diameter"),
        mm("piston_diameter"),
        mm("rod_diameter"),
        str(g.get("ducts", 1)),
    ]


def _row(rec: dict, label: str) -> list[str]:
    dyn = rec["dynamic_range"]
    return [
        label,
        *_geometry_cells(rec),
        f"{rec['force_N'] / 1e3:.4g}",
        f"{rec['zero_field_force_N'] / 1e3:.4g}",
        "-" if dyn is None else f"{dyn:.4g}",
        f"{rec['fluid_volume_m3'] * 1e6:.4g}",
        f"{rec['outer_diameter_m'] * 1e3:.4g}",
        f"{rec['length_m'] * 1e3:.4g}",
        f"{rec['bingham_number']:.3g}" if rec["bingham_number"] is not None else "-",
        f"{rec['plug_fraction']:.3g}",
        f"{rec['gap_ratio']:.3g}",
    ]


_HEAD = [
    "#",
    "h [mm]",
    "L [mm]",
    "d [mm]",
    "Dp [mm]",
    "dr [mm]",
    "n",
    "F [kN]",
    "F0 [kN]",
    "F/F0",
    "V [cm3]",
    "OD [mm]",
    "len [mm]",
    "Bi",
    "phi",
    "h/d",
]


def _grid(rows: list[list[str]]) -> str:
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    return "\n".join("  ".join(c.rjust(w) for c, w in zip(r, widths)) for r in rows)


def _table(result) -> str:
    req = result.requirements
    p = req.points[0]
    lines = [
        f"{one_line(req.name or 'requirements', 120)}: {req.configuration} damper, objective {req.objective}",
        (
            f"{result.evaluated} candidates evaluated, {result.feasible_count} feasible "
            f"(figures at point 1: v = {p.velocity * 1e3:.4g} mm/s)"
        ),
        result.ranking_note(),
    ]
    if result.feasible:
        lines.append(_grid([_HEAD] + [_row(d, str(d["rank"])) for d in result.designs]))
        lines.append("active constraints: (the limits each design sits on, within the active tolerance)")
        lines += [
            f"  {d['rank']}: {', '.join(d['active_constraints']) or 'none (inside every limit)'}"
            for d in result.designs
        ]
        if req.coil is not None:
            lines.append(_coil_grid(result.designs))
        lines.append(f"Pareto front ({', '.join(req.search.pareto)}): {len(result.pareto)} designs (--out writes them)")
    else:
        lines.append("no feasible design; conflicts:")
        lines += [f"  - {c}" for c in result.conflicts]
        if result.nearest is not None:
            lines.append("nearest design:")
            lines.append(_grid([_HEAD] + [_row(result.nearest, "-")]))
    return "\n".join(lines)


_COIL_HEAD = [
    "#",
    "N",
    "d_w [mm]",
    "d_c [mm]",
    "L_p [mm]",
    "OD [mm]",
    "I [A]",
    "B_g [T]",
    "tau_y [kPa]",
    "R [ohm]",
    "P [W]",
    "L/R [ms]",
    "J [A/mm2]",
    "fill",
    "sat",
]


def _coil_grid(designs: list[dict]) -> str:
    """The coils of the designs (figures of the magnetic circuit at the design current, point 1 for B and tau_y)."""
    rows = [_COIL_HEAD]
    for d in designs:
        c, m, p = d["coil"], d["magnetics"], d["points"][0]
        tc = m["time_constant_s"]
        rows.append(
            [
                str(d.get("rank", "-")),
                str(c["turns"]),
                *(
                    c[k].removesuffix(" mm")
                    for k in ("wire_diameter", "core_diameter", "pole_length", "housing_outer_diameter")
                ),
                f"{m['design_current_A']:.4g}",
                f"{p['gap_flux_density_T']:.3g}",
                f"{p['yield_stress_Pa'] / 1e3:.4g}",
                f"{m['coil_resistance_ohm']:.4g}",
                f"{m['power_W']:.4g}",
                "-" if tc is None else f"{tc * 1e3:.4g}",
                f"{p['current_density_A_per_m2'] / 1e6:.3g}",
                f"{m['fill_factor']:.2f}",
                f"{p['saturation_ratio']:.2f}",
            ]
        )
    return (
        "coils (magnetic circuit at the design current; sat: largest field over the knee field of a part):\n"
        + _grid(rows)
    )
