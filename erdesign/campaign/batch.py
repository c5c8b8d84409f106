"""Batches of records: one command (``identify``, ``fit`` or ``diagnose``) on every record of a campaign, each record an
independent task on an executor (:mod:`erdesign.executor`), the results in one table.

The table has one row per record, in input order (CONTRACTS.md section 6, ``erdesign batch``):

* ``record`` (the path as given), ``status`` (``ok`` / ``error``), ``error`` (one line, empty when ok);
* ``esr``, the command's own columns (``verdict``, ``missing_effect``, ``missing_effects``, ``findings`` for
  diagnose; ``at_bounds`` ...), and the parameters as columns ``NAME [unit]`` (SI; ``[-]`` when dimensionless);
* ``outlier`` and ``outlier_reason`` (:func:`flag_outliers`: the production-line check);
* ``seconds`` (wall time of the record's task), ``warnings``, and the task's key: ``sha256`` (of the record file's
  bytes), ``damper`` and ``effects``.

A bad record (a corrupt file, a missing column, a control the damper does not take) is a row with its error, never a
stopped batch: every task catches its own errors (:func:`run_task`).  The table is written atomically
(:mod:`erdesign.output`: a temporary file in the same folder, then renamed) while the batch runs, so a batch killed
half-way is resumed (``resume=True``) by running only the records whose key (file content, damper, effects) is not
in the table yet.

The batch holds no physics and no fitting: a row is built from the public results of
:func:`erdesign.identification.identify.identify`, :func:`erdesign.diagnosis.diagnose.calibrate` and
:func:`erdesign.diagnosis.diagnose.diagnose`, the functions behind ``erdesign identify``, ``fit`` and ``diagnose``.
"""

from __future__ import annotations

import csv
import hashlib
import math
import os
import time
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import ErdesignError, did_you_mean
from ..executor import Executor, executor_for
from ..output import atomic_output

__all__ = [
    "BatchTask",
    "BatchResult",
    "BatchCommand",
    "COMMANDS",
    "run_batch",
    "run_task",
    "make_tasks",
    "read_manifest",
    "flag_outliers",
    "read_table",
    "write_table",
    "file_sha256",
    "OUTLIER_Z",
    "OUTLIER_MIN_ROWS",
    "TABLE_FORMATS",
]

#: A record is an outlier when the robust z-score of any of its parameters (or of log ESR) exceeds this.
OUTLIER_Z = 5.0
#: Fewer ok rows than this in a group (one damper, one set of effects): no outlier is flagged.
OUTLIER_MIN_ROWS = 5
#: MAD of a normal distribution = 0.6745 sigma: 1.4826 MAD estimates sigma (Rousseeuw and Croux 1993).
MAD_TO_SIGMA = 1.4826
#: Output formats, by the file's suffix.
TABLE_FORMATS = (".csv", ".parquet")

# Columns every table has, in this order; the command's columns and the parameters go between ``esr`` and
# ``outlier``.
_HEAD = ("record", "status", "error", "esr")
_TAIL = ("outlier", "outlier_reason", "warnings", "seconds", "sha256", "damper", "effects")
_FLOATS = {"esr", "seconds"}


# --------------------------------------------------------------------------------------------------- the commands


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def _parameter_columns(model, values: Mapping[str, float]) -> dict[str, float]:
    """``{"NAME [unit]": SI value}`` for every parameter of a fitted model."""
    out = {}
    for name in model.parameter_names:
        unit = model.parameter(name).unit or "-"
        out[f"{name} [{unit}]"] = float(values[name])
    return out


def _read_for_damper(path: str, damper):
    """A measurement file checked against the damper, as ``erdesign fit`` and ``diagnose`` read it."""
    from ..data.measurement import read_for_damper

    return read_for_damper([path], damper)[0]


def _fit_row(path: str, damper_file: str, effects: str, options: Mapping[str, Any]) -> dict:
    from ..damper.files import load_damper
    from ..diagnosis.diagnose import calibrate, parameters_at_bounds

    damper = load_damper(damper_file)
    record = _read_for_damper(path, damper)
    result = calibrate(damper, record, effects, exclude_clipped=True if options.get("exclude_clipped") else None)
    return {
        "esr": result.esr,
        "findings": ",".join(sorted({f.kind for f in result.findings})),
        "at_bounds": "; ".join(parameters_at_bounds(result)),
        **_parameter_columns(result.model, result.values),
    }


