r"""The pieces every fit of erdesign shares, written once: which parameters are free, the search space (log space
for log-scale parameters), the penalty for non-finite residuals, the stopping tolerance, the start box of
multi-starts, the uncertainty of the free parameters, the threshold of a "strong" correlation, the one rule of a
parameter "at a bound" (:func:`at_bound`), and the one solver: :func:`solve` of a :class:`Problem` (what is fitted)
by a :class:`Strategy` (how: starts, global search, projection, time budget, stall rule, executor).

:func:`erdesign.identification.fit.fit`, :func:`erdesign.identification.identify.identify`,
:func:`~erdesign.identification.identify.identify_joint` and the diagnosis's calibration
(:mod:`erdesign.diagnosis.calibration`, through ``fit``) build a problem and a strategy and call :func:`solve`, so
that a model fitted by any of them to the same samples is set up and searched the same way.
"""

from __future__ import annotations

import copy
import math
import numbers
import time as _time
from collections.abc import Mapping, Sequence
from contextlib import nullcontext
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from .._util import si_array
from ..data.measurement import Measurement
from ..errors import ErdesignError
from ..models._kernels import frozen_substeps
from ..models.base import Model

__all__ = [
    "AT_BOUND_RTOL",
    "CORRELATION_THRESHOLD",
    "FAIL_RATIO",
    "worse_than_reference",
    "FTOL",
    "PENALTY",
    "STALL_RTOL",
    "FitError",
    "Outcome",
    "Problem",
    "Residual",
    "Strategy",
    "SumOfSquares",
    "Transform",
    "ValueMap",
    "at_bound",
    "baseline_esr",
    "control_reference_for",
    "finite_residual",
    "local_fit",
    "mostly_at_bounds",
    "problem",
    "resolve_free",
    "solve",
    "start_box",
    "strong_correlations",
    "uncertainty",
    "with_control_reference",
]


class FitError(ErdesignError):
    """The fit cannot be set up (no free parameter, too few samples, model fails on the record)."""


#: Residual [N] put in place of a non-finite one (a trial point where the model overflows): large enough that the
#: optimiser backs away, finite so that its trust region stays defined.
PENALTY = 1e12

#: Relative decrease of the sum of squares below which the optimiser stops: 1e-6 changes the ESR in its sixth
#: digit, far below what a record can tell (scipy's default 1e-8 spends hundreds of simulations on such digits).
FTOL = 1e-6

#: |correlation| above which two free parameters are reported as correlated (the data fix their combination, not
#: each value).
CORRELATION_THRESHOLD = 0.9


def finite_residual(r: np.ndarray) -> np.ndarray:
    """``r`` with every non-finite entry replaced by :data:`PENALTY`."""
    return np.where(np.isfinite(r), r, PENALTY)


class Transform:
    """Free parameters <-> search vector: log space for log-scale parameters, the value itself otherwise."""

    def __init__(self, model: Model, free: Sequence[str]):
        self.params = [model.parameter(n) for n in free]
        self.log = np.array([p.log_scale for p in self.params], dtype=bool)

    def to_search(self, values: Sequence[float]) -> np.ndarray:
        v = np.asarray(values, dtype=float)
        with np.errstate(divide="ignore"):
            return np.where(self.log, np.log(np.where(self.log, v, 1.0)), v)

    def to_values(self, z: np.ndarray) -> np.ndarray:
        return np.where(self.log, np.exp(np.where(self.log, z, 0.0)), z)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo = np.array([p.lower for p in self.params], dtype=float)
        hi = np.array([p.upper for p in self.params], dtype=float)
        return self.to_search(lo), self.to_search(hi)

    def dvalue_dz(self, z: np.ndarray) -> np.ndarray:
        return np.where(self.log, np.exp(np.where(self.log, z, 0.0)), 1.0)


class ValueMap:
    """Search vector -> all parameter values: ``base`` with ``names`` set from z (:class:`Transform`).  A class, not
    a closure, so that the residuals built on it can be sent to worker processes."""

    def __init__(self, base: Mapping[str, float], names: Sequence[str], tr: Transform):
        self.base, self.names, self.tr = dict(base), tuple(names), tr

    def __call__(self, z: np.ndarray) -> dict[str, float]:
        out = dict(self.base)
        out.update(zip(self.names, (float(v) for v in self.tr.to_values(z))))
        return out


class Residual:
    """Model minus measured force [N] on the compared samples of each record (all, or those of its mask), each
    record's part times its weight (when ``weights`` are given), concatenated, as a function of the search vector;
    non-finite entries replaced by :data:`PENALTY`.  Counts simulations, keeps the best point, reports progress and
    raises :class:`_OutOfTime` past ``deadline`` (:func:`time.monotonic`).  Picklable without ``progress``."""

    def __init__(
        self,
        model: Model,
        records: Sequence[Measurement],
        values: ValueMap,
        masks: Sequence[np.ndarray | None] | None = None,
        weights: Sequence[float] | None = None,
        deadline: float | None = None,
        progress=None,
    ):
        self.model, self.records, self.values = model, tuple(records), values
        self.masks = tuple(masks) if masks is not None else (None,) * len(self.records)
        self.weights, self.deadline, self.progress = weights, deadline, progress
        self.forces = [r.require_force() for r in self.records]
        self.total = sum(len(r) if m is None else int(m.sum()) for r, m in zip(self.records, self.masks))
        compared = [
            (1.0 if weights is None else w) * (F if m is None else F[m])
            for F, m, w in zip(self.forces, self.masks, weights or [None] * len(self.forces))
        ]
        self.spread = float(sum(np.sum((c - c.mean()) ** 2) for c in compared))
        """Sum of squares of the compared (weighted) forces about their mean: the ESR's denominator."""
        self.calls, self.best_cost, self.best_z, self.last_report = 0, math.inf, None, _time.monotonic()

    def __call__(self, z: np.ndarray) -> np.ndarray:
        if self.deadline is not None and _time.monotonic() > self.deadline:
            raise _OutOfTime
        v = self.values(z)
        if self.weights is None:
            parts = [self.model.force(r, v) - F for r, F in zip(self.records, self.forces)]
        else:
            parts = [w * (self.model.force(r, v) - F) for r, F, w in zip(self.records, self.forces, self.weights)]
        parts = [p if m is None else p[m] for p, m in zip(parts, self.masks)]
        out = finite_residual(parts[0] if len(parts) == 1 else np.concatenate(parts))
        cost = float(np.dot(out, out))
        self.calls += 1
        if cost < self.best_cost:
            self.best_cost, self.best_z = cost, np.array(z, dtype=float)
        now = _time.monotonic()
        if self.progress is not None and now - self.last_report > 2.0:
            self.last_report = now
            self.progress(
                f"joint fit of {len(self.records)} records: {self.calls} simulations of all, "
                f"mean weighted sum of squares {self.best_cost / self.total:.4g}"
            )
        return out


