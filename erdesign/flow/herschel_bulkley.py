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

    Solves :func:`herschel_bulkley_slit_flow_rate` (dp) = Q for dp per element: bracket from the yield
    pressure drop :math:`2\tau_y L/h` upwards (:func:`scipy.optimize.elementwise.bracket_root`), then
    Chandrupatla's method (:func:`~scipy.optimize.elementwise.find_root`) on :math:`\ln(\Delta p)`.

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
    # imported here: scipy.optimize doubles the start-up time of every command that imports erdesign.flow
    from scipy.optimize.elementwise import bracket_root, find_root

    check_flow_args(Q=Q, tau_y=tau_y, K=K, m=m, L=L, d=d, h=h)
    Q = np.asarray(Q, dtype=float)
    tau_y, K = np.broadcast_arrays(np.asarray(tau_y, dtype=float) + 0 * Q, np.asarray(K, dtype=float) + 0 * Q)
    Qa = np.abs(Q)
    dp_y = 2.0 * tau_y * L / h
    # power-law (tau_y = 0) pressure drop of this flow: the viscous part; dp_y + it is a first guess
    p = 1.0 / m
    H = 0.5 * h
    with np.errstate(divide="ignore"):
        tau_pl = (Qa / (np.pi * d) * (p + 2) * K**p / (2 * H**2)) ** (1.0 / p)
    dp_pl = tau_pl * 2.0 * L / h
    floor = np.maximum(dp_y, 1e-300)
    x0 = np.log(np.maximum(dp_y + dp_pl, floor * (1 + 1e-12)) + 1e-300)

    def f(logdp, Qa, tau_y, K):
        return _slit_flow_rate(np.exp(logdp), tau_y, K, m, L, d, h) - Qa

    flowing = Qa > 0
    out = np.array(dp_y, dtype=float)
    if np.any(flowing):
        a = (Qa[flowing], tau_y[flowing], K[flowing])
        xf = x0[flowing]
        xmin = np.where(dp_y[flowing] > 0, np.log(np.maximum(dp_y[flowing], 1e-300)), xf - 60.0)
        br = bracket_root(f, np.maximum(xf - 0.5, xmin), xf + 0.5, xmin=xmin, args=a, maxiter=200)
        res = find_root(f, (br.bracket[0], br.bracket[1]), args=a, tolerances={"xatol": 1e-13, "xrtol": 0})
        out[flowing] = np.exp(res.x)
    out = np.copysign(out, Q)
    return float(out) if out.ndim == 0 else out
