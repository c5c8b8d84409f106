r"""The quasi-steady force of a damper: the one SI kernel, vectorised over velocity, fluid and geometry.

Quasi-steady means the gap flow is taken as steady at each instant (no fluid inertia, no compressibility, no
pre-yield elasticity).  :meth:`erdesign.damper.Damper.state`, the physics model
(:class:`erdesign.effects.chain.PhysicsDamper`), design synthesis (:mod:`erdesign.design.evaluate`), the app's sweeps
and the report all call :func:`quasi_steady_state` (or its two halves :func:`valve_state` and :func:`mixed_state`);
nothing else writes the force of a damper down.  Two pieces serve the physics model, which evaluates the gap at
every sample of a record many times over and sometimes sets the duct flow itself (a bypass): the gap law of the
valve alone, :func:`valve_pressure_drop`, and the mixed gap tabulated once per head, :class:`MixedGapTable`
(:func:`mixed_gap_table`; 1e-5 of :func:`mixed_state`).  (The series stage, which needs the gap's flow from the
pressure and the head's speed, uses the closed form of
:func:`erdesign.effects.compressibility.moving_wall_gap_flow`.)

Valve damper (Makris et al. 1996, eq 14), ``n`` stationary annular ducts in parallel:

.. math::
    F = \Delta p\,A_p + F_s \operatorname{sgn}(v), \qquad Q = \frac{v A_p}{n}, \qquad
    A_p = \frac{\pi}{4}(D_p^2 - d_r^2)

with :math:`\Delta p(Q, \tau_y, \eta)` the Bingham gap flow: the thin gap of :mod:`erdesign.flow.bingham`
(Makris eqs 5-7 with h^3), or the exact concentric annulus of :mod:`erdesign.flow.annulus_bingham`.

Mixed (moving-electrode) damper (Kamath and Wereley 1997, section II): pressure drag plus shear drag of the moving
head, :math:`F = \Delta p\,A_p + F_\text{shear} + F_s \operatorname{sgn}(v)`, from the Couette-Poiseuille Bingham
flow of :func:`erdesign.flow.mixed_mode.mixed_mode_damper_force`.

Reynolds number of the gap flow (Makris eq 1), with the mean speed of the fluid in the gap

.. math::
    \mathrm{Re} = \frac{\bar u h \rho}{\eta}, \qquad
    \bar u = \frac{|Q|}{\pi d h} \;\text{(valve)}, \qquad
    \bar u = \max\!\left(\frac{|v| A_p}{\pi d h}, |v|\right) \;\text{(mixed: the wall moves at } |v|\text{)}.

At ``v = 0`` the force is the break-away force (the limit ``v -> 0+``, signed by the sign bit of ``v``): the gap
is blocked and any force up to it is held with no motion.
"""

from __future__ import annotations

from functools import lru_cache
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from .._util import scalar_or_array
from ..flow.annulus_bingham import annulus_bingham_flow
from ..flow.areas import piston_area
from ..flow.bingham import bingham_slit_flow
from ..flow.mixed_mode import couette_poiseuille_bingham, mixed_mode_damper_force
from ..flow.newtonian import slit_pressure_drop

if TYPE_CHECKING:  # pragma: no cover
    from .damper import Damper

__all__ = [
    "QuasiSteadyState",
    "quasi_steady_state",
    "damping_constant",
    "valve_state",
    "valve_pressure_drop",
    "mixed_state",
    "MixedGapTable",
    "mixed_gap_table",
    "damper_state",
    "CRITICAL_REYNOLDS",
]

#: Reynolds number below which the duct flow is taken as laminar (Makris et al., section 2: R_crit = 2300).
CRITICAL_REYNOLDS = 2300.0