class SumOfSquares:
    """The sum of squares of a residual (the objective of a global search); picklable."""

    def __init__(self, residual):
        self.residual = residual

    def __call__(self, z: np.ndarray) -> float:
        r = self.residual(z)
        return float(np.dot(r, r))


def local_fit(residual, lo: np.ndarray, hi: np.ndarray, max_nfev: int | None, z: np.ndarray):
    """One local start: bounded trust-region-reflective least squares (:func:`scipy.optimize.least_squares`) of
    ``residual`` from z, with the one :data:`FTOL`.  A module-level function: a task for an executor."""
    from scipy.optimize import least_squares  # imported on use: not at start-up

    return least_squares(
        residual, np.clip(z, lo, hi), bounds=(lo, hi), method="trf", x_scale="jac", max_nfev=max_nfev, ftol=FTOL
    )


def resolve_free(
    model: Model,
    records: Sequence[Measurement],
    free: Sequence[str] | None = None,
    fixed: Mapping[str, float] | None = None,
) -> tuple[tuple[str, ...], dict[str, float]]:
    """The free parameters and the held values (SI) of a fit of ``model`` to ``records``.

    Held, unless the caller names them in ``free``: the parameters chosen a priori (not ``fitted``) and the control
    parameters when no record has a control column (:meth:`~erdesign.models.base.Model.fixed_for`), and the control
    parameters when every record's control is zero (the records cannot show the control dependence).  ``fixed``
    (SI) overrides.  Unknown names are errors; so is a fit with nothing free.
    """
    fixed = dict(fixed or {})
    for k in list(fixed) + list(free or ()):
        model.parameter(k)  # unknown names are errors
    auto = dict(model.fixed_for(records[0])) if hasattr(model, "fixed_for") else {}
    if all(r.control_kind is not None and not np.any(r.control) for r in records):
        auto.update({k: model.parameter(k).default for k in model.control_parameters})
    auto = {k: v for k, v in auto.items() if free is None or k not in free}
    fixed = {**auto, **fixed}
    names = tuple(n for n in (free if free is not None else model.parameter_names) if n not in fixed)
    if not names:
        raise FitError(f"{model.name}: no free parameter to fit")
    return names, fixed


@dataclass(frozen=True)
class Problem:
    """A fit set up: the model (a copy with the records' control reference), the records and the samples of each
    that are compared (``masks``, None for all), the free parameters, the held values, the start values of all
    parameters (``base``, SI) and the search space (``transform``, bounds ``lo``/``hi``, start ``z0``)."""

    model: Model
    records: tuple[Measurement, ...]
    masks: tuple[np.ndarray | None, ...]
    free: tuple[str, ...]
    fixed: dict[str, float]
    base: dict[str, float]
    transform: Transform
    lo: np.ndarray
    hi: np.ndarray
    z0: np.ndarray
    weights: tuple[float, ...] | None = None
    """Weight of each record's residual (None: all 1)."""

    @property
    def values(self) -> ValueMap:
        """Search vector -> all parameter values."""
        return ValueMap(self.base, self.free, self.transform)


def problem(
    model: Model,
    records: Sequence[Measurement],
    *,
    free: Sequence[str] | None = None,
    fixed: Mapping[str, float] | None = None,
    start: Mapping[str, float] | None = None,
    masks: Sequence[np.ndarray | None] | None = None,
    control_reference: bool = True,
    samples: int | None = None,
    label: str = "record",
) -> Problem:
    """Set up a fit of ``model`` to ``records``: the free parameters (:func:`resolve_free`), the start values (the
    model's guess from the first record, then ``start``, then ``fixed``; checked within bounds), the search space.
    With ``control_reference`` the fit works on a copy of the model with the records' reference
    (:func:`with_control_reference`); otherwise on the model as given (it is not changed).  Unknown names in
    ``start`` are errors; so are ``samples`` (the number compared) too few for the free parameters (the error
    names ``label``)."""
    records = tuple(records)
    fixed, start = _values_arg(fixed, "fixed"), _values_arg(start, "start")
    if isinstance(free, str):  # free="c0" was read letter by letter: "no parameter 'c'"
        raise FitError(f"free: expected a list of parameter names, got the text {free!r} (write [{free!r}])")
    if masks is not None:
        masks = [_mask_arg(m, r) for m, r in zip(masks, records)]
    if control_reference:
        model = with_control_reference(model, records)
    free, fixed = resolve_free(model, records, free, fixed)
    if samples is not None and samples <= len(free):
        raise FitError(f"{label}: {samples} samples cannot determine {len(free)} parameters")
    for k in start or {}:
        model.parameter(k)
    guess = {k: v for k, v in model.initial_guess(records[0]).items() if k in model.parameter_names}
    base = model.check_values({**guess, **(start or {}), **fixed})
    tr = Transform(model, free)
    lo, hi = tr.bounds()
    z0 = np.clip(tr.to_search([base[n] for n in free]), lo, hi)
    return Problem(
        model, records, tuple(masks) if masks is not None else (None,) * len(records), free, fixed, base, tr, lo, hi, z0
    )


