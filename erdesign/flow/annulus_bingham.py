r"""Steady flow of a Bingham plastic through a concentric annulus with stationary walls, exact (SI kernels).

The exact counterpart of :mod:`erdesign.flow.bingham`, which unrolls the annulus into a slit.  The duct has inner
radius :math:`R_1 = (d - h)/2` and outer radius :math:`R_2 = (d + h)/2`; a pressure drop :math:`\Delta p` over the
length :math:`L` (:math:`G = \Delta p / L > 0`) drives the fluid in :math:`+z`.  The axial momentum balance
:math:`\frac{1}{r}\frac{d}{dr}(r\tau) = -G` gives the shear stress (positive where the velocity grows with r)

.. math:: \tau(r) = \frac{G}{2}\left(\frac{\lambda^2}{r} - r\right),

which is independent of the fluid.  Where :math:`|\tau| < \tau_y` the fluid is a rigid plug,
:math:`r_a \le r \le r_b`; :math:`\tau(r_a) = \tau_y` and :math:`\tau(r_b) = -\tau_y` give

.. math:: r_b - r_a = \frac{2\tau_y}{G}, \qquad \lambda^2 = r_a r_b ,

so the plug is exactly as thick as in the slit, :math:`\phi = (r_b - r_a)/h = \Delta p_y/\Delta p` with the same
blocking pressure drop :math:`\Delta p_y = 2\tau_y L/h`; only its radial position differs.  With
:math:`\tau \mp \tau_y = \frac{G}{2r}(r_a - r)(r + r_b)` (inner layer) and :math:`\frac{G}{2r}(r_b - r)(r + r_a)`
(outer layer), integrating :math:`du/dr = (\tau \mp \tau_y)/\eta` from each wall gives the plug velocity from
either side,

.. math::
    u_p &= \frac{G}{2\eta}\Big[\frac{t_1^2}{2} + r_b R_1\,P\!\big(\tfrac{t_1}{R_1}\big)\Big], \qquad t_1 = r_a - R_1,
    \\
    u_p &= \frac{G}{2\eta}\Big[\frac{t_2^2}{2} + r_a r_b\,Q\!\big(\tfrac{t_2}{r_b}\big)\Big], \qquad t_2 = R_2 - r_b,

with :math:`P(x) = (1 + x)\ln(1 + x) - x` and :math:`Q(y) = y - \ln(1 + y)`.  Equating the two (velocity
continuity across the plug) fixes the plug position; it is a monotonic equation in :math:`t_1` on
:math:`[0, h - 2\tau_y/G]`, solved element by element by Newton's method kept inside that bracket, in a compiled
loop (:mod:`erdesign.flow._compiled`).  The flow rate follows by integrating the closed-form velocity by
parts, which leaves the rational integrands

.. math::
    \frac{Q}{2\pi} = u_p\frac{R_2^2 - R_1^2}{2}
      - \frac{1}{2}\int_{R_1}^{r_a} (r^2 - R_1^2)\,\frac{du}{dr}\,dr
      + \frac{1}{2}\int_{r_b}^{R_2} (R_2^2 - r^2)\,\frac{du}{dr}\,dr ,

integrated by a Gauss-Legendre rule of 8, 16 or 32 points chosen by h/d (exact to rounding for h/d < 0.9, see
:func:`annulus_bingham_shape`).
Everything is written as a shape factor :math:`S = Q / Q_N`, the flow rate over the thin-gap Newtonian flow rate
:math:`Q_N = \pi d h^3 \Delta p / (12 \eta L)` at the same pressure drop (slit Bingham:
:math:`S = 1 - \tfrac32\phi + \tfrac12\phi^3`; Newtonian annulus: the conductance ratio of
:mod:`erdesign.flow.newtonian`).

:func:`thin_gap_error_bingham` compares the thin-gap form with this exact solution; docs/theory/thin_gap.md tabulates
it.  All functions take SI floats or numpy arrays that broadcast against each other.

References
----------
Fredrickson, A. G. and Bird, R. B. (1958), Non-Newtonian flow in annuli, Ind. Eng. Chem. 50(3), 347-352.
Bird, Stewart and Lightfoot, Transport Phenomena, 2nd ed. (2002), problem 2B.7 (Newtonian annulus, eq 2.4-17) and
the Bingham model, eq 8.3-2.  Makris et al. (1996), eq 2 (linear stress in the thin-gap limit) and eqs 5-7.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ._checks import check_flow_args

from .bingham import bingham_slit_flow

__all__ = [
    "annulus_bingham_shape",
    "annulus_bingham_flow_rate",
    "annulus_bingham_flow",
    "annulus_bingham_pressure_drop",
    "annulus_bingham_plug_fraction",
    "annulus_bingham_velocity",
    "AnnulusBinghamFlow",
    "thin_gap_error_bingham",
]


def _compiled():
    """The numba loops (:mod:`erdesign.flow._compiled`), imported on first use."""
    from . import _compiled as compiled

    return compiled


def _flat(*arrays):
    """Broadcast float arrays, their common shape and their contiguous 1-D views (for the compiled loops)."""
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in arrays))
    return arrays[0].shape, [np.array(a, order="C").ravel() for a in arrays]  # copies: the views are not writeable


def _shape_and_offset(phi, eps):
    """Shape factor S = Q/Q_N and plug offset t1 (in units of h) for arrays phi (plug fraction, [0, 1]) and
    eps = h/d: the plug position by Newton's method on velocity continuity, the flow rate by Gauss-Legendre
    quadrature of the layer integrals, element by element in a compiled loop."""
    shape, (phi, eps) = _flat(phi, eps)
    out = _compiled().annulus_shape_offset(phi, eps, np.empty((2, phi.size)))
    return out[0].reshape(shape), out[1].reshape(shape)


def annulus_bingham_shape(plug_fraction, h_over_d):
    r"""Flow-rate shape factor of Bingham flow through a concentric annulus: Q over the thin-gap Newtonian Q.

    .. math::
        S(\phi, h/d) = \frac{Q}{\pi d h^3 \Delta p/(12 \eta L)}
        = 6\,\hat u_p - 6\,\frac{h}{d}\,(\hat J_1 + \hat J_2)

    with :math:`\hat u_p = 2\eta u_p/(G h^2)` the plug velocity and :math:`\hat J_{1,2}` the two layer integrals of
    the module notes, in units of :math:`G h^4/(2\eta)`.

    Parameters
    ----------
    plug_fraction : float or array
        Plug thickness over gap, :math:`\phi = \Delta p_y/\Delta p`, [-], in [0, 1].
    h_over_d : float or array
        Gap over mean diameter, [-], in (0, 1).

    Returns
    -------
    float or array
        S [-]: 0 for a blocked gap (:math:`\phi = 1`); the Newtonian conductance ratio
        :math:`1 + (h/d)^2/15 + \dots` at :math:`\phi = 0`; :math:`1 - \tfrac32\phi + \tfrac12\phi^3` as
        :math:`h/d \to 0`.

    Notes
    -----
    The layer integrands are a cubic polynomial plus a pole at :math:`r = 0`.  An n-point Gauss-Legendre rule
    converges like :math:`\rho^{-2n}` with :math:`\rho = a + \sqrt{a^2 - 1}`, :math:`a \ge 1 + 2R_1/h = d/h`; the
    smallest of 8, 16 and 32 points with :math:`\rho^{-2n} < 10^{-20}` is used (8 up to h/d = 0.1, 16 up to 0.3):
    below 1e-19 relative for h/d <= 0.8 and 1e-9 at h/d = 0.95 (tests/test_flow_numerical.py and
    tests/test_flow_compiled.py check it against scipy.integrate.quad).  The closed-form antiderivative was not
    used because its terms are of order :math:`(d/h)^2` larger than the result and cancel.

    Examples
    --------
    >>> round(float(annulus_bingham_shape(0.0, 0.5)), 6)     # Newtonian annulus, h/d = 0.5
    1.019282
    >>> round(float(annulus_bingham_shape(0.5, 1e-4)), 6)    # thin gap: 1 - 3/4 + 1/16
    0.3125

    References
    ----------
    Fredrickson and Bird (1958); Bird, Stewart and Lightfoot (2002), problem 2B.7 and eq 8.3-2.
    """
    check_flow_args(plug_fraction=plug_fraction, h_over_d=h_over_d)
    shape, _ = _shape_and_offset(plug_fraction, h_over_d)
    return shape if shape.ndim else float(shape)


def annulus_bingham_flow_rate(dp, tau_y, eta, L, d, h):
    r"""Flow rate of a Bingham plastic through a concentric annulus for a given pressure drop (exact).

    .. math::
        Q = \operatorname{sgn}(\Delta p)\,\frac{\pi d h^3 |\Delta p|}{12 \eta L}\,S(\phi, h/d), \qquad
        \phi = \frac{\Delta p_y}{|\Delta p|}, \quad \Delta p_y = \frac{2\tau_y L}{h},

    and :math:`Q = 0` for :math:`|\Delta p| \le \Delta p_y`; :math:`S` is :func:`annulus_bingham_shape`.

    Parameters
    ----------
    dp : float or array
        Pressure drop along the duct, signed, [Pa].
    tau_y : float or array
        Yield stress, [Pa]; zero gives the exact Newtonian annulus.
    eta : float or array
        Plastic viscosity, [Pa s].
    L : float or array
        Duct length, [m].
    d : float or array
        Mean diameter of the annulus, [m].
    h : float or array
        Gap (radial clearance), [m]; ``0 < h < d``.

    Returns
    -------
    float or array
        Flow rate, [m^3/s], with the sign of ``dp``.

    Notes
    -----
    Laminar, steady, fully developed, concentric, stationary walls, no wall slip, rigid-plastic plug (no
    pre-yield elasticity).  Same signature as :func:`erdesign.flow.bingham.bingham_flow_rate`.

    Examples
    --------
    Makris's duct at 3 kV/mm and 8 MPa (thin gap, erdesign.flow.bingham: 2.0609e-05 m^3/s):

    >>> f"{annulus_bingham_flow_rate(8e6, 1800.0, 13.0, 0.0546, 0.0143, 0.0008):.4e}"
    '2.0613e-05'

    References
    ----------
    Fredrickson and Bird (1958); Makris et al. (1996), eq 6 (its thin-gap limit, printed with h^2 for h^3).
    """
    check_flow_args(annulus=True, dp=dp, tau_y=tau_y, eta=eta, L=L, d=d, h=h)
    dp = np.asarray(dp, dtype=float)
    dp_abs = np.abs(dp)
    dp_y = 2.0 * tau_y * L / h
    with np.errstate(divide="ignore", invalid="ignore"):
        phi = np.where(dp_abs > dp_y, dp_y / dp_abs, 1.0)
    shape = annulus_bingham_shape(phi, np.asarray(h / d, dtype=float))
    q = np.sign(dp) * np.pi * d * h**3 * dp_abs / (12.0 * eta * L) * shape
    return q if np.ndim(q) else float(q)


class AnnulusBinghamFlow(NamedTuple):
    """Result of :func:`annulus_bingham_flow`."""

    pressure_drop: float | np.ndarray
    """Pressure drop with the sign of the flow, [Pa]."""
    plug_fraction: float | np.ndarray
    """Plug thickness over gap, [-]: 0 Newtonian, 1 blocked gap."""
    plug_inner_radius: float | np.ndarray
    """Radius of the plug's inner edge r_a, [m] (for a Newtonian fluid: the radius of maximum velocity)."""
    plug_outer_radius: float | np.ndarray
    """Radius of the plug's outer edge r_b, [m]."""


