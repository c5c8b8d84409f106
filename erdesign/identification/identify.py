r"""Identification workflows on top of :func:`erdesign.identification.fit.fit`: one record, several records jointly
(e.g. one sinusoid per coil current with the current-dependent parameters shared), and cross-validation tables in the
style of Vivas-López et al. (n.d.) Table 4 (identify on one experiment, score the ESR on every other).
"""

from __future__ import annotations

import math
import time as _time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..data.measurement import Measurement
from ..data.metrics import esr
from ..errors import ErdesignError
from ..models.base import Model
from .engine import (
    FitError,
    Strategy,
    control_reference_for,
    mostly_at_bounds,
    problem,
    solve,
    worse_than_reference,
)
from .result import (
    FitResult,
    fit_report,
    fit_statistics,
    parameter_table,
    result_json,
    strong_correlations,
)

__all__ = [
    "CrossValidation",
    "JointResult",
    "ParameterSource",
    "Simulation",
    "choose_control_reference",
    "cross_validation",
    "fit_report",
    "fit_statistics",
    "identify",
    "identify_joint",
    "joint_json",
    "joint_report",
    "parameter_table",
    "resolve_parameters",
    "result_json",
    "score",
    "simulate",
    "strong_correlations",
]


def choose_control_reference(model: Model, records: Sequence[Measurement]) -> float:
    """Set ``model.control_reference`` to :func:`~erdesign.identification.engine.control_reference_for` the records
    and return it (for a model the caller then simulates; the fits themselves work on a copy)."""
    ref = control_reference_for(records)
    model.control_reference = ref
    return ref


def control_reference_text(model: Model, control_kind: str | None) -> str | None:
    """The fitted model's control reference as text with its unit (``"1 A"``), or None when the model does not use
    the control, the records have none, or the model is the physics damper (whose control is the field itself).
    Field-dependent models work with u = control / reference, so the parameters that multiply u are per unit u and
    the reference is part of their meaning (docs/models.md: the power of ten at or below the records' largest
    |control|)."""
    from ..fluid import CONTROL_UNITS
    from ..units import Q_, format_quantity

    if not model.uses_control or control_kind is None or model.name == "physics":
        return None
    return format_quantity(Q_(model.control_reference, CONTROL_UNITS[control_kind]).to_compact())


#: Singular value (of the Jacobian with unit-norm columns) below which a direction of parameter space is taken as
#: not seen by the data: exact redundancies leave ~1e-8 (finite-difference noise), real information 1e-3 and up.
NULL_SV = 1e-6


def _null_parameters(J, z, tr, names, prefer=()):
    """The fewest parameters to hold so that the data fix the rest: for each near-null direction of the scaled
    Jacobian, the parameter with the largest share of it (a control slope when it has a comparable share: the
    record then cannot show the control dependence)."""
    Js = np.asarray(J, dtype=float) / tr.dvalue_dz(z)[np.newaxis, :]
    norms = np.linalg.norm(Js, axis=0)
    held = [n for n, q in zip(names, norms) if q == 0]
    live = [i for i, q in enumerate(norms) if q > 0]
    if len(live) < 2:
        return held
    _, sv, Vt = np.linalg.svd(Js[:, live] / norms[live], full_matrices=False)
    for v in Vt[sv < NULL_SV * sv.max()]:
        share = np.abs(v)
        order = [live[i] for i in np.argsort(-share)]
        top = share.max()
        pick = next(
            (i for i in order if names[i] in prefer and share[live.index(i)] > 0.3 * top and names[i] not in held), None
        )
        if pick is None:
            pick = next((i for i in order if names[i] not in held), None)
        if pick is not None:
            held.append(names[pick])
    return held


#: Relative rise of the sum of squares allowed when the parameters found not identifiable are held at their start
#: values; above it the free fit is kept.
HELD_RTOL = 1e-3


