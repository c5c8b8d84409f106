r"""Identification workflows on top of :func:`erdesign.fit.fit`: one record, several records jointly (e.g. one
sinusoid per coil current with the current-dependent parameters shared), and cross-validation tables in the style
of seed 002 Table 4 (identify on one experiment, score the ESR on every other).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np
from scipy.optimize import least_squares

from .fit import FitError, FitResult, fit
from .measurement import Measurement
from .metrics import esr
from .models.base import Model

__all__ = ["identify", "identify_joint", "cross_validation", "CrossValidation", "JointResult",
           "choose_control_reference"]


def choose_control_reference(model: Model, records: Sequence[Measurement]) -> float:
    """Power of ten near the largest |control| of the records (1 when they have none), so that the model's
    dimensionless control u = control / reference is of order one and its per-unit parameters stay readable."""
    peak = max((float(np.max(np.abs(r.control))) for r in records if r.control_kind is not None), default=0.0)
    ref = 10.0 ** math.floor(math.log10(peak)) if peak > 0 else 1.0
    model.control_reference = ref
    return ref


def identify(model: Model, record: Measurement, *, starts: int = 4, global_search: bool = False,
             **options) -> FitResult:
    """Identify ``model`` on ``record``: choose the control reference, fit (multi-start), and train the network
    of a hybrid model (``maxwell_neural``) on the residual of its parametric part."""
    choose_control_reference(model, [record])
    result = fit(model, record, starts=starts, global_search=global_search, **options)
    if hasattr(model, "train"):
        model.train(record, result.values)
        result.force = model.simulate(record, result.values)
        result.residual = record.require_force() - result.force
        result.esr = esr(record.require_force(), result.force)
    return result


@dataclass
class JointResult:
    """Parameters shared by several records and the ESR on each."""

    model: Model
    values: dict[str, float]
    esr: list[float]
    names: list[str]
    success: bool


def identify_joint(model: Model, records: Sequence[Measurement], *, free: Sequence[str] | None = None,
                   fixed: Mapping[str, float] | None = None, start: Mapping[str, float] | None = None,
                   max_nfev: int | None = None) -> JointResult:
    """One parameter set for several records (each simulated from rest), by least squares on all residuals.

    Each record's residual is weighted by 1 / its force standard deviation, so that a record with small forces
    (zero current) counts as much as one with large forces.
    """
    if not records:
        raise FitError("identify_joint: no records")
    choose_control_reference(model, records)
    fixed = dict(fixed or {})
    if all(r.control_kind is None for r in records):
        fixed = {**model.fixed_for(records[0]), **fixed}
    else:
        fixed = {**{p.name: p.default for p in model.parameters if not p.fitted}, **fixed}
    names = [n for n in (free or model.parameter_names) if n not in fixed]
    base = model.check_values({**model.initial_guess(records[0]), **(start or {}), **fixed})
    params = [model.parameter(n) for n in names]
    log = np.array([p.log_scale for p in params])
    lo = np.array([math.log(p.lower) if p.log_scale else p.lower for p in params])
    hi = np.array([math.log(p.upper) if p.log_scale else p.upper for p in params])
    z0 = np.clip([math.log(base[n]) if p.log_scale else base[n] for n, p in zip(names, params)], lo, hi)
    forces = [r.require_force() for r in records]
    weights = [1.0 / max(float(np.std(F)), 1e-12) for F in forces]

    def values(z):
        v = dict(base)
        v.update({n: float(math.exp(q) if lg else q) for n, q, lg in zip(names, z, log)})
        return v

    def residual(z):
        v = values(z)
        parts = [w * (model.force(r, v) - F) for r, F, w in zip(records, forces, weights)]
        out = np.concatenate(parts)
        return np.where(np.isfinite(out), out, 1e6)

    res = least_squares(residual, z0, bounds=(lo, hi), x_scale="jac", max_nfev=max_nfev)
    v = values(res.x)
    return JointResult(model, v, [esr(F, model.force(r, v)) for r, F in zip(records, forces)],
                       [r.name for r in records], bool(res.success))


@dataclass
class CrossValidation:
    """ESR table: ``table[i][j]`` is the ESR on record i of the model identified on record j (seed 002 Table 4)."""

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


def cross_validation(model_factory, records: Sequence[Measurement], **fit_options) -> CrossValidation:
    """Identify a fresh model (``model_factory()``) on each record and score it on every record."""
    n = len(records)
    table = np.empty((n, n))
    for j, rec in enumerate(records):
        model = model_factory()
        r = identify(model, rec, **fit_options)
        for i, other in enumerate(records):
            table[i, j] = r.esr if i == j else esr(other.require_force(), model.simulate(other, r.values))
    return CrossValidation([r.name or f"record {k}" for k, r in enumerate(records)], table)
