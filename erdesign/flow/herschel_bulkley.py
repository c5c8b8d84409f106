r"""Herschel-Bulkley (shear-thinning) fluid through a thin stationary annular gap: SI kernels.

.. math:: \tau = \tau_y + K\,\dot\gamma^{m}\quad(|\tau| > \tau_y)

Thin gap (half-gap :math:`H = h/2`, wall stress :math:`\tau_w = \Delta p\,h/(2L)`, :math:`S = \tau_w - \tau_y`,
:math:`p = 1/m`): the flow rate is explicit,

.. math::
    Q = \pi d\;\frac{2H^2}{\tau_w^2 K^{p}}\;S^{p+1}\left(\frac{S}{p+2} + \frac{\tau_y}{p+1}\right),
    \qquad Q = 0 \text{ for } \tau_w \le \tau_y,

(integrate :math:`q = 2\int_0^H y\,|du/dy|\,dy` with the linear stress of Makris et al. (1996), eq 2), and the
pressure drop for a given flow is found per element with a vectorised bracketed root.  ``m = 1`` is the
Buckingham-Reiner flow of :mod:`erdesign.flow.bingham`.  The effect that uses them is
:mod:`erdesign.effects.shear_thinning`.
"""

from __future__ import annotations

import numpy as np

from ._checks import check_flow_args

__all__ = ["herschel_bulkley_slit_flow_rate", "herschel_bulkley_pressure_drop"]


def herschel_bulkley_slit_flow_rate(dp, tau_y, K, m, L, d, h):
    r"""Flow rate of a Herschel-Bulkley fluid through a thin annular gap for a pressure drop (explicit).

    .. math::
        Q = \operatorname{sgn}(\Delta p)\,\pi d\,\frac{2H^2}{\tau_w^2 K^{1/m}}\,S^{1/m+1}
        \left(\frac{S}{1/m+2} + \frac{\tau_y}{1/m+1}\right), \quad \tau_w = \frac{|\Delta p| h}{2L},
        \quad S = \max(\tau_w - \tau_y, 0)

    Parameters
    ----------
    dp : float or array
        Pressure drop, signed, [Pa].
    tau_y : float or array
        Yield stress, [Pa].
    K : float or array
        Consistency, [Pa s^m].
    m : float
        Flow index, [-] (1: Bingham, < 1 shear thinning).
    L, d, h : float
        Duct length, mean diameter, gap, [m].

    Returns
    -------
    float or array
        Q, [m^3/s].

    Notes
    -----
    For m = 1 it is the Buckingham-Reiner flow of :func:`erdesign.flow.bingham.bingham_flow_rate` (tested).

    Examples
    --------
    >>> from erdesign.flow.bingham import bingham_flow_rate
    >>> q1 = herschel_bulkley_slit_flow_rate(5e5, 1800.0, 13.0, 1.0, 0.0546, 0.0143, 0.0008)
    >>> round(float(q1 / bingham_flow_rate(5e5, 1800.0, 13.0, 0.0546, 0.0143, 0.0008)), 12)
    1.0
    """
    check_flow_args(dp=dp, tau_y=tau_y, K=K, m=m, L=L, d=d, h=h)
    return _slit_flow_rate(dp, tau_y, K, m, L, d, h)


def _slit_flow_rate(dp, tau_y, K, m, L, d, h):
    """:func:`herschel_bulkley_slit_flow_rate` without the checks (called in the root finding of
    :func:`herschel_bulkley_pressure_drop`, whose arguments are checked once)."""
    p = 1.0 / m
    H = 0.5 * h
    tau_w = np.abs(dp) * h / (2.0 * L)
    S = np.maximum(tau_w - tau_y, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = (
            2.0
            * H**2
            / np.where(tau_w > 0, tau_w, 1.0) ** 2
            * K ** (-p)
            * S ** (p + 1)
            * (S / (p + 2) + tau_y / (p + 1))
        )
    return np.sign(dp) * np.pi * d * q


def herschel_bulkley_pressure_drop(Q, tau_y, K, m, L, d, h):
    r"""Pressure drop of Herschel-Bulkley flow through a thin annular gap for a flow rate (vectorised root).

    Solves :func:`herschel_bulkley_slit_flow_rate` (dp) = Q for dp per element, in one compiled pass
    (:func:`erdesign.flow._compiled.hb_slit_pressure_drop`): Newton's method on the logarithm of the wall stress
    above yield, :math:`\ln(\tau_w - \tau_y)`, where the log of the flow is nearly linear (exactly so far above
    yield and near it), started from the larger of the two limits' roots, which bounds the root from below; to
    1e-13 in :math:`\ln(\Delta p)`.

    Parameters
    ----------
    Q : float or array
        Flow rate, signed, [m^3/s].
    tau_y, K, m, L, d, h
        As :func:`herschel_bulkley_slit_flow_rate`.

    Returns
    -------
    float or array
        Pressure drop with the sign of Q, [Pa]; the break-away value :math:`2\tau_y L/h` at Q = 0.

    Examples
    --------
    >>> round(herschel_bulkley_pressure_drop(1e-5, 1800.0, 13.0, 1.0, 0.0546, 0.0143, 0.0008) / 1e6, 4)
    4.0712
    """
    # numba, imported here: ``import erdesign.flow`` does not pay for it
    from ._compiled import hb_slit_pressure_drop

    check_flow_args(Q=Q, tau_y=tau_y, K=K, m=m, L=L, d=d, h=h)
    Q = np.asarray(Q, dtype=float)
    args = np.broadcast_arrays(Q, *(np.asarray(a, dtype=float) for a in (tau_y, K, m, L, d, h)))
    Qb, rest = args[0], [np.ascontiguousarray(a).ravel() for a in args[1:]]
    out = hb_slit_pressure_drop(np.abs(Qb).ravel(), *rest, np.empty(Qb.size)).reshape(Qb.shape)
    out = np.copysign(out, Qb)
    return float(out) if out.ndim == 0 else out
