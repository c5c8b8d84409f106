r"""Shear thinning: the post-yield stress grows slower than linearly with shear rate (Herschel-Bulkley).

.. math:: \tau = \tau_y + K\,\dot\gamma^{m}\quad(|\tau| > \tau_y), \qquad K = \eta\,\dot\gamma_\text{ref}^{\,1-m}

The consistency K is tied to the plastic viscosity so that the Herschel-Bulkley and Bingham curves meet at the
reference shear rate :math:`\dot\gamma_\text{ref}` = 1000 1/s (mid-range of damper gaps); ``m = 1`` is Bingham.

Valve ducts (thin gap, half-gap :math:`H = h/2`, wall stress :math:`\tau_w = \Delta p\,h/(2L)`,
:math:`S = \tau_w - \tau_y`, :math:`p = 1/m`): the flow rate is explicit,

.. math::
    Q = \pi d\;\frac{2H^2}{\tau_w^2 K^{p}}\;S^{p+1}\left(\frac{S}{p+2} + \frac{\tau_y}{p+1}\right),
    \qquad Q = 0 \text{ for } \tau_w \le \tau_y,

(integrate :math:`q = 2\int_0^H y\,|du/dy|\,dy` with the linear stress of Makris eq 2), and the pressure drop for a
given flow is found per sample with a vectorised bracketed root.  Mixed (moving-electrode) gaps: erdesign uses the
Bingham Couette-Poiseuille solution with the apparent viscosity :math:`K\dot\gamma_a^{m-1}` at the apparent shear
rate :math:`\dot\gamma_a = 6|Q|/(\pi d h^2) + |v|/h` (an approximation, stated here).
"""

from __future__ import annotations

import numpy as np
from scipy.optimize.elementwise import bracket_root, find_root

from ..parameters import Parameter
from .base import Effect, peak_speed

__all__ = ["ShearThinning", "herschel_bulkley_slit_flow_rate", "herschel_bulkley_pressure_drop",
           "REFERENCE_SHEAR_RATE"]

#: Shear rate at which the Herschel-Bulkley consistency matches the plastic viscosity, [1/s].
REFERENCE_SHEAR_RATE = 1000.0


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
    p = 1.0 / m
    H = 0.5 * h
    tau_w = np.abs(dp) * h / (2.0 * L)
    S = np.maximum(tau_w - tau_y, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = 2.0 * H**2 / np.where(tau_w > 0, tau_w, 1.0) ** 2 * K ** (-p) * S ** (p + 1) * (
            S / (p + 2) + tau_y / (p + 1))
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
        return herschel_bulkley_slit_flow_rate(np.exp(logdp), tau_y, K, m, L, d, h) - Qa

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


class ShearThinning(Effect):
    name = "shear_thinning"
    title = "Shear thinning (Herschel-Bulkley)"
    mechanism = ("After yield the stress grows slower than linearly with the shear rate (flow index m < 1): the "
                 "damper is stiffer than Bingham at low speed and softer at high speed.")
    signature = ("residual even-odd pattern in speed: the model is too low at moderate post-yield speeds and too "
                 "high at the highest speeds (the force-velocity curve bends over)")
    stage = "constitutive"
    neutral = {"flow_index": 1.0}
    source = "Herschel-Bulkley law; the MR-model review (c0 falling with speed: shear thinning)"

    def parameters(self, damper):
        return (Parameter("flow_index", "", 1.0, 0.2, 1.5, "Herschel-Bulkley flow index m (1: Bingham)"),)

    def start(self, damper, record):
        return {"flow_index": 0.8}

    def check(self, record, damper):
        v = np.abs(record.velocity)
        if peak_speed(record) == 0 or np.percentile(v, 90) < 2 * np.percentile(v, 30):
            return "the speeds of the record span less than a factor of 2, too narrow to see the curve bend"
        return None

    def gap_law(self, law, values):
        return law._replace(flow_index=values["flow_index"], reference_shear_rate=REFERENCE_SHEAR_RATE)