def annulus_bingham_flow(Q, tau_y, eta, L, d, h):
    r"""Pressure drop, plug fraction and plug position of Bingham flow through a concentric annulus, for a flow rate.

    Solves :math:`S(\phi, h/d) / \phi = N` for the plug fraction, with :math:`S` from
    :func:`annulus_bingham_shape` and the flow ratio

    .. math::
        N = \frac{\Delta p_N}{\Delta p_y} = \frac{6\eta |Q|}{\pi d h^2 \tau_y} = \frac{6}{\mathrm{Bi}},
        \qquad \Delta p = \frac{\Delta p_y}{\phi} = \frac{2\tau_y L}{\phi h}.

    Parameters
    ----------
    Q : float or array
        Flow rate through the duct, signed, [m^3/s].
    tau_y : float or array
        Yield stress, [Pa], >= 0.
    eta : float or array
        Plastic viscosity, [Pa s], > 0.
    L : float or array
        Duct length, [m].
    d : float or array
        Mean diameter of the annulus, [m].
    h : float or array
        Gap, [m]; ``0 < h < d``.

    Returns
    -------
    AnnulusBinghamFlow
        ``pressure_drop`` [Pa] with the sign of ``Q``, ``plug_fraction`` [-], ``plug_inner_radius`` and
        ``plug_outer_radius`` [m].

    Notes
    -----
    :math:`S/\phi` falls monotonically from infinity (:math:`\phi \to 0`) to 0 (:math:`\phi = 1`), so the root is
    bracketed by :math:`[\phi_0, 1]` with :math:`\phi_0 = 1/(2N + 3)` (the slit bound :math:`S \ge 1 - \tfrac32\phi`
    with a factor of 2 to spare).  The root is found element by element in a compiled loop: from the thin-gap plug
    fraction (in error by O((h/d)^2)), one step with the thin-gap slope, then secant steps kept inside
    :math:`[0, 1]` (2-6 evaluations of :math:`S`); each evaluation solves the plug position by Newton's method
    started from the last one (one or two steps).
    As in :func:`erdesign.flow.bingham.bingham_slit_flow`, ``Q = 0`` returns the break-away pressure drop
    :math:`\Delta p_y` (signed like ``Q``, ``-0.0`` included) with a plug filling the gap, ``tau_y = 0`` returns
    the exact Newtonian annulus, and a yield stress whose :math:`\Delta p_y` is below 1e-12 of the viscous pressure
    drop (a denormal one, say) the Newtonian annulus plus :math:`\tfrac32\Delta p_y` with a plug fraction of 0.

    Examples
    --------
    Makris's duct at 1 in/s piston speed and 3 kV/mm (thin gap: 7.674 MPa, plug fraction 0.032):

    >>> Ap = 3.141592653589793 / 4 * (0.0334**2 - 0.01125**2)
    >>> r = annulus_bingham_flow(Q=0.0254 * Ap, tau_y=1800.0, eta=13.0, L=0.0546, d=0.0143, h=0.0008)
    >>> round(r.pressure_drop / 1e6, 3), round(r.plug_fraction, 3)
    (7.673, 0.032)

    References
    ----------
    Fredrickson and Bird (1958); Makris et al. (1996), eq 7 (thin-gap limit, printed with h^2 for h^3).
    """
    check_flow_args(annulus=True, Q=Q, tau_y=tau_y, eta=eta, L=L, d=d, h=h)
    Q, tau_y, eta, L, d, h = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (Q, tau_y, eta, L, d, h)))
    eps = h / d
    Q_abs = np.abs(Q)
    dp_y = 2.0 * tau_y * L / h
    # as in bingham_slit_flow: a yield stress below 1e-12 of the viscous pressure drop (a denormal one, say) leaves a
    # flow ratio that overflows; there the Newtonian annulus plus 3/2 dp_y is exact to 1e-12
    plastic = dp_y > 1e-12 * (12.0 * eta * L * Q_abs / (np.pi * d * h**3))
    moving = Q_abs > 0.0
    solve = plastic & moving
    phi = np.where(plastic, 1.0, 0.0)  # blocked gap (Q = 0) or Newtonian, overwritten where a root is needed
    t1 = np.zeros_like(phi)  # plug offset / h: 0 for a blocked gap
    shape = np.ones_like(phi)  # S, needed for the Newtonian fluid only
    if np.any(solve):
        ratio = 6.0 * eta[solve] * Q_abs[solve] / (np.pi * d[solve] * h[solve] ** 2 * tau_y[solve])
        phi[solve], t1[solve] = _compiled().annulus_plug_fraction(ratio, eps[solve], np.empty((2, ratio.size)))
    if not np.all(plastic):
        shape[~plastic], t1[~plastic] = _shape_and_offset(0.0, eps[~plastic])
    with np.errstate(divide="ignore", invalid="ignore"):
        dp_newtonian = 12.0 * eta * L * Q_abs / (np.pi * d * h**3 * shape)
        dp_abs = np.where(plastic, dp_y / phi, dp_newtonian + 1.5 * dp_y)
    dp = np.copysign(dp_abs, Q)
    R1 = 0.5 * (d - h)
    r_a = R1 + t1 * h
    r_b = r_a + np.where(phi < 1.0, phi, 1.0) * h
    out = AnnulusBinghamFlow(dp, phi, r_a, r_b)
    if dp.ndim == 0:
        return AnnulusBinghamFlow(*(float(v) for v in out))
    return out


