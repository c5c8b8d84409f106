"""Benchmark: how often ``erdesign diagnose`` names the right missing effect on records of the independent truth rig.

Every case of the catalogue (:func:`erdesign.simulation.truthrig.cases.benchmark_cases`) is simulated by the truth rig,
written to a CSV file and read back with :func:`erdesign.data.measurement.read_measurement` (the reader users use), and
diagnosed with :func:`erdesign.diagnosis.diagnose.diagnose`.  Correct means: a clean record -> verdict
``nothing_missing``; a mechanism outside the effect library -> ``unexplained``; library mechanism(s) ->
``missing_effect`` naming one of them.  An exception is a failure of the tool (``diagnose`` must never crash) and is
listed with its message.

Run::

    python benchmarks/bench_diagnosis_accuracy.py --subset fast                 # seven cases, about a minute
    python benchmarks/bench_diagnosis_accuracy.py --subset issue23 --jobs 1 --no-detectability --out i23.json \
        --write-docs                                 # the classes of issue 23, docs/diagnosis_benchmark_issue23.md
    python benchmarks/bench_diagnosis_accuracy.py --jobs 2 --out results.json --write-docs   # the catalogue

Options: ``--subset full|core|issue23|fast`` (``full`` = ``core``, the catalogue by true class, + ``issue23``, its
classes reported one by one as well), ``--jobs N`` (processes, default 2), ``--cases PATTERN`` (shell pattern or
substring of case names), ``--out FILE`` (JSON of every case), ``--write-docs`` (docs/diagnosis_benchmark.md),
``--no-long`` (skip the timing of one 60 s record at 1 kHz, target < 30 s), ``--no-detectability``,
``--from-json FILE`` (summarise a previous ``--out`` file, with ``--write-docs`` rewrite the page from it).
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):  # one core per process
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import fnmatch  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
import traceback  # noqa: E402
from collections import Counter, defaultdict  # noqa: E402
from concurrent.futures import ProcessPoolExecutor, as_completed  # noqa: E402
from pathlib import Path  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
SUBSETS = ("full", "core", "issue23", "fast")  # erdesign.simulation.truthrig.cases.SUBSETS (imported late)
DOCS = ROOT / "docs" / "diagnosis_benchmark.md"
LONG_TARGET = 30.0
#: Benchmark class of the cases of the core catalogue (the issue-23 classes carry their own, ``Case.group``).
CORE = "core"
VERDICTS = ("nothing_missing", "unexplained", "missing_effect")


# ---------------------------------------------------------------------------------------------------- one case
def verdict_of(diagnosis) -> str:
    """The three-way verdict; derived from ``missing_effect`` where the Diagnosis does not give one yet."""
    v = getattr(diagnosis, "verdict", None)
    if v:
        return str(v)
    return "missing_effect" if getattr(diagnosis, "missing_effect", None) else "nothing_missing"


def is_correct(case, verdict: str, missing: str | None, findings=()) -> bool:
    """Right verdict (or one of the case's also-accepted ones), and the data finding the case's artefact makes."""
    if getattr(case, "finding", "") and case.finding not in findings:
        return False
    if verdict in getattr(case, "also_accepted", ()):
        return True
    if case.expected in ("nothing_missing", "unexplained"):
        return verdict == case.expected
    return verdict == "missing_effect" and missing in case.accepted


def _finite(x):
    try:
        x = float(x)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


def _error(exc: BaseException) -> str:
    last = traceback.extract_tb(exc.__traceback__)[-1] if exc.__traceback__ else None
    where = f" ({Path(last.filename).name}:{last.lineno})" if last else ""
    return f"{type(exc).__name__}: {exc}{where}"


def run_case(case, detectability: bool = True) -> dict:
    """Simulate, write, read back and diagnose one case; never raises."""
    from erdesign.data.measurement import read_measurement
    from erdesign.diagnosis.diagnose import diagnose

    row = {
        "name": case.name,
        "group": case.group or CORE,
        "damper": case.damper,
        "excitation": case.excitation,
        "noise": case.noise,
        "kind": case.kind,
        "size": case.size,
        "mechanisms": {k: dict(v) for k, v in case.mechanisms.items()},
        "expected": case.expected,
        "accepted": sorted(case.accepted),
        "seed": case.seed,
        "duration_s": case.duration,
        "rate_Hz": case.rate,
        "samples": None,
        "verdict": None,
        "missing_effect": None,
        "baseline_esr": None,
        "noise_floor_esr": None,
        "ranking": None,
        "correct": False,
        "error": None,
        "error_stage": None,
        "time_s": None,
        "effect_esr": None,
        "effect_size_over_noise": None,
        "visible_over_noise": None,
    }
    try:
        rec = case.make()
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / f"{case.name}.csv"
            rec.write(path)
            record = read_measurement(path)
        damper = case.load_damper()
        row["samples"] = len(record)
    except Exception as exc:  # a failure of the truth rig or the reader, not of diagnose
        row.update(error=_error(exc), error_stage="record")
        return row
    if isinstance(detectability, dict):  # measured by an earlier run on the same case
        row.update({k: detectability.get(k) for k in ("effect_esr", "effect_size_over_noise", "visible_over_noise")})
    elif detectability:
        try:
            det = case.detectability()
            row["effect_esr"] = _finite(det["effect_esr"])
            row["effect_size_over_noise"] = _finite(det["effect_size_over_noise"])
            row["visible_over_noise"] = _finite(det["visible_over_noise"])
        except Exception as exc:
            row["detectability_error"] = _error(exc)
    t0 = time.perf_counter()
    try:
        d = diagnose(damper, record)
    except Exception as exc:
        row.update(error=_error(exc), error_stage="diagnose", time_s=time.perf_counter() - t0)
        return row
    row["time_s"] = time.perf_counter() - t0
    verdict = verdict_of(d)
    missing = getattr(d, "missing_effect", None)
    findings = [f.kind for f in getattr(d, "findings", ())]
    row.update(
        verdict=verdict,
        missing_effect=missing,
        baseline_esr=_finite(getattr(d, "baseline_esr", None)),
        findings=findings,
        noise_floor_esr=_finite(getattr(d, "noise_floor_esr", None)),
        ranking=[
            [getattr(c, "effect", "?"), _finite(getattr(c, "esr", None))]
            for c in (getattr(d, "ranking", None) or [])[:3]
        ],
        correct=is_correct(case, verdict, missing, findings),
    )
    return row


def run_long(detail: bool = True) -> dict:
    """Diagnose one 60 s record sampled at 1 kHz (timing requirement: under 30 s)."""
    from dataclasses import replace

    from erdesign.data.measurement import read_measurement
    from erdesign.diagnosis.diagnose import diagnose
    from erdesign.simulation.truthrig.cases import benchmark_cases

    base = next(c for c in benchmark_cases("full") if c.name.startswith("seal_friction-large-mr_valve-"))
    case = replace(base, name="long-60s-1kHz", duration=60.0, rate=1000.0)
    out = {
        "name": case.name,
        "samples": None,
        "time_s": None,
        "verdict": None,
        "missing_effect": None,
        "error": None,
        "target_s": LONG_TARGET,
    }
    try:
        rec = case.make()
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "long.csv"
            rec.write(path)
            record = read_measurement(path)
        out["samples"] = len(record)
        t0 = time.perf_counter()
        d = diagnose(case.load_damper(), record)
        out.update(
            time_s=time.perf_counter() - t0, verdict=verdict_of(d), missing_effect=getattr(d, "missing_effect", None)
        )
    except Exception as exc:
        out["error"] = _error(exc)
    return out


# ---------------------------------------------------------------------------------------------------- summary
def _true_class(row) -> str:
    if row["kind"] == "clean":
        return "clean"
    if row["kind"] == "out_of_library":
        return "out of library"
    if row["kind"] == "pair":
        return "pair"
    return row["expected"]


def _said(row) -> str:
    if row["error"]:
        return "exception"
    if row["verdict"] == "missing_effect":
        return row["missing_effect"] or "missing_effect (no name)"
    return row["verdict"]


def _visible(row):
    """What no recalibration of the clean damper removes, over the noise (``visible_over_noise`` of
    :func:`erdesign.simulation.truthrig.cases.effect_size_over_noise`); runs before it had only
    ``effect_size_over_noise``."""
    v = row.get("visible_over_noise")
    return v if v is not None else row.get("effect_size_over_noise")


def summarise(rows: list[dict]) -> dict:
    from erdesign.effects import EFFECT_NAMES
    from erdesign.simulation.truthrig.cases import UNDETECTABLE

    n = len(rows)
    classes = ["clean", "out of library", *EFFECT_NAMES, "pair"]
    per_class = {}
    for cls in classes:
        sel = [r for r in rows if _true_class(r) == cls]
        if sel:
            per_class[cls] = {"cases": len(sel), "correct": sum(r["correct"] for r in sel)}
    columns = ["nothing_missing", "unexplained", *EFFECT_NAMES, "exception"]
    confusion = {cls: Counter(_said(r) for r in rows if _true_class(r) == cls) for cls in classes}
    extra = sorted({s for c in confusion.values() for s in c} - set(columns))
    columns += extra
    by = {}
    for key in ("damper", "excitation", "noise", "size"):
        groups = defaultdict(list)
        for r in rows:
            groups[str(r[key]) or "-"].append(r["correct"])
        by[key] = {k: [sum(v), len(v)] for k, v in sorted(groups.items())}
    per_group = {}
    for r in rows:
        g = per_group.setdefault(r.get("group", CORE), {"cases": 0, "correct": 0, "time_max_s": 0.0})
        g["cases"] += 1
        g["correct"] += bool(r["correct"])
        g["time_max_s"] = max(g["time_max_s"], r["time_s"] or 0.0)
    times = [r["time_s"] for r in rows if r["time_s"] is not None]
    detect = [r for r in rows if r["effect_size_over_noise"] is not None]
    undetectable = [r for r in detect if _visible(r) is not None and _visible(r) < UNDETECTABLE]
    detectable_rows = [r for r in rows if r not in undetectable]
    return {
        "cases": n,
        "correct": sum(r["correct"] for r in rows),
        "accuracy": sum(r["correct"] for r in rows) / n if n else math.nan,
        "accuracy_detectable": (
            sum(r["correct"] for r in detectable_rows) / len(detectable_rows) if detectable_rows else math.nan
        ),
        "per_class": per_class,
        "per_group": per_group,
        "confusion_columns": columns,
        "confusion": {k: dict(v) for k, v in confusion.items() if sum(v.values())},
        "by": by,
        "exceptions": [[r["name"], r["error_stage"], r["error"]] for r in rows if r["error"]],
        "time_mean_s": sum(times) / len(times) if times else None,
        "time_max_s": max(times) if times else None,
        "slowest": sorted(([r["name"], r["time_s"]] for r in rows if r["time_s"] is not None), key=lambda x: -x[1])[:8],
        "undetectable": [[r["name"], _visible(r)] for r in undetectable],
        "effect_size_over_noise": {
            s: sorted(r["effect_size_over_noise"] for r in detect if r["size"] == s) for s in ("moderate", "large")
        },
        "visible_over_noise": {
            s: sorted(_visible(r) for r in detect if r["size"] == s and _visible(r) is not None)
            for s in ("moderate", "large")
        },
        "wrong": [[r["name"], r["expected"], _said(r), _visible(r)] for r in rows if not r["correct"]],
    }


def _pct(a, b) -> str:
    return f"{a}/{b} ({100 * a / b:.0f} %)" if b else "-"


def _quantiles(values) -> str:
    if not values:
        return "-"
    v = sorted(values)
    q = lambda p: v[min(len(v) - 1, int(p * (len(v) - 1) + 0.5))]  # noqa: E731
    return f"min {v[0]:.3g}, median {q(0.5):.3g}, max {v[-1]:.3g}"


def confusion_table(summary: dict) -> list[str]:
    short = {
        "nothing_missing": "nothing",
        "unexplained": "unexpl.",
        "seal_friction": "seal_fr",
        "fluid_inertia": "inertia",
        "compressibility": "compress",
        "leakage": "leakage",
        "viscous_heating": "heating",
        "field_lag": "lag",
        "shear_thinning": "thinning",
        "gas_spring": "gas_spr",
        "preyield_elasticity": "preyield",
        "exception": "EXC",
    }
    cols = summary["confusion_columns"]
    head = "| true \\ said | " + " | ".join(short.get(c, c) for c in cols) + " |"
    lines = [head, "|" + "---|" * (len(cols) + 1)]
    for cls, counts in summary["confusion"].items():
        lines.append(f"| {cls} | " + " | ".join(str(counts.get(c, 0) or "") for c in cols) + " |")
    return lines


def report_lines(summary: dict, long: dict | None, wall: float, meta: dict) -> list[str]:
    s = summary
    out = [
        f"cases: {s['cases']}; correct: {_pct(s['correct'], s['cases'])}; on the detectable cases: "
        f"{100 * s['accuracy_detectable']:.0f} %",
        f"diagnose: erdesign/diagnosis/diagnose.py at {meta['diagnose_commit'][:10]}"
        f"{' + uncommitted changes' if meta['diagnose_dirty'] else ''}; wall time {wall:.0f} s on "
        f"{meta['jobs']} processes",
        "",
        "per class (clean: no false 'missing'; out of library: 'unexplained'; "
        "library effect: recall; pair: one of the two named):",
    ]
    for cls, c in s["per_class"].items():
        out.append(f"  {cls:<22} {_pct(c['correct'], c['cases'])}")
    if set(s.get("per_group", {})) - {CORE}:
        out.append("per benchmark class (core: the catalogue above by true class; the others: issue 23):")
        for grp, c in s["per_group"].items():
            out.append(f"  {grp:<22} {_pct(c['correct'], c['cases'])}; slowest diagnosis {c['time_max_s']:.1f} s")
    for key, groups in s["by"].items():
        out.append(f"by {key}: " + ", ".join(f"{k} {_pct(a, b)}" for k, (a, b) in groups.items()))
    out += ["", "confusion matrix (rows: true class; columns: verdict or named effect):", *confusion_table(s), ""]
    out.append(f"exceptions: {len(s['exceptions'])}")
    out += [f"  {name} [{stage}]: {msg}" for name, stage, msg in s["exceptions"]]
    if s["time_mean_s"] is not None:
        out.append(f"diagnose wall time per case: mean {s['time_mean_s']:.1f} s, max {s['time_max_s']:.1f} s")
        out.append("slowest: " + ", ".join(f"{n} {t:.1f} s" for n, t in s["slowest"][:5]))
    for size, v in s["effect_size_over_noise"].items():
        out.append(f"effect size over noise, {size}: {_quantiles(v)}")
    if s["undetectable"]:
        out.append(
            f"undetectable by design (effect < 3 x noise): {len(s['undetectable'])}: "
            + ", ".join(f"{n} ({x:.2g})" for n, x in s["undetectable"])
        )
    if long:
        if long["error"]:
            out.append(f"60 s record at 1 kHz: exception: {long['error']}")
        else:
            out.append(
                f"60 s record at 1 kHz ({long['samples']} samples): diagnose {long['time_s']:.1f} s "
                f"(target < {LONG_TARGET:g} s: {'met' if long['time_s'] < LONG_TARGET else 'NOT met'}); "
                f"verdict {long['verdict']}, {long['missing_effect']}"
            )
    return out


def docs_path(subset: str) -> Path:
    """The page a run writes: docs/diagnosis_benchmark.md for the catalogue (``full``, ``core``), a page of its own
    for a subset of classes (docs/diagnosis_benchmark_issue23.md), so that a run of some classes never replaces the
    catalogue's numbers."""
    return DOCS if subset in ("full", "core") else DOCS.with_name(f"diagnosis_benchmark_{subset}.md")


def group_lines(summary: dict, rows: list[dict]) -> list[str]:
    """The per-class section of the page: one line per benchmark class, then every case of the issue-23 classes
    with what it should be called, what diagnose said and how long it took."""
    groups = {g: c for g, c in summary.get("per_group", {}).items() if g != CORE}
    if not groups:
        return []
    lines = [
        "## Classes of issue 23",
        "",
        "Each class of issue 23 (`Case.group`, design rules in the docstring of `cases.py`), and the core "
        "catalogue (all the classes above, by true class) as one line:",
        "",
        "| class | correct | slowest diagnosis |",
        "|---|---|---|",
    ]
    lines += [
        f"| {g} | {_pct(c['correct'], c['cases'])} | {c['time_max_s']:.1f} s |" for g, c in summary["per_group"].items()
    ]
    lines += ["", "| case | expected | said | diagnose [s] |", "|---|---|---|---|"]
    for r in rows:
        if r.get("group", CORE) == CORE:
            continue
        expected = r["expected"] if len(r["accepted"]) < 2 else " or ".join(r["accepted"])
        mark = "" if r["correct"] else " **(wrong)**"
        t = "-" if r["time_s"] is None else f"{r['time_s']:.1f}"
        lines.append(f"| `{r['name']}` | {expected} | {_said(r)}{mark} | {t} |")
    return lines + [""]


#: The loop on measured records (not run by this script: minutes each; the studies' own pages and tests have the
#: numbers and reproduce them).
REAL_DATA = """\
The truth rig is the team's own; two measured sets test what it cannot:

- **Dyke's `ransim_u`** (Spencer et al. 1997 prototype MR damper, 3 kHz band-limited random motion and command,
  `examples/spencer1997.toml`; [case_studies/dyke.md](case_studies/dyke.md)): the findings leave out 217 clipped
  samples and a 0.38 s excursion of the displacement; following its own verdicts the loop names field lag, then
  gas spring + leakage (a pair), then pre-yield elasticity, and ends `unexplained` at ESR 0.0176 on the judged
  samples with 7 free parameters.  On all unclipped samples that model has ESR 0.0994 when fitted on every sample
  outside the excursion, 0.104 as `erdesign fit` fits it (the judged samples only); the modified Bouc-Wen, 13
  parameters, 0.092 there; fitted on the first half it predicts the second within 1.19 x its own ESR outside the
  excursion.
- **Quiroz (2022)** (a small MR damper at five coil currents, `examples/quiroz2022.toml`;
  [case_studies/quiroz.md](case_studies/quiroz.md)): the 30 raw sinusoids are diagnosed together (one parameter
  set; the preprocessed files are found `smoothed`, a causal moving average over a tenth of a period): following
  its verdicts the loop names pre-yield elasticity, then ends `unexplained` at training ESR 0.012; fitted jointly
  on the sines, that model predicts the earthquake-type validation record at mean ESR 0.099 (through the record's
  own smoothing), within 1.5 x the modified Bouc-Wen's 0.066."""


def write_docs(
    summary: dict,
    long: dict | None,
    wall: float,
    meta: dict,
    subset: str,
    command: str,
    rows: list[dict] | None = None,
    path: Path = DOCS,
) -> None:
    s = summary
    lines = [
        "# Diagnosis benchmark" + ("" if path == DOCS else f": subset `{path.stem.split('_', 2)[-1]}`"),
        "",
        "How often `erdesign diagnose` names the right missing effect on records made by the independent "
        "truth rig (`erdesign/simulation/truthrig/`, which shares no code with the fitted model). The "
        "catalogue is `erdesign/simulation/truthrig/cases.py` (`benchmark_cases()`); its docstring gives the "
        "design rules and "
        "`mechanism_parameters` the physical size of every mechanism. Each record is written to CSV and read "
        "back with `read_measurement` before it is diagnosed.",
        "",
        "Correct means: clean record (the true damper is exactly Bingham, calibration factors perturbed) -> "
        "`nothing_missing`; mechanism outside the library (blow-off, single rod, cavitation, free play) -> "
        "`unexplained`; library mechanism(s) -> `missing_effect` naming it (for a pair: either).",
        "",
        *(
            [
                "The subset `full` is the core catalogue (reported by true class) and the classes of issue 23 "
                "(reported one by one as well, below); the issue-23 classes alone: `--subset issue23`, written to "
                "`docs/diagnosis_benchmark_issue23.md`.",
                "",
            ]
            if path == DOCS
            else []
        ),
        f"Latest run: {meta['date']}, subset `{subset}`, {s['cases']} cases, erdesign/diagnosis/diagnose.py at "
        f"`{meta['diagnose_commit'][:10]}`{' (with uncommitted changes)' if meta['diagnose_dirty'] else ''}, "
        f"{meta['jobs']} processes, {wall:.0f} s.",
        "",
        "Regenerate:",
        "",
        "```bash",
        command,
        "```",
        "",
        "## Result",
        "",
        f"Overall: **{_pct(s['correct'], s['cases'])}** correct; on the cases detectable by design "
        f"(what no recalibration absorbs at least 3 x the noise): {100 * s['accuracy_detectable']:.0f} %.",
        "",
        "| true class | correct |",
        "|---|---|",
    ]
    lines += [f"| {cls} | {_pct(c['correct'], c['cases'])} |" for cls, c in s["per_class"].items()]
    lines += ["", "By damper, excitation, force noise and size:", ""]
    for key, groups in s["by"].items():
        lines.append(f"- {key}: " + ", ".join(f"{k} {_pct(a, b)}" for k, (a, b) in groups.items()))
    lines += [
        "",
        "## Confusion matrix",
        "",
        "Rows: the true class; columns: the verdict, or the effect named.",
        "",
        *confusion_table(s),
        "",
    ]
    lines += group_lines(s, rows or [])
    lines += [
        "## Detectability",
        "",
        "Energy of the force change the hidden mechanisms make (noise-free truth runs with and without them) "
        "over the energy of the force noise:",
        "",
    ]
    for size, v in s["effect_size_over_noise"].items():
        lines.append(f"- {size}: {_quantiles(v)}")
    if any(s.get("visible_over_noise", {}).values()):
        lines += [
            "",
            "What is left of it after the truth rig's own clean damper is recalibrated to the run with the "
            "mechanisms (its viscosity and yield-stress factors refitted): what no calibration can absorb, "
            "over the energy of the force noise (`visible_over_noise`):",
            "",
        ]
        for size, v in s["visible_over_noise"].items():
            lines.append(f"- {size}: {_quantiles(v)}")
    if s["undetectable"]:
        lines += [
            "",
            f"Undetectable by design (what is left after recalibration below 3 x the noise), kept in the "
            f"catalogue and counted: "
            f"{', '.join(f'`{n}` ({x:.2g})' for n, x in s['undetectable'])}.",
        ]
    lines += ["", "## Timing", ""]
    if s["time_mean_s"] is not None:
        lines.append(
            f"Diagnose per case: mean {s['time_mean_s']:.1f} s, max {s['time_max_s']:.1f} s "
            f"(slowest: {', '.join(f'`{n}` {t:.1f} s' for n, t in s['slowest'][:5])})."
        )
    if long:
        if long["error"]:
            lines.append(f"\nOne 60 s record at 1 kHz: exception `{long['error']}`.")
        else:
            lines.append(
                f"\nOne 60 s record at 1 kHz ({long['samples']} samples): {long['time_s']:.1f} s "
                f"(target < {LONG_TARGET:g} s)."
            )
    lines += ["", "## Real data", "", REAL_DATA]
    lines += ["", "## Exceptions", ""]
    lines += [f"- `{n}` [{stage}]: {msg}" for n, stage, msg in s["exceptions"]] or ["None."]
    lines += ["", "## Misdiagnosed cases", "", "| case | expected | said | effect / noise |", "|---|---|---|---|"]
    for name, exp, said, det in s["wrong"]:
        lines.append(f"| `{name}` | {exp} | {said} | {'-' if det is None else f'{det:.3g}'} |")
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


# ---------------------------------------------------------------------------------------------------- main
def _git(*args) -> str:
    try:
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=True).stdout.strip()
    except Exception:
        return ""