def _diagnose_row(path: str, damper_file: str, effects: str, options: Mapping[str, Any]) -> dict:
    from ..damper.files import load_damper
    from ..diagnosis.diagnose import diagnose

    damper = load_damper(damper_file)
    record = _read_for_damper(path, damper)
    result = diagnose(
        damper,
        record,
        effects,
        exclude_clipped=True if options.get("exclude_clipped") else None,
        force_noise=options.get("force_noise"),
    )
    out = result.as_json()
    return {
        "esr": out["baseline_esr"],
        "verdict": out["verdict"],
        "missing_effect": out["missing_effect"] or "",
        "missing_effects": ",".join(out["missing_effects"]),
        "noise_floor_esr": out["noise_floor_esr"],
        "findings": ",".join(sorted({f["kind"] for f in out["findings"]})),
        **_parameter_columns(result.baseline.model, result.baseline.values),
    }


def _identify_row(path: str, damper_file: str | None, effects: str, options: Mapping[str, Any]) -> dict:
    from ..data.readers import read_records
    from ..identification.identify import control_reference_text, identify, result_json
    from ..models.registry import get_model

    name = options["model"]
    records = read_records(path, "auto", "record")
    if len(records) != 1:
        raise ErdesignError(f"{path} holds {len(records)} records; a batch takes one record per file")
    record = records[0]
    extra = {"damper": damper_file, "effects": tuple(e for e in effects.split(",") if e)} if name == "physics" else {}
    model = get_model(name, **extra)
    result = identify(
        model,
        record,
        starts=options.get("starts", 4),
        max_time=options.get("max_time"),
        decimate=options.get("decimate", 1),
        exclude_clipped=bool(options.get("exclude_clipped")),
    )
    reference = control_reference_text(result.model, record.control_kind)
    out = result_json(result, name, reference)
    return {
        "esr": out["esr"],
        "success": out["success"],
        "control_reference": reference or "",
        "at_bounds": ",".join(out["at_bounds"]),
        "not_identifiable": ",".join(out["not_identifiable"]),
        **{f"{n} [{p['unit'] or '-'}]": p["value"] for n, p in out["parameters_si"].items()},
    }


@dataclass(frozen=True)
class BatchCommand:
    """One command a batch can run: how a record becomes a row, and which options it takes."""

    name: str
    row: Callable[[str, Any, str, Mapping[str, Any]], dict]
    """``row(record_path, damper, effects, options) -> columns`` (raises on a bad record)."""
    options: tuple[str, ...]
    """Options of the command besides damper and effects (names as in :func:`run_batch`'s ``options``)."""
    needs_damper: bool
    columns: tuple[str, ...]
    """The command's own columns, before the parameters."""


#: The commands of ``erdesign batch``, by name.
COMMANDS: dict[str, BatchCommand] = {
    "identify": BatchCommand(
        "identify",
        _identify_row,
        ("model", "starts", "max_time", "decimate", "exclude_clipped"),
        False,
        ("success", "control_reference", "at_bounds", "not_identifiable"),
    ),
    "fit": BatchCommand("fit", _fit_row, ("exclude_clipped", "force_noise"), True, ("findings", "at_bounds")),
    "diagnose": BatchCommand(
        "diagnose",
        _diagnose_row,
        ("exclude_clipped", "force_noise"),
        True,
        ("verdict", "missing_effect", "missing_effects", "noise_floor_esr", "findings"),
    ),
}


# ------------------------------------------------------------------------------------------------------ the tasks


@dataclass(frozen=True)
class BatchTask:
    """Everything one record's task needs (picklable: it travels to a worker process or a Dask worker)."""

    command: str
    record: str
    """The record as the user named it (the ``record`` column)."""
    path: str
    """The file to read (absolute, so that a worker in another folder finds it)."""
    sha256: str
    damper: str = ""
    effects: str = ""
    options: tuple[tuple[str, Any], ...] = ()

    @property
    def key(self) -> tuple[str, str, str]:
        """What makes two tasks the same task: the file's content, the damper and the effects."""
        return (self.sha256, self.damper, self.effects)


