"""``erdesign batch {identify,fit,diagnose} RECORDS... | --manifest M.csv [options of that command] [--jobs N]
[--scheduler ADDRESS] --out T.csv|T.parquet [--resume]``: one command on every record, one row per record
(:mod:`erdesign.campaign.batch`)."""

from __future__ import annotations

import sys
import time

import click

from .main import NumberRange, cli, emit_json, WholeNumber, executor_options, json_number

__all__ = ["batch"]


_EXAMPLES = """
\b
Examples:
  erdesign batch diagnose records/*.csv --damper makris.toml --out diagnoses.csv
  erdesign batch fit --manifest line.csv --jobs 4 --out fits.parquet
  erdesign batch identify records/*.csv --model bingham --scheduler tcp://10.0.0.5:8786 --out ids.csv
  erdesign batch diagnose records/*.csv --damper makris.toml --out diagnoses.csv --resume
"""


class Progress:
    """Records done / total, rate and time left on stderr: one line rewritten in place on a terminal; elsewhere
    (a log, a test) a line at most every ``every`` seconds and at the end."""

    def __init__(self, every: float = 10.0):
        self.tty = sys.stderr.isatty()
        self.every = every
        self.last = -float("inf")
        self.first: tuple[int, float] | None = None

    def __call__(self, done: int, total: int, elapsed: float) -> None:
        if self.first is None:
            self.first = (done, elapsed)  # records kept by --resume do not count in the rate
            return
        now = time.perf_counter()
        if not self.tty and done < total and now - self.last < self.every:
            return
        self.last = now
        ran, spent = done - self.first[0], elapsed - self.first[1]
        rate = ran / spent if spent > 0 else 0.0
        left = f", {(total - done) / rate:.0f} s left" if rate > 0 and done < total else ""
        line = f"batch: {done}/{total} records, {rate:.3g} records/s{left}"
        if self.tty:
            click.echo(f"\r{line}\x1b[K", err=True, nl=done >= total)
        else:
            click.echo(line, err=True)


@cli.command(epilog=_EXAMPLES)
@click.argument("command", type=click.Choice(["identify", "fit", "diagnose"]))
@click.argument("records", nargs=-1, metavar="RECORDS...")
@click.option(
    "--manifest",
    default=None,
    metavar="M.csv",
    help="A CSV of the records: a 'record' column, optional 'damper' and 'effects' columns (paths "
    "relative to the manifest).",
)
@click.option(
    "--damper",
    "damper_file",
    default=None,
    metavar="DAMPER.toml",
    help="Damper file or bundled example name (fit, diagnose; identify --model physics).",
)
@click.option("--effects", default="", help="Effects in the model, comma separated (fit, diagnose, physics).")
@click.option(
    "--exclude-clipped",
    is_flag=True,
    default=None,
    help="Leave force samples at a flat top or bottom out even where the detector is unsure.",
)
@click.option("--force-noise", default=None, metavar="F", help='The load cell\'s noise, e.g. "5 N" (fit, diagnose).')
@click.option("--model", "model_name", default=None, help="Registry name (identify; see 'erdesign models').")
@click.option("--starts", default=None, type=WholeNumber(1, 100), help="Most local starts (identify; default 4).")
@click.option(
    "--max-time",
    default=None,
    type=NumberRange(min=0.1),
    metavar="SECONDS",
    help="Wall-time budget of each record's identification (identify).",
)
@click.option(
    "--decimate",
    default=None,
    type=WholeNumber(1, 1000),
    metavar="K",
    help="Fit on every K-th sample only (identify).",
)
@executor_options(default_jobs="all")
@click.option("--out", "out", required=True, metavar="T.csv|T.parquet", help="The table to write.")
@click.option(
    "--resume",
    is_flag=True,
    help="Keep the rows already in the table (same file content, damper and effects) and run only the rest.",
)
@click.option(
    "--save-every",
    default=2.0,
    show_default=True,
    type=NumberRange(min=0),
    metavar="SECONDS",
    help="How often the table is rewritten while the batch runs (0: after every record).",
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON summary object instead of a summary line.")
def batch(
    command: str,
    records: tuple[str, ...],
    manifest: str | None,
    damper_file: str | None,
    effects: str,
    exclude_clipped: bool | None,
    force_noise: str | None,
    model_name: str | None,
    starts: int | None,
    max_time: float | None,
    decimate: int | None,
    executor: dict,
    out: str,
    resume: bool,
    save_every: float,
    as_json: bool,
) -> None:
    """Run identify, fit or diagnose on every record; one row per record in one table.

    A bad record is a row with its error, never a stopped batch.  The table is rewritten atomically while the
    batch runs, so that a batch stopped half-way continues with --resume.  Outliers (a parameter or the ESR far
    from the batch's median, robust z-score above 5) are flagged in the 'outlier' column.
    """
    from ..campaign.batch import run_batch
    from .diagnose import force_noise_option

    force_noise_option(force_noise)  # a bad value is named before any record runs
    options = {
        "exclude_clipped": exclude_clipped,
        "force_noise": force_noise,
        "model": model_name,
        "starts": starts,
        "max_time": max_time,
        "decimate": decimate,
    }
    result = run_batch(
        command,
        records,
        manifest=manifest,
        damper=damper_file,
        effects=effects,
        options=options,
        out=out,
        resume=resume,
        **executor,
        progress=Progress(),
        save_every=save_every,
    )
    summary = result.summary()
    if as_json:
        emit_json({k: json_number(v) if isinstance(v, float) else v for k, v in summary.items()})
        return
    click.echo(
        f"{summary['records']} records ({summary['ran']} run, {summary['reused']} kept from the table): "
        f"{summary['ok']} ok, {summary['errors']} errors, {summary['outliers']} outliers, "
        f"{summary['seconds']:.1f} s on {summary['executor']} -> {out}"
    )