def _values_arg(values: Any, name: str) -> dict[str, float] | None:
    """``fixed`` or ``start`` as a dict of name -> SI float, or a :class:`FitError` naming the argument and key: a
    pandas Series was "The truth value of a Series is ambiguous", a text value "ufunc 'isfinite' not supported"."""
    if values is None:
        return None
    if not isinstance(values, Mapping):
        raise FitError(f"{name}: expected a mapping of parameter name -> value (a dict), got {type(values).__name__}")
    out = {}
    for k, v in values.items():
        x = si_array(v, f"{name}[{k!r}]")
        if x.ndim != 0:
            raise FitError(f"{name}[{k!r}]: expected one value, got an array of shape {x.shape}")
        out[k] = float(x)
    return out


def _mask_arg(mask: Any, record: Measurement) -> np.ndarray | None:
    """A mask of the samples to compare: true/false, one per sample of ``record`` (a list of 10 for 1000 samples was
    an IndexError; 0/1 integers were read as indices)."""
    if mask is None:
        return None
    arr = np.asarray(mask)
    if arr.dtype != bool or arr.shape != record.time.shape:
        raise FitError(
            f"mask: expected true/false for each of the {record.time.size} samples, got {arr.dtype} of shape {arr.shape}"
        )
    return arr


def control_reference_for(records: Sequence[Measurement]) -> float:
    """Power of ten near the largest |control| of the records (1 when they have none), so that a model's
    dimensionless control u = control / reference is of order one and its per-unit parameters stay readable."""
    peak = max((float(np.max(np.abs(r.control))) for r in records if r.control_kind is not None), default=0.0)
    return 10.0 ** math.floor(math.log10(peak)) if peak > 0 else 1.0


def with_control_reference(model: Model, records: Sequence[Measurement]) -> Model:
    """A shallow copy of ``model`` with the control reference of ``records`` (:func:`control_reference_for`): fits
    work on it, so the caller's model object is never changed."""
    out = copy.copy(model)
    out.control_reference = control_reference_for(records)
    return out


def start_box(lo: np.ndarray, hi: np.ndarray, z0: np.ndarray, log: np.ndarray | None = None):
    """Box for sampling starts around the start z0, within the bounds: two decades either way for log-scale
    parameters, +-3 (1 + |z0|) otherwise (physical bounds such as 1e7 N are far too wide to sample uniformly)."""
    span = 3.0 * (1.0 + np.abs(z0))
    if log is not None:
        span = np.where(log, np.log(100.0), span)
    return np.maximum(lo, z0 - span), np.minimum(hi, z0 + span)


def uncertainty(jac: np.ndarray, z: np.ndarray, tr: Transform, rss: float, n: int, k: int):
    """Standard errors and correlations of the free parameters from the Jacobian at the optimum.

    The Jacobian columns are scaled to unit norm before the SVD pseudo-inverse (parameters in N, N s/m and 1/m^2
    differ by many decades; unscaled, the well-determined but small columns would look singular); directions the
    data do not constrain get NaN errors instead of garbage."""
    J = np.asarray(jac, dtype=float) / tr.dvalue_dz(z)[np.newaxis, :]  # d residual / d value (chain rule)
    s2 = rss / max(n - k, 1)
    norms = np.linalg.norm(J, axis=0)
    scale = np.where(norms > 0, norms, 1.0)
    U, sv, Vt = np.linalg.svd(J / scale, full_matrices=False)
    good = sv > (sv.max() if sv.size else 0.0) * 1e-10
    inv = np.where(good, 1.0 / np.where(good, sv, 1.0) ** 2, 0.0)
    cov = ((Vt.T * inv) @ Vt) * s2 / np.outer(scale, scale)
    var = np.diag(cov).copy()
    unidentifiable = (np.abs(Vt[~good]).max(axis=0) > 1e-3 if (~good).any() else np.zeros(k, bool)) | (norms == 0)
    se = np.where(unidentifiable | (var < 0), np.nan, np.sqrt(np.maximum(var, 0.0)))
    with np.errstate(invalid="ignore", divide="ignore"):
        d = np.sqrt(np.maximum(var, 0.0))
        corr = cov / np.outer(d, d)
    corr[~np.isfinite(corr)] = np.nan
    np.fill_diagonal(corr, 1.0)
    return se, corr


def strong_correlations(
    free: Sequence[str], correlation: np.ndarray, threshold: float = CORRELATION_THRESHOLD
) -> list[tuple[str, str, float]]:
    """Pairs of free parameters whose correlation exceeds ``threshold`` in magnitude, strongest first."""
    pairs = []
    for i in range(len(free)):
        for j in range(i + 1, len(free)):
            c = correlation[i, j]
            if np.isfinite(c) and abs(c) > threshold:
                pairs.append((free[i], free[j], float(c)))
    return sorted(pairs, key=lambda p: -abs(p[2]))


# ------------------------------------------------------------------------------------------------- at a bound
#: A free parameter is "at a bound" when its distance to the bound is below this fraction of its range (in log
#: space for log-scale parameters; for a linear one, of the range or 1e3 x its own scale, whichever is smaller).
AT_BOUND_RTOL = 1e-6


def at_bound(parameter, value: float, stderr: float | None = None) -> str | None:
    """ "lower" / "upper" when ``value`` of ``parameter`` (a :class:`~erdesign.parameters.Parameter`) sits on a
    bound, else None: within :data:`AT_BOUND_RTOL` of its range (log space for log-scale parameters; a wide linear
    range, a stiffness from 0 to 1e9 N/m, must not call 259 N/m "at 0": there the tolerance follows the parameter's
    own scale, its default or value, times 1e3), or within one standard error ``stderr`` when one is given.  The one
    rule of the report, the poor-fit check (:func:`mostly_at_bounds`) and the diagnosis."""
    p = parameter
    v, lo, hi = float(value), p.lower, p.upper
    if p.log_scale:
        v, lo, hi = math.log(max(v, 1e-300)), math.log(lo), (math.log(hi) if math.isfinite(hi) else hi)
    span = (hi - lo) if math.isfinite(hi - lo) else max(abs(v), 1.0)
    if not p.log_scale:
        span = min(span, max(abs(p.default), abs(v), 1e-300) * 1e3)
    near = stderr if stderr is not None and math.isfinite(stderr) else 0.0
    if math.isfinite(lo) and (v - lo <= AT_BOUND_RTOL * span or abs(float(value) - p.lower) < near):
        return "lower"
    if math.isfinite(hi) and (hi - v <= AT_BOUND_RTOL * span or abs(float(value) - p.upper) < near):
        return "upper"
    return None


