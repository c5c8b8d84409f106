r"""Compressibility: fluid and accumulator compliance in series with the nonlinear duct law.

The chambers hold a volume :math:`V` of fluid of effective bulk modulus :math:`\beta` (oil, entrained air, hose and
seal compliance).  The pressure force :math:`P = \Delta p\,A_p` is then a state: the piston compresses the fluid
at rate :math:`A_p v` while the ducts (and a bypass, if any) pass the flow that the current pressure drives,

.. math:: \dot P = k_h\,\big(v - u(P, v)\big), \qquad k_h = \frac{2\beta A_p^2}{V},

where :math:`u(P, v)` is the piston speed whose flow the ducts pass at the pressure force :math:`P` (two chambers
of volume :math:`V` each, in series); it depends on the piston speed :math:`v` only on a moving-electrode (mixed)
head, whose gap's inner wall is the head itself.  For a yield-stress fluid :math:`u(P) = 0` for :math:`|P| \le F_y`: after every
reversal the column acts as a spring of stiffness :math:`k_h` until the ducts yield again, so the force ramps over
:math:`2F_y/k_h` of stroke.  A linear lag of the quasi-steady force (the form erdesign used before, exact only at
zero field) cannot make that ramp; this module integrates the nonlinear law itself.

:math:`u` is exact for the thin-gap duct laws: Buckingham-Reiner (Bingham) and its Herschel-Bulkley
generalisation are explicit in the pressure drop, plus the laminar bypass :math:`P/C_l`; for the moving-electrode
(mixed) gap the Couette-Poiseuille Bingham flow is explicit in the pressure gradient and the head's speed
(:func:`moving_wall_gap_flow`, closed form zone by zone), and the head's shear drag is taken from the same solution
at the column's pressure (:func:`compliant_gap_forces`): while the column is compressed after a reversal, the gap
passes less than the displaced flow and the head drags the fluid at its own speed.  The stiff ODE is
integrated by backward Euler on equal substeps, at least :data:`SUBSTEPS` per sample and none longer than
:data:`MAX_SUBSTEP` (the velocity linear between samples, the control held at its value of the interval's start, as
a zero-order hold, until the substep that ends on the next sample), each a scalar monotone equation solved by
safeguarded false position, in a compiled loop (numba).  Backward Euler is L-stable: a column much stiffer than the
ducts gives the quasi-steady force at any step size.
"""

from __future__ import annotations

import math

import numpy as np

from .._compile import njit
from ..parameters import Parameter
from .base import DuctLaw, Effect

__all__ = [
    "Compressibility",
    "hydraulic_stiffness",
    "compliant_pressure_force",
    "compliant_gap_forces",
    "moving_wall_gap_flow",
    "DuctLaw",
    "BULK_MODULUS",
    "SUBSTEPS",
    "MAX_SUBSTEP",
]

#: Effective bulk modulus used for the prior, [Pa]: silicone oil is 1-1.5 GPa, less with entrained air.
BULK_MODULUS = 1.0e9
#: Fewest backward-Euler substeps per sample ...
SUBSTEPS = 8
#: ... and the longest substep, [s].  Measured on truth-rig records of a compliant mixed head at 1 kHz (the column's
#: ramp after a reversal lasts a few ms): 4 substeps of 0.25 ms leave 1.5-2.7 x the noise after calibration, 8 of
#: 0.125 ms 1.0-1.25 x, 16 no better (what is left there is the truth rig's own step at a field change).
MAX_SUBSTEP = 1.25e-4


def hydraulic_stiffness(bulk_modulus, Ap, chamber_volume):
    r"""Stiffness of the fluid column seen by the piston, two chambers in series.

    .. math:: k_h = \frac{2\beta A_p^2}{V}

    Parameters
    ----------
    bulk_modulus : float
        Effective bulk modulus beta, [Pa].
    Ap : float
        Piston area, [m^2].
    chamber_volume : float
        Fluid volume of one chamber, V, [m^3].

    Returns
    -------
    float
        k_h, [N/m].

    Examples
    --------
    >>> round(hydraulic_stiffness(1e9, 7.7676e-4, 7.7676e-4 * 0.0334) / 1e6, 2)   # MN/m, Makris chambers
    46.51
    """
    return 2.0 * bulk_modulus * Ap**2 / chamber_volume