def run_task(task: BatchTask) -> dict:
    """One record's row.  Never raises: any error becomes ``status = "error"`` with the message on one line, and the
    warnings the command gives are kept in the row (``warnings``)."""
    command = COMMANDS[task.command]
    row = {"record": task.record, "sha256": task.sha256, "damper": task.damper, "effects": task.effects}
    start = time.perf_counter()
    # catch_warnings is process-wide: exact in a pool worker or a one-thread Dask worker; on a Dask worker running
    # several threads a warning may land in another record's row (the other columns are unaffected)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            columns = command.row(task.path, task.damper or None, task.effects, dict(task.options))
            row.update(status="ok", error="", **columns)
        except ErdesignError as exc:
            row.update(status="error", error=_one_line(exc))
        except OSError as exc:
            row.update(status="error", error=_one_line(f"{task.record}: {exc.strerror or exc}"))
        except Exception as exc:  # noqa: BLE001  (a bug, not bad input: still a row, and it says so)
            row.update(status="error", error=_one_line(f"internal error: {type(exc).__name__}: {exc}"))
    if task.path != task.record:  # messages name the record as the user gave it
        row["error"] = row["error"].replace(task.path, task.record)
    row["warnings"] = "; ".join(dict.fromkeys(_one_line(w.message) for w in caught))
    row["seconds"] = time.perf_counter() - start
    return row


def file_sha256(path: str | Path) -> str:
    """sha256 of a file's bytes (hex), or "" when it cannot be read (its task then says why)."""
    digest = hashlib.sha256()
    if not Path(path).is_file():  # a folder, a device (/dev/zero never ends) or nothing: its task says why
        return ""
    try:
        with open(path, "rb") as fh:
            for block in iter(lambda: fh.read(1 << 20), b""):
                digest.update(block)
    except OSError:
        return ""
    return digest.hexdigest()


def _damper_reference(damper: str | None, folder: Path | None) -> str:
    """A damper file as an absolute path (relative to ``folder`` when given), or a bundled example's name."""
    if not damper:
        return ""
    from ..damper.files import example_names

    path = Path(damper) if folder is None else folder / damper
    if path.exists() or damper not in example_names():
        return str(path.resolve())
    return damper


def read_manifest(path: str | Path) -> list[dict[str, str]]:
    """The rows of a manifest CSV: ``record`` (required), ``damper`` and ``effects`` (optional); paths relative to
    the manifest's folder.  Returns ``[{"record", "path", "damper", "effects"}, ...]`` (``damper`` absolute)."""
    import io

    from ..limits import MAX_TOML_BYTES, decode_text, read_input_bytes

    path = Path(path)
    try:
        # the one reader of input files: a size limit, binary and UTF-16 refused, a named pipe refused (not waited on)
        text = decode_text(read_input_bytes(path, MAX_TOML_BYTES, "a manifest CSV file"), str(path), "a manifest CSV")
        with io.StringIO(text, newline="") as fh:
            reader = csv.DictReader(fh)
            fields = [f.strip() for f in (reader.fieldnames or [])]
            if "record" not in fields:
                hint = did_you_mean(fields[0] if fields else "", ["record"])
                if len(fields) == 1 and ";" in fields[0]:
                    hint = " (the columns are separated by ';': a manifest separates them by ',')"
                raise ErdesignError(
                    f"--manifest: {path} has no 'record' column (columns: {', '.join(fields) or 'none'}){hint}"
                )
            twice = sorted({f for f in fields if fields.count(f) > 1})
            if twice:  # 'record,record': the second was taken without a word
                raise ErdesignError(f"--manifest: {path} line 1: the column {twice[0]!r} appears twice")
            unknown = sorted(set(fields) - {"record", "damper", "effects"})
            if unknown:
                raise ErdesignError(
                    f"--manifest: {path}: unknown column(s) {', '.join(map(repr, unknown))}; a manifest has "
                    "'record' and optional 'damper' and 'effects'"
                )
            rows = []
            for raw in reader:
                line = reader.line_num  # the file's line (blank lines are skipped, not counted away)
                if raw.get(None):  # 'a.csv,seal_friction,fluid_inertia': the last effect was dropped
                    raise ErdesignError(
                        f"--manifest: {path} line {line}: {len(fields) + len(raw[None])} cells for {len(fields)} "
                        'columns; quote a cell that holds commas (effects: "seal_friction,fluid_inertia")'
                    )
                row = {k.strip(): (v or "").strip() for k, v in raw.items() if k is not None}
                if not row.get("record"):
                    raise ErdesignError(f"--manifest: {path} line {line}: empty 'record'")
                if [row.get(f, "") for f in fields] == fields:
                    raise ErdesignError(f"--manifest: {path} line {line}: the header again; remove the line")
                rows.append(
                    {
                        "record": row["record"],
                        "path": str((path.parent / row["record"]).resolve()),
                        "damper": _damper_reference(row.get("damper"), path.parent),
                        "effects": row.get("effects", ""),
                    }
                )
    except FileNotFoundError:
        raise ErdesignError(f"--manifest: no such file {path}") from None
    except ErdesignError as exc:
        raise ErdesignError(f"--manifest: {_one_line(exc).removeprefix('--manifest: ')}") from None
    except OSError as exc:  # a folder, no permission, a symbolic link loop
        raise ErdesignError(f"--manifest: {path}: cannot be read ({exc.strerror or exc})") from None
    except (UnicodeDecodeError, csv.Error) as exc:
        raise ErdesignError(f"--manifest: {path} is not a CSV file ({_one_line(exc)})") from None
    if not rows:
        raise ErdesignError(f"--manifest: {path} lists no record")
    return rows