def annulus_bingham_pressure_drop(Q, tau_y, eta, L, d, h):
    """Pressure drop of Bingham flow through a concentric annulus for a flow rate (exact), [Pa].

    The ``pressure_drop`` of :func:`annulus_bingham_flow`; see there for the equation, parameters and notes.
    Same signature as :func:`erdesign.flow.bingham.bingham_pressure_drop`.

    Examples
    --------
    >>> round(annulus_bingham_pressure_drop(1e-6, 0.0, 7.0, 0.0546, 0.0143, 0.0008) / 1e3, 2)  # kPa, Newtonian
    199.35
    """
    return annulus_bingham_flow(Q, tau_y, eta, L, d, h).pressure_drop


def annulus_bingham_plug_fraction(Q, tau_y, eta, L, d, h):
    """Plug thickness over gap of Bingham flow through a concentric annulus for a flow rate (exact), [-].

    The ``plug_fraction`` of :func:`annulus_bingham_flow`; see there.
    """
    return annulus_bingham_flow(Q, tau_y, eta, L, d, h).plug_fraction


def annulus_bingham_velocity(r, dp, tau_y, eta, L, d, h):
    r"""Axial velocity profile of Bingham flow through a concentric annulus for a pressure drop (exact).

    .. math::
        u(r) = \frac{G}{2\eta}\begin{cases}
          \tfrac12\big[t_1^2 - (r_a - r)^2\big] + r_b R_1 P(x) + r_b (r_a - r)\ln(1 + x),
             & R_1 \le r \le r_a,\ x = \frac{r - R_1}{R_1} \\
          2\eta u_p / G, & r_a \le r \le r_b \\
          \tfrac12\big[t_2^2 - (r - r_b)^2\big] + r_a r Q(y) + r_a (r - r_b)\ln(1 + y),
             & r_b \le r \le R_2,\ y = \frac{R_2 - r}{r}
        \end{cases}

    with :math:`G = |\Delta p|/L` and the plug edges :math:`r_a, r_b` of the module notes.

    Parameters
    ----------
    r : float or array
        Radius, [m], in :math:`[(d - h)/2, (d + h)/2]`.
    dp, tau_y, eta, L, d, h : float or array
        As in :func:`annulus_bingham_flow_rate`: pressure drop [Pa], yield stress [Pa], plastic viscosity [Pa s],
        length, mean diameter and gap [m].

    Returns
    -------
    float or array
        Velocity, [m/s], with the sign of ``dp``; zero everywhere when :math:`|\Delta p| \le 2\tau_y L/h`.

    Notes
    -----
    The logarithmic terms are arranged so that every term is non-negative (no cancellation as h/d -> 0).

    Examples
    --------
    Makris's duct at 3 kV/mm and 8 MPa: walls at r = 6.75 and 7.55 mm, plug from 7.134 to 7.158 mm.

    >>> u = annulus_bingham_velocity([0.00675, 0.0071, 0.00715, 0.00755], 8e6, 1800.0, 13.0, 0.0546, 0.0143, 0.0008)
    >>> [round(float(v), 3) + 0.0 for v in u]
    [0.0, 0.841, 0.847, 0.0]

    References
    ----------
    Fredrickson and Bird (1958); Bird, Stewart and Lightfoot (2002), problem 2B.7.
    """
    check_flow_args(annulus=True, r=r, dp=dp, tau_y=tau_y, eta=eta, L=L, d=d, h=h)
    r, dp, tau_y, eta, L, d, h = np.broadcast_arrays(
        *(np.asarray(a, dtype=float) for a in (r, dp, tau_y, eta, L, d, h))
    )
    G = np.abs(dp) / L
    dp_y = 2.0 * tau_y * L / h
    with np.errstate(divide="ignore", invalid="ignore"):
        phi = np.where(np.abs(dp) > dp_y, dp_y / np.abs(dp), 1.0)
    eps = h / d
    shape, (rho, phi_, eps) = _flat(r / h, phi, h / d)
    u_hat = _compiled().annulus_velocity(rho, phi_, eps, np.empty(rho.size)).reshape(shape)
    u = np.sign(dp) * np.where(phi < 1.0, 0.5 * G * h**2 / eta * u_hat, 0.0)
    return u if u.ndim else float(u)