def identify(
    model: Model,
    record: Measurement,
    *,
    starts: int = 4,
    global_search: bool = False,
    max_time: float | None = None,
    decimate: int = 1,
    exclude_clipped: bool = False,
    progress=None,
    free: Sequence[str] | None = None,
    fixed: Mapping[str, float] | None = None,
    start: Mapping[str, float] | None = None,
    seed: int = 0,
    max_nfev: int | None = None,
    fix_unidentifiable: bool = True,
    warm_start: bool = False,
    projection: bool | None = None,
    executor=None,
) -> FitResult:
    """Identify ``model`` on ``record`` by bounded least squares, at the scale of real records.

    * The fit works on a copy of the model with the control reference chosen from the record
      (:func:`~erdesign.identification.engine.control_reference_for`; ``result.model``): ``model`` is not changed.
      A control column of zeros holds the control slopes, as no control column does.
    * One local start (trust-region reflective, :func:`scipy.optimize.least_squares`) from the model's guess;
      further starts (Latin hypercube around it, as :func:`erdesign.identification.fit.fit`, and the model's own
      guess when ``start`` moved the first start away from it) only when it fails: the optimiser did not
      converge, the fit is no better than the reference Bingham fit (c0 v + f_c sgn v + f0 by linear least squares
      on the same samples), or more than half the free parameters sit on a bound.  Then all ``starts - 1`` others
      run, on ``executor`` (:func:`erdesign.executor.executor_for`; default one after the other in this process),
      and the best is kept: the result does not depend on the executor.  A best fit no better than the reference is not a success (``success`` False,
      ``poor_fit``, a warning).
    * All samples are fitted; ``decimate`` > 1 fits on every ``decimate``-th sample only (the scores are still on
      all samples).  ``warm_start`` first fits long records (> 20,000 samples) on every k-th sample (at least 1 kHz
      kept), then all samples.  It is off by default: on Dyke's 3 kHz record the 1 kHz optimum lies in a stiff
      region of the modified Bouc-Wen model (38 kernel sub-steps per sample instead of 1) far from the full-rate
      optimum, and the fit took 46 s of CPU with it against 11 s without, to the same ESR 0.0918.
    * Variable projection (Golub and Pereyra 1973, 2003; ``projection``, default the model's
      ``projection_default``, True for all but :class:`~erdesign.models.bouc_wen.BoucWen`): the free parameters
      the force is affine in (:attr:`~erdesign.models.base.Model.linear_parameters`) are solved by linear least
      squares inside each residual (bounded when the unbounded solution leaves the bounds), the optimiser sees
      only the others, and its Jacobian is Kaufman's (1975) projected one.  All free parameters' standard errors
      come from one full Jacobian at the end.  On Dyke's record (modified Bouc-Wen, k1 projected) the fit takes
      about half the simulations of the plain one to the same ESR; a Bingham fit is one linear solve
      (docs/identification.md).
    * Jacobians are forward differences with the kernels' sub-step counts held at those of the point
      (:class:`~erdesign.models._kernels.frozen_substeps`: an adaptive count that jumps inside a difference adds the
      discretisation error divided by the step) and steps of 1e-6 of each parameter's scale (a parameter at zero
      gets the scale of its unit's other parameters, not scipy's absolute 1.5e-8).  On Dyke's record the fit
      reaches the same optimum with scipy's own differences; these guard the cases where the jumps or a step
      below the kernels' round-off would make a Jacobian column noise.
    * ``max_time`` [s] bounds the wall time: the best point found so far is returned (``success`` False, with a
      message saying so).  ``progress`` (a callable taking a string) receives a line every few seconds.
    * ``exclude_clipped``: force samples at a flat top or bottom (:func:`erdesign.data.measurement.clipped_samples`) are
      left out of the residual and the scores.
    * Parameters the data cannot identify (a null direction of the Jacobian) are held at their start values and
      the fit repeated (``fix_unidentifiable``); they are listed in ``result.not_identifiable``.

    Returns a :class:`~erdesign.identification.fit.FitResult` whose typed fields carry the report's content (initial
    values, parameters not identifiable, warnings, the reference fit's ESR, poor fit; :func:`fit_report`).
    """
    from ..data.measurement import clipped_samples

    t_start = _time.monotonic()
    say = progress or (lambda msg: None)
    F_all = record.require_force()
    check = getattr(model, "check_record", None)
    if check is not None:
        check(record)
    notes: list[str] = []
    if record.control_kind is not None and np.ptp(record.control) > 0 and not model.uses_control:
        notes.append(
            f"{model.name} has no control dependence, but the record's {record.control_kind} varies "
            f"({np.min(record.control):.4g} to {np.max(record.control):.4g} SI): the fit averages over it"
        )
    clipped = clipped_samples(F_all)
    mask = ~clipped if exclude_clipped and clipped.any() else None
    if clipped.any() and not exclude_clipped:
        notes.append(
            f"{int(clipped.sum())} force samples sit at a flat top or bottom ({F_all[clipped][0]:.6g} N): "
            "a load cell at its limit? exclude_clipped=True leaves them out"
        )
    n_scored = int(F_all.size if mask is None else mask.sum())
    pb = problem(
        model,
        [record],
        free=free,
        fixed=fixed,
        start=start,
        masks=[mask],
        samples=n_scored,
        label=record.name or "record",
    )
    model, free_names, fixed, initial = pb.model, pb.free, pb.fixed, dict(pb.base)  # model: a copy
    if projection is None:
        projection = getattr(model, "projection_default", True)
    decimate = max(1, int(decimate))
    strategy = Strategy(
        starts=starts,
        global_search=global_search,
        seed=seed,
        max_nfev=max_nfev,
        rescue=True,
        tracked=True,
        projection=bool(projection),
        warm_start=warm_start,
        decimate=decimate,
        max_time=max_time,
        executor=executor,
    )
    result = solve(pb, strategy, progress)
    baseline, out_of_time = result.baseline_esr, result.out_of_time
    k = len(free_names)
    not_identifiable = _null_parameters(
        result.jacobian, result.search, pb.transform, free_names, model.control_parameters
    )
    if not_identifiable and fix_unidentifiable and k > len(not_identifiable) and not out_of_time:
        say(f"not identifiable from this record: {', '.join(not_identifiable)}; held at their start values")
        held = {n: initial[n] for n in not_identifiable}
        refit = identify(
            model,
            record,
            starts=1,
            max_time=None if max_time is None else max(1.0, t_start + float(max_time) - _time.monotonic()),
            decimate=decimate,
            exclude_clipped=exclude_clipped,
            progress=progress,
            free=[n for n in free_names if n not in held],
            fixed={**fixed, **held},
            start={**result.values, **held},
            seed=seed,
            max_nfev=max_nfev,
            fix_unidentifiable=False,
            warm_start=warm_start,
            projection=projection,
        )
        # Held at their start values, directions the data do not see should leave the fit as good; when the fit
        # gets worse (on a Quiroz record ESR 0.019 -> 7.0: the start values were zeros the found optimum needs),
        # the free fit is kept and the parameters are only reported.
        if refit.rss <= result.rss * (1.0 + HELD_RTOL):
            refit.not_identifiable = sorted(set(not_identifiable) | set(refit.not_identifiable))
            refit.initial = initial
            refit.warnings = [*notes, *[w for w in refit.warnings if w not in notes]]
            refit.seconds = _time.monotonic() - t_start
            return refit
        notes.append(
            f"not identifiable from this record: {', '.join(not_identifiable)}; held at their start "
            f"values the fit got worse (ESR {refit.esr:.4g} against {result.esr:.4g}), so they are left "
            "at the fitted values"
        )
    if out_of_time:
        notes.append(
            f"stopped at max_time {max_time:g} s before the optimiser converged: the values are the best found so far"
        )
    result.not_identifiable, result.warnings = not_identifiable, notes
    result.seconds, result.clipped_samples = _time.monotonic() - t_start, int(clipped.sum())
    result.excluded_samples, result.decimate, result.mask = 0 if mask is None else int(clipped.sum()), decimate, mask
    if hasattr(model, "train"):
        model.train(record, result.values)
        result.force = model.simulate(record, result.values)
        result.residual = F_all - result.force
        result.esr = esr(F_all, result.force)
    # A fit no better than the reference (a Bingham model: viscous plus friction plus offset, by linear least
    # squares on the same samples) or set by the bounds is not a success, whatever the optimiser's message says.
    bounded = mostly_at_bounds(model, free_names, result.values)
    poor = worse_than_reference(result.esr, baseline) or bounded
    result.poor_fit = poor
    if poor:
        result.success = False
        notes.append(
            f"poor fit: ESR {result.esr:.4g} after {result.starts_tried} start(s), against "
            f"{baseline:.4g} for the reference Bingham fit (c0 v + f_c sgn v + f0)"
            + (" with most parameters at a bound" if bounded else "")
            + ": try more starts, other fixed parameters or another model"
        )
    return result


