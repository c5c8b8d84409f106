"""The ``erdesign`` command line (shared/CONTRACTS.md section 3).

Every command takes ``--json``: stdout is then exactly one JSON object.  Errors go to stderr as one line without a
traceback and the exit code is 1 (bad input) or 2 (bad command-line usage); warnings go to stderr as
``warning: ...`` lines.  The commands hold no physics: they call the library and print its results.

Values on the command line are strings with units (``--velocity "1 in/s"``, ``--field "3 kV/mm"``).  A plain number
is read in SI units (m/s; the field in the SI unit of the damper's control: V/m, A/m, T, A or V).
"""

from __future__ import annotations

import json
import math
import sys
import warnings
from typing import Any

import click

from . import __version__
from .damper_file import load_damper
from .errors import ErdesignError
from .units import Q_, format_quantity

__all__ = ["main", "run", "cli"]


def _value(text: str, si_unit: str) -> Any:
    """A command-line value: a quantity string, or a plain number in SI units."""
    try:
        return Q_(float(text), si_unit)
    except ValueError:
        return text


def _emit_json(obj: dict) -> None:
    click.echo(json.dumps(obj, allow_nan=False))


def _json_number(x: float | None) -> float | None:
    return None if x is None or not math.isfinite(x) else x


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="erdesign")
def cli() -> None:
    """erdesign: design and diagnose ER and MR dampers with annular ducts."""


@cli.command()
@click.argument("damper_file", metavar="DAMPER.toml")
@click.option("--velocity", required=True, help='Piston velocity, e.g. "1 in/s" or "0.0254" (m/s).')
@click.option("--field", default=None, help='Control: field, current or voltage, e.g. "3 kV/mm" (default 0).')
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (SI units) instead of a table.")
def size(damper_file: str, velocity: str, field: str | None, as_json: bool) -> None:
    """Quasi-steady design point of a damper at one piston velocity and control."""
    damper = load_damper(damper_file)
    r = damper.size(velocity=_value(velocity, "m/s"),
                    field=None if field is None else _value(field, damper.fluid.control_unit))
    if as_json:
        out = r.as_json()
        out["dynamic_range"] = _json_number(out["dynamic_range"])
        _emit_json(out)
        return
    click.echo(_size_table(damper, r))


def _size_table(damper, r) -> str:
    g = damper.geometry

    def q(x, unit=None, digits=4):
        return format_quantity(x.to(unit) if unit else x.to_compact(), None, digits)

    config = f"{g.configuration}, {r.flow_model}, h/d = {r.gap_ratio:.3g}"
    rows = [
        ("piston area A_p", q(r.piston_area, "cm^2")),
        ("flow rate Q = v A_p", q(r.flow_rate, "mL/s")
         + (f"  ({q(r.flow_per_duct, 'mL/s')} per duct)" if g.ducts > 1 else "")),
        ("yield stress / viscosity", f"{q(r.yield_stress, 'kPa')} / {q(r.viscosity, 'Pa*s')}"),
        ("pressure drop", q(r.pressure_drop, "MPa")),
        ("force (with seal friction)", q(r.force)),
        ("zero-field force", q(r.zero_field_force)),
        ("dynamic range F(E)/F(0)", "undefined (zero-field force is 0)" if r.dynamic_range is None
         else f"{r.dynamic_range:.4g}"),
        ("yield force of the fluid", q(r.yield_force)),
        ("seal friction", q(r.seal_friction, "N")),
        ("damping constant C (eq 15)" if g.configuration == "valve" else "damping constant C (zero field)",
         q(r.damping_constant, "kN*s/m")),
        ("Reynolds number (eq 1)", f"{r.reynolds:.4g} ({'laminar' if r.laminar else 'NOT laminar: > 2300'})"),
        ("plug fraction", f"{r.plug_fraction:.4g}"),
    ]
    width = max(len(k) for k, _ in rows)
    head = (f"{damper.name or 'damper'} ({config})\n"
            f"at v = {format_quantity(r.velocity.to_compact())}, "
            f"control = {format_quantity(r.field.to(damper.fluid.field_unit))}")
    return head + "\n" + "\n".join(f"  {k:<{width}}  {v}" for k, v in rows)


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``erdesign`` console script; returns the exit code."""
    args = sys.argv[1:] if argv is None else argv

    def show_warning(message, category, filename, lineno, file=None, line=None):
        click.echo(f"warning: {message}", err=True)

    warnings.showwarning = show_warning
    try:
        cli.main(args=args, prog_name="erdesign", standalone_mode=False)
    except click.exceptions.Abort:
        click.echo("erdesign: aborted", err=True)
        return 1
    except click.UsageError as exc:
        command = exc.ctx.command_path if exc.ctx else "erdesign"
        click.echo(f"{command}: {exc.format_message()} (see '{command} --help')", err=True)
        return 2
    except click.ClickException as exc:
        click.echo(f"erdesign: {exc.format_message()}", err=True)
        return exc.exit_code or 1
    except ErdesignError as exc:
        click.echo(f"error: {' '.join(str(exc).split())}", err=True)
        return 1
    except OSError as exc:
        click.echo(f"error: {exc}", err=True)
        return 1
    except Exception as exc:  # a bug, not bad input: still one line, but say so
        click.echo(f"internal error: {type(exc).__name__}: {' '.join(str(exc).split())} "
                   "(please report this with the command that caused it)", err=True)
        return 3
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())


def run() -> None:
    """Console-script wrapper: exit with :func:`main`'s code."""
    sys.exit(main())