def mostly_at_bounds(model: Model, free: Sequence[str], values: Mapping[str, float]) -> bool:
    """More than half of the free parameters at a bound (:func:`at_bound`): a fit the bounds, not the data, set."""
    on = sum(at_bound(model.parameter(n), values[n]) is not None for n in free)
    return bool(free) and on > len(free) / 2


# ------------------------------------------------------------------------------------------------- the solver
#: A start "fails" when the optimiser stops without converging, leaves more than this fraction of the variance the
#: reference Bingham fit leaves (:func:`baseline_esr`), or ends with most free parameters at a bound: with
#: ``Strategy.rescue`` the other starts are then run, and a best fit above it is a poor fit.
FAIL_RATIO = 1.0

#: ESRs closer than this (relative) are the same number: the same least-squares problem solved two ways (a Bingham
#: model identified against the reference Bingham fit) agrees to the last few digits only (7.581952112373274e-05
#: against 7.581952112373271e-05), which must not make the fit "worse" than the reference.
SAME_ESR_RTOL = 1e-9


def worse_than_reference(esr_value: float, baseline: float) -> bool:
    """An ESR above :data:`FAIL_RATIO` times the reference fit's, beyond rounding (:data:`SAME_ESR_RTOL`)."""
    return bool(esr_value > FAIL_RATIO * baseline * (1.0 + SAME_ESR_RTOL))


#: Records longer than this get a warm start on a decimated copy (at least 1 kHz kept) before all samples.
WARM_START_SAMPLES = 20_000

#: The stall rule of tracked fits: stopped when the best sum of squares improved by less than STALL_RTOL over the
#: last STALL_JACOBIANS Jacobians' worth of simulations.
STALL_RTOL = 1e-4
STALL_JACOBIANS = 3


class _OutOfTime(Exception):
    """Raised inside the residual when the time budget is spent (the best point so far is kept)."""


class _Stalled(Exception):
    """Raised inside the residual when the best sum of squares has improved by less than STALL_RTOL over the last
    STALL_JACOBIANS Jacobians' worth of simulations: the optimiser is polishing digits the data do not hold (its
    finite-difference steps also see the sub-step count of the kernels switch)."""


def baseline_esr(record: Measurement, F: np.ndarray, mask: np.ndarray | None) -> float:
    """ESR of the reference fit: the Bingham model (``bingham``: c0 v + f_c sgn v + f0, its control terms being
    collinear with these on a record of one control) by linear least squares on the fitted samples."""
    from ..data.metrics import esr

    v = record.velocity
    A = np.column_stack([v, np.sign(v), np.ones_like(v)])
    if mask is not None:
        A, F = A[mask], F[mask]
    coef, *_ = np.linalg.lstsq(A, F, rcond=None)
    return esr(F, A @ coef)


@dataclass(frozen=True)
class Strategy:
    """How :func:`solve` searches a :class:`Problem`.

    ``starts`` local starts: the first from the problem's start values, the others from a Latin hypercube in
    :func:`start_box` (seeded by ``seed``); ``global_search`` adds a differential-evolution start second.  With
    ``rescue`` the other starts run only when the first fails (:data:`FAIL_RATIO`), plus one from the model's own
    guess (its reference-fit mapping) when the problem starts elsewhere; without it all run.  ``tracked`` selects
    the identification's residual (Jacobians by forward differences with the kernels' sub-step counts held, the
    stall rule ``stall_rtol`` (None: :data:`STALL_RTOL`), progress lines, optionally ``coarse_steps``,
    ``projection`` of the linear parameters, a ``warm_start`` and ``decimate``); otherwise scipy's own differences
    on the plain residual.  ``max_time`` [s] bounds the wall time, ``max_nfev`` each start.  The starts run on
    ``executor`` (:func:`erdesign.executor.executor_for`); the result does not depend on it."""

    starts: int = 1
    global_search: bool = False
    seed: int = 0
    max_nfev: int | None = None
    rescue: bool = False
    tracked: bool = False
    projection: bool = False
    coarse_steps: bool = True
    stall_rtol: float | None = None
    warm_start: bool = False
    decimate: int = 1
    max_time: float | None = None
    executor: object = None

    def __post_init__(self):
        # fit(starts=0) ran nothing and max_nfev=0 reached scipy ("`max_nfev` must be None or positive integer")
        for name in ("starts", "max_nfev", "decimate"):
            value = getattr(self, name)
            if name == "max_nfev" and value is None:
                continue
            if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 1:
                raise FitError(f"{name}: must be a whole number >= 1, got {value!r}")


@dataclass
class Outcome:
    """One local start: the search vector reached (all free parameters), its sum of squares on the fitted samples,
    the optimiser's verdict, its Jacobian at ``x`` on the problem's samples when it has one, simulations run."""

    x: np.ndarray
    cost: float
    success: bool
    status: int
    message: str
    nfev: int = 0
    jac: np.ndarray | None = None
    calls: int = 0
    spread: float = math.nan
    out_of_time: bool = False


