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
from ..models._kernels import coarse_steps, frozen_substeps
from ..models.base import Model
from . import engine
from .engine import (
    FTOL,
    FitError,
    SumOfSquares,
    Transform,
    ValueMap,
    control_reference_for,
    finite_residual,
    problem,
    start_box,
    uncertainty,
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


class _OutOfTime(Exception):
    """Raised inside the residual when the time budget is spent (the best point so far is kept)."""


class _Stalled(Exception):
    """Raised inside the residual when the best sum of squares has improved by less than STALL_RTOL over the last
    STALL_JACOBIANS Jacobians' worth of simulations: the optimiser is polishing digits the data do not hold (its
    finite-difference steps also see the sub-step count of the kernels switch)."""


STALL_RTOL = 1e-4
STALL_JACOBIANS = 3


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
        self.spread = float(np.sum((F[mask] - F[mask].mean()) ** 2)) if mask is not None else \
            float(np.sum((F - F.mean()) ** 2))
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
        if len(self.history) > window + 2 * (len(z) + 1) and \
                self.history[-window - 1] <= self.best_cost * (1.0 + self.stall_rtol):
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
        parameters) and steps of 1e-6 of each parameter's scale (:func:`_fd_steps`), inside the bounds."""
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

    def __init__(self, model, record, F, mask, full_values, deadline, progress, label, stall_rtol, steps,
                 projection):
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
            sol = (theta, np.full(n, engine.PENALTY), None, None)
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
            U, sv, _ = np.linalg.svd(Bf / np.where(np.linalg.norm(Bf, axis=0) > 0, np.linalg.norm(Bf, axis=0), 1.0),
                                     full_matrices=False)
            U = U[:, sv > 1e-10 * sv.max()] if sv.size and sv.max() > 0 else U[:, :0]
            J -= U @ (U.T @ J)
        return J


class _LinearResult:
    """Stands in for scipy's OptimizeResult when every free parameter enters linearly: one linear solve."""

    def __init__(self, tracker):
        self.x = np.empty(0)
        self.cost = 0.5 * tracker.best_cost
        self.status, self.success, self.nfev, self.jac = 1, True, tracker.calls, None
        self.message = "linear least squares: every free parameter enters the force linearly"


def _fd_steps(tr, names, model, z, lo, hi, rel=1e-6):
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
        pick = next((i for i in order if names[i] in prefer and share[live.index(i)] > 0.3 * top
                     and names[i] not in held), None)
        if pick is None:
            pick = next((i for i in order if names[i] not in held), None)
        if pick is not None:
            held.append(names[pick])
    return held


class _StalledResult:
    """Stands in for scipy's OptimizeResult when the optimiser was stopped for lack of progress."""

    def __init__(self, z, tracker):
        self.x = z
        self.cost = 0.5 * tracker.best_cost
        self.status = 2
        self.success = True
        self.nfev = tracker.calls
        self.jac = None
        self.message = (f"converged: the sum of squares improved by less than {100 * STALL_RTOL:g} % over the last "
                        f"{STALL_JACOBIANS} Jacobians")


def _fd_jacobian(fun, z, steps):
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


#: Records longer than this get a warm start on a decimated copy (at least 1 kHz kept) before all samples.
WARM_START_SAMPLES = 20_000

#: A start "fails" when the optimiser stops without converging or leaves more than this fraction of the variance
#: that the reference Bingham fit leaves (F ~ c v + f sgn v + f0, :func:`_baseline_esr`): extra starts are then
#: tried, and a best fit above it is a poor fit (``success`` False).
FAIL_RATIO = 1.0
#: Relative rise of the sum of squares allowed when the parameters found not identifiable are held at their start
#: values; above it the free fit is kept.
HELD_RTOL = 1e-3


def _mostly_at_bounds(z, lo, hi) -> bool:
    """More than half of the free parameters on a bound of the search space (a fit the bounds, not the data, set)."""
    on = np.isclose(z, lo, rtol=1e-9, atol=1e-12) | np.isclose(z, hi, rtol=1e-9, atol=1e-12)
    return bool(z.size and on.sum() > z.size / 2)