@njit(cache=True)
def moving_wall_gap_flow(g, U, tau_y, eta, h):
    r"""Flow per unit width and stress on the moving wall of Bingham flow in a slit with one moving wall, from the
    pressure gradient and the wall speed: the Couette-Poiseuille law of
    :func:`erdesign.flow.mixed_mode.couette_poiseuille_bingham` read the other way (scalar, compiled).

    With the stress :math:`\tau(y) = \tau_0 + g y` across the gap (``y`` from the moving wall), the no-slip
    condition reads, with :math:`\Phi(s) = \tfrac12\max(|s| - \tau_y, 0)^2` and :math:`H = g h`,

    .. math::
        \Phi(\tau_0 + H) - \Phi(\tau_0) = -\eta U g, \qquad
        \eta q = -\frac{1}{g^2}\int_{\tau_0}^{\tau_0 + H} (s - \tau_0)\,D(s)\,\mathrm{d}s,

    :math:`D(s) = \operatorname{sgn}(s)\max(|s| - \tau_y, 0)`.  The left side is non-decreasing and piecewise
    quadratic in :math:`\tau_0`; for :math:`g > 0` the zone that holds the root follows from the sign and size of
    :math:`R = -\eta U g` against :math:`H^2/2` and :math:`E^2/2`, :math:`E = H - 2\tau_y` (whole gap above or
    below the yield band, one sheared layer at a wall, or the band straddled), each solved in closed form for the
    thickness of its sheared layers in stress units (no difference of large numbers); the flow is then one closed
    form per sheared layer.  ``g < 0`` by the symmetry :math:`(g, U, q, \tau) \to (-g, -U, -q, -\tau)`; ``g = 0``
    is plain Couette flow.

    Parameters
    ----------
    g : float
        Pressure gradient dp/dx, [Pa/m]; positive when the pressure rises in the direction of ``U``.
    U : float
        Speed of the moving wall, [m/s].
    tau_y : float
        Yield stress, [Pa], >= 0.
    eta : float
        Plastic viscosity, [Pa s], > 0.
    h : float
        Gap, [m].

    Returns
    -------
    (q, tau_0) : (float, float)
        Flow per unit width along ``U`` in the frame of the fixed wall, [m^2/s], and the stress on the moving wall,
        [Pa] (the fluid pulls the wall with tau_0 per unit area).  A blocked gap (``U = 0``, ``|g| h <= 2 tau_y``)
        passes nothing and is given the centred plug, :math:`\tau_0 = -g h/2`.

    Notes
    -----
    Thin gap, laminar, steady, no slip, as :func:`~erdesign.flow.mixed_mode.couette_poiseuille_bingham`, which
    solves for the gradient given the flow; tests/test_effects.py checks that this law returns the flow and the wall
    stress given that gradient.

    References
    ----------
    Kamath and Wereley (1997), section II; derivation in docs/theory/mixed_mode.md.
    """
    if g == 0.0:
        if U == 0.0:
            return 0.0, 0.0
        return 0.5 * U * h, -math.copysign(tau_y + eta * abs(U) / h, U)
    s = 1.0
    if g < 0.0:
        s, g, U = -1.0, -g, -U
    H = g * h
    R = -eta * U * g
    E = H - 2.0 * tau_y
    # sheared layers: 'hi' = tau(h) - tau_y at the fixed wall, 'j' = -tau_y - tau_0 at the moving wall (stress units)
    if R >= 0.5 * H * H:  # the whole gap above the band: m = tau_0 - tau_y >= 0
        m = -eta * U / h - 0.5 * H
        t0 = tau_y + m
        I = H * H * (H / 3.0 + 0.5 * m)
    elif R <= -0.5 * H * H:  # the whole gap below the band: j >= H
        j = 0.5 * H + eta * U / h
        t0 = -tau_y - j
        I = H * H * (H / 3.0 - 0.5 * j)
    elif E > 0.0 and abs(R) < 0.5 * E * E:  # the band straddled: a layer at each wall, hi + j = E
        hi = 0.5 * (E + 2.0 * R / E)
        j = 0.5 * (E - 2.0 * R / E)
        t0 = -tau_y - j
        I = hi * hi * (hi / 3.0 + 0.5 * (H - hi)) - j * j * j / 6.0
    elif R > 0.0:  # one layer, at the fixed wall
        hi = math.sqrt(2.0 * R)
        t0 = tau_y - H + hi
        I = hi * hi * (hi / 3.0 + 0.5 * (H - hi))
    elif R < 0.0:  # one layer, at the moving wall
        j = math.sqrt(-2.0 * R)
        t0 = -tau_y - j
        I = -j * j * j / 6.0
    else:  # blocked: any tau_0 in the band holds; the centred plug
        t0 = -0.5 * H
        I = 0.0
    q = -I / (g * g * eta)
    return s * q, s * t0