class JointResult(FitResult):
    """A :class:`~erdesign.identification.result.FitResult` of several records (one parameter set): ``esr`` is the
    mean of the records' ESRs (each record weighs alike, as in the fit), ``records`` lists each one's."""

    @property
    def names(self) -> list[str]:
        """The records' names, in order."""
        return [r["name"] for r in self.records]

    @property
    def record_esr(self) -> list[float]:
        """The ESR on each record, in order."""
        return [r["esr"] for r in self.records]

    @property
    def mean_esr(self) -> float:
        """Mean of the per-record ESRs (:attr:`esr`)."""
        return self.esr


def identify_joint(
    model: Model,
    records: Sequence[Measurement],
    *,
    free: Sequence[str] | None = None,
    fixed: Mapping[str, float] | None = None,
    start: Mapping[str, float] | None = None,
    max_nfev: int | None = None,
    max_time: float | None = None,
    exclude_clipped: bool = False,
    progress=None,
) -> JointResult:
    """One parameter set for several records (each simulated from rest), by least squares on all residuals.

    Each record's residual is weighted by 1 / its force standard deviation, so that a record with small forces
    (zero current) counts as much as one with large forces.  ``max_time`` [s] stops with the best point found so
    far (``success`` False); ``exclude_clipped`` leaves each record's flat-top force samples out of the residual
    and the scores; ``progress`` (a callable taking a string) receives a line every few seconds.
    """
    import dataclasses

    from ..data.measurement import clipped_samples

    if not records:
        raise FitError("identify_joint: no records")
    for r in records:
        model.check_record(r)
        r.require_force()
    masks = []
    notes = []
    for r in records:
        clipped = clipped_samples(r.force)
        masks.append(~clipped if exclude_clipped and clipped.any() else None)
        if clipped.any() and not exclude_clipped:
            notes.append(
                f"{r.name or 'a record'}: {int(clipped.sum())} force samples sit at a flat top or bottom; "
                "exclude_clipped=True leaves them out"
            )
    total = sum(len(r) if m is None else int(m.sum()) for r, m in zip(records, masks))
    pb = problem(
        model, records, free=free, fixed=fixed, start=start, masks=masks, samples=total, label="identify_joint"
    )
    weights = tuple(
        1.0 / max(float(np.std(r.force if m is None else r.force[m])), 1e-12) for r, m in zip(records, masks)
    )
    pb = dataclasses.replace(pb, weights=weights)
    result = solve(pb, Strategy(max_nfev=max_nfev, max_time=max_time), progress)
    if result.out_of_time:
        notes.append(
            f"stopped at max_time {max_time:g} s before the optimiser converged: the values are the best found so far"
        )
    result.excluded_samples = [0 if m is None else int((~m).sum()) for m in masks]
    result.warnings, result.initial = notes, {n: pb.base[n] for n in pb.free}
    if len(records) == 1:  # the per-record list of one record
        result.records = [{"name": records[0].name, "samples": result.n, "esr": result.esr}]
    return JointResult(**{f.name: getattr(result, f.name) for f in dataclasses.fields(FitResult)})


