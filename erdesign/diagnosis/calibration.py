"""Calibration (stage 3 of diagnosis): the baseline and its effects fitted to the judged samples of one or several
records, and the checks a record must pass first.

:func:`calibrate` is what ``erdesign fit`` runs; :func:`erdesign.diagnosis.diagnose.diagnose` fits every model
through :func:`_fit` on the same samples (:mod:`erdesign.diagnosis.records`), so both state one ESR for one model.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace
from typing import Mapping, Sequence

import numpy as np

from ..damper import Damper
from ..data.findings import excluded_mask, find_data_problems
from ..data.measurement import Measurement
from ..data.metrics import esr
from ..effects import EffectError
from ..effects.base import reversal_count
from ..effects.chain import PhysicsDamper, check_control
from ..errors import ErdesignError, PlausibilityWarning
from ..identification.fit import FitResult, fit
from .records import MAX_SAMPLES, prepare

__all__ = ["DiagnosisError", "calibrate", "data_findings", "fitted_model"]


class DiagnosisError(ErdesignError):
    """The record cannot be diagnosed (too short, wrong control, unknown effect)."""


def _finite_or_none(x):
    return float(x) if x is not None and math.isfinite(x) else None


def _free_parameters(model: PhysicsDamper, record: Measurement) -> list[str]:
    free = list(model.parameter_names)
    if not np.any(np.abs(record.control) > 0) or model.damper.fluid.yield_stress == 0:
        free.remove("yield_stress_factor")  # no field: the yield stress cannot be seen
    return free


def calibrate(
    damper: Damper,
    record: Measurement | Sequence[Measurement],
    effects: Sequence[str] | str = (),
    *,
    start: Mapping[str, float] | None = None,
    exclude_clipped: bool | None = None,
    max_samples: int = MAX_SAMPLES,
) -> FitResult:
    """Fit the baseline (two calibration factors) plus ``effects`` to one record or several records of one damper.

    The fit runs on the samples :func:`diagnose` judges (:mod:`erdesign.diagnosis.records`: transients kept at full
    rate, the sign of the velocity known, clipped samples left out), so the ESR it states is the one
    ``erdesign diagnose`` states for the same model.  ``fitted_model(result)`` gives the model for a whole record.

    Raises a one-line error when a record's control does not match the damper or an effect cannot be seen in
    the records.
    """
    records = _as_records(record)
    model = PhysicsDamper(damper, effects)
    for r in records:
        check_control(damper, r)
        _check_record(r, to_judge=False)
    _check_effects_seen(model, records, damper)
    findings = data_findings(records, exclude_clipped=exclude_clipped)
    prep = prepare(
        records,
        [excluded_mask([f for f in findings if f.record == _name(r, i)], len(r)) for i, r in enumerate(records)],
        max_samples=max_samples,
    )
    result = _fit(model, prep.work, start, mask=prep.mask())
    result.findings = findings
    result.records = _record_esrs(model, result.values, prep.work, prep)
    return result


def unseen_reason(effect, records: Sequence[Measurement], damper: Damper) -> str | None:
    """Why none of ``records`` can show ``effect`` (an :class:`erdesign.effects.base.Effect`), or None when any of
    them can: each full record is asked on its own (its own sampling step, its own fields)."""
    whys = [effect.check(r, damper) for r in records]
    return None if any(w is None for w in whys) else whys[0]


def _check_effects_seen(model: PhysicsDamper, records: Sequence[Measurement], damper: Damper) -> None:
    """A one-line error when no record can show one of the model's effects (:func:`unseen_reason`)."""
    for e in model.effects:
        why = unseen_reason(e, records, damper)
        if why:
            raise EffectError(
                f"{e.name}: cannot be judged from {records[0].name or 'this record'}"
                + (f" or the other {len(records) - 1} records" if len(records) > 1 else "")
                + f": {why}"
            )


def data_findings(records: Sequence[Measurement], *, exclude_clipped: bool | None = None) -> list:
    """Data-quality findings of every record (:func:`erdesign.data.findings.find_data_problems`), each naming its
    record."""
    out = []
    for i, r in enumerate(records):
        named = r if r.name else replace(r, name=_name(r, i))
        out += find_data_problems(named, exclude_clipped=exclude_clipped)
    return out


def _fit(model: PhysicsDamper, record: Measurement, start=None, mask=None) -> FitResult:
    free = _free_parameters(model, record)
    guess = {**model.initial_guess(record), **{k: v for k, v in (start or {}).items() if k in model.parameter_names}}
    fixed = {} if "yield_stress_factor" in free else {"yield_stress_factor": guess.get("yield_stress_factor", 1.0)}
    return fit(model, record, free=free, fixed=fixed, start=guess, max_nfev=200, mask=mask)


def fitted_model(result: FitResult) -> PhysicsDamper:
    """The physics model of a fit, for the whole record (diagnosis fits on the samples where the sign of the
    velocity is known, :func:`erdesign.identification.fit.fit`'s ``mask``; the model is the damper's own).

    >>> from erdesign import load_example
    >>> from erdesign.simulation.rig import run_rig, sine
    >>> record = run_rig(load_example("makris"), sine(0.005, 2.0, 3e6, cycles=2, rate=200), seed=1).record
    >>> from erdesign.diagnosis.diagnose import diagnose
    >>> d = diagnose(load_example("makris"), record, candidates=["seal_friction"])
    >>> model = fitted_model(d.baseline)
    >>> model.simulate(record, d.baseline.values).shape == record.force.shape
    True
    """
    return getattr(result.model, "inner", result.model)