def _baseline_esr(record, F, mask):
    """ESR of the reference fit: the Bingham model (``bingham``: c0 v + f_c sgn v + f0, its control terms being
    collinear with these on a record of one control) by linear least squares on the fitted samples."""
    v = record.velocity
    A = np.column_stack([v, np.sign(v), np.ones_like(v)])
    if mask is not None:
        A, F = A[mask], F[mask]
    coef, *_ = np.linalg.lstsq(A, F, rcond=None)
    return esr(F, A @ coef)


def identify(model: Model, record: Measurement, *, starts: int = 4, global_search: bool = False,
             max_time: float | None = None, decimate: int = 1, exclude_clipped: bool = False, progress=None,
             free: Sequence[str] | None = None, fixed: Mapping[str, float] | None = None,
             start: Mapping[str, float] | None = None, seed: int = 0, max_nfev: int | None = None,
             fix_unidentifiable: bool = True, warm_start: bool = False, projection: bool | None = None) -> FitResult:
    """Identify ``model`` on ``record`` by bounded least squares, at the scale of real records.

    * The fit works on a copy of the model with the control reference chosen from the record
      (:func:`~erdesign.identification.engine.control_reference_for`; ``result.model``): ``model`` is not changed.
      A control column of zeros holds the control slopes, as no control column does.
    * One local start (trust-region reflective, :func:`scipy.optimize.least_squares`) from the model's guess;
      further starts (Latin hypercube around it, as :func:`erdesign.identification.fit.fit`) only when it fails: the
      optimiser did not converge, the fit is no better than the reference Bingham fit (c0 v + f_c sgn v + f0 by
      linear least squares on the same samples), or more than half the free parameters sit on a bound.  ``starts``
      bounds the number.  A best fit no better than the reference is not a success (``success`` False,
      ``extra["poor_fit"]``, a warning).
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
      the fit repeated (``fix_unidentifiable``); they are listed in ``result.extra["not_identifiable"]``.

    Returns a :class:`~erdesign.identification.fit.FitResult` whose ``extra`` carries the report's content (initial
    values, parameters at a bound, strong correlations, warnings, fit statistics; :func:`fit_report`).
    """
    from scipy.optimize import least_squares

    from ..data.measurement import clipped_samples
    t_start = _time.monotonic()
    deadline = None if max_time is None else t_start + float(max_time)
    say = progress or (lambda msg: None)
    F_all = record.require_force()
    check = getattr(model, "check_record", None)
    if check is not None:
        check(record)
    notes: list[str] = []
    if record.control_kind is not None and np.ptp(record.control) > 0 and not model.uses_control:
        notes.append(f"{model.name} has no control dependence, but the record's {record.control_kind} varies "
                     f"({np.min(record.control):.4g} to {np.max(record.control):.4g} SI): the fit averages over it")
    clipped = clipped_samples(F_all)
    mask = ~clipped if exclude_clipped and clipped.any() else None
    if clipped.any() and not exclude_clipped:
        notes.append(f"{int(clipped.sum())} force samples sit at a flat top or bottom ({F_all[clipped][0]:.6g} N): "
                     "a load cell at its limit? exclude_clipped=True leaves them out")
    n_scored = int(F_all.size if mask is None else mask.sum())
    pb = problem(model, [record], free=free, fixed=fixed, start=start, masks=[mask], samples=n_scored,
                 label=record.name or "record")
    model, free_names, fixed, base = pb.model, pb.free, pb.fixed, pb.base  # model: a copy, the caller's unchanged
    initial = dict(base)

    if projection is None:
        projection = getattr(model, "projection_default", True)
    linear = tuple(n for n in free_names if n in model.linear_parameters) if projection else ()

    def run(free_names, base, z_start, stage_records, label):
        """Least squares over ``free_names`` on each (record, force, mask) of ``stage_records`` in turn."""
        if linear:
            return run_projected(free_names, base, z_start, stage_records, label)
        tr = Transform(model, free_names)
        lo, hi = tr.bounds()
        z = np.clip(tr.to_search([base[n] for n in free_names]) if z_start is None else z_start, lo, hi)
        full_values = ValueMap(base, free_names, tr)
        res, out_of_time, tracker = None, False, None
        for k, (rec, F, m, stage) in enumerate(stage_records):
            tracker = _Tracker(model, rec, F, m, full_values, deadline, progress, f"{label}, {stage}",
                               stall.get(k, STALL_RTOL), _fd_steps(tr, free_names, model, z, lo, hi))
            try:
                with coarse_steps():
                    res = least_squares(tracker, z, jac=tracker.jacobian, bounds=(lo, hi), method="trf",
                                        x_scale="jac", max_nfev=max_nfev, ftol=FTOL, xtol=1e-8)
                z = res.x
            except _Stalled:
                z = tracker.best_z
                res = _StalledResult(z, tracker)
            except _OutOfTime:
                out_of_time = True
                if tracker.best_z is not None:
                    z = tracker.best_z
                res = None
                break
        return tr, z, res, out_of_time, full_values, tracker

    def run_projected(free_names, base, z_start, stage_records, label):
        """:func:`run` by variable projection: least squares over the nonlinear free parameters, the ``linear``
        ones solved inside each residual; returns the same as ``run``, in the space of all free parameters."""
        tr = Transform(model, free_names)
        lo, hi = tr.bounds()
        z = np.clip(tr.to_search([base[n] for n in free_names]) if z_start is None else z_start, lo, hi)
        nl = tuple(n for n in free_names if n not in linear)
        nl_index = [free_names.index(n) for n in nl]
        trn = Transform(model, nl)
        lon, hin = lo[nl_index], hi[nl_index]
        zn = z[nl_index]
        theta = np.array([base[n] for n in linear])
        nl_values = ValueMap(base, nl, trn)
        res, out_of_time, tracker = None, False, None
        for k, (rec, F, m, stage) in enumerate(stage_records):
            tracker = _ProjectedTracker(model, rec, F, m, nl_values, deadline, progress, f"{label}, {stage}",
                                        stall.get(k, STALL_RTOL), _fd_steps(trn, nl, model, zn, lon, hin),
                                        _Projection(model, rec, F, m, linear))
            try:
                if not nl:
                    tracker(zn)
                    res = _LinearResult(tracker)
                else:
                    with coarse_steps():
                        res = least_squares(tracker, zn, jac=tracker.jacobian, bounds=(lon, hin), method="trf",
                                            x_scale="jac", max_nfev=max_nfev, ftol=FTOL, xtol=1e-8)
                    zn = res.x
                    if not np.array_equal(tracker.last[0], zn):
                        tracker(zn)
                theta = tracker.last[3][0]
            except _Stalled:
                zn, theta = tracker.best_z, tracker.best_theta
                res = _StalledResult(zn, tracker)
            except _OutOfTime:
                out_of_time = True
                if tracker.best_z is not None:
                    zn, theta = tracker.best_z, tracker.best_theta
                res = None
                break
        vals = {**nl_values(zn), **dict(zip(linear, (float(t) for t in theta)))}
        z = np.clip(tr.to_search([vals[n] for n in free_names]), lo, hi)
        return tr, z, res, out_of_time, ValueMap(base, free_names, tr), tracker

    # stages: a decimated warm start on long records, then all samples (or only the decimated record)
    decimate = max(1, int(decimate))
    fit_rec = record if decimate == 1 else record.select(slice(None, None, decimate))
    fit_mask = mask if decimate == 1 or mask is None else mask[::decimate]
    stages = []
    stall: dict[int, float] = {}
    if warm_start and decimate == 1 and len(record) > WARM_START_SAMPLES:
        # at least 1 kHz kept: coarser, the motion read as linear between samples cuts reversals enough to move
        # the optimum of a hysteretic model (on Dyke's 3 kHz record every 5th sample gave ESR 0.121 on all samples
        # for an optimum of 0.101 on the decimated copy)
        k = int(max(2, min(math.ceil(len(record) / 15_000), math.floor(record.sample_rate / 1000.0))))
        coarse = record.select(slice(None, None, k))
        stages.append((coarse, coarse.force, None if mask is None else mask[::k], f"every {k}th sample"))
        stall = {0: 1e-3}  # the warm start needs no more than three digits
    stages.append((fit_rec, fit_rec.force, fit_mask, "all samples" if decimate == 1 else
                   f"every {decimate}th sample"))
    baseline = _baseline_esr(record, F_all, mask)

    tr0 = Transform(model, free_names)
    lo0, hi0 = tr0.bounds()
    z0 = np.clip(tr0.to_search([base[n] for n in free_names]), lo0, hi0)
    candidates = [z0]
    if starts > 1:
        from scipy.stats import qmc
        box_lo, box_hi = start_box(lo0, hi0, z0, tr0.log)
        candidates.extend(qmc.scale(qmc.LatinHypercube(d=len(free_names), seed=seed).random(starts - 1),
                                    box_lo, box_hi))
    if global_search:
        from scipy.optimize import differential_evolution
        box_lo, box_hi = start_box(lo0, hi0, z0, None)
        probe = _Tracker(model, fit_rec, fit_rec.force, fit_mask,
                         ValueMap(base, free_names, tr0), deadline,
                         progress, "global search")
        try:
            de = differential_evolution(SumOfSquares(probe), list(zip(box_lo, box_hi)),
                                        seed=seed, tol=1e-8, polish=False, maxiter=200, popsize=15, init="sobol")
            candidates.insert(1, de.x)
        except _OutOfTime:
            if probe.best_z is not None:
                candidates.insert(1, probe.best_z)
    best = None
    tried = 0
    for i, zc in enumerate(candidates):
        if deadline is not None and _time.monotonic() > deadline:
            break
        tried += 1
        if i:
            say(f"start {i + 1} of at most {len(candidates)}")
        out = run(free_names, base, zc, stages, f"start {i + 1}")
        tr, z, res, out_of_time, full_values, tracker = out
        cost = tracker.best_cost if res is None else 2.0 * res.cost
        if best is None or cost < best[0]:
            best = (cost, out)
        spread = tracker.spread
        failed = out_of_time or res is None or res.status <= 0 or cost / spread > FAIL_RATIO * baseline or \
            _mostly_at_bounds(z, *tr.bounds())
        if not failed or out_of_time:
            break
        if i + 1 < len(candidates):
            say(f"start {i + 1} failed (ESR {cost / spread:.4g}; reference Bingham fit "
                f"{baseline:.4g}): trying another start")
    _, (tr, z, res, out_of_time, full_values, tracker) = best
    values = full_values(z)

    def full_residual(zz, names=free_names, trn=tr, base=base):
        vals = dict(base)
        vals.update(zip(names, (float(v) for v in trn.to_values(zz))))
        r = model.force(record, vals) - F_all
        r = r if mask is None else r[mask]
        return finite_residual(r)

    r_full = full_residual(z)
    if res is not None and res.jac is not None and stages[-1][0] is record and np.array_equal(res.x, z):
        J = res.jac
    else:
        J = _fd_jacobian(full_residual, z, _fd_steps(tr, free_names, model, z, *tr.bounds()))[1]
    rss = float(np.dot(r_full, r_full))
    k = len(free_names)
    stderr, corr = uncertainty(J, z, tr, rss, n_scored, k)
    not_identifiable = _null_parameters(J, z, tr, free_names, model.control_parameters)
    if not_identifiable and fix_unidentifiable and len(not_identifiable) < k and not out_of_time:
        say(f"not identifiable from this record: {', '.join(not_identifiable)}; held at their start values")
        held = {n: initial[n] for n in not_identifiable}
        result = identify(model, record, starts=1, max_time=None if deadline is None else
                          max(1.0, deadline - _time.monotonic()), decimate=decimate, exclude_clipped=exclude_clipped,
                          progress=progress, free=[n for n in free_names if n not in held],
                          fixed={**fixed, **held}, start={**values, **held}, seed=seed, max_nfev=max_nfev,
                          fix_unidentifiable=False, warm_start=warm_start, projection=projection)
        # Held at their start values, directions the data do not see should leave the fit as good; when the fit
        # gets worse (on a Quiroz record ESR 0.019 -> 7.0: the start values were zeros the found optimum needs),
        # the free fit is kept and the parameters are only reported.
        if result.rss <= rss * (1.0 + HELD_RTOL):
            result.extra["not_identifiable"] = sorted(set(not_identifiable) | set(result.extra["not_identifiable"]))
            result.extra["initial"] = initial
            result.extra["warnings"] = [*notes, *[w for w in result.extra["warnings"] if w not in notes]]
            result.extra["seconds"] = _time.monotonic() - t_start
            return result
        notes.append(f"not identifiable from this record: {', '.join(not_identifiable)}; held at their start "
                     f"values the fit got worse (ESR {result.rss / tracker.spread:.4g} against "
                     f"{rss / tracker.spread:.4g}), so they are left at the fitted values")
    force = model.force(record, values)
    resid = F_all - force
    scored = resid if mask is None else resid[mask]
    rss_n = max(rss / n_scored, np.finfo(float).tiny)
    message = str(res.message) if res is not None else "stopped by max_time: the best point found so far"
    if out_of_time:
        notes.append(f"stopped at max_time {max_time:g} s before the optimiser converged: the values are the best "
                     "found so far")
    result = FitResult(
        model=model, values=values, free=free_names, stderr=dict(zip(free_names, stderr)), correlation=corr,
        force=force, residual=resid, esr=esr(F_all if mask is None else F_all[mask], force if mask is None else
                                            force[mask]),
        rss=rss, n=n_scored, aic=n_scored * math.log(rss_n) + 2 * k, bic=n_scored * math.log(rss_n) + k *
        math.log(n_scored), success=bool(res is not None and res.success and not out_of_time), message=message,
        record_name=record.name,
        extra={"initial": initial, "not_identifiable": not_identifiable, "warnings": notes, "starts_tried": tried,
               "simulations": tracker.calls if tracker else 0, "seconds": _time.monotonic() - t_start,
               "baseline_esr": baseline, "clipped_samples": int(clipped.sum()),
               "excluded_samples": 0 if mask is None else int(clipped.sum()), "decimate": decimate,
               "nfev": int(res.nfev) if res is not None else 0, "mask": mask, "projected": list(linear)})
    _ = scored
    if hasattr(model, "train"):
        model.train(record, result.values)
        result.force = model.simulate(record, result.values)
        result.residual = F_all - result.force
        result.esr = esr(F_all, result.force)
    # A fit no better than the reference (a Bingham model: viscous plus friction plus offset, by linear least
    # squares on the same samples) or set by the bounds is not a success, whatever the optimiser's message says.
    poor = bool(result.esr > FAIL_RATIO * baseline or _mostly_at_bounds(z, *tr.bounds()))
    result.extra["poor_fit"] = poor
    if poor:
        result.success = False
        notes.append(f"poor fit: ESR {result.esr:.4g} after {tried} start(s), against {baseline:.4g} for the reference "
                     "Bingham fit (c0 v + f_c sgn v + f0)" + (" with most parameters at a bound"
                                                             if _mostly_at_bounds(z, *tr.bounds()) else "")
                     + ": try more starts, other fixed parameters or another model")
    return result


