r"""Bingham plastic in a thin gap with one moving wall: mixed-mode (moving-electrode) dampers (SI kernels).

In Kamath and Wereley's mixed-mode damper the piston head (diameter ``Dp``, length ``L``) is the inner electrode.
When it moves at velocity ``v`` it drags the fluid in the gap forward (shear mode) while the fluid it displaces is
pushed back through the same gap (flow mode).  Unrolled, the annular gap is a slit of height ``h`` and width
:math:`b = \pi d`, with ``d = Dp + h`` the mean diameter: a plane Couette-Poiseuille flow of a Bingham plastic.

Coordinates: ``y`` runs across the gap from the moving wall (``y = 0``, velocity ``U``) to the fixed wall
(``y = h``); ``x`` along it.  With :math:`g = \mathrm{d}p/\mathrm{d}x` (uniform), momentum and the Bingham law give

.. math::
    \tau(y) = \tau_0 + g y, \qquad
    \frac{\mathrm{d}u}{\mathrm{d}y} = \frac{D(\tau)}{\eta}, \qquad
    D(\tau) = \operatorname{sgn}(\tau)\max(|\tau| - \tau_y, 0),

and the two conditions that fix the unknowns :math:`\tau_0` (stress at the moving wall) and :math:`g`:

.. math::
    -\eta U = \int_0^h D(\tau_0 + g y)\,\mathrm{d}y \quad \text{(no slip at } y = h),
    \qquad
    \eta q = -\int_0^h y\,D(\tau_0 + g y)\,\mathrm{d}y \quad \text{(flow per unit width)}.

The second form follows from :math:`q = \int_0^h u\,\mathrm{d}y` by parts with :math:`u(h) = 0`; it equals the
:math:`P`/:math:`R` form of the design brief (eqs (1)-(2) in docs/theory/mixed_mode.md) but stays accurate as
:math:`g \to 0`, where that form divides small differences by :math:`g^2`.

Solution method (one compiled loop over the elements, :mod:`erdesign.flow._compiled`):

1. Scale stresses by :math:`\tau_s = \tau_y + \eta|U|/h + \eta|q|/h^2`, so that
   :math:`\varepsilon = \tau_y/\tau_s`, :math:`\bar U = \eta U/(\tau_s h)` and :math:`\bar q = \eta q/(\tau_s h^2)`
   satisfy :math:`\varepsilon + |\bar U| + |\bar q| = 1`: every number is O(1) from the Newtonian fluid
   (:math:`\varepsilon = 0`) to the blocked gap (:math:`\varepsilon = 1`).  This is the brief's scaling by
   :math:`\tau_y` with :math:`\tau_y` replaced by :math:`\tau_s`, which also covers :math:`\tau_y = 0`.
2. For a given gradient :math:`G = g h/\tau_s` the no-slip condition is a monotone piecewise-quadratic equation in
   :math:`t_0 = \tau_0/\tau_s`, solved in closed form zone by zone (both wall stresses beyond the yield band on
   the same side, one wall inside the band, the band straddled).  The wall stresses are kept as their offsets
   from the band edges :math:`\pm\varepsilon`, each from its own closed form, so that thin sheared layers (near
   the blocked gap, near regime boundaries) keep full relative precision.
3. The flow :math:`\bar q(G)` is then non-increasing in :math:`G`; its root is found element by element by
   Chandrupatla's method (the algorithm and tolerances of :func:`scipy.optimize.elementwise.find_root`, compiled)
   from the bracket :math:`G_N \pm (3\varepsilon + 10^{-3})` around the Newtonian value
   :math:`G_N = 12(\bar U/2 - \bar q)` (:math:`|G - G_N| \le 3\varepsilon` held on 4e5 random cases, with
   equality approached in valve mode; the bracket is widened should it ever miss).

Symmetry: :math:`(U, q) \to (-U, -q)` maps the solution to :math:`(g, \tau) \to (-g, -\tau)`; the code reduces
every case to :math:`G \ge 0` with it.

All kernels take SI floats or numpy arrays that broadcast against each other.
"""

from __future__ import annotations

from enum import IntEnum
from typing import NamedTuple

import numpy as np

from ..errors import ErdesignError
from ._checks import check_flow_args
from .areas import piston_area

__all__ = [
    "GapFlowRegime",
    "CouettePoiseuilleBingham",
    "couette_poiseuille_bingham",
    "couette_poiseuille_bingham_velocity",
    "MixedModeDamperForce",
    "mixed_mode_damper_force",
    "mixed_mode_yield_force",
]