class QuasiSteadyState(NamedTuple):
    """Quasi-steady state of a damper at a piston velocity and control, SI (floats or arrays)."""

    force: Any
    """Total force on the piston, with the sign of the velocity, [N]."""
    pressure_drop: Any
    """Pressure drop across the piston, [Pa]."""
    pressure_force: Any
    """Pressure drop times piston area, [N]."""
    shear_force: Any
    """Shear drag of the moving electrode (mixed mode; 0 for valve), [N]."""
    friction_force: Any
    """Seal friction F_s sgn(v), [N]."""
    flow_rate: Any
    """Total volumetric flow displaced by the piston, v A_p, [m^3/s]."""
    flow_per_duct: Any
    """Flow through one duct (valve) or through the gap (mixed), [m^3/s]."""
    plug_fraction: Any
    """Plug thickness over gap, [-]: 0 fully yielded / Newtonian, 1 blocked."""
    reynolds: Any
    """Reynolds number of the gap flow (Makris eq 1), [-]."""
    yield_stress: Any
    """Yield stress at the control, [Pa]."""
    viscosity: Any
    """Plastic viscosity at the control, [Pa s]."""
    mean_velocity: Any = None
    """Mean speed of the fluid in the gap, u (mixed: at least the wall speed |v|), [m/s]."""


def _state(force, dp, pressure_force, shear_force, friction, Q_total, Q, phi, mean_velocity, h, rho, tau_y, eta):
    reynolds = mean_velocity * h * rho / eta  # Makris eq 1: Re = u h / nu = Q / (pi d nu)
    return QuasiSteadyState(
        *(
            scalar_or_array(a)
            for a in (
                force,
                dp,
                pressure_force,
                shear_force,
                friction,
                Q_total,
                Q,
                phi,
                reynolds,
                tau_y,
                eta,
                mean_velocity,
            )
        )
    )


def _valve_gap_flow(Q, tau_y, eta, L, d, h, exact_annulus):
    """(pressure drop [Pa], plug fraction [-]) of Bingham flow Q through one duct, thin gap or exact annulus."""
    annulus = np.asarray(exact_annulus, dtype=bool)
    if annulus.ndim == 0:
        if annulus:
            r = annulus_bingham_flow(Q, tau_y, eta, L, d, h)
            return r.pressure_drop, r.plug_fraction
        if not np.any(tau_y):
            # Newtonian (zero field): Makris eq 4, the tau_y = 0 branch of bingham_slit_flow bit for bit, without
            # the cubic's root (design synthesis evaluates every candidate at zero field)
            dp = slit_pressure_drop(Q, eta, L, d, h)
            return dp, np.zeros(np.shape(dp))
        return bingham_slit_flow(Q, tau_y, eta, L, d, h)
    Q, tau_y, eta, L, d, h, annulus = np.broadcast_arrays(Q, tau_y, eta, L, d, h, annulus)
    dp, phi = np.empty(Q.shape), np.empty(Q.shape)
    for where, exact in ((~annulus, False), (annulus, True)):
        if np.any(where):
            dp[where], phi[where] = _valve_gap_flow(
                Q[where], tau_y[where], eta[where], L[where], d[where], h[where], exact
            )
    return dp, phi