@dataclass
class JointResult:
    """Parameters shared by several records and the ESR on each."""

    model: Model
    values: dict[str, float]
    esr: list[float]
    names: list[str]
    success: bool
    free: tuple[str, ...] = ()
    message: str = ""
    extra: dict | None = None
    """``seconds``, ``simulations`` (of all records), ``excluded_samples`` per record, ``warnings``, ``initial``."""

    @property
    def mean_esr(self) -> float:
        """Mean of the per-record ESRs (each record weighs alike, as in the fit)."""
        return float(np.mean(self.esr))


class _JointResidual:
    """The residuals of several records, each weighted by 1 / its force standard deviation and on its mask,
    concatenated; counts simulations, keeps the best point, reports progress and enforces the time budget."""

    def __init__(self, model, records, forces, weights, masks, values, deadline, progress, total):
        self.model, self.records, self.forces, self.weights, self.masks = model, records, forces, weights, masks
        self.values, self.deadline, self.progress, self.total = values, deadline, progress, total
        self.calls, self.best, self.best_z, self.last_report = 0, math.inf, None, _time.monotonic()

    def __call__(self, z):
        if self.deadline is not None and _time.monotonic() > self.deadline:
            raise _OutOfTime
        v = self.values(z)
        parts = [w * (self.model.force(r, v) - F) for r, F, w in zip(self.records, self.forces, self.weights)]
        out = finite_residual(np.concatenate([p if m is None else p[m] for p, m in zip(parts, self.masks)]))
        cost = float(np.dot(out, out))
        self.calls += 1
        if cost < self.best:
            self.best, self.best_z = cost, np.array(z, dtype=float)
        now = _time.monotonic()
        if self.progress is not None and now - self.last_report > 2.0:
            self.last_report = now
            self.progress(f"joint fit of {len(self.records)} records: {self.calls} simulations of all, "
                          f"mean weighted sum of squares {self.best / self.total:.4g}")
        return out