def _shown(value: Any) -> str:
    return f"{type(value).__name__} {' '.join(repr(value).split())[:60]}"


def _check_batch_arguments(records, damper, effects, options) -> None:
    """The arguments of :func:`make_tasks` of the right kinds, or an error naming the argument: a text as
    ``records`` was a batch of its characters ('A.csv': records 'A', '.', 'c', ...), and a None, a Measurement, a
    Damper or a list of options failed inside Python ("expected str, bytes or os.PathLike object")."""
    if isinstance(records, (str, bytes, os.PathLike)):
        raise ErdesignError(
            f"records: expected a list of record files, got {_shown(records)}; for one, give [{records!r}]"
        )
    for i, r in enumerate(records or ()):
        if not isinstance(r, (str, os.PathLike)) or not str(r).strip():
            raise ErdesignError(f"records[{i}]: expected the name of a record file (a str or Path), got {_shown(r)}")
    if damper is not None and not isinstance(damper, (str, os.PathLike)):
        raise ErdesignError(
            f"damper: expected the name of a damper file or of a bundled example (a str or Path), got {_shown(damper)}"
        )
    if not isinstance(effects, str):
        raise ErdesignError(f"effects: expected effect names separated by commas (a str), got {_shown(effects)}")
    if options is not None and not isinstance(options, Mapping):
        raise ErdesignError(f"options: expected a mapping of option names to values, got {_shown(options)}")


def make_tasks(
    command: str,
    records: Sequence[str] = (),
    *,
    manifest: str | Path | None = None,
    damper: str | None = None,
    effects: str = "",
    options: Mapping[str, Any] | None = None,
) -> list[BatchTask]:
    """The tasks of a batch, in input order: the ``records`` given, or the rows of a ``manifest`` (whose ``damper``
    and ``effects``, when given on a row, replace the batch's).  Checks the command and its options."""
    if command not in COMMANDS:
        raise ErdesignError(f"batch: unknown command {command!r}; one of {', '.join(COMMANDS)}")
    spec = COMMANDS[command]
    _check_batch_arguments(records, damper, effects, options)
    options = {k: v for k, v in (options or {}).items() if v is not None}
    misplaced = sorted(set(options) - set(spec.options))
    if misplaced:
        raise ErdesignError(f"batch {command}: option {', '.join(misplaced)} does not apply to {command}")
    if command == "identify" and not options.get("model"):
        raise ErdesignError("batch identify: give the model (--model NAME)")
    if bool(records) == (manifest is not None):
        raise ErdesignError(
            f"batch {command}: give the records or a manifest (--manifest), not both"
            if records
            else f"batch {command}: give the records, or a manifest (--manifest)"
        )
    if manifest is not None:
        entries = read_manifest(manifest)
        for e in entries:
            e["damper"] = e["damper"] or _damper_reference(damper, None)
            e["effects"] = e["effects"] or effects
    else:
        entries = [
            {"record": r, "path": str(Path(r).resolve()), "damper": _damper_reference(damper, None), "effects": effects}
            for r in records
        ]
    needs_damper = spec.needs_damper or options.get("model") == "physics"
    if needs_damper and any(not e["damper"] for e in entries):
        raise ErdesignError(f"batch {command}: give the damper (--damper D.toml, or a 'damper' column in the manifest)")
    frozen = tuple(sorted(options.items()))
    return [
        BatchTask(command, e["record"], e["path"], file_sha256(e["path"]), e["damper"], e["effects"], frozen)
        for e in entries
    ]