class _Tracker:
    """Residual of one record (optionally on a subset of samples) that counts simulations, keeps the best point,
    reports progress and enforces the time budget; :meth:`jacobian` is its finite-difference Jacobian."""

    def __init__(self, model, record, F, mask, full_values, deadline, progress, label, stall_rtol=None, steps=None):
        self.stall_rtol = STALL_RTOL if stall_rtol is None else stall_rtol
        self.model, self.record, self.F, self.mask = model, record, F, mask
        self.full_values, self.deadline, self.progress, self.label = full_values, deadline, progress, label
        self.steps = steps
        self.best_cost, self.best_z, self.calls = math.inf, None, 0
        self.history: list[float] = []
        self.spread = (
            float(np.sum((F[mask] - F[mask].mean()) ** 2)) if mask is not None else float(np.sum((F - F.mean()) ** 2))
        )
        self.last_report = _time.monotonic()
        self.last = None

    def _residual(self, z):
        if self.deadline is not None and _time.monotonic() > self.deadline:
            raise _OutOfTime
        r = self.model.force(self.record, self.full_values(z)) - self.F
        if self.mask is not None:
            r = r[self.mask]
        return finite_residual(r)

    def _book(self, z, r):
        cost = float(np.dot(r, r))
        self.calls += 1
        if cost < self.best_cost:
            self.best_cost, self.best_z = cost, np.array(z, dtype=float)
        self.history.append(self.best_cost)
        window = STALL_JACOBIANS * (len(z) + 1)
        if len(self.history) > window + 2 * (len(z) + 1) and self.history[-window - 1] <= self.best_cost * (
            1.0 + self.stall_rtol
        ):
            raise _Stalled
        now = _time.monotonic()
        if self.progress is not None and now - self.last_report > 2.0:
            self.last_report = now
            self.progress(f"{self.label}: {self.calls} simulations, best ESR {self.best_cost / self.spread:.4g}")

    def __call__(self, z):
        with frozen_substeps() as plans:  # records the kernels' sub-step counts for the Jacobian at z
            r = self._residual(z)
        self.last = (np.array(z, dtype=float), r, plans)
        self._book(z, r)
        return r

    def jacobian(self, z):
        """Forward differences at z with the sub-step counts of the simulation at z held (smooth in the
        parameters) and steps of 1e-6 of each parameter's scale (:func:`fd_steps`), inside the bounds."""
        if self.last is None or not np.array_equal(self.last[0], z):
            self(z)
        z0, r0, plans = self.last
        J = np.empty((r0.size, z0.size))
        with frozen_substeps(plans):
            for j, h in enumerate(self.steps):
                zp = z0.copy()
                zp[j] += h
                rj = self._residual(zp)
                self._book(zp, rj)
                J[:, j] = (rj - r0) / h
        return J


class _Projection:
    r"""Variable projection (Golub and Pereyra 1973) of the free parameters the force is affine in: for given
    nonlinear parameters, :math:`F = r + B\theta` (:meth:`~erdesign.models.base.Model.linear_terms`) and the linear
    ones :math:`\theta` are the bounded linear least-squares solution - unbounded (scaled columns, LAPACK) when it
    falls inside the bounds, :func:`scipy.optimize.lsq_linear` otherwise."""

    def __init__(self, model, record, F, mask, linear):
        self.model, self.record, self.F, self.mask, self.linear = model, record, F, mask, tuple(linear)
        self.others = tuple(k for k in model.linear_parameters if k not in self.linear)  # held: in the rest
        self.lo = np.array([model.parameter(k).lower for k in self.linear], dtype=float)
        self.hi = np.array([model.parameter(k).upper for k in self.linear], dtype=float)

    def solve(self, values):
        """(theta, residual = model - measured on the fitted samples, B, free columns); None when not finite."""
        cols, rest = self.model.linear_terms(self.record, values)
        rest = np.asarray(rest, dtype=float) + sum((values[k] * cols[k] for k in self.others), 0.0)
        B = np.column_stack([cols[k] for k in self.linear])
        y = self.F - rest
        if self.mask is not None:
            B, y = B[self.mask], y[self.mask]
        if not (np.all(np.isfinite(B)) and np.all(np.isfinite(y))):
            return None
        norms = np.linalg.norm(B, axis=0)
        scale = np.where(norms > 0, norms, 1.0)
        Bs = B / scale
        ts, *_ = np.linalg.lstsq(Bs, y, rcond=None)
        theta = ts / scale
        free = np.ones(theta.size, dtype=bool)
        if np.any(theta < self.lo) or np.any(theta > self.hi):
            from scipy.optimize import lsq_linear

            sol = lsq_linear(Bs, y, bounds=(self.lo * scale, self.hi * scale), method="bvls")
            theta = np.clip(sol.x / scale, self.lo, self.hi)
            free = sol.active_mask == 0
        return theta, B @ theta - y, B, free


class _ProjectedTracker(_Tracker):
    """The residual of :class:`_Tracker` over the nonlinear free parameters only, the linear ones solved inside
    (:class:`_Projection`).  Its Jacobian is Kaufman's (1975): forward differences of the force with the linear
    parameters held at their solution, projected onto the orthogonal complement of the basis columns whose
    parameters are not at a bound - P+1 simulations less the number of linear parameters, and no second-order
    term (Golub and Pereyra 2003, section 3)."""

    def __init__(self, model, record, F, mask, full_values, deadline, progress, label, stall_rtol, steps, projection):
        super().__init__(model, record, F, mask, full_values, deadline, progress, label, stall_rtol, steps)
        self.projection = projection
        self.best_theta = None

    def _book(self, z, r, theta=None):
        if theta is not None and float(np.dot(r, r)) < self.best_cost:
            self.best_theta = np.array(theta)
        super()._book(z, r)

    def _values(self, z, theta):
        return {**self.full_values(z), **dict(zip(self.projection.linear, (float(t) for t in theta)))}

    def __call__(self, z):
        if self.deadline is not None and _time.monotonic() > self.deadline:
            raise _OutOfTime
        with frozen_substeps() as plans:
            sol = self.projection.solve(self.full_values(z))
        if sol is None:
            theta = np.clip(np.zeros(len(self.projection.linear)), self.projection.lo, self.projection.hi)
            n = self.F.size if self.mask is None else int(self.mask.sum())
            sol = (theta, np.full(n, PENALTY), None, None)
        theta, r = sol[0], finite_residual(sol[1])
        self.last = (np.array(z, dtype=float), r, plans, sol)
        self._book(z, r, theta)
        return r

    def jacobian(self, z):
        if self.last is None or not np.array_equal(self.last[0], z):
            self(z)
        z0, r0, plans, (theta, _, B, free) = self.last
        J = np.empty((r0.size, z0.size))
        with frozen_substeps(plans):
            for j, h in enumerate(self.steps):
                zp = z0.copy()
                zp[j] += h
                if self.deadline is not None and _time.monotonic() > self.deadline:
                    raise _OutOfTime
                rj = self.model.force(self.record, self._values(zp, theta)) - self.F
                rj = finite_residual(rj if self.mask is None else rj[self.mask])
                self._book(zp, rj, theta)
                J[:, j] = (rj - r0) / h
        if B is not None and free.any():
            Bf = B[:, free]
            # an orthonormal basis of the columns' range by SVD, not QR: columns may be dependent (a control slope
            # on a record of constant control), and QR's Q would then remove directions outside the range
            U, sv, _ = np.linalg.svd(
                Bf / np.where(np.linalg.norm(Bf, axis=0) > 0, np.linalg.norm(Bf, axis=0), 1.0), full_matrices=False
            )
            U = U[:, sv > 1e-10 * sv.max()] if sv.size and sv.max() > 0 else U[:, :0]
            J -= U @ (U.T @ J)
        return J