def identify_joint(model: Model, records: Sequence[Measurement], *, free: Sequence[str] | None = None,
                   fixed: Mapping[str, float] | None = None, start: Mapping[str, float] | None = None,
                   max_nfev: int | None = None, max_time: float | None = None, exclude_clipped: bool = False,
                   progress=None) -> JointResult:
    """One parameter set for several records (each simulated from rest), by least squares on all residuals.

    Each record's residual is weighted by 1 / its force standard deviation, so that a record with small forces
    (zero current) counts as much as one with large forces.  ``max_time`` [s] stops with the best point found so
    far (``success`` False); ``exclude_clipped`` leaves each record's flat-top force samples out of the residual
    and the scores; ``progress`` (a callable taking a string) receives a line every few seconds.
    """
    from ..data.measurement import clipped_samples

    t_start = _time.monotonic()
    deadline = None if max_time is None else t_start + float(max_time)
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
            notes.append(f"{r.name or 'a record'}: {int(clipped.sum())} force samples sit at a flat top or bottom; "
                         "exclude_clipped=True leaves them out")
    total = sum(len(r) if m is None else int(m.sum()) for r, m in zip(records, masks))
    pb = problem(model, records, free=free, fixed=fixed, start=start, masks=masks, samples=total,
                 label="identify_joint")
    model, names, base, lo, hi, z0 = pb.model, pb.free, pb.base, pb.lo, pb.hi, pb.z0  # model: a copy
    values = pb.values
    forces = [r.require_force() for r in records]
    weights = [1.0 / max(float(np.std(F if m is None else F[m])), 1e-12) for F, m in zip(forces, masks)]

    residual = _JointResidual(model, records, forces, weights, masks, values, deadline, progress, total)

    from scipy.optimize import least_squares  # imported on use: not at start-up

    try:
        res = least_squares(residual, z0, bounds=(lo, hi), x_scale="jac", max_nfev=max_nfev, ftol=FTOL)
        z, success, message = res.x, bool(res.success), str(res.message)
    except _OutOfTime:
        z = z0 if residual.best_z is None else residual.best_z
        success, message = False, "stopped by max_time: the best point found so far"
        notes.append(f"stopped at max_time {max_time:g} s before the optimiser converged: the values are the best "
                     "found so far")
    v = values(z)
    scores = []
    for r, F, m in zip(records, forces, masks):
        M = model.force(r, v)
        scores.append(esr(F if m is None else F[m], M if m is None else M[m]))
    return JointResult(model, v, scores, [r.name for r in records], success, tuple(names), message,
                       {"seconds": _time.monotonic() - t_start, "simulations": residual.calls,
                        "excluded_samples": [0 if m is None else int((~m).sum()) for m in masks],
                        "warnings": notes, "initial": {n: base[n] for n in names}})