def joint_report(result: JointResult, validation: Sequence[tuple[str, dict]] = ()) -> str:
    """The report of a joint identification: per-record ESR, the shared parameters, validation, warnings."""
    model = result.model
    width = max(len(n or "") for n in result.names)
    lines = [
        f"[[Joint fit]] {model.title or model.name} on {len(result.names)} records, one parameter set",
        f"  free parameters {len(result.free)}, simulations of all records {'?' if result.simulations is None else result.simulations}, "
        f"{result.seconds:.1f} s" + ("" if result.success else f"  - {result.message}"),
        f"[[ESR per record]] (mean {result.mean_esr:.4g})",
    ]
    excluded = result.excluded_samples or [0] * len(result.names)
    lines += [
        f"  {name or 'record':<{width}}  {e:.4g}" + (f"  ({k} clipped left out)" if k else "")
        for name, e, k in zip(result.names, result.record_esr, excluded)
    ]
    lines.append("[[Parameters]]")
    pw = max(len(n) for n in model.parameter_names)
    for name in model.parameter_names:
        text = model.parameter(name).format(result.values[name])
        lines.append(f"  {name:<{pw}}  {text}" + ("" if name in result.free else " (fixed)"))
    if validation:
        lines.append("[[Validation]] (the identified set on other records)")
        lines += [f"  {name}: ESR {m['esr']:.4g}, RMS residual {m['rms_residual_N']:.4g} N" for name, m in validation]
    if result.warnings:
        lines.append("[[Warnings]]")
        lines += [f"  {w}" for w in result.warnings]
    return "\n".join(lines)


