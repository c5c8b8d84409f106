"""The ``erdesign`` command group, its entry point and the helpers the commands share.

The commands themselves live one per module beside this one (``size.py`` ...).  The group knows them by name
(:data:`COMMANDS`) and imports a command's module only when that command runs, so that ``erdesign --help`` does not
pay for the library behind every command.  Contract (docs/cli.md):

Every command takes ``--json``: stdout is then exactly one JSON object.  Errors go to stderr as one line without a
traceback and the exit code is 1 (bad input) or 2 (bad command-line usage); warnings go to stderr as
``warning: ...`` lines.  The commands hold no physics: they call the library and print its results.

Values on the command line are strings with units (``--velocity "1 in/s"``, ``--field "3 kV/mm"``).  A plain number
is read in SI units (m/s; the field in the SI unit of the damper's control: V/m, A/m, T, A or V).
"""

from __future__ import annotations

import importlib
import json
import math
import os
import signal
import sys
import threading
import warnings
from typing import Any

import click

from .. import __version__
from ..errors import ErdesignError, one_line
from ..output import SIGTERM_EXIT, terminate_as_exit

__all__ = [
    "main",
    "run",
    "cli",
    "value_arg",
    "emit_json",
    "json_number",
    "check_effects_option",
    "COMMANDS",
    "NumberRange",
    "WholeNumber",
]


def _number_text(kind: click.ParamType, value: Any, param, ctx, *, whole: bool) -> Any:
    """The text of a numeric option read as the library reads numbers (:func:`erdesign.units.plain_number`), or a
    usage error naming the option.

    click's own types use Python's ``int()`` and ``float()``, which read digit separators (``"1_000"``) and digits
    of other scripts (``"\u0661\u0660"``) that no other number in erdesign is read from: refused here, with the
    library's words.  A whole number may be written as a float that is one (``"1e5"``)."""
    from ..errors import UnitError
    from ..units import clean_value_text, plain_number

    if not isinstance(value, str):
        return value
    number = plain_number(value)
    if number is None:
        try:  # says what is wrong with the text (a digit separator, an Arabic-Indic digit, a comma ...)
            clean_value_text(value, "", number=False)
        except UnitError as exc:
            kind.fail(str(exc).removeprefix(": ").split(", e.g. ")[0], param, ctx)
        kind.fail(f"{value!r} is not a {'whole number' if whole else 'number'}", param, ctx)
    if math.isnan(number):
        kind.fail(f"{value!r} is not a number", param, ctx)
    if whole:
        if not math.isfinite(number) or number != int(number):
            kind.fail(f"{value!r} is not a whole number", param, ctx)
        return int(number)
    return number


class NumberRange(click.FloatRange):
    """The type of every real-number option: click's FloatRange reading numbers as the rest of erdesign does
    (:func:`_number_text`), and without NaN (``--max-time nan`` passed its bounds: every comparison with NaN is
    false, and it meant no limit at all)."""

    def convert(self, value, param, ctx):
        return super().convert(_number_text(self, value, param, ctx, whole=False), param, ctx)


class WholeNumber(click.IntRange):
    """The type of every whole-number option (``--seed``, ``--jobs``, ``--samples`` ...): click's IntRange reading
    numbers as the rest of erdesign does (:func:`_number_text`).  Without bounds it takes any whole number."""

    def convert(self, value, param, ctx):
        return super().convert(_number_text(self, value, param, ctx, whole=True), param, ctx)