def joint_report(result: JointResult, validation: Sequence[tuple[str, dict]] = ()) -> str:
    """The report of a joint identification: per-record ESR, the shared parameters, validation, warnings."""
    model = result.model
    ex = result.extra or {}
    width = max(len(n or "") for n in result.names)
    lines = [f"[[Joint fit]] {model.title or model.name} on {len(result.names)} records, one parameter set",
             f"  free parameters {len(result.free)}, simulations of all records {ex.get('simulations', '?')}, "
             f"{ex.get('seconds', 0.0):.1f} s" + ("" if result.success else f"  - {result.message}"),
             f"[[ESR per record]] (mean {result.mean_esr:.4g})"]
    excluded = ex.get("excluded_samples") or [0] * len(result.names)
    lines += [f"  {name or 'record':<{width}}  {e:.4g}" + (f"  ({k} clipped left out)" if k else "")
              for name, e, k in zip(result.names, result.esr, excluded)]
    lines.append("[[Parameters]]")
    pw = max(len(n) for n in model.parameter_names)
    for name in model.parameter_names:
        text = model.parameter(name).format(result.values[name])
        lines.append(f"  {name:<{pw}}  {text}" + ("" if name in result.free else " (fixed)"))
    if validation:
        lines.append("[[Validation]] (the identified set on other records)")
        lines += [f"  {name}: ESR {m['esr']:.4g}, RMS residual {m['rms_residual_N']:.4g} N" for name, m in validation]
    if ex.get("warnings"):
        lines.append("[[Warnings]]")
        lines += [f"  {w}" for w in ex["warnings"]]
    return "\n".join(lines)