def joint_json(
    result: JointResult, model_name: str, control_reference: str | None, validation: Sequence[tuple[str, dict]] = ()
) -> dict:
    """The ``identify --joint --json`` object: ``model``, ``esr`` (the mean of the per-record ESRs), ``records``
    (name, esr, excluded_samples), ``parameters`` (strings with units), ``parameters_si`` (value, unit, status
    "free" or "fixed", initial), ``control_reference``, ``success``, ``message``, ``warnings``, ``validation``."""

    def num(x):
        return None if x is None or not math.isfinite(x) else float(x)

    model = result.model
    excluded = result.excluded_samples or [0] * len(result.names)
    initial = result.initial
    return {
        "model": model_name,
        "joint": True,
        "esr": num(result.mean_esr),
        "records": [
            {"record": n, "esr": num(e), "excluded_samples": k}
            for n, e, k in zip(result.names, result.record_esr, excluded)
        ],
        "parameters": {n: model.parameter(n).format(v) for n, v in result.values.items()},
        "parameters_si": {
            n: {
                "value": float(v),
                "unit": model.parameter(n).unit,
                "status": "free" if n in result.free else "fixed",
                "initial": None if n not in initial else float(initial[n]),
            }
            for n, v in result.values.items()
        },
        "control_reference": control_reference,
        "success": bool(result.success),
        "message": result.message,
        "simulations": result.simulations,
        "seconds": num(result.seconds),
        "warnings": list(result.warnings),
        "validation": [
            {"record": name, **{k: num(v) if isinstance(v, float) else v for k, v in m.items()}}
            for name, m in validation
        ],
    }


@dataclass
class CrossValidation:
    """ESR table: ``table[i][j]`` is the ESR on record i of the model identified on record j (Vivas-López et al., Table 4)."""

    names: list[str]
    table: np.ndarray

    @property
    def average(self) -> np.ndarray:
        """Mean ESR of each identification record over all validation records (the table's last row)."""
        return self.table.mean(axis=0)

    def markdown(self) -> str:
        head = "| validation \\ identification | " + " | ".join(self.names) + " |"
        rule = "|---" * (len(self.names) + 1) + "|"
        rows = [f"| {n} | " + " | ".join(f"{x:.4f}" for x in row) + " |" for n, row in zip(self.names, self.table)]
        rows.append("| average | " + " | ".join(f"{x:.4f}" for x in self.average) + " |")
        return "\n".join([head, rule, *rows])


def _cross_validation_column(model_factory, records: Sequence[Measurement], fit_options: dict, j: int) -> list:
    """ESR on every record of the model identified on record j (one column of the table; a task)."""
    r = identify(model_factory(), records[j], **fit_options)
    return [
        r.esr if i == j else esr(other.require_force(), r.model.simulate(other, r.values))
        for i, other in enumerate(records)
    ]


def cross_validation(model_factory, records: Sequence[Measurement], *, executor=None, **fit_options) -> CrossValidation:
    """Identify a fresh model (``model_factory()``) on each record and score it on every record.

    The identifications run on ``executor`` (:func:`erdesign.executor.executor_for`; default one after the other in
    this process); on worker processes ``model_factory`` must be picklable (``functools.partial(get_model,
    "bingham")``, not a lambda).  The table does not depend on the executor."""
    from functools import partial

    from ..executor import executor_for

    records = list(records)
    runner = executor_for(executor)
    try:
        columns = runner.map(
            partial(_cross_validation_column, model_factory, records, fit_options), range(len(records))
        )
    finally:
        if runner is not executor:
            runner.close()
    table = np.array(columns, dtype=float).T.reshape(len(records), len(records))
    return CrossValidation([r.name or f"record {k}" for k, r in enumerate(records)], table)