def valve_state(v, tau_y, eta, rho, seal_friction, h, L, d, Ap, n=1, exact_annulus=False) -> QuasiSteadyState:
    r"""Quasi-steady state of valve dampers: Bingham flow through ``n`` annular ducts in parallel (vectorised).

    .. math::
        Q = \frac{v A_p}{n}, \quad F = \Delta p(Q, \tau_y, \eta)\,A_p + F_s\operatorname{sgn}(v), \quad
        \mathrm{Re} = \frac{\bar u h \rho}{\eta}, \quad \bar u = \frac{|Q|}{\pi d h}

    Parameters
    ----------
    v : float or array
        Piston velocity, [m/s].
    tau_y : float or array
        Yield stress at the control, [Pa], >= 0.
    eta : float or array
        Plastic viscosity at the control, [Pa s], > 0.
    rho : float or array
        Density, [kg/m^3].
    seal_friction : float or array
        Seal friction F_s, [N], >= 0.
    h, L, d : float or array
        Gap, duct length and duct mean diameter, [m].
    Ap : float or array
        Piston area, [m^2].
    n : int or array
        Number of ducts in parallel, [-].
    exact_annulus : bool or array of bool
        True: the exact concentric annulus (:func:`erdesign.flow.annulus_bingham.annulus_bingham_flow`); False:
        the thin gap (:func:`erdesign.flow.bingham.bingham_slit_flow`).  An array chooses per element.

    Returns
    -------
    QuasiSteadyState
        Floats for scalar input, arrays of the broadcast shape otherwise; ``shear_force`` is 0.

    Notes
    -----
    Laminar, steady, no wall slip; every argument broadcasts against the others.  Where ``tau_y`` is zero
    everywhere the thin-gap pressure drop is Makris eq 4 (the Newtonian limit of the cubic, identical to it).

    Examples
    --------
    Makris's damper at 1 in/s and 3 kV/mm (tau_y = 1.8 kPa, eta = 13 Pa s; ``erdesign size`` gives 6.07 kN):

    >>> from math import pi
    >>> Ap = pi / 4 * (0.0334**2 - 0.01125**2)
    >>> s = valve_state(0.0254, 1800.0, 13.0, 1290.0, 112.0, 0.0008, 0.0546, 0.0143, Ap)
    >>> round(s.force / 1e3, 2), round(s.plug_fraction, 3), round(s.reynolds, 3)
    (6.07, 0.032, 0.044)

    References
    ----------
    Makris et al. (1996), eqs 1, 4-7 (with h^3) and 14; Fredrickson and Bird (1958) for the annulus.
    """
    v = np.asarray(v, dtype=float)
    Q_total = v * Ap
    Q = Q_total / n
    dp, phi = _valve_gap_flow(Q, tau_y, eta, L, d, h, exact_annulus)
    pressure_force = dp * Ap
    shear_force = np.zeros(np.broadcast(dp, v).shape)
    friction = np.copysign(seal_friction, v)
    mean_velocity = np.abs(Q) / (np.pi * d * h)
    return _state(
        pressure_force + shear_force + friction,
        dp,
        pressure_force,
        shear_force,
        friction,
        Q_total,
        Q,
        phi,
        mean_velocity,
        h,
        rho,
        tau_y,
        eta,
    )


def mixed_state(v, tau_y, eta, rho, seal_friction, h, L, d, Dp, dr) -> QuasiSteadyState:
    r"""Quasi-steady state of mixed-mode (moving-electrode) dampers: pressure plus shear drag (vectorised).

    .. math::
        F = \Delta p\,A_p + F_\text{shear} + F_s\operatorname{sgn}(v), \quad
        \mathrm{Re} = \frac{\bar u h \rho}{\eta}, \quad \bar u = \max\!\left(\frac{|v| A_p}{\pi d h}, |v|\right)

    with :math:`\Delta p, F_\text{shear}` from :func:`erdesign.flow.mixed_mode.mixed_mode_damper_force`.

    Parameters
    ----------
    v, tau_y, eta, rho, seal_friction
        As in :func:`valve_state`.
    h : float or array
        Gap between head and cylinder, [m].
    L : float or array
        Length of the piston head (electrode), [m].
    d : float or array
        Mean diameter of the gap, [m]: ``Dp + h`` (:class:`~erdesign.geometry.Geometry` holds it so); used for the
        mean speed only, the flow itself is solved with ``Dp + h``.
    Dp, dr : float or array
        Head and rod diameters, [m].

    Returns
    -------
    QuasiSteadyState
        ``flow_rate`` and ``flow_per_duct`` are both the displaced flow v A_p.

    Notes
    -----
    Thin gap, laminar, quasi-steady (docs/theory/mixed_mode.md).  Each element is a bracketed root of
    :func:`~erdesign.flow.mixed_mode.couette_poiseuille_bingham` (closed form at zero yield stress).

    Examples
    --------
    >>> s = mixed_state(0.05, 2000.0, 0.1, 1200.0, 0.0, 1e-3, 0.02, 0.031, 0.03, 0.01)
    >>> round(s.force, 1), round(s.shear_force, 2), round(s.plug_fraction, 2)
    (71.1, 5.0, 0.76)

    References
    ----------
    Kamath and Wereley (1997), section II; Makris et al. (1996), eq 1.
    """
    v = np.asarray(v, dtype=float)
    Q_total = v * piston_area(Dp, dr)
    m = mixed_mode_damper_force(v, tau_y, eta, L, Dp, dr, h)
    friction = np.copysign(seal_friction, v)
    # the fluid in the gap moves at up to the wall speed |v| as well as at the mean flow speed
    mean_velocity = np.maximum(np.abs(Q_total) / (np.pi * d * h), np.abs(v))
    return _state(
        m.pressure_force + m.shear_force + friction,
        m.pressure_drop,
        m.pressure_force,
        m.shear_force,
        friction,
        Q_total,
        Q_total,
        m.plug_fraction,
        mean_velocity,
        h,
        rho,
        tau_y,
        eta,
    )


