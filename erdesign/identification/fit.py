r"""Calibrate a model to a record: bounded nonlinear least squares, uncertainties, information criteria.

:func:`fit` minimises :math:`J = \sum_i (F_i - F_\text{model}(t_i; p))^2` (Kamath and Wereley 1997, eq 13) over the free
parameters within their physical bounds (:func:`scipy.optimize.least_squares`, trust-region reflective), with
optional multi-start (Latin hypercube over the bounds) and an optional global stage
(:func:`scipy.optimize.differential_evolution`) for models with several minima.  Parameters marked ``log_scale`` are
searched in log space.

The result (:class:`FitResult`) carries values, standard errors and correlations from the Gauss-Newton covariance
:math:`s^2 (J^T J)^{-1}` with :math:`s^2 = \text{RSS}/(n - k)`, the ESR (Vivas-López et al., eq 7), and

.. math:: \text{AIC} = n \ln(\text{RSS}/n) + 2k, \qquad \text{BIC} = n \ln(\text{RSS}/n) + k \ln n .

Standard errors assume independent residuals; with correlated residuals (model error, filtered data) they are too
small, which the report says.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from functools import partial

import numpy as np

from ..data.measurement import Measurement
from ..data.metrics import esr
from ..models.base import Model, ParameterError
from .engine import FitError, Residual, SumOfSquares, local_fit, problem, start_box, uncertainty
from .result import FitResult

__all__ = ["FitError", "FitResult", "evaluate", "fit"]


def fit(model: Model, record: Measurement, *, free: Sequence[str] | None = None,
        fixed: Mapping[str, float] | None = None, start: Mapping[str, float] | None = None, starts: int = 1,
        global_search: bool = False, seed: int = 0, max_nfev: int | None = None, executor=None,
        mask: np.ndarray | None = None) -> FitResult:
    """Fit ``model`` to the force of ``record`` by bounded least squares.

    Parameters
    ----------
    model : Model
    record : Measurement
        Must have a force.
    free : sequence of str, optional
        Parameters to fit (default: all not in ``fixed``).
    fixed : mapping, optional
        Parameter values held fixed (SI).
    start : mapping, optional
        Starting values (SI); default :meth:`Model.initial_guess`.
    starts : int
        Number of local starts: the first from ``start``, the others from a Latin hypercube over the bounds.
    global_search : bool
        Run differential evolution on the RSS first and polish its best point with least squares.
    seed : int
        Random seed of the multi-start / global stage (results are reproducible).
    max_nfev : int, optional
        Limit on function evaluations per local start.
    executor : optional
        Where the local starts run (:func:`erdesign.executor.executor_for`: an executor, or a Dask client); default
        in this process, one after the other.  The result does not depend on it.
    mask : bool array, optional
        Samples the fit compares (all by default): the model is simulated on the whole record and scored on these
        (the diagnosis fits on the samples where the sign of the velocity is known).  The result's force, residual,
        ESR and sample count are those of the masked samples.

    Returns
    -------
    FitResult
    """
    F = record.require_force() if mask is None else record.require_force()[mask]
    check = getattr(model, "check_record", None)
    if check is not None:
        check(record)
    pb = problem(model, [record], free=free, fixed=fixed, start=start, masks=[mask], control_reference=False,
                 samples=len(F), label=record.name or "record")
    free, tr, lo, hi, z0 = pb.free, pb.transform, pb.lo, pb.hi, pb.z0
    full_values = pb.values
    residual = Residual(model, record, full_values, mask)

    from scipy.optimize import (
        differential_evolution,  # imported on use: not at start-up
    )
    from scipy.stats import qmc

    r0 = residual(z0)
    if not np.all(np.isfinite(model.force(record, full_values(z0)))):
        raise FitError(f"{model.name}: the model gives non-finite forces at the starting values")
    candidates = [z0]
    box_lo, box_hi = start_box(lo, hi, z0, None if global_search else tr.log)
    if global_search:
        de = differential_evolution(SumOfSquares(residual), list(zip(box_lo, box_hi)),
                                    seed=seed, tol=1e-8, polish=False, maxiter=200, popsize=15, init="sobol")
        candidates.append(de.x)
    if starts > 1:
        sampler = qmc.LatinHypercube(d=len(free), seed=seed)
        candidates.extend(qmc.scale(sampler.random(starts - 1), box_lo, box_hi))
    from ..executor import executor_for  # imported on use: not at start-up
    runner = executor_for(executor)
    try:
        results = runner.map(partial(local_fit, residual, lo, hi, max_nfev), candidates)
    finally:
        if runner is not executor:
            runner.close()
    best = None
    for res in results:  # the first of equal costs, whatever the executor
        if best is None or res.cost < best.cost:
            best = res
    values = full_values(best.x)
    model_force = model.force(record, values)
    model_force = model_force if mask is None else model_force[mask]
    resid = F - model_force
    rss = float(np.sum(resid**2))
    n, k = len(F), len(free)
    stderr, corr = uncertainty(best.jac, best.x, tr, rss, n, k)
    rss_n = max(rss / n, np.finfo(float).tiny)
    return FitResult(
        model=model, values=values, free=free, stderr=dict(zip(free, stderr)), correlation=corr,
        force=model_force, residual=resid, esr=esr(F, model_force), rss=rss, n=n,
        aic=n * math.log(rss_n) + 2 * k, bic=n * math.log(rss_n) + k * math.log(n),
        success=bool(best.success), message=str(best.message), record_name=record.name,
        extra={"initial_cost": float(np.sum(r0**2) / 2), "nfev": int(best.nfev)})


def evaluate(model: Model, record: Measurement, values: Mapping[str, float]) -> float:
    """ESR of ``model`` with ``values`` on ``record``."""
    try:
        return esr(record.require_force(), model.simulate(record, values))
    except ParameterError:
        raise