# ------------------------------------------------------------------------------------------------------ outliers


def flag_outliers(
    rows: list[dict], columns: Sequence[str], *, z_max: float = OUTLIER_Z, min_rows: int = OUTLIER_MIN_ROWS
) -> None:
    """Flag the rows whose parameters sit far from the batch's distribution (sets ``outlier`` and
    ``outlier_reason`` in place).

    Within each group of ok rows of one damper and one set of effects (a population of like records), for every
    parameter column and for log10 of the ESR, the robust z-score is

    .. math:: z_i = \\frac{x_i - \\operatorname{median}(x)}{1.4826\\,\\operatorname{MAD}(x)}

    (1.4826 MAD estimates the standard deviation of a normal sample; Rousseeuw and Croux 1993), and a row with
    :math:`|z| >` ``z_max`` on any of them is an outlier.  The scale is floored at 1e-9 |median| so that a parameter
    that is the same on every row (a fixed one) flags nothing.  Groups of fewer than ``min_rows`` ok rows are not
    judged.  Error rows are never outliers (their ``status`` says enough)."""
    for row in rows:
        row["outlier"] = False
        row["outlier_reason"] = ""
    groups: dict[tuple, list[dict]] = {}
    for row in rows:
        if row.get("status") == "ok":
            groups.setdefault((row.get("damper", ""), row.get("effects", "")), []).append(row)
    for members in groups.values():
        if len(members) < min_rows:
            continue
        for col in ["esr", *columns]:
            values = [_number(r.get(col)) for r in members]
            if col == "esr":
                values = [math.log10(v) if v is not None and v > 0 else None for v in values]
            finite = sorted(v for v in values if v is not None and math.isfinite(v))
            if len(finite) < min_rows:
                continue
            median = _median(finite)
            scale = max(MAD_TO_SIGMA * _median([abs(v - median) for v in finite]), 1e-9 * abs(median), 1e-300)
            for row, v in zip(members, values):
                if v is None or not math.isfinite(v):
                    continue
                z = (v - median) / scale
                if abs(z) > z_max:
                    row["outlier"] = True
                    what = "log10(esr)" if col == "esr" else col
                    row["outlier_reason"] = "; ".join(filter(None, [row["outlier_reason"], f"{what} z={z:+.1f}"]))