def valve_pressure_drop(Q, tau_y, eta, L, d, h, exact_annulus=False):
    """Pressure drop [Pa] of Bingham flow ``Q`` [m^3/s] through one stationary duct: the gap law of
    :func:`valve_state`, for callers that set the duct flow themselves (a bypass in parallel splits the piston's
    flow, :class:`erdesign.effects.chain.PhysicsDamper`).  Thin gap or exact annulus (``exact_annulus``), as there.

    Examples
    --------
    Makris's damper at 1 in/s and 3 kV/mm, the pressure drop of the :func:`valve_state` example:

    >>> from math import pi
    >>> Ap = pi / 4 * (0.0334**2 - 0.01125**2)
    >>> dp = valve_pressure_drop(0.0254 * Ap, 1800.0, 13.0, 0.0546, 0.0143, 0.0008)
    >>> round(float(dp) / 1e3, 1), bool(dp * Ap + 112.0 == valve_state(0.0254, 1800.0, 13.0, 1290.0, 112.0, 0.0008,
    ...                                                           0.0546, 0.0143, Ap).force)
    (7674.4, True)
    """
    return _valve_gap_flow(Q, tau_y, eta, L, d, h, exact_annulus)[0]


class MixedGapTable:
    r"""The moving-electrode gap of one head, tabulated once in its Bingham number: the fast path of
    :func:`mixed_state` for the physics model, which evaluates the gap at every sample of a record many times over.

    With the flow per unit circumference :math:`q = -u A_p / (\pi (D_p + h))` and the wall speed equal to the
    flow speed :math:`u` (no bypass), the Couette-Poiseuille Bingham solution of
    :func:`~erdesign.flow.mixed_mode.couette_poiseuille_bingham` depends on the head's geometry and on
    :math:`s = B/(1+B)`, :math:`B = \tau_y h / (\eta |u|)`, alone:

    .. math::
        \Delta p = \operatorname{sgn}(u)\,G_p(w)\,\frac{\eta |u| + \tau_y h}{h^2} L, \qquad
        F_\text{shear} = -\operatorname{sgn}(u)\,G_s(w)\,\frac{\eta |u| + \tau_y h}{h}\,\pi D_p L,
        \qquad w = \sqrt{1 - s},

    tabulated on ``points`` values of :math:`w` uniform in [0, 1] (the solution varies like :math:`\sqrt{1-s}` as
    the plug fills the gap) and read by linear interpolation: relative error below 1e-5 against
    :func:`mixed_state` (tests/test_quasi_steady.py).  :func:`mixed_gap_table` builds one per head and keeps it.

    Parameters
    ----------
    h, Dp, dr : float
        Gap, head diameter and rod diameter, [m].
    points : int
        Table points.

    Examples
    --------
    >>> t = mixed_gap_table(1e-3, 0.03, 0.01)
    >>> dp, shear = t.forces(0.05, 2000.0, 0.1, 0.02)
    >>> s = mixed_state(0.05, 2000.0, 0.1, 1200.0, 0.0, 1e-3, 0.02, 0.031, 0.03, 0.01)
    >>> bool(abs(dp / s.pressure_drop - 1) < 1e-5 and abs(shear / s.shear_force - 1) < 1e-5)
    True
    """

    def __init__(self, h: float, Dp: float, dr: float, points: int = 4001):
        self.h, self.Dp, self.dr = float(h), float(Dp), float(dr)
        w = np.linspace(0.0, 1.0, points)
        s = 1.0 - w**2
        # U = 1 m/s, eta = 1 Pa s; tau_y from the Bingham number B = s / (1 - s) = tau_y h / (eta U)
        with np.errstate(divide="ignore"):
            B = np.where(s < 1.0, s / (1.0 - np.minimum(s, 1 - 1e-16)), np.inf)
        tau_y = np.where(np.isfinite(B), B / h, 1.0)
        U = np.where(np.isfinite(B), 1.0, 0.0)
        eta = np.where(np.isfinite(B), 1.0, 1e-300)
        sol = couette_poiseuille_bingham(U, -U * piston_area(Dp, dr) / (np.pi * (Dp + h)), tau_y, eta, h)
        scale = eta * U + tau_y * h
        self.w = w
        #: G_p(w) = dp h^2 / (L (eta U + tau_y h)) and G_s(w) = tau_wall h / (eta U + tau_y h)
        self.pressure = sol.pressure_gradient * h**2 / scale
        self.shear = sol.wall_stress_moving * h / scale
        for a in (self.w, self.pressure, self.shear):
            a.setflags(write=False)

    def forces(self, u, tau_y, eta, L, *, shear: bool = True):
        """(pressure drop [Pa], shear drag [N]) of the gap at flow speed ``u`` [m/s] (= the wall speed), yield
        stress ``tau_y`` [Pa], plastic viscosity ``eta`` [Pa s] and head length ``L`` [m]; vectorised (one compiled
        pass, :func:`erdesign.flow._compiled.head_table_forces`: np.interp's values on the uniform grid).  With
        ``shear=False`` the drag is None (not read from the table: a root in the pressure drop needs only that)."""
        from ..flow import _compiled

        u, tau_y, eta, L = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (u, tau_y, eta, L)))
        shape = u.shape
        args = [np.ascontiguousarray(a).ravel() for a in (u, tau_y, eta, L)]
        dp = np.empty(args[0].size)
        drag = np.empty(args[0].size if shear else 0)
        _compiled.head_table_forces(*args, self.h, self.Dp, self.pressure, self.shear, dp, drag)
        if not shape:
            return float(dp[0]), (float(drag[0]) if shear else None)
        return dp.reshape(shape), (drag.reshape(shape) if shear else None)