def fd_steps(tr, names, model, z, lo, hi, rel=1e-6):
    """Finite-difference steps in the search space: ``rel`` in log space for log-scale parameters; otherwise
    ``rel`` times the parameter's scale, the largest |value| among the free parameters of its unit (a control
    slope that starts at zero gets the scale of its base value), 1 when they are all zero.  A step points into the
    bounds."""
    z = np.asarray(z, dtype=float)
    units = [model.parameter(n).unit for n in names]
    steps = np.empty(z.size)
    for j, (unit, lg) in enumerate(zip(units, tr.log)):
        if lg:
            scale = 1.0
        else:
            same = [abs(z[k]) for k in range(z.size) if units[k] == unit and not tr.log[k]]
            scale = max(same) or 1.0
        h = rel * scale
        steps[j] = -h if z[j] + h > hi[j] and z[j] - h >= lo[j] else h
    return steps


def fd_jacobian(fun, z, steps):
    """Forward-difference Jacobian of ``fun`` at z with the given steps and the kernels' sub-step counts held;
    returns (r0, J)."""
    J = np.empty((0, z.size))
    with frozen_substeps():
        r0 = fun(z)
        J = np.empty((r0.size, z.size))
        for j, h in enumerate(steps):
            zp = z.copy()
            zp[j] += h
            J[:, j] = (fun(zp) - r0) / h
    return r0, J


def _stalled_message() -> str:
    return (
        f"converged: the sum of squares improved by less than {100 * STALL_RTOL:g} % over the last "
        f"{STALL_JACOBIANS} Jacobians"
    )


def _stages(pb: Problem, st: Strategy):
    """(record, force, mask, label) of each stage of a tracked start: a decimated warm start on long records, then
    all samples (or only the decimated record); and the stall tolerance of each stage."""
    record, mask = pb.records[0], pb.masks[0]
    decimate = max(1, int(st.decimate))
    fit_rec = record if decimate == 1 else record.select(slice(None, None, decimate))
    fit_mask = mask if decimate == 1 or mask is None else mask[::decimate]
    stages, stall = [], {}
    if st.warm_start and decimate == 1 and len(record) > WARM_START_SAMPLES:
        # at least 1 kHz kept: coarser, the motion read as linear between samples cuts reversals enough to move
        # the optimum of a hysteretic model (on Dyke's 3 kHz record every 5th sample gave ESR 0.121 on all samples
        # for an optimum of 0.101 on the decimated copy)
        k = int(max(2, min(math.ceil(len(record) / 15_000), math.floor(record.sample_rate / 1000.0))))
        coarse = record.select(slice(None, None, k))
        stages.append((coarse, coarse.force, None if mask is None else mask[::k], f"every {k}th sample"))
        stall = {0: 1e-3}  # the warm start needs no more than three digits
    stages.append((fit_rec, fit_rec.force, fit_mask, "all samples" if decimate == 1 else f"every {decimate}th sample"))
    return stages, stall


def _linear_free(pb: Problem, st: Strategy) -> tuple[str, ...]:
    return tuple(n for n in pb.free if n in pb.model.linear_parameters) if st.projection else ()


