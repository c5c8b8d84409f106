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
:mod:`erdesign.simulation.truthrig.kernels` can call them; :func:`bingham_valve_flow` and
:func:`herschel_bulkley_valve_flow` are their vectorised public faces.
"""

from __future__ import annotations

import math

import numpy as np

from ..._compile import guvectorize, njit, vectorize

__all__ = ["REFERENCE_SHEAR_RATE", "bingham_valve_flow", "herschel_bulkley_valve_flow", "consistency"]

#: Reference shear rate that ties the Herschel-Bulkley consistency to the plastic viscosity, [1/s].
REFERENCE_SHEAR_RATE = 1000.0


@njit(cache=True)
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


@njit(cache=True)
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


@vectorize(["float64(float64, float64, float64, float64, float64, float64, float64)"], cache=True)
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
    q = _slit_flow_ufunc(
        np.abs(dp),
        np.asarray(tau_y, dtype=float),
        K,
        np.asarray(flow_index, dtype=float),
        float(L),
        math.pi * float(d),
        float(h),
    )
    return _out(np.copysign(q, dp))


# ---------------------------------------------------------------------------------------------------- moving wall
# The gap of a moving-electrode (mixed-mode) head: plane Couette-Poiseuille flow, again flow from pressure.
#
# y runs from the fixed wall (y = 0, the cylinder) to the moving wall (y = h, the head, speed U along s); the
# pressure rises along s with gradient g = dp / L (dp: pressure ahead of the head minus behind it, the chamber the
# head moves into being "ahead").  Momentum gives a linear stress tau(y) = tau_0 + g y; no slip gives
#
#     U = int_0^h rate(tau_0 + g y) dy = [Phi(tau_0 + g h) - Phi(tau_0)] / g,      Phi(tau) = int_0^tau rate,
#
# non-decreasing in tau_0, solved for tau_0 by Newton steps inside a bracket; then the flow per unit width along s
#
#     q = int_0^h u dy = h U - int_0^h y rate dy = h U - [Psi(tau_h) - Psi(tau_0) - tau_0 (Phi(tau_h) - Phi(tau_0))] / g^2
#
# with Psi(tau) = int_0^tau s rate(s) ds, and the machine pushes the head with the wall stress tau_h = tau_0 + g h
# (the fluid's traction on the head is -tau_h).  For |g h| small beside the stresses the differences cancel; there
# the midpoint expansion U = h rate(tau_m), q = h^2 rate(tau_m)/2 - g h^3 rate'(tau_m)/12 (tau_m = tau_0 + g h/2)
# is used, good to O((g h / tau)^2).  Herschel-Bulkley rate: sgn(tau) ((|tau| - tau_y)_+ / K)^(1/m).

_SMALL_GRADIENT = 1e-4


@njit(cache=True)
def _hb_rate(tau, tau_y, Kn, n):
    S = abs(tau) - tau_y
    if S <= 0.0:
        return 0.0
    r = Kn * S**n
    return r if tau > 0.0 else -r


@njit(cache=True)
def _hb_rate_slope(tau, tau_y, Kn, n):
    S = abs(tau) - tau_y
    if S <= 0.0:
        return 0.0
    return n * Kn * S ** (n - 1.0)


@njit(cache=True)
def _hb_phi(tau, tau_y, Kn, n):
    S = abs(tau) - tau_y
    if S <= 0.0:
        return 0.0
    return Kn * S ** (n + 1.0) / (n + 1.0)


@njit(cache=True)
def _hb_psi(tau, tau_y, Kn, n):
    S = abs(tau) - tau_y
    if S <= 0.0:
        return 0.0
    value = Kn * (S ** (n + 2.0) / (n + 2.0) + tau_y * S ** (n + 1.0) / (n + 1.0))
    return value if tau > 0.0 else -value


@njit(cache=True)
def _wall_speed(tau0, g, h, tau_y, Kn, n):
    """(U, dU/dtau_0) of the profile with fixed-wall stress tau_0 and gradient g."""
    d = g * h
    if abs(d) <= _SMALL_GRADIENT * (abs(tau0) + tau_y) or d == 0.0:
        tm = tau0 + 0.5 * d
        return h * _hb_rate(tm, tau_y, Kn, n), h * _hb_rate_slope(tm, tau_y, Kn, n)
    return (
        (_hb_phi(tau0 + d, tau_y, Kn, n) - _hb_phi(tau0, tau_y, Kn, n)) / g,
        (_hb_rate(tau0 + d, tau_y, Kn, n) - _hb_rate(tau0, tau_y, Kn, n)) / g,
    )


@njit(cache=True)
def moving_wall_flow(dp, U, tau_y, K, m, L, h):
    """(q, tau_h): flow per unit width along s [m^2/s] and the stress on the moving wall [Pa] of a Herschel-Bulkley
    slit with pressure drop ``dp`` (ahead minus behind) over ``L`` and one wall moving at ``U`` (notes above)."""
    q, tau_h, _ = moving_wall_flow_from(dp, U, tau_y, K, m, L, h, math.nan)
    return q, tau_h


@njit(cache=True)
def moving_wall_flow_from(dp, U, tau_y, K, m, L, h, guess):
    """:func:`moving_wall_flow` with Newton started at the fixed-wall stress ``guess`` (NaN: no guess); returns
    (q, tau_h, tau_0), tau_0 to start the next call with."""
    n = 1.0 / m
    Kn = K ** (-n)
    g = dp / L
    # bracket: at +-A the whole gap shears at least as fast as |U| / h in one direction
    A = tau_y + K * (abs(U) / h) ** m + abs(g) * h
    lo, hi = -A, A
    tau0 = 0.0 if U == 0.0 else (0.5 * (lo + hi))
    if lo < guess < hi:
        tau0 = guess
    for _ in range(200):
        f, slope = _wall_speed(tau0, g, h, tau_y, Kn, n)
        f -= U
        if f == 0.0:
            break
        if f < 0.0:
            lo = tau0
        else:
            hi = tau0
        new = tau0 - f / slope if slope > 0.0 else 0.5 * (lo + hi)
        if abs(new - tau0) <= 1e-14 * (abs(tau0) + tau_y + abs(g) * h) or hi - lo <= 1e-15 * A:
            tau0 = new  # converged (a last step may touch the bracket's end: round-off)
            break
        if not (lo < new < hi):
            new = 0.5 * (lo + hi)
        tau0 = new
    d = g * h
    if abs(d) <= _SMALL_GRADIENT * (abs(tau0) + tau_y) or d == 0.0:
        tm = tau0 + 0.5 * d
        q = 0.5 * h * h * _hb_rate(tm, tau_y, Kn, n) - g * h**3 / 12.0 * _hb_rate_slope(tm, tau_y, Kn, n)
    else:
        th = tau0 + d
        phi = _hb_phi(th, tau_y, Kn, n) - _hb_phi(tau0, tau_y, Kn, n)
        speed = phi / g
        q = h * speed - (_hb_psi(th, tau_y, Kn, n) - _hb_psi(tau0, tau_y, Kn, n) - tau0 * phi) / (g * g)
    return q, tau0 + d, tau0


@guvectorize(
    ["void(float64, float64, float64, float64, float64, float64, float64, float64[:])"],
    "(),(),(),(),(),(),()->()",
    cache=True,
)
def _moving_wall_flow_ufunc(dp, U, tau_y, K, m, L, h, out):
    out[0] = moving_wall_flow(dp, U, tau_y, K, m, L, h)[0]


@guvectorize(
    ["void(float64, float64, float64, float64, float64, float64, float64, float64[:])"],
    "(),(),(),(),(),(),()->()",
    cache=True,
)
def _moving_wall_stress_ufunc(dp, U, tau_y, K, m, L, h, out):
    out[0] = moving_wall_flow(dp, U, tau_y, K, m, L, h)[1]


def mixed_gap_flow(dp, wall_speed, tau_y, eta, flow_index, L, d, h):
    r"""Flow rate and moving-wall stress of the gap of a moving-electrode head, from the pressure drop.

    Plane Couette-Poiseuille flow of a Herschel-Bulkley fluid (consistency :math:`K = \eta\,
    \dot\gamma_\text{ref}^{1-m}`) in a slit of width :math:`\pi d`: the head (one wall) moves at ``wall_speed``
    along the axis, the pressure ahead of it exceeds that behind it by ``dp``.

    Parameters
    ----------
    dp : float or array
        Pressure ahead of the head minus behind it, [Pa].
    wall_speed : float or array
        Speed of the head along the axis, [m/s].
    tau_y, eta, flow_index
        Yield stress [Pa], plastic viscosity at the reference shear rate [Pa s], flow index m [-] (1: Bingham).
    L, d, h : float
        Head (gap) length, mean diameter and gap, [m].

    Returns
    -------
    (Q, tau_wall) : floats or arrays
        Flow rate along the direction of the head's motion, [m^3/s] (fixed frame; negative: back-flow), and the
        shear stress the head must overcome, [Pa] (the machine pushes the head with tau_wall x its area).

    Notes
    -----
    Steady, laminar, thin gap, no slip (module notes).  Written from the pressure drop, the other way round from
    :func:`erdesign.flow.mixed_mode.couette_poiseuille_bingham`, which ``tests/test_truthrig.py`` compares it with.

    Examples
    --------
    Newtonian: Q = pi d (U h / 2 - h^3 dp / (12 eta L)), tau_wall = eta U / h + dp h / (2 L).

    >>> Q, tau = mixed_gap_flow(1e5, 0.1, 0.0, 0.5, 1.0, 0.05, 0.04, 1e-3)
    >>> round(Q * 1e6, 3), round(tau, 3)             # cm^3/s, Pa
    (-35.605, 1050.0)
    """
    K = consistency(eta, flow_index)
    args = [np.asarray(a, dtype=float) for a in (dp, wall_speed, tau_y, K, flow_index)] + [float(L), float(h)]
    b = math.pi * float(d)
    # (the compiled loop may evaluate a guarded Newton step speculatively: no result depends on it)
    with np.errstate(divide="ignore", invalid="ignore"):
        Q = b * _moving_wall_flow_ufunc(*args)
        tau = _moving_wall_stress_ufunc(*args)
    return _out(Q), _out(tau)