def select(cases, pattern: str | None):
    if not pattern:
        return cases
    patterns = [q.strip() for q in pattern.split(",") if q.strip()]

    def hit(name: str, q: str) -> bool:
        return fnmatch.fnmatch(name, q) if any(ch in q for ch in "*?[") else q in name

    return [c for c in cases if any(hit(c.name, q) for q in patterns)]


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument(
        "--subset",
        choices=SUBSETS,
        default="full",
        help="full (core + issue23), core (the catalogue of 2026-11-23), issue23 (its classes), fast",
    )
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--cases", default=None, help="shell patterns or substrings of case names, comma-separated")
    p.add_argument("--out", default=None, help="JSON file of every case")
    p.add_argument(
        "--write-docs",
        action="store_true",
        help=f"write {DOCS.relative_to(ROOT)} (full, core) or docs/diagnosis_benchmark_SUBSET.md",
    )
    p.add_argument("--no-long", action="store_true", help="skip the 60 s, 1 kHz timing record")
    p.add_argument("--no-detectability", action="store_true", help="skip the noise-free detectability runs")
    p.add_argument("--from-json", default=None, help="summarise (and --write-docs) a previous --out file, no runs")
    p.add_argument(
        "--detectability-from",
        default=None,
        help="take the detectability of each case from a previous --out file where the case (name and "
        "mechanism parameters) is the same; measure it for the others",
    )
    args = p.parse_args(argv)
    sys.path.insert(0, str(ROOT))
    if args.from_json:
        data = json.loads(Path(args.from_json).read_text(encoding="utf-8"))
        rows = data["cases"]
        if args.cases:
            rows = [r for r in rows if fnmatch.fnmatch(r["name"], args.cases) or args.cases in r["name"]]
        summary = summarise(rows)
        wall = data.get("wall_s", math.nan)
        print("\n".join(report_lines(summary, data.get("long_record"), wall, data["meta"])))
        if args.write_docs:
            command = (
                "python benchmarks/bench_diagnosis_accuracy.py --subset "
                + data["subset"]
                + f" --jobs {data['meta']['jobs']} --out results.json --write-docs"
            )
            subset = data["subset"] + (f"` (partial run, {len(rows)} cases done`" if data.get("partial") else "")
            path = docs_path(data["subset"])
            write_docs(summary, data.get("long_record"), wall, data["meta"], subset, command, rows, path)
            print(f"wrote {path.relative_to(ROOT)}")
        return 0

    from erdesign.simulation.truthrig.cases import benchmark_cases

    cases = select(benchmark_cases(args.subset), args.cases)
    if not cases:
        print(f"no case matches {args.cases!r}", file=sys.stderr)
        return 2
    meta = {
        "date": datetime.date.today().isoformat(),
        "diagnose_commit": _git("log", "-1", "--format=%H", "--", "erdesign/diagnosis/diagnose.py") or "unknown",
        "diagnose_dirty": bool(
            _git("status", "--porcelain", "--", "erdesign/diagnosis/diagnose.py", "erdesign/effects")
        ),
        "head": _git("rev-parse", "HEAD"),
        "jobs": args.jobs,
    }
    print(f"{len(cases)} cases ({args.subset}) on {args.jobs} processes", flush=True)
    t0 = time.perf_counter()
    rows = []
    detect = not args.no_detectability
    known = {}
    if args.detectability_from and detect:
        for r in json.loads(Path(args.detectability_from).read_text(encoding="utf-8"))["cases"]:
            if r.get("visible_over_noise") is not None:
                known[r["name"]] = r

    def detect_of(c):
        r = known.get(c.name)
        same = r is not None and r["mechanisms"] == {k: dict(v) for k, v in c.mechanisms.items()}
        return r if same else detect

    def save(partial: bool, long=None, summary=None) -> None:
        if args.out:
            wall = time.perf_counter() - t0
            Path(args.out).write_text(
                json.dumps(
                    {
                        "meta": meta,
                        "subset": args.subset,
                        "wall_s": wall,
                        "partial": partial,
                        "summary": summary,
                        "long_record": long,
                        "cases": rows,
                    },
                    indent=1,
                ),
                encoding="utf-8",
            )

    # interleaved over the classes, so that a run stopped early has seen every class
    queue = _interleaved(cases)
    if args.jobs <= 1:
        for c in queue:
            rows.append(run_case(c, detect_of(c)))
            _progress(rows[-1], len(rows), len(cases))
            save(True)
    else:
        with ProcessPoolExecutor(max_workers=args.jobs) as pool:
            futures = [pool.submit(run_case, c, detect_of(c)) for c in queue]
            for fut in as_completed(futures):
                rows.append(fut.result())
                _progress(rows[-1], len(rows), len(cases))
                save(True)
    wall = time.perf_counter() - t0
    order = {c.name: i for i, c in enumerate(cases)}
    rows.sort(key=lambda r: order[r["name"]])
    long = None if args.no_long else run_long()
    summary = summarise(rows)
    print()
    print("\n".join(report_lines(summary, long, wall, meta)))
    save(False, long, summary)
    if args.write_docs:
        command = (
            "python benchmarks/bench_diagnosis_accuracy.py --subset "
            + args.subset
            + f" --jobs {args.jobs} --out results.json --write-docs"
        )
        path = docs_path(args.subset)
        write_docs(summary, long, wall, meta, args.subset, command, rows, path)
        print(f"wrote {path.relative_to(ROOT)}")
    return 0


def _interleaved(cases):
    groups = defaultdict(list)
    for c in cases:
        groups[(c.group, c.expected if c.kind == "single" else c.kind)].append(c)
    out = []
    while any(groups.values()):
        for g in groups.values():
            if g:
                out.append(g.pop(0))
    return out


def _progress(row, done, total) -> None:
    mark = "ok " if row["correct"] else ("EXC" if row["error"] else "-- ")
    said = row["error"] if row["error"] else f"{row['verdict']} {row['missing_effect'] or ''}"
    t = f"{row['time_s']:.1f} s" if row["time_s"] is not None else "-"
    det = row["effect_size_over_noise"]
    print(
        f"[{done:3d}/{total}] {mark} {row['name']:<60} {t:>7}  E/N {'-' if det is None else f'{det:8.3g}'}  {said}",
        flush=True,
    )


if __name__ == "__main__":
    sys.exit(main())