@njit(cache=True)
def _piston_speed(P, v, kind, tau_y, K, m, L, d, h, Ap, ducts, bypass):
    """Piston speed [m/s] whose flow the ducts and bypass pass at pressure force P [N] (signed) with the piston at
    speed v [m/s].  Kind 0 is the explicit thin-gap flow of
    :func:`erdesign.flow.herschel_bulkley.herschel_bulkley_slit_flow_rate` written for one sample in the compiled
    loop (tests/test_effects.py checks the two agree); kind 1 the moving-electrode gap, whose flow depends on the
    pressure and on the head's speed (:func:`moving_wall_gap_flow`)."""
    if kind == 1:
        q = moving_wall_gap_flow(P / (Ap * L), v, tau_y, K, h)[0]
        return -math.pi * d * q / Ap + P * bypass
    aP = abs(P)
    dp = aP / Ap
    u = 0.0
    tau_w = dp * h / (2.0 * L)
    if tau_w > tau_y:
        S = tau_w - tau_y
        if m == 1.0:  # Bingham: the same expression without the two powers (a third of the loop's time)
            q = 0.5 * h * h / (tau_w * tau_w) / K * (S * S) * (S / 3.0 + tau_y / 2.0)
        else:
            p = 1.0 / m
            q = 0.5 * h * h / (tau_w * tau_w) * K ** (-p) * S ** (p + 1.0) * (S / (p + 2.0) + tau_y / (p + 1.0))
        u = ducts * math.pi * d * q / Ap
    u += aP * bypass
    return u if P >= 0.0 else -u


@njit(cache=True)
def _series_root(p, T, c, vj, kind, ty, KK, m, L, d, h, Ap, ducts, bypass, dp_last):
    """The pressure force x with x + c u(x, vj) = T (increasing in x), safeguarded false position (Illinois),
    started from the previous substep's value p extrapolated by its last change ``dp_last``.

    g(x) = x + c u(x, vj) - T has g' >= 1, so |x - root| <= |g(x)|: the iteration stops once |g| is below the
    tolerance (1e-12 of the force), which bounds the error as the bracket's width would, in about half the
    evaluations (4 per substep instead of 9 on 1 kHz records)."""
    # widen a bracket around the extrapolated value until it holds the root.  For the stationary ducts u(0) = 0 and
    # u has the sign of P, so the root also lies between 0 and T, which caps the widening.
    if kind == 0:
        a, b = min(0.0, T), max(0.0, T)
    else:
        a, b = -math.inf, math.inf
    # the first step: twice the previous substep's change (a few doublings at most when that was tiny), never more
    # than |T - p|, the change were the ducts closed
    step = abs(T - p) + 1e-9 * (abs(T) + abs(p)) + 1e-300
    step = min(step, max(2.0 * abs(dp_last), 1e-6 * step))
    x0 = min(max(p + dp_last, a), b)
    g0 = x0 + c * _piston_speed(x0, vj, kind, ty, KK, m, L, d, h, Ap, ducts, bypass) - T
    tol = 1e-12 * (abs(T) + abs(x0) + 1e-300)
    if abs(g0) <= tol:
        return x0  # g' >= 1, so |x0 - root| <= |g0|
    lo, glo, hi, ghi = x0, g0, x0, g0
    if g0 < 0.0:
        while True:
            hi = min(lo + step, b)
            ghi = hi + c * _piston_speed(hi, vj, kind, ty, KK, m, L, d, h, Ap, ducts, bypass) - T
            if ghi >= 0.0 or hi >= b:
                break
            lo, glo = hi, ghi
            step *= 2.0
    else:
        while True:
            lo = max(hi - step, a)
            glo = lo + c * _piston_speed(lo, vj, kind, ty, KK, m, L, d, h, Ap, ducts, bypass) - T
            if glo <= 0.0 or lo <= a:
                break
            hi, ghi = lo, glo
            step *= 2.0
    if glo == 0.0:
        return lo
    if ghi == 0.0:
        return hi
    x = 0.0
    side = 0
    tol = 1e-12 * (abs(T) + abs(lo) + abs(hi) + 1e-300)
    for _ in range(200):
        x = (lo * ghi - hi * glo) / (ghi - glo)
        if not (lo < x < hi):
            x = 0.5 * (lo + hi)
        gx = x + c * _piston_speed(x, vj, kind, ty, KK, m, L, d, h, Ap, ducts, bypass) - T
        if abs(gx) <= tol or hi - lo < tol:
            break
        if gx < 0.0:
            lo, glo = x, gx
            if side == -1:
                ghi *= 0.5  # Illinois: keep the stale end from stalling the iteration
            side = -1
        else:
            hi, ghi = x, gx
            if side == 1:
                glo *= 0.5
            side = 1
    return x