# Command name -> (module beside this one, one-line help shown by ``erdesign --help``).  The module registers the
# command on :data:`cli` when it is imported; tests/test_cli_startup.py checks that the help lines here are the
# commands' own.
COMMANDS: dict[str, tuple[str, str]] = {
    "app": ("app", "Open the design app (Size, Simulate, Compare and diagnose, Report) in the browser."),
    "batch": ("batch", "Run identify, fit or diagnose on every record; one row per record in one table."),
    "characterize": (
        "characterize",
        "Find a damper's characteristics, build its customized model and cross-validate it (Vivas-López et al.).",
    ),
    "design": ("design", "Feasible damper geometries ranked by the objective, or the conflicts when there are none."),
    "doe": ("doe", "Write a test programme (RP, DSFS; SC, ICPS, PRBS actuation; E1-E5) as a record to play."),
    "diagnose": (
        "diagnose",
        "Calibrate the physics baseline, show where it fails and rank the effects that could be missing.",
    ),
    "examples": (
        "examples",
        "List the bundled example dampers and requirements; their names work wherever such a file is asked for.",
    ),
    "fit": ("fit", "Calibrate the baseline of the damper (viscosity and yield-stress factors) plus the named effects."),
    "identify": (
        "identify",
        "Identify a model's parameters from a measurement (simulation from rest at the first sample).",
    ),
    "magnetics": (
        "magnetics",
        "Magnetic circuit of an MR damper with a [coil]: gap flux density, yield stress, coil R, L, L/R, power.",
    ),
    "materials": (
        "materials",
        'List the fluids of the materials database (name it in a damper file: material = "...").',
    ),
    "models": ("models", "List the damper models with their sources and parameters."),
    "report": (
        "report",
        "Write a self-contained engineering report on a damper (inputs, results, equations, checks, plots).",
    ),
    "simulate": ("simulate", "Run a model with given parameters on a measurement and score it (ESR and more)."),
    "size": ("size", "Quasi-steady design point of a damper at one piston velocity and control."),
    "vehicle": (
        "vehicle",
        "Quarter vehicle with the damper, passive or semi-active: ride figures (Butz and von Stryk 2002).",
    ),
    "tolerance": (
        "tolerance",
        "Spread of force, zero-field force, dynamic range and damping constant under tolerances, with Sobol indices.",
    ),
}