def _tracked_start(pb: Problem, st: Strategy, deadline, progress, label, z_start) -> Outcome:
    """One tracked start from ``z_start`` through the stages (:func:`_stages`); by variable projection when the
    strategy projects and linear parameters are free.  A module-level function: a task for an executor."""
    from scipy.optimize import least_squares

    from ..models._kernels import coarse_steps

    model, free, base, tr, lo, hi = pb.model, pb.free, pb.base, pb.transform, pb.lo, pb.hi
    stages, stall = _stages(pb, st)
    linear = _linear_free(pb, st)
    z = np.clip(z_start, lo, hi)
    if linear:
        nl = tuple(n for n in free if n not in linear)
        nl_index = [free.index(n) for n in nl]
        trn = Transform(model, nl)
        lon, hin = lo[nl_index], hi[nl_index]
        zn = z[nl_index]
        theta = np.array([base[n] for n in linear])
        run_values = ValueMap(base, nl, trn)
    else:
        trn, lon, hin, zn, run_values = tr, lo, hi, z, ValueMap(base, free, tr)
    res, out_of_time, tracker = None, False, None
    for k, (rec, F, m, stage) in enumerate(stages):
        names = nl if linear else free
        steps = fd_steps(trn, names, model, zn, lon, hin)
        rtol = stall.get(k, STALL_RTOL if st.stall_rtol is None else st.stall_rtol)
        if linear:
            tracker = _ProjectedTracker(
                model,
                rec,
                F,
                m,
                run_values,
                deadline,
                progress,
                f"{label}, {stage}",
                rtol,
                steps,
                _Projection(model, rec, F, m, linear),
            )
        else:
            tracker = _Tracker(model, rec, F, m, run_values, deadline, progress, f"{label}, {stage}", rtol, steps)
        try:
            if linear and not nl:  # every free parameter enters linearly: one linear solve
                tracker(zn)
                res = Outcome(
                    np.empty(0),
                    tracker.best_cost,
                    True,
                    1,
                    "linear least squares: every free parameter enters the force linearly",
                    tracker.calls,
                )
            else:
                with coarse_steps() if st.coarse_steps else nullcontext():
                    sol = least_squares(
                        tracker,
                        zn,
                        jac=tracker.jacobian,
                        bounds=(lon, hin),
                        method="trf",
                        x_scale="jac",
                        max_nfev=st.max_nfev,
                        ftol=FTOL,
                        xtol=1e-8,
                    )
                res = Outcome(
                    sol.x, 2.0 * sol.cost, bool(sol.success), int(sol.status), str(sol.message), int(sol.nfev), sol.jac
                )
                zn = sol.x
                if linear and not np.array_equal(tracker.last[0], zn):
                    tracker(zn)
            if linear:
                theta = tracker.last[3][0]
        except _Stalled:
            zn = tracker.best_z
            if linear:
                theta = tracker.best_theta
            res = Outcome(zn, tracker.best_cost, True, 2, _stalled_message(), tracker.calls)
        except _OutOfTime:
            out_of_time = True
            if tracker.best_z is not None:
                zn = tracker.best_z
                if linear:
                    theta = tracker.best_theta
            res = None
            break
    if linear:
        vals = {**run_values(zn), **dict(zip(linear, (float(t) for t in theta)))}
        z = np.clip(tr.to_search([vals[n] for n in free]), lo, hi)
    else:
        z = zn
    if res is None:
        return Outcome(
            z,
            tracker.best_cost,
            False,
            0,
            "stopped by max_time: the best point found so far",
            0,
            None,
            tracker.calls,
            tracker.spread,
            out_of_time,
        )
    full_samples = stages[-1][0] is pb.records[0]
    jac = res.jac if res.jac is not None and full_samples and np.array_equal(res.x, z) else None
    return Outcome(
        z, res.cost, res.success, res.status, res.message, res.nfev, jac, tracker.calls, tracker.spread, out_of_time
    )


def _plain_start(residual, lo, hi, max_nfev, z) -> Outcome:
    """One start of :func:`local_fit` on a :class:`Residual` (fit, calibration, joint fits).  A task."""
    try:
        res = local_fit(residual, lo, hi, max_nfev, z)
    except _OutOfTime:
        x = np.clip(z, lo, hi) if residual.best_z is None else residual.best_z
        return Outcome(
            x,
            residual.best_cost,
            False,
            0,
            "stopped by max_time: the best point found so far",
            0,
            None,
            residual.calls,
            residual.spread,
            out_of_time=True,
        )
    return Outcome(
        res.x,
        2.0 * res.cost,
        bool(res.success),
        int(res.status),
        str(res.message),
        int(res.nfev),
        res.jac,
        residual.calls,
        residual.spread,
    )


def _start_task(pb: Problem, st: Strategy, deadline, progress, residual, item) -> Outcome:
    """Start ``i`` of ``n`` from z (``item``): tracked or plain.  A task for an executor."""
    i, n, z = item
    if progress is not None and i:
        progress(f"start {i + 1} of at most {n}")
    if st.tracked:
        return _tracked_start(pb, st, deadline, progress, f"start {i + 1}", z)
    return _plain_start(residual, pb.lo, pb.hi, st.max_nfev, z)


def _candidates(pb: Problem, st: Strategy, deadline, progress) -> list[np.ndarray]:
    """Start points: the problem's start, the model's own guess (with ``rescue``, more than one start and a start
    elsewhere), a differential-evolution point (``global_search``), ``starts - 1`` Latin-hypercube points."""
    from scipy.stats import qmc

    free, tr, lo, hi, z0 = pb.free, pb.transform, pb.lo, pb.hi, pb.z0
    out = [z0]
    if st.rescue and st.starts > 1:
        guess = {k: v for k, v in pb.model.initial_guess(pb.records[0]).items() if k in pb.model.parameter_names}
        try:
            ref = pb.model.check_values({**pb.base, **guess, **pb.fixed})
        except ErdesignError:
            ref = None
        if ref is not None:
            zr = np.clip(tr.to_search([ref[n] for n in free]), lo, hi)
            if not np.array_equal(zr, z0):
                out.append(zr)
    if st.global_search:
        from scipy.optimize import differential_evolution

        box_lo, box_hi = start_box(lo, hi, z0, None)
        if st.tracked:
            probe = _Tracker(pb.model, *_stages(pb, st)[0][-1][:3], pb.values, deadline, progress, "global search")
        else:
            probe = Residual(pb.model, pb.records, pb.values, pb.masks, pb.weights, deadline, progress)
        try:
            de = differential_evolution(
                SumOfSquares(probe),
                list(zip(box_lo, box_hi)),
                seed=st.seed,
                tol=1e-8,
                polish=False,
                maxiter=200,
                popsize=15,
                init="sobol",
            )
            out.append(de.x)
        except (_OutOfTime, _Stalled):
            # out of time, or the tracker's stall rule (meant for a local optimiser polishing digits) fired inside
            # the evolution: the best point it met is the start
            if probe.best_z is not None:
                out.append(probe.best_z)
    if st.starts > 1:
        box_lo, box_hi = start_box(lo, hi, z0, tr.log)
        out.extend(qmc.scale(qmc.LatinHypercube(d=len(free), seed=st.seed).random(st.starts - 1), box_lo, box_hi))
    return out


def _failed(pb: Problem, out: Outcome, baseline: float) -> bool:
    """A start that did not converge, stopped on time, is no better than the reference fit or sits mostly at
    bounds (:data:`FAIL_RATIO`)."""
    return (
        out.out_of_time
        or out.status <= 0
        or worse_than_reference(out.cost / out.spread, baseline)
        or mostly_at_bounds(pb.model, pb.free, pb.values(out.x))
    )