def _median(values: Sequence[float]) -> float:
    s = sorted(values)
    n = len(s)
    return s[n // 2] if n % 2 else 0.5 * (s[n // 2 - 1] + s[n // 2])


def _number(x) -> float | None:
    if x is None or x == "" or isinstance(x, bool):
        return None
    try:
        return float(x)
    except (TypeError, ValueError):
        return None


# ------------------------------------------------------------------------------------------------------ the table


def _columns(rows: Sequence[dict], command: str) -> list[str]:
    """The table's columns: the fixed head, the command's columns, the parameters (first seen first), the tail."""
    own = list(COMMANDS[command].columns) if command in COMMANDS else []
    params = []
    for row in rows:
        params.extend(k for k in row if k.endswith("]") and k not in params)
    return [*_HEAD, *own, *params, *_TAIL]


def _is_float_column(name: str) -> bool:
    return name in _FLOATS or name.endswith(("]", "_esr"))


def write_table(
    path: str | Path, rows: Sequence[dict], columns: Sequence[str], *, overwrite: bool = False, option: str = "--out"
) -> None:
    """Write the table atomically (:func:`erdesign.output.atomic_output`: a temporary file in the same folder, synced,
    then given the name; a reader, or a batch killed while writing, sees the old table or the new one, never half of
    one).  An existing ``path`` only with ``overwrite`` (the batch's own table, saved again as it runs)."""
    path = Path(path)
    with atomic_output(path, overwrite=overwrite, option=option) as tmp:
        if path.suffix.lower() == ".parquet":
            _write_parquet(tmp, rows, columns)
        else:
            with open(tmp, "w", newline="", encoding="utf-8") as fh:
                writer = csv.writer(fh)
                writer.writerow(columns)
                for row in rows:
                    writer.writerow([_cell(row.get(c)) for c in columns])


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else ""
    return str(value)


def _pyarrow():
    try:
        import pyarrow
        import pyarrow.parquet
    except ImportError:
        raise ErdesignError("--out: a .parquet table needs pyarrow (pip install pyarrow), or write a .csv") from None
    return pyarrow


def _write_parquet(path: Path, rows: Sequence[dict], columns: Sequence[str]) -> None:
    pa = _pyarrow()
    arrays = {}
    for c in columns:
        values = [row.get(c) for row in rows]
        if c == "outlier" or c == "success":
            arrays[c] = pa.array([None if v is None or v == "" else bool(v) for v in values], pa.bool_())
        elif _is_float_column(c):
            arrays[c] = pa.array([_number(v) for v in values], pa.float64())
        else:
            arrays[c] = pa.array(["" if v is None else str(v) for v in values], pa.string())
    pa.parquet.write_table(pa.table(arrays), path)


def read_table(path: str | Path) -> list[dict]:
    """The rows of a batch table (CSV or Parquet) as written by :func:`write_table`, numbers as floats."""
    path = Path(path)
    if path.suffix.lower() == ".parquet":
        pa = _pyarrow()
        try:
            rows = pa.parquet.read_table(path).to_pylist()
        except (OSError, pa.ArrowException) as exc:
            raise ErdesignError(f"--resume: cannot read {path}: {_one_line(exc)}") from None
    else:
        try:
            with open(path, newline="", encoding="utf-8") as fh:
                rows = list(csv.DictReader(fh))
        except (UnicodeDecodeError, csv.Error) as exc:
            raise ErdesignError(f"--resume: cannot read {path}: {_one_line(exc)}") from None
        for row in rows:
            for c, v in row.items():
                if c in ("outlier", "success"):
                    row[c] = None if v == "" else v == "true"
                elif _is_float_column(c):
                    row[c] = None if v in ("", None) else float(v)
    if rows and not {"sha256", "status", "record"} <= set(rows[0]):
        raise ErdesignError(f"--resume: {path} is not a batch table (no 'record', 'status' and 'sha256' columns)")
    return rows


# ---------------------------------------------------------------------------------------------------- the batch


@dataclass
class BatchResult:
    """The table of a batch (rows in input order) and how it was made."""

    command: str
    rows: list[dict]
    columns: list[str]
    reused: int = 0
    """Rows taken from the table being resumed (not run again)."""
    seconds: float = 0.0
    executor: str = ""
    out: str | None = None

    @property
    def errors(self) -> int:
        return sum(r["status"] != "ok" for r in self.rows)

    @property
    def outliers(self) -> int:
        return sum(bool(r.get("outlier")) for r in self.rows)

    def summary(self) -> dict:
        """The ``erdesign batch --json`` object."""
        ran = len(self.rows) - self.reused
        return {
            "command": self.command,
            "records": len(self.rows),
            "ok": len(self.rows) - self.errors,
            "errors": self.errors,
            "outliers": self.outliers,
            "reused": self.reused,
            "ran": ran,
            "seconds": self.seconds,
            "records_per_second": ran / self.seconds if self.seconds > 0 else None,
            "executor": self.executor,
            "out": self.out,
        }


def run_batch(
    command: str,
    records: Sequence[str] = (),
    *,
    manifest: str | Path | None = None,
    damper: str | None = None,
    effects: str = "",
    options: Mapping[str, Any] | None = None,
    out: str | Path | None = None,
    resume: bool = False,
    executor: Executor | Any = None,
    jobs: int | None = None,
    scheduler: str | Any = None,
    progress: Callable[[int, int, float], None] | None = None,
    save_every: float = 2.0,
) -> BatchResult:
    """Run ``command`` (``"identify"``, ``"fit"`` or ``"diagnose"``) on every record; one row per record.

    Parameters
    ----------
    command : str
        A name of :data:`COMMANDS`.
    records : sequence of str
        Record files; or ``manifest``: a CSV with ``record`` and optional ``damper`` and ``effects`` columns.
    damper, effects : str
        The damper file (or bundled example name) and effects of every record (a manifest row may name its own).
    options : mapping
        The command's options: ``exclude_clipped``, ``force_noise`` (fit, diagnose); ``model``, ``starts``,
        ``max_time``, ``decimate``, ``exclude_clipped`` (identify).  None values are left out.
    out : path, optional
        The table (``.csv`` or ``.parquet``), rewritten atomically at least every ``save_every`` seconds while the
        batch runs and at its end.  An existing table is refused unless ``resume``.
    resume : bool
        Keep the rows of ``out`` whose key (sha256 of the record file, damper, effects) matches a record, and run
        only the others.
    executor, jobs, scheduler
        Where the tasks run (:func:`erdesign.executor.executor_for`; default serial).  The rows are the same on
        every executor, ``seconds`` apart.
    progress : callable, optional
        ``progress(done, total, elapsed_seconds)`` after each finished record (records kept by ``resume`` count as
        done from the start).

    Returns
    -------
    BatchResult
    """
    started = time.perf_counter()
    if out is not None:
        out = Path(out)
        if out.suffix.lower() not in TABLE_FORMATS:
            raise ErdesignError(f"--out: {out} must end in .csv or .parquet")
        if out.exists() and not resume:
            raise ErdesignError(
                f"--out: {out} exists; add --resume to continue that batch, or choose another file "
                "(it is never overwritten)"
            )
        if not out.parent.is_dir():
            raise ErdesignError(f"--out: no such folder {out.parent}")
        if out.suffix.lower() == ".parquet":
            _pyarrow()
    tasks = make_tasks(command, records, manifest=manifest, damper=damper, effects=effects, options=options)
    rows: list[dict | None] = [None] * len(tasks)
    if resume and out is not None and out.exists():
        kept = {}
        for row in read_table(out):
            if row.get("sha256"):
                kept.setdefault((row["sha256"], row.get("damper") or "", row.get("effects") or ""), row)
        for i, task in enumerate(tasks):
            if task.key in kept:
                rows[i] = {**kept[task.key], "record": task.record}
    reused = sum(r is not None for r in rows)
    todo = [i for i, r in enumerate(rows) if r is None]

    saved = [bool(resume)]  # the first save creates the table exclusively (unless resuming it)

    def save() -> None:
        done = [r for r in rows if r is not None]
        write_table(out, done, _columns(done, command), overwrite=saved[0])
        saved[0] = True

    owned = not isinstance(executor, Executor)
    ex = executor_for(executor, jobs=jobs, scheduler=scheduler)
    last_save = time.perf_counter()
    done = reused
    try:
        if progress is not None:
            progress(done, len(tasks), time.perf_counter() - started)
        for j, row in ex.imap(run_task, [tasks[i] for i in todo]):
            rows[todo[j]] = row
            done += 1
            if progress is not None:
                progress(done, len(tasks), time.perf_counter() - started)
            if out is not None and time.perf_counter() - last_save >= save_every:
                save()
                last_save = time.perf_counter()
    except BaseException:
        if out is not None and done > reused:
            save()  # an interrupted batch keeps what it finished, for --resume
        raise
    finally:
        if owned:
            ex.close()
    columns = _columns(rows, command)
    flag_outliers(rows, [c for c in columns if c.endswith("]")])
    if out is not None:
        save()
    return BatchResult(
        command,
        list(rows),
        columns,
        reused=reused,
        seconds=time.perf_counter() - started,
        executor=ex.description,
        out=None if out is None else str(out),
    )