class GapFlowRegime(IntEnum):
    """Where the rigid plug (:math:`|\\tau| \\le \\tau_y`) sits in the gap; the ``regime`` codes of the kernels.

    ``GapFlowRegime(code).name`` turns a code back into its name.
    """

    FULLY_YIELDED = 0
    """No plug of finite thickness: the whole gap is sheared (always so for tau_y = 0)."""
    FLOATING_PLUG = 1
    """The plug lies strictly inside the gap, sheared layers on both sides."""
    PLUG_AT_MOVING_WALL = 2
    """The plug touches the moving wall and moves with it at ``U``."""
    PLUG_AT_FIXED_WALL = 3
    """The plug touches the fixed wall and is at rest."""
    BLOCKED = 4
    """The plug fills the gap: no flow (only for U = 0, q = 0 and tau_y > 0)."""


class CouettePoiseuilleBingham(NamedTuple):
    """Result of :func:`couette_poiseuille_bingham`."""

    pressure_gradient: float | np.ndarray
    """g = dp/dx along the gap, [Pa/m]; positive when pressure rises in the direction of ``U``."""
    wall_stress_moving: float | np.ndarray
    """Shear stress tau(0) at the moving wall, [Pa]; the fluid pulls that wall with tau(0) per unit area."""
    wall_stress_fixed: float | np.ndarray
    """Shear stress tau(h) at the fixed wall, [Pa]."""
    plug_y1: float | np.ndarray
    """Edge of the plug nearer the moving wall, [m], clipped to [0, h]."""
    plug_y2: float | np.ndarray
    """Edge of the plug nearer the fixed wall, [m], clipped to [0, h]; equal to ``plug_y1`` when there is no plug."""
    plug_fraction: float | np.ndarray
    """Plug thickness over gap, (y2 - y1)/h, [-]."""
    regime: int | np.ndarray
    """Plug position, a :class:`GapFlowRegime` code (-1 where an input is not finite)."""


class MixedModeDamperForce(NamedTuple):
    """Result of :func:`mixed_mode_damper_force`."""

    force: float | np.ndarray
    """Force the actuator applies to the piston rod, with the sign of ``v``, [N]."""
    pressure_drop: float | np.ndarray
    """Pressure ahead of the piston head minus pressure behind it, with the sign of ``v``, [Pa]."""
    pressure_force: float | np.ndarray
    """Pressure-drag part of the force, pressure_drop * Ap, [N]."""
    shear_force: float | np.ndarray
    """Shear-drag part of the force, -tau(0) * A_s, [N]."""
    flow_rate: float | np.ndarray
    """Volumetric flow through the gap in the cylinder frame, -v * Ap, [m^3/s]."""
    plug_fraction: float | np.ndarray
    """Plug thickness over gap, [-]."""


def _compiled():
    """The numba loops (:mod:`erdesign.flow._compiled`), imported on first use: numba costs about a second of
    start-up, which commands that solve no mixed-mode gap should not pay."""
    from . import _compiled as compiled

    return compiled


# ----------------------------------------------------------------------------------------------------------------
# Dimensionless core (the closed forms of the solve are in erdesign.flow._compiled).  Stresses in units of tau_s,
# lengths in units of h; eps = tau_y / tau_s is the half-width of the yield band.  Every case is first oriented so
# that G >= 0 (odd symmetry t -> -t, G -> -G, U -> -U, q -> -q) and its wall stresses t0 (moving wall) and
# t1 = t0 + G (fixed wall) are carried as their four offsets from the band edges, lo0 = t0 + eps, hi0 = t0 - eps,
# lo1 = t1 + eps, hi1 = t1 - eps, each computed directly by its own closed form.  A thin sheared layer is measured
# by one of these offsets; forming it as a difference of O(1) numbers would lose it near the blocked gap and near
# the regime boundaries.
# ----------------------------------------------------------------------------------------------------------------