def joint_json(result: JointResult, model_name: str, control_reference: str | None,
               validation: Sequence[tuple[str, dict]] = ()) -> dict:
    """The ``identify --joint --json`` object: ``model``, ``esr`` (the mean of the per-record ESRs), ``records``
    (name, esr, excluded_samples), ``parameters`` (strings with units), ``parameters_si`` (value, unit, status
    "free" or "fixed", initial), ``control_reference``, ``success``, ``message``, ``warnings``, ``validation``."""
    def num(x):
        return None if x is None or not math.isfinite(x) else float(x)

    model = result.model
    ex = result.extra or {}
    excluded = ex.get("excluded_samples") or [0] * len(result.names)
    initial = ex.get("initial", {})
    return {"model": model_name, "joint": True, "esr": num(result.mean_esr),
            "records": [{"record": n, "esr": num(e), "excluded_samples": k}
                        for n, e, k in zip(result.names, result.esr, excluded)],
            "parameters": {n: model.parameter(n).format(v) for n, v in result.values.items()},
            "parameters_si": {n: {"value": float(v), "unit": model.parameter(n).unit,
                                  "status": "free" if n in result.free else "fixed",
                                  "initial": None if n not in initial else float(initial[n])}
                              for n, v in result.values.items()},
            "control_reference": control_reference, "success": bool(result.success), "message": result.message,
            "simulations": ex.get("simulations"), "seconds": num(ex.get("seconds")),
            "warnings": list(ex.get("warnings", ())),
            "validation": [{"record": name, **{k: num(v) if isinstance(v, float) else v for k, v in m.items()}}
                           for name, m in validation]}


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
    return [r.esr if i == j else esr(other.require_force(), r.model.simulate(other, r.values))
            for i, other in enumerate(records)]


