r"""Power-law fits of yield-stress curves: where a power-law summary of a richer law holds, and how well."""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ...errors import ErdesignError

__all__ = ["PowerLawFit", "fit_power_law"]


class PowerLawFit(NamedTuple):
    """Result of :func:`fit_power_law`: the power law and where and how well it holds (SI)."""

    yield_stress: float
    """tau_ref, fitted yield stress at the reference control, [Pa]."""
    reference_field: float
    """E_ref, the reference control (the top of the fit range unless given), SI unit of the control."""
    yield_exponent: float
    """n, [-]."""
    exponent_stderr: float
    """Standard error of n from the least-squares fit in log-log coordinates, [-] (0 for an exact fit)."""
    field_min: float
    """Smallest control of the points fitted (> 0), SI unit of the control."""
    field_max: float
    """Largest control of the points fitted, SI unit of the control."""
    max_relative_error: float
    """Largest |tau_fit / tau - 1| over the points fitted, [-]."""
    points: int
    """Number of points fitted."""


def fit_power_law(E, tau_y, *, anchor=None) -> PowerLawFit:
    r"""Fit :math:`\tau_y = \tau_\text{ref}(E/E_\text{ref})^n` to a yield-stress curve by least squares in logs.

    .. math:: \ln\tau_y = \ln\tau_\text{ref} + n \ln\frac{E}{E_\text{ref}}

    Parameters
    ----------
    E : array
        Control at each point, SI unit of its kind.  Points with ``E <= 0`` or ``tau_y <= 0`` are left out (the
        logarithm is undefined there; the power law passes through the origin anyway).
    tau_y : array
        Yield stress at each point, [Pa].
    anchor : (float, float), optional
        ``(E_ref, tau_ref)``: make the law pass exactly through this point and fit the exponent alone,
        :math:`n = \sum x y / \sum x^2` with :math:`x = \ln(E/E_\text{ref})`, :math:`y = \ln(\tau_y/\tau_\text{ref})`.
        Without it both :math:`\tau_\text{ref}` and n are fitted (:func:`scipy.stats.linregress`) and
        :math:`E_\text{ref}` is the largest control fitted.

    Returns
    -------
    PowerLawFit
        The law, the standard error of n, the fit range and the largest relative error over it.

    Notes
    -----
    Least squares on logarithms weighs relative errors equally along the curve.  For a saturating curve no power
    law fits well over a wide range: the returned ``max_relative_error`` says how badly, and ``field_min`` /
    ``field_max`` say where the summary may be used at all.

    Examples
    --------
    >>> E = np.array([1e6, 2e6, 3e6]); fit = fit_power_law(E, 1800.0 * (E / 3e6) ** 2)
    >>> round(fit.yield_exponent, 6), round(fit.yield_stress, 3), fit.reference_field
    (2.0, 1800.0, 3000000.0)

    References
    ----------
    Butz and von Stryk (2002), section 2, for the law; the fit is ordinary least squares.
    """
    E = np.asarray(E, dtype=float).ravel()
    tau = np.asarray(tau_y, dtype=float).ravel()
    if E.shape != tau.shape:
        raise ErdesignError(f"fit_power_law: E and tau_y must have the same length, got {E.size} and {tau.size}")
    keep = (E > 0) & (tau > 0) & np.isfinite(E) & np.isfinite(tau)
    E, tau = E[keep], tau[keep]
    if anchor is None:
        if E.size < 2 or np.ptp(E) == 0:
            raise ErdesignError("fit_power_law: need at least two points of positive, distinct control and stress")
        E_ref = float(E.max())
        x, y = np.log(E / E_ref), np.log(tau)
        if E.size == 2:
            n = float((y[1] - y[0]) / (x[1] - x[0]))
            log_tau_ref, stderr = float(y[0] - n * x[0]), 0.0
        else:
            from scipy.stats import linregress  # imported here: scipy.stats costs ~0.5 s at start-up

            r = linregress(x, y)
            n, log_tau_ref, stderr = float(r.slope), float(r.intercept), float(r.stderr)
        tau_ref = math.exp(log_tau_ref)
    else:
        E_ref, tau_ref = (float(a) for a in anchor)
        if not (E_ref > 0 and tau_ref > 0):
            raise ErdesignError(f"fit_power_law: anchor must be a positive (E_ref, tau_ref), got {anchor!r}")
        x, y = np.log(E / E_ref), np.log(tau / tau_ref)
        if not np.any(x != 0):
            raise ErdesignError("fit_power_law: need a point away from the anchor to fit the exponent")
        n = float(np.sum(x * y) / np.sum(x * x))
        dof = max(E.size - 1, 1)
        stderr = float(math.sqrt(np.sum((y - n * x) ** 2) / dof / np.sum(x * x)))
    fitted = tau_ref * (E / E_ref) ** n
    return PowerLawFit(
        yield_stress=float(tau_ref),
        reference_field=float(E_ref),
        yield_exponent=n,
        exponent_stderr=stderr,
        field_min=float(E.min()),
        field_max=float(E.max()),
        max_relative_error=float(np.max(np.abs(fitted / tau - 1.0))),
        points=int(E.size),
    )