def thin_gap_error_bingham(h_over_d, bingham_number):
    r"""Relative error of the thin-gap (slit) Bingham pressure drop against the exact annulus, at the same flow rate.

    .. math::
        \varepsilon = \frac{\Delta p_\text{slit}}{\Delta p_\text{annulus}} - 1
                    = \frac{\phi_\text{annulus}}{\phi_\text{slit}} - 1 ,
        \qquad \mathrm{Bi} = \frac{\tau_y h}{\eta \bar u}, \quad \bar u = \frac{Q}{\pi d h}

    Parameters
    ----------
    h_over_d : float or array
        Gap over mean diameter, [-], in (0, 1).
    bingham_number : float or array
        Bingham number of the mean velocity, [-], >= 0 (``numpy.inf``: blocked gap).

    Returns
    -------
    float or array
        Relative error [-]; positive: the thin-gap form over-predicts the pressure drop.  It equals
        :func:`erdesign.flow.newtonian.thin_gap_error` (about :math:`(h/d)^2/15`) at Bi = 0 and tends to 0 as
        Bi -> infinity, because both forms share the blocking pressure drop :math:`2\tau_y L/h`.

    Notes
    -----
    Because the plug thickness is :math:`\Delta p_y/\Delta p` in both geometries, the ratio of pressure drops is
    the ratio of plug fractions.  docs/theory/thin_gap.md tabulates this function.

    Examples
    --------
    >>> f"{thin_gap_error_bingham(0.5, 0.0):.4f}, {thin_gap_error_bingham(0.5, 10.0):.4f}"
    '0.0193, 0.0124'

    References
    ----------
    Fredrickson and Bird (1958) for the exact annulus; Makris et al. (1996), eqs 5-7 for the thin gap.
    """
    check_flow_args(h_over_d=h_over_d, bingham_number=bingham_number)
    eps, bi = np.broadcast_arrays(np.asarray(h_over_d, dtype=float), np.asarray(bingham_number, dtype=float))
    # Unit mean velocity, viscosity, length and diameter; tau_y from Bi (infinite Bi is a blocked gap: Q = 0).
    blocked = np.isinf(bi)
    Q = np.where(blocked, 0.0, np.pi * eps)
    tau_y = np.where(blocked, 1.0, bi) / eps
    slit = bingham_slit_flow(Q, tau_y, 1.0, 1.0, 1.0, eps).pressure_drop
    exact = annulus_bingham_flow(Q, tau_y, 1.0, 1.0, 1.0, eps).pressure_drop
    err = np.asarray(slit / exact - 1.0)
    return err if err.ndim else float(err)