@lru_cache(maxsize=64)
def mixed_gap_table(h: float, Dp: float, dr: float) -> MixedGapTable:
    """The :class:`MixedGapTable` of a head (built once per geometry and kept: fits build many models of one
    damper)."""
    return MixedGapTable(h, Dp, dr)


def quasi_steady_state(
    configuration, v, tau_y, eta, rho, seal_friction, h, L, d, Dp, dr, n=1, exact_annulus=False
) -> QuasiSteadyState:
    r"""Quasi-steady state of dampers of one configuration, vectorised over velocity, fluid and geometry.

    Dispatches to :func:`valve_state` (with :math:`A_p = \frac{\pi}{4}(D_p^2 - d_r^2)`) or :func:`mixed_state`;
    see the module notes for the equations.

    Parameters
    ----------
    configuration : str
        ``"valve"`` or ``"mixed"``.
    v : float or array
        Piston velocity, [m/s].
    tau_y, eta : float or array
        Yield stress [Pa] and plastic viscosity [Pa s] at the control.
    rho : float or array
        Density, [kg/m^3].
    seal_friction : float or array
        Seal friction F_s, [N].
    h, L, d, Dp, dr : float or array
        Gap, duct (head) length, mean diameter of the gap, piston (head) and rod diameters, [m].
    n : int or array
        Ducts in parallel (valve; a mixed damper has one gap).
    exact_annulus : bool or array of bool
        Valve only: the exact annulus instead of the thin gap.

    Returns
    -------
    QuasiSteadyState

    Examples
    --------
    Three gaps at once (broadcasting): the valve force falls steeply as the gap opens.

    >>> import numpy as np
    >>> s = quasi_steady_state("valve", 0.0254, 1800.0, 13.0, 1290.0, 112.0, np.array([0.6e-3, 0.8e-3, 1.0e-3]),
    ...                        0.0546, 0.0143, 0.0334, 0.01125)
    >>> np.round(s.force / 1e3, 2)
    array([13.95,  6.07,  3.25])

    References
    ----------
    Makris et al. (1996), eq 14; Kamath and Wereley (1997), section II.
    """
    if configuration == "valve":
        return valve_state(v, tau_y, eta, rho, seal_friction, h, L, d, piston_area(Dp, dr), n, exact_annulus)
    if configuration == "mixed":
        if np.any(exact_annulus) or np.any(np.asarray(n) != 1):
            raise ValueError("quasi_steady_state: a mixed damper has one gap and the thin-gap model only")
        return mixed_state(v, tau_y, eta, rho, seal_friction, h, L, d, Dp, dr)
    raise ValueError(f"quasi_steady_state: configuration must be 'valve' or 'mixed', got {configuration!r}")


