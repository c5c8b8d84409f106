r"""The pieces every fit of erdesign shares, written once: which parameters are free, the search space (log space
for log-scale parameters), the penalty for non-finite residuals, the stopping tolerance, the start box of
multi-starts, the uncertainty of the free parameters and the threshold of a "strong" correlation.

:func:`erdesign.identification.fit.fit`, :func:`erdesign.identification.identify.identify`,
:func:`~erdesign.identification.identify.identify_joint` and the diagnosis's calibration
(:mod:`erdesign.diagnosis.calibration`) build their fits from these, so that a model fitted by any of them to the
same samples is set up the same way.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from collections.abc import Mapping, Sequence

import numpy as np

from ..data.measurement import Measurement
from ..errors import ErdesignError
from ..models.base import Model

__all__ = [
    "CORRELATION_THRESHOLD",
    "FTOL",
    "PENALTY",
    "FitError",
    "Residual",
    "SumOfSquares",
    "Transform",
    "ValueMap",
    "control_reference_for",
    "finite_residual",
    "local_fit",
    "resolve_free",
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
    """Model minus measured force [N] on the fitted samples (all, or those of ``mask``) as a function of the search
    vector, non-finite entries replaced by :data:`PENALTY`.  Picklable (multi-starts on an executor)."""

    def __init__(self, model: Model, record: Measurement, values: ValueMap, mask: np.ndarray | None = None):
        self.model, self.record, self.values, self.mask = model, record, values, mask
        self.F = record.require_force()

    def __call__(self, z: np.ndarray) -> np.ndarray:
        r = self.model.force(self.record, self.values(z)) - self.F
        return finite_residual(r if self.mask is None else r[self.mask])


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
    return least_squares(residual, np.clip(z, lo, hi), bounds=(lo, hi), method="trf", x_scale="jac",
                         max_nfev=max_nfev, ftol=FTOL)


def resolve_free(model: Model, records: Sequence[Measurement], free: Sequence[str] | None = None,
                 fixed: Mapping[str, float] | None = None) -> tuple[tuple[str, ...], dict[str, float]]:
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

    @property
    def values(self) -> ValueMap:
        """Search vector -> all parameter values."""
        return ValueMap(self.base, self.free, self.transform)


def problem(model: Model, records: Sequence[Measurement], *, free: Sequence[str] | None = None,
            fixed: Mapping[str, float] | None = None, start: Mapping[str, float] | None = None,
            masks: Sequence[np.ndarray | None] | None = None, control_reference: bool = True,
            samples: int | None = None, label: str = "record") -> Problem:
    """Set up a fit of ``model`` to ``records``: the free parameters (:func:`resolve_free`), the start values (the
    model's guess from the first record, then ``start``, then ``fixed``; checked within bounds), the search space.
    With ``control_reference`` the fit works on a copy of the model with the records' reference
    (:func:`with_control_reference`); otherwise on the model as given (it is not changed).  Unknown names in
    ``start`` are errors; so are ``samples`` (the number compared) too few for the free parameters (the error
    names ``label``)."""
    records = tuple(records)
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
    return Problem(model, records, tuple(masks) if masks is not None else (None,) * len(records), free, fixed,
                   base, tr, lo, hi, z0)


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


def strong_correlations(free: Sequence[str], correlation: np.ndarray,
                        threshold: float = CORRELATION_THRESHOLD) -> list[tuple[str, str, float]]:
    """Pairs of free parameters whose correlation exceeds ``threshold`` in magnitude, strongest first."""
    pairs = []
    for i in range(len(free)):
        for j in range(i + 1, len(free)):
            c = correlation[i, j]
            if np.isfinite(c) and abs(c) > threshold:
                pairs.append((free[i], free[j], float(c)))
    return sorted(pairs, key=lambda p: -abs(p[2]))
