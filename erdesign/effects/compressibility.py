r"""Compressibility: fluid and accumulator compliance in series with the nonlinear duct law.

The chambers hold a volume :math:`V` of fluid of effective bulk modulus :math:`\beta` (oil, entrained air, hose and
seal compliance).  The pressure force :math:`P = \Delta p\,A_p` is then a state: the piston compresses the fluid
at rate :math:`A_p v` while the ducts (and a bypass, if any) pass the flow that the current pressure drives,

.. math:: \dot P = k_h\,\big(v - u(P)\big), \qquad k_h = \frac{2\beta A_p^2}{V},

where :math:`u(P)` is the piston speed whose flow the ducts pass at the pressure force :math:`P` (two chambers of
volume :math:`V` each, in series).  For a yield-stress fluid :math:`u(P) = 0` for :math:`|P| \le F_y`: after every
reversal the column acts as a spring of stiffness :math:`k_h` until the ducts yield again, so the force ramps over
:math:`2F_y/k_h` of stroke.  A linear lag of the quasi-steady force (the form erdesign used before, exact only at
zero field) cannot make that ramp; this module integrates the nonlinear law itself.

:math:`u(P)` is exact for the thin-gap duct laws: Buckingham-Reiner (Bingham) and its Herschel-Bulkley
generalisation are explicit in the pressure drop, plus the laminar bypass :math:`P/C_l`; for the moving-electrode
(mixed) gap the Couette-Poiseuille Bingham solution is inverted through a monotone table (the wall speed taken
equal to the flow speed, :meth:`erdesign.damper.quasi_steady.MixedGapTable.inverse`).  The stiff ODE is
integrated by backward Euler on ``substeps`` equal substeps per sample (the velocity linear between samples), each
a scalar monotone equation solved by safeguarded false position, in a compiled loop (numba).  Backward Euler is L-stable: a column much
stiffer than the ducts gives the quasi-steady force at any step size.
"""

from __future__ import annotations

import math
import numpy as np
from numba import njit

from ..parameters import Parameter
from .base import DuctLaw, Effect

__all__ = ["Compressibility", "hydraulic_stiffness", "compliant_pressure_force", "DuctLaw", "BULK_MODULUS",
           "SUBSTEPS"]

#: Effective bulk modulus used for the prior, [Pa]: silicone oil is 1-1.5 GPa, less with entrained air.
BULK_MODULUS = 1.0e9
#: Backward-Euler substeps per sample.
SUBSTEPS = 4


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
def _piston_speed(P, kind, tau_y, K, m, L, d, h, Ap, ducts, bypass, w_tab, G_tab):
    """Piston speed [m/s] whose flow the ducts and bypass pass at pressure force P [N] (signed).  Kind 0 is the
    explicit thin-gap flow of :func:`erdesign.flow.herschel_bulkley.herschel_bulkley_slit_flow_rate` written for one
    sample in the compiled loop (tests/test_effects.py checks the two agree)."""
    aP = abs(P)
    dp = aP / Ap
    u = 0.0
    if kind == 0:
        tau_w = dp * h / (2.0 * L)
        if tau_w > tau_y:
            S = tau_w - tau_y
            p = 1.0 / m
            q = 0.5 * h * h / (tau_w * tau_w) * K ** (-p) * S ** (p + 1.0) * (S / (p + 2.0) + tau_y / (p + 1.0))
            u = ducts * math.pi * d * q / Ap
    else:
        # dp h / (L tau_y) = G(w), w^2 = eta U / (eta U + tau_y h); G increases from G(0) (yield) to infinity
        if tau_y <= 0.0:
            u = dp * h * h / (L * K * G_tab[-1] * (1.0 - w_tab[-1] ** 2))
        else:
            Pi = dp * h / (L * tau_y)
            if Pi > G_tab[0]:
                if Pi >= G_tab[-1]:
                    # beyond the table: the Newtonian asymptote eta U + tau_y h = dp h^2 / (L g1)
                    g1 = G_tab[-1] * (1.0 - w_tab[-1] ** 2)
                    u = max(dp * h * h / (L * g1) - tau_y * h, 0.0) / K
                else:
                    ww = np.interp(Pi, G_tab, w_tab)
                    u = tau_y * h * ww * ww / (K * (1.0 - ww * ww))
    u += aP * bypass
    return u if P >= 0.0 else -u