def damping_constant(configuration, eta0, rho, h, L, d, Dp, dr, n=1, exact_annulus=False):
    r"""Small-velocity damping constant of the zero-field fluid, [N s/m], vectorised over fluid and geometry.

    The quasi-steady fluid force (pressure plus shear drag, seal friction left out) of the Newtonian fluid
    :math:`\eta_0` at 1 m/s, which is linear in the velocity, so exact at any velocity; for a thin-gap valve it is
    Makris eq 15, :math:`C = 12\eta_0 L A_p^2 / (n\pi d h^3)`.  Arguments as in :func:`quasi_steady_state`.
    :meth:`Damper.damping_constant_si <erdesign.damper.Damper.damping_constant_si>` is this for one damper.

    >>> round(damping_constant("valve", 7.0, 1290.0, 0.0008, 0.0546, 0.0143, 0.0334, 0.01125) / 1e3, 1)
    120.3
    """
    s = quasi_steady_state(configuration, 1.0, 0.0, eta0, rho, 0.0, h, L, d, Dp, dr, n, exact_annulus)
    return scalar_or_array(s.pressure_force + s.shear_force)


def damper_state(damper: "Damper", v, tau_y, eta) -> QuasiSteadyState:
    """Quasi-steady state of a :class:`~erdesign.damper.Damper` at velocity ``v`` [m/s] with the fluid's yield
    stress ``tau_y`` [Pa] and plastic viscosity ``eta`` [Pa s] given (per sample, e.g. calibrated or lagged).

    :meth:`Damper.state <erdesign.damper.Damper.state>` is this at the fluid's properties of a control.

    Examples
    --------
    >>> from erdesign import load_example
    >>> round(damper_state(load_example("makris"), 0.0254, 1800.0, 13.0).force / 1e3, 2)
    6.07
    """
    g = damper.geometry
    return quasi_steady_state(
        g.configuration,
        v,
        tau_y,
        eta,
        damper.fluid.density,
        damper.seal_friction,
        g.gap,
        g.duct_length,
        g.duct_mean_diameter,
        g.piston_diameter,
        g.rod_diameter,
        g.ducts,
        damper.uses_exact_annulus,
    )
