r"""The truth rig's own valve laws: the flow rate of a slit as an explicit function of the pressure drop.

Written independently of :mod:`erdesign.flow` (which solves for the pressure drop from the flow rate): here the
flow rate follows from the pressure drop by integrating the velocity profile, and the rig inverts it with a
bracketed root where it needs the pressure drop.

Thin-gap slit of width :math:`b = \pi d`, gap :math:`h` (half-gap :math:`H = h/2`), length :math:`L`, pressure
gradient :math:`G = \Delta p / L`.  The shear stress is linear across the gap, :math:`\tau = G y` (``y`` from the
mid-plane), and the wall stress is :math:`\tau_w = G H = \Delta p\,h/(2L)`.  For a Herschel-Bulkley fluid,
:math:`\tau = \tau_y + K\dot\gamma^m` where it flows, the flow per unit width is (integration by parts,
:math:`q = 2\int_0^H y\,\dot\gamma\,\mathrm{d}y`, then :math:`s = G y - \tau_y`)

.. math::
    q = \frac{2}{G^2 K^{1/m}}\left[\frac{S^{1/m+2}}{1/m+2} + \tau_y\,\frac{S^{1/m+1}}{1/m+1}\right],
    \qquad S = \tau_w - \tau_y > 0,

and :math:`q = 0` for :math:`\tau_w \le \tau_y` (the gap is blocked below the yield pressure drop
:math:`\Delta p_y = 2\tau_y L/h`).  With :math:`m = 1`, :math:`K = \eta` this is the Buckingham-Reiner law of a
Bingham plastic,

.. math::
    Q = \frac{b h^3 \Delta p}{12 \eta L}\,(1 - r)^2\left(1 + \frac{r}{2}\right)
      = \frac{b h^3 \Delta p}{12 \eta L}\left(1 - \frac{3}{2} r + \frac{1}{2} r^3\right),
    \qquad r = \frac{\tau_y}{\tau_w} = \frac{\Delta p_y}{\Delta p} \le 1,

the explicit form of Makris et al. eq 6 (printed there with :math:`h^2`; :math:`h^3` is dimensionally right).

The consistency of the Herschel-Bulkley fluid is tied to the plastic viscosity by a reference shear rate,
:math:`K = \eta\,\dot\gamma_\text{ref}^{1-m}` with :math:`\dot\gamma_\text{ref}` = :data:`REFERENCE_SHEAR_RATE`, so
that both fluids have the same stress at that rate and :math:`m = 1` is the Bingham fluid.

The scalar kernels are compiled with numba (``cache=True``) so that the time-stepping loops of
:mod:`erdesign.truthrig.kernels` can call them; :func:`bingham_valve_flow` and :func:`herschel_bulkley_valve_flow`
are their vectorised public faces.
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["REFERENCE_SHEAR_RATE", "bingham_valve_flow", "herschel_bulkley_valve_flow", "consistency"]

#: Reference shear rate that ties the Herschel-Bulkley consistency to the plastic viscosity, [1/s].
REFERENCE_SHEAR_RATE = 1000.0


@numba.njit(cache=True)
def slit_flow(dp, tau_y, K, m, L, b, h):
    """Flow rate [m^3/s] of a Herschel-Bulkley slit at pressure drop ``dp`` >= 0 [Pa] (module notes)."""
    if dp <= 0.0:
        return 0.0
    G = dp / L
    tau_w = 0.5 * G * h
    S = tau_w - tau_y
    if S <= 0.0:
        return 0.0
    if m == 1.0:
        r = tau_y / tau_w
        return b * h**3 * dp / (12.0 * K * L) * (1.0 - r) ** 2 * (1.0 + 0.5 * r)
    n = 1.0 / m
    return b * 2.0 / (G * G * K**n) * (S ** (n + 2.0) / (n + 2.0) + tau_y * S ** (n + 1.0) / (n + 1.0))


@numba.njit(cache=True)
def slit_flow_slope(dp, tau_y, K, m, L, b, h):
    """dQ/d(dp) of :func:`slit_flow`, [m^3/(s Pa)] (0 below the yield pressure drop)."""
    if dp <= 0.0:
        return 0.0
    G = dp / L
    H = 0.5 * h
    tau_w = G * H
    S = tau_w - tau_y
    if S <= 0.0:
        return 0.0
    n = 1.0 / m
    q = slit_flow(dp, tau_y, K, m, L, b, h) / b
    # q = 2 I(S) / (G^2 K^n) with dI/dS = S^n tau_w and dS/dG = H
    dq_dG = -2.0 * q / G + 2.0 * H * S**n * tau_w / (G * G * K**n)
    return b * dq_dG / L


def consistency(eta, flow_index):
    """Herschel-Bulkley consistency K = eta * gamma_ref**(1 - m), [Pa s^m] (module notes)."""
    return np.asarray(eta, dtype=float) * REFERENCE_SHEAR_RATE ** (1.0 - np.asarray(flow_index, dtype=float))


@numba.vectorize(["float64(float64, float64, float64, float64, float64, float64, float64)"], cache=True)
def _slit_flow_ufunc(dp, tau_y, K, m, L, b, h):
    return slit_flow(dp, tau_y, K, m, L, b, h)


def _out(q):
    return float(q) if np.ndim(q) == 0 else q


def bingham_valve_flow(dp, tau_y, eta, L, d, h):
    r"""Flow rate through a thin annular duct of a Bingham plastic at a pressure drop (Buckingham-Reiner).

    .. math::
        Q = \frac{\pi d h^3 \Delta p}{12 \eta L}\left(1 - \frac{3}{2} r + \frac{1}{2} r^3\right),
        \quad r = \frac{2 \tau_y L}{\Delta p\,h}, \qquad Q = 0 \text{ for } r \ge 1.

    Parameters
    ----------
    dp : float or array
        Pressure drop along the duct, [Pa]; the flow takes its sign.
    tau_y : float or array
        Yield stress, [Pa], >= 0.
    eta : float or array
        Plastic viscosity, [Pa s], > 0.
    L : float
        Duct length, [m].
    d : float
        Mean diameter of the annulus, [m] (the slit width is pi d).
    h : float
        Gap, [m].

    Returns
    -------
    float or array
        Q, [m^3/s].

    Notes
    -----
    Steady laminar thin-gap flow (error O(h/d) against the exact annulus), no wall slip.  The factored form
    :math:`(1 - r)^2 (1 + r/2)` keeps full relative precision just above the yield pressure drop.

    Examples
    --------
    The Makris damper's duct at the Newtonian limit: Q = pi d h^3 dp / (12 eta L).

    >>> q = bingham_valve_flow(1e6, 0.0, 7.0, 0.0546, 0.0143, 0.8e-3)
    >>> round(q * 1e6, 3)        # cm^3/s
    5.015
    >>> bingham_valve_flow(2 * 1800 * 0.0546 / 0.8e-3, 1800.0, 13.0, 0.0546, 0.0143, 0.8e-3)   # at yield
    0.0

    References
    ----------
    Makris, Burton, Hill and Jordan (1996), eq 6 (with h^3 for the printed h^2); Buckingham (1921), Reiner (1926)
    for the slit.
    """
    return herschel_bulkley_valve_flow(dp, tau_y, eta, 1.0, L, d, h)


def herschel_bulkley_valve_flow(dp, tau_y, eta, flow_index, L, d, h):
    r"""Flow rate through a thin annular duct of a Herschel-Bulkley fluid at a pressure drop.

    .. math::
        Q = \frac{2 \pi d}{G^2 K^{1/m}}\left[\frac{S^{1/m+2}}{1/m+2} + \tau_y\frac{S^{1/m+1}}{1/m+1}\right],
        \quad G = \frac{\Delta p}{L},\ S = \frac{G h}{2} - \tau_y,\ K = \eta\,\dot\gamma_\text{ref}^{1-m}

    Parameters
    ----------
    dp : float or array
        Pressure drop, [Pa]; the flow takes its sign.
    tau_y : float or array
        Yield stress, [Pa], >= 0.
    eta : float or array
        Plastic viscosity at the reference shear rate, [Pa s] (K = eta gamma_ref^(1-m)).
    flow_index : float or array
        m, [-], > 0 (m < 1 shear thinning, m = 1 Bingham).
    L, d, h : float
        Duct length, mean diameter and gap, [m].

    Returns
    -------
    float or array
        Q, [m^3/s].

    Notes
    -----
    From the velocity profile of the slit (module notes); the same assumptions as :func:`bingham_valve_flow`.
    ``tests/test_truthrig.py`` checks it against numerical quadrature of the profile.

    Examples
    --------
    >>> q1 = herschel_bulkley_valve_flow(2e5, 1000.0, 1.0, 1.0, 0.05, 0.04, 1e-3)
    >>> q1 == bingham_valve_flow(2e5, 1000.0, 1.0, 0.05, 0.04, 1e-3)
    True

    References
    ----------
    Herschel and Bulkley (1926) for the law; the slit integral as in Bird, Armstrong and Hassager (1987), ch. 4.
    """
    dp = np.asarray(dp, dtype=float)
    K = consistency(eta, flow_index)
    q = _slit_flow_ufunc(np.abs(dp), np.asarray(tau_y, dtype=float), K, np.asarray(flow_index, dtype=float),
                         float(L), math.pi * float(d), float(h))
    return _out(np.copysign(q, dp))
