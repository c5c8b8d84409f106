r"""Steady flow of a Bingham plastic through a thin annular gap with stationary walls (SI kernels).

The valve (flow) mode of Makris's damper: fluid pushed through a stationary annular duct of mean diameter ``d``,
gap ``h`` and length ``L``.  In the thin-gap limit the duct is a slit of width :math:`\pi d`.  The shear stress is
linear across the gap (Makris eq 2); where it is below the yield stress :math:`\tau_y` the fluid moves as a rigid
plug, of thickness :math:`\delta = 2\tau_y L/\Delta p`; the layers beside the walls are sheared (Makris eq 5).

With the plug fraction :math:`\phi = \delta/h = \Delta p_y/\Delta p` and the blocking (yield) pressure drop
:math:`\Delta p_y = 2\tau_y L/h`, the flow rate is the Buckingham-Reiner form for a slit

.. math::
    Q = \frac{\pi d h^3 \Delta p}{12 \eta L}\left(1 - \frac{3}{2}\phi + \frac{1}{2}\phi^3\right),
    \qquad |\Delta p| > \Delta p_y ,

which is Makris eq 6 written for Q.  Makris prints eq 6 and eq 7 with :math:`h^2` in the viscous term; dimensional
consistency needs :math:`h^3` (the :math:`\tau_y \to 0` limit must be his eq 4, which has :math:`h^3`).  The
corrected cubic in :math:`\Delta p` is

.. math::
    \Delta p^3 - \left(3\tau_y\frac{L}{h} + \frac{12\eta L Q}{\pi d h^3}\right)\Delta p^2
    + 4\tau_y^3\left(\frac{L}{h}\right)^3 = 0 .

Dividing by :math:`\Delta p^3` turns it into a depressed cubic in the plug fraction,
:math:`\phi^3 - (3 + 2N)\phi + 2 = 0` with :math:`N = \Delta p_N/\Delta p_y = 6/\mathrm{Bi}`
(:math:`\Delta p_N` the Newtonian pressure drop of eq 4, Bi the Bingham number), whose physical root
(:math:`0 < \phi \le 1`) has the closed form

.. math::
    \phi = 2m\,\sin\!\left(\tfrac{1}{3}\arcsin m^{-3}\right), \qquad m = \sqrt{1 + 2N/3}.

This trigonometric root is exact and branch-free, so :func:`bingham_pressure_drop` needs no ``np.roots``.  It
gives phi to rounding from the blocked gap to the Newtonian limit (N -> infinity, phi -> 1/N), but not the thin
sheared layer :math:`1 - \phi \approx \sqrt{2N/3}` as the gap blocks (all its digits are lost below N ~ 1e-16, and
a round trip Q -> dp -> Q then returns Q = 0); below N = 0.5 the sheared fraction is therefore found by a few Newton
steps on the cubic written for it (:func:`_plug_and_sheared_fractions`), and :func:`bingham_flow_rate` takes it as
:math:`(\Delta p - \Delta p_y)/\Delta p`, so a round trip is limited by the conditioning alone.  tests/test_flow_bingham.py derives the cubic with sympy, checks it against ``np.roots`` element by
element and checks the printed h^2 form fails a pint dimension check.

All functions take SI floats or numpy arrays that broadcast against each other.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ._checks import check_flow_args

__all__ = [
    "yield_pressure_drop",
    "bingham_number",
    "bingham_flow_rate",
    "bingham_pressure_drop",
    "bingham_plug_fraction",
    "bingham_slit_flow",
    "BinghamSlitFlow",
]


#: Flow arrays of at least this many elements go through the compiled one-pass loop
#: (:func:`erdesign.flow._compiled.slit_flow`, the same arithmetic element by element, equal to a few ulp;
#: tests/test_flow_compiled.py); smaller ones through numpy, so that a command that evaluates a few velocities does
#: not pay numba's import (about a second).
COMPILED_MIN_SIZE = 4096


def yield_pressure_drop(tau_y, L, h):
    r"""Pressure drop at which a Bingham plastic starts to flow through a gap with stationary walls.

    .. math:: \Delta p_y = \frac{2\,\tau_y\,L}{h}

    Parameters
    ----------
    tau_y : float or array
        Yield stress, [Pa].
    L : float or array
        Duct length, [m].
    h : float or array
        Gap, [m].

    Returns
    -------
    float or array
        Yield (blocking) pressure drop, [Pa].  Below it the plug fills the gap and nothing flows.

    Examples
    --------
    >>> yield_pressure_drop(tau_y=1800.0, L=0.0546, h=0.0008)   # Makris duct at 3 kV/mm
    245700.0

    References
    ----------
    Makris et al., eq 2 with the stress reaching tau_y at both walls (r = h/2 from the centre plane).
    """
    check_flow_args(tau_y=tau_y, L=L, h=h)
    return 2.0 * tau_y * L / h


def bingham_number(Q, tau_y, eta, d, h):
    r"""Bingham number of slit flow: yield stress over the viscous stress scale of the mean velocity.

    .. math:: \mathrm{Bi} = \frac{\tau_y h}{\eta \bar u}, \qquad \bar u = \frac{|Q|}{\pi d h}

    Parameters
    ----------
    Q : float or array
        Flow rate, [m^3/s].
    tau_y : float or array
        Yield stress, [Pa].
    eta : float or array
        Plastic viscosity, [Pa s].
    d, h : float or array
        Mean diameter and gap, [m].

    Returns
    -------
    float or array
        Bi [-]; 0 for a Newtonian fluid, infinite for a blocked gap (Q = 0).  It relates to the ratio used in
        :func:`bingham_pressure_drop` by :math:`\Delta p_N / \Delta p_y = 6/\mathrm{Bi}`.
    """
    check_flow_args(Q=Q, tau_y=tau_y, eta=eta, d=d, h=h)
    with np.errstate(divide="ignore"):
        return tau_y * h * np.pi * d * h / (eta * np.abs(Q))


def bingham_flow_rate(dp, tau_y, eta, L, d, h):
    r"""Flow rate of a Bingham plastic through a thin annular gap for a given pressure drop (explicit).

    .. math::
        Q = \operatorname{sgn}(\Delta p)\,\frac{\pi d h^3 |\Delta p|}{12 \eta L}
            \left(1 - \tfrac{3}{2}\phi + \tfrac{1}{2}\phi^3\right), \quad \phi = \frac{\Delta p_y}{|\Delta p|},

    and :math:`Q = 0` for :math:`|\Delta p| \le \Delta p_y = 2\tau_y L/h` (the plug fills the gap).

    Parameters
    ----------
    dp : float or array
        Pressure drop along the duct, signed, [Pa].
    tau_y : float or array
        Yield stress, [Pa]; zero gives Hagen-Poiseuille flow (Makris eq 4).
    eta : float or array
        Plastic viscosity, [Pa s].
    L : float or array
        Duct length, [m].
    d : float or array
        Mean diameter of the annulus, [m].
    h : float or array
        Gap, [m].

    Returns
    -------
    float or array
        Flow rate, [m^3/s], with the sign of ``dp``.

    Notes
    -----
    Thin-gap (parallel-plate) approximation, laminar, steady, no wall slip.  The exact annulus differs by
    O((h/d)^2); see :mod:`erdesign.flow.newtonian` and docs/theory.md.

    References
    ----------
    Makris et al., eq 6 (printed with h^2; h^3 is dimensionally right).  Phillips (1969) for the derivation.
    """
    check_flow_args(dp=dp, tau_y=tau_y, eta=eta, L=L, d=d, h=h)
    dp_abs = np.abs(dp)
    dp_y = yield_pressure_drop(tau_y, L, h)
    with np.errstate(divide="ignore", invalid="ignore"):
        # the sheared fraction 1 - phi from the difference of the pressure drops (exact near yield), not 1 - phi
        eps = np.where(dp_abs > dp_y, (dp_abs - dp_y) / dp_abs, 0.0)
    shape = 0.5 * eps**2 * (3.0 - eps)  # = 1 - 3 phi/2 + phi^3/2 with phi = 1 - eps: accurate as phi -> 1
    return np.sign(dp) * np.pi * d * h**3 * dp_abs / (12.0 * eta * L) * shape


def _plug_and_sheared_fractions(N):
    r"""phi and 1 - phi for N = dp_newtonian/dp_yield >= 0, each without cancellation.

    phi is the physical root in (0, 1] of :math:`\phi^3 - (3 + 2N)\phi + 2 = 0`.  The trigonometric root gives phi to
    rounding, but the sheared fraction :math:`\epsilon = 1 - \phi` only to 1e-16/epsilon (every digit is lost
    below N ~ 1e-16, where the gap is nearly blocked and epsilon ~ 1e-8).  With :math:`\phi = 1 - \epsilon` the
    cubic reads :math:`g(\epsilon) = \epsilon^2 (3 - \epsilon) - 2N(1 - \epsilon) = 0`, so below N = 0.5
    epsilon is found by Newton's method on g from :math:`\sqrt{2N/3}` (relative error O(sqrt N) at the start; six
    quadratic steps reach rounding) and phi = 1 - epsilon; above, phi comes from the trigonometric root and
    epsilon = 1 - phi.  Both are then accurate to a few ulp over N = 1e-30 to 1e6 (tests/test_flow_bingham.py)."""
    N = np.asarray(N, dtype=float)
    m = np.sqrt(1.0 + (2.0 / 3.0) * N)
    phi = 2.0 * m * np.sin(np.arcsin(m**-3) / 3.0)
    eps = 1.0 - phi
    small = N < 0.5
    if np.any(small):
        phi, eps = np.array(phi, dtype=float), np.array(eps, dtype=float)  # writable copies (0-d for a scalar)
        Ns = N[small]
        e = np.sqrt(2.0 * Ns / 3.0)
        for _ in range(6):
            g = e * e * (3.0 - e) - 2.0 * Ns * (1.0 - e)
            slope = 6.0 * e - 3.0 * e * e + 2.0 * Ns
            e = e - np.divide(g, slope, out=np.zeros_like(e), where=slope > 0)
        # (at N = 0 this is the blocked gap exactly: epsilon = 0, phi = 1)
        eps[small], phi[small] = e, 1.0 - e
    return phi, eps


def _plug_fraction_of_ratio(N):
    """Physical root phi in (0, 1] of phi^3 - (3 + 2N) phi + 2 = 0, for N = dp_newtonian/dp_yield >= 0."""
    return _plug_and_sheared_fractions(N)[0]


class BinghamSlitFlow(NamedTuple):
    """Result of :func:`bingham_slit_flow`."""

    pressure_drop: float | np.ndarray
    """Pressure drop with the sign of the flow, [Pa]."""
    plug_fraction: float | np.ndarray
    """Plug thickness over gap, [-]: 0 Newtonian, 1 blocked gap."""


def bingham_slit_flow(Q, tau_y, eta, L, d, h):
    r"""Pressure drop and plug fraction of Bingham flow through a thin annular gap, for a given flow rate.

    Solves the corrected Makris cubic (eq 7 with h^3) in closed form, see the module notes:

    .. math::
        \Delta p = \frac{\Delta p_y}{\phi}, \quad \phi = 2m\sin\!\left(\tfrac13\arcsin m^{-3}\right),
        \quad m = \sqrt{1 + \tfrac{2}{3}\frac{\Delta p_N}{\Delta p_y}},
        \quad \Delta p_N = \frac{12\eta L |Q|}{\pi d h^3}, \quad \Delta p_y = \frac{2\tau_y L}{h}

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
        Gap, [m].

    Returns
    -------
    BinghamSlitFlow
        ``pressure_drop`` [Pa] with the sign of ``Q`` and ``plug_fraction`` [-].

    Notes
    -----
    At ``Q = 0`` the gap is blocked: any pressure drop up to :math:`\Delta p_y` is in equilibrium with no flow.
    The function returns the break-away value :math:`\Delta p_y` (the limit :math:`Q \to 0^+`; the sign is taken
    from the sign bit of ``Q``, so ``-0.0`` gives :math:`-\Delta p_y`) and a plug fraction of 1.
    For :math:`\tau_y = 0` it returns Makris eq 4 and a plug fraction of 0.
    From :data:`COMPILED_MIN_SIZE` elements on, the same arithmetic runs in one compiled pass over the arrays
    (numba): 1e7 flows take about the time of a plain numba loop instead of 4-5 times it (docs/performance.md).

    Examples
    --------
    Makris's duct at 1 in/s piston speed and 3 kV/mm (tau_y = 1.8 kPa, eta = 13 Pa s):

    >>> Ap = 3.141592653589793 / 4 * (0.0334**2 - 0.01125**2)
    >>> r = bingham_slit_flow(Q=0.0254 * Ap, tau_y=1800.0, eta=13.0, L=0.0546, d=0.0143, h=0.0008)
    >>> round(r.pressure_drop / 1e6, 3), round(r.plug_fraction, 3)
    (7.674, 0.032)

    References
    ----------
    Makris et al., eqs 5-7 (printed with h^2 where h^3 is dimensionally right).
    """
    return _slit_flow(Q, tau_y, eta, L, d, h, plug=True)


def _slit_flow(Q, tau_y, eta, L, d, h, plug):
    """:func:`bingham_slit_flow`; with ``plug=False`` the compiled loop skips writing the plug fraction (None),
    which :func:`bingham_pressure_drop` does not need."""
    check_flow_args(Q=Q, tau_y=tau_y, eta=eta, L=L, d=d, h=h)
    if np.broadcast(Q, tau_y, eta, L, d, h).size >= COMPILED_MIN_SIZE:
        # numba, imported here: small calls (one velocity) do not pay for it
        from . import _compiled

        if all(np.ndim(a) == 0 for a in (tau_y, eta, L, d, h)):  # many flows through one duct
            Q = np.asarray(Q, dtype=float)
            dp = np.empty(Q.shape)
            phi = np.empty(Q.shape if plug else 0)
            _compiled.slit_flow_one_duct(
                np.ascontiguousarray(Q).ravel(),
                *(float(a) for a in (tau_y, eta, L, d, h)),
                dp.reshape(-1),
                phi.reshape(-1),
            )
        else:
            dp, phi = _compiled.slit_flow(Q, tau_y, eta, L, d, h)
        return BinghamSlitFlow(dp, phi if plug else None)
    Q_abs = np.abs(Q)
    dp_y = yield_pressure_drop(tau_y, L, h)
    dp_n = 12.0 * eta * L * Q_abs / (np.pi * d * h**3)
    # a yield stress 1e-12 of the viscous pressure drop (or a denormal one, e.g. a field decaying through a lag)
    # leaves a plug fraction that underflows; there the large-ratio limit dp_n + 3/2 dp_y is exact to 1e-12
    plastic = dp_y > 1e-12 * dp_n
    with np.errstate(divide="ignore", invalid="ignore"):
        phi = _plug_fraction_of_ratio(dp_n / np.where(plastic, dp_y, 1.0))
        dp_abs = np.where(plastic, dp_y / phi, dp_n + 1.5 * dp_y)
    phi = np.where(plastic, phi, 0.0)
    dp = np.copysign(dp_abs, Q)
    if np.ndim(dp) == 0:
        return BinghamSlitFlow(float(dp), float(phi))
    return BinghamSlitFlow(dp, phi)


def bingham_pressure_drop(Q, tau_y, eta, L, d, h):
    """Pressure drop of Bingham flow through a thin annular gap for a flow rate, [Pa].

    The ``pressure_drop`` of :func:`bingham_slit_flow`; see there for the equation, parameters and notes.
    """
    return _slit_flow(Q, tau_y, eta, L, d, h, plug=False).pressure_drop


def bingham_plug_fraction(Q, tau_y, eta, L, d, h):
    """Plug thickness over gap of Bingham flow through a thin annular gap for a flow rate, [-].

    The ``plug_fraction`` of :func:`bingham_slit_flow`; see there.
    """
    return bingham_slit_flow(Q, tau_y, eta, L, d, h).plug_fraction