# ------------------------------------------------------------------------------------------- simulate and score
def score(force, model_force, mask=None) -> dict:
    """Figures of merit of a model force against a measured one, over the samples of ``mask`` (all by default).

    Keys (SI): ``esr`` (Vivas-López et al., eq 7), ``r_squared`` (1 - ESR), ``rms_residual_N`` and ``peak_residual_N``
    (Makris's RMS and PV of the difference signal), ``samples_scored``.
    """
    F = np.asarray(force, dtype=float)
    M = np.asarray(model_force, dtype=float)
    if mask is not None:
        F, M = F[mask], M[mask]
    e = esr(F, M)
    d = F - M
    return {
        "esr": e,
        "r_squared": 1.0 - e,
        "rms_residual_N": float(np.sqrt(np.mean(d**2))),
        "peak_residual_N": float(np.max(np.abs(d))),
        "samples_scored": int(F.size),
    }


@dataclass
class ParameterSource:
    """Where a parameter set came from: ``kind`` is "published", "json" or "list"."""

    kind: str
    label: str
    source: str = ""
    note: str = ""


@dataclass
class Simulation:
    """A model run with given parameters on a record, and its scores."""

    model: Model
    values: dict[str, float]
    force: np.ndarray
    """Model force [N] at every sample."""
    metrics: dict
    clipped: int
    """Force samples of the record at a flat top or bottom (:func:`erdesign.data.measurement.clipped_samples`)."""
    excluded: int
    """Samples left out of the scores (the clipped ones when asked)."""
    source: ParameterSource | None = None
    warnings: list[str] | None = None


def _control_reference_from_text(text: str, record: Measurement, where: str) -> float:
    from ..fluid import CONTROL_UNITS
    from ..units import parse_quantity

    q = parse_quantity(text, f"{where}: control_reference")
    try:
        return float(q.to(CONTROL_UNITS[record.control_kind]).magnitude)
    except Exception:
        raise ErdesignError(
            f"{where}: control_reference {text!r} is not a {record.control_kind} (the record's control)"
        ) from None