@njit(cache=True)
def _integrate(t, v, P0, k, kind, tau_y, K, m, L, d, h, Ap, ducts, bypass, counts):
    """P at the samples, and (kind 1) the head's shear drag at them, [N]; ``counts[i]`` substeps in interval i."""
    n = t.size
    P = np.empty(n)
    S = np.zeros(n)
    P[0] = P0
    p = P0
    dp = 0.0
    for i in range(n - 1):
        substeps = counts[i]
        dt = (t[i + 1] - t[i]) / substeps
        for j in range(substeps):
            vj = v[i] + (v[i + 1] - v[i]) * (j + 1.0) / substeps
            # the control is held over the interval (zero-order hold: a command that steps at sample i + 1 acts
            # from then on) and the sample's own control acts at the sample
            e = i + 1 if j == substeps - 1 else i
            c = k * dt
            pn = _series_root(p, p + c * vj, c, vj, kind, tau_y[e], K[e], m, L, d, h, Ap, ducts, bypass, dp)
            dp = pn - p
            p = pn
        P[i + 1] = p
    if kind == 1:
        # the wall's drag at the pressure and speed of each sample (shear area pi Dp L, Dp = d - h)
        for i in range(n):
            tau0 = moving_wall_gap_flow(P[i] / (Ap * L), v[i], tau_y[i], K[i], h)[1]
            S[i] = -tau0 * math.pi * (d - h) * L
    return P, S


def compliant_pressure_force(t, v, stiffness, law: DuctLaw, initial: float, substeps: int | None = None):
    r"""Pressure force of a damper whose fluid column is a spring in series with the nonlinear duct law.

    .. math:: \dot P = k_h\,\big(v(t) - u(P, v, t)\big), \qquad P(t_0) = P_0

    (:func:`compliant_gap_forces` gives the moving head's shear drag with it).

    Parameters
    ----------
    t : array
        Time, [s].
    v : array
        Piston velocity, [m/s].
    stiffness : float
        Hydraulic stiffness k_h, [N/m].
    law : DuctLaw
        The ducts' flow at a pressure (per-sample yield stress and viscosity: field, heating).
    initial : float
        P at t[0], [N] (the quasi-steady value: the column starts settled).
    substeps : int, optional
        Backward-Euler substeps per sample; default at least :data:`SUBSTEPS`, and none longer than
        :data:`MAX_SUBSTEP`.

    Returns
    -------
    array
        P, [N].

    Notes
    -----
    :math:`u(P, v)` is the piston speed whose flow the ducts pass at the pressure force :math:`P`; it depends on
    the piston speed :math:`v` only for the moving-electrode gap (``law.kind`` 1), whose wall is the head itself
    (:func:`moving_wall_gap_flow`).  Backward Euler, first order in the substep; L-stable (module notes).  At zero field the law is a Maxwell
    element and the result converges to its closed form (tests/test_effects.py); with a yield stress the force
    after a reversal ramps with slope k_h over 2 F_y / k_h of stroke.

    Examples
    --------
    A Newtonian duct of damping C = 100 N s/m behind a column of 1000 N/m, the piston started at 1 m/s from
    rest: P = C v (1 - exp(-t k/C)).

    >>> import numpy as np
    >>> t = np.linspace(0, 1, 1001); v = np.ones(1001)
    >>> law = DuctLaw(0, np.zeros(1001), np.full(1001, 1.0), 1.0, 1.0, 1.0 / np.pi, (12 * 1 / 100) ** (1 / 3), 1.0, 1)
    >>> P = compliant_pressure_force(t, v, 1000.0, law, 0.0, substeps=16)
    >>> bool(abs(P[100] / (100 * (1 - np.exp(-1.0))) - 1) < 2e-3)
    True

    References
    ----------
    Lumped hydraulic capacitance (Merritt, Hydraulic Control Systems, 1967, ch. 3); Buckingham-Reiner slit flow
    (Makris et al. 1996, eqs 5-7 with h^3); at zero field the Maxwell model of Makris et al. 1996, eq 13.
    """
    return compliant_gap_forces(t, v, stiffness, law, initial, substeps)[0]