class OneValueCommand(click.Command):
    """A command whose options that take one value refuse to be given twice.

    click keeps the last of ``--damper a.toml --damper b.toml`` without a word: the user meant one of the two, or
    both (a record each?).  Flags (``--force --force``), counted options and options that take several values
    (``multiple=True``) may repeat."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        if not ctx.resilient_parsing:
            refuse_repeated_options(self, ctx, args)
        return super().parse_args(ctx, args)


def refuse_repeated_options(command: click.Command, ctx: click.Context, args: list[str]) -> None:
    """A usage error naming the first option of ``command`` that takes one value and is given more than once in
    ``args``; nothing when none is (or the arguments do not parse: click's own parse then says why)."""
    try:
        opts, _, order = command.make_parser(ctx).parse_args(args=list(args))
    except click.UsageError:
        return
    seen: set[str] = set()
    for param in order:
        one_value = (
            isinstance(param, click.Option) and not (param.multiple or param.count or param.is_flag) and param.name
        )
        if not one_value:
            continue
        if param.name in seen:
            flag = max(param.opts, key=len)
            raise click.UsageError(
                f"{flag} is given more than once; it is read once (only the last would count): give it once, or "
                "run the command once for each",
                ctx,
            )
        seen.add(param.name)


class LazyGroup(click.Group):
    """A click group that imports a command's module only when the command is looked up to run."""

    command_class = OneValueCommand

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(set(COMMANDS) | set(self.commands))

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name not in self.commands and cmd_name in COMMANDS:
            importlib.import_module(f".{COMMANDS[cmd_name][0]}", __package__)
        install_option_checks(self)  # the shared option checks, on commands however they were imported
        return self.commands.get(cmd_name)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """The command list of ``--help`` from :data:`COMMANDS`, without importing the commands."""
        names = self.list_commands(ctx)
        limit = formatter.width - 6 - max((len(name) for name in names), default=0)
        rows = [
            (
                name,
                self.commands[name].get_short_help_str(limit)
                if name in self.commands
                else click.utils.make_default_short_help(COMMANDS[name][1], limit),
            )
            for name in names
        ]
        if rows:
            with formatter.section("Commands"):
                formatter.write_dl(rows)


def value_arg(text: str, si_unit: str) -> Any:
    """A command-line value: a quantity string, or a plain number in SI units."""
    from ..units import Q_, plain_number

    number = plain_number(text)
    return text if number is None else Q_(number, si_unit)


def check_effects_option(ctx, param, value):
    """Callback of every ``--effects`` option: names separated by commas, none empty and none twice (``",,"`` was
    read as no effect at all)."""
    if value is None or value == "":
        return value
    items = [e.strip() for e in value.split(",")]
    if any(not e for e in items):
        raise click.BadParameter(
            f"{value!r} has an empty name; give effect names separated by commas, e.g. 'seal_friction,fluid_inertia'",
            ctx=ctx,
            param=param,
        )
    twice = sorted({e for e in items if items.count(e) > 1})
    if twice:
        raise click.BadParameter(f"{', '.join(twice)} given twice", ctx=ctx, param=param)
    return ",".join(items)


def install_option_checks(group: click.Group) -> None:
    """Attach the shared checks to the options of every command of ``group`` that has them (``--effects``)."""
    for command in group.commands.values():
        for param in command.params:
            if param.name == "effects" and param.callback is None:
                param.callback = check_effects_option


#: ``--exclude-clipped`` of the commands that fit or diagnose a measurement (fit, diagnose): one definition.
exclude_clipped_option = click.option(
    "--exclude-clipped",
    is_flag=True,
    help="Leave force samples at a flat top or bottom out even where the detector is unsure "
    "(clipped samples it is sure of are left out anyway).",
)


def executor_options(default_jobs: str):
    """The ``--jobs N`` and ``--scheduler ADDRESS`` options of a command whose independent tasks run on an executor
    (:mod:`erdesign.executor`).  ``default_jobs`` is ``"all"`` (all cores) or ``"1"`` (in this process: for
    commands whose usual run is shorter than starting a pool).  The command receives ``executor``: a dict of
    ``jobs`` and ``scheduler`` for :func:`erdesign.executor.executor_for`.  Giving both is a usage error."""
    default_text = "all cores" if default_jobs == "all" else "1: in this process"

    def decorate(command):
        def settle(ctx, param, value):
            jobs, scheduler = ctx.params.pop("jobs", None), value
            if jobs is not None and scheduler:
                raise click.UsageError(
                    "--jobs and --scheduler: give one of them (the cluster's workers replace the local processes)"
                )
            if scheduler:
                return {"jobs": None, "scheduler": scheduler}
            if jobs is None:
                from ..executor import default_jobs as all_cores

                jobs = all_cores() if default_jobs == "all" else 1
            return {"jobs": jobs, "scheduler": None}

        command = click.option(
            "--scheduler",
            "executor",
            default=None,
            metavar="ADDRESS",
            callback=settle,
            help="Run the tasks on a Dask distributed cluster, e.g. tcp://10.0.0.5:8786 (its "
            "workers need erdesign and the files).",
        )(command)
        return click.option(
            "--jobs",
            default=None,
            type=WholeNumber(min=1),
            metavar="N",
            is_eager=True,
            help=f"Run the independent tasks on N local processes (default: {default_text}); the "
            "results are the same for any N.",
        )(command)

    return decorate


def emit_json(obj: dict) -> None:
    click.echo(json.dumps(obj, allow_nan=False))


def json_number(x: float | None) -> float | None:
    return None if x is None or not math.isfinite(x) else x


#: The type of every --seed option: numpy's generators take a whole number >= 0 (-1 was an internal error).
SEED = WholeNumber(min=0)

#: Library argument names in messages -> the flags that set them (the library names its own arguments).
LIBRARY_TO_FLAG = (
    ("exclude_clipped=True", "--exclude-clipped"),
    ("max_time", "--max-time"),
    ("control_reference: ", "--control-reference: "),
    # the sample-count limit (erdesign.limits.check_sample_count) names the arguments that made the count
    ("duration, rate: ", "--duration, --rate: "),
    ("duration, dt: ", "--duration, --dt: "),
    ("control_range: ", "--control-range: "),
)


def as_flags(text: str) -> str:
    """A library message with its argument names replaced by the command line's flags (:data:`LIBRARY_TO_FLAG`)."""
    for name, flag in LIBRARY_TO_FLAG:
        text = text.replace(name, flag)
    return text


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="erdesign")
def cli() -> None:
    """erdesign: design and diagnose ER and MR dampers with annular ducts."""


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``erdesign`` console script; returns the exit code."""
    args = sys.argv[1:] if argv is None else argv
    if "numpy" not in sys.modules:
        # One BLAS thread unless the user says otherwise: the matrices here are small and tall (an SVD of 60,000 x 13
        # per optimiser step), where a second thread only contends (10 x slower on a loaded two-core machine).  The
        # library limits its fits with threadpoolctl (identification/engine.py: solve) and its worker processes too
        # (executor.py), but threadpoolctl reaches only the libraries already loaded, and scipy loads its own
        # OpenBLAS on first use; so the command line, which owns its process, also sets the variables before any
        # BLAS is loaded.
        for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
            os.environ.setdefault(name, "1")

    def show_warning(message, category, filename, lineno, file=None, line=None):
        click.echo(f"warning: {one_line(message)}", err=True)

    warnings.showwarning = show_warning
    try:
        with _sigterm_as_exit():
            cli.main(args=args, prog_name="erdesign", standalone_mode=False)
            sys.stdout.flush()  # a reader that stopped (``| head``) is met here, not at the interpreter's exit
    except SystemExit as exc:
        if _reader_gone(exc):
            return _closed_pipe()
        if exc.code == SIGTERM_EXIT:
            click.echo("erdesign: stopped (SIGTERM); no output file was left half-written", err=True)
            return SIGTERM_EXIT
        raise
    except BrokenPipeError:
        return _closed_pipe()
    except click.exceptions.Abort:
        click.echo("erdesign: aborted", err=True)
        return 1
    except RecursionError:  # a Python limit reached by the input (deeply nested data), not a bug to report
        click.echo("error: the input is nested too deeply to read", err=True)
        return 1
    except click.UsageError as exc:
        command = exc.ctx.command_path if exc.ctx else "erdesign"
        click.echo(f"{command}: {one_line(exc.format_message())} (see '{command} --help')", err=True)
        return 2
    except click.ClickException as exc:
        click.echo(f"erdesign: {one_line(exc.format_message())}", err=True)
        return exc.exit_code or 1
    except ErdesignError as exc:
        click.echo(f"error: {one_line(exc)}", err=True)
        return 1
    except OSError as exc:
        click.echo(f"error: {one_line(exc)}", err=True)
        return 1
    except Exception as exc:  # a bug, not bad input: still one line, but say so
        click.echo(
            f"internal error: {type(exc).__name__}: {one_line(exc)} "
            "(please report this with the command that caused it)",
            err=True,
        )
        return 3
    return 0


#: Exit code of a command whose reader closed the pipe (the shell's 128 + signal; SIGTERM's is
#: :data:`erdesign.output.SIGTERM_EXIT`).
CLOSED_PIPE_EXIT = 128 + getattr(signal, "SIGPIPE", 13)


def _stop_workers(frame) -> bool:
    """SIGTERM during a command (:func:`_sigterm_as_exit`): stop the worker processes it started, then exit (True);
    False, with the signal sent again 50 ms on, while a worker is being started: stopped there, it would run on,
    unseen (and fail loudly)."""
    caller = frame
    while caller is not None:
        if caller.f_code.co_name == "start" and "multiprocessing" in caller.f_code.co_filename:
            timer = threading.Timer(0.05, os.kill, (os.getpid(), signal.SIGTERM))
            timer.daemon = True
            timer.start()  # the signal again once the worker is started and known
            return False
        caller = caller.f_back
    multiprocessing = sys.modules.get("multiprocessing")
    if multiprocessing is not None:
        for child in multiprocessing.active_children():
            child.terminate()
    return True


def _sigterm_as_exit():
    """While a command runs: SIGTERM stops the worker processes it started and raises SystemExit, so that its
    ``finally`` blocks run (a batch saves the records it finished, temporary files are removed, the pool is shut
    down).  SIGTERM's default ended the process at once: a batch's pool workers and fork server were left running,
    holding the terminal's pipes open.  :func:`erdesign.output.terminate_as_exit` with :func:`_stop_workers`."""
    return terminate_as_exit(_stop_workers)


def _reader_gone(exc: SystemExit) -> bool:
    """True for click's exit after a write to a closed pipe (it catches the EPIPE and exits 1 without a word)."""
    return exc.code == 1 and type(sys.stdout).__name__ == "_PacifyFlushWrapper"


def _closed_pipe() -> int:
    """The exit of a command whose reader closed its output (``erdesign ... --json | head -c 10``): no message
    and no traceback, as any Unix tool, and the code of a process ended by SIGPIPE (141), never 1 (bad input).
    Standard output is pointed at the null device so that the interpreter's last flush cannot fail again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.__stdout__.fileno())
        os.close(devnull)
    except (OSError, AttributeError, ValueError):  # pragma: no cover - no real stdout (in-process)
        pass
    return CLOSED_PIPE_EXIT


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())


def run() -> None:
    """Console-script wrapper: exit with :func:`main`'s code."""
    sys.exit(main())
