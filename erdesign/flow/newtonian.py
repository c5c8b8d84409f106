"""Steady laminar flow of a Newtonian fluid through an annular duct (SI kernels).

Two descriptions of the same duct (inner radius ``(d - h)/2``, outer radius ``(d + h)/2``):

* the thin-gap (parallel-plate) approximation, Makris et al. eq 4, which unrolls the annulus into a slit of width
  ``pi d`` and height ``h``;
* the exact concentric-annulus Hagen-Poiseuille solution (Bird, Stewart and Lightfoot, *Transport Phenomena*,
  2nd ed., eq 2.4-17), to which the thin-gap form is the first term in an expansion in ``h/d``.

:func:`thin_gap_error` reports how far apart they are: the thin-gap form over-predicts the pressure drop by
``(h/d)**2 / 15`` to leading order, so by 0.02 % for the Makris duct (h/d = 0.056) and by 1.9 % at h/d = 0.5.

All arguments are SI floats or numpy arrays and broadcast against each other.
"""

from __future__ import annotations

import numpy as np

from ._checks import check_flow_args

__all__ = [
    "slit_pressure_drop",
    "slit_flow_rate",
    "annulus_pressure_drop",
    "annulus_flow_rate",
    "annulus_conductance_ratio",
    "thin_gap_error",
]


def slit_pressure_drop(Q, eta, L, d, h):
    r"""Pressure drop of Newtonian flow through a thin annular gap (parallel-plate approximation).

    .. math:: \Delta p = \frac{12\,\eta\,L\,Q}{\pi\,d\,h^3}

    Parameters
    ----------
    Q : float or array
        Volumetric flow rate through the duct, signed, [m^3/s].
    eta : float or array
        Dynamic viscosity, [Pa s].
    L : float or array
        Duct length, [m].
    d : float or array
        Mean diameter of the annulus, [m].
    h : float or array
        Gap (radial clearance), [m].

    Returns
    -------
    float or array
        Pressure drop, with the sign of ``Q``, [Pa].

    Notes
    -----
    Valid for laminar flow (Reynolds number of Makris eq 1 below about 2300) and ``h << d``; the error of the
    thin-gap form against the exact annulus is :func:`thin_gap_error`.

    Examples
    --------
    >>> round(slit_pressure_drop(Q=1e-6, eta=7.0, L=0.0546, d=0.0143, h=0.0008) / 1e3, 2)  # kPa
    199.4

    References
    ----------
    Makris, Burton, Hill and Jordan, ER damper with annular ducts for seismic protection applications, eq 4.
    """
    check_flow_args(Q=Q, eta=eta, L=L, d=d, h=h)
    return 12.0 * eta * L * Q / (np.pi * d * h**3)


def slit_flow_rate(dp, eta, L, d, h):
    r"""Flow rate of a Newtonian fluid through a thin annular gap for a given pressure drop, [m^3/s].

    The inverse of :func:`slit_pressure_drop`: :math:`Q = \pi d h^3 \Delta p / (12 \eta L)`.
    Parameters as in :func:`slit_pressure_drop`, with ``dp`` the pressure drop [Pa].
    """
    check_flow_args(dp=dp, eta=eta, L=L, d=d, h=h)
    return np.pi * d * h**3 * dp / (12.0 * eta * L)


def annulus_conductance_ratio(d, h):
    r"""Ratio of the exact annulus flow rate to the thin-gap flow rate at the same pressure drop.

        .. math::
            \frac{Q_\text{exact}}{Q_\text{slit}} =
            \frac{3}{2 d h^3}\left[R_2^4 - R_1^4 - \frac{(R_2^2 - R_1^2)^2}{\ln(R_2/R_1)}\right],
            \qquad R_{1,2} = \frac{d \mp h}{2}

        Parameters
        ----------
        d : float or array
            Mean diameter, [m].
        h : float or array
            Gap, [m]; ``0 < h < d``.

        Returns
        -------
        float or array
            The ratio (dimensionless); ``1 + e^2/15 + 11 e^4/315 + O(e^6)`` with ``e = h/d`` (series derived with
            sympy in tests/test_flow_newtonian.py).

        Notes
        -----
        Written in the ratio ``e = h/d`` with ``log1p`` so that it stays accurate as ``h/d -> 0``, where the bracket
        is a difference of nearly equal terms.  Below ``h/d = 1e-2`` the series is used (its first omitted term,
    ``107 e^6/4725``, is below 3e-14 there).
    """
    check_flow_args(annulus=True, d=d, h=h)
    e = np.asarray(h, dtype=float) / np.asarray(d, dtype=float)
    # R2/R1 = (1 + e)/(1 - e); R2^4 - R1^4 = d^4 e (1 + e^2)/2; (R2^2 - R1^2)^2 = d^4 e^2.
    with np.errstate(divide="ignore", invalid="ignore"):
        log_ratio = np.log1p(e) - np.log1p(-e)
        exact = 1.5 / e**3 * (0.5 * e * (1.0 + e * e) - e * e / log_ratio)
    e2 = e * e
    series = 1.0 + e2 * (1.0 / 15.0 + e2 * (11.0 / 315.0 + e2 * (107.0 / 4725.0 + e2 * 2549.0 / 155925.0)))
    out = np.where(e < 0.05, series, exact)
    return out if out.ndim else float(out)


def annulus_pressure_drop(Q, eta, L, d, h):
    r"""Pressure drop of Newtonian flow through a concentric annulus, exact Hagen-Poiseuille solution, [Pa].

    .. math:: \Delta p = \frac{12\,\eta\,L\,Q}{\pi\,d\,h^3} \Big/ \frac{Q_\text{exact}}{Q_\text{slit}}

    Parameters as in :func:`slit_pressure_drop`.  See :func:`annulus_conductance_ratio` for the ratio.

    References
    ----------
    Bird, Stewart and Lightfoot, Transport Phenomena, 2nd ed. (2002), section 2.4, eq 2.4-17.
    """
    return slit_pressure_drop(Q, eta, L, d, h) / annulus_conductance_ratio(d, h)


def annulus_flow_rate(dp, eta, L, d, h):
    """Flow rate of Newtonian flow through a concentric annulus (exact) for a pressure drop ``dp``, [m^3/s]."""
    return slit_flow_rate(dp, eta, L, d, h) * annulus_conductance_ratio(d, h)


def thin_gap_error(h_over_d):
    r"""Relative error of the thin-gap pressure drop against the exact annulus, Newtonian fluid.

    .. math:: \varepsilon = \frac{\Delta p_\text{slit}}{\Delta p_\text{exact}} - 1
              = \frac{Q_\text{exact}}{Q_\text{slit}} - 1 \approx \frac{(h/d)^2}{15}

    Parameters
    ----------
    h_over_d : float or array
        Gap over mean diameter, [-]; ``0 < h/d < 1``.

    Returns
    -------
    float or array
        Relative error [-]; positive: the thin-gap form over-predicts the pressure drop (and under-predicts the
        flow) of the real annulus.

    Examples
    --------
    >>> f"{thin_gap_error(0.8 / 14.3):.2e}"   # the Makris duct
    '2.09e-04'
    """
    return annulus_conductance_ratio(1.0, h_over_d) - 1.0