def cross_validation(model_factory, records: Sequence[Measurement], *, executor=None,
                     **fit_options) -> CrossValidation:
    """Identify a fresh model (``model_factory()``) on each record and score it on every record.

    The identifications run on ``executor`` (:func:`erdesign.executor.executor_for`; default one after the other in
    this process); on worker processes ``model_factory`` must be picklable (``functools.partial(get_model,
    "bingham")``, not a lambda).  The table does not depend on the executor."""
    from functools import partial

    from ..executor import executor_for
    records = list(records)
    runner = executor_for(executor)
    try:
        columns = runner.map(partial(_cross_validation_column, model_factory, records, fit_options),
                             range(len(records)))
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
    return {"esr": e, "r_squared": 1.0 - e, "rms_residual_N": float(np.sqrt(np.mean(d**2))),
            "peak_residual_N": float(np.max(np.abs(d))), "samples_scored": int(F.size)}


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
    from ..units import Q_
    try:
        q = Q_(text)
        return float(q.to(CONTROL_UNITS[record.control_kind]).magnitude)
    except Exception:
        raise ErdesignError(f"{where}: control_reference {text!r} is not a {record.control_kind} "
                            f"(the record's control)") from None


def resolve_parameters(model: Model, spec: str, record: Measurement, *,
                       control_reference: str | None = None,
                       where: str = "params") -> tuple[dict[str, float], ParameterSource, list[str]]:
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
        try:
            data = json.loads(path.read_text())
        except FileNotFoundError:
            raise ErdesignError(f"{where}: no such file {spec}") from None
        except (json.JSONDecodeError, UnicodeDecodeError) as exc:
            raise ErdesignError(f"{where}: {spec} is not a JSON file ({exc})") from None
        if not isinstance(data, dict) or not isinstance(data.get("parameters"), dict):
            raise ErdesignError(f"{where}: {spec} has no 'parameters' object (expected the output of "
                                "'erdesign identify --json')")
        if data.get("model") not in (None, model.name):
            raise ErdesignError(f"{where}: {spec} holds parameters of model {data['model']}, not {model.name}")
        ref_text = control_reference or data.get("control_reference")
        if model.uses_control and kind is not None:
            if ref_text:
                model.control_reference = _control_reference_from_text(ref_text, record, where)
            else:
                ref = choose_control_reference(model, [record])
                notes.append(f"{spec} gives no control_reference: u = {kind} / {ref:g} (SI), the rule identify "
                             "uses on this record")
        si = data.get("parameters_si")
        if isinstance(si, dict) and si:
            values = {k: float(v["value"] if isinstance(v, dict) else v) for k, v in si.items()}
            for k in values:
                model.parameter(k)
        else:
            values = parse_parameter_values(model, data["parameters"], control_kind=kind,
                                            control_reference=model.control_reference, where=spec)
        return values, ParameterSource("json", spec), notes
    if "=" in spec:
        texts = parse_parameter_list(spec)
        if model.uses_control and kind is not None:
            if control_reference:
                model.control_reference = _control_reference_from_text(control_reference, record,
                                                                       "control_reference")
            else:
                choose_control_reference(model, [record])
        values = parse_parameter_values(model, texts, control_kind=kind, control_reference=model.control_reference)
        return values, ParameterSource("list", f"{where} list"), notes
    pub = published_set(model.name, spec)
    if pub.control_kind is not None:
        if kind is None:
            notes.append(f"{spec} is for a record with a {pub.control_kind} column; {record.name or 'the record'} "
                         "has none: the control is taken as zero")
        elif kind != pub.control_kind:
            raise ErdesignError(f"{where}: {spec} is for a {pub.control_kind} control (its coefficients are per "
                                f"unit {pub.control_kind}); the record's control is a {kind}")
        model.control_reference = pub.control_reference
    elif model.uses_control and kind is not None and np.ptp(record.control) > 0:
        notes.append(f"{spec} describes one fixed field; the record's {kind} varies and is ignored by its "
                     "coefficients")
    return dict(pub.values), ParameterSource("published", spec, pub.source, pub.note), notes


def simulate(model: Model, record: Measurement, values: Mapping[str, float], *, exclude_clipped: bool = False,
             source: ParameterSource | None = None) -> Simulation:
    """Run ``model`` with ``values`` on the record's motion and control (from rest at the first sample) and score
    it against the record's force (all samples, or without the clipped ones when ``exclude_clipped``)."""
    from ..data.measurement import clipped_samples
    F = record.require_force()
    force = model.simulate(record, values)
    clipped = clipped_samples(F)
    mask = ~clipped if exclude_clipped and clipped.any() else None
    metrics = score(F, force, mask)
    notes = []
    if not np.all(np.isfinite(force)):
        raise ErdesignError(f"{model.name}: the parameters give non-finite forces on {record.name or 'the record'}")
    if clipped.any() and not exclude_clipped:
        level = F[clipped]
        notes.append(f"{int(clipped.sum())} force samples sit at a flat {'top' if level[0] > 0 else 'bottom'} "
                     f"({level[0]:.6g} N): a load cell or amplifier at its limit; exclude_clipped=True scores without "
                     f"them")
    return Simulation(model, model.check_values(values), force, metrics, int(clipped.sum()),
                      int(clipped.sum()) if mask is not None else 0, source, notes)