def solve(pb: Problem, st: Strategy, progress=None):
    """Fit the problem ``pb`` with the strategy ``st`` (:func:`_solve` does the work) with one BLAS thread
    (:mod:`threadpoolctl`): the matrices of a fit are small and tall (an SVD of 60,000 x 13 per step of a projected
    fit), where a second thread only contends - 10 x slower on a loaded two-core machine.  Worker processes of an
    executor run one thread anyway; this keeps a library call from the caller's own process equally lean."""
    with _blas_controller().limit(limits=1, user_api="blas"):
        return _solve(pb, st, progress)


_BLAS_CONTROLLER = None


def _blas_controller():
    """The process's :class:`threadpoolctl.ThreadpoolController`, made once: making one scans every loaded library
    (2-5 ms, about 4 % of a small diagnosis when paid per fit).  numpy's and scipy's BLAS are loaded first (each
    wheel brings its own OpenBLAS), because a controller sees only the libraries already loaded."""
    global _BLAS_CONTROLLER
    if _BLAS_CONTROLLER is None:
        import scipy.linalg  # noqa: F401  (loads scipy's BLAS)
        from threadpoolctl import ThreadpoolController

        _BLAS_CONTROLLER = ThreadpoolController()
    return _BLAS_CONTROLLER


def _solve(pb: Problem, st: Strategy, progress=None):
    """Fit a :class:`Problem` by the :class:`Strategy`: the starts (:func:`_candidates`) on the strategy's executor,
    the best (the first of equal costs, whatever the executor), its uncertainty (:func:`uncertainty`, from the
    optimiser's Jacobian when it has one on the problem's samples, else forward differences) and statistics, as a
    :class:`~erdesign.identification.result.FitResult` on the problem's records: ``force`` and ``residual`` at every
    sample (records concatenated), ESR on the compared samples (the mean of the records' ESRs, listed in
    ``records``, when there are several), ``search`` and ``jacobian`` at the optimum.  ``progress`` (a callable
    taking a string) receives lines from the starts run in this process.  ``baseline_esr`` of the result is the
    reference Bingham fit's on the first record (with ``rescue``)."""
    from functools import partial

    from ..data.metrics import esr
    from ..executor import SerialExecutor, executor_for
    from .result import FitResult

    t_start = _time.monotonic()
    deadline = None if st.max_time is None else t_start + float(st.max_time)
    if st.tracked and len(pb.records) > 1:
        raise FitError("a tracked fit is of one record")
    model, free, tr, lo, hi = pb.model, pb.free, pb.transform, pb.lo, pb.hi
    record, mask = pb.records[0], pb.masks[0]
    baseline = baseline_esr(record, record.require_force(), mask) if st.rescue else None
    runner = executor_for(st.executor)
    try:
        here = isinstance(runner, SerialExecutor)
        residual = (
            None
            if st.tracked
            else Residual(model, pb.records, pb.values, pb.masks, pb.weights, deadline, progress if here else None)
        )
        candidates = _candidates(pb, st, deadline, progress)
        items = [(i, len(candidates), z) for i, z in enumerate(candidates)]
        # the tasks carry the strategy without its executor (a pool or a client is not sent to its own workers)
        task = partial(_start_task, pb, replace(st, executor=None), deadline, progress if here else None, residual)
        if st.rescue:
            outcomes = [_start_task(pb, st, deadline, progress, residual, items[0])]
            first = outcomes[0]
            if len(items) > 1 and not first.out_of_time and _failed(pb, first, baseline):
                if progress is not None:
                    progress(
                        f"start 1 failed (ESR {first.cost / first.spread:.4g}; reference Bingham fit "
                        f"{baseline:.4g}): trying {len(items) - 1} more starts"
                    )
                outcomes += runner.map(task, items[1:])
        else:
            outcomes = runner.map(task, items)
    finally:
        if runner is not st.executor:
            runner.close()
    best = None
    for out in outcomes:  # the first of equal costs, whatever the executor
        if best is None or out.cost < best.cost:
            best = out
    z = best.x
    values = pb.values(z)
    final = Residual(model, pb.records, pb.values, pb.masks, pb.weights)
    if best.jac is not None:
        r_obj, J = final(z), best.jac
    else:
        r_obj, J = fd_jacobian(final, z, fd_steps(tr, free, model, z, lo, hi))
    rss_obj = float(np.dot(r_obj, r_obj))
    forces = [model.force(r, values) for r in pb.records]
    scores, parts = [], []
    for r, Fm, m in zip(pb.records, forces, pb.masks):
        F = r.require_force()
        scores.append(esr(F if m is None else F[m], Fm if m is None else Fm[m]))
        parts.append(finite_residual(Fm - F if m is None else (Fm - F)[m]))
    rss = rss_obj if pb.weights is None else float(sum(np.dot(p, p) for p in parts))
    n, k = sum(p.size for p in parts), len(free)
    stderr, corr = uncertainty(J, z, tr, rss_obj, n, k)
    rss_n = max(rss / n, np.finfo(float).tiny)
    force = np.concatenate(forces) if len(forces) > 1 else forces[0]
    measured = np.concatenate([r.require_force() for r in pb.records]) if len(forces) > 1 else record.force
    return FitResult(
        model=model,
        values=values,
        free=free,
        stderr=dict(zip(free, stderr)),
        correlation=corr,
        force=force,
        residual=measured - force,
        esr=scores[0] if len(scores) == 1 else float(np.mean(scores)),
        rss=rss,
        n=n,
        aic=n * math.log(rss_n) + 2 * k,
        bic=n * math.log(rss_n) + k * math.log(n),
        success=bool(best.success and not best.out_of_time),
        message=best.message,
        record_name=record.name,
        initial=dict(pb.base),
        starts_tried=sum(o.calls > 0 for o in outcomes),
        simulations=best.calls,
        nfev=best.nfev,
        seconds=_time.monotonic() - t_start,
        projected=list(_linear_free(pb, st)) if st.tracked else [],
        baseline_esr=baseline,
        records=[]
        if len(scores) == 1
        else [{"name": r.name, "samples": int(p.size), "esr": e} for r, p, e in zip(pb.records, parts, scores)],
        search=np.array(z, dtype=float),
        jacobian=J,
        out_of_time=best.out_of_time,
    )