@njit(cache=True)
def _integrate(t, v, P0, k, kind, tau_y, K, m, L, d, h, Ap, ducts, bypass, w_tab, G_tab, substeps):
    n = t.size
    P = np.empty(n)
    P[0] = P0
    p = P0
    for i in range(n - 1):
        dt = (t[i + 1] - t[i]) / substeps
        ty, KK = tau_y[i + 1], K[i + 1]
        for j in range(substeps):
            vj = v[i] + (v[i + 1] - v[i]) * (j + 1.0) / substeps
            c = k * dt
            T = p + c * vj
            # g(P) = P + c u(P) - T is increasing, g(0) = -T: the root lies between 0 and T
            lo, hi = min(0.0, T), max(0.0, T)
            glo = lo + c * _piston_speed(lo, kind, ty, KK, m, L, d, h, Ap, ducts, bypass, w_tab, G_tab) - T
            ghi = hi + c * _piston_speed(hi, kind, ty, KK, m, L, d, h, Ap, ducts, bypass, w_tab, G_tab) - T
            x = 0.0
            if glo == 0.0:
                x = lo
            elif ghi == 0.0:
                x = hi
            else:
                side = 0
                tol = 1e-12 * (abs(T) + 1e-300)
                for _ in range(200):
                    x = (lo * ghi - hi * glo) / (ghi - glo)
                    if not (lo < x < hi):
                        x = 0.5 * (lo + hi)
                    gx = x + c * _piston_speed(x, kind, ty, KK, m, L, d, h, Ap, ducts, bypass, w_tab, G_tab) - T
                    if gx == 0.0 or hi - lo < tol:
                        break
                    if gx < 0.0:
                        lo, glo = x, gx
                        if side == -1:
                            ghi *= 0.5          # Illinois: keep the stale end from stalling the iteration
                        side = -1
                    else:
                        hi, ghi = x, gx
                        if side == 1:
                            glo *= 0.5
                        side = 1
            p = x
        P[i + 1] = p
    return P


def compliant_pressure_force(t, v, stiffness, law: DuctLaw, initial: float, substeps: int = SUBSTEPS):
    r"""Pressure force of a damper whose fluid column is a spring in series with the nonlinear duct law.

    .. math:: \dot P = k_h\,\big(v(t) - u(P, t)\big), \qquad P(t_0) = P_0

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
    substeps : int
        Backward-Euler substeps per sample.

    Returns
    -------
    array
        P, [N].

    Notes
    -----
    Backward Euler, first order in the substep; L-stable (module notes).  At zero field the law is a Maxwell
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
    t = np.ascontiguousarray(t, dtype=float)
    v = np.ascontiguousarray(v, dtype=float)
    n = t.size
    tau_y = np.ascontiguousarray(np.broadcast_to(np.asarray(law.tau_y, dtype=float), (n,)))
    K = np.ascontiguousarray(np.broadcast_to(np.asarray(law.K, dtype=float), (n,)))
    if not (np.isfinite(stiffness) and stiffness > 0):
        raise ValueError(f"compressibility: hydraulic stiffness must be positive and finite, got {stiffness}")
    return _integrate(t, v, float(initial), float(stiffness), int(law.kind), tau_y, K, float(law.m), float(law.L),
                      float(law.d), float(law.h), float(law.Ap), int(law.ducts), float(law.bypass),
                      np.ascontiguousarray(law.w, dtype=float), np.ascontiguousarray(law.G, dtype=float),
                      int(substeps))


class Compressibility(Effect):
    name = "compressibility"
    title = "Compressibility (fluid and accumulator compliance)"
    mechanism = ("The fluid in the chambers is compressed before it flows: a spring k_h = 2 beta A_p^2 / V in series "
                 "with the ducts, so after each reversal the force ramps over 2 F_y / k_h of stroke until the ducts "
                 "yield again, and lags the motion by C/k_h after that.")
    signature = ("residual in phase with the displacement at high speed (the loop leans and rounds off at the ends "
                 "of the stroke, force lags velocity), present at zero field too")
    stage = "series"
    continuous_at_reversal = True
    neutral = {"hydraulic_stiffness": "upper"}
    # entrained air and hose / seal compliance soften the column by tens of times; nothing stiffens it much
    plausible_ratio = {"hydraulic_stiffness": (0.02, 5.0)}
    source = "Lumped hydraulic capacitance; Makris et al. (1996) eq 13 (Maxwell) at zero field"

    def parameters(self, damper):
        k = self.prior(damper)["hydraulic_stiffness"]
        return (Parameter("hydraulic_stiffness", "N/m", k, 1e2, 1e12,
                          "stiffness of the fluid column, 2 beta A_p^2 / V", log_scale=True),)

    def prior(self, damper):
        g = damper.geometry
        V = g.piston_area * g.piston_diameter + np.pi * g.duct_mean_diameter * g.gap * g.duct_length * g.ducts
        return {"hydraulic_stiffness": hydraulic_stiffness(BULK_MODULUS, g.piston_area, V)}

    def series_pressure_force(self, t, v, pressure_force, duct_law, values):
        # the column starts settled: at the quasi-steady pressure force of the first sample
        return compliant_pressure_force(t, v, values["hydraulic_stiffness"], duct_law, pressure_force[0])