def compliant_gap_forces(t, v, stiffness, law: DuctLaw, initial: float, substeps: int | None = None):
    r"""Pressure force and the moving head's shear drag behind a compliant fluid column: :func:`compliant_pressure_force`
    with, for the moving-electrode gap (``law.kind`` 1), the drag :math:`-\tau_0(P, v)\,\pi D_p L` of the gap's
    flow at the pressure and head speed of each sample (zeros for stationary ducts).

    Returns
    -------
    (P, S) : (array, array)
        Pressure force and shear drag, [N].

    Examples
    --------
    A Newtonian moving-electrode gap at constant speed settles on its quasi-steady force (the mixed-mode kernel):

    >>> import numpy as np
    >>> from erdesign.flow.mixed_mode import mixed_mode_damper_force
    >>> h, Dp, dr, L, eta = 1e-3, 0.04, 0.012, 0.025, 0.25
    >>> Ap = np.pi / 4 * (Dp**2 - dr**2)
    >>> t = np.linspace(0, 0.5, 501); v = np.full(501, 0.1)
    >>> law = DuctLaw(1, np.zeros(501), np.full(501, eta), 1.0, L, Dp + h, h, Ap, 1)
    >>> P, S = compliant_gap_forces(t, v, 1e6, law, 0.0)
    >>> ref = mixed_mode_damper_force(0.1, 0.0, eta, L, Dp, dr, h)
    >>> bool(abs(P[-1] / ref.pressure_force - 1) < 1e-9 and abs(S[-1] / ref.shear_force - 1) < 1e-9)
    True
    """
    t = np.ascontiguousarray(t, dtype=float)
    v = np.ascontiguousarray(v, dtype=float)
    n = t.size
    tau_y = np.ascontiguousarray(np.broadcast_to(np.asarray(law.tau_y, dtype=float), (n,)))
    K = np.ascontiguousarray(np.broadcast_to(np.asarray(law.K, dtype=float), (n,)))
    if not (np.isfinite(stiffness) and stiffness > 0):
        raise ValueError(f"compressibility: hydraulic stiffness must be positive and finite, got {stiffness}")
    if substeps is None:
        # at least SUBSTEPS per sample and none longer than MAX_SUBSTEP: a thinned or slowly sampled record is
        # integrated as finely in time as one sampled at 1/MAX_SUBSTEP / SUBSTEPS
        counts = np.maximum(SUBSTEPS, np.ceil(np.diff(t) / MAX_SUBSTEP * (1 - 1e-9))).astype(np.int64)
    else:
        counts = np.full(max(n - 1, 0), int(substeps), dtype=np.int64)
    return _integrate(
        t,
        v,
        float(initial),
        float(stiffness),
        int(law.kind),
        tau_y,
        K,
        float(law.m),
        float(law.L),
        float(law.d),
        float(law.h),
        float(law.Ap),
        int(law.ducts),
        float(law.bypass),
        counts,
    )


class Compressibility(Effect):
    name = "compressibility"
    title = "Compressibility (fluid and accumulator compliance)"
    mechanism = (
        "The fluid in the chambers is compressed before it flows: a spring k_h = 2 beta A_p^2 / V in series "
        "with the ducts, so after each reversal the force ramps over 2 F_y / k_h of stroke until the ducts "
        "yield again, and lags the motion by C/k_h after that."
    )
    signature = (
        "residual in phase with the displacement at high speed (the loop leans and rounds off at the ends "
        "of the stroke, force lags velocity), present at zero field too"
    )
    stage = "series"
    continuous_at_reversal = True
    neutral = {"hydraulic_stiffness": "upper"}
    # entrained air and hose / seal compliance soften the column by tens of times; nothing stiffens it much
    plausible_ratio = {"hydraulic_stiffness": (0.02, 5.0)}
    source = "Lumped hydraulic capacitance; Makris et al. (1996) eq 13 (Maxwell) at zero field"

    def parameters(self, damper):
        k = self.prior(damper)["hydraulic_stiffness"]
        return (
            Parameter(
                "hydraulic_stiffness",
                "N/m",
                k,
                1e2,
                1e12,
                "stiffness of the fluid column, 2 beta A_p^2 / V",
                log_scale=True,
            ),
        )

    def prior(self, damper):
        g = damper.geometry
        V = g.piston_area * g.piston_diameter + np.pi * g.duct_mean_diameter * g.gap * g.duct_length * g.ducts
        return {"hydraulic_stiffness": hydraulic_stiffness(BULK_MODULUS, g.piston_area, V)}

    def series_pressure_force(self, t, v, pressure_force, duct_law, values):
        # the column starts settled: at the quasi-steady pressure force of the first sample
        return compliant_pressure_force(t, v, values["hydraulic_stiffness"], duct_law, pressure_force[0])

    def series_forces(self, t, v, pressure_force, shear_force, duct_law, values):
        # the moving head's drag follows the gap's flow at the column's pressure, not the quasi-steady one
        P, S = compliant_gap_forces(t, v, values["hydraulic_stiffness"], duct_law, pressure_force[0])
        return P, (S if duct_law.kind == 1 else shear_force)