def resolve_parameters(
    model: Model, spec: str, record: Measurement, *, control_reference: str | None = None, where: str = "params"
) -> tuple[dict[str, float], ParameterSource, list[str]]:
    """SI values of ``model`` from a parameter specification, and the control reference set on the model.

    ``spec`` is one of: a JSON file written by ``erdesign identify --json`` (its ``parameters_si`` when present,
    else its ``parameters`` strings, and its ``control_reference``); a list ``"name=value unit, ..."``; or the name
    of a published set of the model (:mod:`erdesign.models.published`).  Returns (values, source, warnings).
    Errors name the specification as ``where`` (the command line passes its flag).
    """
    import json
    from pathlib import Path

    from ..models.published import (
        parse_parameter_list,
        parse_parameter_values,
        published_set,
    )

    notes: list[str] = []
    kind = record.control_kind
    path = Path(spec)
    if spec.lower().endswith(".json") or path.is_file():
        from ..limits import MAX_TOML_BYTES, nested_too_deeply, read_input_bytes

        try:
            data = json.loads(read_input_bytes(path, MAX_TOML_BYTES, "a JSON file of parameters", spec).decode())
        except FileNotFoundError:
            raise ErdesignError(f"{where}: no such file {spec}") from None
        except IsADirectoryError:
            raise ErdesignError(f"{where}: {spec} is a folder, not a JSON file") from None
        except (json.JSONDecodeError, UnicodeDecodeError) as exc:
            raise ErdesignError(f"{where}: {spec} is not a JSON file ({exc})") from None
        except RecursionError:
            raise ErdesignError(f"{where}: {nested_too_deeply(spec)}") from None
        except ErdesignError as exc:
            raise ErdesignError(f"{where}: {exc}") from None
        if not isinstance(data, dict) or not isinstance(data.get("parameters"), dict):
            raise ErdesignError(
                f"{where}: {spec} has no 'parameters' object (expected the output of 'erdesign identify --json')"
            )
        if data.get("model") not in (None, model.name):
            raise ErdesignError(f"{where}: {spec} holds parameters of model {data['model']}, not {model.name}")
        ref_text = control_reference or data.get("control_reference")
        if model.uses_control and kind is not None:
            if ref_text:
                model.control_reference = _control_reference_from_text(ref_text, record, where)
            else:
                ref = choose_control_reference(model, [record])
                notes.append(
                    f"{spec} gives no control_reference: u = {kind} / {ref:g} (SI), the rule identify "
                    "uses on this record"
                )
        si = data.get("parameters_si")
        if isinstance(si, dict) and si:
            values = {k: float(v["value"] if isinstance(v, dict) else v) for k, v in si.items()}
            for k in values:
                model.parameter(k)
        else:
            values = parse_parameter_values(
                model, data["parameters"], control_kind=kind, control_reference=model.control_reference, where=spec
            )
        return values, ParameterSource("json", spec), notes
    if "=" in spec:
        texts = parse_parameter_list(spec)
        if model.uses_control and kind is not None:
            if control_reference:
                model.control_reference = _control_reference_from_text(control_reference, record, "control_reference")
            else:
                choose_control_reference(model, [record])
        values = parse_parameter_values(model, texts, control_kind=kind, control_reference=model.control_reference)
        return values, ParameterSource("list", f"{where} list"), notes
    pub = published_set(model.name, spec)
    if pub.control_kind is not None:
        if kind is None:
            notes.append(
                f"{spec} is for a record with a {pub.control_kind} column; {record.name or 'the record'} "
                "has none: the control is taken as zero"
            )
        elif kind != pub.control_kind:
            raise ErdesignError(
                f"{where}: {spec} is for a {pub.control_kind} control (its coefficients are per "
                f"unit {pub.control_kind}); the record's control is a {kind}"
            )
        model.control_reference = pub.control_reference
    elif model.uses_control and kind is not None and np.ptp(record.control) > 0:
        notes.append(f"{spec} describes one fixed field; the record's {kind} varies and is ignored by its coefficients")
    return dict(pub.values), ParameterSource("published", spec, pub.source, pub.note), notes


def simulate(
    model: Model,
    record: Measurement,
    values: Mapping[str, float],
    *,
    exclude_clipped: bool = False,
    source: ParameterSource | None = None,
) -> Simulation:
    """Run ``model`` with ``values`` on the record's motion and control (from rest at the first sample) and score
    it against the record's force (all samples, or without the clipped ones when ``exclude_clipped``).  A record
    without force (a test plan of ``erdesign doe``) is run and not scored: its metrics are None."""
    from ..data.measurement import clipped_samples

    F = record.force
    force = model.simulate(record, values)
    if F is None:
        if not np.all(np.isfinite(force)):
            raise ErdesignError(f"{model.name}: the parameters give non-finite forces on {record.name or 'the record'}")
        unscored = {
            "esr": None,
            "r_squared": None,
            "rms_residual_N": None,
            "peak_residual_N": None,
            "samples_scored": 0,
        }
        return Simulation(model, model.check_values(values), force, unscored, 0, 0, source, [])
    clipped = clipped_samples(F)
    mask = ~clipped if exclude_clipped and clipped.any() else None
    metrics = score(F, force, mask)
    notes = []
    if not np.all(np.isfinite(force)):
        raise ErdesignError(f"{model.name}: the parameters give non-finite forces on {record.name or 'the record'}")
    if clipped.any() and not exclude_clipped:
        level = F[clipped]
        notes.append(
            f"{int(clipped.sum())} force samples sit at a flat {'top' if level[0] > 0 else 'bottom'} "
            f"({level[0]:.6g} N): a load cell or amplifier at its limit; exclude_clipped=True scores without "
            f"them"
        )
    return Simulation(
        model,
        model.check_values(values),
        force,
        metrics,
        int(clipped.sum()),
        int(clipped.sum()) if mask is not None else 0,
        source,
        notes,
    )
