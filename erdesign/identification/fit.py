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

from collections.abc import Mapping, Sequence

import numpy as np

from ..data.measurement import Measurement
from ..data.metrics import esr
from ..models.base import Model, ParameterError
from .engine import FitError, Strategy, _mask_arg, problem, solve
from .result import FitResult

__all__ = ["FitError", "FitResult", "evaluate", "fit"]


def fit(
    model: Model,
    record: Measurement,
    *,
    free: Sequence[str] | None = None,
    fixed: Mapping[str, float] | None = None,
    start: Mapping[str, float] | None = None,
    starts: int = 1,
    global_search: bool = False,
    seed: int = 0,
    max_nfev: int | None = None,
    executor=None,
    mask: np.ndarray | None = None,
) -> FitResult:
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
    if not isinstance(model, Model):  # a Damper or a list: "'Damper' object has no attribute 'require_force'"
        hint = (
            " (a damper: use erdesign.calibrate, or a model of erdesign.get_model)" if hasattr(model, "fluid") else ""
        )
        raise FitError(f"model: expected a model (erdesign.get_model), got {type(model).__name__}{hint}")
    if not isinstance(record, Measurement):
        raise FitError(
            f"record: expected a Measurement (erdesign.read_measurement or Measurement.from_arrays), got "
            f"{type(record).__name__}"
        )
    mask = _mask_arg(mask, record)
    F = record.require_force() if mask is None else record.require_force()[mask]
    check = getattr(model, "check_record", None)
    if check is not None:
        check(record)
    pb = problem(
        model,
        [record],
        free=free,
        fixed=fixed,
        start=start,
        masks=[mask],
        control_reference=False,
        samples=len(F),
        label=record.name or "record",
    )
    if not np.all(np.isfinite(model.force(record, pb.values(pb.z0)))):
        raise FitError(f"{model.name}: the model gives non-finite forces at the starting values")
    result = solve(
        pb, Strategy(starts=starts, global_search=global_search, seed=seed, max_nfev=max_nfev, executor=executor)
    )
    if mask is not None:  # force and residual of the compared samples
        result.force, result.residual = result.force[mask], result.residual[mask]
    return result


def evaluate(model: Model, record: Measurement, values: Mapping[str, float]) -> float:
    """ESR of ``model`` with ``values`` on ``record``."""
    try:
        return esr(record.require_force(), model.simulate(record, values))
    except ParameterError:
        raise