def _velocity_pos(Y, G, lo0, hi0, lo1, hi1):
    """u_bar(Y) = -int_Y^1 D(t0 + G s) ds for G >= 0 (integrated from the fixed wall, where u = 0)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        rest = 1.0 - Y
        w = hi1 / G
        d = np.minimum(rest, w)
        above = np.where(
            hi0 >= 0.0, rest * (hi0 + G * (1.0 + Y) / 2.0), np.where(hi1 > 0.0, G * d * (2.0 * w - d) / 2.0, 0.0)
        )
        e = np.maximum(-lo0 / G - Y, 0.0)  # distance from Y up to the lower edge of the band
        below = np.where(lo1 <= 0.0, rest * (lo1 - G * rest / 2.0), np.where(lo0 < 0.0, -G * e**2 / 2.0, 0.0))
    return -(above + below)


def _check_positive(**values):
    for name, value in values.items():
        if np.any(np.asarray(value) <= 0.0):
            raise ErdesignError(f"{name}: must be positive, got {value!r}")


def _flat_inputs(U, q, tau_y, eta, h):
    """Checked inputs broadcast to one shape: (shape, five contiguous 1-D float arrays) for the compiled loops."""
    check_flow_args(U=U, q=q, tau_y=tau_y, eta=eta, h=h)
    U, q, tau_y, eta, h = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (U, q, tau_y, eta, h)))
    return U.shape, [np.array(a, order="C").ravel() for a in (U, q, tau_y, eta, h)]  # copies, not broadcast views


def _out(x):
    return x if np.ndim(x) else x.item()


def couette_poiseuille_bingham(U, q, tau_y, eta, h):
    r"""Pressure gradient, wall stresses and plug of Bingham flow in a slit with one moving wall.

    Solves, for the pressure gradient :math:`g` and the moving-wall stress :math:`\tau_0`,

    .. math::
        \int_0^h D(\tau_0 + g y)\,\mathrm{d}y = -\eta U, \qquad
        -\int_0^h y\,D(\tau_0 + g y)\,\mathrm{d}y = \eta q, \qquad
        D(\tau) = \operatorname{sgn}(\tau)\max(|\tau| - \tau_y, 0),

    the no-slip and flow-rate conditions of plane Couette-Poiseuille flow of a Bingham plastic (module notes).

    Parameters
    ----------
    U : float or array
        Velocity of the moving wall (``y = 0``) along ``x``, [m/s]; the wall at ``y = h`` is at rest.
    q : float or array
        Flow rate per unit width along ``x``, in the frame of the fixed wall, [m^2/s].
    tau_y : float or array
        Yield stress, [Pa], >= 0; zero gives Newtonian Couette-Poiseuille flow.
    eta : float or array
        Plastic viscosity, [Pa s], > 0.
    h : float or array
        Gap, [m], > 0.

    Returns
    -------
    CouettePoiseuilleBingham
        ``pressure_gradient`` g [Pa/m], ``wall_stress_moving`` tau(0) [Pa], ``wall_stress_fixed`` tau(h) [Pa],
        ``plug_y1``, ``plug_y2`` [m], ``plug_fraction`` [-] and ``regime`` (a :class:`GapFlowRegime` code: 0 fully
        yielded, 1 floating plug, 2 plug at the moving wall, 3 plug at the fixed wall, 4 blocked; -1 where an
        input is not finite, with NaN in the other fields).

    Notes
    -----
    Steady, laminar, fully developed flow between parallel plates (the thin-gap limit of an annulus, error
    O(h/d)); no wall slip; fluid inertia and entrance lengths neglected.  Newtonian limit (``tau_y = 0``, exact):

    .. math:: g = \frac{12\eta}{h^3}\left(\frac{U h}{2} - q\right), \qquad \tau_0 = -\frac{\eta U}{h} - \frac{g h}{2}.

    Regime map for ``U > 0`` and ``tau_y > 0`` (docs/theory/mixed_mode.md, section 4): floating plug for
    :math:`q < q^*`, plug at the fixed wall up to :math:`q = Uh/3`, fully yielded for :math:`Uh/3 < q < 2Uh/3`,
    plug at the moving wall up to :math:`q = Uh - q^*`, floating beyond; :math:`q^* = U h Y_1/3` with
    :math:`Y_1^2/(1 - Y_1) = \eta U/(\tau_y h)`.  ``(U, q) -> (-U, -q)`` reverses all signs.

    With ``U = 0`` this is the valve-mode slit of :func:`erdesign.flow.bingham.bingham_slit_flow` with
    :math:`g = -\Delta p/L`.  At ``U = q = 0`` (blocked gap) any :math:`|g| \le 2\tau_y/h` is in equilibrium; the
    break-away value :math:`g = -\operatorname{sgn}(q)\,2\tau_y/h` is returned, the sign taken from the sign bit
    of ``q`` (``-0.0`` gives :math:`+2\tau_y/h`), with a centred plug (:math:`\tau_0 = -g h/2`).  Without a plug
    ``plug_y1 = plug_y2`` is the wall nearer to the yield band.  The pressure gradient is a bracketed root
    (secant steps from the valve-mode slit root, Chandrupatla's method as the fallback, compiled) converged to
    round-off of :math:`g h/\tau_s`, with
    :math:`\tau_s = \tau_y + \eta|U|/h + \eta|q|/h^2`; it is ill-conditioned only where the flow hardly depends
    on it, e.g. for :math:`\eta|U|/(\tau_y h) < 10^{-30}` with :math:`q \approx U h`.  Non-finite inputs give NaN.

    Examples
    --------
    A wall moving forward against a back-flow (the mixed-mode damper): the plug floats in the gap.

    >>> r = couette_poiseuille_bingham(U=0.05, q=-1e-3, tau_y=2000.0, eta=0.1, h=1e-3)
    >>> round(r.pressure_gradient / 1e6, 3), round(r.wall_stress_moving), GapFlowRegime(r.regime).name
    (6.464, -3245, 'FLOATING_PLUG')

    References
    ----------
    Kamath and Wereley, nonlinear viscoelastic-plastic mechanisms-based model of an ER damper, section II (the
    mixed-mode moving-electrode damper and its quasi-steady Bingham design, their Ref. 11); derivation in
    docs/theory/mixed_mode.md.
    """
    shape, flat = _flat_inputs(U, q, tau_y, eta, h)
    out = _compiled().couette_poiseuille(*flat, np.empty((7, flat[0].size))).reshape((7,) + shape)
    return CouettePoiseuilleBingham(
        pressure_gradient=_out(out[0]),
        wall_stress_moving=_out(out[1]),
        wall_stress_fixed=_out(out[2]),
        plug_y1=_out(out[3]),
        plug_y2=_out(out[4]),
        plug_fraction=_out(out[5]),
        regime=_out(out[6].astype(int)),
    )


def couette_poiseuille_bingham_velocity(y, U, q, tau_y, eta, h):
    r"""Velocity profile across the gap of Bingham Couette-Poiseuille flow, [m/s].

    .. math:: u(y) = U + \frac{1}{\eta}\int_0^y D(\tau_0 + g s)\,\mathrm{d}s

    with :math:`g` and :math:`\tau_0` from :func:`couette_poiseuille_bingham`, integrated piece by piece (exact).

    Parameters
    ----------
    y : float or array
        Distance from the moving wall, [m], in [0, h].  Use ``y[:, None]`` for profiles of several cases.
    U, q, tau_y, eta, h
        As in :func:`couette_poiseuille_bingham`.

    Returns
    -------
    float or array
        Velocity along ``x`` in the frame of the fixed wall, [m/s]; ``U`` at ``y = 0``, 0 at ``y = h``.

    Examples
    --------
    >>> y = [0.0, 1e-4, 5e-4, 9e-4]                    # plug from y = 0.19 mm to 0.81 mm
    >>> u = couette_poiseuille_bingham_velocity(y, U=0.05, q=-1e-3, tau_y=2000.0, eta=0.1, h=1e-3)
    >>> [round(float(x), 4) for x in u]
    [0.05, -0.8719, -1.1492, -0.8957]

    References
    ----------
    As :func:`couette_poiseuille_bingham`.
    """
    check_flow_args(y=y, U=U, q=q, h=h)  # y against the others (their own checks follow)
    shape, flat = _flat_inputs(U, q, tau_y, eta, h)
    scale, G, sign, *offsets = _compiled().mixed_gap_state(*flat, np.empty((7, flat[0].size))).reshape((7,) + shape)
    Y = np.asarray(y, dtype=float) / np.asarray(h, dtype=float)
    u_bar = sign * _velocity_pos(Y, sign * G, *offsets)
    return _out(u_bar * scale * np.asarray(h, dtype=float) / np.asarray(eta, dtype=float))


def mixed_mode_damper_force(v, tau_y, eta, L, Dp, dr, h):
    r"""Quasi-steady force of a mixed-mode (moving-electrode) Bingham damper: pressure drag plus shear drag.

    .. math::
        F = \Delta p\,A_p - \tau_0\,A_s, \qquad \Delta p = g L, \qquad
        A_p = \frac{\pi}{4}(D_p^2 - d_r^2), \qquad A_s = \pi D_p L,

    with :math:`g, \tau_0` from :func:`couette_poiseuille_bingham` at :math:`U = v`, :math:`q = -v A_p/(\pi d)`,
    :math:`d = D_p + h`.

    Parameters
    ----------
    v : float or array
        Piston velocity relative to the cylinder, [m/s].
    tau_y : float or array
        Yield stress, [Pa], >= 0.
    eta : float or array
        Plastic viscosity, [Pa s], > 0.
    L : float or array
        Length of the piston head (electrode), [m].
    Dp : float or array
        Piston-head diameter, [m].
    dr : float or array
        Rod diameter (rod on both sides), [m], < Dp.
    h : float or array
        Radial gap between head and cylinder, [m].

    Returns
    -------
    MixedModeDamperForce
        ``force`` [N] (applied by the actuator, sign of ``v``), ``pressure_drop`` [Pa], ``pressure_force`` [N],
        ``shear_force`` [N], ``flow_rate`` [m^3/s] and ``plug_fraction`` [-].

    Notes
    -----
    The displaced volume :math:`v A_p` returns through the gap, :math:`Q = -v A_p` exactly (the gap annulus
    moves with the head).  The flow width uses the mean diameter (:math:`b = \pi d`, which makes
    :math:`b h` the exact annulus area) while the shear acts on the real electrode surface
    :math:`A_s = \pi D_p L`; the two differ at O(h/d), the accuracy of the thin-gap model.  In this damper the
    plug always floats, and as :math:`v \to 0^+`, :math:`g h/\tau_y \to 2` and :math:`\tau_0 \to -\tau_y`, so the
    force tends to :func:`mixed_mode_yield_force` (proof in docs/theory/mixed_mode.md).  At ``v = 0`` the
    break-away force with the sign bit of ``v`` is returned.  Quasi-steady: no fluid inertia, compressibility,
    pre-yield elasticity or seal friction (Kamath and Wereley's measured loops include all of these).

    Examples
    --------
    >>> r = mixed_mode_damper_force(v=0.05, tau_y=2000.0, eta=0.1, L=0.02, Dp=0.03, dr=0.01, h=1e-3)
    >>> round(r.force, 1), round(r.pressure_force, 1), round(r.shear_force, 2), round(r.plug_fraction, 3)
    (71.1, 66.1, 5.0, 0.76)

    References
    ----------
    Kamath and Wereley, section II: "the resisting force of the damper is then a sum of the viscous drag due to
    the relative motion between the electrodes and the pressure drag force"; derivation in
    docs/theory/mixed_mode.md.
    """
    check_flow_args(v=v, tau_y=tau_y, eta=eta, L=L, Dp=Dp, dr=dr, h=h)
    Ap = piston_area(Dp, dr)
    _check_positive(Ap=Ap)
    b = np.pi * (Dp + h)
    sol = couette_poiseuille_bingham(v, -v * Ap / b, tau_y, eta, h)
    dp = sol.pressure_gradient * L
    pressure_force = dp * Ap
    shear_force = -sol.wall_stress_moving * np.pi * Dp * L
    return MixedModeDamperForce(
        force=_out(np.asarray(pressure_force + shear_force)),
        pressure_drop=_out(np.asarray(dp)),
        pressure_force=_out(np.asarray(pressure_force)),
        shear_force=_out(np.asarray(shear_force)),
        flow_rate=_out(np.asarray(-v * Ap, dtype=float) + np.zeros_like(dp)),
        plug_fraction=sol.plug_fraction,
    )


def mixed_mode_yield_force(tau_y, L, Dp, dr, h):
    r"""Yield (break-away) force of a mixed-mode damper: the force as the piston velocity tends to zero.

    .. math:: F_y = \tau_y\left(\frac{2 L A_p}{h} + A_s\right), \qquad A_p = \frac{\pi}{4}(D_p^2 - d_r^2),
              \quad A_s = \pi D_p L

    Parameters
    ----------
    tau_y : float or array
        Yield stress, [Pa].
    L : float or array
        Length of the piston head, [m].
    Dp : float or array
        Piston-head diameter, [m].
    dr : float or array
        Rod diameter, [m].
    h : float or array
        Gap, [m].

    Returns
    -------
    float or array
        Yield force, [N]: the valve-mode blocking pressure :math:`2\tau_y L/h` on :math:`A_p` plus the yield
        stress on the electrode surface.

    Notes
    -----
    The limit :math:`v \to 0^+` of :func:`mixed_mode_damper_force`: the plug fills the gap, the stress is
    :math:`-\tau_y` at the piston and :math:`+\tau_y` at the cylinder (docs/theory/mixed_mode.md).  The pressure
    term dominates by :math:`2 A_p/(h A_s) \approx D_p/(2h)` for a thin rod.

    Examples
    --------
    >>> round(mixed_mode_yield_force(tau_y=2000.0, L=0.02, Dp=0.03, dr=0.01, h=1e-3), 2)
    54.04

    References
    ----------
    Kamath and Wereley, section II (pressure drag plus shear drag); their Fig. 4 reads an idealised yield force
    from the measured force-velocity loops (about 50 N at 3 kV/mm, seal friction included).
    """
    check_flow_args(tau_y=tau_y, L=L, Dp=Dp, dr=dr, h=h)
    return tau_y * (2.0 * L * piston_area(Dp, dr) / h + np.pi * Dp * L)