def _implausible_record(record: Measurement, damper: Damper) -> list[str]:
    """Possible but implausible records for this damper (a likely unit mistake in a column header)."""
    out = []
    stroke = float(np.ptp(record.displacement))
    speed = float(np.max(np.abs(record.velocity)))
    Dp = damper.geometry.piston_diameter
    unit = lambda col: record.units.get(col, "SI")  # noqa: E731
    if stroke > 50 * Dp:
        out.append(
            f"the stroke is {stroke:.3g} m, {stroke / Dp:.3g} x the piston diameter: is the displacement "
            f"column's unit [{unit('displacement')}] right?"
        )
    if speed > 20.0:
        out.append(
            f"the piston speed reaches {speed:.3g} m/s, beyond any damper test: is the displacement or time "
            "column's unit right?"
        )
    F = record.force
    if F is not None:
        Fy = float(np.max(np.abs(damper.yield_force_si(record.control)))) + damper.seal_friction
        Fpred = float(np.max(np.abs(damper.force_si(np.clip(record.velocity, -20, 20), record.control))))
        Fmax = float(np.max(np.abs(F)))
        ref = max(Fpred, Fy, 1e-9)
        # (300, not 1000: a force column off by exactly a unit prefix must be caught with the model's own error)
        if Fmax > 300 * ref or Fmax < ref / 300:
            out.append(
                f"the measured force peaks at {Fmax:.3g} N where the damper file predicts about {ref:.3g} N: "
                f"is the force column's unit [{unit('force')}] right?"
            )
    return out


def _check_record(record: Measurement, *, to_judge: bool = True) -> None:
    """A one-line error for a record that cannot be fitted; with ``to_judge`` (diagnosis) also for one too short to
    judge any effect (a fit of a short record is only warned about: erdesign.data.measurement.check_record)."""
    if record.force is None:
        raise DiagnosisError(f"{record.name or 'record'}: has no force column")
    for name, a in (("force", record.force), ("displacement", record.displacement), ("velocity", record.velocity)):
        if not np.all(np.isfinite(a)):
            raise DiagnosisError(f"{record.name or 'record'}: the {name} has non-finite values")
    if not to_judge:
        return
    if len(record) < 50:
        raise DiagnosisError(
            f"{record.name or 'record'}: {len(record)} samples are too few to judge any effect "
            "(need at least 50, over at least one cycle)"
        )
    if reversal_count(record.velocity) < 2:
        raise DiagnosisError(
            f"{record.name or 'record'}: the piston reverses fewer than twice; at least one full "
            "cycle is needed to judge any effect"
        )


def _name(record: Measurement, i: int) -> str:
    return record.name or f"record {i + 1}"


def _as_records(record) -> list[Measurement]:
    if isinstance(record, Measurement):
        return [record]
    if isinstance(record, (str, bytes)) or hasattr(record, "columns") or not hasattr(record, "__iter__"):
        # a DataFrame's iteration gave its column names: "record 1: expected a Measurement, got str"
        hint = (
            "; make one with Measurement.from_arrays(time, displacement, force)" if hasattr(record, "columns") else ""
        )
        raise DiagnosisError(
            f"record: expected a Measurement or a list of them, got {type(record).__name__} "
            f"{' '.join(repr(record).split())[:60]}{hint}"
        )
    records = list(record)
    if not records:
        raise DiagnosisError("no record given")
    for i, r in enumerate(records):
        if not isinstance(r, Measurement):
            raise DiagnosisError(f"record {i + 1}: expected a Measurement, got {type(r).__name__}")
    names = [_name(r, i) for i, r in enumerate(records)]
    if len(set(names)) < len(names):
        records = [replace(r, name=f"{_name(r, i)} ({i + 1})") for i, r in enumerate(records)]
    _warn_repeated(records)
    return records


def _warn_repeated(records: Sequence[Measurement]) -> None:
    """Warn, naming both, of a record whose samples are those of an earlier one (the same file given twice, or a
    copy under another name): it counts twice in the calibration and in the judged samples, without a word."""
    for j, b in enumerate(records):
        for i, a in enumerate(records[:j]):
            if len(a) == len(b) and all(
                np.array_equal(getattr(a, key), getattr(b, key)) for key in ("time", "displacement", "force")
            ):
                warnings.warn(
                    f"{_name(b, j)}: the same samples as {_name(a, i)}: the record counts twice in the calibration; "
                    "give each record once",
                    PlausibilityWarning,
                    stacklevel=4,
                )
                break


def _record_esrs(model: PhysicsDamper, values, work: Measurement, prep) -> list[dict]:
    """ESR of the model on each record's judged samples."""
    with np.errstate(all="ignore"):
        Fm = model.force(work, values)
    out = []
    for (name, seg), n_full in zip(prep.segments, prep.full_samples):
        keep = prep.judged[seg]
        e = esr(work.force[seg][keep], Fm[seg][keep]) if keep.sum() > 2 else math.nan
        out.append({"name": name, "samples": int(n_full), "esr": _finite_or_none(e)})
    return out
